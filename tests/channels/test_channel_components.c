/* Components, classification, centrelines, radii, bottlenecks, lining atoms
 * and pruning (core/discrete/channel_components.c): hand-made voxel sets with known
 * answers, then the synthetic pore and the closed shell end to end. */
#include "channel_math.h"
#include "synth.h"
#include "vb_test.h"

static uint32_t V(const vbc_grid *g, int i, int j, int k)
{
    return (uint32_t)(i + g->nx * (j + g->ny * k));
}

static vbc_grid unit_grid(int n)
{
    vbc_grid g = {n, n, n, 3, {0.0, 0.0, 0.0}, 1.0};
    return g;
}

/* A straight run of voxels along x at (., 5, 5) from i = 2 to 11 with a mouth
 * at i = 2, a diagonal segment touching it, and a separate blob: two
 * components; one atom at the origin bounds the radii. */
static void test_handmade(vb_ctx *ctx)
{
    vbc_grid g = unit_grid(16);
    vb_sphere_set *s = vb_test_spheres_alloc(1, 0);
    s->r[0] = 1.0;
    s->x[0] = 6.5;
    s->y[0] = 9.5;
    s->z[0] = 5.5;
    uint32_t v[40];
    size_t n = 0;
    /* Scrambled order: the analysis sorts. */
    for (int i = 11; i >= 2; i--)
        v[n++] = V(&g, i, 5, 5) | (i == 2 ? VBC_MOUTH_BIT : 0u);
    v[n++] = V(&g, 12, 6, 6); /* diagonal neighbour of (11,5,5): same component */
    v[n++] = V(&g, 2, 12, 12);
    v[n++] = V(&g, 3, 12, 12);
    vbc_options opt = {0.0, 0.0, 0.5, 1, NULL};
    vbc_result res;
    CHECK_INT(vbc_analyse(ctx, &g, s, v, n, &opt, &res), VB_OK);
    CHECK_INT(res.components, 2);
    CHECK_INT(res.nchannels, 2);
    CHECK_INT(res.pruned, 0);
    /* Longest first: the run, a channel (it has a mouth), 11 voxels. */
    const vbc_channel *c = &res.channels[0];
    CHECK_INT(c->kind, VBC_CHANNEL);
    CHECK_INT(c->voxels, 11);
    CHECK_INT(c->mouths, 1);
    CHECK_INT(c->npoints, 11);
    CHECK_NEAR(c->length, 9.0 + sqrt(3.0), 1e-12);
    /* It starts at the mouth (2.5, 5.5, 5.5) and ends at (12.5, 6.5, 6.5). */
    const vbc_point *p = res.points + c->first_point;
    CHECK_NEAR(p[0].x, 2.5, 1e-12);
    CHECK_NEAR(p[c->npoints - 1].x, 12.5, 1e-12);
    CHECK_NEAR(p[c->npoints - 1].z, 6.5, 1e-12);
    /* Nearest surface to (6.5, 5.5, 5.5) is 4 - 1 = 3 Å: the bottleneck. */
    CHECK_NEAR(c->bottleneck, 3.0, 1e-12);
    CHECK_NEAR(p[c->bottleneck_at].x, 6.5, 1e-12);
    CHECK_INT(p[c->bottleneck_at].atom, 0);
    CHECK_INT(c->nlining, 1);
    CHECK_INT(res.lining[c->first_lining], 0);
    /* The blob: two voxels, no mouth, a cavity of length 1, lined by the
     * only atom (the nearest atom always lines a point). */
    c = &res.channels[1];
    CHECK_INT(c->kind, VBC_CAVITY);
    CHECK_INT(c->voxels, 2);
    CHECK_NEAR(c->length, 1.0, 1e-12);
    CHECK_INT(c->nlining, 1);
    vbc_result_free(&res);

    /* Pruning: cavities dropped, then a length threshold, then a radius one. */
    opt.keep_cavities = 0;
    CHECK_INT(vbc_analyse(ctx, &g, s, v, n, &opt, &res), VB_OK);
    CHECK_INT(res.nchannels, 1);
    CHECK_INT(res.pruned, 1);
    vbc_result_free(&res);
    opt.min_length = 11.0;
    CHECK_INT(vbc_analyse(ctx, &g, s, v, n, &opt, &res), VB_OK);
    CHECK_INT(res.nchannels, 0);
    CHECK_INT(res.pruned, 2);
    vbc_result_free(&res);
    opt.min_length = 0.0;
    opt.min_radius = 3.01;
    CHECK_INT(vbc_analyse(ctx, &g, s, v, n, &opt, &res), VB_OK);
    CHECK_INT(res.nchannels, 0);
    vbc_result_free(&res);
    /* No voxels: nothing, and no allocation. */
    CHECK_INT(vbc_analyse(ctx, &g, s, v, 0, &opt, &res), VB_OK);
    CHECK_INT(res.nchannels, 0);
    CHECK(res.channels == NULL);
    vb_spheres_free(s);
}

/* Two mouths on a branched component: the centreline joins the two mouths
 * that are farthest apart along the voxels, not the longest dead end. */
static void test_mouth_to_mouth(vb_ctx *ctx)
{
    vbc_grid g = unit_grid(32);
    vb_sphere_set *s = vb_test_spheres_alloc(1, 0);
    s->r[0] = 1.0;
    uint32_t v[64];
    size_t n = 0;
    for (int i = 4; i <= 14; i++)
        v[n++] = V(&g, i, 10, 10) | ((i == 4 || i == 14) ? VBC_MOUTH_BIT : 0u);
    /* A 20-voxel dead-end branch from the middle. */
    for (int j = 11; j <= 30; j++)
        v[n++] = V(&g, 9, j, 10);
    vbc_options opt = {0.0, 0.0, 0.5, 0, NULL};
    vbc_result res;
    CHECK_INT(vbc_analyse(ctx, &g, s, v, n, &opt, &res), VB_OK);
    CHECK_INT(res.nchannels, 1);
    CHECK_INT(res.channels[0].mouths, 2);
    CHECK_NEAR(res.channels[0].length, 10.0, 1e-12);
    vbc_result_free(&res);
    vb_spheres_free(s);
}

/* Clearance through the cell list equals brute force. */
static void test_cells(vb_ctx *ctx)
{
    vb_sphere_set *s = synth_shell(300, 12.0, 1.0);
    for (size_t i = 0; i < s->n; i++)
        s->r[i] = 1.0 + 0.01 * (double)(i % 50);
    vbc_cells *c;
    CHECK_INT(vbc_cells_build(ctx, s, 4.0, &c), VB_OK);
    int bad = 0;
    for (int t = 0; t < 200; t++) {
        double p[3] = {-20.0 + 0.2 * t, 7.0 * sin(0.3 * t), 30.0 * cos(0.11 * t)};
        int32_t atom;
        double d = vbc_cells_clearance(c, p, &atom);
        double best = INFINITY;
        int32_t arg = -1;
        for (size_t i = 0; i < s->n; i++) {
            /* The same arithmetic as the cell list (pow() may differ from
             * x * x by an ulp without optimisation): this checks the search. */
            double dx = p[0] - s->x[i], dy = p[1] - s->y[i], dz = p[2] - s->z[i];
            double e = sqrt(dx * dx + dy * dy + dz * dz) - s->r[i];
            if (e < best) {
                best = e;
                arg = (int32_t)i;
            }
        }
        bad += d != best || atom != arg;
    }
    CHECK_INT(bad, 0);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

static int analyse_synth(vb_ctx *ctx, const vb_sphere_set *s, double probe, int n,
                         const vbc_options *opt, vbc_result *res, vbc_grid *g)
{
    CHECK_INT(vbc_grid_fit(ctx, s, probe, n, 3, g), VB_OK);
    size_t nv = vbc_grid_voxels(g);
    float *atoms = malloc(4 * s->n * sizeof(float));
    int32_t *labels = malloc(nv * sizeof(int32_t));
    int *rb = malloc((size_t)vbc_rb_size(g->nx, g->ny, g->nz) * sizeof(int));
    uint8_t *flags = malloc(nv);
    vbc_atoms_pack(g, s, probe, atoms);
    synth_labels(g, atoms, s->n, labels);
    vbc_masks_ref(g, atoms, s->n, labels, 3, rb, flags);
    uint32_t *list;
    size_t nl;
    CHECK_INT(vbc_flags_compact(ctx, g, flags, &list, &nl), VB_OK);
    int rc = vbc_analyse(ctx, g, s, list, nl, opt, res);
    free(list);
    free(atoms);
    free(labels);
    free(rb);
    free(flags);
    return rc;
}

/* The pore: one channel longer than 15 Å along z, mouth to mouth, bottleneck
 * near the clearance 4.4 Å, lined by all 96 atoms. */
static void test_cylinder_pore(vb_ctx *ctx)
{
    vb_sphere_set *s = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    vbc_options opt = {15.0, 0.0, 1.0, 0, NULL};
    vbc_result res;
    vbc_grid g;
    CHECK_INT(analyse_synth(ctx, s, 1.0, 64, &opt, &res, &g), VB_OK);
    CHECK_INT(res.nchannels, 1);
    CHECK(res.components > 1);
    if (res.nchannels == 1) {
        const vbc_channel *c = &res.channels[0];
        const vbc_point *p = res.points + c->first_point;
        CHECK_INT(c->kind, VBC_CHANNEL);
        CHECK(c->length > 20.0 && c->length < 26.0);
        CHECK(fabs(p[0].z - p[c->npoints - 1].z) > 20.0);
        double off = 0.0;
        for (size_t t = 0; t < c->npoints; t++)
            off = fmax(off, hypot(p[t].x, p[t].y));
        CHECK(off < 2.0 * g.h);
        CHECK_NEAR(c->bottleneck, 4.4, 2.0 * g.h);
        CHECK(fabs(p[c->bottleneck_at].z) < 9.2);
        CHECK_INT(c->nlining, 96);
    }
    vbc_result_free(&res);
    vb_spheres_free(s);
}

/* The shell: a cavity, kept only when asked for, never a channel. */
static void test_shell_cavity(vb_ctx *ctx)
{
    vb_sphere_set *s = synth_shell(240, 9.0, 1.6);
    vbc_options opt = {2.0, 0.0, 1.0, 1, NULL};
    vbc_result res;
    vbc_grid g;
    CHECK_INT(analyse_synth(ctx, s, 1.0, 48, &opt, &res, &g), VB_OK);
    size_t cav = 0, chan_inside = 0;
    for (size_t t = 0; t < res.nchannels; t++) {
        const vbc_channel *c = &res.channels[t];
        const vbc_point *p = res.points + c->first_point;
        int inside = hypot(hypot(p[0].x, p[0].y), p[0].z) < 9.0;
        cav += c->kind == VBC_CAVITY && inside;
        chan_inside += c->kind == VBC_CHANNEL && inside;
    }
    CHECK_INT(cav, 1);
    CHECK_INT(chan_inside, 0);
    vbc_result_free(&res);
    opt.keep_cavities = 0;
    CHECK_INT(analyse_synth(ctx, s, 1.0, 48, &opt, &res, &g), VB_OK);
    size_t kept_cav = 0;
    for (size_t t = 0; t < res.nchannels; t++)
        kept_cav += res.channels[t].kind == VBC_CAVITY;
    CHECK_INT(kept_cav, 0);
    vbc_result_free(&res);
    vb_spheres_free(s);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    test_handmade(ctx);
    test_mouth_to_mouth(ctx);
    test_cells(ctx);
    test_cylinder_pore(ctx);
    test_shell_cavity(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
