/* The plain-C twin of the channel graph's batch sweeps (vbc_paths.h):
 * relaxation over a frontier to the fixed point, then the predecessor
 * rule, as gpu/channel_paths.cl computes them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_paths_math.h"
#include "vb_parallel.h"
#include "vbc_paths.h"

/* pred[q] by the rule of vbc_paths.h from the fixed point dist, for the
 * positions of slice i (PRED_SLICE of them). */
#define PRED_SLICE 4096

typedef struct {
    const vbc_paths_graph *G;
    vbc_paths_batch *b;
    uint32_t *scratch[VB_MAX_THREADS]; /* per thread: frontier, next, stamps (3 n) */
    uint32_t round[VB_MAX_THREADS];    /* per thread: rounds so far (stamps stay unique) */
} twin;

static void preds(void *arg, size_t i, int tid)
{
    const twin *T = arg;
    const vbc_paths_graph *G = T->G;
    const vbc_paths_batch *b = T->b;
    size_t hi = (i + 1) * PRED_SLICE < G->n ? (i + 1) * PRED_SLICE : G->n;
    (void)tid;
    for (size_t q = i * PRED_SLICE; q < hi; q++) {
        double dq = b->dist[q];
        uint32_t best = UINT32_MAX;
        double bd = INFINITY;
        if (dq > 0.0 && dq < INFINITY)
            for (size_t e = G->adj_start[q]; e < G->adj_start[q + 1]; e++) {
                uint32_t u = G->adj[e];
                double du = b->dist[u];
                if (du + vbc_path_step(G->adj_len[e], G->clear[u], G->clear[q], b->weighted) == dq &&
                    vbc_path_pred_before(du, u, bd, best)) {
                    bd = du;
                    best = u;
                }
            }
        b->pred[q] = best;
    }
}

/* The component of source i relaxed from it over a frontier (the voxels
 * lowered in the round before) until no voxel falls; components are
 * disjoint, so sources run on threads at once. */
static void relax_one(void *arg, size_t i, int tid)
{
    twin *T = arg;
    const vbc_paths_graph *G = T->G;
    vbc_paths_batch *b = T->b;
    uint32_t *cur = T->scratch[tid], *next = cur + G->n, *stamp = next + G->n;
    size_t nc = 1;
    cur[0] = b->src[i];
    b->dist[b->src[i]] = 0.0;
    while (nc > 0) {
        size_t nn = 0;
        uint32_t round = ++T->round[tid];
        for (size_t k = 0; k < nc; k++) {
            uint32_t u = cur[k];
            for (size_t e = G->adj_start[u]; e < G->adj_start[u + 1]; e++) {
                uint32_t q = G->adj[e];
                double nd = b->dist[u] +
                            vbc_path_step(G->adj_len[e], G->clear[u], G->clear[q], b->weighted);
                if (nd < b->dist[q]) {
                    b->dist[q] = nd;
                    if (stamp[q] != round) {
                        stamp[q] = round;
                        next[nn++] = q;
                    }
                }
            }
        }
        uint32_t *t = cur;
        cur = next;
        next = t;
        nc = nn;
    }
}

int vbc_paths_sweep_ref(const vbc_paths_graph *G, vbc_paths_batch *b)
{
    size_t n = G->n;
    int nt = vb_threads(0), ok = 1;
    if ((size_t)nt > b->nsrc)
        nt = b->nsrc ? (int)b->nsrc : 1;
    twin T;
    memset(&T, 0, sizeof T);
    T.G = G;
    T.b = b;
    for (int t = 0; t < nt; t++)
        ok &= (T.scratch[t] = calloc(3 * (n ? n : 1), sizeof(uint32_t))) != NULL;
    if (ok) {
        for (size_t t = 0; t < n; t++)
            b->dist[t] = INFINITY;
        vb_parallel_for(relax_one, &T, b->nsrc, nt);
        b->rounds = 0;
        for (int t = 0; t < nt; t++)
            b->rounds = T.round[t] > b->rounds ? T.round[t] : b->rounds;
        vb_parallel_for(preds, &T, (n + PRED_SLICE - 1) / PRED_SLICE, vb_threads(0));
    }
    for (int t = 0; t < nt; t++)
        free(T.scratch[t]);
    return ok ? 0 : -1;
}

static int ref_begin(void *user, const vbc_paths_graph *G)
{
    (void)user;
    (void)G;
    return VB_EDEVICE; /* no device: every batch on the twin */
}

static void ref_end(void *user)
{
    (void)user;
}

const vbc_paths_engine *vbc_paths_engine_ref(void)
{
    static const vbc_paths_engine ref = {NULL, ref_begin, NULL, ref_end};
    return &ref;
}

int vbc_paths_mode(void)
{
    const char *e = getenv("VORBALL_DEVICE_PATHS");
    return e && (strcmp(e, "1") == 0 || strcmp(e, "2") == 0) ? e[0] - '0' : 0;
}
