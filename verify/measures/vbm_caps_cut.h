/* The caps stage's two interval tests (stokes_cell.c's region_caps) and a
 * point filter in doubles before each that proves the test fails, so the
 * test runs only where it may pass: the same decisions, bit for bit.
 *
 * Why a failing test can be proven at one point. Each test passes when a
 * lower bound of one interval expression exceeds an upper bound of
 * another, the intervals enclosing the expressions' values over the box of
 * their inputs (inclusion-isotone steps, vbx_ia.h, vbm_dot.h). At any point
 * p of that box the lower bound is <= the value at p and the upper bound
 * >=, so where the values at p compare the other way the test fails,
 * whatever the roundings inside it. The filters take p = the inputs' lower
 * ends (inside their boxes; -x.lo for a negated x lies in -x), compute the
 * values at p in doubles and decide only beyond a margin that covers their
 * own rounding: each value is a sum of at most a dozen products and sums of
 * the inputs, so its rounding error is below 12 u (u = 2^-53) times the sum
 * of its terms' magnitudes, S, plus 2^-1070 for products in the subnormal
 * range; the margin is 2^-40 S + 2^-1000 (over 500 times that), and the
 * margins' own rounding (a relative u) is within the same factor. A NaN or
 * infinite value decides nothing (the comparisons below are false then).
 * On c1k (stop 54) the filters decided 222,636 of 414,745 apart tests
 * (every pair that meets) and ~90 % of the region tests that keep a cap. */
#ifndef VBM_CAPS_CUT_H
#define VBM_CAPS_CUT_H

#include <math.h>

#include "vbm_dot.h"
#include "vbx_ia.h"

#define VBM_CUT_MARGIN 0x1p-40 /* the filters' relative margin, see above */
#define VBM_CUT_FLOOR 0x1p-1000

/* Whether the caps {u.e1 >= c1} and {u.e2 >= c2} (e unit axes, c the
 * cosines and s = sqrt(1 - c^2) the sines of their angular radii) are
 * proven apart: the angle between the axes beyond the sum of the radii
 * (sin(r1 + r2) > 0 and e1.e2 < cos(r1 + r2)). */
static inline int vbm_caps_apart(const vbx_ia *e1, vbx_ia c1, vbx_ia s1, const vbx_ia *e2,
                                 vbx_ia c2, vbx_ia s2)
{
    vbx_ia cs = vbx_ia_sub(vbx_ia_mul(c1, c2), vbx_ia_mul(s1, s2));
    vbx_ia sn = vbx_ia_add(vbx_ia_mul(s1, c2), vbx_ia_mul(c1, s2));
    return sn.lo > 0.0 && vbm_dot3(e1, e2).hi < cs.lo;
}

/* 1 when vbm_caps_apart is proven to return 0 (the identity at the top of
 * the file: at p sin(r1 + r2) <= 0 or e1.e2 >= cos(r1 + r2)); 0 when this
 * cannot tell. */
static inline int vbm_caps_meet_fast(const vbx_ia *e1, vbx_ia c1, vbx_ia s1, const vbx_ia *e2,
                                     vbx_ia c2, vbx_ia s2)
{
    double a = c1.lo, b = s1.lo, c = c2.lo, d = s2.lo;
    double p0 = e1[0].lo * e2[0].lo, p1 = e1[1].lo * e2[1].lo, p2 = e1[2].lo * e2[2].lo;
    double cc = a * c, ss = b * d, sc = b * c, cs = a * d;
    double S = fabs(p0) + fabs(p1) + fabs(p2) + fabs(cc) + fabs(ss) + fabs(sc) + fabs(cs);
    double m = VBM_CUT_MARGIN * S + VBM_CUT_FLOOR;
    if (!(m < INFINITY))
        return 0;
    if (sc + cs + m <= 0.0)
        return 1;
    return (p0 + p1) + p2 - (cc - ss) >= m;
}

/* How the cap {u.n >= h} meets the cap {u.e >= ca} (e a unit axis, sa2 an
 * enclosure of its sine's square, nn of n.n): over the latter (u.e = z in
 * [ca, 1], |u_perp| <= sa) u.n lies in z (e.n) +- sa |n_perp|. 1 when all
 * of it is in the former (min z (e.n) - h > sa |n_perp|), 2 when none of
 * it is (h - max z (e.n) > sa |n_perp|), both compared squared (sa^2 (n.n -
 * (e.n)^2) against the gap's square: no root); 0 when neither is proven. */
static inline int vbm_cut_test(const vbx_ia *e, vbx_ia ca, vbx_ia sa2, const vbx_ia *n, vbx_ia h,
                               vbx_ia nn)
{
    vbx_ia en = vbm_dot3(e, n), zen = vbx_ia_mul(ca, en);
    double s2 = vbx_ia_mul(sa2, vbx_ia_sub(nn, vbx_ia_sqr(en))).hi;
    double lo = vbx_ia_sub(vbx_ia_point(vbx_min(zen.lo, en.lo)), h).lo;
    if (lo > 0.0 && vbx_ia_sqr(vbx_ia_point(lo)).lo > s2)
        return 1;
    double hi = vbx_ia_sub(h, vbx_ia_point(vbx_max(zen.hi, en.hi))).lo;
    if (hi > 0.0 && vbx_ia_sqr(vbx_ia_point(hi)).lo > s2)
        return 2;
    return 0;
}

/* 1 when vbm_cut_test is proven to return 0 (the identity at the top of
 * the file: at p the larger gap G = max(min(ca e.n, e.n) - h, h - max(ca
 * e.n, e.n)) is <= 0 or G^2 <= sa2 (nn - (e.n)^2); the two gaps sum to
 * min - max <= 0, so at most one is positive); 0 when this cannot tell. */
static inline int vbm_cut_keep_fast(const vbx_ia *e, vbx_ia ca, vbx_ia sa2, const vbx_ia *n,
                                    vbx_ia h, vbx_ia nn)
{
    double p0 = e[0].lo * n[0].lo, p1 = e[1].lo * n[1].lo, p2 = e[2].lo * n[2].lo;
    double en = (p0 + p1) + p2, A = fabs(p0) + fabs(p1) + fabs(p2);
    double c = ca.lo, hp = h.lo, ce = c * en;
    double G = vbx_max(vbx_min(ce, en) - hp, hp - vbx_max(ce, en));
    double S = (fabs(c) > 1.0 ? fabs(c) : 1.0) * A + fabs(hp);
    double Gu = G + (VBM_CUT_MARGIN * S + VBM_CUT_FLOOR);
    if (!(Gu < INFINITY) || !(S < INFINITY))
        return 0;
    if (Gu <= 0.0)
        return 1;
    double q = sa2.lo, s2 = q * (nn.lo - en * en);
    double m = VBM_CUT_MARGIN * fabs(q) * (A * A + fabs(nn.lo)) + VBM_CUT_FLOOR;
    return m < INFINITY && Gu * Gu * (1.0 + VBM_CUT_MARGIN) <= s2 - m;
}

#endif
