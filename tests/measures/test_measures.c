/* Cell measures (verify/measures/): enclosures against closed forms.
 *  - one ball: 4/3 pi r^3 and 4 pi r^2;
 *  - two equal balls: the cell is the ball cut by the bisector plane (cap
 *    volume, cap area, contact disc), both sides of the contact;
 *  - two equal balls on a slanted axis (radii equal as written: a plane);
 *  - three equal balls on a triangle: congruent cells, a straight edge;
 *  - two and three unequal balls (hyperboloid faces): the volumes add up to
 *    the union's volume and the SAS areas to its area (inclusion-exclusion:
 *    lenses of pairs; the outer balls of the three do not meet);
 *  - nested, internally tangent and externally tangent balls;
 *  - contacts from one side (the default) against both sides met
 *    (contacts_both), in closed form and by patches: the same pairs, each
 *    met enclosure inside the one-sided one, both within the tolerance;
 *  - bad options. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_parallel.h"
#include "vb_spheres.h"
#include "measures_balls.h"
#include "vb_test.h"

static int run_both(vb_ctx *ctx, const char *text, double tol, int both, int patches,
                    vb_cell_measures *m)
{
    vb_sphere_set *s = spheres(ctx, text);
    if (!s)
        return -1;
    vb_measure_options o;
    vb_measure_defaults(&o);
    o.tolerance = tol;
    o.contacts_both = both;
    o.patches = patches;
    o.contacts = 1;
    o.threads = 2;
    o.max_patches = 200000; /* the closed forms are asked to 1e-6 */
    int rc = vb_cell_measures_compute(ctx, s, &o, m);
    vb_spheres_free(s);
    return rc;
}

static int run(vb_ctx *ctx, const char *text, double tol, vb_cell_measures *m)
{
    return run_both(ctx, text, tol, 0, 0, m);
}

static void test_one_ball(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx, "1.5 -2 0.25 1.7\n", 1e-6, &m), VB_OK);
    double r = 1.7 + 1.4, v = 4.0 / 3.0 * PI * r * r * r, a = 4.0 * PI * r * r;
    CHECK(encloses(m.vol_lo[0], m.vol_hi[0], v, 1e-6 * v));
    CHECK(encloses(m.sas_lo[0], m.sas_hi[0], a, 1e-6 * a));
    CHECK_INT(m.ncontacts, 0);
    vb_cell_measures_free(&m);
}

static void test_two_equal(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx, "0 0 0 1\n1.5 0 0 1\n", 1e-6, &m), VB_OK);
    double r = 2.4, h = r - 0.75;
    double v = 4.0 / 3.0 * PI * r * r * r - cap_volume(r, h);
    double a = 4.0 * PI * r * r - 2.0 * PI * r * h, c = PI * (r * r - 0.75 * 0.75);
    for (int i = 0; i < 2; i++) {
        CHECK(encloses(m.vol_lo[i], m.vol_hi[i], v, 1e-6 * v));
        CHECK(encloses(m.sas_lo[i], m.sas_hi[i], a, 1e-6 * a));
    }
    CHECK_INT(m.ncontacts, 1);
    if (m.ncontacts == 1) {
        CHECK_INT(m.contacts[0].i, 0);
        CHECK_INT(m.contacts[0].j, 1);
        CHECK(encloses(m.contacts[0].lo, m.contacts[0].hi, c, 1e-6 * c));
    }
    vb_cell_measures_free(&m);
}

/* Two equal balls on a slanted axis: the face is a plane (radii equal,
 * decided exactly from the input, so the difference of radii is 0, not an
 * interval across 0), cut by the cube faces' directions obliquely. Cap
 * volume, cap area and the contact disc, to 1e-6, from both sides, and no
 * atom loose. */
static void test_slanted_pair(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx, "0.1 0.2 -0.3 1.6\n1.0 -0.9 0.4 1.60\n", 1e-6, &m), VB_OK);
    double r = 3.0, d = sqrt(0.81 + 1.21 + 0.49), h = r - 0.5 * d;
    double v = 4.0 / 3.0 * PI * r * r * r - cap_volume(r, h);
    double a = 4.0 * PI * r * r - 2.0 * PI * r * h, c = PI * (r * r - 0.25 * d * d);
    for (int i = 0; i < 2; i++) {
        CHECK(encloses(m.vol_lo[i], m.vol_hi[i], v, 1e-6 * v));
        CHECK(encloses(m.sas_lo[i], m.sas_hi[i], a, 1e-6 * a));
    }
    CHECK_INT(m.nloose, 0);
    CHECK_INT(m.ncontacts, 1);
    if (m.ncontacts == 1)
        CHECK(encloses(m.contacts[0].lo, m.contacts[0].hi, c, 1e-6 * c));
    vb_cell_measures_free(&m);
}

/* Three equal balls on an equilateral triangle (side 2 to 15 digits, in a
 * generic orientation; expanded radius 2.4: the three faces meet in a
 * Voronoi edge, a line since the radii are equal). The cells are congruent:
 * their enclosures, to 1e-6, meet pairwise, as do the three contacts', and
 * no atom is left loose (before kappa's exact 0, every patch on that edge
 * fell back to min..max). Left out: the triangle in the xy plane, where a
 * bisector plane through the third centre runs along patch sides (a = 0)
 * and that atom refines there to the end of its budget. */
static void test_equal_triple(vb_ctx *ctx)
{
    vb_cell_measures m;
    CHECK_INT(run(ctx,
                  "0 0 0 1\n1.680782753630657 0.486044557674782 0.968880809518112 1\n"
                  "0.251797868105846 1.858305293526159 0.695197288307431 1\n",
                  1e-6, &m),
              VB_OK);
    CHECK_INT(m.nloose, 0);
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        CHECK(m.vol_lo[i] <= m.vol_hi[j] && m.vol_lo[j] <= m.vol_hi[i]);
        CHECK(m.sas_lo[i] <= m.sas_hi[j] && m.sas_lo[j] <= m.sas_hi[i]);
        CHECK(m.vol_hi[i] - m.vol_lo[i] <= 1e-6 * m.vol_hi[i]);
    }
    CHECK_INT(m.ncontacts, 3);
    for (size_t k = 0; m.ncontacts == 3 && k < 3; k++) {
        const vb_contact *a = &m.contacts[k], *b = &m.contacts[(k + 1) % 3];
        CHECK(a->lo <= b->hi && b->lo <= a->hi && a->hi - a->lo <= 1e-6 * a->hi);
    }
    vb_cell_measures_free(&m);
}

static void test_unequal(vb_ctx *ctx)
{
    vb_cell_measures m;
    double v, a, vlo, vhi, alo, ahi;
    CHECK_INT(run(ctx, "0 0 0 1.2\n2.1 0.3 -0.2 1.8\n", 1e-5, &m), VB_OK);
    union2(2.6, 3.2, sqrt(2.1 * 2.1 + 0.09 + 0.04), &v, &a);
    sums(&m, &vlo, &vhi, &alo, &ahi);
    CHECK(encloses(vlo, vhi, v, 1e-5 * v));
    CHECK(encloses(alo, ahi, a, 1e-5 * a));
    CHECK_INT(m.ncontacts, 1);
    vb_cell_measures_free(&m);

    /* three in a row: balls 0 and 2 (expanded radii 2.9 and 3.0, 6.4 apart)
     * do not meet, so the union is the sum less the two lenses */
    CHECK_INT(run(ctx, "0 0 0 1.5\n3.1 0.2 0 1.9\n6.4 0 0 1.6\n", 1e-4, &m), VB_OK);
    double v01, a01, v12, a12, d01 = sqrt(3.1 * 3.1 + 0.04), d12 = sqrt(3.3 * 3.3 + 0.04);
    double r0 = 2.9, r1 = 3.3, r2 = 3.0;
    union2(r0, r1, d01, &v01, &a01);
    union2(r1, r2, d12, &v12, &a12);
    double b1v = 4.0 / 3.0 * PI * r1 * r1 * r1, b1a = 4.0 * PI * r1 * r1;
    v = v01 + v12 - b1v;
    a = a01 + a12 - b1a;
    sums(&m, &vlo, &vhi, &alo, &ahi);
    CHECK(encloses(vlo, vhi, v, 1e-4 * v));
    CHECK(encloses(alo, ahi, a, 1e-4 * a));
    CHECK_INT(m.ncontacts, 2);
    vb_cell_measures_free(&m);
}

static void test_nested_tangent(vb_ctx *ctx)
{
    vb_cell_measures m;
    /* sphere 1 strictly inside sphere 0; sphere 2 touches 0 from inside */
    CHECK_INT(run(ctx, "0 0 0 3\n0.5 0 0 1\n0 2 0 1\n", 1e-6, &m), VB_OK);
    double r = 4.4, v = 4.0 / 3.0 * PI * r * r * r, a = 4.0 * PI * r * r;
    CHECK(m.empty[1] && m.empty[2] && !m.empty[0]);
    CHECK(m.vol_hi[1] == 0.0 && m.sas_hi[1] == 0.0 && m.vol_hi[2] == 0.0);
    CHECK_INT(m.nempty, 2);
    CHECK(encloses(m.vol_lo[0], m.vol_hi[0], v, 1e-6 * v));
    CHECK(encloses(m.sas_lo[0], m.sas_hi[0], a, 1e-6 * a));
    CHECK_INT(m.ncontacts, 0);
    vb_cell_measures_free(&m);
    /* expanded balls touching from outside (distance 2.4 + 2.4): whole balls */
    CHECK_INT(run(ctx, "0 0 0 1\n0 0 4.8 1\n", 1e-6, &m), VB_OK);
    r = 2.4;
    v = 4.0 / 3.0 * PI * r * r * r;
    for (int i = 0; i < 2; i++)
        CHECK(encloses(m.vol_lo[i], m.vol_hi[i], v, 1e-6 * v));
    /* the touching point may keep a contact [0, tiny] (area 0 enclosed) */
    CHECK(m.ncontacts == 0 || (m.contacts[0].lo == 0.0 && m.contacts[0].hi < 1e-6));
    vb_cell_measures_free(&m);
}

/* Six unequal balls in a cluster (every pair's expanded balls meet, some
 * faces cut by others): each contact from the side that writes it (i < j)
 * against both sides integrated and met (a disjoint pair would fail the
 * run with VB_EINTERNAL), in closed form and by patches. */
static void test_one_side(vb_ctx *ctx)
{
    static const char *six = "0 0 0 1.7\n2.9 0.4 -0.3 1.5\n0.6 3.1 0.2 1.8\n"
                             "-0.4 0.5 2.8 1.6\n2.2 2.6 2.1 1.9\n-2.5 1.3 -1.1 1.4\n";
    for (int patches = 0; patches < 2; patches++) {
        double tol = patches ? 1e-3 : 1e-6;
        vb_cell_measures one, both;
        CHECK_INT(run_both(ctx, six, tol, 0, patches, &one), VB_OK);
        CHECK_INT(run_both(ctx, six, tol, 1, patches, &both), VB_OK);
        CHECK(one.ncontacts >= 10);
        CHECK_INT(one.ncontacts, both.ncontacts);
        for (size_t k = 0; k < one.ncontacts && k < both.ncontacts; k++) {
            const vb_contact *a = &one.contacts[k], *b = &both.contacts[k];
            CHECK(a->i == b->i && a->j == b->j && a->i < a->j);
            CHECK(a->lo <= b->lo && b->hi <= a->hi); /* the meet lies in either side */
            CHECK(a->hi - a->lo <= tol * a->hi || patches); /* patches: a budget */
        }
        for (size_t i = 0; i < 6; i++) /* the atoms' values do not depend on it */
            CHECK(one.vol_lo[i] <= both.vol_hi[i] && both.vol_lo[i] <= one.vol_hi[i] &&
                  one.sas_lo[i] <= both.sas_hi[i] && both.sas_lo[i] <= one.sas_hi[i]);
        vb_cell_measures_free(&one);
        vb_cell_measures_free(&both);
    }
}

static void test_bad_options(vb_ctx *ctx)
{
    vb_sphere_set *s = spheres(ctx, "0 0 0 1\n");
    vb_measure_options o;
    vb_cell_measures m;
    vb_measure_defaults(&o);
    o.probe = -0.1;
    CHECK_INT(vb_cell_measures_compute(ctx, s, &o, &m), VB_EMISUSE);
    vb_measure_defaults(&o);
    o.tolerance = 1.0;
    CHECK_INT(vb_cell_measures_compute(ctx, s, &o, &m), VB_EMISUSE);
    o.tolerance = 0.0;
    CHECK_INT(vb_cell_measures_compute(ctx, s, &o, &m), VB_EMISUSE);
    vb_measure_defaults(&o);
    o.max_patches = 95;
    CHECK_INT(vb_cell_measures_compute(ctx, s, &o, &m), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "--max-patches needs an integer >= 96") == 0);
    vb_spheres_free(s);
}

/* The options' ranges at their edges (vb_measure_options_check, the
 * check of `vorball cells` and vorball.cells). */
static void test_options_check(vb_ctx *ctx)
{
    vb_measure_options o;
    vb_measure_defaults(&o);
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    o.probe = 0.0;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    o.probe = -0.0;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    o.probe = -1e-300;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    CHECK(strstr(vb_errmsg(ctx), "--probe") != NULL);
    o.probe = HUGE_VAL;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    o.probe = NAN;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    vb_measure_defaults(&o);
    o.tolerance = 0x1p-1074;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    o.tolerance = nextafter(1.0, 0.0);
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    o.tolerance = 1.0;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "--tolerance 1: must lie in (0, 1)") == 0);
    o.tolerance = 0.0;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    o.tolerance = NAN;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    vb_measure_defaults(&o);
    size_t patches[] = {0, 96, 97, 1000000};
    for (size_t k = 0; k < sizeof patches / sizeof *patches; k++) {
        o.max_patches = patches[k];
        CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    }
    o.max_patches = 95;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    o.max_patches = 1;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "--max-patches needs an integer >= 96") == 0);
    vb_measure_defaults(&o);
    int threads[] = {0, 1, VB_MAX_THREADS};
    for (size_t k = 0; k < sizeof threads / sizeof *threads; k++) {
        o.threads = threads[k];
        CHECK_INT(vb_measure_options_check(ctx, &o), VB_OK);
    }
    o.threads = VB_MAX_THREADS + 1;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    o.threads = -1;
    CHECK_INT(vb_measure_options_check(ctx, &o), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "--threads needs 1..64") == 0);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0);
    test_options_check(ctx);
    test_one_ball(ctx);
    test_two_equal(ctx);
    test_slanted_pair(ctx);
    test_equal_triple(ctx);
    test_unequal(ctx);
    test_nested_tangent(ctx);
    test_one_side(ctx);
    test_bad_options(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
