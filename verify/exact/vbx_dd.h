/* Double-double numbers with a proven radius: the rounding filter of
 * vb_certify_quads (quad_filter.c).
 *
 * A value is (h, l, r): some real in [h + l - r, h + l + r], with the pair
 * normalised (|l| <= u |h|, u = 2^-53; every pair below comes out of
 * two_sum, which guarantees it). Operations run in round-to-nearest with no
 * mode switch; two_sum and two_prod are exact (error-free transformations),
 * so the only roundings are the few plain operations named in each bound,
 * and each bound is written beside its constant.
 *
 * Range: the derivations assume no overflow and no underflow. Callers keep
 * every magnitude within [2^-400, 2^900] or exactly 0 (vbx_dd_sane checks
 * the results that matter): the split of two_prod needs |x| < 2^995, and
 * products of low parts stay far above 2^-1022. */
#ifndef VBX_DD_H
#define VBX_DD_H

#include <float.h>
#include <math.h>

typedef struct vbx_dd {
    double h, l, r;
} vbx_dd;

#define VBX_DD_U 0x1p-53
/* One factor for the rounding of a radius: each radius below is a sum and
 * product of at most 6 non-negative doubles computed in round-to-nearest,
 * so the computed value is at least the exact one over (1 + u)^6, and
 * (1 + u)^7 < 1 + 8u = 1 + 2^-50 (with one extra (1 + u) that some bounds
 * fold in, as they say). */
#define VBX_DD_UP (1.0 + 0x1p-50)

/* a + b = s + e exactly (Knuth; no branch, no condition on the order). */
static inline void vbx_two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* a + b = s + e exactly when |a| >= |b| or a = 0 (Dekker's fast two-sum). */
static inline void vbx_fast_two_sum(double a, double b, double *s, double *e)
{
    double x = a + b;
    *s = x;
    *e = b - (x - a);
}

/* Veltkamp's split: x = hi + lo with both parts on 26 bits (exact when
 * |x| < 2^995, so that 134217729 x does not overflow). */
static inline void vbx_split(double x, double *hi, double *lo)
{
    double t = 134217729.0 * x; /* 2^27 + 1 */
    double h = t - (t - x);
    *hi = h;
    *lo = x - h;
}

/* a b = p + e exactly, given no overflow or underflow: Dekker's product,
 * or, where the file is compiled for FMA (quad_filter_fma.c), e = fma(a, b,
 * -p), the one rounding of an exact value that is itself a double. Both
 * give the same p and e (e is the exact remainder), so the results do not
 * depend on which ran. */
static inline void vbx_two_prod(double a, double b, double *p, double *e)
{
    double x = a * b;
    *p = x;
#ifdef VBX_DD_USE_FMA
    *e = __builtin_fma(a, b, -x);
#else
    double ah, al, bh, bl;
    vbx_split(a, &ah, &al);
    vbx_split(b, &bh, &bl);
    *e = ((ah * bh - x) + ah * bl + al * bh) + al * bl;
#endif
}

static inline vbx_dd vbx_dd_exact(double x)
{
    vbx_dd r = {x, 0.0, 0.0};
    return r;
}

static inline vbx_dd vbx_dd_neg(vbx_dd a)
{
    vbx_dd r = {-a.h, -a.l, a.r};
    return r;
}

/* Sum. With S = |h1| + |h2|:
 *   (sh, sl) = two_sum(h1, h2), (th, tl) = two_sum(l1, l2)    exact
 *   v = fl(sl + th)            error e1
 *   (sh2, sl2) = two_sum(sh, v)                               exact
 *   w = fl(sl2 + tl)           error e2
 *   (zh, zl) = two_sum(sh2, w)                                exact
 * so zh + zl = h1 + l1 + h2 + l2 + e1 + e2. |sl| <= u |sh| <= u (1 + u) S
 * and |th| <= (1 + u)(|l1| + |l2|) <= u (1 + u) S, so |e1| <= u |sl + th|
 * <= 2u^2 (1 + u) S; |sh2| <= (1 + u)(|sh| + |v|) <= (1 + u)^2 (1 + 3u) S,
 * |sl2| <= u |sh2| and |tl| <= u |th|, so |e2| <= u^2 (1 + 6u) S. In all
 * |e1| + |e2| <= (3 + 8u) u^2 S <= 3.01 u^2 S. */
static inline vbx_dd vbx_dd_add(vbx_dd a, vbx_dd b)
{
    double sh, sl, th, tl, sh2, sl2;
    vbx_two_sum(a.h, b.h, &sh, &sl);
    vbx_two_sum(a.l, b.l, &th, &tl);
    vbx_two_sum(sh, sl + th, &sh2, &sl2);
    vbx_dd z;
    vbx_two_sum(sh2, sl2 + tl, &z.h, &z.l);
    z.r = (a.r + b.r + 3.01 * VBX_DD_U * VBX_DD_U * (fabs(a.h) + fabs(b.h))) * VBX_DD_UP;
    return z;
}

static inline vbx_dd vbx_dd_sub(vbx_dd a, vbx_dd b)
{
    return vbx_dd_add(a, vbx_dd_neg(b));
}

/* Product. With P = |h1 h2|:
 *   (ph, pl) = two_prod(h1, h2)                               exact
 *   a = fl(h1 l2), b = fl(l1 h2)       errors <= u^2 P each (|h1 l2|,
 *                                      |l1 h2| <= u P)
 *   c = fl(a + b)                      error <= 2u^2 (1 + u) P
 *   d = fl(pl + c)                     error <= u |pl + c| <= 3u^2 (1 + 2u) P
 *   (zh, zl) = fast_two_sum(ph, d)     exact: |d| <= 3u (1 + 2u) P < |ph|,
 *                                      or ph = 0 (then the product is 0)
 * and l1 l2 (<= u^2 P) is dropped: the pair is within (8 + 8u) u^2 P
 * <= 8.01 u^2 P of (h1 + l1)(h2 + l2). The radii add
 * |h1 + l1| r2 + |h2 + l2| r1 + r1 r2 <= (1 + u)(|h1| r2 + |h2| r1) + r1 r2
 * (the (1 + u) is the one VBX_DD_UP folds in). */
static inline vbx_dd vbx_dd_mul(vbx_dd a, vbx_dd b)
{
    double ph, pl;
    vbx_two_prod(a.h, b.h, &ph, &pl);
    double d = pl + (a.h * b.l + a.l * b.h);
    vbx_dd z;
    vbx_fast_two_sum(ph, d, &z.h, &z.l);
    double P = fabs(a.h * b.h);
    z.r = (fabs(a.h) * b.r + fabs(b.h) * a.r + a.r * b.r + 8.01 * VBX_DD_U * VBX_DD_U * P) *
          VBX_DD_UP;
    return z;
}

/* Multiplication by a power of two is exact (no overflow or underflow). */
static inline vbx_dd vbx_dd_scale2(vbx_dd a, double p2)
{
    vbx_dd z = {a.h * p2, a.l * p2, a.r * fabs(p2)};
    return z;
}

/* Square root of a value known to be positive, for r <= h / 4 (else the
 * radius is set to +inf: "cannot tell"). One Newton step from
 * s0 = fl(sqrt(h)): for the exact m = h + l and s* = sqrt(m),
 * s0 + (m - s0^2) / (2 s0) - s* = (s0 - s*)^2 / (2 s0), and
 * |s0 - s*| <= u sqrt(h) + |l| / (2 sqrt(h (1 - u))) <= 1.51 u sqrt(h), so
 * the exact step is within 1.14 u^2 sqrt(h) of s*. Rounding: p + pe = s0^2
 * exactly (two_prod) and h - p is exact (Sterbenz: p is within 3u of h);
 * e = fl(fl(h - p - pe) + l) is within 7.1 u^2 h of m - s0^2 (both sums
 * are at most 4u h in magnitude), and c = fl(e / (2 s0)) within
 * 3.6 u^2 sqrt(h) + u |e| / (2 s0) <= 5.2 u^2 sqrt(h) of (m - s0^2) / (2 s0);
 * two_sum(s0, c) is exact. In all 6.4 u^2 sqrt(h) <= 6.5 u^2 s0: 8 u^2 s0
 * is used. The input radius moves the root by at most
 * r / (sqrt(m - r) + sqrt(m)) <= r / (2 sqrt(0.74 h)) <= 0.59 r / sqrt(h)
 * <= 0.6 r / s0 (m - r >= h (1 - u) - h / 4); 1.5 r / s0 is used. */
static inline vbx_dd vbx_dd_sqrt(vbx_dd a)
{
    vbx_dd z;
    double s0 = sqrt(a.h), p, pe;
    vbx_two_prod(s0, s0, &p, &pe);
    double e = ((a.h - p) - pe) + a.l;
    vbx_two_sum(s0, e / (2.0 * s0), &z.h, &z.l);
    if (!(a.h > 0.0) || !(a.r <= 0.25 * a.h))
        z.r = INFINITY;
    else
        z.r = (8.0 * VBX_DD_U * VBX_DD_U * s0 + 1.5 * a.r / s0) * VBX_DD_UP;
    return z;
}

/* Sign of every value of a, if they share one: +1, -1, or 0 ("cannot
 * tell"). f = fl(h + l) is within u |f| of h + l, so h + l > r when
 * fl(f (1 - 2^-52)) > r (that product is below f (1 - u)); likewise for
 * negative values. A NaN or infinite radius answers 0. */
static inline int vbx_dd_sign(vbx_dd a)
{
    double f = a.h + a.l, m = fabs(f) * (1.0 - 0x1p-52);
    if (!(m > a.r))
        return 0;
    return f > 0.0 ? 1 : -1;
}

/* Magnitudes in the range the bounds assume (and a finite radius). */
static inline int vbx_dd_sane(vbx_dd a)
{
    double m = fabs(a.h);
    return (m == 0.0 || (m >= 0x1p-400 && m <= 0x1p900)) && a.r <= 0x1p900;
}

#endif
