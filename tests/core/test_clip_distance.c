/* vbs_clip_distance: the proven bounds of core/cells/sampler_cull.c, D 128 M^3
 * for equal radii (written in any form: 1.5 and 1.50 are equal) and
 * D 3e4 M^7 otherwise, with D the bounding-box diagonal plus twice the
 * largest radius and M = D / q for the finest decimal unit q. */
#include <math.h>
#include <stdlib.h>

#include "vb_test.h"
#include "vbs_internal.h"

static double clip_of(vb_ctx *ctx, const char *text)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.format = VB_FMT_XYZR;
    vb_sphere_set *s = NULL;
    if (vb_spheres_read_buffer(ctx, "test", text, strlen(text), &ro, &s) != VB_OK)
        return -1.0;
    double L = vbs_clip_distance(s);
    vb_spheres_free(s);
    return L;
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return 1;
    /* Centres (0,0,0) and (3,4,0.01): diagonal ~5; radius 1.5 (also
     * written 1.50): D = diagonal + 3, q = 0.01. */
    double D = sqrt(25.0001) + 3.0, M = D / 0.01;
    double equal = clip_of(ctx, "0 0 0 1.5\n3 4 0.01 1.50\n");
    CHECK(fabs(equal / (D * 128.0 * M * M * M) - 1.0) < 1e-12);
    /* Radii 1.5 and 1.25: the same D and q. */
    double unequal = clip_of(ctx, "0 0 0 1.5\n3 4 0.01 1.25\n");
    CHECK(fabs(unequal / (D * 3e4 * pow(M, 7.0)) - 1.0) < 1e-12);
    /* A finer unit raises the bound; huge ones are capped at 1e200. */
    CHECK(clip_of(ctx, "0 0 0 1.5\n3 4 0.001 1.25\n") > unequal);
    CHECK(clip_of(ctx, "0 0 0 1.5\n3 4 0.000000000000000000000000001 1.25\n") == 1e200);
    vb_close(ctx);
    VB_TEST_END();
}
