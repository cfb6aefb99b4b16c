/* Plausibility of the clusters (ours): a vertex whose tangent sphere is cut
 * by another sphere (beyond tol) is spurious whichever cells see it, so the
 * test runs before the targeted search (only plausible vertices are
 * searched) and again after it, for the counts. Only clusters that need it
 * are tested: incomplete ones, and those seen from sphere 0 (Fig. 13). */
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

typedef struct plaus_ctx {
    const vbs_clusters *m;
    const vb_cand_vec *raw;
    const vbs_hash *hash;
    double tol;
    uint8_t *plaus;
    uint32_t *mem[VB_MAX_THREADS], *found[VB_MAX_THREADS];
    uint32_t *tbuf[VB_MAX_THREADS];
    size_t tcap[VB_MAX_THREADS], mcap[VB_MAX_THREADS];
    int err;
} plaus_ctx;

static void plaus_eval(void *arg, size_t c, int tid)
{
    plaus_ctx *p = arg;
    const vbs_clusters *m = p->m;
    size_t k = m->cl_start[c + 1] - m->cl_start[c];
    if (p->mcap[tid] < k) {
        size_t nc = 2 * k;
        uint32_t *a = realloc(p->mem[tid], 4 * nc * sizeof *a);
        uint32_t *b = a ? realloc(p->found[tid], nc * sizeof *b) : NULL;
        if (a)
            p->mem[tid] = a;
        if (b)
            p->found[tid] = b;
        if (!b) {
            p->err = VB_ENOMEM;
            return;
        }
        p->mcap[tid] = nc;
    }
    size_t nm, nf = vbs_cluster_sets(m, p->raw, c, p->mem[tid], &nm, p->found[tid]);
    p->plaus[c] = 1;
    if (nf < nm || p->found[tid][0] == 0) {
        const vbs_cand *rep = p->raw->v + m->cl_items[m->cl_start[c]];
        uint32_t q4[4];
        memcpy(q4, rep->ids, sizeof q4);
        int rc = VB_OK;
        p->plaus[c] = vbs_tangent_intruder(p->hash, rep, q4, p->tol, &p->tbuf[tid], &p->tcap[tid],
                                       &rc) == VBS_INF_COLOUR;
        if (rc != VB_OK)
            p->err = rc;
    }
}

int vbs_plausible(const vbs_clusters *m, const vb_cand_vec *raw, const vbs_hash *hash,
                         double tol, uint8_t *plaus, int nthreads)
{
    plaus_ctx pc;
    memset(&pc, 0, sizeof pc);
    pc.m = m;
    pc.raw = raw;
    pc.hash = hash;
    pc.tol = tol;
    pc.plaus = plaus;
    vb_parallel_for(plaus_eval, &pc, m->ncl, nthreads);
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        free(pc.mem[t]);
        free(pc.found[t]);
        free(pc.tbuf[t]);
    }
    return pc.err;
}
