/* The direction cover (vb_cover.h) behind the proposer table: its OpenCL
 * backend on a device (the device layer's cover_open), or the host's
 * threads. It proposes quadruples whose exact roots hold every vertex, so
 * the result says `complete`; with a sink in the arguments they go to it
 * part by part (vb_cover_run_parts), a device's batches each as a part of
 * its own, for the certifier to overlap. */
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_proposer.h"

typedef struct cover_state {
    vb_cover_backend *be;   /* NULL: the host */
} cover_state;

static int cover_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void **state)
{
    *state = NULL;
    cover_state *s = calloc(1, sizeof *s);
    if (!s)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    int rc = dev ? layer->cover_open(ctx, dev, &s->be) : VB_OK;
    if (rc != VB_OK) {
        free(s);
        return rc;
    }
    *state = s;
    return VB_OK;
}

static int cover_run(vb_ctx *ctx, void *state, const vb_proposer_await *aw,
                     const vb_sphere_set *set, const vb_propose_args *args,
                     vb_proposal *res)
{
    cover_state *s = state ? state : aw->state(aw->user);
    if (!s)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "no cover backend");
    vb_cover_options o;
    memset(&o, 0, sizeof o);
    if (args->cover)
        o = *args->cover;
    o.threads = args->opt.threads;
    /* Each device batch to the sink as soon as it is read back (the
     * certifier overlaps the device); VORBALL_COVER_STREAM=0 keeps them for
     * the part's end (measurements). */
    const char *sb = getenv("VORBALL_COVER_STREAM");
    o.stream_batches = args->quads_sink && !(sb && strcmp(sb, "0") == 0);
    vb_quad_list q = {0};
    vb_cover_stats st;
    int rc = args->quads_sink
                 ? vb_cover_run_parts(ctx, set, &o, s->be, vb_cover_pipeline_parts(),
                                      args->quads_sink, args->quads_user, &st)
                 : vb_cover_run(ctx, set, &o, s->be, &q, &st);
    if (rc != VB_OK) {
        vb_quad_list_free(&q);
        return rc;
    }
    res->quads.q = q.q;
    res->quads.n = q.n;
    res->quads.cap = q.cap;
    res->complete = 1;
    res->cover_cells = st.cells;
    res->cover_quads = st.quads;
    res->cover_patches = st.patches;
    res->cover_host_cells = st.host_cells;
    res->cover_handed_cells = st.handed_cells;
    res->t_cover_device = st.t_device;
    res->device_bytes_peak = s->be ? s->be->device_bytes_peak : 0;
    res->times.envelope += st.t_host;
    return VB_OK;
}

static const char *cover_backend(const void *state)
{
    const cover_state *s = state;
    return s && s->be ? s->be->name : "ref";
}

static const char *cover_device(const void *state)
{
    const cover_state *s = state;
    return s && s->be ? s->be->device : "host threads";
}

static void cover_close(void *state)
{
    cover_state *s = state;
    if (s)
        vb_cover_backend_close(s->be);
    free(s);
}

const vb_proposer vb_proposer_cover = {
    "cover", cover_open, cover_run, cover_backend, cover_device, cover_close,
};
