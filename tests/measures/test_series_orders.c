/* The univariate series' operations to an order kmax (vbm1_mul_to,
 * vbm1_recip_to, vbm1_sqrt_to, vbm1_log_to, vbm1_mul_coef:
 * verify/measures/series1.c), which the contact's integrals take at
 * arcs' ends (kmax 0), pieces' middles (K - 1) and over pieces (order K
 * alone: arc_integral.c). On 300 random series with interval
 * coefficients, every kmax from 0 to K: coefficients 0..kmax the same
 * doubles as the full operation's, the others exactly 0; the single
 * coefficient of a product the full product's. And values: the series of
 * 1 / (1 + x), sqrt(1 + x), log(1 + x) at 0 and (1 + x)^2 hold their exact
 * Taylor coefficients (-1)^n, binom(1/2, n), (-1)^(n+1) / n, and 1, 2, 1. */
#include <stdint.h>

#include "vbm_series1.h"
#include "vb_test.h"

static double rnd(uint64_t *s)
{
    return (double)(vb_test_xorshift(s) >> 11) / 9007199254740992.0;
}

/* A series with f_0 in [1, 2] and the rest in [-1, 1], each coefficient an
 * interval a few ulps to 1e-9 wide. */
static void random_series(uint64_t *s, vbm_s1 *f)
{
    for (int k = 0; k <= VBM1_K; k++) {
        double m = k ? 2.0 * rnd(s) - 1.0 : 1.0 + rnd(s), w = 1e-9 * rnd(s) * rnd(s);
        vbx_ia c = {m - w, m + w};
        f->c[k] = c;
    }
}

static int same(vbx_ia a, vbx_ia b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* r's coefficients 0..kmax those of full, bit for bit, the others 0. */
static int orders_match(const vbm_s1 *r, const vbm_s1 *full, int kmax)
{
    for (int n = 0; n <= VBM1_K; n++)
        if (n <= kmax ? !same(r->c[n], full->c[n]) : !(r->c[n].lo == 0.0 && r->c[n].hi == 0.0))
            return 0;
    return 1;
}

/* Every coefficient of r set to [7, 7]: what an operation leaves above
 * kmax shows. */
static vbm_s1 *poison(vbm_s1 *r)
{
    for (int n = 0; n <= VBM1_K; n++)
        r->c[n] = vbx_ia_point(7.0);
    return r;
}

static int holds(vbx_ia a, double v)
{
    return a.lo <= v && v <= a.hi;
}

int main(void)
{
    uint64_t seed = 0x5eed47u;
    int bad_mul = 0, bad_recip = 0, bad_sqrt = 0, bad_log = 0, bad_coef = 0, cases = 0;
    for (int c = 0; c < 300; c++) {
        vbm_s1 f, g, full, r;
        random_series(&seed, &f);
        random_series(&seed, &g);
        for (int kmax = 0; kmax <= VBM1_K; kmax++, cases++) {
            vbm1_mul(&full, &f, &g);
            vbm1_mul_to(poison(&r), &f, &g, kmax);
            bad_mul += !orders_match(&r, &full, kmax);
            bad_coef += !same(vbm1_mul_coef(&f, &g, kmax), full.c[kmax]);
            bad_recip += !(vbm1_recip(&full, &f) && vbm1_recip_to(poison(&r), &f, kmax) &&
                           orders_match(&r, &full, kmax));
            bad_sqrt += !(vbm1_sqrt(&full, &f) && vbm1_sqrt_to(poison(&r), &f, kmax) &&
                          orders_match(&r, &full, kmax));
            bad_log += !(vbm1_log(&full, &f) && vbm1_log_to(poison(&r), &f, kmax) &&
                         orders_match(&r, &full, kmax));
        }
    }
    printf("orders 0..K of %d cases: mul %d, coef %d, recip %d, sqrt %d, log %d differ\n", cases,
           bad_mul, bad_coef, bad_recip, bad_sqrt, bad_log);
    CHECK_INT(bad_mul, 0);
    CHECK_INT(bad_coef, 0);
    CHECK_INT(bad_recip, 0);
    CHECK_INT(bad_sqrt, 0);
    CHECK_INT(bad_log, 0);

    /* the values: 1 + x at 0 */
    vbm_s1 x1, r, sq;
    vbm1_var(&x1, vbx_ia_point(0.0));
    x1.c[0] = vbx_ia_point(1.0);
    int kmax = 6;
    CHECK(vbm1_recip_to(&r, &x1, kmax));
    for (int n = 0; n <= kmax; n++)
        CHECK(holds(r.c[n], n % 2 ? -1.0 : 1.0));
    CHECK(vbm1_sqrt_to(&r, &x1, kmax));
    /* binom(1/2, n): dyadic, exact doubles */
    static const double bin[7] = {1.0, 0.5, -0.125, 0.0625, -0.0390625, 0.02734375, -0.0205078125};
    for (int n = 0; n <= kmax; n++)
        CHECK(holds(r.c[n], bin[n]));
    CHECK(vbm1_log_to(&r, &x1, kmax));
    CHECK(holds(r.c[0], 0.0));
    for (int n = 1; n <= 3; n++) /* 1, -1/2, 1/3: the nearest doubles within the enclosures' ulps */
        CHECK(fabs(vbx_ia_mid(r.c[n]) - (n % 2 ? 1.0 : -1.0) / n) < 1e-15 &&
              r.c[n].hi - r.c[n].lo < 1e-14);
    CHECK(holds(r.c[1], 1.0) && holds(r.c[2], -0.5));
    vbm1_mul_to(&sq, &x1, &x1, 2);
    CHECK(holds(sq.c[0], 1.0) && holds(sq.c[1], 2.0) && holds(sq.c[2], 1.0));
    CHECK(holds(vbm1_mul_coef(&x1, &x1, 1), 2.0));
    VB_TEST_END();
}
