/* Cell measures in closed form (verify/measures/stokes_cell.c: Stokes over
 * the arcs bounding the regions of directions each neighbour owns), without
 * contacts (with them every atom goes by patches):
 *  - one ball, two equal balls (cap volume and area per atom), two unequal
 *    balls (per-atom SAS: the sphere less the cap inside the other ball; the
 *    volumes add up to the union's), three unequal balls in a row (union by
 *    inclusion-exclusion), every atom in closed form and within 1e-6;
 *  - 60 balls of protein radii in a 9 A box (seeded): every enclosure meets
 *    the patch method's (1000 patches per atom), the same bytes on 1 and 2
 *    threads;
 *  - four equal balls on a square (four owners at one point: the arcs'
 *    ends cannot be ordered): the patches take over, and the four atoms
 *    agree. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_spheres.h"
#include "measures_balls.h"
#include "vb_test.h"

/* patches: 0 closed forms first, 1 patches only. */
static int run(vb_ctx *ctx, const char *text, int patches, int threads, vb_cell_measures *m)
{
    vb_sphere_set *s = spheres(ctx, text);
    if (!s)
        return -1;
    vb_measure_options o;
    vb_measure_defaults(&o);
    o.threads = threads;
    o.patches = patches;
    o.max_patches = patches ? 1000 : 0; /* wide, but proven: they must meet */
    int rc = vb_cell_measures_compute(ctx, s, &o, m);
    vb_spheres_free(s);
    return rc;
}

static void test_small(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx, "1.5 -2 0.25 1.7\n", 0, 1, &m), VB_OK);
    double r = 3.1, v = 4.0 / 3.0 * PI * r * r * r, a = 4.0 * PI * r * r;
    CHECK_INT(m.nclosed, 1);
    CHECK(encloses(m.vol_lo[0], m.vol_hi[0], v, 1e-6 * v));
    CHECK(encloses(m.sas_lo[0], m.sas_hi[0], a, 1e-6 * a));
    vb_cell_measures_free(&m);

    /* equal radii 1 (expanded 2.4) at distance 3: each cell is its ball cut
     * by the bisector plane at 1.5, a cap of height 0.9 removed */
    CHECK_INT(run(ctx, "0 0 0 1\n1 2 2 1\n", 0, 1, &m), VB_OK);
    r = 2.4;
    double h = r - 1.5;
    v = 4.0 / 3.0 * PI * r * r * r - cap_volume(r, h);
    a = 4.0 * PI * r * r - 2.0 * PI * r * h;
    CHECK_INT(m.nclosed, 2);
    CHECK_INT(m.nloose, 0);
    for (int i = 0; i < 2; i++) {
        CHECK(encloses(m.vol_lo[i], m.vol_hi[i], v, 1e-6 * v));
        CHECK(encloses(m.sas_lo[i], m.sas_hi[i], a, 1e-6 * a));
    }
    vb_cell_measures_free(&m);

    /* unequal: expanded radii 2.6 and 3.2, distance d; sphere i keeps all
     * but the cap inside the other ball (radical plane at x from c0) */
    CHECK_INT(run(ctx, "0 0 0 1.2\n2.1 0.3 -0.2 1.8\n", 0, 1, &m), VB_OK);
    double r0 = 2.6, r1 = 3.2, d = sqrt(2.1 * 2.1 + 0.09 + 0.04);
    double x = (d * d + r0 * r0 - r1 * r1) / (2.0 * d), h0 = r0 - x, h1 = r1 - (d - x);
    double a0 = 4.0 * PI * r0 * r0 - 2.0 * PI * r0 * h0;
    double a1 = 4.0 * PI * r1 * r1 - 2.0 * PI * r1 * h1;
    v = 4.0 / 3.0 * PI * (r0 * r0 * r0 + r1 * r1 * r1) - cap_volume(r0, h0) - cap_volume(r1, h1);
    CHECK_INT(m.nclosed, 2);
    CHECK(encloses(m.sas_lo[0], m.sas_hi[0], a0, 1e-6 * a0));
    CHECK(encloses(m.sas_lo[1], m.sas_hi[1], a1, 1e-6 * a1));
    double vlo, vhi, alo, ahi;
    sums(&m, &vlo, &vhi, &alo, &ahi);
    CHECK(encloses(vlo, vhi, v, 1e-6 * v));
    CHECK(encloses(alo, ahi, a0 + a1, 1e-6 * (a0 + a1)));
    vb_cell_measures_free(&m);
}

static void test_row(vb_ctx *ctx)
{
    /* balls 0 and 2 (expanded radii 2.9 and 3.0, 6.4 apart) do not meet */
    vb_cell_measures m;
    CHECK_INT(run(ctx, "0 0 0 1.5\n3.1 0.2 0 1.9\n6.4 0 0 1.6\n", 0, 1, &m), VB_OK);
    double v01, a01, v12, a12, r1 = 3.3;
    union2(2.9, r1, sqrt(3.1 * 3.1 + 0.04), &v01, &a01);
    union2(r1, 3.0, sqrt(3.3 * 3.3 + 0.04), &v12, &a12);
    double v = v01 + v12 - 4.0 / 3.0 * PI * r1 * r1 * r1, a = a01 + a12 - 4.0 * PI * r1 * r1;
    double vlo, vhi, alo, ahi;
    sums(&m, &vlo, &vhi, &alo, &ahi);
    CHECK_INT(m.nclosed, 3);
    CHECK_INT(m.nloose, 0);
    CHECK(encloses(vlo, vhi, v, 1e-6 * v));
    CHECK(encloses(alo, ahi, a, 1e-6 * a));
    vb_cell_measures_free(&m);
}

static int meets(double alo, double ahi, double blo, double bhi)
{
    return alo <= bhi && blo <= ahi;
}

static void test_cluster(vb_ctx *ctx)
{
    static const double radii[4] = {1.7, 1.55, 1.52, 1.8};
    char *text = malloc(60 * 64);
    if (!text) {
        CHECK(0);
        return;
    }
    size_t len = 0;
    srand(31);
    for (int i = 0; i < 60; i++)
        len += (size_t)snprintf(text + len, 64, "%.3f %.3f %.3f %.2f\n", 9.0 * rand() / RAND_MAX,
                                9.0 * rand() / RAND_MAX, 9.0 * rand() / RAND_MAX,
                                radii[rand() % 4]);
    vb_cell_measures c, c2, p;
    CHECK_INT(run(ctx, text, 0, 1, &c), VB_OK);
    CHECK_INT(run(ctx, text, 0, 2, &c2), VB_OK);
    CHECK_INT(run(ctx, text, 1, 2, &p), VB_OK);
    CHECK(c.nclosed + c.nempty >= 55); /* nearly all in closed form (57) */
    CHECK(c.nloose <= c.n - c.nclosed); /* only atoms the patches took */
    CHECK_INT(p.nclosed, 0);
    size_t bad = 0;
    for (size_t i = 0; i < c.n && i < p.n; i++)
        bad += !meets(c.vol_lo[i], c.vol_hi[i], p.vol_lo[i], p.vol_hi[i]) ||
               !meets(c.sas_lo[i], c.sas_hi[i], p.sas_lo[i], p.sas_hi[i]);
    CHECK_INT(bad, 0);
    CHECK(memcmp(c.vol_lo, c2.vol_lo, c.n * sizeof(double)) == 0);
    CHECK(memcmp(c.sas_hi, c2.sas_hi, c.n * sizeof(double)) == 0);
    vb_cell_measures_free(&c);
    vb_cell_measures_free(&c2);
    vb_cell_measures_free(&p);
    free(text);
}

static void test_square(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx, "0 0 0 1\n2.5 0 0 1\n0 2.5 0 1\n2.5 2.5 0 1\n", 0, 2, &m), VB_OK);
    CHECK(m.nclosed < 4);
    for (int i = 1; i < 4; i++) {
        CHECK(meets(m.vol_lo[0], m.vol_hi[0], m.vol_lo[i], m.vol_hi[i]));
        CHECK(meets(m.sas_lo[0], m.sas_hi[0], m.sas_lo[i], m.sas_hi[i]));
    }
    vb_cell_measures_free(&m);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0);
    test_small(ctx);
    test_row(ctx);
    test_cluster(ctx);
    test_square(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
