/* Interval dot products with one rounding bound per end instead of one per
 * operation: the arrangement's 3-vectors (cap_arcs.c, stokes_cell.c) and
 * the Taylor coefficients' convolutions and recurrences (series1.c,
 * series_rat.c), which are most of the cell measures' operations.
 *
 * Proof (round to nearest, u = 2^-53, eta = 2^-1075, no FMA contraction:
 * vbx_ia.h's assumptions), for m <= VBM_DOT_MAX terms. For x_k in A_k and
 * y_k in B_k the exact x_k y_k >= L_k, the least of the four exact corner
 * products, and rounding is monotone, so the least rounded corner is
 * l_k = fl(L_k), with |l_k - L_k| <= u |L_k| + eta (eta: a product in the
 * subnormal range), so |L_k| <= (1 + 2u) |l_k| + 2 eta. The recursive sum
 * s of the l_k (from 0; additions are exact where they would underflow) is
 * within gamma_(m-1) S <= (m - 1)(1 + 16u) u S of their exact sum
 * (Higham's bound), S = sum |l_k|. So
 *   |s - sum L_k| <= (m - 1)(1 + 16u) u S + u (1 + 2u) S + (1 + 2u) m eta
 *                 <= (m + 0.01) u S + 2 m eta.
 * The margin is b = fl(fl(S' w) + 2^-1060), S' the recursive sum of the
 * |l_k| in floating point (>= S (1 - u)^(m-1) >= S (1 - 16u)) and w =
 * (m + 1) 2^-53 (exact); the product loses at most a factor 1 - u or eta
 * (underflow), the addition a factor 1 - u, so b >= (m + 1) u S (1 - 18u) +
 * (2^-1060 - eta)(1 - u) > (m + 0.01) u S + 2 m eta. The low end is
 * pred(fl(s - b)) <= s - b <= sum L_k <= the exact dot product (pred:
 * vbx_ia.h's proof); the high end the same from the greatest corners, with
 * succ. An infinite or NaN corner (S' not finite) takes the
 * operation-by-operation route, as vbx_ia_mul and vbx_ia_add treat it. Two
 * roundings where m products and m - 1 sums take 4m - 2; the width within a
 * few ulps of S of theirs (test_dot3). */
#ifndef VBM_DOT_H
#define VBM_DOT_H

#include <stddef.h>

#include "vbx_ia.h"

#define VBM_DOT_MAX 16 /* the most terms the proof above allows */

/* vbx_ia_mul([a, a], b) bit for bit: its corners a b.lo, a b.hi come
 * twice, and the least (greatest) of x, y, x, y is that of x, y under
 * vbx_min (vbx_max) whatever the NaNs (min(m, m) = m for the m =
 * min(x, y) both halves give). Two products and two comparisons where
 * the general product takes four and six: the pieces' series moved to a
 * point (series_rat.c's shift), constant factors of series (vbm1_affine,
 * vbm1_log's k r_k). */
static inline vbx_ia vbm_ia_mul_point(double a, vbx_ia b)
{
    double p1 = a * b.lo, p2 = a * b.hi;
    vbx_ia r = {vbx_pred(vbx_min(p1, p2)), vbx_succ(vbx_max(p1, p2))};
    return r;
}

/* sum_{k<m} a[k sa] b[k sb], operation by operation (vbx_ia.h). */
static inline vbx_ia vbm_dotn_slow(const vbx_ia *a, ptrdiff_t sa, const vbx_ia *b, ptrdiff_t sb,
                                   int m)
{
    vbx_ia s = vbx_ia_point(0.0);
    for (int k = 0; k < m; k++)
        s = vbx_ia_add(s, vbx_ia_mul(a[k * sa], b[k * sb]));
    return s;
}

/* An enclosure of sum_{k<m} a[k sa] b[k sb] (strides in elements, either
 * sign; 0 <= m <= VBM_DOT_MAX). */
static inline __attribute__((always_inline)) vbx_ia vbm_dotn(const vbx_ia *a, ptrdiff_t sa,
                                                            const vbx_ia *b, ptrdiff_t sb, int m)
{
    if (m <= 0)
        return vbx_ia_point(0.0);
    double sl = 0.0, sh = 0.0, al = 0.0, ah = 0.0;
    for (int k = 0; k < m; k++) {
        vbx_ia x = a[k * sa], y = b[k * sb];
        double p1 = x.lo * y.lo, p2 = x.lo * y.hi, p3 = x.hi * y.lo, p4 = x.hi * y.hi;
        double l = vbx_min(vbx_min(p1, p2), vbx_min(p3, p4));
        double h = vbx_max(vbx_max(p1, p2), vbx_max(p3, p4));
        sl += l;
        sh += h;
        al += fabs(l);
        ah += fabs(h);
    }
    if (!(al < INFINITY && ah < INFINITY))
        return vbm_dotn_slow(a, sa, b, sb, m);
    double w = (double)(m + 1) * 0x1p-53;
    double bl = al * w + 0x1p-1060, bh = ah * w + 0x1p-1060;
    vbx_ia r = {vbx_pred(sl - bl), vbx_succ(sh + bh)};
    return r;
}

/* a . b for 3-vectors: vbm_dotn's operations for m = 3 in its order, bit
 * for bit, unrolled and inlined (the arrangement's restrictions and caps
 * take three at a time; as a call each was a tenth of their work). */
static inline __attribute__((always_inline)) double vbm_lo3(vbx_ia x, vbx_ia y, double *h)
{
    double p1 = x.lo * y.lo, p2 = x.lo * y.hi, p3 = x.hi * y.lo, p4 = x.hi * y.hi;
    *h = vbx_max(vbx_max(p1, p2), vbx_max(p3, p4));
    return vbx_min(vbx_min(p1, p2), vbx_min(p3, p4));
}

static inline __attribute__((always_inline)) vbx_ia vbm_dot3(const vbx_ia *a, const vbx_ia *b)
{
    double h0, h1, h2;
    double l0 = vbm_lo3(a[0], b[0], &h0), l1 = vbm_lo3(a[1], b[1], &h1),
           l2 = vbm_lo3(a[2], b[2], &h2);
    double sl = ((0.0 + l0) + l1) + l2, sh = ((0.0 + h0) + h1) + h2;
    double al = ((0.0 + fabs(l0)) + fabs(l1)) + fabs(l2);
    double ah = ((0.0 + fabs(h0)) + fabs(h1)) + fabs(h2);
    if (__builtin_expect(!(al < INFINITY && ah < INFINITY), 0))
        return vbm_dotn_slow(a, 1, b, 1, 3);
    double w = 4.0 * 0x1p-53;
    double bl = al * w + 0x1p-1060, bh = ah * w + 0x1p-1060;
    vbx_ia r = {vbx_pred(sl - bl), vbx_succ(sh + bh)};
    return r;
}

static inline vbx_ia vbm_dot3_slow(const vbx_ia *a, const vbx_ia *b)
{
    return vbm_dotn_slow(a, 1, b, 1, 3);
}

#endif
