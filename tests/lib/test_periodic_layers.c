/* The per-bin reach of periodic images (core/periodic/reach.c) against the
 * one global layer: the same periodic vertices, byte for byte, from fewer
 * spheres; on an fcc unit cell, random balls in an orthorhombic and in a
 * triclinic box, and a small cluster alone in a large box (the protein in
 * vacuum, where the per-bin reach cuts most: in the rectangular box every
 * image of this small cluster is needed, the corners of its cell meet
 * all 26; in the skewed box a sixth fewer). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vorball.h"

static unsigned long long lcg_state = 12345;

static double uniform(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg_state >> 11) / 9007199254740992.0;
}

/* The bytes of the periodic vertex file of set in box. */
static char *periodic_bytes(vb_ctx *ctx, const vb_sphere_set *set, const vb_box *box, int full,
                            size_t *len, size_t *spheres, size_t *layer)
{
    vb_vertices_config cfg = {0};
    cfg.device = VB_DEVICE_REF;
    cfg.propose.threads = 2;
    vb_periodic_result res;
    vb_periodic_result_init(&res);
    res.full_layer = full;
    char *buf = NULL;
    *len = 0;
    FILE *f = open_memstream(&buf, len);
    CHECK_INT(vb_periodic_vertices_run(ctx, set, box, &cfg, vb_default_backends(), &res), VB_OK);
    CHECK_INT(vb_periodic_write(ctx, f, &res.v, 0, NULL), VB_OK);
    fclose(f);
    *spheres = res.img.set ? res.img.set->n : 0;
    *layer = res.img.layer_spheres;
    CHECK(res.v.n > 0);
    vb_periodic_result_free(&res);
    return buf;
}

static void same_bytes(vb_ctx *ctx, const char *name, const char *xyzr, const char *const *boxarg,
                       int nbox, int expect_fewer)
{
    vb_read_options ro = {0};
    vb_sphere_set *set = NULL;
    CHECK_INT(vb_spheres_read_buffer(ctx, name, xyzr, strlen(xyzr), &ro, &set), VB_OK);
    CHECK_INT(vb_spheres_validate(ctx, set, 4), VB_OK);
    vb_box box;
    CHECK_INT(vb_box_parse_args(ctx, boxarg, nbox, &box), VB_OK);
    size_t la, lb, na, nb, layer_a, layer_b;
    char *a = periodic_bytes(ctx, set, &box, 0, &la, &na, &layer_a);
    char *b = periodic_bytes(ctx, set, &box, 1, &lb, &nb, &layer_b);
    CHECK(la > 0 && la == lb && memcmp(a, b, la) == 0);
    CHECK(na <= nb);
    CHECK_INT((long)layer_a, (long)nb); /* the full layer is the global one */
    if (expect_fewer) /* a tenth fewer at least */
        CHECK(10 * na < 9 * nb);
    printf("%s: %zu spheres (per-bin reach), %zu (full layer), %zu bytes\n", name, na, nb, la);
    free(a);
    free(b);
    vb_spheres_free(set);
}

static char *balls(int n, const double lo[3], const double hi[3], double rlo, double rhi)
{
    char *s = malloc((size_t)n * 64 + 1);
    size_t w = 0;
    for (int i = 0; i < n; i++) {
        double c[3];
        for (int a = 0; a < 3; a++)
            c[a] = lo[a] + (hi[a] - lo[a]) * uniform();
        w += (size_t)sprintf(s + w, "%.3f %.3f %.3f %.2f\n", c[0], c[1], c[2],
                             rlo + (rhi - rlo) * uniform());
    }
    s[w] = '\0';
    return s;
}

int main(void)
{
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    const char fcc[] = "0.1 0.2 0.3 1.2\n2.1 2.2 0.3 1.2\n2.1 0.2 2.3 1.2\n0.1 2.2 2.3 1.2\n";
    const char *four[3] = {"4", "4", "4"};
    same_bytes(ctx, "fcc", fcc, four, 3, 0);
    const double lo[3] = {0, 0, 0}, hi[3] = {9, 8, 7};
    char *r = balls(40, lo, hi, 0.8, 1.6);
    const char *rect[3] = {"9", "8", "7"};
    same_bytes(ctx, "random", r, rect, 3, 0);
    const char *tri[9] = {"9", "0", "0", "2", "8", "0", "-1.5", "1", "7"};
    same_bytes(ctx, "triclinic", r, tri, 9, 0);
    free(r);
    /* 60 balls in a 9 A cube at the middle of a 30 A box: vacuum around. */
    const double clo[3] = {10.5, 10.5, 10.5}, chi[3] = {19.5, 19.5, 19.5};
    char *cl = balls(60, clo, chi, 1.2, 1.9);
    const char *big[3] = {"30", "30", "30"};
    same_bytes(ctx, "cluster", cl, big, 3, 0);
    const char *bigtri[9] = {"30", "0", "0", "0", "30", "0", "15", "15", "21.2132"};
    same_bytes(ctx, "cluster-triclinic", cl, bigtri, 9, 1);
    free(cl);
    vb_close(ctx);
    VB_TEST_END();
}
