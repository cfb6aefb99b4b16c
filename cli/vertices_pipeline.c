/* Backend choice, fallback, sampling and certification for vertices/bench. */
#include "vertices_pipeline.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "vbg_sampler.h"

void vb_pipeline_opts_defaults(vb_pipeline_opts *o)
{
    memset(o, 0, sizeof *o);
    vb_cli_input_defaults(&o->in);
    o->kind = VB_DEVICE_AUTO;
}

int vb_pipeline_option(const char *cmd, int argc, char **argv, int *i, vb_pipeline_opts *o,
                       vb_ctx *ctx)
{
    int used = vb_cli_input_option(&o->in, argc, argv, i);
    if (used != 0)
        return used;
    vb_sampler_options *so = &o->so;
    const char *a = argv[*i];
    int has = *i + 1 < argc;
    if (strcmp(a, "--device") == 0) {
        if (!has || vb_device_kind_parse(ctx, argv[*i + 1], &o->kind) != VB_OK) {
            vb_cli_usage_error(cmd, "--device needs auto, gpu, cpu or ref");
            return -1;
        }
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--samples") == 0) {
        size_t s;
        if (!has || vb_cli_parse_size(argv[*i + 1], &s) || s < 2 || s > 4096) {
            vb_cli_usage_error(cmd, "--samples needs an integer in 2..4096");
            return -1;
        }
        so->samples = (unsigned)s;
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--tol") == 0) {
        double t;
        if (!has || vb_cli_parse_double(argv[*i + 1], &t) || !(t > 0.0)) {
            vb_cli_usage_error(cmd, "--tol needs a positive number");
            return -1;
        }
        so->tol = t;
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--tiles") == 0) {
        size_t t;
        if (!has || vb_cli_parse_size(argv[*i + 1], &t) || t < 1 || t > 64 || (t & (t - 1))) {
            vb_cli_usage_error(cmd, "--tiles needs a power of two in 1..64");
            return -1;
        }
        so->tiles = (unsigned)t;
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--threads") == 0) {
        size_t t;
        if (!has || vb_cli_parse_size(argv[*i + 1], &t) || t < 1 || t > 64) {
            vb_cli_usage_error(cmd, "--threads needs an integer in 1..64");
            return -1;
        }
        so->threads = (unsigned)t;
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--all-pairs") == 0) {
        so->all_pairs = 1;
        return 1;
    }
    return 0;
}

void vb_pipeline_result_init(vb_pipeline_result *r)
{
    memset(r, 0, sizeof *r);
    vb_sampler_result_init(&r->sampler);
    vb_vertex_list_init(&r->certified);
    vb_vertex_list_init(&r->rejected);
}

void vb_pipeline_result_free(vb_pipeline_result *r)
{
    vb_sampler_result_free(&r->sampler);
    vb_vertex_list_free(&r->certified);
    vb_vertex_list_free(&r->rejected);
    vb_pipeline_result_init(r);
}

typedef struct bar {
    double start;
    int shown;
} bar;

/* Draws only after a second and only on a terminal, so logs stay clean. */
static void bar_update(void *user, double frac)
{
    bar *b = user;
    if (vb_now() - b->start < 1.0)
        return;
    int w = 40, k = (int)(frac * w + 0.5);
    fprintf(stderr, "\rsampling [%.*s%*s] %3d%%", k, "########################################",
            w - k, "", (int)(frac * 100.0 + 0.5));
    fflush(stderr);
    b->shown = 1;
}

/* The OpenCL set-up (context, queue, program build or cache load) runs on
 * its own thread, with its own context for messages, while the sampler
 * culls the first batch; the sampler takes the backend (or, when the device
 * cannot be used, the reference backend after warning W760) through
 * await_backend before its first batch. */
typedef struct opener {
    vb_ctx *ctx;              /* the pipeline's context (warnings, fallback) */
    vb_ctx *tctx;             /* the thread's context */
    vb_device_kind kind;
    pthread_t th;
    int started, joined;
    vbg_runtime *rt;
    vb_sampler_backend *be;   /* what await_backend handed out */
    int rc;
    atomic_int done;          /* open_device has finished */
    double t_start, t_setup, t_wait;
} opener;

static void *open_device(void *arg)
{
    opener *op = arg;
    op->rc = op->tctx ? vbg_runtime_open(op->tctx, op->kind, &op->rt) : VB_ENOMEM;
    if (op->rc == VB_OK)
        op->rc = vbg_sampler_open(op->tctx, op->rt, &op->be);
    if (op->rc != VB_OK) {
        vbg_runtime_close(op->rt);
        op->rt = NULL;
        op->be = NULL;
    }
    op->t_setup = vb_now() - op->t_start;
    atomic_store(&op->done, 1);
    return NULL;
}

/* Without its thread the set-up runs inside await_backend: nothing to
 * cull ahead for. */
static int backend_ready(void *user)
{
    opener *op = user;
    return !op->started || atomic_load(&op->done);
}

static void opener_join(opener *op)
{
    if (op->joined)
        return;
    if (op->started)
        pthread_join(op->th, NULL);
    else
        open_device(op);
    op->joined = 1;
}

static vb_sampler_backend *await_backend(void *user)
{
    opener *op = user;
    double t0 = vb_now();
    opener_join(op);
    op->t_wait = vb_now() - t0;
    if (op->rc == VB_OK) {
        vb_info(op->ctx, "OpenCL device: %s", vbg_runtime_device_name(op->rt));
        return op->be;
    }
    vb_warn(op->ctx, 760, NULL, 0, "no usable OpenCL device (%s); using the reference backend",
            op->tctx ? vb_errmsg(op->tctx) : "out of memory");
    if (vb_sampler_ref_open(op->ctx, &op->be) != VB_OK)
        op->be = NULL;
    return op->be;
}

static int sample(vb_ctx *ctx, const vb_sphere_set *set, vb_sampler_backend *be, opener *op,
                  const vb_sampler_options *opt, int progress, vb_pipeline_result *res)
{
    vb_sampler_options o = *opt;
    bar b = {vb_now(), 0};
    if (progress && isatty(fileno(stderr))) {
        o.progress = bar_update;
        o.progress_user = &b;
    }
    if (!be) {
        o.await_backend = await_backend;
        o.backend_ready = backend_ready;
        o.await_user = op;
        /* The batch size cannot wait for the device: GPUs want large
         * launches; the output does not depend on it. */
        if (!o.batch_rays)
            o.batch_rays = op->kind == VB_DEVICE_CPU ? 1u << 22 : 1u << 25;
    }
    int rc = vb_sampler_run(ctx, set, &o, be, &res->sampler);
    if (!be)
        be = op->be;
    if (be) {
        snprintf(res->backend, sizeof res->backend, "%s", be->name);
        snprintf(res->device, sizeof res->device, "%s", be->device);
    }
    if (b.shown)
        fputs("\r\033[K", stderr);
    return rc;
}

/* Sorted quadruples already handed to the certifier. */
typedef struct quads {
    uint32_t *q;
    size_t n, cap;
} quads;

static int cmp_quad_sorted(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    for (int k = 0; k < 4; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

static int quads_add(quads *s, const vb_vertex_list *v)
{
    for (size_t k = 0; k < v->n; k++) {
        if (v->start[k + 1] - v->start[k] != 4)
            continue;
        if (s->n == s->cap) {
            size_t nc = s->cap ? 2 * s->cap : 1024;
            uint32_t *p = realloc(s->q, 4 * nc * sizeof *p);
            if (!p)
                return VB_ENOMEM;
            s->q = p;
            s->cap = nc;
        }
        memcpy(s->q + 4 * s->n++, v->ids + v->start[k], 4 * sizeof *s->q);
    }
    if (s->n)
        qsort(s->q, s->n, 4 * sizeof *s->q, cmp_quad_sorted);
    return VB_OK;
}

/* Appends src to dst, then sorts and drops exact repeats (same members and
 * the same rounded exact point: the same canonical vertex). */
static int merge_certified(vb_vertex_list *dst, const vb_vertex_list *src)
{
    for (size_t k = 0; k < src->n; k++)
        if (vb_vertex_list_push(dst, src->ids + src->start[k], src->start[k + 1] - src->start[k],
                                src->x[k], src->y[k], src->z[k], src->t[k], src->dist[k],
                                src->status[k]))
            return VB_ENOMEM;
    if (vb_vertex_list_sort(dst))
        return VB_ENOMEM;
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    for (size_t k = 0; k < dst->n; k++) {
        size_t n = dst->start[k + 1] - dst->start[k];
        if (k > 0 && n == dst->start[k] - dst->start[k - 1] &&
            memcmp(dst->ids + dst->start[k], dst->ids + dst->start[k - 1], n * sizeof *dst->ids) == 0 &&
            dst->x[k] == dst->x[k - 1] && dst->y[k] == dst->y[k - 1] && dst->z[k] == dst->z[k - 1] &&
            dst->t[k] == dst->t[k - 1])
            continue;
        if (vb_vertex_list_push(&out, dst->ids + dst->start[k], n, dst->x[k], dst->y[k], dst->z[k],
                                dst->t[k], dst->dist[k], dst->status[k])) {
            vb_vertex_list_free(&out);
            return VB_ENOMEM;
        }
    }
    vb_vertex_list_free(dst);
    *dst = out;
    return VB_OK;
}

/* Candidates the certifier refused because a sphere cuts their tangent
 * sphere sit next to vertices with that sphere: certify the quadruples with
 * the intruder swapped in, for a few rounds (jittered lattices, nearly
 * degenerate protein vertices). */
static int repair(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                  vb_pipeline_result *res)
{
    quads seen = {0};
    vb_vertex_list todo, next, ok, bad;
    vb_vertex_list_init(&todo);
    vb_vertex_list_init(&next);
    vb_vertex_list_init(&ok);
    vb_vertex_list_init(&bad);
    int rc = quads_add(&seen, &res->sampler.candidates);
    for (size_t k = 0; rc == VB_OK && k < res->rejected.n; k++)
        rc = vb_vertex_list_push(&todo, res->rejected.ids + res->rejected.start[k],
                                 res->rejected.start[k + 1] - res->rejected.start[k],
                                 res->rejected.x[k], res->rejected.y[k], res->rejected.z[k],
                                 res->rejected.t[k], 0.0, VB_VERTEX_CANDIDATE);
    for (int round = 0; rc == VB_OK && round < 4 && todo.n > 0; round++) {
        vb_vertex_list swaps;
        vb_vertex_list_init(&swaps);
        for (size_t k = 0; rc == VB_OK && k < todo.n; k++) {
            const uint32_t *ids = todo.ids + todo.start[k];
            if (todo.start[k + 1] - todo.start[k] != 4)
                continue;
            double p[4] = {todo.x[k], todo.y[k], todo.z[k], todo.t[k]};
            vb_cert_result cr;
            rc = vb_certify_candidate(ctx, cert, ids, 4, p, 0.0, &cr);
            if (rc == VB_OK && cr.verdict == VB_CERT_INTRUDER)
                rc = vb_sampler_swap_candidates(set, ids, cr.intruder, p, &swaps);
        }
        /* Keep the swaps not certified before. */
        for (size_t k = 0; rc == VB_OK && k < swaps.n; k++) {
            const uint32_t *q = swaps.ids + swaps.start[k];
            if (seen.n && bsearch(q, seen.q, seen.n, 4 * sizeof *seen.q, cmp_quad_sorted))
                continue;
            rc = vb_vertex_list_push(&next, q, 4, swaps.x[k], swaps.y[k], swaps.z[k], swaps.t[k],
                                     0.0, VB_VERTEX_CANDIDATE);
        }
        vb_vertex_list_free(&swaps);
        if (rc == VB_OK)
            rc = quads_add(&seen, &next);
        if (rc == VB_OK)
            rc = vb_certify_list(ctx, cert, &next, 0.0, &ok, &bad);
        if (rc == VB_OK)
            rc = merge_certified(&res->certified, &ok);
        res->repaired_candidates += next.n;
        vb_vertex_list_free(&todo);
        todo = bad;
        vb_vertex_list_init(&bad);
        vb_vertex_list_free(&next);
        vb_vertex_list_free(&ok);
    }
    vb_vertex_list_free(&todo);
    free(seen.q);
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (repair)");
    return rc;
}

/* The device failed mid-run: the reference backend gives the same
 * certified output, so warn (W762), close *be and sample again on a
 * reference backend left in *be. */
static int rerun_on_ref(vb_ctx *ctx, const vb_sphere_set *set, vb_sampler_backend **be,
                        opener *op, const vb_sampler_options *opt, int progress,
                        vb_pipeline_result *res)
{
    vb_warn(ctx, 762, NULL, 0, "OpenCL device failed (%s); rerunning on the reference backend",
            vb_errmsg(ctx));
    vb_clear_error(ctx);
    vb_sampler_backend_close(*be);
    *be = NULL;
    vb_sampler_result_free(&res->sampler);
    int rc = vb_sampler_ref_open(ctx, be);
    return rc == VB_OK ? sample(ctx, set, *be, op, opt, progress, res) : rc;
}

/* Exact certification of the sampled candidates, then the repair rounds;
 * t_certify and t_total (from t0) are set. */
static int certify(vb_ctx *ctx, const vb_sphere_set *set, const vb_sampler_options *opt,
                   double t0, vb_pipeline_result *res)
{
    double t1 = vb_now();
    vb_certifier *cert = NULL;
    int rc = vb_certifier_open(ctx, set, &cert);
    if (rc == VB_OK)
        vb_certifier_set_threads(cert, opt->threads);
    /* No distance limit here: the exact solution nearest the candidate is
     * what gets certified, and far-away vertices (hull cells, nearly
     * coplanar centres) have candidates whose absolute error exceeds tol. */
    if (rc == VB_OK)
        rc = vb_certify_list(ctx, cert, &res->sampler.candidates, 0.0, &res->certified,
                             &res->rejected);
    if (rc == VB_OK)
        rc = repair(ctx, set, cert, res);
    vb_certifier_close(cert);
    for (size_t k = 0; rc == VB_OK && k < res->certified.n; k++)
        if (res->certified.dist[k] > res->max_dist)
            res->max_dist = res->certified.dist[k];
    double t2 = vb_now();
    res->t_certify = t2 - t1;
    res->t_total = t2 - t0;
    return rc;
}

int vb_pipeline_run(vb_ctx *ctx, const vb_sphere_set *set, vb_device_kind kind,
                    const vb_sampler_options *opt, int progress, vb_pipeline_result *res)
{
    double t0 = vb_now();
    vb_sampler_backend *be = NULL;
    vbg_runtime *rt = NULL;
    int rc = VB_OK;
    opener op;
    memset(&op, 0, sizeof op);
    op.ctx = ctx;
    op.kind = kind;
    op.t_start = t0;
    if (kind != VB_DEVICE_REF) {
        if (vb_open(&op.tctx, NULL) != VB_OK)
            op.tctx = NULL;
        op.started = pthread_create(&op.th, NULL, open_device, &op) == 0;
    } else if ((rc = vb_sampler_ref_open(ctx, &be)) != VB_OK) {
        return rc;
    }
    rc = sample(ctx, set, be, &op, opt, progress, res);
    if (kind != VB_DEVICE_REF) {
        opener_join(&op); /* when sampling failed before it needed the device */
        be = op.be;
        rt = op.rt;
        vb_close(op.tctx);
        res->t_setup = op.t_setup;
        res->t_setup_wait = op.t_wait;
    }
    if (rc != VB_OK && VB_CATEGORY(rc) == VB_EDEVICE && rt)
        rc = rerun_on_ref(ctx, set, &be, &op, opt, progress, res);
    /* Releasing the context takes tens of milliseconds on a GPU: after the
     * certification, which does not need it. */
    if (rc == VB_OK)
        rc = certify(ctx, set, opt, t0, res);
    vb_sampler_backend_close(be);
    vbg_runtime_close(rt);
    return rc;
}

int vb_pipeline_device_open(vb_ctx *ctx, vb_device_kind kind, vb_pipeline_device *dev)
{
    double t0 = vb_now();
    memset(dev, 0, sizeof *dev);
    int rc = VB_OK;
    if (kind != VB_DEVICE_REF) {
        rc = vbg_runtime_open(ctx, kind, &dev->rt);
        if (rc == VB_OK)
            rc = vbg_sampler_open(ctx, dev->rt, &dev->be);
        if (rc != VB_OK) {
            if (VB_CATEGORY(rc) == VB_ENOMEM)
                return rc;
            vb_warn(ctx, 760, NULL, 0, "no usable OpenCL device (%s); using the reference backend",
                    vb_errmsg(ctx));
            vb_clear_error(ctx);
            vbg_runtime_close(dev->rt);
            dev->rt = NULL;
        } else {
            vb_info(ctx, "OpenCL device: %s", vbg_runtime_device_name(dev->rt));
        }
    }
    if (!dev->be)
        rc = vb_sampler_ref_open(ctx, &dev->be);
    dev->t_open = vb_now() - t0;
    return rc;
}

void vb_pipeline_device_close(vb_pipeline_device *dev)
{
    vb_sampler_backend_close(dev->be);
    vbg_runtime_close(dev->rt);
    memset(dev, 0, sizeof *dev);
}

int vb_pipeline_run_on(vb_ctx *ctx, const vb_sphere_set *set, vb_pipeline_device *dev,
                       const vb_sampler_options *opt, int progress, vb_pipeline_result *res)
{
    double t0 = vb_now();
    opener unused;
    memset(&unused, 0, sizeof unused);
    int rc = sample(ctx, set, dev->be, &unused, opt, progress, res);
    if (rc != VB_OK && VB_CATEGORY(rc) == VB_EDEVICE && dev->rt) {
        /* Later runs on dev stay on the reference backend. */
        rc = rerun_on_ref(ctx, set, &dev->be, &unused, opt, progress, res);
        vbg_runtime_close(dev->rt);
        dev->rt = NULL;
    }
    return rc == VB_OK ? certify(ctx, set, opt, t0, res) : rc;
}
