/* The matching stage of the sampling pipeline: the phases of vbs_match.h in
 * order over the sorted raw candidates.
 *
 *   1. clusters (Sec. 5.4)                  match_cluster.c
 *   2. plausibility of the clusters         plausibility.c
 *   3. targeted search (Sec. 5.5)           match_targeted.c
 *   4. clusters again, with what 5.5 found  match_cluster.c
 *   5. the counts of the vertices sampled   plausibility.c (below: tally)
 *   6. tangent spheres and swaps (Fig. 8)   quad_roots.c
 *   7. neighbourhood completion             ring_completion.c
 *
 * Phases 6 and 7 fill res->candidates, which the exact certifier judges. */
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

/* Phase 5: the vertices among the clusters: those found from all of their
 * spheres and those with an empty tangent sphere (the spurious ones die
 * there); how many of them sampling and 5.5 did not find from all of their
 * spheres. */
static int tally(const vbs_clusters *m, const vb_cand_vec *raw, const vbs_hash *hash,
                 double tol, int nthreads, vb_proposal *res)
{
    uint32_t *mem = malloc(4 * (raw->n + 1) * sizeof *mem);
    uint32_t *found = malloc((raw->n + 1) * sizeof *found);
    uint8_t *empty = malloc(m->ncl + 1);
    int rc = mem && found && empty ? VB_OK : VB_ENOMEM;
    if (rc == VB_OK)
        rc = vbs_plausible(m, raw, hash, tol, empty, nthreads);
    for (size_t c = 0; rc == VB_OK && c < m->ncl; c++) {
        size_t nm, nf = vbs_cluster_sets(m, raw, c, mem, &nm, found);
        int complete = nf == nm && memcmp(mem, found, nm * sizeof *mem) == 0;
        res->clusters++;
        res->incomplete += (uint64_t)!complete;
        res->sampled_vertices += empty[c];
        res->vertices_incomplete += (uint64_t)(empty[c] && !complete);
    }
    free(mem);
    free(found);
    free(empty);
    return rc;
}

int vbs_match(vb_ctx *ctx, const vb_sphere_set *set, const vbs_culler *cu,
              const vbs_params *params, unsigned target_depth, int nthreads,
              vb_cand_vec *raw, vb_proposal *res)
{
    vbs_clusters m = {set, params->tol, {NULL, 0, 0}, NULL, NULL, NULL, NULL, 0};
    vbs_work *wk = NULL;
    size_t nwk = 0, wcap = 0;
    vb_cand_vec extra = {0};
    uint8_t *plaus = NULL;
    int rc = vbs_clusters_build(&m, raw, nthreads);
    /* A vertex whose tangent sphere is not empty is spurious whichever
     * cells see it: test first, search only for the plausible ones. */
    if (rc == VB_OK && !(plaus = malloc(m.ncl + 1)))
        rc = VB_ENOMEM;
    if (rc == VB_OK)
        rc = vbs_plausible(&m, raw, cu->hash, params->tol, plaus, nthreads);
    if (rc == VB_OK)
        rc = vbs_targeted_work(&m, raw, plaus, &wk, &nwk, &wcap, res);
    double t0 = vb_now();
    if (rc == VB_OK)
        rc = vbs_targeted_search(set, cu, params, target_depth, nthreads, raw, &m, wk, nwk,
                                 &extra, res);
    res->times.targeted += vb_now() - t0;
    /* The candidates 5.5 found follow the raw ones. */
    for (size_t k = 0; rc == VB_OK && k < extra.n; k++)
        if (vb_cand_vec_push(raw, extra.v + k))
            rc = VB_ENOMEM;
    if (rc == VB_OK && extra.n > 0)
        rc = vbs_clusters_build(&m, raw, nthreads);
    if (rc == VB_OK)
        rc = tally(&m, raw, cu->hash, params->tol, nthreads, res);
    double t1 = vb_now();
    /* The rounding guard of the tangent test: 1e-9 of the bounding-box
     * diagonal (the default tol is 1e-5 of it). */
    double diag = 1e5 * vb_sampler_default_tol(set);
    vbs_roots roots = {set, cu->hash, 1e-9 * diag, NULL, 0, {{{NULL, 0, 0, {NULL, 0, 0}}}}, res};
    if (rc == VB_OK)
        rc = vbs_tangent_phase(&roots, raw, nthreads);
    res->from_sampling = res->candidates.n;
    double t2 = vb_now();
    res->times.tangent += t2 - t1;
    if (rc == VB_OK)
        rc = vbs_complete_ring(&roots, nthreads);
    res->times.completion += vb_now() - t2;
    free(roots.qbuf);
    vbs_qset_free(&roots.seen);
    free(plaus);
    vb_cand_vec_free(&extra);
    free(wk);
    vbs_clusters_free(&m);
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "out of memory (matching)");
    return VB_OK;
}
