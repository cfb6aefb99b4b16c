/* Unit tests of core/cells/vb_geom_shared.h, the math shared by the reference
 * backend and the sampling kernels: face mapping, the ray/bisector hit and
 * its sheet, Newton on three bisectors, the double tangent-sphere solver. */
#include <math.h>
#include <stdint.h>

#include "vb_geom_shared.h"
#include "vb_test.h"

static uint64_t lcg = 12345;

static double rnd(void)
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg >> 11) / 9007199254740992.0;
}

static void test_faces(void)
{
    int bad = 0;
    for (vbs_u32 f = 0; f < 6; f++)
        for (int k = 0; k < 50; k++) {
            double u = 2 * rnd() - 1, v = 2 * rnd() - 1, d[3], u2, v2;
            vbs_face_dir(f, u, v, d);
            CHECK_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-15);
            vbs_u32 f2 = vbs_dir_face(d, &u2, &v2);
            bad += f2 != f || fabs(u2 - u) > 1e-14 || fabs(v2 - v) > 1e-14;
        }
    CHECK_INT(bad, 0);
    CHECK(vbs_sample_coord(0, 30) == -1.0);
    CHECK(vbs_sample_coord(29, 30) == 1.0);
    CHECK_INT(vbs_tile_of(-1.0, 4), 0);
    CHECK_INT(vbs_tile_of(1.0, 4), 3);
    CHECK_INT(vbs_tile_of(-0.49, 4), 1);
}

/* The hit lies on the correct sheet (equidistant, unsquared), and a miss
 * means the distance difference never reaches zero along the ray. */
static void test_ray_hit(void)
{
    int hits = 0, misses = 0, bad = 0;
    for (int k = 0; k < 2000; k++) {
        vbs_bisector b;
        double cj[3] = {6 * rnd() - 3, 6 * rnd() - 3, 6 * rnd() - 3}, rj = 0.3 + 2 * rnd();
        if (!vbs_bisector_make(0, 0, 0, 1.0, 1.0, cj[0], cj[1], cj[2], rj, 7, &b))
            continue;
        double d[3];
        vbs_face_dir((vbs_u32)(k % 6), 2 * rnd() - 1, 2 * rnd() - 1, d);
        double s = vbs_ray_hit(b.ex, b.ey, b.ez, b.delta, b.num, d);
        if (s >= 0.0) {
            hits++;
            double P[3] = {s * d[0], s * d[1], s * d[2]};
            bad += !(fabs(vbs_defect(&b, P)) <= 1e-9 * (1 + s));
        } else {
            misses++;
            for (double t = 0.0; t < 1e4; t = t * 1.5 + 0.01) {
                double q[3] = {t * d[0] - cj[0], t * d[1] - cj[1], t * d[2] - cj[2]};
                bad += sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - rj - (t - 1.0) <= 0.0;
            }
        }
    }
    CHECK(hits > 500);
    CHECK(misses > 100);
    CHECK_INT(bad, 0);
}

/* Lower envelope: lowest id wins an exact tie. */
static void test_envelope_tie(void)
{
    vbs_bisector b[2];
    CHECK(vbs_bisector_make(0, 0, 0, 1, 1, 4, 0, 0, 1, 9, &b[0]));
    CHECK(vbs_bisector_make(0, 0, 0, 1, 1, 0, 4, 0, 1, 3, &b[1]));
    vbs_u32 list[2] = {0, 1};
    double d[3] = {sqrt(0.5), sqrt(0.5), 0.0}, s;
    CHECK_INT(vbs_envelope(b, list, 2, 1e9, d, &s), 3);
    double far[3] = {0.0, 0.0, 1.0};
    CHECK_INT(vbs_envelope(b, list, 2, 1e9, far, &s), VBS_INF_COLOUR);
}

/* Four spheres tangent to a chosen sphere: the solver returns it, and Newton
 * on the three bisectors of sphere 0 converges to it from nearby. */
static void test_tangent_and_newton(void)
{
    int found = 0, newton_ok = 0, trials = 0;
    for (int k = 0; k < 200; k++) {
        double p[3] = {rnd(), rnd(), rnd()}, t = 0.5 + rnd();
        double s[4][4];
        for (int a = 0; a < 4; a++) {
            double u[3] = {2 * rnd() - 1, 2 * rnd() - 1, 2 * rnd() - 1};
            double n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            double r = 0.5 + rnd(), dist = t + r;
            for (int c = 0; c < 3; c++)
                s[a][c] = p[c] + dist * u[c] / n;
            s[a][3] = r;
        }
        double roots[2][4];
        int nr = vbs_tangent_roots(s, roots);
        for (int q = 0; q < nr; q++)
            found += fabs(roots[q][0] - p[0]) < 1e-7 && fabs(roots[q][1] - p[1]) < 1e-7 &&
                     fabs(roots[q][2] - p[2]) < 1e-7 && fabs(roots[q][3] - t) < 1e-7;
        vbs_bisector tri[3];
        int ok = 1;
        for (int a = 0; a < 3; a++)
            ok &= vbs_bisector_make(s[0][0], s[0][1], s[0][2], s[0][3], s[0][3], s[a + 1][0], s[a + 1][1],
                                    s[a + 1][2], s[a + 1][3], (vbs_u32)a, &tri[a]);
        if (!ok)
            continue;
        trials++;
        double P[3];
        for (int c = 0; c < 3; c++)
            P[c] = (p[c] - s[0][c]) / s[0][3] + 1e-3 * (rnd() - 0.5);
        if (vbs_newton(&tri[0], &tri[1], &tri[2], 1e-12, 40, P) == VBS_NEWTON_OK) {
            double w[3];
            for (int c = 0; c < 3; c++)
                w[c] = s[0][c] + s[0][3] * P[c];
            newton_ok += fabs(w[0] - p[0]) < 1e-8 && fabs(w[1] - p[1]) < 1e-8 &&
                         fabs(w[2] - p[2]) < 1e-8;
        }
    }
    CHECK(found >= 195);
    CHECK(trials > 150);
    CHECK(newton_ok >= trials - 5);
}

/* Three coplanar bisector planes through one line: singular (Fig. 6). */
static void test_singular(void)
{
    vbs_bisector tri[3];
    CHECK(vbs_bisector_make(0, 0, 0, 1, 1, 3, 0, 0, 1, 1, &tri[0]));
    CHECK(vbs_bisector_make(0, 0, 0, 1, 1, 0, 3, 0, 1, 2, &tri[1]));
    CHECK(vbs_bisector_make(0, 0, 0, 1, 1, 3, 3, 0, 1, 3, &tri[2]));
    double P[3] = {1.5, 1.5, 0.2};
    CHECK_INT(vbs_newton(&tri[0], &tri[1], &tri[2], 1e-12, 40, P), VBS_NEWTON_SINGULAR);
}

int main(void)
{
    test_faces();
    test_ray_hit();
    test_envelope_tie();
    test_tangent_and_newton();
    test_singular();
    VB_TEST_END();
}
