/* The double interval atan (integrands.c, which replaced MPFR's for the own
 * arcs' angles and the patches' corners) against MPFR's atan rounded down
 * and up: every enclosure holds both (so the exact value, which lies
 * between them; an enclosure's ends are doubles, so lo <= atan x exactly
 * when lo <= atan x rounded down), on points from 1e-20 to 1e20 of both
 * signs, near the range reduction's seams (1, tan(pi/8)), subnormal and
 * huge, and on narrow and wide intervals; a point's within 32 ulps of
 * |atan x|, a narrow interval's within that of MPFR's two ends. */
#include <float.h>
#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <stdlib.h>

#include "vbm_piece.h"
#include "vb_test.h"

static double mpfr_atan_d(double x, mpfr_rnd_t rnd)
{
    mpfr_t t;
    mpfr_init2(t, 53);
    mpfr_set_d(t, x, MPFR_RNDN);
    mpfr_atan(t, t, rnd);
    double r = mpfr_get_d(t, rnd);
    mpfr_clear(t);
    return r;
}

/* vbm_ia_atan([lo, hi]) holds [atan lo rounded down, atan hi rounded up]
 * and is at most 32 ulps (of its larger end) wider than that. */
static int atan_holds(double lo, double hi)
{
    double dl = mpfr_atan_d(lo, MPFR_RNDD), dh = mpfr_atan_d(hi, MPFR_RNDU);
    vbx_ia r = vbm_ia_atan((vbx_ia){lo, hi});
    double mag = vbx_max(fabs(dl), fabs(dh));
    double w = (dh - dl) + vbx_max(mag * 0x1p-52 * 32.0, 0x1p-1070);
    int ok = r.lo <= dl && dh <= r.hi && r.hi - r.lo <= w;
    if (!ok)
        fprintf(stderr, "  atan([%.17g, %.17g]): [%.17g, %.17g] vs [%.17g, %.17g]\n", lo, hi, r.lo,
                r.hi, dl, dh);
    return ok;
}

int main(void)
{
    size_t bad = 0;
    srand(54);
    for (int i = 0; i < 10000; i++) {
        double u = (double)rand() / RAND_MAX, v = (double)rand() / RAND_MAX;
        double x = pow(10.0, 40.0 * u - 20.0) * (i & 1 ? -1.0 : 1.0);
        bad += !atan_holds(x, x);
        /* near the seams: a = 1 (the flip) and tan(pi/8) (one halving) */
        double s = (i & 2 ? 1.0 : 0.41421356237309503) * (1.0 + (v - 0.5) * 1e-6);
        bad += !atan_holds(s, s);
        /* narrow intervals (the arcs' angles: a few ulps) and wide ones */
        double h = x + fabs(x) * 1e-12 * v;
        bad += !atan_holds(x, h);
        double wl = 6.0 * u - 3.0;
        bad += !atan_holds(wl, wl + 2.0 * v);
    }
    const double sp[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 4.9406564584124654e-324, DBL_MIN, DBL_MAX,
                         -DBL_MAX, 1e308, 3.6, 0.19891236737965800, 0.7};
    for (size_t k = 0; k < sizeof sp / sizeof sp[0]; k++)
        bad += !atan_holds(sp[k], sp[k]);
    bad += !atan_holds(-1.0, 1.0);
    CHECK_INT(bad, 0);
    /* not finite: MPFR's ends */
    vbx_ia r = vbm_ia_atan((vbx_ia){-INFINITY, INFINITY});
    CHECK(r.lo <= -1.5707963267948966 && r.hi >= 1.5707963267948966 && r.hi < 1.6);
    vbm_ia_release();
    VB_TEST_END();
}
