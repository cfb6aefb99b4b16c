/* The direction cover (vb_cover.h) behind the proposer table: its OpenCL
 * backend on a device (the device layer's cover_open), or the host's
 * threads. It proposes quadruples whose exact roots hold every vertex, so
 * the result says `complete`; with a sink in the arguments they go to it
 * part by part (vb_cover_run_parts), a device's batches each as a part of
 * its own, for the certifier to overlap. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cert_filter.h"
#include "vb_cover.h"
#include "vb_diag.h"
#include "vb_parallel.h"
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

/* The certification filter between the cover and the certifier: each list
 * of quadruples (a streamed part, or the whole run's) is made canonical
 * and judged, on the device when the backend has the filter, else (or
 * while another part holds the device or its cover runs, or after the
 * device failed) by the twin on host threads; the verdicts travel with the
 * list. */
typedef struct judging {
    cover_state *s;
    vb_cert_filter f;
    unsigned threads;        /* all of the run's host threads */
    vb_cover_sink sink;      /* where judged parts go (NULL: the run's list) */
    void *user;
    vb_ctx *dctx;            /* the device judge's messages (under mu) */
    pthread_mutex_t mu;      /* one device call at a time; failed */
    pthread_mutex_t tmu;     /* t (host threads add to it while the device judges) */
    atomic_int callers;      /* lists being judged now (their threads share the CPUs) */
    double t;                /* seconds judging, summed over the lists */
    int failed;              /* the device judge failed: the twin from then on */
    int tried;               /* the filter was built (or found not to apply) */
} judging;

static int judge_list(judging *j, vb_quad_list *l)
{
    int nt = vb_threads(j->threads);
    int rc = vb_quad_list_canonical(l, nt);
    if (rc != VB_OK || l->n == 0)
        return rc;
    double t0 = vb_now();
    l->verdict = malloc(l->n);
    if (!l->verdict)
        return VB_OK; /* unjudged: the certifier does it all */
    const uint32_t(*q)[4] = (const uint32_t(*)[4])l->q;
    vb_cover_backend *be = j->s->be;
    int done = 0;
    if (be && be->judge && j->dctx && !atomic_load(&be->running) &&
        pthread_mutex_trylock(&j->mu) == 0) {
        if (!j->failed) {
            done = be->judge(j->dctx, be, &j->f, q, l->n, l->verdict) == VB_OK;
            j->failed = !done;
        }
        pthread_mutex_unlock(&j->mu);
    }
    if (!done) {
        int busy = atomic_fetch_add(&j->callers, 1) + 1;
        vb_cert_filter_judge(&j->f, q, l->n, l->verdict,
                             (unsigned)(nt / busy > 0 ? nt / busy : 1));
        atomic_fetch_sub(&j->callers, 1);
    }
    pthread_mutex_lock(&j->tmu);
    j->t += vb_now() - t0;
    pthread_mutex_unlock(&j->tmu);
    return VB_OK;
}

/* vb_cover_sink: the part judged, then handed on. */
static int judge_sink(void *user, vb_quad_list *part)
{
    judging *j = user;
    int rc = judge_list(j, part);
    return rc == VB_OK ? j->sink(j->user, part) : rc;
}

/* Whether the filter judges a run: VORBALL_DEVICE_CERT=1, or unset where
 * the device has the filter (a GPU: device_judges). */
static int judging_wanted(int device_judges)
{
    int mode = vb_cert_filter_mode();
    return mode == 1 || (mode < 0 && device_judges);
}

/* Builds j's filter of set (host work, no device needed); *on = 1 when it
 * was made. j is zeroed first. */
static int judging_build(vb_ctx *ctx, judging *j, const vb_sphere_set *set, int *on)
{
    memset(j, 0, sizeof *j);
    *on = 0;
    j->tried = 1;
    int rc = vb_cert_filter_build(ctx, set, &j->f);
    if (rc != VB_OK || !j->f.ok) {
        vb_cert_filter_free(&j->f);
        return rc;
    }
    *on = 1;
    return VB_OK;
}

/* Sets up j for the run on s: *on = 1 where the filter judges
 * (judging_wanted). A filter built ahead (j->tried, *on) is kept where it
 * judges and freed where it does not; one not tried is built now. */
static int judging_open(vb_ctx *ctx, judging *j, cover_state *s, const vb_sphere_set *set,
                        const vb_propose_args *args, int *on)
{
    if (!judging_wanted(s->be && s->be->judge)) {
        vb_cert_filter_free(&j->f);
        *on = 0;
        return VB_OK;
    }
    int rc = j->tried ? VB_OK : judging_build(ctx, j, set, on);
    if (rc != VB_OK || !*on)
        return rc;
    j->s = s;
    j->threads = args->opt.threads;
    j->sink = args->quads_sink;
    j->user = args->quads_user;
    if (s->be && s->be->judge && vb_open_worker(&j->dctx, ctx) != VB_OK)
        j->dctx = NULL;
    pthread_mutex_init(&j->mu, NULL);
    pthread_mutex_init(&j->tmu, NULL);
    atomic_init(&j->callers, 0);
    return VB_OK;
}

/* W767 when the device's filter failed (the twin judged instead). */
static void judging_close(vb_ctx *ctx, judging *j, vb_proposal *res)
{
    if (j->failed && j->dctx)
        vb_warn(ctx, VB_W_CERT_FILTER_DEVICE, NULL, 0,
                "the certification filter failed on the device (%s): quadruples judged on "
                "host threads",
                vb_errmsg(j->dctx));
    res->t_cert_filter += j->t;
    vb_close(j->dctx);
    pthread_mutex_destroy(&j->mu);
    pthread_mutex_destroy(&j->tmu);
    vb_cert_filter_free(&j->f);
}

static int cover_run(vb_ctx *ctx, void *state, const vb_proposer_await *aw,
                     const vb_sphere_set *set, const vb_propose_args *args,
                     vb_proposal *res)
{
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
    /* What needs no device first, while the device's set-up goes on on its
     * own thread (core/cells/vertices.c): the tree, and the certification
     * filter where the device asked for is likely a GPU (aw->gpu; freed if
     * the device turns out to have none); then the state. */
    judging j;
    memset(&j, 0, sizeof j);
    int on = 0;
    vb_cover_tree *tree = NULL;
    vbq_env env;
    double t0 = vb_now();
    int rc = vb_cover_prepare(ctx, set, &o, &tree, &env);
    if (rc == VB_OK && !state && judging_wanted(aw->gpu))
        rc = judging_build(ctx, &j, set, &on);
    res->t_cover_prepare = vb_now() - t0;
    cover_state *s = rc != VB_OK ? NULL : state ? state : aw->state(aw->user);
    if (rc == VB_OK && !s)
        rc = vb_error(ctx, VB_EINTERNAL, NULL, 0, "no cover backend");
    if (rc == VB_OK)
        rc = judging_open(ctx, &j, s, set, args, &on);
    if (rc != VB_OK) {
        vb_cert_filter_free(&j.f);
        vb_cover_tree_free(tree);
        return rc;
    }
    o.env = &env;
    /* The device's clocks run since it opened (bench reuses it): this
     * run's share is the difference (the most patches of a task: this
     * run's, counted from zero). */
    vb_cover_clocks before = {0};
    if (s->be) {
        memset(s->be->clocks.task_max, 0, sizeof s->be->clocks.task_max);
        s->be->clocks.first_nb_max = s->be->clocks.first_lab_max = 0;
        s->be->clocks.first_q_max = 0;
        before = s->be->clocks;
    }
    if (args->quads_sink && on)
        rc = vb_cover_run_parts(ctx, set, &o, s->be, vb_cover_pipeline_parts(), judge_sink, &j,
                                &st);
    else if (args->quads_sink)
        rc = vb_cover_run_parts(ctx, set, &o, s->be, vb_cover_pipeline_parts(), args->quads_sink,
                                args->quads_user, &st);
    else
        rc = vb_cover_run(ctx, set, &o, s->be, &q, &st);
    if (rc == VB_OK && on && !args->quads_sink)
        rc = judge_list(&j, &q);
    if (on)
        judging_close(ctx, &j, res);
    vb_cover_tree_free(tree);
    if (rc != VB_OK) {
        vb_quad_list_free(&q);
        return rc;
    }
    res->quads.q = q.q;
    res->quads.n = q.n;
    res->quads.cap = q.cap;
    res->quads.verdict = q.verdict;
    res->complete = 1;
    res->cover_cells = st.cells;
    res->cover_quads = st.quads;
    res->cover_patches = st.patches;
    res->cover_host_cells = st.host_cells;
    res->cover_handed_cells = st.handed_cells;
    res->cover_resumed_patches = st.resumed_patches;
    res->cover_neighbours = st.neighbours;
    res->cover_max_cell_neighbours = st.max_cell_neighbours;
    res->t_cover_device = st.t_device;
    for (int i = 0; i < VB_COVER_STEPS && s->be; i++) {
        const vb_cover_clocks *now = &s->be->clocks;
        res->cover_clocks.kernel_s[i] = now->kernel_s[i] - before.kernel_s[i];
        res->cover_clocks.launch_s[i] = now->launch_s[i] - before.launch_s[i];
        res->cover_clocks.launches[i] = now->launches[i] - before.launches[i];
        res->cover_clocks.tasks[i] = now->tasks[i] - before.tasks[i];
        res->cover_clocks.patches[i] = now->patches[i] - before.patches[i];
        res->cover_clocks.wasted_patches[i] = now->wasted_patches[i] - before.wasted_patches[i];
        res->cover_clocks.wasted_tasks[i] = now->wasted_tasks[i] - before.wasted_tasks[i];
        res->cover_clocks.task_max[i] = now->task_max[i];
    }
    if (s->be) {
        const vb_cover_clocks *now = &s->be->clocks;
        res->cover_clocks.first_nb_max = now->first_nb_max;
        res->cover_clocks.first_lab_max = now->first_lab_max;
        res->cover_clocks.first_q_max = now->first_q_max;
        res->cover_clocks.first_past_half = now->first_past_half - before.first_past_half;
    }
    res->cover_steps = st.steps;
    /* The filter's buffers beside the cover's: at most their sum at once. */
    res->device_bytes_peak =
        s->be ? s->be->device_bytes_peak + (on ? s->be->judge_bytes_peak : 0) : 0;
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
