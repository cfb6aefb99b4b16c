/* The angles that order the ends of a circle's restrictions (cap_arcs.c):
 * vbm_fast_angle (cap_geom.c) must lie within 1e-14 of the exact angle
 * (atan2l in long double as the reference) and within 2e-14 of glibc's
 * atan2 moved to [0, 2 pi), as its derivation says (VBM_FAST_ANGLE_ERR,
 * 1e-13, is what cap_arcs.c relies on), on 2 M random directions of
 * random lengths and on the points where its reduction switches (the
 * eighths' thresholds, the diagonals, the axes). And the arcs vbm_cap_arcs
 * finds must carry atan2's angles of their ends, not the fast ones: on
 * random intersections of caps, every arc end made by a restriction has
 * tp (tq, less 2 pi past the wrap) equal bit for bit to atan2's angle of
 * its middle. */
#include <math.h>
#include <stdint.h>

#include "vbm_caps.h"
#include "vb_test.h"

#define TWO_PI 6.283185307179586

static double uniform(uint64_t *s)
{
    return (double)(vb_test_xorshift(s) >> 11) * 0x1p-53;
}

static double atan2_0(double x, double y)
{
    double t = atan2(y, x);
    return t < 0.0 ? t + TWO_PI : t;
}

/* The errors of vbm_fast_angle at (x, y) against atan2 and atan2l, the
 * wrap at 0 = 2 pi taken either way. */
static void errors(double x, double y, double *e_libm, double *e_exact)
{
    double f = vbm_fast_angle(x, y), a = atan2_0(x, y);
    long double t = atan2l((long double)y, (long double)x);
    if (t < 0.0L)
        t += 2.0L * 3.14159265358979323846264338327950288L;
    double d1 = fabs(f - a), d2 = (double)fabsl((long double)f - t);
    d1 = fmin(d1, fabs(d1 - TWO_PI));
    d2 = fmin(d2, fabs(d2 - TWO_PI));
    *e_libm = fmax(*e_libm, d1);
    *e_exact = fmax(*e_exact, d2);
}

static void check_angles(void)
{
    uint64_t s = 0x9e3779b97f4a7c15u;
    double el = 0.0, ee = 0.0;
    for (int i = 0; i < 2000000; i++) {
        double th = TWO_PI * uniform(&s), r = 0.5 + uniform(&s);
        errors(r * cos(th), r * sin(th), &el, &ee);
    }
    /* where the reduction switches: t = (2 i + 1) / 16 and its neighbours,
     * in every octant; the diagonals and the axes */
    for (int i = 0; i <= 16; i++)
        for (int d = -3; d <= 3; d++)
            for (int o = 0; o < 8; o++) {
                double t = i / 16.0 + d * 0x1p-52, x = 1.0, y = t;
                if (t < 0.0 || t > 1.0)
                    continue;
                if (o & 1) {
                    x = t;
                    y = 1.0;
                }
                if (o & 2)
                    x = -x;
                if (o & 4)
                    y = -y;
                errors(x, y, &el, &ee);
            }
    double ax[][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, -0x1p-60}, {-1, 0x1p-60}, {-1, -0x1p-60}};
    for (size_t i = 0; i < sizeof ax / sizeof *ax; i++)
        errors(ax[i][0], ax[i][1], &el, &ee);
    printf("fast angle: max error %.3g against atan2, %.3g against atan2l\n", el, ee);
    CHECK(el <= 2e-14);
    CHECK(ee <= 1e-14);
    CHECK(2e-14 <= 0.2 * VBM_FAST_ANGLE_ERR);
}

static void unit(uint64_t *s, double *u)
{
    double z = 2.0 * uniform(s) - 1.0, ph = TWO_PI * uniform(s), r = sqrt(1.0 - z * z);
    u[0] = r * cos(ph);
    u[1] = r * sin(ph);
    u[2] = z;
}

static void check_arcs(void)
{
    uint64_t s = 0x243f6a8885a308d3u;
    vbm_capwork w = {0};
    vbm_cap caps[12];
    size_t ends = 0, bad = 0, found = 0;
    for (int it = 0; it < 3000; it++) {
        size_t n = 2 + (size_t)(uniform(&s) * 10.0);
        for (size_t m = 0; m < n; m++) {
            double u[3], c = m == 0 ? 0.9 - 1.6 * uniform(&s) : 0.95 - 1.2 * uniform(&s);
            unit(&s, u);
            for (int k = 0; k < 3; k++)
                caps[m].n[k] = vbx_ia_point(m == 0 ? (k == 2) : 0.6 * u[k] + (k == 2));
            double nn = 0.0;
            for (int k = 0; k < 3; k++)
                nn += caps[m].n[k].lo * caps[m].n[k].lo;
            caps[m].h = vbx_ia_point(c * sqrt(nn));
        }
        if (vbm_cap_arcs(caps, NULL, n, NULL, NULL, 0, &w) != 1)
            continue;
        found += w.narc > 0;
        for (size_t i = 0; i < w.narc; i++) {
            const vbm_arc *a = &w.arc[i];
            if (a->pcap != VBM_NO_CAP) {
                ends++;
                bad += a->tp != atan2_0(vbx_ia_mid(a->p[0]), vbx_ia_mid(a->p[1]));
            }
            if (a->qcap != VBM_NO_CAP) {
                double t = atan2_0(vbx_ia_mid(a->q[0]), vbx_ia_mid(a->q[1]));
                ends++;
                bad += a->tq != t && a->tq != t + TWO_PI;
            }
        }
    }
    vbm_caps_free(&w);
    printf("arcs: %zu intersections with arcs, %zu ends, %zu not atan2's\n", found, ends, bad);
    CHECK(found > 1000);
    CHECK(ends > 3000);
    CHECK_INT(bad, 0);
}

int main(void)
{
    check_angles();
    check_arcs();
    VB_TEST_END();
}
