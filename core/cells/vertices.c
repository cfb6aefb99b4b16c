/* The vertex pipeline as a library call (vb_vertices.h): the device opened
 * on its own thread by the one fallback rule, the proposer, exact
 * certification through the certifier table, the intruder-swap repair
 * rounds and the canonical merge. Orchestration only: the geometry lives in
 * the proposer, the certifier and vb_sampler_swap_candidates. */
#include "vb_array.h"
#include "vb_cover.h"
#include "vb_vertices.h"

#include "vbv_certify.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_geom_shared.h"
#include "vb_parallel.h"
#include "vb_sampler.h"

static const vb_proposer *proposer_of(vb_ctx *ctx, const vb_vertices_config *cfg)
{
    const vb_proposer *p = vb_proposer_find(cfg->proposer);
    if (!p)
        vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown proposer '%s'", cfg->proposer);
    return p;
}

void vb_vertices_result_init(vb_vertices_result *r)
{
    memset(r, 0, sizeof *r);
    vb_proposal_init(&r->proposal);
    vb_vertex_list_init(&r->certified);
    vb_vertex_list_init(&r->rejected);
}

void vb_vertices_result_free(vb_vertices_result *r)
{
    if (r->part_state && r->part_ops)
        r->part_ops->close(r->part_state);
    if (r->cert && r->cert_ops)
        r->cert_ops->close(r->cert);
    vb_proposal_free(&r->proposal);
    vb_vertex_list_free(&r->certified);
    vb_vertex_list_free(&r->rejected);
    vb_vertices_result_init(r);
}

static int open_proposer(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void *user,
                         void **engine)
{
    const vb_proposer *p = user;
    return p->open(ctx, layer, dev, engine);
}

vb_device_kind vb_vertices_device(const vb_sphere_set *set, const vb_vertices_config *cfg,
                                  const vb_device_layer *layer)
{
    return vb_vertices_device_for(set->n, cfg, layer);
}

vb_device_kind vb_vertices_device_for(size_t n, const vb_vertices_config *cfg,
                                      const vb_device_layer *layer)
{
    if (cfg->device != VB_DEVICE_AUTO || vb_proposer_find(cfg->proposer) != &vb_proposer_cover)
        return cfg->device;
    size_t below = cfg->host_below;
    if (below == 0) {
        const char *env = getenv("VORBALL_HOST_BELOW");
        char *end;
        unsigned long long v = env && *env ? strtoull(env, &end, 10) : 0;
        below = v > 0 && *end == '\0' ? (size_t)v : VB_HOST_BELOW_DEFAULT;
    }
    /* Without a GPU auto stays the CPU device (PoCL), the project's embedded
     * default (STYLE.md), although the host threads took less CPU there at
     * every size measured (results/process_stop43.md). */
    if (n >= below || !layer || !layer->gpu_present || !layer->gpu_present())
        return VB_DEVICE_AUTO;
    return VB_DEVICE_REF;
}

static vb_engine_request request_of(const vb_vertices_config *cfg, const vb_proposer *p)
{
    vb_engine_request req = {cfg->device, open_proposer, (void *)p, VB_W_DEVICE_FALLBACK,
                             "vertices"};
    return req;
}

/* The device set-up (context, queue, program build or cache load) runs on
 * its own thread, with its own context for messages, while the proposer
 * starts (the sampler culls its first batches); the proposer takes its
 * state (or, when the device cannot be used, the twin's after warning
 * W760) through await_state. */
typedef struct opener {
    vb_ctx *ctx;              /* the pipeline's context (warnings, fallback) */
    vb_ctx *tctx;             /* the thread's context */
    const vb_device_layer *layer;
    const vb_proposer *prop;
    vb_engine_request req;
    vb_jobs job;
    int started, joined;
    vb_device *dev;           /* NULL on the twin */
    void *state;              /* what await_state handed out */
    int rc;
    atomic_int done;          /* open_device has finished */
    double t_start, t_setup, t_wait;
} opener;

static void *open_device(void *arg)
{
    opener *op = arg;
    op->rc = op->tctx ? vb_device_try(op->tctx, op->layer, &op->req, &op->dev, &op->state)
                      : VB_ENOMEM;
    op->t_setup = vb_now() - op->t_start;
    atomic_store(&op->done, 1);
    return NULL;
}

/* Without its thread the set-up runs inside await_state: nothing to
 * propose ahead for. */
static int opener_ready(void *user)
{
    opener *op = user;
    return !op->started || atomic_load(&op->done);
}

static void opener_join(opener *op)
{
    if (op->joined)
        return;
    vb_jobs_join(&op->job);
    op->joined = 1;
}

static void *await_state(void *user)
{
    opener *op = user;
    double t0 = vb_now();
    opener_join(op);
    op->t_wait = vb_now() - t0;
    if (op->rc == VB_OK) {
        vb_info(op->ctx, "OpenCL device: %s", op->layer->name(op->dev));
        return op->state;
    }
    if (VB_CATEGORY(op->rc) != VB_EDEVICE) {
        vb_error(op->ctx, op->rc, NULL, 0, "%s", op->tctx ? vb_errmsg(op->tctx) : "out of memory");
        return NULL;
    }
    /* Asked again after the fallback (a proposer reading its backend's
     * figures at the end): the same host state, warned once. */
    if (op->state)
        return op->state;
    vb_device_fallback_warn(op->ctx, &op->req, vb_errmsg(op->tctx));
    if (op->prop->open(op->ctx, op->layer, NULL, &op->state) != VB_OK)
        op->state = NULL;
    return op->state;
}

/* Starts the opener's thread for the device of req (op zeroed before). */
static void opener_start(opener *op, vb_ctx *ctx, const vb_device_layer *layer,
                         const vb_proposer *p, vb_engine_request req)
{
    op->ctx = ctx;
    op->layer = layer;
    op->prop = p;
    op->req = req;
    op->t_start = vb_now();
    if (vb_open_worker(&op->tctx, ctx) != VB_OK)
        op->tctx = NULL;
    op->started = vb_jobs_start(&op->job, open_device, op, sizeof *op, 1) == 1;
}

/* An opener that no run consumed: waited for, and what it opened closed. */
static void opener_drop(opener *op)
{
    opener_join(op);
    if (op->state)
        op->prop->close(op->state);
    if (op->rc == VB_OK && op->dev)
        op->layer->close(op->dev);
    vb_close(op->tctx);
}

/* What a run opened, closed on a thread of its own while the caller goes on
 * (completes and writes): releasing a GPU context takes tens of ms. */
typedef struct closer {
    const vb_proposer *p;
    void *state;
    const vb_device_layer *layer;
    vb_device *dev;
} closer;

static void *close_run(void *arg)
{
    closer *c = arg;
    if (c->state)
        c->p->close(c->state);
    if (c->dev)
        c->layer->close(c->dev);
    return NULL;
}

struct vb_vertices_early {
    opener op;
    vb_device_kind kind;             /* the device it opens */
    const vb_device_layer *layer;
    int taken;                       /* a run consumed op */
    closer cl;                       /* what that run opened, ... */
    vb_jobs closing;                 /* ... closed on this thread */
    int closing_started;
};

int vb_vertices_open_early(vb_ctx *ctx, const vb_vertices_backends *be,
                           const vb_vertices_config *cfg, size_t n_hint,
                           vb_vertices_early **out)
{
    *out = NULL;
    const vb_proposer *p = vb_proposer_find(cfg->proposer);
    vb_device_kind kind = vb_vertices_device_for(n_hint, cfg, be->devices);
    const char *env = getenv("VORBALL_DEVICE_EARLY"); /* "0": opened by the run, for timings */
    if (!p || kind == VB_DEVICE_REF || (env && strcmp(env, "0") == 0))
        return VB_OK;
    vb_vertices_early *e = calloc(1, sizeof *e);
    if (!e)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    vb_vertices_config c = *cfg;
    c.device = kind;
    e->kind = kind;
    e->layer = be->devices;
    opener_start(&e->op, ctx, be->devices, p, request_of(&c, p));
    *out = e;
    return VB_OK;
}

void vb_vertices_early_free(vb_vertices_early *e)
{
    if (!e)
        return;
    if (e->closing_started)
        vb_jobs_join(&e->closing);
    if (!e->taken)
        opener_drop(&e->op);
    free(e);
}

/* The opener of a run on `kind`: cfg->early's when it opens that device on
 * the same layer (then taken), else local, started now (an early one for
 * another device goes on beside the run: vb_vertices_early_free waits for
 * it). */
static opener *opener_of(vb_ctx *ctx, const vb_vertices_config *cfg, const vb_device_layer *layer,
                         const vb_proposer *p, opener *local)
{
    vb_vertices_early *e = cfg->early;
    if (e && !e->taken && e->kind == cfg->device && e->layer == layer && e->op.prop == p) {
        e->taken = 1;
        e->op.ctx = ctx;
        return &e->op;
    }
    opener_start(local, ctx, layer, p, request_of(cfg, p));
    return local;
}

/* Runs the proposer on state (NULL: through await) and names what ran. */
static int propose(vb_ctx *ctx, const vb_proposer *p, void *state, const vb_proposer_await *aw,
                   const vb_sphere_set *set, const vb_propose_args *args, vb_vertices_result *res)
{
    int rc = p->run(ctx, state, aw, set, args, &res->proposal);
    if (!state && aw)
        state = ((opener *)aw->user)->state;
    if (state) {
        snprintf(res->backend, sizeof res->backend, "%s", p->backend(state));
        snprintf(res->device, sizeof res->device, "%s", p->device(state));
    }
    return rc;
}

/* The device failed mid-run: the twin gives the same certified output, so
 * warn (W762), close *state and propose again on the twin, left in *state. */
static int rerun_on_twin(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev,
                         const vb_proposer *p, void **state, const vb_sphere_set *set,
                         const vb_propose_args *args, vb_vertices_result *res)
{
    vb_device_failed_warn(ctx, VB_W_DEVICE_FAILED_RERUN, layer->name(dev), vb_errmsg(ctx),
                          "rerunning on the reference backend");
    vb_clear_error(ctx);
    p->close(*state);
    *state = NULL;
    vb_proposal_free(&res->proposal);
    int rc = p->open(ctx, layer, NULL, state);
    return rc == VB_OK ? propose(ctx, p, *state, NULL, set, args, res) : rc;
}

/* Every exact root of each proposed quadruple, certified: the certifier's
 * own quadruple judge when it has one, else one candidate per double root
 * of the tangent system (vbs_tangent_roots; the base's centre when the
 * double solve finds none), each of which selects the exact root nearest
 * it. */
static int certify_quads(vb_ctx *ctx, const vb_certifier_ops *ops, void *cert,
                         const vb_sphere_set *set, vb_vertices_result *res)
{
    const vb_proposal *sr = &res->proposal;
    if (ops->certify_quads) {
        vb_quad_list l = {sr->quads.q, sr->quads.n, sr->quads.cap, sr->quads.verdict};
        return vbv_certify_quads(ctx, ops, cert, &l, &res->certified, &res->rejected);
    }
    vb_vertex_list cand;
    vb_vertex_list_init(&cand);
    int rc = VB_OK;
    for (size_t k = 0; rc == VB_OK && k < sr->quads.n; k++) {
        const uint32_t *q = sr->quads.q[k];
        double sp[4][4], roots[2][4];
        for (int a = 0; a < 4; a++) {
            sp[a][0] = set->x[q[a]];
            sp[a][1] = set->y[q[a]];
            sp[a][2] = set->z[q[a]];
            sp[a][3] = set->r[q[a]];
        }
        int nr = vbs_tangent_roots(sp, roots);
        if (nr == 0)
            rc = vb_vertex_list_push(&cand, q, 4, sp[0][0], sp[0][1], sp[0][2], 0.0, 0.0,
                                     VB_VERTEX_CANDIDATE);
        for (int r = 0; rc == VB_OK && r < nr; r++)
            rc = vb_vertex_list_push(&cand, q, 4, roots[r][0], roots[r][1], roots[r][2],
                                     roots[r][3], 0.0, VB_VERTEX_CANDIDATE);
    }
    if (rc == VB_OK)
        rc = ops->certify_list(ctx, cert, &cand, &res->certified, &res->rejected);
    vb_vertex_list_free(&cand);
    return rc == VB_ENOMEM ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certify)") : rc;
}

/* Exact certification of the candidates, then the repair rounds (not for
 * a proposer that proves completeness: its refused quadruples are simply
 * not vertices); t_certify and t_total (from t0) are set. The certifier is
 * the stream's when the proposer streamed its quadruples there (their
 * vertices are then merged), else the set-up's (started before the
 * proposer). */
static int certify(vb_ctx *ctx, const vb_certifier_ops *ops, vbv_cert_open *co,
                   vbv_cert_stream *cs, const vb_sphere_set *set, int keep, double t0,
                   vb_vertices_result *res)
{
    double t1 = vb_now();
    int rc = VB_OK;
    void *cert = NULL, *pstate = NULL;
    const vb_part_work *pw = NULL;
    if (cs) {
        rc = vbv_cert_stream_finish(ctx, cs, &res->certified);
        res->t_certify_overlap = cs->t_overlap;
        res->certify_parts = cs->certified_parts;
        res->t_part_overlap = cs->t_pw_overlap;
        res->t_part_after = cs->t_pw - cs->t_pw_overlap;
        pw = cs->pw;
        res->part_work_on = pw != NULL;
        pstate = vbv_cert_stream_take_work(cs);
        cert = vbv_cert_stream_free(cs);
    } else {
        cert = vbv_cert_open_join(ctx, co, &rc);
    }
    /* Quadruples the proposer kept (it streamed none, or had no stream). */
    if (rc == VB_OK && res->proposal.complete && res->proposal.quads.n)
        rc = certify_quads(ctx, ops, cert, set, res);
    else if (rc == VB_OK && !res->proposal.complete)
        rc = ops->certify_list(ctx, cert, &res->proposal.candidates, &res->certified,
                               &res->rejected);
    if (rc == VB_OK && !res->proposal.complete)
        rc = vbv_vertices_repair(ctx, set, ops, cert, res);
    if (cert && rc == VB_OK && keep && !res->cert) {
        /* kept for a later stage on the same set (cfg->keep_certifier) */
        res->cert = cert;
        res->cert_ops = ops;
        res->cert_set = set;
        res->part_state = pstate;
        res->part_ops = pstate ? pw : NULL;
        pstate = NULL;
    } else if (cert) {
        if (pstate) /* its tracers work on cert */
            pw->close(pstate);
        pstate = NULL;
        ops->close(cert);
    }
    if (pstate)
        pw->close(pstate);
    for (size_t k = 0; rc == VB_OK && k < res->certified.n; k++)
        if (res->certified.dist[k] > res->max_dist)
            res->max_dist = res->certified.dist[k];
    double t2 = vb_now();
    res->t_certify = t2 - t1;
    res->t_total = t2 - t0;
    return rc;
}

/* What the proposer sees of cfg: with a stream, the quadruples of a
 * complete proposer go to it part by part. */
static vb_propose_args args_of(const vb_vertices_config *cfg, vbv_cert_stream *cs)
{
    vb_propose_args a = {cfg->propose, cfg->cover, NULL, NULL};
    if (cs) {
        a.quads_sink = vbv_cert_stream_sink;
        a.quads_user = cs;
    }
    return a;
}

/* Starts the set-up and, when the certifier judges quadruples, a stream
 * over it (*csp NULL otherwise, or when the stream cannot be made). */
static void certifier_start(const vb_certifier_ops *ops, const vb_sphere_set *set,
                            const vb_vertices_config *cfg, vbv_cert_open *co,
                            vbv_cert_stream *cs, vbv_cert_stream **csp, vb_ctx *ctx)
{
    vbv_cert_open_start(co, ops, set, cfg->propose.threads, ctx);
    *csp = NULL;
    if (ops->certify_quads && vbv_cert_stream_init(cs, co, ctx) == VB_OK) {
        *csp = cs;
        /* the work's state lives on in the result with the certifier */
        cs->pw = cfg->keep_certifier ? cfg->part_work : NULL;
    }
}

/* A proposal stopped by the stream (its sink failed) carries the stream's
 * error: its message is moved to ctx. Any other status is returned. */
static int stream_error(vb_ctx *ctx, vbv_cert_stream *cs, int rc)
{
    if (rc != VB_OK && cs && cs->rc == rc)
        return vb_error(ctx, rc, NULL, 0, "%s", vb_errmsg(cs->tctx));
    return rc;
}

/* After a failed proposal: the certifier and its work dropped. */
static void certifier_discard(const vb_certifier_ops *ops, vbv_cert_open *co, vbv_cert_stream *cs)
{
    if (cs) {
        void *cert = vbv_cert_stream_free(cs);
        if (cert)
            ops->close(cert);
    } else {
        vbv_cert_open_discard(co);
    }
}

int vb_vertices_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertices_config *cfg,
                    const vb_vertices_backends *be, vb_vertices_result *res)
{
    double t0 = vb_now();
    const vb_proposer *p = proposer_of(ctx, cfg);
    if (!p)
        return VB_EMISUSE;
    vb_vertices_config chosen = *cfg;
    chosen.device = vb_vertices_device(set, cfg, be->devices);
    cfg = &chosen;
    int mrc = vb_vertices_memory_check(ctx, set, cfg, 0);
    if (mrc != VB_OK)
        return mrc;
    void *state = NULL;
    vb_device *dev = NULL;
    int rc = VB_OK, async = cfg->device != VB_DEVICE_REF;
    opener local, *op = NULL;
    memset(&local, 0, sizeof local);
    if (async)
        op = opener_of(ctx, cfg, be->devices, p, &local);
    else if ((rc = p->open(ctx, be->devices, NULL, &state)) != VB_OK)
        return rc;
    vbv_cert_open co;
    vbv_cert_stream css, *cs;
    certifier_start(be->certifier, set, cfg, &co, &css, &cs, ctx);
    vb_propose_args pa = args_of(cfg, cs);
    int gpu = cfg->device == VB_DEVICE_GPU ||
              (cfg->device == VB_DEVICE_AUTO && be->devices && be->devices->gpu_present &&
               be->devices->gpu_present());
    vb_proposer_await aw = {await_state, opener_ready, op, cfg->device, gpu};
    double tp = vb_now();
    rc = propose(ctx, p, state, async ? &aw : NULL, set, &pa, res);
    res->t_propose = vb_now() - tp;
    if (async) {
        opener_join(op); /* when the proposer failed before it needed the device */
        state = op->state;
        dev = op->rc == VB_OK ? op->dev : NULL;
        vb_close(op->tctx);
        op->tctx = NULL;
        res->t_setup = op->t_setup;
        res->t_setup_wait = op->t_wait;
    }
    rc = stream_error(ctx, cs, rc);
    if (rc != VB_OK && VB_CATEGORY(rc) == VB_EDEVICE && dev) {
        if (cs)
            vbv_cert_stream_reset(cs);
        rc = stream_error(ctx, cs, rerun_on_twin(ctx, be->devices, dev, p, &state, set, &pa, res));
    }
    /* Releasing a GPU context takes tens of milliseconds: after the
     * certification, which does not need it. */
    if (rc == VB_OK)
        rc = certify(ctx, be->certifier, &co, cs, set, cfg->keep_certifier, t0, res);
    else
        certifier_discard(be->certifier, &co, cs);
    double tr = vb_now();
    closer cl = {p, state, be->devices, dev};
    vb_vertices_early *e = cfg->early;
    if (e && op == &e->op && !e->closing_started) {
        /* Closed beside what the caller does next; vb_vertices_early_free
         * waits for it. */
        e->cl = cl;
        vb_jobs_start(&e->closing, close_run, &e->cl, sizeof e->cl, 1);
        e->closing_started = 1;
    } else {
        close_run(&cl);
    }
    res->t_release = vb_now() - tr;
    return rc;
}

/* The device is opened at the first run that needs it: the crossover of
 * `--device auto` (vb_vertices_device) depends on the input, which the
 * engine does not know when it is opened. */
struct vb_vertices_engine {
    vb_vertices_backends be;
    const vb_proposer *prop;
    vb_device_kind kind;  /* the device asked for at opening */
    size_t host_below;    /* the opening's crossover (vb_vertices_config) */
    int opened;           /* the device of kind was opened (or fell back) */
    vb_device *dev;       /* NULL on the twin */
    void *state;          /* on dev, or the twin when the device fell back */
    void *host;           /* the twin of runs kept on host threads (crossover) */
    double t_open;
};

int vb_vertices_open(vb_ctx *ctx, const vb_vertices_backends *be, const vb_vertices_config *cfg,
                     vb_vertices_engine **out)
{
    *out = NULL;
    const vb_proposer *p = proposer_of(ctx, cfg);
    if (!p)
        return VB_EMISUSE;
    vb_vertices_engine *e = calloc(1, sizeof *e);
    if (!e)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    e->be = *be;
    e->prop = p;
    e->kind = cfg->device;
    e->host_below = cfg->host_below;
    *out = e;
    return VB_OK;
}

double vb_vertices_open_seconds(const vb_vertices_engine *e)
{
    return e->t_open;
}

void vb_vertices_close(vb_vertices_engine *e)
{
    if (!e)
        return;
    if (e->state)
        e->prop->close(e->state);
    if (e->host)
        e->prop->close(e->host);
    if (e->dev)
        e->be.devices->close(e->dev);
    free(e);
}

/* The device a run of set on e uses: e's kind, or the host threads where
 * the crossover keeps the run (vb_vertices_device). */
static vb_device_kind engine_kind(const vb_vertices_engine *e, const vb_sphere_set *set,
                                  vb_vertices_config *c)
{
    memset(c, 0, sizeof *c);
    c->device = e->kind;
    c->proposer = e->prop->name;
    c->host_below = e->host_below;
    return vb_vertices_device(set, c, e->be.devices);
}

/* The state a run on `kind` proposes on, opened when first needed: the
 * twin when the crossover keeps the run on host threads, else the device
 * of e's kind (W760 and the twin when it cannot be used). */
static int engine_state(vb_ctx *ctx, vb_vertices_engine *e, const vb_vertices_config *c,
                        vb_device_kind kind, void **state)
{
    int rc = VB_OK;
    if (kind == VB_DEVICE_REF && e->kind != VB_DEVICE_REF) {
        if (!e->host)
            rc = e->prop->open(ctx, e->be.devices, NULL, &e->host);
        *state = e->host;
        return rc;
    }
    if (!e->opened) {
        double t0 = vb_now();
        vb_engine_request req = request_of(c, e->prop);
        rc = vb_device_open_engine(ctx, e->be.devices, &req, &e->dev, &e->state);
        if (rc != VB_OK)
            return rc;
        if (e->dev)
            vb_info(ctx, "OpenCL device: %s", e->be.devices->name(e->dev));
        e->opened = 1;
        e->t_open = vb_now() - t0;
    }
    *state = e->state;
    return rc;
}

int vb_vertices_run_on(vb_ctx *ctx, vb_vertices_engine *e, const vb_sphere_set *set,
                       const vb_vertices_config *cfg, vb_vertices_result *res)
{
    vb_vertices_config c, chosen = *cfg;
    chosen.device = engine_kind(e, set, &c);
    int rc = vb_vertices_memory_check(ctx, set, &chosen,
                                      chosen.device == VB_DEVICE_REF || e->opened);
    void *state = NULL;
    if (rc == VB_OK)
        rc = engine_state(ctx, e, &c, chosen.device, &state);
    if (rc != VB_OK)
        return rc;
    double t0 = vb_now(); /* the opening is the engine's, not the run's */
    vbv_cert_open co;
    vbv_cert_stream css, *cs;
    certifier_start(e->be.certifier, set, cfg, &co, &css, &cs, ctx);
    vb_propose_args pa = args_of(cfg, cs);
    double tp = vb_now();
    rc = stream_error(ctx, cs, propose(ctx, e->prop, state, NULL, set, &pa, res));
    res->t_propose = vb_now() - tp;
    if (rc != VB_OK && VB_CATEGORY(rc) == VB_EDEVICE && e->dev && state == e->state) {
        /* Later runs on e stay on the twin. */
        if (cs)
            vbv_cert_stream_reset(cs);
        rc = stream_error(ctx, cs, rerun_on_twin(ctx, e->be.devices, e->dev, e->prop, &e->state,
                                                 set, &pa, res));
        e->be.devices->close(e->dev);
        e->dev = NULL;
    }
    if (rc != VB_OK) {
        certifier_discard(e->be.certifier, &co, cs);
        return rc;
    }
    return certify(ctx, e->be.certifier, &co, cs, set, cfg->keep_certifier, t0, res);
}

void vb_vertices_certificate(const vb_vertices_result *r, char *buf, size_t size)
{
    const vb_proposal *s = &r->proposal;
    if (!s->complete) {
        buf[0] = '\0';
        return;
    }
    snprintf(buf, size,
             "complete: %zu certified vertices, every vertex of the diagram "
             "(direction cover of %llu cells, every root decided exactly)",
             r->certified.n, (unsigned long long)s->cover_cells);
}
