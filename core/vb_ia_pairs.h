/* vb_ia_shared.h's interval steps with both bounds in one SSE2 register,
 * host only (included by vb_ia_shared.h on x86-64 hosts): vb_ia_add_p,
 * _sub_p, _mul_p, _sqr_p and _div_p return vb_ia_add's, ... bounds bit for
 * bit, for every input (test_ia_pairs compares them on special values and
 * random bit patterns). A translation unit that defines VB_IA_HOST_PAIRS
 * before vb_ia_shared.h gets them under the plain names (the certification
 * filter's host twin, core/cells/cert_scan.c); the kernels never see them.
 *
 * Why the bits are the same. Each lane runs the scalar step's operations on
 * the same operands in the same order (addpd, mulpd, divpd round each lane
 * as addsd, mulsd, divsd; minpd(x, y) and maxpd(x, y) are x < y ? x : y
 * and x > y ? x : y, vb_fmin and vb_fmax exactly, for NaN and signed zeros
 * too). The outward step is vb_ia_out: where both lanes' magnitudes a lie
 * in [2^-966, DBL_MAX] it is vb_succ's own fast path, x + a 5 2^-55 for
 * the upper bound and x - a 5 2^-55 = -vb_succ(-x) = vb_pred(x) for the
 * lower one (negation is exact and rounding to nearest symmetric);
 * otherwise (a zero, a tiny or infinite bound, NaN) it calls vb_pred and
 * vb_succ themselves. */
#ifndef VB_IA_PAIRS_H
#define VB_IA_PAIRS_H

#include <emmintrin.h>

/* [lo, hi] as one register (lo in the low lane), and back. */
static inline __m128d vb_ia_v(vb_ia a)
{
    return _mm_set_pd(a.hi, a.lo);
}

static inline vb_ia vb_ia_of(__m128d v)
{
    return vb_ia_make(_mm_cvtsd_f64(v), _mm_cvtsd_f64(_mm_unpackhi_pd(v, v)));
}

/* [vb_pred(v.lo), vb_succ(v.hi)]. */
static inline vb_ia vb_ia_out(__m128d v)
{
    const __m128d mag = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
    __m128d a = _mm_and_pd(v, mag);
    __m128d ok = _mm_and_pd(_mm_cmpge_pd(a, _mm_set1_pd(0x1p-966)),
                            _mm_cmple_pd(a, _mm_set1_pd(DBL_MAX)));
    if (__builtin_expect(_mm_movemask_pd(ok) == 3, 1))
        return vb_ia_of(_mm_add_pd(v, _mm_mul_pd(a, _mm_set_pd(0x1.4p-53, -0x1.4p-53))));
    vb_ia r = vb_ia_of(v);
    return vb_ia_make(vb_pred(r.lo), vb_succ(r.hi));
}

static inline vb_ia vb_ia_add_p(vb_ia a, vb_ia b)
{
    return vb_ia_out(_mm_add_pd(vb_ia_v(a), vb_ia_v(b)));
}

/* (a.lo - b.hi, a.hi - b.lo). */
static inline vb_ia vb_ia_sub_p(vb_ia a, vb_ia b)
{
    return vb_ia_out(_mm_sub_pd(vb_ia_v(a), _mm_set_pd(b.lo, b.hi)));
}

/* The corners as (a.lo b.lo, a.hi b.lo) and (a.lo b.hi, a.hi b.hi): their
 * lane-wise minimum is (fmin(p1, p2), fmin(p3, p4)), vb_ia_mul's pairs in
 * its order; likewise the maximum. */
static inline vb_ia vb_ia_mul_p(vb_ia a, vb_ia b)
{
    __m128d av = vb_ia_v(a);
    __m128d c0 = _mm_mul_pd(av, _mm_set1_pd(b.lo)), c1 = _mm_mul_pd(av, _mm_set1_pd(b.hi));
    __m128d mn = _mm_min_pd(c0, c1), mx = _mm_max_pd(c0, c1);
    __m128d lo = _mm_min_sd(mn, _mm_unpackhi_pd(mn, mn));
    __m128d hi = _mm_max_sd(mx, _mm_unpackhi_pd(mx, mx));
    return vb_ia_out(_mm_unpacklo_pd(lo, hi));
}

static inline vb_ia vb_ia_sqr_p(vb_ia a)
{
    double l = a.lo < 0.0 ? -a.lo : a.lo, h = a.hi < 0.0 ? -a.hi : a.hi;
    __m128d m = _mm_set_pd(vb_fmax(l, h), vb_fmin(l, h));
    vb_ia r = vb_ia_out(_mm_mul_pd(m, m));
    r.lo = a.lo <= 0.0 && a.hi >= 0.0 ? 0.0 : vb_fmax(r.lo, 0.0);
    return r;
}

static inline vb_ia vb_ia_div_p(vb_ia a, vb_ia b)
{
    if (b.lo > 0.0)
        return vb_ia_out(_mm_div_pd(vb_ia_v(a), _mm_set_pd(a.hi >= 0.0 ? b.lo : b.hi,
                                                          a.lo >= 0.0 ? b.hi : b.lo)));
    if (b.hi < 0.0)
        return vb_ia_out(_mm_div_pd(_mm_set_pd(a.lo, a.hi), _mm_set_pd(a.lo >= 0.0 ? b.lo : b.hi,
                                                                       a.hi >= 0.0 ? b.hi : b.lo)));
    return vb_ia_make(-VB_IA_INF, VB_IA_INF);
}

#endif
