/* The channel frame pipeline: the reference engine, the engine a device
 * kind opens, and the fallback from OpenCL to the reference in the middle
 * of a run (see vbc_channel_pipe.h). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "channel_math.h"
#include "vb_array.h"
#include "vb_diag.h"
#include "vb_parallel.h"
#include "vbc_channel_pipe.h"
#include "vbc_paths.h"

struct vbc_pipe {
    vbj_variant variant;
    const vb_device_layer *layer;
    vb_device *dev;      /* OpenCL (NULL on the reference) */
    vbc_engine *engine;
    long ocl_frames;     /* frames run on OpenCL so far */
    long fault_at;       /* vbc_pipe_inject_device_fault */
    /* Held for reading while a pore stage uses the engine's walls (on a
     * thread of its own, frames in flight), for writing while a failed
     * device's engine is closed. */
    pthread_rwlock_t walls_lock;
};

void vbc_frame_out_free(vbc_frame_out *o)
{
    free(o->voxels);
    free(o->flags);
    free(o->labels);
    free(o->clearance);
    free(o->comp);
    memset(o, 0, sizeof *o);
}

int vbc_frame_seeds(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms,
                    vbj_seeds *out)
{
    memset(out, 0, sizeof *out);
    uint32_t n = (uint32_t)g->nx;
    if (n < 2 || (n & (n - 1)) != 0 || g->ny != g->nx || (g->dim == 3 && g->nz != g->nx))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "channel grid %dx%dx%d: sides must be one power of two",
                        g->nx, g->ny, g->nz);
    if (natoms == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, NULL, 0, "no atoms in the frame");
    /* JFA puts pixel p's centre at p, we put voxel i's at i + 0.5. */
    int rc = vbj_seeds_alloc(ctx, g->dim, n, natoms, out);
    for (size_t a = 0; a < natoms && rc == VB_OK; a++)
        rc = vbj_seed_set(ctx, out, a, atoms4[4 * a] - 0.5, atoms4[4 * a + 1] - 0.5,
                          g->dim == 3 ? atoms4[4 * a + 2] - 0.5 : 0.0);
    if (rc != VB_OK)
        vbj_seeds_free(out);
    return rc;
}

void vbc_engine_close(vbc_engine *e)
{
    if (e)
        e->close(e);
}

/* The reference engine's state: its JFA reference backend. */
typedef struct ref_state {
    vbj_variant variant;
    vbj_backend *jfa;
} ref_state;

/* The reference frame when no caller reads the labels or the edge bit of
 * voxels that are not interior (vbc_channel_pipe.h): the masks first, then
 * the exact labels of the voxels that the interior's classification reads
 * only (vbc_masks_need), then that classification. The channel voxels are
 * those of the whole run: the labels read are the same, and a voxel that is
 * not interior is no channel whatever its labels. */
static int ref_frame_interior(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms,
                              const vbj_seeds *seeds, uint8_t *flags, int *rb, vbc_frame_out *out)
{
    double t1 = 1e3 * vb_now();
    uint32_t *list = NULL;
    size_t n = 0;
    int rc = vbc_masks_shape(ctx, g, atoms4, natoms, rb, flags, &list, &n);
    uint8_t *need = rc == VB_OK ? malloc(vbc_grid_voxels(g)) : NULL;
    if (rc == VB_OK && !need)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "channel masks of %zu voxels", vbc_grid_voxels(g));
    if (rc != VB_OK) {
        free(list);
        return rc;
    }
    vbc_masks_need(g, list, n, need);
    double t2 = 1e3 * vb_now();
    vbj_result jr;
    rc = vbj_ref_exact_need(ctx, seeds, need, &jr);
    free(need);
    double t3 = 1e3 * vb_now();
    out->ms_jfa = t3 - t2;
    if (rc == VB_OK) {
        out->jfa = jr.counts;
        n = vbc_masks_edges(g, (const int32_t *)jr.labels, g->dim == 3 ? 3 : 2, rb, list, n, flags);
        /* A shrink that fails leaves the longer block, as good. */
        if (n)
            (void)vb_array_resize((void **)&list, n, sizeof *list);
        out->voxels = n ? list : NULL;
        out->nvoxels = n;
        if (!n)
            free(list);
        list = NULL;
    }
    free(list);
    out->ms_masks = t2 - t1 + (1e3 * vb_now() - t3);
    vbj_result_free(&jr);
    return rc;
}

/* The reference frame: JFA labels in C, the masks of channel_masks_ref.c
 * (bit for bit those of gpu/channels.cl), the voxel list in index order. */
static int ref_frame(vb_ctx *ctx, vbc_engine *e, const vbc_grid *g, const float *atoms4,
                     size_t natoms, double probe, unsigned want, vbc_frame_out *out)
{
    ref_state *st = e->state;
    vbj_seeds seeds;
    vbj_result jr;
    memset(&jr, 0, sizeof jr);
    memset(out, 0, sizeof *out);
    uint8_t *flags = NULL;
    int *rb = NULL;
    (void)probe;
    double t0 = 1e3 * vb_now();
    int rc = vbc_frame_seeds(ctx, g, atoms4, natoms, &seeds);
    if (rc != VB_OK)
        return rc;
    double t1 = 1e3 * vb_now();
    out->ms_upload = t1 - t0;
    flags = malloc(vbc_grid_voxels(g));
    rb = malloc((size_t)vbc_rb_size(g->nx, g->ny, g->nz) * sizeof *rb);
    if (!flags || !rb) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "channel masks of %zu voxels", vbc_grid_voxels(g));
        goto done;
    }
    if (VBJ_IS_EXACT(st->variant) && !(want & (VBC_WANT_LABELS | VBC_WANT_EDGES))) {
        rc = ref_frame_interior(ctx, g, atoms4, natoms, &seeds, flags, rb, out);
    } else {
        vbj_options jo = {st->variant, 0, VBJ_WANT_LABELS, 0};
        if ((rc = vbj_run(ctx, st->jfa, &seeds, &jo, &jr)) != VB_OK)
            goto done;
        double t2 = 1e3 * vb_now();
        out->ms_jfa = t2 - t1;
        out->jfa = jr.counts;
        /* Seed indices are below VBJ_MAX_SEEDS, so the int32 view is lossless. */
        vbc_masks_ref(g, atoms4, natoms, (const int32_t *)jr.labels, g->dim == 3 ? 3 : 2, rb, flags);
        rc = vbc_flags_compact(ctx, g, flags, &out->voxels, &out->nvoxels);
        out->ms_masks = 1e3 * vb_now() - t2;
    }
    if (rc != VB_OK)
        goto done;
    if (want & VBC_WANT_FLAGS) {
        out->flags = flags;
        flags = NULL;
    }
    if (want & VBC_WANT_LABELS) {
        out->labels = jr.labels;
        jr.labels = NULL;
    }
done:
    free(flags);
    free(rb);
    vbj_result_free(&jr);
    vbj_seeds_free(&seeds);
    if (rc != VB_OK)
        vbc_frame_out_free(out);
    return rc;
}

static void ref_close(vbc_engine *e)
{
    ref_state *st = e->state;
    vbj_backend_close(st->jfa);
    free(st);
    free(e);
}

int vbc_engine_ref_open(vb_ctx *ctx, vbj_variant variant, vbc_engine **out)
{
    *out = NULL;
    vbc_engine *e = calloc(1, sizeof *e);
    ref_state *st = calloc(1, sizeof *st);
    int rc = e && st ? vbj_ref_open(ctx, &st->jfa)
                     : vb_error(ctx, VB_ENOMEM, NULL, 0, "channel pipeline");
    if (rc != VB_OK) {
        free(e);
        free(st);
        return rc;
    }
    st->variant = variant;
    e->name = "ref";
    snprintf(e->device, sizeof e->device, "%s", st->jfa->device);
    e->state = st;
    e->frame = ref_frame;
    e->close = ref_close;
    *out = e;
    return VB_OK;
}

static int open_engine(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void *user,
                       void **engine)
{
    const vbc_pipe *p = user;
    vbc_engine *e = NULL;
    int rc = dev ? layer->channels_open(ctx, dev, (int)p->variant, &e)
                 : vbc_engine_ref_open(ctx, p->variant, &e);
    *engine = e;
    return rc;
}

/* Drops the OpenCL engine and its device; the reference takes over. */
static int to_reference(vb_ctx *ctx, vbc_pipe *p)
{
    pthread_rwlock_wrlock(&p->walls_lock);
    vbc_engine_close(p->engine);
    p->engine = NULL;
    if (p->dev)
        p->layer->close(p->dev);
    p->dev = NULL;
    int rc = vbc_engine_ref_open(ctx, p->variant, &p->engine);
    pthread_rwlock_unlock(&p->walls_lock);
    return rc;
}

vb_device_kind vbc_channels_device(vb_device_kind kind, const vb_device_layer *layer)
{
    if (kind != VB_DEVICE_AUTO || (layer && layer->gpu_present && layer->gpu_present()))
        return kind;
    return VB_DEVICE_REF;
}

int vbc_pipe_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device_kind kind,
                  vbj_variant variant, vbc_pipe **out)
{
    *out = NULL;
    vbc_pipe *p = calloc(1, sizeof *p);
    if (!p)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel pipeline");
    p->variant = variant;
    p->layer = layer;
    p->fault_at = -1;
    pthread_rwlock_init(&p->walls_lock, NULL);
    vb_engine_request req = {kind, open_engine, p, VB_W_CHANNELS_DEVICE_FALLBACK, "channels"};
    void *e = NULL;
    int rc = vb_device_open_engine(ctx, layer, &req, &p->dev, &e);
    p->engine = e;
    if (rc != VB_OK) {
        vbc_pipe_close(p);
        return rc;
    }
    *out = p;
    return VB_OK;
}

void vbc_pipe_close(vbc_pipe *p)
{
    if (!p)
        return;
    vbc_engine_close(p->engine);
    if (p->dev)
        p->layer->close(p->dev);
    pthread_rwlock_destroy(&p->walls_lock);
    free(p);
}

const char *vbc_pipe_device_name(const vbc_pipe *p)
{
    return p->engine->device;
}

const struct vbc_paths_engine *vbc_pipe_paths(const vbc_pipe *p)
{
    return p->engine && p->engine->paths ? p->engine->paths : vbc_paths_engine_ref();
}

const struct vbc_walls_engine *vbc_pipe_walls_hold(vbc_pipe *p)
{
    pthread_rwlock_rdlock(&p->walls_lock);
    return p->engine ? p->engine->walls : NULL;
}

void vbc_pipe_walls_release(vbc_pipe *p)
{
    pthread_rwlock_unlock(&p->walls_lock);
}

int vbc_pipe_is_ref(const vbc_pipe *p)
{
    return p->dev == NULL;
}

void vbc_pipe_inject_device_fault(vbc_pipe *p, long frame)
{
    p->fault_at = frame;
}

int vbc_pipe_frame(vb_ctx *ctx, vbc_pipe *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                   double probe, unsigned want, vbc_frame_out *out)
{
    memset(out, 0, sizeof *out);
    if (p->dev) {
        int rc = p->ocl_frames++ == p->fault_at
                     ? vb_error(ctx, VB_EDEVICE, NULL, 0, "injected device fault")
                     : p->engine->frame(ctx, p->engine, g, atoms4, natoms, probe, want, out);
        if (VB_CATEGORY(rc) != VB_EDEVICE)
            return rc;
        vb_device_failed_warn(ctx, VB_W_CHANNELS_DEVICE_FAILED, p->engine->device, vb_errmsg(ctx),
                              "this frame and the rest run on the reference backend (C)");
        vb_clear_error(ctx);
        if ((rc = to_reference(ctx, p)) != VB_OK)
            return rc;
    }
    return p->engine->frame(ctx, p->engine, g, atoms4, natoms, probe, want, out);
}
