/* The interval dot products of the cell measures (vbm_dotn and vbm_dot3,
 * verify/measures/vbm_dot.h: one rounding bound per end) against exact
 * values: for 200000 random interval vectors of 3 terms and 100000 of 1 to
 * VBM_DOT_MAX terms, the second read backwards (stride -1, as the Taylor
 * convolutions read it), magnitudes from 2^-1074 to 2^1000, points and
 * wide intervals, mixed signs, the exact dot product (MPFR, 4300 bits:
 * every product and sum of doubles exact) of the intervals' corners that
 * give the least and the greatest value lies in the enclosure; the enclosure is no more than 8 ulps of the sum of the
 * products' magnitudes wider than the operation-by-operation one
 * (vbm_dot3_slow); infinite ends give what vbm_dot3_slow gives. A bound
 * made without the rounding margin (the bare rounded sums) misses on some
 * of the triples: the margin is needed. */
#include <math.h>
#include <mpfr.h>
#include <stdint.h>

#include "vbm_dot.h"
#include "vb_test.h"

static uint64_t seed = 12345;

static double rnd(void)
{
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    return (double)(seed >> 11) / 9007199254740992.0;
}

/* A random double: sign, mantissa and an exponent chosen by `kind`. */
static double value(int kind)
{
    double m = 1.0 + rnd(), s = rnd() < 0.5 ? -1.0 : 1.0;
    int e = kind == 0 ? (int)(rnd() * 40.0) - 20 : (int)(rnd() * 2074.0) - 1074;
    if (e > 1000)
        e = 1000;
    return s * ldexp(m, e);
}

static vbx_ia interval(int kind)
{
    double a = value(kind);
    if (rnd() < 0.3)
        return vbx_ia_point(a);
    double b = rnd() < 0.5 ? a + fabs(a) * rnd() * 1e-10 : value(kind);
    vbx_ia r = {a < b ? a : b, a < b ? b : a};
    return r;
}

/* The exact least (hi = 0) or greatest (hi = 1) of a . b over the boxes
 * (m terms): per term the best of the four corners, summed exactly. */
static void exact_end(mpfr_t s, const vbx_ia *a, const vbx_ia *b, int m, int hi)
{
    mpfr_t p, best;
    mpfr_inits2(4300, p, best, (mpfr_ptr)0);
    mpfr_set_zero(s, 1);
    for (int k = 0; k < m; k++) {
        for (int c = 0; c < 4; c++) {
            mpfr_set_d(p, c & 1 ? a[k].hi : a[k].lo, MPFR_RNDN);
            mpfr_mul_d(p, p, c & 2 ? b[k].hi : b[k].lo, MPFR_RNDN);
            if (c == 0 || (hi ? mpfr_greater_p(p, best) : mpfr_less_p(p, best)))
                mpfr_set(best, p, MPFR_RNDN);
        }
        mpfr_add(s, s, best, MPFR_RNDN);
    }
    mpfr_clears(p, best, (mpfr_ptr)0);
}

int main(void)
{
    mpfr_t lo, hi;
    mpfr_inits2(4300, lo, hi, (mpfr_ptr)0);
    long missed = 0, wide = 0, bare_missed = 0, narrower = 0;
    for (int it = 0; it < 300000; it++) {
        int kind = it % 3 == 0; /* a third over the whole range */
        int m = it < 200000 ? 3 : 1 + it % VBM_DOT_MAX;
        vbx_ia a[VBM_DOT_MAX], b[VBM_DOT_MAX], br[VBM_DOT_MAX];
        for (int k = 0; k < m; k++) {
            a[k] = interval(kind);
            b[k] = interval(kind);
        }
        for (int k = 0; k < m; k++)
            br[k] = b[m - 1 - k];
        vbx_ia f = m == 3 ? vbm_dot3(a, b) : vbm_dotn(a, 1, &br[m - 1], -1, m);
        vbx_ia g = vbm_dotn_slow(a, 1, b, 1, m);
        exact_end(lo, a, b, m, 0);
        exact_end(hi, a, b, m, 1);
        if (!(mpfr_cmp_d(lo, f.lo) >= 0 && mpfr_cmp_d(hi, f.hi) <= 0))
            missed++;
        /* without the margin: the bare rounded sums of the corners */
        double sl = 0.0, sh = 0.0, mag = 0.0;
        for (int k = 0; k < m; k++) {
            double p[4] = {a[k].lo * b[k].lo, a[k].lo * b[k].hi, a[k].hi * b[k].lo,
                           a[k].hi * b[k].hi};
            double l = fmin(fmin(p[0], p[1]), fmin(p[2], p[3]));
            double h = fmax(fmax(p[0], p[1]), fmax(p[2], p[3]));
            sl += l;
            sh += h;
            mag += fabs(l) + fabs(h);
        }
        bare_missed += !(mpfr_cmp_d(lo, sl) >= 0 && mpfr_cmp_d(hi, sh) <= 0);
        double extra = (f.hi - f.lo) - (g.hi - g.lo);
        if (extra > (m + 1) * 0x1p-52 * mag + 0x1p-1055)
            wide++;
        narrower += extra < 0.0;
    }
    CHECK(missed == 0);
    CHECK(wide == 0);
    CHECK(bare_missed > 0);
    printf("vbm_dotn: %ld missed, %ld wider than m + 1 ulps of the magnitudes, bare sums missed "
           "%ld, %ld narrower than the slow route's\n",
           missed, wide, bare_missed, narrower);
    /* infinite ends: the slow route's answer */
    vbx_ia a[3] = {{1.0, INFINITY}, {0.5, 0.5}, {-2.0, 3.0}};
    vbx_ia b[3] = {{2.0, 2.0}, {1.0, INFINITY}, {-1.0, 1.0}};
    vbx_ia f = vbm_dot3(a, b), g = vbm_dot3_slow(a, b);
    CHECK(f.lo == g.lo && f.hi == g.hi && f.hi == INFINITY);
    mpfr_clears(lo, hi, (mpfr_ptr)0);
    mpfr_free_cache();
    VB_TEST_END();
}
