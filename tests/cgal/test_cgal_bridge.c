/* The CGAL bridge on small inline sets whose Voronoi vertices are known by
 * hand, and the comparison's every category of difference. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cgal.h"
#include "vb_test.h"
#include "vb_test_spheres.h"

/* A sphere set from decimals given as mantissa and a shared exponent. */
static vb_sphere_set *make_set(size_t n, const long (*c)[4], int exp10)
{
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    double scale = pow(10.0, exp10);
    for (size_t i = 0; i < n; i++) {
        vb_decimal *d[4] = {&s->ex[i], &s->ey[i], &s->ez[i], &s->er[i]};
        double *f[4] = {&s->x[i], &s->y[i], &s->z[i], &s->r[i]};
        for (int k = 0; k < 4; k++) {
            d[k]->mant = c[i][k];
            d[k]->exp10 = exp10;
            *f[k] = (double)c[i][k] * scale;
        }
    }
    return s;
}

static size_t degree(const vb_vertex_list *v, size_t k)
{
    return v->start[k + 1] - v->start[k];
}

/* The unit cube's corners, radius 0.5: one vertex of degree 8 at the centre. */
static void test_cube(vb_ctx *ctx)
{
    long c[8][4];
    for (int i = 0; i < 8; i++) {
        c[i][0] = (i & 1) * 10;
        c[i][1] = ((i >> 1) & 1) * 10;
        c[i][2] = ((i >> 2) & 1) * 10;
        c[i][3] = 5;
    }
    vb_sphere_set *s = make_set(8, (const long(*)[4])c, -1);
    vb_cgal_diagram *d = NULL;
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_VORONOI, &d), VB_OK);
    CHECK_INT(vb_cgal_size(d), 1);
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    CHECK_INT(vb_cgal_to_list(ctx, d, &v), VB_OK);
    CHECK_INT(degree(&v, 0), 8);
    CHECK(v.x[0] == 0.5 && v.y[0] == 0.5 && v.z[0] == 0.5);
    CHECK_NEAR(v.t[0], sqrt(0.75) - 0.5, 1e-16);
    char *x, *y, *z;
    CHECK_INT(vb_cgal_exact_point(ctx, d, 0, &x, &y, &z), VB_OK);
    CHECK_STR(x, "1/2");
    CHECK_STR(z, "1/2");
    free(x);
    free(y);
    free(z);

    /* vorball's list equal to CGAL's: identical. */
    vb_cgal_diff diff;
    CHECK_INT(vb_cgal_compare(ctx, d, s, &v, NULL, 0, NULL, &diff), VB_OK);
    CHECK(vb_cgal_identical(&diff));
    CHECK_INT(diff.matched, 1);

    /* The vertex as two quadruples (Voronota style): split unless allowed. */
    vb_vertex_list q;
    vb_vertex_list_init(&q);
    uint32_t a[4] = {0, 1, 2, 4}, b[4] = {3, 5, 6, 7};
    vb_vertex_list_push(&q, a, 4, v.x[0], v.y[0], v.z[0], v.t[0], 0, VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(&q, b, 4, v.x[0], v.y[0], v.z[0], v.t[0], 0, VB_VERTEX_CERTIFIED);
    CHECK_INT(vb_cgal_compare(ctx, d, s, &q, NULL, VB_CGAL_ALLOW_SPLIT, NULL, &diff), VB_OK);
    CHECK(vb_cgal_identical(&diff));
    CHECK_INT(vb_cgal_compare(ctx, d, s, &q, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.split, 1);
    CHECK(!vb_cgal_identical(&diff));

    /* Voronota's fan {0,1,2,j}: {0,1,2,3} is a face of the cube and fixes no
     * point alone; it joins the vertex printed at its coordinates. */
    vb_vertex_list fan;
    vb_vertex_list_init(&fan);
    for (uint32_t j = 3; j < 8; j++) {
        uint32_t f[4] = {0, 1, 2, j};
        vb_vertex_list_push(&fan, f, 4, v.x[0], v.y[0], v.z[0], v.t[0], 0, VB_VERTEX_CERTIFIED);
    }
    CHECK_INT(vb_cgal_compare(ctx, d, s, &fan, NULL, VB_CGAL_ALLOW_SPLIT, NULL, &diff), VB_OK);
    CHECK(vb_cgal_identical(&diff));
    CHECK_INT(diff.matched, 1);
    CHECK_INT(vb_cgal_compare(ctx, d, s, &fan, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.invalid, 1);
    CHECK_INT(diff.split, 1);
    /* Printed elsewhere, the face line cannot be placed. */
    fan.x[0] = 0.25;
    CHECK_INT(vb_cgal_compare(ctx, d, s, &fan, NULL, VB_CGAL_ALLOW_SPLIT, NULL, &diff), VB_OK);
    CHECK_INT(diff.invalid, 1);
    vb_vertex_list_free(&fan);

    /* Only one quadruple: same exact point, fewer members. */
    q.n = 1;
    CHECK_INT(vb_cgal_compare(ctx, d, s, &q, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.membership, 1);
    CHECK_INT(diff.matched, 0);

    /* One ulp off in y, and a face of the cube (coplanar ids) as a vertex. */
    vb_vertex_list_free(&q);
    vb_vertex_list_push(&q, &v.ids[0], 8, v.x[0], nextafter(v.y[0], 1.0), v.z[0], v.t[0], 0,
                        VB_VERTEX_CERTIFIED);
    uint32_t face[4] = {0, 1, 2, 3};
    vb_vertex_list_push(&q, face, 4, 0.5, 0.5, 0.0, 0.1, 0, VB_VERTEX_CERTIFIED);
    char buf[1024] = "";
    FILE *rep = fmemopen(buf, sizeof buf, "w");
    CHECK_INT(vb_cgal_compare(ctx, d, s, &q, NULL, 0, rep, &diff), VB_OK);
    fclose(rep);
    CHECK_INT(diff.rounding, 1);
    CHECK_INT(diff.invalid, 1);
    CHECK(strstr(buf, "rounding\t0,1,2,3,4,5,6,7\ty") != NULL);
    CHECK(strstr(buf, "invalid\t0,1,2,3\tcentres do not span 3D") != NULL);

    /* Nothing from vorball: one missing. */
    vb_vertex_list_free(&q);
    CHECK_INT(vb_cgal_compare(ctx, d, s, &q, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.missing, 1);
    vb_vertex_list_free(&v);
    vb_cgal_free(d);
    vb_spheres_free(s);
}

/* 3 x 3 x 3 simple cubic block, spacing 2: eight degree-8 vertices at the
 * odd points; a ninth vertex from a wrong lattice point is extra. */
static void test_lattice(vb_ctx *ctx)
{
    long c[27][4];
    for (int i = 0; i < 27; i++) {
        c[i][0] = 2 * (i % 3);
        c[i][1] = 2 * ((i / 3) % 3);
        c[i][2] = 2 * (i / 9);
        c[i][3] = 1;
    }
    vb_sphere_set *s = make_set(27, (const long(*)[4])c, 0);
    vb_cgal_diagram *d = NULL;
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_VORONOI, &d), VB_OK);
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    CHECK_INT(vb_cgal_to_list(ctx, d, &v), VB_OK);
    CHECK_INT(v.n, 8);
    int odd = 1;
    for (size_t k = 0; k < v.n; k++)
        odd &= degree(&v, k) == 8 && fabs(fmod(v.x[k], 2.0)) == 1.0 &&
                fabs(fmod(v.z[k], 2.0)) == 1.0;
    CHECK(odd);
    /* The same set through the power diagram with equal weights. */
    vb_cgal_diagram *p = NULL;
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_POWER, &p), VB_OK);
    vb_cgal_diff diff;
    CHECK_INT(vb_cgal_compare(ctx, p, s, &v, NULL, 0, NULL, &diff), VB_OK);
    CHECK(vb_cgal_identical(&diff));
    CHECK_INT(diff.matched, 8);
    /* Spheres 0, 1, 3, 9 (a corner tetrahedron) meet at (1,1,1): a second
     * line for that vertex, whose members it does not change. */
    uint32_t corner[4] = {0, 1, 3, 9};
    vb_vertex_list_push(&v, corner, 4, 1, 1, 1, 0, 0, VB_VERTEX_CERTIFIED);
    CHECK_INT(vb_cgal_compare(ctx, d, s, &v, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.extra, 0);
    CHECK_INT(diff.membership, 0);
    CHECK_INT(diff.split, 1);
    uint32_t skew[4] = {0, 1, 3, 18}; /* circumcentre (1,1,2): not a vertex */
    v.n = 8;
    v.nids = v.start[8];
    vb_vertex_list_push(&v, skew, 4, 1, 1, 1, 0, 0, VB_VERTEX_CERTIFIED);
    CHECK_INT(vb_cgal_compare(ctx, d, s, &v, NULL, 0, NULL, &diff), VB_OK);
    CHECK_INT(diff.extra, 1);
    vb_vertex_list_free(&v);
    vb_cgal_free(p);
    vb_cgal_free(d);
    vb_spheres_free(s);
}

/* Unequal radii: refused for Voronoi; the power vertex of
 * (0,0,0) r1, (2,0,0) r1, (0,2,0) r2, (0,0,2) r1 is (1, 1/4, 1). */
static void test_power(vb_ctx *ctx)
{
    const long c[4][4] = {{0, 0, 0, 1}, {2, 0, 0, 1}, {0, 2, 0, 2}, {0, 0, 2, 1}};
    vb_sphere_set *s = make_set(4, c, 0);
    vb_cgal_diagram *d = NULL;
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_VORONOI, &d), VB_EINPUT);
    CHECK(d == NULL);
    CHECK(strstr(vb_errmsg(ctx), "radii differ") != NULL);
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_POWER, &d), VB_OK);
    CHECK_INT(vb_cgal_size(d), 1);
    char *x, *y, *z;
    CHECK_INT(vb_cgal_exact_point(ctx, d, 0, &x, &y, &z), VB_OK);
    CHECK_STR(x, "1");
    CHECK_STR(y, "1/4");
    CHECK_STR(z, "1");
    free(x);
    free(y);
    free(z);
    /* Only the ids count with unequal radii. */
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    uint32_t ids[4] = {3, 2, 1, 0};
    vb_vertex_list_push(&v, ids, 4, 0.9, 0.3, 0.9, 0.5, 0, VB_VERTEX_CERTIFIED);
    vb_cgal_diff diff;
    CHECK_INT(vb_cgal_compare(ctx, d, s, &v, NULL, 0, NULL, &diff), VB_OK);
    CHECK(vb_cgal_identical(&diff));
    vb_vertex_list_free(&v);
    vb_cgal_free(d);
    vb_spheres_free(s);
}

/* Coplanar centres: no vertices, not an error. */
static void test_flat(vb_ctx *ctx)
{
    const long c[5][4] = {{0, 0, 0, 1}, {3, 0, 0, 1}, {0, 3, 0, 1}, {3, 3, 0, 1}, {1, 2, 0, 1}};
    vb_sphere_set *s = make_set(5, c, 0);
    vb_cgal_diagram *d = NULL;
    CHECK_INT(vb_cgal_build(ctx, s, VB_CGAL_VORONOI, &d), VB_OK);
    CHECK_INT(vb_cgal_size(d), 0);
    vb_cgal_free(d);
    vb_spheres_free(s);
}

int main(void)
{
    vb_ctx *ctx = NULL;
    vb_config cfg = {0};
    cfg.verbosity = 0;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    test_cube(ctx);
    test_lattice(ctx);
    test_power(ctx);
    test_flat(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
