/* The first radius of a cell's near list (vb_cover_prepare's env.near,
 * core/cells/cover_tree.c) on simple cubic lattices of k^3 spheres (spacing
 * 3.35, radius 1.68): the list (radius near + 2 R_max) must reach the
 * lattice's vertex neighbours at sqrt(3) spacing whatever k, in particular
 * where the 2 x 2 x 2 blocks fall exactly into the Morton leaves (k = 8,
 * 16: a leaf spans one spacing, and the leaves alone gave 0.6 spacings,
 * which left every cell's corners to fetches). */
#include <math.h>
#include <stdint.h>

#include "vb_cover.h"
#include "vb_test.h"
#include "vb_test_spheres.h"

static double near_of(vb_ctx *ctx, int k, double *rmax)
{
    vb_sphere_set *s = vb_test_spheres_alloc((size_t)k * k * k, 1);
    size_t n = 0;
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++)
            for (int c = 0; c < k; c++) {
                /* thousandths: 10.25 + 3.35 a, -3.7 + 3.35 b, 0.125 + 3.35 c */
                int64_t m[3] = {10250 + 3350 * a, -3700 + 3350 * b, 125 + 3350 * c};
                double *col[3] = {s->x, s->y, s->z};
                vb_decimal *dec[3] = {s->ex, s->ey, s->ez};
                for (int d = 0; d < 3; d++) {
                    col[d][n] = (double)m[d] / 1000.0;
                    dec[d][n] = (vb_decimal){m[d], -3};
                }
                s->r[n] = 1.68;
                s->er[n++] = (vb_decimal){168, -2};
            }
    vb_cover_tree *tree = NULL;
    vbq_env env;
    double near = -1.0;
    if (vb_spheres_validate(ctx, s, 4) == VB_OK && vb_cover_prepare(ctx, s, NULL, &tree, &env) == VB_OK) {
        near = env.near;
        *rmax = env.rmax_all;
    }
    vb_cover_tree_free(tree);
    vb_spheres_free(s);
    return near;
}

int main(void)
{
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    int ks[4] = {8, 10, 14, 16};
    for (int t = 0; t < 4; t++) {
        double rmax = 0.0, near = near_of(ctx, ks[t], &rmax);
        CHECK(near > 0.0);
        CHECK(near + 2.0 * rmax > sqrt(3.0) * 3.35);
    }
    /* 16^3: the parents span three spacings, the guess is 0.3 of that */
    double rmax = 0.0;
    CHECK(fabs(near_of(ctx, 16, &rmax) - 0.3 * 3.0 * 3.35) < 1e-9);
    /* 14^3: the leaves span three spacings already (0.6 of that) */
    CHECK(fabs(near_of(ctx, 14, &rmax) - 0.6 * 3.0 * 3.35) < 1e-9);
    vb_close(ctx);
    VB_TEST_END();
}
