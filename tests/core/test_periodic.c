/* core/periodic/: boxes (vectors, lengths and angles, --box, the files'),
 * exact image decimals, the bound of the largest empty sphere and the
 * canonical translate. */
#include <math.h>
#include <string.h>

#include "input_test_util.h"
#include "vb_periodic.h"

static void boxes(vb_ctx *ctx)
{
    vb_box b;
    const char *rect[3] = {"4", "5.5", "6.25"};
    CHECK_INT(vb_box_parse_args(ctx, rect, 3, &b), VB_OK);
    CHECK(dec_is(b.ev[0], "4") && dec_is(b.ev[4], "5.5") && dec_is(b.ev[8], "6.25"));
    CHECK(dec_is(b.ev[1], "0") && dec_is(b.ev[3], "0") && b.v[8] == 6.25);
    /* Three right angles: the lengths exactly. */
    const char *right[6] = {"4", "5.5", "6.25", "90", "90.0", "90"};
    vb_box r;
    CHECK_INT(vb_box_parse_args(ctx, right, 6, &r), VB_OK);
    for (int k = 0; k < 9; k++)
        CHECK(vb_decimal_cmp(r.ev[k], b.ev[k]) == 0 && r.v[k] == b.v[k]);
    /* Other angles: a along x, b in xy, components to 6 decimals. */
    const char *tri[6] = {"10", "10", "10", "90", "90", "120"};
    CHECK_INT(vb_box_parse_args(ctx, tri, 6, &r), VB_OK);
    CHECK(dec_is(r.ev[3], "-5") && dec_is(r.ev[4], "8.660254") && dec_is(r.ev[8], "10"));
    /* Flat boxes, decided exactly: E120. */
    const char *flat[9] = {"1", "2", "3", "2", "4", "6.000", "1", "0", "0"};
    CHECK_INT(vb_box_parse_args(ctx, flat, 9, &r), VB_EINPUT_BOX);
    const char *nearly[9] = {"1", "2", "3", "2", "4", "6.000000001", "1", "0", "0"};
    CHECK_INT(vb_box_parse_args(ctx, nearly, 9, &r), VB_OK);
    CHECK_INT(vb_box_parse_args(ctx, rect, 2, &r), VB_EINPUT_BOX);
    const char *bad[6] = {"4", "4", "4", "90", "180", "90"};
    CHECK_INT(vb_box_parse_args(ctx, bad, 6, &r), VB_EINPUT_BOX);
}

static void file_boxes(vb_ctx *ctx)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.keep_water = 1;
    const char gro[] = "t\n 2\n    1SOL     OW    1   0.126   0.163   0.112\n"
                       "    1SOL    HW1    2   0.190   0.094   0.093\n"
                       "   0.8   0.75   0.7   0   0   0.1   0   0.05  -0.05\n";
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_read_buffer(ctx, "t.gro", gro, strlen(gro), &ro, &s), VB_OK);
    CHECK(s && s->box);
    if (s && s->box) {
        /* nm to A; v1(x) v2(y) v3(z) v1(y) v1(z) v2(x) v2(z) v3(x) v3(y). */
        CHECK(dec_is(s->box->ev[0], "8") && dec_is(s->box->ev[4], "7.5"));
        CHECK(dec_is(s->box->ev[3], "1") && dec_is(s->box->ev[6], "0.5"));
        CHECK(dec_is(s->box->ev[7], "-0.5") && dec_is(s->box->ev[8], "7"));
    }
    vb_spheres_free(s);
    const char nobox[] = "t\n 1\n    1SOL     OW    1   0.126   0.163   0.112\n   0 0 0\n";
    CHECK_INT(vb_spheres_read_buffer(ctx, "n.gro", nobox, strlen(nobox), &ro, &s), VB_OK);
    CHECK(s && !s->box);
    vb_spheres_free(s);
    const char pdb[] =
        "CRYST1   40.960   18.650   22.520  90.00  90.00  90.00 P 1           1\n"
        "ATOM      1  N   THR A   1      17.047  14.099   3.625  1.00 13.79           N\n";
    CHECK_INT(vb_spheres_read_buffer(ctx, "c.pdb", pdb, strlen(pdb), &ro, &s), VB_OK);
    CHECK(s && s->box && dec_is(s->box->ev[0], "40.96") && dec_is(s->box->ev[8], "22.52"));
    vb_spheres_free(s);
    /* The NMR convention 1 1 1: no box. */
    const char nmr[] =
        "CRYST1    1.000    1.000    1.000  90.00  90.00  90.00 P 1           1\n"
        "ATOM      1  N   THR A   1      17.047  14.099   3.625  1.00 13.79           N\n";
    CHECK_INT(vb_spheres_read_buffer(ctx, "n.pdb", nmr, strlen(nmr), &ro, &s), VB_OK);
    CHECK(s && !s->box);
    vb_spheres_free(s);
}

/* The fcc unit cell of the pipeline test (a = 4, radius 1.2): its largest
 * empty spheres are the octahedral holes, t = 2 - 1.2 = 0.8 exactly; the
 * bound must hold it and stay near it. Images are exact decimals. */
static void images(vb_ctx *ctx)
{
    const char xyzr[] = "0.1 0.2 0.3 1.2\n2.1 2.2 0.3 1.2\n2.1 0.2 2.3 1.2\n0.1 2.2 2.3 1.2\n";
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_read_buffer(ctx, "fcc.xyzr", xyzr, strlen(xyzr), &ro, &s), VB_OK);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    const char *four[3] = {"4", "4", "4"};
    vb_box b;
    CHECK_INT(vb_box_parse_args(ctx, four, 3, &b), VB_OK);
    vb_periodic_images img;
    CHECK_INT(vb_periodic_images_build(ctx, s, &b, &img), VB_OK);
    CHECK(img.rho >= 0.8 && img.rho < 1.3);
    CHECK_NEAR(img.reach, 2.0 * (img.rho + 1.2), 1e-6);
    CHECK_INT((long)img.n0, 4);
    CHECK(img.set->n > 4 && img.set->n < 4 * 125);
    size_t found = 0;
    for (size_t k = 4; k < img.set->n; k++) {
        uint32_t a = img.atom[k];
        const int16_t *sh = img.shift[k];
        CHECK(sh[0] || sh[1] || sh[2]);
        /* Every image within the reach of some atom's box range. */
        if (a == 0 && sh[0] == -1 && sh[1] == 1 && sh[2] == 0) {
            found++;
            CHECK(dec_is(img.set->ex[k], "-3.9") && dec_is(img.set->ey[k], "4.2") &&
                  dec_is(img.set->ez[k], "0.3"));
            CHECK(img.set->x[k] == -3.9 && img.set->y[k] == 4.2);
        }
    }
    CHECK_INT((long)found, 1);
    vb_periodic_images_free(&img);
    /* A flat box for its atoms: E135. */
    const char *flat[3] = {"40", "40", "0.5"};
    CHECK_INT(vb_box_parse_args(ctx, flat, 3, &b), VB_OK);
    CHECK_INT(vb_periodic_images_build(ctx, s, &b, &img), VB_EINPUT_BOX_SMALL);
    vb_spheres_free(s);
}

static void canonical(void)
{
    vb_periodic_member scratch[8];
    /* Lowest id 0 twice: the translate putting either at 0. */
    const vb_periodic_member a[4] = {{0, {0, 0, 0}}, {0, {1, 0, 0}}, {1, {0, 0, 0}}, {2, {1, 1, 0}}};
    const vb_periodic_member b[4] = {{0, {-1, 0, 0}}, {0, {0, 0, 0}}, {1, {-1, 0, 0}}, {2, {0, 1, 0}}};
    CHECK(!vb_periodic_is_canonical(a, 4, scratch));
    CHECK(vb_periodic_is_canonical(b, 4, scratch));
    const vb_periodic_member c[4] = {{0, {0, 0, 1}}, {1, {0, 0, 1}}, {2, {0, 0, 1}}, {3, {0, 0, 1}}};
    const vb_periodic_member e[4] = {{0, {0, 0, 0}}, {1, {0, 0, 0}}, {2, {0, 0, 0}}, {3, {0, 0, 0}}};
    CHECK(!vb_periodic_is_canonical(c, 4, scratch));
    CHECK(vb_periodic_is_canonical(e, 4, scratch));
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return 1;
    boxes(ctx);
    file_boxes(ctx);
    images(ctx);
    canonical();
    vb_close(ctx);
    VB_TEST_END();
}
