/* Exact numbers: the scaled-integer sphere set, signs in Q(sqrt(D)) and
 * correctly rounded doubles of its elements. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "vbx_exact.h"
#include "vbx_ldstep.h"

/* Largest exponent spread accepted: 10^(2 * 340) integers are still cheap
 * for GMP, and the input readers already refuse |exp10| > 340. */
#define VBX_MAX_SCALE 800

static const vb_decimal *decimal_of(const vb_sphere_set *set, size_t i, int k)
{
    switch (k) {
    case 0: return &set->ex[i];
    case 1: return &set->ey[i];
    case 2: return &set->ez[i];
    default: return &set->er[i];
    }
}

/* enclose_q where num and den are doubles exactly (|num|, den < 2^53, the
 * usual input decimals): the IEEE quotient q = RN(num / den) is the nearest
 * double, and its remainder q den - num is a double (the remainder of a
 * correctly rounded division is representable), so fma gives it exactly;
 * its sign says on which side of the exact value q lies, and the other
 * side is the neighbouring double. The same three doubles as the MPFR
 * path. 1 when done, 0 when the numbers are too large. */
static int enclose_small(const mpz_t num, const mpz_t den, vbx_ia *r, double *nearest)
{
    if (mpz_sizeinbase(num, 2) > 53 || mpz_sizeinbase(den, 2) > 53)
        return 0;
    double n = mpz_get_d(num), d = mpz_get_d(den);
    double q = n / d, rem = fma(q, d, -n);
    *nearest = q;
    r->lo = rem > 0.0 ? vbx_pred(q) : q;
    r->hi = rem < 0.0 ? vbx_succ(q) : q;
    return 1;
}

/* Encloses the rational num / den (den > 0) in doubles. RNDD/RNDU at 64 bits
 * then a directed conversion to double keep each side on its side. */
static vbx_ia enclose_q(const mpz_t num, const mpz_t den, double *nearest)
{
    vbx_ia fast;
    if (enclose_small(num, den, &fast, nearest))
        return fast;
    mpq_t q;
    mpfr_t f;
    mpq_init(q);
    mpfr_init2(f, 64);
    mpq_set_num(q, num);
    mpq_set_den(q, den);
    mpq_canonicalize(q);
    vbx_ia r;
    mpfr_set_q(f, q, MPFR_RNDD);
    r.lo = mpfr_get_d(f, MPFR_RNDD);
    mpfr_set_q(f, q, MPFR_RNDU);
    r.hi = mpfr_get_d(f, MPFR_RNDU);
    mpfr_set_prec(f, 53);
    mpfr_set_q(f, q, MPFR_RNDN);
    *nearest = mpfr_get_d(f, MPFR_RNDN);
    mpfr_clear(f);
    mpq_clear(q);
    return r;
}

int vbx_data_init(vb_ctx *ctx, vbx_data *d, const vb_sphere_set *set)
{
    d->n = set->n;
    d->c = NULL;
    d->box = NULL;
    d->near = NULL;
    mpz_init_set_ui(d->scale, 1);
    d->rmax = 0.0;
    long emin = 0;
    for (size_t i = 0; i < set->n; i++)
        for (int k = 0; k < 4; k++) {
            long e = decimal_of(set, i, k)->exp10;
            if (e < emin)
                emin = e;
        }
    long emax = 0;
    for (size_t i = 0; i < set->n; i++)
        for (int k = 0; k < 4; k++) {
            long e = decimal_of(set, i, k)->exp10;
            if (e > emax)
                emax = e;
        }
    if (emax - emin > VBX_MAX_SCALE) {
        mpz_clear(d->scale); /* a failed init holds nothing */
        return vb_error(ctx, VB_EINPUT_MAGNITUDE, set->source, 0,
                        "decimal exponents span %ld orders of magnitude; the exact "
                        "certifier accepts at most %d",
                        emax - emin, VBX_MAX_SCALE);
    }
    d->c = malloc(4 * (set->n ? set->n : 1) * sizeof *d->c);
    d->box = malloc(4 * (set->n ? set->n : 1) * sizeof *d->box);
    d->near = malloc(4 * (set->n ? set->n : 1) * sizeof *d->near);
    if (!d->c || !d->box || !d->near) {
        free(d->c);
        free(d->box);
        free(d->near);
        d->c = NULL;
        d->box = NULL;
        d->near = NULL;
        mpz_clear(d->scale);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (exact sphere data)");
    }
    mpz_ui_pow_ui(d->scale, 10, (unsigned long)(-emin));
    mpz_t p;
    mpz_init(p);
    for (size_t i = 0; i < set->n; i++)
        for (int k = 0; k < 4; k++) {
            const vb_decimal *dec = decimal_of(set, i, k);
            mpz_t *z = &d->c[4 * i + k];
            mpz_init_set_si(*z, (long)dec->mant);
            mpz_ui_pow_ui(p, 10, (unsigned long)(dec->exp10 - emin));
            mpz_mul(*z, *z, p);
            d->box[4 * i + k] = enclose_q(*z, d->scale, &d->near[4 * i + k]);
            if (k == 3 && d->box[4 * i + k].hi > d->rmax)
                d->rmax = d->box[4 * i + k].hi;
        }
    mpz_clear(p);
    return VB_OK;
}

void vbx_data_free(vbx_data *d)
{
    if (d->c)
        for (size_t i = 0; i < 4 * d->n; i++)
            mpz_clear(d->c[i]);
    free(d->c);
    free(d->box);
    free(d->near);
    mpz_clear(d->scale);
    d->c = NULL;
    d->box = NULL;
    d->near = NULL;
}

int vbx_sign_qsqrt(const mpz_t a, const mpz_t b, const mpz_t D, mpz_t t1, mpz_t t2)
{
    int sa = mpz_sgn(a);
    int sb = mpz_sgn(D) ? mpz_sgn(b) : 0;
    if (sb == 0)
        return sa;
    if (sa == 0 || sa == sb)
        return sb;
    /* Opposite signs: |a| against |b| sqrt(D), compared squared. */
    mpz_mul(t1, a, a);
    mpz_mul(t2, b, b);
    mpz_mul(t2, t2, D);
    int c = mpz_cmp(t1, t2);
    return c > 0 ? sa : (c < 0 ? sb : 0);
}

/* Encloses (num + b sqrt(D)) / den at the precision of lo and hi. */
static void enclose_qsqrt(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den,
                          mpfr_t lo, mpfr_t hi, mpfr_t sl, mpfr_t sh)
{
    if (mpz_sgn(b) == 0 || mpz_sgn(D) == 0) {
        mpfr_set_z(lo, num, MPFR_RNDD);
        mpfr_set_z(hi, num, MPFR_RNDU);
    } else {
        mpfr_set_z(sl, D, MPFR_RNDD);
        mpfr_sqrt(sl, sl, MPFR_RNDD);
        mpfr_set_z(sh, D, MPFR_RNDU);
        mpfr_sqrt(sh, sh, MPFR_RNDU);
        if (mpz_sgn(b) > 0) {
            mpfr_mul_z(lo, sl, b, MPFR_RNDD);
            mpfr_mul_z(hi, sh, b, MPFR_RNDU);
        } else {
            mpfr_mul_z(lo, sh, b, MPFR_RNDD);
            mpfr_mul_z(hi, sl, b, MPFR_RNDU);
        }
        mpfr_add_z(lo, lo, num, MPFR_RNDD);
        mpfr_add_z(hi, hi, num, MPFR_RNDU);
    }
    if (mpz_sgn(den) > 0) {
        mpfr_div_z(lo, lo, den, MPFR_RNDD);
        mpfr_div_z(hi, hi, den, MPFR_RNDU);
    } else {
        /* Dividing by a negative number swaps the ends. */
        mpfr_div_z(sl, hi, den, MPFR_RNDD);
        mpfr_div_z(sh, lo, den, MPFR_RNDU);
        mpfr_swap(lo, sl);
        mpfr_swap(hi, sh);
    }
}

int vbx_round_mpfr(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
                   double *lo, double *hi)
{
    int rc = VB_EPREC;
    mpfr_prec_t prec = 80;
    mpfr_t l, h, sl, sh;
    mpfr_inits2(prec, l, h, sl, sh, (mpfr_ptr)0);
    int first = 1;
    /* 2^20 bits is far beyond any input the readers accept; reaching it means
     * a bug, reported as VB_EPREC rather than looping forever. */
    while (prec <= ((mpfr_prec_t)1 << 20)) {
        mpfr_set_prec(l, prec);
        mpfr_set_prec(h, prec);
        mpfr_set_prec(sl, prec);
        mpfr_set_prec(sh, prec);
        enclose_qsqrt(num, b, D, den, l, h, sl, sh);
        if (first) {
            *lo = mpfr_get_d(l, MPFR_RNDD);
            *hi = mpfr_get_d(h, MPFR_RNDU);
            first = 0;
        }
        /* Rounding to nearest is monotone: if both ends of an enclosure
         * round to the same double, so does every value between them. */
        double dl = mpfr_get_d(l, MPFR_RNDN), dh = mpfr_get_d(h, MPFR_RNDN);
        if (dl == dh) {
            /* A zero is written +0 whatever the sign of the enclosure's
             * ends, so the output does not depend on which quadruple of a
             * degenerate vertex was solved. */
            *out = dl == 0.0 ? 0.0 : dl;
            rc = VB_OK;
            break;
        }
        prec *= 2;
    }
    mpfr_clears(l, h, sl, sh, (mpfr_ptr)0);
    return rc;
}

/* The fast path needs integers read 64 bits at a time into a long double
 * that holds 64 bits exactly (x87 extended; binary128 also qualifies). */
#if LDBL_MANT_DIG >= 64 && GMP_NUMB_BITS == 64 && GMP_NAIL_BITS == 0
#define VBX_FAST_ROUND 1
#else
#define VBX_FAST_ROUND 0
#endif

#if VBX_FAST_ROUND
/* Error bound: the argument of vbx_ia.h, in long double. Each +, *, /, sqrt
 * of long doubles returns the nearest long double r of the exact result x
 * (IEEE round-to-nearest; on x87 the default 64-bit precision control), so
 * pred(r) <= x <= succ(r). Moving every computed end one step outward keeps
 * each interval an enclosure, op by op. The steps are vbx_ldstep.h's, the
 * values of nextafterl without its call (proof there). */
static long double ld_down(long double x)
{
    return vbx_ld_pred(x);
}

static long double ld_up(long double x)
{
    return vbx_ld_succ(x);
}

/* 2^(64 k): the scales of the integers the certifier meets (a few hundred
 * bits); longer ones take ldexpl. */
#define VBX_POW2_N 16
static const long double pow2_64k[VBX_POW2_N] = {
    0x1p0L,   0x1p64L,  0x1p128L, 0x1p192L, 0x1p256L, 0x1p320L, 0x1p384L, 0x1p448L,
    0x1p512L, 0x1p576L, 0x1p640L, 0x1p704L, 0x1p768L, 0x1p832L, 0x1p896L, 0x1p960L};

/* Encloses the integer z: its top 64 bits t give t 2^s <= |z| <= (t + 1) 2^s,
 * both exact in a 64-bit mantissa (t + 1 <= 2^64). 0 when z is too long for
 * the exponent range (never for inputs the readers accept). */
static int ld_enclose_z(const mpz_t z, long double *lo, long double *hi)
{
    int sg = mpz_sgn(z);
    if (sg == 0) {
        *lo = *hi = 0.0L;
        return 1;
    }
    size_t n = mpz_sizeinbase(z, 2);
    if (n > (size_t)LDBL_MAX_EXP - 64)
        return 0;
    long double a, b;
    if (n <= 64) {
        a = b = (long double)mpz_getlimbn(z, 0);
    } else {
        size_t sh = n - 64, i = sh / 64;
        unsigned o = (unsigned)(sh % 64);
        uint64_t t = (uint64_t)mpz_getlimbn(z, (mp_size_t)i) >> o;
        if (o)
            t |= (uint64_t)mpz_getlimbn(z, (mp_size_t)i + 1) << (64 - o);
        /* Scaling by a power of two is exact (no overflow: n is bounded). */
        long double p2 = sh < 64 * VBX_POW2_N ? (long double)((uint64_t)1 << (sh % 64)) *
                                                    pow2_64k[sh / 64]
                                              : ldexpl(1.0L, (int)sh);
        a = (long double)t * p2;
        b = ((long double)t + 1.0L) * p2;
    }
    *lo = sg > 0 ? a : -b;
    *hi = sg > 0 ? b : -a;
    return 1;
}

/* Product (or quotient when div) of [al, ah] and [bl, bh], outward. */
static void ld_mul(long double al, long double ah, long double bl, long double bh, int div,
                   long double *lo, long double *hi)
{
    long double p[4];
    if (div) {
        p[0] = al / bl;
        p[1] = al / bh;
        p[2] = ah / bl;
        p[3] = ah / bh;
    } else {
        p[0] = al * bl;
        p[1] = al * bh;
        p[2] = ah * bl;
        p[3] = ah * bh;
    }
    long double mn = p[0], mx = p[0];
    for (int i = 1; i < 4; i++) {
        mn = p[i] < mn ? p[i] : mn;
        mx = p[i] > mx ? p[i] : mx;
    }
    *lo = ld_down(mn);
    *hi = ld_up(mx);
}
#endif

void vbx_round_prepare(vbx_round_common *rc, const mpz_t D, const mpz_t den, mpz_ptr t1,
                       mpz_ptr t2)
{
    rc->ok = 0;
    rc->root = 0;
    rc->dl = rc->dh = rc->sl = rc->sh = 0.0L;
    rc->D = D;
    rc->t1 = t1;
    rc->t2 = t2;
#if VBX_FAST_ROUND
    if (!ld_enclose_z(den, &rc->dl, &rc->dh) || rc->dl == 0.0L)
        return;
    if (mpz_sgn(D) != 0) {
        long double Dl, Dh;
        if (!ld_enclose_z(D, &Dl, &Dh))
            return;
        /* D > 0, so Dl >= 1 and its square root is positive. */
        rc->sl = ld_down(sqrtl(Dl));
        rc->sh = ld_up(sqrtl(Dh));
        rc->root = 1;
    }
    rc->ok = 1;
#endif
}

#if VBX_FAST_ROUND
/* The end of vbx_round_with: divides the enclosure [vl, vh] of the
 * numerator by den and rounds; 1 when decided. */
static int ld_finish(const vbx_round_common *rc, long double vl, long double vh, double *out,
                     double *lo, double *hi)
{
    /* den is a non-zero integer: its enclosure excludes 0. */
    ld_mul(vl, vh, rc->dl, rc->dh, 1, &vl, &vh);
    /* Rounding to nearest double is monotone, so when both ends round to
     * one double every value between them, the exact one included, does. */
    double rl = (double)vl, rh = (double)vh;
    /* -0.0 == +0.0, so the signs are compared too: an enclosure of a value
     * next to 0 rounds to -0 below it and to +0 above. */
    if (rl != rh || signbit(rl) != signbit(rh) || !isfinite(rl) || !(fabsl(vl) <= LDBL_MAX) ||
        !(fabsl(vh) <= LDBL_MAX))
        return 0;
    *out = rl;
    *lo = (long double)rl > vl ? vbx_pred(rl) : rl;
    *hi = (long double)rh < vh ? vbx_succ(rh) : rh;
    return 1;
}
#endif

int vbx_round_with(const vbx_round_common *rc, const mpz_t num, const mpz_t b, double *out,
                   double *lo, double *hi)
{
#if VBX_FAST_ROUND
    long double nl, nh, bl, bh, pl, ph;
    if (!rc->ok || !ld_enclose_z(num, &nl, &nh))
        return 0;
    int sn = mpz_sgn(num), sb = rc->root ? mpz_sgn(b) : 0;
    /* An exact 0 is left to MPFR, whose sign of zero (from the directed
     * roundings of its enclosure) is the one the output has always had. */
    if (sn == 0 && sb == 0)
        return 0;
    if (sb == 0)
        return ld_finish(rc, nl, nh, out, lo, hi);
    if (!ld_enclose_z(b, &bl, &bh))
        return 0;
    ld_mul(bl, bh, rc->sl, rc->sh, 0, &pl, &ph);
    if (ld_finish(rc, ld_down(nl + pl), ld_up(nh + ph), out, lo, hi))
        return 1;
    if (sn == 0 || sn == sb)
        return 0;
    /* Opposite signs cancel in num + b sqrt(D), widening the enclosure by
     * the ratio of the parts to the sum. Rationalise: num + b sqrt(D) =
     * (num^2 - b^2 D) / (num - b sqrt(D)), an exact integer over a sum of
     * two terms of one sign. */
    mpz_mul(rc->t1, num, num);
    mpz_mul(rc->t2, b, b);
    mpz_mul(rc->t2, rc->t2, rc->D);
    mpz_sub(rc->t1, rc->t1, rc->t2);
    long double ml = ld_down(nl - ph), mh = ld_up(nh - pl), vl, vh;
    /* t1 = 0: exactly 0 (D a square), MPFR's zero as above. */
    if (mpz_sgn(rc->t1) == 0 || !(ml > 0.0L || mh < 0.0L) || !ld_enclose_z(rc->t1, &vl, &vh))
        return 0;
    ld_mul(vl, vh, ml, mh, 1, &vl, &vh);
    return ld_finish(rc, vl, vh, out, lo, hi);
#else
    (void)rc;
    (void)num;
    (void)b;
    (void)out;
    (void)lo;
    (void)hi;
    return 0;
#endif
}

int vbx_round_fast(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
                   double *lo, double *hi)
{
    vbx_round_common rc;
    mpz_t t1, t2;
    mpz_inits(t1, t2, (mpz_ptr)0);
    vbx_round_prepare(&rc, D, den, t1, t2);
    int ok = vbx_round_with(&rc, num, b, out, lo, hi);
    mpz_clears(t1, t2, (mpz_ptr)0);
    return ok;
}

int vbx_round(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
              double *lo, double *hi, uint64_t *slow)
{
    if (vbx_round_fast(num, b, D, den, out, lo, hi))
        return VB_OK;
    if (slow)
        ++*slow;
    return vbx_round_mpfr(num, b, D, den, out, lo, hi);
}
