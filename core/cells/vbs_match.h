/* Internal to the matching stage of the sampling pipeline: the phases that
 * matching.c runs in order on the sorted raw candidates, one file each.
 *
 *   match_cluster.c    Sec. 5.4   candidates within tol are one vertex
 *   plausibility.c     (ours)     a vertex whose tangent sphere is cut is spurious
 *   match_targeted.c   Sec. 5.5   targeted search from the missing members
 *   quad_roots.c       Fig. 8     both tangent spheres of every quadruple, intruder swaps
 *   ring_completion.c  (ours)     neighbourhood completion across common edges
 *   tangent_test.c     (ours)     the empty-tangent-sphere test in double
 *   quad_set.c         (ours)     the set of quadruples already handled
 *
 * Our additions only ever add candidates: the exact certifier judges them. */
#ifndef VBS_MATCH_H
#define VBS_MATCH_H

#include "vb_hash.h"
#include "vb_uf.h"
#include "vbs_internal.h"

/* ---- Sec. 5.4: clusters (match_cluster.c) ------------------------------ */

/* Clusters of raw candidates: candidate k belongs to cluster cl_of[k];
 * cluster c holds cl_items[cl_start[c] .. cl_start[c+1]). */
typedef struct vbs_clusters {
    const vb_sphere_set *set;
    double tol;
    vb_uf uf;             /* the clusters while they are built */
    uint32_t *order;      /* candidates sorted by x */
    uint32_t *cl_of;      /* cluster of each candidate */
    uint32_t *cl_start;   /* CSR of candidates per cluster */
    uint32_t *cl_items;
    size_t ncl;
} vbs_clusters;

/* Clusters of the candidates of cv closer than m->tol (point and tangent
 * radius); numbered in the order of their first candidate, candidates
 * inside a cluster in their order. Replaces what m held. VB_OK or
 * VB_ENOMEM. */
int vbs_clusters_build(vbs_clusters *m, const vb_cand_vec *cv, int nthreads);
void vbs_clusters_free(vbs_clusters *m);

/* Members (sorted union of ids, *nmem of them, into mem) and finders
 * (sorted bases that found it, returned count, into found) of cluster c.
 * mem holds 4 and found 1 entry per candidate of the cluster. */
size_t vbs_cluster_sets(const vbs_clusters *m, const vb_cand_vec *cv, size_t c, uint32_t *mem,
                        size_t *nmem, uint32_t *found);

/* Ascending sort of four ids (the same order qsort gives, without its call
 * overhead on the hot paths of the swaps and the completion). */
static inline void vbs_sort4(uint32_t q[4])
{
    for (int a = 1; a < 4; a++) {
        uint32_t x = q[a];
        int b = a;
        while (b > 0 && q[b - 1] > x) {
            q[b] = q[b - 1];
            b--;
        }
        q[b] = x;
    }
}

/* ---- the tangent test (tangent_test.c; vbs_tangent_empty in vbs_internal.h) */

/* Returns the sphere (outside q[0..3] and the contained ones) that reaches
 * deepest, by more than tol, into the tangent sphere of candidate k (lowest
 * id on ties), or VBS_INF_COLOUR when there is none. buf/cap: the caller's
 * scratch for the grid query; *err gets VB_ENOMEM on allocation failure. */
uint32_t vbs_tangent_intruder(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4],
                              double tol, uint32_t **buf, size_t *cap, int *err);

/* ---- plausibility (plausibility.c) ------------------------------------- */

/* plaus[c] = 1 for every cluster c of m that needs no tangent test (found
 * from all its members, and not from sphere 0) or whose tangent sphere is
 * empty beyond tol; 0 for the spurious ones. In parallel. VB_OK or
 * VB_ENOMEM. */
int vbs_plausible(const vbs_clusters *m, const vb_cand_vec *raw, const vbs_hash *hash,
                  double tol, uint8_t *plaus, int nthreads);

/* ---- Sec. 5.5: targeted search (match_targeted.c) ---------------------- */

/* One search: vertex `cluster` from the cell of sphere `base`. */
typedef struct vbs_work {
    uint32_t base, cluster;
} vbs_work;

/* Pass 1 over the clusters: completeness, the first cell (Fig. 13), and the
 * searches Sec. 5.5 runs for the plausible incomplete ones (appended to
 * *wk, *nwk of *wcap). Counts complete_first and first_cell in res. */
int vbs_targeted_work(const vbs_clusters *m, const vb_cand_vec *raw, const uint8_t *plaus,
                      vbs_work **wk, size_t *nwk, size_t *wcap, vb_proposal *res);

/* Runs the searches wk[0..nwk) (sorted here) in parallel; what they find
 * is appended to extra in search order (seq renumbered), the counters
 * targeted_searches and targeted_found go to res. VB_OK or VB_ENOMEM. */
int vbs_targeted_search(const vb_sphere_set *set, const vbs_culler *cu, const vbs_params *params,
                        unsigned depth, int nthreads, const vb_cand_vec *raw,
                        const vbs_clusters *m, vbs_work *wk, size_t nwk, vb_cand_vec *extra,
                        vb_proposal *res);

/* ---- the set of handled quadruples (quad_set.c) ------------------------ */

/* VBS_QPARTS tables (the library's vb_hash over an array of the
 * quadruples entered), a quadruple's table chosen by the top bits of its
 * hash, so that inserts into different tables can run on different
 * threads. Zero-initialised is empty. */
#define VBS_QPARTS 64
typedef struct vbs_qtab {
    uint32_t (*keys)[4]; /* the quadruples entered, in order */
    size_t cap, n;       /* keys allocated (VB_ARRAY_FIT), held */
    vb_hash h;           /* items of keys by quadruple */
} vbs_qtab;

typedef struct vbs_qset {
    vbs_qtab part[VBS_QPARTS];
} vbs_qset;

/* 1 when the sorted quadruple q is in the set (read-only: safe on several
 * threads while nobody inserts). */
int vbs_qset_has(const vbs_qset *s, const uint32_t q[4]);

/* Inserts q: 1 if new, 0 if present, -1 on allocation failure. */
int vbs_qset_add(vbs_qset *s, const uint32_t q[4]);

/* Inserts q[k] for every k < n with !skip[k] (skip may be NULL), the
 * tables of the set in parallel. fresh (may be NULL) gets 1 where q[k]
 * entered the set, else 0: within a table the items go in index order, so
 * set and flags are those of vbs_qset_add called for k = 0, 1, ... in turn.
 * Returns VB_OK or VB_ENOMEM. */
int vbs_qset_add_bulk(vbs_qset *s, const uint32_t (*q)[4], size_t n, const uint8_t *skip,
                      uint8_t *fresh, int nthreads);

void vbs_qset_free(vbs_qset *s);

/* ---- Fig. 8: tangent spheres of quadruples (quad_roots.c) -------------- */

/* What the root phases share: the set, its grid, the rounding guard of the
 * tangent test, the quadruples handled so far and the result they add
 * candidates to. */
typedef struct vbs_roots {
    const vb_sphere_set *set;
    const vbs_hash *hash;
    double guard;            /* rounding guard of the tangent test, relative */
    uint32_t *qbuf;
    size_t qcap;
    vbs_qset seen;
    vb_proposal *res;
} vbs_roots;

/* Both tangent spheres (centre, radius) of the spheres q[0..3]
 * (vbs_tangent_roots); returns how many. */
int vbs_quad_roots(const vb_sphere_set *s, const uint32_t q[4], double roots[2][4]);

/* Every distinct quadruple of the raw candidates gets both of its tangent
 * spheres, each kept (res->candidates) when empty; a sampled quadruple
 * whose own sphere is cut tries the quadruples with the intruder swapped
 * in. All of them end in e->seen. Counts dropped and swaps. VB_OK or
 * VB_ENOMEM. */
int vbs_tangent_phase(vbs_roots *e, const vb_cand_vec *raw, int nthreads);

/* ---- neighbourhood completion (ring_completion.c) ---------------------- */

/* Every vertex in e->res->candidates tries, for each triple of its spheres,
 * the spheres that come closest to its tangent sphere as the fourth; new
 * vertices take part in the next round. Counts ring_tries and dropped.
 * VB_OK or VB_ENOMEM. */
int vbs_complete_ring(vbs_roots *e, int nthreads);

#endif
