/* vb_certify_list: many candidates over worker threads, one canonical result.
 *
 * Phase 1 (parallel): each worker owns a certifier clone (solvers, scratch)
 * and a context (stats, error), takes chunks of candidates from a shared
 * counter and writes each outcome into the candidate's own slot. Phase 2
 * (serial, in candidate order): keys are looked up and the output lists
 * built exactly as one thread does it. Which worker judged a candidate
 * changes nothing it computes, so the lists, keys and summed stats are the
 * same for every thread count. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbx_cert.h"

/* Candidates a worker takes at a time: large enough to make the shared
 * counter cheap, small enough to balance uneven candidates. */
#define CHUNK 32
/* Fewer candidates than this per thread are not worth a thread. */
#define MIN_PER_THREAD 64

/* Outcome of one candidate. */
typedef struct cert_out {
    double x, y, z, t, dist;
    size_t moff;     /* VB_CERT_OK: members in the worker's pool */
    uint32_t nm;
    uint16_t worker;
    int8_t verdict, sigma;
} cert_out;

typedef struct worker {
    vb_certifier *c;
    vb_ctx *ctx;
    uint16_t index;
    uint32_t *pool;  /* members of the certified candidates */
    size_t npool, cap;
    size_t fail_at;  /* candidate of the first error, SIZE_MAX = none */
    int rc;
    const vb_vertex_list *cand;
    double tol;
    cert_out *outs;
    atomic_size_t *next;
} worker;

void vb_certifier_set_threads(vb_certifier *c, unsigned threads)
{
    c->threads = threads;
}

uint64_t vb_certifier_slow_rounds(const vb_certifier *c)
{
    return c->slow_rounds + c->sol.slow_rounds + c->canon.slow_rounds;
}

static int judge(worker *w, size_t k)
{
    const vb_vertex_list *cand = w->cand;
    const uint32_t *ids = cand->ids + cand->start[k];
    size_t nids = cand->start[k + 1] - cand->start[k];
    double p[3] = {cand->x[k], cand->y[k], cand->z[k]};
    vb_cert_result res;
    int sigma = 0;
    int rc = vbx_certify_one(w->ctx, w->c, ids, nids, p, w->tol, &res, &sigma);
    if (rc != VB_OK)
        return rc;
    cert_out *o = &w->outs[k];
    o->x = res.x;
    o->y = res.y;
    o->z = res.z;
    o->t = res.t;
    o->dist = res.dist;
    o->verdict = (int8_t)res.verdict;
    o->sigma = (int8_t)sigma;
    o->worker = w->index;
    o->nm = 0;
    if (res.verdict != VB_CERT_OK)
        return VB_OK;
    if (VB_ARRAY_FIT(w->pool, w->cap, w->npool + res.nmembers, 4096) != VB_OK)
        return vb_error(w->ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    memcpy(w->pool + w->npool, res.members, res.nmembers * sizeof *res.members);
    o->moff = w->npool;
    o->nm = (uint32_t)res.nmembers;
    w->npool += res.nmembers;
    return VB_OK;
}

static void *work(void *arg)
{
    worker *w = arg;
    size_t n = w->cand->n;
    for (;;) {
        size_t k0 = atomic_fetch_add(w->next, CHUNK);
        if (k0 >= n)
            break;
        size_t k1 = k0 + CHUNK < n ? k0 + CHUNK : n;
        for (size_t k = k0; k < k1; k++) {
            int rc = judge(w, k);
            if (rc != VB_OK) {
                w->rc = rc;
                w->fail_at = k;
                return NULL;
            }
        }
    }
    return NULL;
}

/* Phase 1 on nt threads: worker 0 is c itself on the caller's thread and
 * context; the others get clones and contexts of their own. */
static int run_workers(vb_ctx *ctx, vb_certifier *c, worker *ws, unsigned nt)
{
    int rc = VB_OK;
    for (unsigned i = 1; i < nt; i++) {
        ws[i] = ws[0];
        ws[i].index = (uint16_t)i;
        ws[i].ctx = NULL;
        ws[i].c = vbx_certifier_worker(c);
        if (!ws[i].c || vb_open_worker(&ws[i].ctx, ctx) != VB_OK) {
            vb_certifier_close(ws[i].c);
            ws[i].c = NULL;
            rc = VB_ENOMEM;
            break;
        }
    }
    /* A thread that cannot start has its share run by the caller. */
    if (rc == VB_OK)
        vb_run_jobs(work, ws, sizeof *ws, (int)nt);
    for (unsigned i = 1; i < nt; i++) {
        if (!ws[i].c)
            break;
        vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(ws[i].ctx));
        c->slow_rounds += ws[i].c->sol.slow_rounds;
        vb_certifier_close(ws[i].c);
    }
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "out of memory (certifier threads)");
    int bad = vb_jobs_first_error(ws, sizeof *ws, (int)nt, offsetof(worker, rc),
                                  offsetof(worker, fail_at));
    if (bad > 0)
        return vb_error(ctx, ws[bad].rc, NULL, 0, "%s", vb_errmsg(ws[bad].ctx));
    return ws[0].rc;
}

static void free_workers(worker *ws, unsigned nt)
{
    for (unsigned i = 0; i < nt; i++) {
        free(ws[i].pool);
        if (i > 0)
            vb_close(ws[i].ctx);
    }
}

/* Phase 2: the canonical lists, in candidate order. */
static int merge(vb_ctx *ctx, vb_certifier *c, const vb_vertex_list *cand, const cert_out *outs,
                 const worker *ws, vb_vertex_list *out, vb_vertex_list *rejected)
{
    size_t *where = NULL, nwhere = 0; /* key -> index in out, SIZE_MAX = none yet */
    int rc = VB_OK;
    for (size_t k = 0; k < cand->n && rc == VB_OK; k++) {
        const cert_out *o = &outs[k];
        if (o->verdict != VB_CERT_OK) {
            if (rejected)
                rc = vb_vertex_list_push(rejected, cand->ids + cand->start[k],
                                         cand->start[k + 1] - cand->start[k], cand->x[k],
                                         cand->y[k], cand->z[k], cand->t[k], o->dist,
                                         VB_VERTEX_REJECTED);
            continue;
        }
        const uint32_t *m = ws[o->worker].pool + o->moff;
        size_t key;
        rc = vbx_cert_key_of(ctx, c, m, o->nm, o->sigma, &key);
        if (rc != VB_OK)
            break;
        rc = vbx_where_fit(&where, &nwhere, key);
        if (rc != VB_OK)
            break;
        if (where[key] == SIZE_MAX) {
            where[key] = out->n;
            rc = vb_vertex_list_push(out, m, o->nm, o->x, o->y, o->z, o->t, o->dist,
                                     VB_VERTEX_CERTIFIED);
        } else {
            /* Another candidate of a vertex already in out: the stats count
             * canonical vertices, not candidates. */
            vb_ctx_stats(ctx)->certified--;
            if (o->dist > out->dist[where[key]])
                out->dist[where[key]] = o->dist;
        }
    }
    free(where);
    return rc;
}

int vb_certify_list(vb_ctx *ctx, vb_certifier *c, const vb_vertex_list *cand, double tol,
                    vb_vertex_list *out, vb_vertex_list *rejected)
{
    unsigned nt = (unsigned)vb_threads(c->threads);
    size_t most = cand->n / MIN_PER_THREAD;
    if (most < 1)
        most = 1;
    if (nt > most)
        nt = (unsigned)most;
    cert_out *outs = malloc((cand->n ? cand->n : 1) * sizeof *outs);
    worker *ws = calloc(nt, sizeof *ws);
    if (!outs || !ws) {
        free(outs);
        free(ws);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    }
    atomic_size_t next;
    atomic_init(&next, 0);
    ws[0].c = c;
    ws[0].ctx = ctx;
    ws[0].fail_at = SIZE_MAX;
    ws[0].cand = cand;
    ws[0].tol = tol;
    ws[0].outs = outs;
    ws[0].next = &next;
    int rc = run_workers(ctx, c, ws, nt);
    if (rc == VB_OK)
        rc = merge(ctx, c, cand, outs, ws, out, rejected);
    free_workers(ws, nt);
    free(outs);
    free(ws);
    if (rc == VB_OK)
        rc = vb_vertex_list_sort(out);
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    return rc;
}
