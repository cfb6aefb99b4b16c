/* vbd_line_end (vbd_cert_shared.h) for four quadruples at once in AVX2
 * lanes, host only (included by cert_scan.c's AVX2 build): U, A, B, C and
 * delta of lane l are vbd_line_end's bounds bit for bit, or lane l is
 * marked for the scalar vbd_line_end.
 *
 * Why the bits are the same. Each lane runs the scalar step's operations
 * (vb_ia_add, _sub, _mul, _sqr of vb_ia_shared.h) on the same operands in
 * the same order: addpd, subpd, mulpd round each lane as the scalar ops;
 * minpd(x, y) and maxpd(x, y) are x < y ? x : y and x > y ? x : y, vb_fmin
 * and vb_fmax exactly; negation flips the sign bit as unary minus does. The
 * outward step of a bound x is vb_succ's fast path where |x| lies in
 * [2^-966, DBL_MAX] (x + |x| 5 2^-55 up, x - |x| 5 2^-55 = vb_pred(x)
 * down) and vb_succ_bits' answer below (a zero to +-2^-1074, a tiny x's
 * pattern one unit towards +inf, or -inf for pred = -succ(-x)); an
 * infinite or NaN bound marks the lane, whose quadruple the scalar code
 * then does again. No FMA: the file is built
 * with -mavx2 only and contraction off. */
#ifndef CERT_LINE4_H
#define CERT_LINE4_H

#include <immintrin.h>

/* Four intervals, one a lane. */
typedef struct ia4 {
    __m256d lo, hi;
} ia4;

/* Bounds stepped outward; lanes with a bound the step cannot take (an
 * infinity or NaN) are or-ed into *bad. */
static inline ia4 ia4_out(__m256d lo, __m256d hi, __m256d *bad)
{
    const __m256d mag = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d small = _mm256_set1_pd(0x1p-966), big = _mm256_set1_pd(DBL_MAX);
    const __m256d zero = _mm256_setzero_pd(), dmin = _mm256_set1_pd(0x1p-1074);
    __m256d al = _mm256_and_pd(lo, mag), ah = _mm256_and_pd(hi, mag);
    /* fin: finite; fast: vb_succ's fast path; else zero or tiny (bits). */
    __m256d finl = _mm256_cmp_pd(al, big, _CMP_LE_OQ), finh = _mm256_cmp_pd(ah, big, _CMP_LE_OQ);
    __m256d fastl = _mm256_cmp_pd(al, small, _CMP_GE_OQ), fasth = _mm256_cmp_pd(ah, small, _CMP_GE_OQ);
    *bad = _mm256_or_pd(*bad, _mm256_andnot_pd(_mm256_and_pd(finl, finh), _mm256_set1_pd(-0.0)));
    ia4 r;
    r.lo = _mm256_add_pd(lo, _mm256_mul_pd(al, _mm256_set1_pd(-0x1.4p-53)));
    r.hi = _mm256_add_pd(hi, _mm256_mul_pd(ah, _mm256_set1_pd(0x1.4p-53)));
    if (__builtin_expect(_mm256_movemask_pd(_mm256_and_pd(fastl, fasth)) != 15, 0)) {
        /* vb_succ_bits: a tiny bound's pattern one unit up (hi) or down
         * (lo) the line, a zero to +-2^-1074. */
        const __m256i one = _mm256_set1_epi64x(1), z = _mm256_setzero_si256();
        __m256i bl = _mm256_castpd_si256(lo), bh = _mm256_castpd_si256(hi);
        __m256i up_h = _mm256_or_si256(_mm256_cmpgt_epi64(z, bh), one);
        __m256i up_l = _mm256_or_si256(_mm256_cmpgt_epi64(z, bl), one);
        __m256d tl = _mm256_castsi256_pd(_mm256_sub_epi64(bl, up_l));
        __m256d th = _mm256_castsi256_pd(_mm256_add_epi64(bh, up_h));
        tl = _mm256_blendv_pd(tl, _mm256_sub_pd(zero, dmin), _mm256_cmp_pd(lo, zero, _CMP_EQ_OQ));
        th = _mm256_blendv_pd(th, dmin, _mm256_cmp_pd(hi, zero, _CMP_EQ_OQ));
        r.lo = _mm256_blendv_pd(tl, r.lo, fastl);
        r.hi = _mm256_blendv_pd(th, r.hi, fasth);
    }
    return r;
}

static inline ia4 ia4_add(ia4 a, ia4 b, __m256d *bad)
{
    return ia4_out(_mm256_add_pd(a.lo, b.lo), _mm256_add_pd(a.hi, b.hi), bad);
}

static inline ia4 ia4_sub(ia4 a, ia4 b, __m256d *bad)
{
    return ia4_out(_mm256_sub_pd(a.lo, b.hi), _mm256_sub_pd(a.hi, b.lo), bad);
}

static inline ia4 ia4_neg(ia4 a)
{
    const __m256d sign = _mm256_set1_pd(-0.0);
    ia4 r = {_mm256_xor_pd(a.hi, sign), _mm256_xor_pd(a.lo, sign)};
    return r;
}

/* vb_ia_mul: the corners p1 .. p4 and fmin(fmin(p1, p2), fmin(p3, p4)). */
static inline ia4 ia4_mul(ia4 a, ia4 b, __m256d *bad)
{
    __m256d p1 = _mm256_mul_pd(a.lo, b.lo), p2 = _mm256_mul_pd(a.lo, b.hi);
    __m256d p3 = _mm256_mul_pd(a.hi, b.lo), p4 = _mm256_mul_pd(a.hi, b.hi);
    return ia4_out(_mm256_min_pd(_mm256_min_pd(p1, p2), _mm256_min_pd(p3, p4)),
                   _mm256_max_pd(_mm256_max_pd(p1, p2), _mm256_max_pd(p3, p4)), bad);
}

/* vb_ia_sqr: 0 below where a holds 0, else max(pred(mn^2), 0). */
static inline ia4 ia4_sqr(ia4 a, __m256d *bad)
{
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    __m256d l = _mm256_blendv_pd(a.lo, _mm256_xor_pd(a.lo, sign), _mm256_cmp_pd(a.lo, zero, _CMP_LT_OQ));
    __m256d h = _mm256_blendv_pd(a.hi, _mm256_xor_pd(a.hi, sign), _mm256_cmp_pd(a.hi, zero, _CMP_LT_OQ));
    __m256d mx = _mm256_max_pd(l, h), mn = _mm256_min_pd(l, h);
    ia4 r = ia4_out(_mm256_mul_pd(mn, mn), _mm256_mul_pd(mx, mx), bad);
    __m256d hold = _mm256_and_pd(_mm256_cmp_pd(a.lo, zero, _CMP_LE_OQ), _mm256_cmp_pd(a.hi, zero, _CMP_GE_OQ));
    r.lo = _mm256_blendv_pd(_mm256_max_pd(r.lo, zero), zero, hold);
    return r;
}

/* Interval i of four arrays (lane l from x[l]), and back. */
static inline ia4 ia4_load(const vb_ia *const *x, int i)
{
    ia4 r = {_mm256_set_pd(x[3][i].lo, x[2][i].lo, x[1][i].lo, x[0][i].lo),
             _mm256_set_pd(x[3][i].hi, x[2][i].hi, x[1][i].hi, x[0][i].hi)};
    return r;
}

static inline void ia4_store(ia4 a, vb_ia *out)
{
    double lo[4], hi[4];
    _mm256_storeu_pd(lo, a.lo);
    _mm256_storeu_pd(hi, a.hi);
    for (int l = 0; l < 4; l++)
        out[l] = vb_ia_make(lo[l], hi[l]);
}

/* vbd_det3 in lanes. */
static inline ia4 ia4_det3(const ia4 *e, const ia4 *M, int c0, int c1, int c2, __m256d *bad)
{
    ia4 t = ia4_sub(ia4_mul(e[c0], M[c1 * 5 + c2], bad), ia4_mul(e[c1], M[c0 * 5 + c2], bad), bad);
    return ia4_add(t, ia4_mul(e[c2], M[c0 * 5 + c1], bad), bad);
}

/* vbd_line_end of lanes l < 4 (e[l], M[l] and L[l]'s D and v from
 * vbd_line_begin): L[l]'s U, A, B, C and *delta[l] as vbd_line_end makes
 * them; bit l of the result set where lane l must be done by the scalar
 * vbd_line_end instead. */
static unsigned line4_end(const vb_ia *const *e, const vb_ia *const *M, vbd_line *const *L,
                          vb_ia *delta)
{
    __m256d bad = _mm256_setzero_pd();
    ia4 ev[5], Mv[25], v[3], D;
    for (int i = 0; i < 5; i++)
        ev[i] = ia4_load(e, i);
    static const int used[6] = {1 * 5 + 2, 1 * 5 + 4, 2 * 5 + 4, 0 * 5 + 4, 0 * 5 + 2, 0 * 5 + 1};
    for (int i = 0; i < 6; i++)
        Mv[used[i]] = ia4_load(M, used[i]);
    const vb_ia *vs[4], *Ds[4];
    for (int l = 0; l < 4; l++) {
        vs[l] = L[l]->v;
        Ds[l] = &L[l]->D;
    }
    for (int k = 0; k < 3; k++)
        v[k] = ia4_load(vs, k);
    D = ia4_load(Ds, 0);
    ia4 U[3];
    U[0] = ia4_det3(ev, Mv, 1, 2, 4, &bad);
    U[1] = ia4_neg(ia4_det3(ev, Mv, 0, 2, 4, &bad));
    U[2] = ia4_det3(ev, Mv, 0, 1, 4, &bad);
    ia4 A = ia4_add(ia4_add(ia4_sqr(v[0], &bad), ia4_sqr(v[1], &bad), &bad), ia4_sqr(v[2], &bad), &bad);
    A = ia4_sub(A, ia4_sqr(D, &bad), &bad);
    ia4 B = ia4_add(ia4_add(ia4_mul(U[0], v[0], &bad), ia4_mul(U[1], v[1], &bad), &bad),
                    ia4_mul(U[2], v[2], &bad), &bad);
    ia4 C = ia4_add(ia4_add(ia4_sqr(U[0], &bad), ia4_sqr(U[1], &bad), &bad), ia4_sqr(U[2], &bad), &bad);
    ia4 dl = ia4_sub(ia4_sqr(B, &bad), ia4_mul(A, C, &bad), &bad);
    vb_ia t[7][4];
    for (int k = 0; k < 3; k++)
        ia4_store(U[k], t[k]);
    ia4_store(A, t[3]);
    ia4_store(B, t[4]);
    ia4_store(C, t[5]);
    ia4_store(dl, t[6]);
    for (int l = 0; l < 4; l++) {
        for (int k = 0; k < 3; k++)
            L[l]->U[k] = t[k][l];
        L[l]->A = t[3][l];
        L[l]->B = t[4][l];
        L[l]->C = t[5][l];
        delta[l] = t[6][l];
    }
    return (unsigned)_mm256_movemask_pd(bad);
}

#endif
