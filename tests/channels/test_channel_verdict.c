/* The pore verdict (vbc_pore.h, core/discrete/channel_verdict.c) on
 * synthetic walls whose gaps are known: a tube of touching atoms walls its
 * axis, a ring with every other atom gone with every other atom gone (gaps wider than the wall
 * probe's disc) does not, half a tube (a groove) does not; the buried length
 * of a tube is its walled span, and a tube shorter than VBC_PORE_MIN_BURIED
 * is no pore; a gap of one missing ring is bridged, of two is not. */
#include "synth.h"
#include "vb_test.h"
#include "vbc_pore.h"

/* A hand-made pore on the z axis from z0 to z1, one point every 0.25 A,
 * radius `r` (only the verdict reads it). */
static void pore_on_z(vbc_pore *p, double z0, double z1, double r)
{
    memset(p, 0, sizeof *p);
    size_t n = (size_t)((z1 - z0) / 0.25 + 0.5) + 1;
    p->pts = calloc(n, sizeof *p->pts);
    p->n = p->pts ? n : 0;
    p->axis.u[2] = 1.0;
    for (size_t k = 0; k < p->n; k++) {
        p->pts[k].s = p->pts[k].z = z0 + 0.25 * (double)k;
        p->pts[k].r = r;
    }
}

static int walled_at(vb_ctx *ctx, const vb_sphere_set *s, double z, double r)
{
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    if (!c)
        return -2;
    void *scratch = NULL;
    size_t len = 0;
    double u[3] = {0, 0, 1}, p[3] = {0, 0, z};
    int w = vbc_plane_walled(c, u, p, r, &scratch, &len);
    free(scratch);
    vbc_cells_free(c);
    return w;
}

/* Keeps the atoms for which keep(x, y) holds. */
static vb_sphere_set *filtered(vb_sphere_set *s, int (*keep)(size_t i, double x, double y))
{
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++)
        n += (size_t)keep(i, s->x[i], s->y[i]);
    vb_sphere_set *t = vb_test_spheres_alloc(n, 0);
    for (size_t i = 0, j = 0; i < s->n; i++)
        if (keep(i, s->x[i], s->y[i])) {
            t->x[j] = s->x[i];
            t->y[j] = s->y[i];
            t->z[j] = s->z[i];
            t->r[j++] = s->r[i];
        }
    vb_spheres_free(s);
    return t;
}

static int every_other(size_t i, double x, double y)
{
    (void)x;
    (void)y;
    return i % 2 == 0;
}

static int half(size_t i, double x, double y)
{
    (void)i;
    (void)y;
    return x > 0.0;
}

static void test_walls(vb_ctx *ctx)
{
    /* 16 atoms of 1.5 A on a 6 A circle: 2.36 A apart, overlapping. The
     * staggered rings put a plane between two rings; the probe disc of 1 A
     * still finds no way out (the atoms 1.3 A above and below come within
     * its reach). */
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    CHECK_INT(walled_at(ctx, tube, 0.0, 4.5), 1);
    CHECK_INT(walled_at(ctx, tube, 1.3, 4.5), 1);
    /* Beyond the tube's ends the plane is open. */
    CHECK_INT(walled_at(ctx, tube, 30.0, 4.5), 0);
    vb_spheres_free(tube);
    /* 8 atoms of 1.0 A on the circle: 4.6 A apart, gaps of 2.6 A > 2 A. A
     * single ring: nothing above or below closes the gaps. */
    vb_sphere_set *sparse = filtered(synth_cylinder(1, 16, 6.0, 1.0, 2.6), every_other);
    CHECK_INT((int)sparse->n, 8);
    CHECK_INT(walled_at(ctx, sparse, 0.0, 5.0), 0);
    vb_spheres_free(sparse);
    /* A groove: half the tube. */
    vb_sphere_set *groove = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), half);
    CHECK_INT(walled_at(ctx, groove, 0.0, 4.5), 0);
    vb_spheres_free(groove);
}

/* Rings 7 (and 8 when `two`) of the 16 of a tube gone. */
static int ring7 = 0, ring8 = 0;
static int without_rings(size_t i, double x, double y)
{
    (void)x;
    (void)y;
    size_t ring = i / 16;
    return !((ring7 && ring == 7) || (ring8 && ring == 8));
}

static double buried_of(vb_ctx *ctx, const vb_sphere_set *s)
{
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    vbc_pore p;
    pore_on_z(&p, -30.0, 30.0, 4.5);
    vbc_pore_verdict v = {0, -1.0, 0, 0, 0};
    CHECK_INT(vbc_pore_judge(c, &p, &v), 0);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    return v.buried;
}

/* A missing ring opens a gap shorter than VBC_WALL_GAP: bridged, the whole
 * tube is buried; two missing rings open a longer one: the run splits. */
static void test_gaps(vb_ctx *ctx)
{
    ring7 = 1;
    vb_sphere_set *one = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), without_rings);
    CHECK_INT((int)one->n, 15 * 16);
    double b1 = buried_of(ctx, one);
    CHECK(b1 >= 42.0 && b1 <= 44.0);
    vb_spheres_free(one);
    ring8 = 1;
    vb_sphere_set *two = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), without_rings);
    double b2 = buried_of(ctx, two);
    CHECK(b2 > 15.0 && b2 < 25.0);
    vb_spheres_free(two);
    ring7 = ring8 = 0;
}

static void test_buried(vb_ctx *ctx)
{
    /* 16 rings 2.6 A apart: atoms from z = -19.5 - 1.5 to 19.5 + 1.5. */
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, tube, 3.0, &c), VB_OK);
    vbc_pore p;
    pore_on_z(&p, -30.0, 30.0, 4.5);
    vbc_pore_verdict v;
    CHECK_INT(vbc_pore_judge(c, &p, &v), 0);
    CHECK(v.is_pore);
    /* Walled within the rings' span, not beyond the last atoms. */
    /* Walled within the atoms' span (|z| <= 21) and the probe's reach
     * beyond it (the disc is a ball of 1 A: an atom 1 A off the plane
     * still walls it), never further: 42 to 44 A. */
    CHECK(v.buried >= 42.0 && v.buried <= 44.0);
    CHECK(p.pts[v.run_lo].s >= -22.0 - 1e-9 && p.pts[v.run_hi].s <= 22.0 + 1e-9);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(tube);
    /* 4 rings: 7.8 A of centres, about 11 A walled: no pore. */
    vb_sphere_set *ring = synth_cylinder(4, 16, 6.0, 1.5, 2.6);
    CHECK_INT(vbc_cells_build(ctx, ring, 3.0, &c), VB_OK);
    pore_on_z(&p, -20.0, 20.0, 4.5);
    CHECK_INT(vbc_pore_judge(c, &p, &v), 0);
    CHECK(!v.is_pore);
    CHECK(v.buried > 5.0 && v.buried < VBC_PORE_MIN_BURIED);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(ring);
}

int main(void)
{
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    test_walls(ctx);
    test_buried(ctx);
    test_gaps(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
