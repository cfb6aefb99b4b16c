/* The interval dot product of 3-vectors that the arrangement of an atom's
 * regions of directions spends most of its operations on (cap_arcs.c,
 * stokes_cell.c): one rounding bound per end instead of one per operation.
 *
 * Proof (round to nearest, u = 2^-53, eta = 2^-1075, no FMA contraction:
 * vbx_ia.h's assumptions). For x_k in A_k and y_k in B_k the exact
 * x_k y_k >= L_k, the least of the four exact corner products, and
 * rounding is monotone, so the least rounded corner is l_k = fl(L_k), with
 * |l_k - L_k| <= u |L_k| + eta (eta: a product in the subnormal range) and
 * so |L_k| <= (1 + 2u) |l_k| + 2 eta. The sum s = fl(fl(l_0 + l_1) + l_2)
 * (additions are exact where they would underflow) is within
 * (2u + u^2) S of l_0 + l_1 + l_2, S = |l_0| + |l_1| + |l_2|. So
 *   |s - sum L_k| <= (2u + u^2) S + u (1 + 2u) S + 6u eta + 3 eta
 *                 <= 3.01 u S + 4 eta.
 * The bound is made as b = fl(fl(fl(|l_0| + |l_1|) + |l_2|) 2^-51 +
 * 2^-1070): the computed S is at least S (1 - u)^2, times the power of two
 * exactly or (underflow) within eta, and the last addition loses at most a
 * factor 1 - u, so b >= (4u S (1 - 2u) - eta + 32 eta) (1 - u) >=
 * 4u S (1 - 3u) + 30 eta > 3.01 u S + 4 eta. The low end is pred(fl(s - b)) <= s - b <=
 * sum L_k <= the exact dot product (pred: vbx_ia.h's proof); the high end
 * the same from the greatest corners, with succ. An infinite or NaN corner
 * (S not finite) takes the operation-by-operation route. Two roundings
 * where three vbx_ia_mul and two vbx_ia_add take ten; the width within a
 * few ulps of S of theirs (test_dot3). */
#ifndef VBM_DOT_H
#define VBM_DOT_H

#include "vbx_ia.h"

static inline vbx_ia vbm_dot3_slow(const vbx_ia *a, const vbx_ia *b)
{
    return vbx_ia_add(vbx_ia_add(vbx_ia_mul(a[0], b[0]), vbx_ia_mul(a[1], b[1])),
                      vbx_ia_mul(a[2], b[2]));
}

/* An enclosure of a . b (a, b three intervals each). */
static inline vbx_ia vbm_dot3(const vbx_ia *a, const vbx_ia *b)
{
    double l[3], h[3];
    for (int k = 0; k < 3; k++) {
        double p1 = a[k].lo * b[k].lo, p2 = a[k].lo * b[k].hi, p3 = a[k].hi * b[k].lo,
               p4 = a[k].hi * b[k].hi;
        l[k] = vbx_min(vbx_min(p1, p2), vbx_min(p3, p4));
        h[k] = vbx_max(vbx_max(p1, p2), vbx_max(p3, p4));
    }
    double sl = (l[0] + l[1]) + l[2], sh = (h[0] + h[1]) + h[2];
    double al = (fabs(l[0]) + fabs(l[1])) + fabs(l[2]);
    double ah = (fabs(h[0]) + fabs(h[1])) + fabs(h[2]);
    if (!(al < INFINITY && ah < INFINITY))
        return vbm_dot3_slow(a, b);
    double bl = al * 0x1p-51 + 0x1p-1070, bh = ah * 0x1p-51 + 0x1p-1070;
    vbx_ia r = {vbx_pred(sl - bl), vbx_succ(sh + bh)};
    return r;
}

#endif
