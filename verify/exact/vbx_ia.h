/* Interval arithmetic in double: the filter of every exact predicate.
 *
 * Error bound (the only one the filters rely on). IEEE 754 binary64 in
 * round-to-nearest returns, for an exact result x of +, -, *, / or sqrt on
 * doubles, the double r nearest to x. The gap between r and its neighbours
 * is at least twice |x - r| on the side where x lies (at a power of two the
 * gap below is half the gap above, and x rounds to r only from within half
 * of the gap on its own side), so  pred(r) <= x <= succ(r).  This holds for
 * subnormal results too, and at overflow: r = +inf means x > DBL_MAX, and
 * pred(+inf) = DBL_MAX. Every bound below is therefore computed in plain
 * round-to-nearest and moved one step outward: no rounding-mode switches, no
 * reliance on -frounding-math, and the enclosure is proven op by op.
 *
 * Bounds may become infinite (an interval never collapses to [inf, inf]:
 * pred(+inf) = DBL_MAX); see vbx_min for NaN corners. The filters decide only on "lo > 0" or "hi < 0", so an unbounded or NaN bound
 * answers "cannot tell" and the exact path runs. Requires FLT_EVAL_METHOD == 0 (no x87 excess precision) and no
 * contraction into FMA (-ffp-contract=off is global; an FMA would round once
 * and stay enclosed anyway). */
#ifndef VBX_IA_H
#define VBX_IA_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "vbx_ia.h needs FLT_EVAL_METHOD == 0 (SSE2 doubles)"
#endif

typedef struct vbx_ia {
    double lo, hi;
} vbx_ia;

/* Next double towards +inf (x itself for +inf and NaN), on the bit
 * pattern (vbx_succ below is the same function). For finite non-zero x the
 * bit pattern moves by one unit towards +inf: +1 when positive, -1
 * when negative (from DBL_MAX that gives +inf's pattern, as it should); the
 * sign is applied arithmetically because a branch on it is unpredictable in
 * the filters. Zero, infinities and NaN (magnitude bits 0 or >= those of
 * +inf, so that magnitude - 1 wraps or reaches 0x7fef...f) take the rare
 * branch: one unsigned comparison tells them apart. */
static inline double vbx_succ_bits(double x)
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    if (__builtin_expect((b & 0x7fffffffffffffffu) - 1u >= 0x7fefffffffffffffu, 0)) {
        if (x == 0.0)
            return 4.9406564584124654e-324; /* smallest subnormal */
        return x > 0.0 || x != x ? x : -DBL_MAX;
    }
    b += 1u - ((b >> 63) << 1);
    memcpy(&x, &b, sizeof b);
    return x;
}

/* Next double towards +inf: vbx_succ_bits(x) bit for bit, in floating
 * point where 2^-966 <= |x| <= DBL_MAX (the bits' path moves x through the
 * integer registers and back, and the filters take this step twice per
 * operation). There, with |x| = M 2^e (1 <= M < 2, x normal) and
 * ulp = 2^(e-52), the product d = fl(|x| 5 2^-55) is normal (>= 2^-1021)
 * and within a relative 2^-53 of 5 M ulp / 8, so 0.625 ulp (1 - 2^-53) <= d
 * < 1.25 ulp (1 + 2^-53), and x + d rounds to nearest as follows:
 *  - x > 0: the exact sum lies in (x + ulp / 2, x + 3 ulp / 2), so the
 *    nearest double is x + ulp (at the top of a binade, x + ulp = 2^(e+1)
 *    and the next double is 2 ulp further); from DBL_MAX the sum passes
 *    DBL_MAX + ulp / 2 and rounds to +inf, as the bits' path gives;
 *  - x < 0, M > 1: the doubles towards zero are x + ulp, x + 2 ulp, ...
 *    down to -2^e, where the spacing halves; the sum is within 3 ulp / 8
 *    (plus the product's error) of x + ulp or, for M = 1 + 2^-52 (x + ulp
 *    = -2^e), at -2^e - 3 ulp / 8, nearer -2^e than -2^e + ulp / 2: x + ulp
 *    either way;
 *  - x = -2^e: the next double towards zero is -2^e + ulp / 2 and d =
 *    5 ulp / 8 exactly: the sum, -2^e + 5 ulp / 8, rounds to it.
 * This needs round-to-nearest, which every filter already assumes; a fused
 * multiply-add would round the exact x + |x| 5 2^-55 once, with the same
 * result. test_exact compares the two paths on special values and on 10^6
 * random bit patterns. */
static inline double vbx_succ(double x)
{
    double a = fabs(x);
    if (__builtin_expect(a >= 0x1p-966 && a <= DBL_MAX, 1))
        return x + a * 0x1.4p-53;
    return vbx_succ_bits(x);
}

/* Next double towards -inf (x itself for -inf and NaN). */
static inline double vbx_pred(double x)
{
    return -vbx_succ(-x);
}

/* Minimum and maximum without libm calls. A NaN operand is either dropped or
 * propagated; both are safe here: a NaN corner comes only from 0 * inf, where
 * another corner carries the infinite bound, and a propagated NaN makes the
 * filter answer "cannot tell". */
static inline double vbx_min(double a, double b)
{
    return a < b ? a : b;
}

static inline double vbx_max(double a, double b)
{
    return a > b ? a : b;
}

static inline vbx_ia vbx_ia_point(double x)
{
    vbx_ia r = {x, x};
    return r;
}

static inline vbx_ia vbx_ia_add(vbx_ia a, vbx_ia b)
{
    vbx_ia r = {vbx_pred(a.lo + b.lo), vbx_succ(a.hi + b.hi)};
    return r;
}

static inline vbx_ia vbx_ia_sub(vbx_ia a, vbx_ia b)
{
    vbx_ia r = {vbx_pred(a.lo - b.hi), vbx_succ(a.hi - b.lo)};
    return r;
}

static inline vbx_ia vbx_ia_neg(vbx_ia a)
{
    vbx_ia r = {-a.hi, -a.lo};
    return r;
}

static inline vbx_ia vbx_ia_mul(vbx_ia a, vbx_ia b)
{
    /* The exact product range is spanned by the four corner products; each
     * rounded corner is enclosed by [pred, succ]. */
    double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
    double lo = vbx_min(vbx_min(p1, p2), vbx_min(p3, p4));
    double hi = vbx_max(vbx_max(p1, p2), vbx_max(p3, p4));
    vbx_ia r = {vbx_pred(lo), vbx_succ(hi)};
    return r;
}

static inline vbx_ia vbx_ia_sqr(vbx_ia a)
{
    double l = fabs(a.lo), h = fabs(a.hi);
    double mx = vbx_max(l, h);
    vbx_ia r;
    if (a.lo <= 0.0 && a.hi >= 0.0)
        r.lo = 0.0;
    else {
        double mn = vbx_min(l, h);
        r.lo = vbx_pred(mn * mn);
        if (r.lo < 0.0)
            r.lo = 0.0;
    }
    r.hi = vbx_succ(mx * mx);
    return r;
}

/* Division; a denominator interval containing 0 gives [-inf, +inf]. */
static inline vbx_ia vbx_ia_div(vbx_ia a, vbx_ia b)
{
    if (!(b.lo > 0.0 || b.hi < 0.0)) {
        vbx_ia r = {-INFINITY, INFINITY};
        return r;
    }
    double q1 = a.lo / b.lo, q2 = a.lo / b.hi, q3 = a.hi / b.lo, q4 = a.hi / b.hi;
    double lo = vbx_min(vbx_min(q1, q2), vbx_min(q3, q4));
    double hi = vbx_max(vbx_max(q1, q2), vbx_max(q3, q4));
    vbx_ia r = {vbx_pred(lo), vbx_succ(hi)};
    return r;
}

/* Square root of the non-negative part of a (negative values clamp to 0:
 * callers only use it where the exact argument is known to be >= 0). */
static inline vbx_ia vbx_ia_sqrt(vbx_ia a)
{
    vbx_ia r;
    r.lo = a.lo > 0.0 ? vbx_pred(sqrt(a.lo)) : 0.0;
    if (r.lo < 0.0)
        r.lo = 0.0;
    r.hi = a.hi > 0.0 ? vbx_succ(sqrt(a.hi)) : 0.0;
    if (a.hi != a.hi) /* NaN propagates */
        r.hi = a.hi;
    return r;
}

/* Sign of the exact value if the interval proves it: +1, -1, or 0 when the
 * interval straddles (or touches) zero or is NaN. */
static inline int vbx_ia_sign(vbx_ia a)
{
    if (a.lo > 0.0)
        return 1;
    if (a.hi < 0.0)
        return -1;
    return 0;
}

static inline double vbx_ia_mid(vbx_ia a)
{
    return 0.5 * a.lo + 0.5 * a.hi;
}

#endif
