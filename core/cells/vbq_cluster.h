/* The exact rank test behind a tie cluster's decision (cover_cluster.c),
 * in two exact arithmetics that give the same answer: 128-bit integers
 * with every operation checked for overflow (cluster_small.c), and GMP
 * (cover_cluster.c), which takes what the first cannot hold. Internal to
 * core/cells; the tests compare the two. */
#ifndef VBQ_CLUSTER_H
#define VBQ_CLUSTER_H

#include <stddef.h>
#include <stdint.h>

#include "vb_spheres.h"

/* What the test found for base i and labels ids[0 .. n): decided = 0 when
 * the labels' vectors V_j = (D_j, Delta_j, N_j) have linear rank >= 4 or
 * some N_j <= 0 (the leaf is enumerated), else 1 with nbasis = their rank
 * (<= 3) and id[0 .. nbasis) the first labels, in list order, that are
 * independent of those before them. */
typedef struct vbq_cluster_ans {
    int decided;
    int nbasis;
    uint32_t id[3];
} vbq_cluster_ans;

typedef __int128 vbq_i128;

/* Checked 128-bit operations: 1 when *r holds the exact result, 0 on
 * overflow (cluster_small.c, cluster_hull.c). */
static inline int vbq_cmul(vbq_i128 a, vbq_i128 b, vbq_i128 *r)
{
    return !__builtin_mul_overflow(a, b, r);
}

static inline int vbq_cadd(vbq_i128 a, vbq_i128 b, vbq_i128 *r)
{
    return !__builtin_add_overflow(a, b, r);
}

static inline int vbq_csub(vbq_i128 a, vbq_i128 b, vbq_i128 *r)
{
    return !__builtin_sub_overflow(a, b, r);
}

/* The decimals x, y, z, r of sphere j scaled to 10^emin, as int64s in o;
 * 0 when one does not fit. */
int vbq_cluster_scaled4(const vb_sphere_set *s, uint32_t j, int32_t emin, int64_t o[4]);

/* v = (D, Delta, N) of sphere j against the base's scaled decimals ci
 * (vbq_cluster_scaled4), exactly; 0 when N does not fit. */
int vbq_cluster_vector(const vb_sphere_set *s, uint32_t j, int32_t emin, const int64_t ci[4],
                       vbq_i128 v[5]);

/* The smallest exponent of the decimals of sphere i and spheres ids[0 ..
 * n): the common scale of the integer vectors. */
int32_t vbq_cluster_emin(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n);

/* The test in checked 128-bit integers, the decimals scaled to 10^emin.
 * Returns 1 with *a filled, or 0 when a number would not fit (nothing
 * decided: ask vbq_cluster_gmp). No allocation. */
int vbq_cluster_small(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                      int32_t emin, vbq_cluster_ans *a);

/* Proves rank >= 4 of the same vectors modulo the prime 2^61 - 1
 * (cluster_modp.c): 1 when it did (vbq_cluster_gmp answers decided = 0),
 * 0 when it proves nothing (ask vbq_cluster_gmp). No allocation. */
int vbq_cluster_modp(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin);

/* The same test in GMP integers (fraction-free elimination); always
 * answers. Allocates only GMP temporaries, freed before it returns. */
void vbq_cluster_gmp(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin, vbq_cluster_ans *a);

/* The decision of labels whose vectors have rank exactly 4 (affine rank 3:
 * cluster_hull.c): the triples of labels that span a supporting plane of
 * their points, 3 ids each, into (*tri, *cap) (grown with VB_ARRAY_FIT),
 * *nt of them. Returns 1 when decided (every vertex of the leaf is a root
 * of one of their quadruples), 0 when not (another rank, some N_j <= 0, a
 * number too large: *nt = 0), -1 out of memory. */
int vbq_cluster_hull(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin, uint32_t **tri, size_t *cap, size_t *nt);

/* A cell's answers so far (cluster_memo.c), so that no list is decided
 * twice: the answer depends on the set's decimals, the base i and the
 * labels in order alone. */
typedef struct vbq_cluster_memo vbq_cluster_memo;

/* An empty memo, or NULL when out of memory. */
vbq_cluster_memo *vbq_cluster_memo_new(void);

/* Frees m (NULL: nothing). */
void vbq_cluster_memo_free(vbq_cluster_memo *m);

/* 1 with *a the answer remembered for base i of s and labels ids[0 .. n)
 * in that order and *tri its hull triples (*nt of them, vbq_cluster_hull;
 * valid until the next put), or 0 when there is none. Asking for another
 * cell (s or i) than the one remembered empties the memo first. */
int vbq_cluster_memo_get(vbq_cluster_memo *m, const vb_sphere_set *s, uint32_t i,
                         const uint32_t *ids, uint32_t n, vbq_cluster_ans *a,
                         const uint32_t **tri, size_t *nt);

/* Remembers answer a of base i of s and labels ids[0 .. n) with its nt
 * hull triples tri (all copied). Out of memory it remembers nothing (the
 * question is answered again later, the same way). */
void vbq_cluster_memo_put(vbq_cluster_memo *m, const vb_sphere_set *s, uint32_t i,
                          const uint32_t *ids, uint32_t n, const vbq_cluster_ans *a,
                          const uint32_t *tri, size_t nt);

#endif
