/* Exact numbers: the scaled-integer sphere set, signs in Q(sqrt(D)) and
 * correctly rounded doubles of its elements. */
#include <stdlib.h>

#include "vbx_exact.h"

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

/* Encloses the rational num / den (den > 0) in doubles. RNDD/RNDU at 64 bits
 * then a directed conversion to double keep each side on its side. */
static vbx_ia enclose_q(const mpz_t num, const mpz_t den, double *nearest)
{
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
    if (emax - emin > VBX_MAX_SCALE)
        return vb_error(ctx, VB_EINPUT_MAGNITUDE, set->source, 0,
                        "decimal exponents span %ld orders of magnitude; the exact "
                        "certifier accepts at most %d",
                        emax - emin, VBX_MAX_SCALE);
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

int vbx_round(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
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
            *out = dl;
            rc = VB_OK;
            break;
        }
        prec *= 2;
    }
    mpfr_clears(l, h, sl, sh, (mpfr_ptr)0);
    return rc;
}
