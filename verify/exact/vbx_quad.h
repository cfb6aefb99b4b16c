/* The filtered tangent solve of one quadruple (verify/exact/quad_filter.c), the
 * fast path of vb_certify_quads.
 *
 * Same equations, unknowns and root order as the exact solver
 * (tangent_solver.c): base a = q[0], rows q[1..3], u = (q, s) with
 * q = p - c_a, s = t + R_a in scaled units (input times 10^E), the line
 * u = (U + mu v) / (2 D) and the roots mu = (-B +- sqrt(delta)) / A. When
 * every row entry is below 2^28 (scaled, relative to the base), v, U and D
 * are computed exactly in 128-bit integers and then enclosed in
 * double-double; when an entry is larger (many decimals: a jittered
 * crystal's 12 places put neighbours' rows near 2^42), they are computed in
 * double-double from the exact 64-bit rows, each with its proven radius. A,
 * B, C, delta, the roots and the coordinates are double-double numbers with
 * a proven radius (vbx_dd.h). They give the double intervals of the decisions (t + R_i and
 * the emptiness scan's box) and, by two exact-sign tests at the midpoints
 * around a guess, the correctly rounded coordinates. The exact solver
 * prefers the free unknown s (k = 3) whenever its minor is non-zero; the
 * filter runs only then, so its root with +sqrt(delta) is the exact
 * solver's root[0] (sigma = +1) and the one with -sqrt(delta) its root[1].
 * Two degenerate cases that double-double cannot decide are decided
 * exactly without the solve (verify/exact/quad_rank.c): rows of rank < 3
 * (every v_k zero: coplanar centres of equal radii, the squares of a
 * crystal), where the exact solver finds no root; and delta = 0, whose one
 * root mu = -B / A is the exact solver's root[0] (sigma = 0).
 * Anything else goes to the exact path. */
#ifndef VBX_QUAD_H
#define VBX_QUAD_H

#include <stdint.h>

#include "vbx_dd.h"
#include "vbx_ia.h"

__extension__ typedef __int128 vbx_i128;

typedef struct vbx_qf_ops vbx_qf_ops;

/* The scaled input as 64-bit integers, when it fits (vb_certifier_open). */
typedef struct vbx_qdata {
    const vbx_qf_ops *ops; /* vbx_qf_ops_plain, or vbx_qf_ops_fma on a CPU with FMA */
    int ok;             /* every scaled value fits |z| < 2^62 and 10^E is exact in double */
    const int64_t *z;   /* 4n: X, Y, Z, R times 10^E */
    double scale;       /* 10^E (exact) */
} vbx_qdata;

/* The line of a quadruple: its rows' radii exactly, v, U and D enclosed. */
typedef struct vbx_qline {
    uint32_t q[4];
    int64_t r[4];       /* R_i - R_a (r[0] = 0) */
    vbx_dd v[4], U[3], D; /* v = kernel (v[3] = -D), U = particular solution (U_3 = 0) */
    int exact;          /* 1: vi and Ui hold v and U exactly (rows below 2^28) */
    vbx_i128 vi[4], Ui[3];
} vbx_qline;

/* vbx_qf_line's answers. */
enum vbx_ql_status {
    VBX_QL_EXACT = 0,   /* the filter cannot set up the line: exact path */
    VBX_QL_LINE = 1,    /* the line is set (D != 0 proven) */
    VBX_QL_FLAT = 2     /* proven: the rows have rank < 3 on (d, r), every v_k = 0, so
                           the exact solver returns VBX_SINGULAR: no root, no vertex */
};

enum vbx_qf_status {
    VBX_QF_EXACT = 0,   /* the filter cannot set up or decide the roots: exact path */
    VBX_QF_NONE = 1,    /* proven: no real root (delta < 0) */
    VBX_QF_TWO = 2,     /* two distinct real roots (delta > 0, A != 0 proven) */
    VBX_QF_ONE = 3      /* one real root (delta = 0 exactly, A != 0 proven): root 0,
                           the exact solver's only root (sigma = 0); sq = 0 */
};

/* What the two roots share, in double-double with proven radii. */
typedef struct vbx_qprep {
    vbx_dd v[4], U[3], D, A, B, C, sq; /* sq = sqrt(delta) */
    int sb;                             /* sign of B, 0 when the enclosure cannot tell */
    int delta_exact;                    /* 1: delta's sign came from vbx_qf_delta_sign */
} vbx_qprep;

/* One root: root 0 is the exact solver's sigma = +1, root 1 sigma = -1. */
typedef struct vbx_qroot {
    vbx_dd Pn, Qd;      /* mu = -Pn / Qd */
    vbx_ia s;           /* t + R_a, scaled */
    vbx_dd N[4], Den[2];/* x, y, z = N[k] / Den[0], t = N[3] / Den[1], input units */
    vbx_ia p[4];        /* enclosures of x, y, z, t (the emptiness scans' box) */
    int have_x;         /* X and DQ set (vbx_qf_power_sign, on first use) */
    vbx_dd X[4], DQ;    /* u = X / (2 DQ): X = U Qd - Pn v, DQ = D Qd */
} vbx_qroot;

/* The line of sorted quadruple q: VBX_QL_LINE when the rows fit (|entry|
 * < 2^62 relative to the base, scaled) and D is proven non-zero (the exact
 * solver's k = 3); VBX_QL_FLAT when the rows are proven of rank < 3 on
 * their first four columns (no tangent sphere is a vertex: the exact solver
 * says VBX_SINGULAR); VBX_QL_EXACT otherwise (the exact path decides).
 * Exact in 128-bit integers when every entry is below 2^28, else
 * double-double, with an exact rank test (vbx_qf_rank_low) where D's
 * enclosure holds 0. */
int vbx_qf_line(const vbx_qdata *z, const uint32_t q[4], vbx_qline *L);

/* A, B, C, delta and sqrt(delta) of L: enum vbx_qf_status. Where the
 * double-double delta cannot tell its sign and L is exact, delta's sign is
 * computed exactly (vbx_qf_delta_sign): VBX_QF_ONE for 0. */
int vbx_qf_prep(const vbx_qline *L, vbx_qprep *P);

/* Is the 3x4 integer matrix m (|entry| < 2^62) of rank < 3, every 3x3
 * minor exactly 0? 1 or 0; exact (192-bit sums of int64 x int128
 * products), no allocation (verify/exact/quad_rank.c). */
int vbx_qf_rank_low(const int64_t m[3][4]);

/* The exact sign of delta = B^2 - A C of an exact line (L->exact): -1, 0
 * or +1, from L->vi and L->Ui in GMP integers (verify/exact/quad_rank.c).
 * Only for the rare line whose double-double delta cannot tell. */
int vbx_qf_delta_sign(const vbx_qline *L);

/* Root `root` of a prepared line with two roots (root 0 of one with one
 * root): Pn, Qd and s. */
void vbx_qf_root(const vbx_qprep *P, int root, vbx_qroot *R);

/* Sign of t + R_i at root enclosure s for member index i (0..3): +1, -1,
 * or 0 when the enclosure cannot tell. */
int vbx_qf_tangent_sign(const vbx_qline *L, vbx_ia s, int i);

/* The point of root R: N, Den and the box p. 1, or 0 when a value leaves
 * the range the double-double bounds assume (the exact path decides). */
int vbx_qf_point(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R);

/* Sign of the power |p - c_j|^2 - (t + R_j)^2 of sphere j at root R, in
 * double-double: the emptiness scan's second stage, for a sphere whose
 * distance the point's double box cannot place (nearly on the tangent
 * sphere: a jittered crystal's near-ties, or a flat face's spheres under a
 * vertex far away, where p and t are large and |p - c_j| - R_j - t cancels
 * in doubles). +1 or -1 when proven, 0 when the radius cannot tell or a
 * value leaves vbx_dd.h's range. Its sign is the distance's only where
 * t + R_j >= 0 (the caller proves it). Sets R's X and DQ on first use. */
int vbx_qf_power_sign(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R,
                      uint32_t j);

/* vbx_qf_power_ia's (q, s) of root R (its point set): q = R's x, y, z box
 * times 10^E minus the base's centre, s = R->s (verify/exact/quad_power.c).
 * The same for every sphere of R's scan: made once per root. */
void vbx_qf_power_qs(const vbx_qdata *z, const vbx_qline *L, const vbx_qroot *R, vbx_ia qs[4]);

/* The sign of sphere j's power at the root whose (q, s) are qs, in double
 * intervals: +1 or -1 when proven, 0 when open. It is the distance's sign
 * only where t + R_j > 0 (the caller proves it). */
int vbx_qf_power_ia(const vbx_qdata *z, const vbx_qline *L, const vbx_ia qs[4], uint32_t j);

/* qs as midpoints mr[0..3] and radii mr[4..7] whose boxes contain qs:
 * made once per root for vbx_qf_power_fast. */
void vbx_qf_power_mr(const vbx_ia qs[4], double mr[8]);

/* vbx_qf_power_ia's sign with a static error bound in plain doubles (no
 * interval product): +1 or -1 when the bound proves it, 0 when open (the
 * caller then asks vbx_qf_power_ia). The same condition on t + R_j. */
int vbx_qf_power_fast(const vbx_qdata *z, const vbx_qline *L, const double mr[8], uint32_t j);

/* 1 when every sphere whose exact centre lies in [lo, hi] and whose exact
 * radius lies in [rlo, rhi] (input units) is proven to have a positive
 * power at the root whose (q, s) mr encloses (vbx_qf_power_mr): then
 * |p - c_j| > |t + R_j|, the sphere is strictly outside the tangent ball.
 * 0 when the bound cannot tell. One test clears a whole group of the
 * emptiness scan (a far root over a jittered face: verify/exact/
 * quad_power.c). */
int vbx_qf_power_box(const vbx_qdata *z, const vbx_qline *L, const double mr[8],
                     const double lo[3], const double hi[3], double rlo, double rhi);

/* A root's group test for a scan's hierarchy walk (vbx_walk_skip): its
 * power bound (vbx_qf_power_box) over a group's centre box [lo, hi] and
 * radii in [rmin, rmax] (rmin a bound for every sphere). */
typedef struct vbx_qf_group {
    const vbx_qdata *z;
    const vbx_qline *L;
    const double *mr;
    double rmin;
} vbx_qf_group;
int vbx_qf_group_outside(const void *group, const double lo[3], const double hi[3], double rmax);

/* The correctly rounded x, y, z, t (input units) of a root with its point:
 * 1 when all four are decided (out set), 0 when one is not (a near tie, a
 * value at 0: the caller rounds exactly). */
int vbx_qf_round(const vbx_qroot *R, double out[4]);

/* The double-double steps, in two builds of quad_filter.c with equal
 * results: plain, and compiled for FMA (faster products; vbx_two_prod). */
struct vbx_qf_ops {
    int (*line)(const vbx_qdata *z, const uint32_t q[4], vbx_qline *L);
    int (*prep)(const vbx_qline *L, vbx_qprep *P);
    void (*root)(const vbx_qprep *P, int root, vbx_qroot *R);
    int (*point)(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R);
    int (*round)(const vbx_qroot *R, double out[4]);
    int (*power)(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R,
                 uint32_t j);
};
extern const vbx_qf_ops vbx_qf_ops_plain;
#ifdef VBX_QF_HAVE_FMA
extern const vbx_qf_ops vbx_qf_ops_fma;
#endif

/* The ops for this CPU. */
const vbx_qf_ops *vbx_qf_ops_best(void);

#endif
