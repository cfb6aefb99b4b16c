/* The exact side of the envelope decision (core/cells/cover_envelope.c,
 * whose top comment gives the argument and the error bounds), shared by its
 * two ways of finding the envelope's vertices: every owned triple tested
 * (cover_envelope.c) and the convex hull of the lifted points
 * (cover_env_hull.c). Host only. */
#ifndef VBQ_ENV_EXACT_H
#define VBQ_ENV_EXACT_H

#include <math.h>

#include <gmp.h>

#include "vb_cover_shared.h"
#include "vb_spheres.h"
#include "vbq_cluster.h"

/* One label of the patch: its sphere (its exact row is made when the
 * first exact sign is asked). */
typedef struct vbq_env_lab {
    vbs_u32 id;
} vbq_env_lab;

typedef struct vbq_env_rows {
    int made, zmade; /* rd made; row made (GMP) */
    vbs_u32 n;
    mpz_t (*row)[4]; /* n + 1 rows: the labels', then infinity's */
    double (*rd)[4]; /* the rows in doubles (within 2u relative) */
    vbq_i128 (*ri)[4]; /* the rows in 128-bit integers, when ifits */
    int ifits;
    mpz_t q[4], t;
} vbq_env_rows;

/* The decision of one patch, and the exact data of the triple at hand:
 * the cofactors C of the rows of j, k, l (det4[R0; j; k; l] = R0 . C) and
 * their doubles (made at the triple's first exact sign; a caller that
 * moves to another triple sets tri_made, fast_made and tri_i to 0). */
typedef struct vbq_env_ctx {
    const vb_sphere_set *s;
    vbs_u32 i, n;
    vbq_env_lab *L;
    vbq_env_rows X;
    int tri_made, fast_made;
    mpz_t C[4], m2[6], acc;
    double c[4];
    double f[4], fe[4]; /* the cofactors from the rows' doubles, and their error bounds */
    vbq_i128 ci[4];     /* the cofactors in 128 bits: tri_i 1 made, -1 they do not fit */
    int tri_i;
    int zinit;          /* the GMP integers (C, m2, acc, X.q, X.t) initialised */
    vbs_u32 exact_calls;
} vbq_env_ctx;

/* The exact sign of det[X; a_k - a_j; a_l - a_j] over the labels of c
 * (indices into c->L; c->n is infinity, a = 0): X = a_m - a_j when q is
 * NULL, else X = q (a row of exact doubles). A proven double filter on the
 * exact rows first, then GMP. Returns -1, 0 or 1, or 2 when it cannot be
 * decided (no memory). Counts itself in c->exact_calls. */
int vbq_env_sign_exact(vbq_env_ctx *c, const double *q, vbs_u32 m, vbs_u32 j, vbs_u32 k,
                       vbs_u32 l);

/* What c allocated, released (its GMP integers are made when the first
 * sign needs them). */
void vbq_env_ctx_free(vbq_env_ctx *c);

/* The rows' doubles rd of c made (vbq_env_sign_exact makes them when
 * first asked). 0: no memory. */
int vbq_env_rows_made(vbq_env_ctx *c);

/* The cofactors of rows j, k, l of det4[R0; j; k; l] = R0 . C in doubles
 * from the rows' doubles (c's rd made): f within fe of C, per entry. */
void vbq_env_cofactors(const vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l, double f[4],
                       double fe[4]);

/* The sign of -det4[R0; j; k; l] (vbq_env_sign_exact's) from row R0's
 * doubles r (a label's rd, or (0, q)) and the cofactors' doubles f, fe of
 * vbq_env_cofactors: -1 or 1 when proven, 0 when the filter cannot tell.
 * Inline: the hull decision (cover_env_hull.c) takes millions of these. */
static inline int vbq_env_sign_rows(const double r[4], const double f[4], const double fe[4])
{
    /* With R0 the exact row (|r - R0| <= 2u |R0|; a q row is exact),
     * |r . f - R0 . C| <= sum |r_a| (2.01u |f_a| + 1.01 fe_a), and forming
     * r . f adds at most 4.01u sum |r_a f_a|: 8u of that sum and 1.01 of
     * sum |r_a| fe_a, with 1 + 1e-12 for the bound's own roundings. */
    double v = 0.0, g = 0.0, ge = 0.0;
    for (int a = 0; a < 4; a++) {
        v += r[a] * f[a];
        g += fabs(r[a] * f[a]);
        ge += fabs(r[a]) * fe[a];
    }
    double b = (8.0 * VBQ_U * g + 1.01 * ge) * (1.0 + 1e-12) + VBQ_TINY;
    return isfinite(b) && (v > b || v < -b) ? (v > b ? -1 : 1) : 0;
}

/* The envelope decision of patch qs (vbq_env_sides) of cell c->i over the
 * labels c->L[0 .. c->n) (equal radii) from the
 * convex hull of their points a_k and the origin (infinity): adds the
 * quadruple (i, j, k, l) of every owned triple that lies on a face of the
 * hull whose outward normal W is in the patch's closed cone (n . W > 0),
 * whose value a_j . W is positive, and whose three points are affinely
 * independent: the same set as testing every owned triple
 * (cover_envelope.c's top). Returns 1 when decided, 0 when it cannot
 * decide (no memory: nothing it added is wrong, the caller subdivides),
 * -1 when q is full (o->status set). Allocates only for its call. */
int vbq_env_hull(vbq_env_ctx *c, const vbq_arena *ar, vbq_cell_out *o, double qs[5][3]);

#endif
