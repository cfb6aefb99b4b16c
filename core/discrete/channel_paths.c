/* The plain-C twin of the channel graph's batch sweeps (vbc_paths.h):
 * relaxation over a frontier to the fixed point, then the predecessor
 * rule, as gpu/channel_paths.cl computes them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_paths_math.h"
#include "vbc_paths.h"

/* pred[q] by the rule of vbc_paths.h from the fixed point dist. */
static void preds(const vbc_paths_graph *G, const vbc_paths_batch *b)
{
    for (size_t q = 0; q < G->n; q++) {
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

int vbc_paths_sweep_ref(const vbc_paths_graph *G, vbc_paths_batch *b)
{
    size_t n = G->n;
    uint32_t *cur = malloc((n ? n : 1) * sizeof *cur), *next = malloc((n ? n : 1) * sizeof *next);
    uint32_t *stamp = malloc((n ? n : 1) * sizeof *stamp);
    if (!cur || !next || !stamp) {
        free(cur);
        free(next);
        free(stamp);
        return -1;
    }
    size_t nc = 0;
    for (size_t t = 0; t < n; t++) {
        b->dist[t] = INFINITY;
        stamp[t] = 0;
    }
    for (size_t i = 0; i < b->nsrc; i++) {
        b->dist[b->src[i]] = 0.0;
        cur[nc++] = b->src[i];
    }
    uint32_t round = 0;
    while (nc > 0) {
        size_t nn = 0;
        round++;
        for (size_t i = 0; i < nc; i++) {
            uint32_t u = cur[i];
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
    b->rounds = round;
    preds(G, b);
    free(cur);
    free(next);
    free(stamp);
    return 0;
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
