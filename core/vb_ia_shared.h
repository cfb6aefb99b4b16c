/* Outward-rounded interval arithmetic in double: the one copy, compiled as
 * C11 on the host (verify/exact/vbx_ia.h, the exact predicates' filters)
 * and as OpenCL C in kernels (core/cells/vbd_cert_shared.h, the device's
 * certification filter). Names carry the prefix vb_ia_ (intervals) or
 * vb_ (the steps).
 *
 * Error bound (the only one the users rely on). IEEE 754 binary64 in
 * round-to-nearest returns, for an exact result x of +, -, *, / or sqrt on
 * doubles, the double r nearest to x. The gap between r and its neighbours
 * is at least twice |x - r| on the side where x lies (at a power of two the
 * gap below is half the gap above, and x rounds to r only from within half
 * of the gap on its own side), so  pred(r) <= x <= succ(r).  This holds for
 * subnormal results too, and at overflow: r = +inf means x > DBL_MAX, and
 * pred(+inf) = DBL_MAX. Every bound below is therefore computed in plain
 * round-to-nearest and moved one step outward: no rounding-mode switches,
 * no reliance on -frounding-math, and the enclosure is proven op by op.
 * OpenCL C (1.2, section 7.4) requires exactly this correct rounding of
 * double +, -, *, / and sqrt; the kernels are built without fast-math or
 * mad and with FP_CONTRACT OFF (set below), and the host needs
 * FLT_EVAL_METHOD == 0 (no x87 excess precision) and -ffp-contract=off
 * (global); an FMA would round once and stay enclosed anyway.
 *
 * Bounds may become infinite (an interval never collapses to [inf, inf]:
 * pred(+inf) = DBL_MAX); see vb_fmin for NaN corners. Users decide only on
 * "lo > 0" or "hi < 0", so an unbounded or NaN bound answers "cannot tell"
 * and their exact path runs. */
#ifndef VB_IA_SHARED_H
#define VB_IA_SHARED_H

#include "vb_cl_compat.h"

#ifdef __OPENCL_C_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF
#define VB_IA_INF INFINITY
#else
#include <float.h>
#include <math.h>
#include <string.h>
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "vb_ia_shared.h needs FLT_EVAL_METHOD == 0 (SSE2 doubles)"
#endif
#define VB_IA_INF HUGE_VAL
#endif

typedef struct vb_ia {
    double lo, hi;
} vb_ia;

/* Next double towards +inf (x itself for +inf and NaN), on the bit
 * pattern (vb_succ below is the same function). For finite non-zero x the
 * bit pattern moves by one unit towards +inf: +1 when positive, -1 when
 * negative (from DBL_MAX that gives +inf's pattern, as it should); the
 * sign is applied arithmetically because a branch on it is unpredictable
 * in the filters. Zero, infinities and NaN (magnitude bits 0 or >= those
 * of +inf, so that magnitude - 1 wraps or reaches 0x7fef...f) take the
 * rare branch: one unsigned comparison tells them apart. */
VB_SHARED_FN double vb_succ_bits(double x)
{
#ifdef __OPENCL_C_VERSION__
    vb_u64 b = as_ulong(x);
#else
    vb_u64 b;
    memcpy(&b, &x, sizeof b);
#endif
    if ((b & 0x7fffffffffffffffUL) - 1u >= 0x7fefffffffffffffUL) {
        if (x == 0.0)
            return 4.9406564584124654e-324; /* smallest subnormal */
        return x > 0.0 || x != x ? x : -1.7976931348623157e308;
    }
    b += 1u - ((b >> 63) << 1);
#ifdef __OPENCL_C_VERSION__
    return as_double(b);
#else
    memcpy(&x, &b, sizeof b);
    return x;
#endif
}

/* Next double towards +inf: vb_succ_bits(x) bit for bit, in floating
 * point where 2^-966 <= |x| <= DBL_MAX (on the host the bits' path moves x
 * through the integer registers and back, and the filters take this step
 * twice per operation; in a kernel, where integers and doubles share the
 * registers, the bits' path is kept). There, with |x| = M 2^e (1 <= M < 2,
 * x normal) and ulp = 2^(e-52), the product d = fl(|x| 5 2^-55) is normal
 * (>= 2^-1021) and within a relative 2^-53 of 5 M ulp / 8, so
 * 0.625 ulp (1 - 2^-53) <= d < 1.25 ulp (1 + 2^-53), and x + d rounds to
 * nearest as follows:
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
VB_SHARED_FN double vb_succ(double x)
{
#ifdef __OPENCL_C_VERSION__
    return vb_succ_bits(x);
#else
    double a = fabs(x);
    if (__builtin_expect(a >= 0x1p-966 && a <= DBL_MAX, 1))
        return x + a * 0x1.4p-53;
    return vb_succ_bits(x);
#endif
}

/* Next double towards -inf (x itself for -inf and NaN). */
VB_SHARED_FN double vb_pred(double x)
{
    return -vb_succ(-x);
}

/* Minimum and maximum without libm calls. A NaN operand is either dropped
 * or propagated; both are safe here: a NaN corner comes only from 0 * inf,
 * where another corner carries the infinite bound, and a propagated NaN
 * makes the user answer "cannot tell". */
VB_SHARED_FN double vb_fmin(double a, double b)
{
    return a < b ? a : b;
}

VB_SHARED_FN double vb_fmax(double a, double b)
{
    return a > b ? a : b;
}

VB_SHARED_FN vb_ia vb_ia_make(double lo, double hi)
{
    vb_ia r;
    r.lo = lo;
    r.hi = hi;
    return r;
}

VB_SHARED_FN vb_ia vb_ia_point(double x)
{
    return vb_ia_make(x, x);
}

/* The steps below with both bounds in one register (vb_ia_pairs.h), where
 * a host translation unit asks for them: the same bits. */
#if !defined(__OPENCL_C_VERSION__) && defined(__SSE2__)
#include "vb_ia_pairs.h"
#if defined(VB_IA_HOST_PAIRS)
#define VB_IA_PAIRS 1
#endif
#endif
#ifndef VB_IA_PAIRS
#define VB_IA_PAIRS 0
#endif

/* An integer |v| < 2^63: exact below 2^53, else [pred, succ] of its
 * nearest double. */
VB_SHARED_FN vb_ia vb_ia_int(vb_i64 v)
{
    double d = (double)v;
    if (v < ((vb_i64)1 << 53) && v > -((vb_i64)1 << 53))
        return vb_ia_make(d, d);
    return vb_ia_make(vb_pred(d), vb_succ(d));
}

VB_SHARED_FN vb_ia vb_ia_add(vb_ia a, vb_ia b)
{
#if VB_IA_PAIRS
    return vb_ia_add_p(a, b);
#else
    return vb_ia_make(vb_pred(a.lo + b.lo), vb_succ(a.hi + b.hi));
#endif
}

VB_SHARED_FN vb_ia vb_ia_sub(vb_ia a, vb_ia b)
{
#if VB_IA_PAIRS
    return vb_ia_sub_p(a, b);
#else
    return vb_ia_make(vb_pred(a.lo - b.hi), vb_succ(a.hi - b.lo));
#endif
}

VB_SHARED_FN vb_ia vb_ia_neg(vb_ia a)
{
    return vb_ia_make(-a.hi, -a.lo);
}

/* The exact product range is spanned by the four corner products; each
 * rounded corner is enclosed by [pred, succ]. */
VB_SHARED_FN vb_ia vb_ia_mul(vb_ia a, vb_ia b)
{
#if VB_IA_PAIRS
    return vb_ia_mul_p(a, b);
#else
    double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
    return vb_ia_make(vb_pred(vb_fmin(vb_fmin(p1, p2), vb_fmin(p3, p4))),
                      vb_succ(vb_fmax(vb_fmax(p1, p2), vb_fmax(p3, p4))));
#endif
}

/* The square: 0 below when a holds 0, else the smaller magnitude's square
 * stepped down (and clamped at 0: a square is never negative). */
VB_SHARED_FN vb_ia vb_ia_sqr(vb_ia a)
{
#if VB_IA_PAIRS
    return vb_ia_sqr_p(a);
#else
    double l = a.lo < 0.0 ? -a.lo : a.lo, h = a.hi < 0.0 ? -a.hi : a.hi;
    double mx = vb_fmax(l, h), mn = vb_fmin(l, h);
    double lo = a.lo <= 0.0 && a.hi >= 0.0 ? 0.0 : vb_fmax(vb_pred(mn * mn), 0.0);
    return vb_ia_make(lo, vb_succ(mx * mx));
#endif
}

/* Quotient; a denominator interval containing 0 gives [-inf, +inf].
 * With the denominator's sign known, the least and greatest of the four
 * corner quotients are known too, so two divisions suffice: for b > 0,
 * x / y grows with x, so the least is at x = a.lo (over y: b.hi when
 * a.lo >= 0, else b.lo) and the greatest at x = a.hi (b.lo when a.hi >= 0,
 * else b.hi); for b < 0 it falls with x, mirrored. Rounding to nearest is
 * monotone, so the rounded corner picked is the least (greatest) of the
 * four rounded ones: the bounds are vb_ia_div4's, bit for bit, wherever no
 * corner is NaN (test_exact compares them). */
VB_SHARED_FN vb_ia vb_ia_div(vb_ia a, vb_ia b)
{
#if VB_IA_PAIRS
    return vb_ia_div_p(a, b);
#else
    if (b.lo > 0.0)
        return vb_ia_make(vb_pred(a.lo / (a.lo >= 0.0 ? b.hi : b.lo)),
                          vb_succ(a.hi / (a.hi >= 0.0 ? b.lo : b.hi)));
    if (b.hi < 0.0)
        return vb_ia_make(vb_pred(a.hi / (a.hi >= 0.0 ? b.hi : b.lo)),
                          vb_succ(a.lo / (a.lo >= 0.0 ? b.lo : b.hi)));
    return vb_ia_make(-VB_IA_INF, VB_IA_INF);
#endif
}

/* The quotient from all four corners (the reference vb_ia_div is checked
 * against). */
VB_SHARED_FN vb_ia vb_ia_div4(vb_ia a, vb_ia b)
{
    if (!(b.lo > 0.0 || b.hi < 0.0))
        return vb_ia_make(-VB_IA_INF, VB_IA_INF);
    double q1 = a.lo / b.lo, q2 = a.lo / b.hi, q3 = a.hi / b.lo, q4 = a.hi / b.hi;
    return vb_ia_make(vb_pred(vb_fmin(vb_fmin(q1, q2), vb_fmin(q3, q4))),
                      vb_succ(vb_fmax(vb_fmax(q1, q2), vb_fmax(q3, q4))));
}

/* sum_k a_k b_k over k < n (1 <= n <= VB_IA_DOT_MAX) with one error bound
 * for the whole expression instead of a step outward per operation (the
 * steps were most of the arc trace's instructions).
 * Proof (u = 2^-53, round to nearest). For each k the exact products of
 * the four corners span a_k b_k; their least L_k and greatest H_k are
 * rounded to l_k = min fl(corner) = fl(L_k) and h_k = fl(H_k) (rounding
 * is monotone), so |l_k - L_k| <= u |l_k| + 2^-1075 (the second term for
 * an underflowing product), likewise h_k. With M = sum_k max(|l_k|,
 * |h_k|), each of the n - 1 additions of lo = fl(...fl(l_0 + l_1)... +
 * l_{n-1}) errs by at most u times its partial sum, at most u (1 + u)^n M
 * (sums are exact below 2^-1022); so |lo - sum L_k| <= n u (1 + u)^n M +
 * n 2^-1075, likewise hi. The computed m~ of M (non-negative terms) is
 * >= M / (1 + u)^(n-1), and e = fl(m~ (n + 1) u) + 2^-1020 >= (n + 1) u
 * (1 - u) m~ + 2^-1020 exceeds n u (1 + u)^(2n-1) m~ + n 2^-1075 for
 * n <= 8 (the product's underflow, below 2^-1075, too). So [lo - e,
 * hi + e] encloses the sum, and one step each way covers the rounding of
 * those two operations. An infinite corner makes m~ and e infinite and the
 * interval unbounded; NaN corners (0 * inf) are dropped or kept as
 * vb_ia_mul's are: "cannot tell" either way. */
#define VB_IA_DOT_MAX 8

VB_SHARED_FN vb_ia vb_ia_dot(const vb_ia *a, const vb_ia *b, int n)
{
    double lo = 0.0, hi = 0.0, mag = 0.0;
    for (int k = 0; k < n; k++) {
        double p1 = a[k].lo * b[k].lo, p2 = a[k].lo * b[k].hi;
        double p3 = a[k].hi * b[k].lo, p4 = a[k].hi * b[k].hi;
        double l = vb_fmin(vb_fmin(p1, p2), vb_fmin(p3, p4));
        double h = vb_fmax(vb_fmax(p1, p2), vb_fmax(p3, p4));
        lo += l;
        hi += h;
        mag += vb_fmax(l < 0.0 ? -l : l, h < 0.0 ? -h : h);
    }
    double e = mag * ((double)(n + 1) * 0x1p-53) + 0x1p-1020;
    return vb_ia_make(vb_pred(lo - e), vb_succ(hi + e));
}

/* Square root of the non-negative part of a (negative values clamp to 0:
 * callers only use it where the exact argument is known to be >= 0); a NaN
 * upper bound propagates. */
VB_SHARED_FN vb_ia vb_ia_sqrt(vb_ia a)
{
    double lo = a.lo > 0.0 ? vb_fmax(vb_pred(sqrt(a.lo)), 0.0) : 0.0;
    double hi = a.hi > 0.0 ? vb_succ(sqrt(a.hi)) : a.hi != a.hi ? a.hi : 0.0;
    return vb_ia_make(lo, hi);
}

/* Sign of the exact value if the interval proves it: +1, -1, or 0 when the
 * interval straddles (or touches) zero or is NaN. */
VB_SHARED_FN int vb_ia_sign(vb_ia a)
{
    return a.lo > 0.0 ? 1 : a.hi < 0.0 ? -1 : 0;
}

VB_SHARED_FN double vb_ia_mid(vb_ia a)
{
    return 0.5 * a.lo + 0.5 * a.hi;
}

#endif
