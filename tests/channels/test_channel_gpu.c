/* The OpenCL pipeline (gpu/channels.cl after Facet-JFA or JFA+1) against the C
 * reference of the masks fed with the same labels: identical flag bytes and
 * the same channel voxel list, on the synthetic pore and the closed shell, in
 * 3D and in 2D. Runs on whatever device "auto" picks (PoCL in CI). */
#include "channel_math.h"
#include "synth.h"
#include "vb_test.h"
#include "vbc_channel_gpu.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The components of the listed voxels by a flood fill over the dense grid
 * (26-connected), each labelled by its smallest voxel index: the answer
 * the device's labels (vbc_cc_* kernels) must give. Returns how many. */
static size_t flood_labels(const vbc_grid *g, const uint32_t *vox, size_t n, uint32_t *label)
{
    size_t nv = vbc_grid_voxels(g), ncomp = 0;
    uint32_t *grid = malloc(nv * sizeof *grid), *stack = malloc(n * sizeof *stack);
    uint32_t *sorted = malloc(n * sizeof *sorted);
    for (size_t v = 0; v < nv; v++)
        grid[v] = UINT32_MAX - 1; /* off the list */
    for (size_t t = 0; t < n; t++) {
        sorted[t] = vox[t] & ~VBC_MOUTH_BIT;
        grid[sorted[t]] = UINT32_MAX; /* listed, not reached */
    }
    qsort(sorted, n, sizeof *sorted, cmp_u32);
    for (size_t t = 0; t < n; t++) { /* ascending: the first reached is the smallest */
        uint32_t root = sorted[t];
        if (grid[root] != UINT32_MAX)
            continue;
        ncomp++;
        size_t top = 0;
        grid[root] = root;
        stack[top++] = root;
        while (top > 0) {
            uint32_t v = stack[--top];
            int i = (int)(v % (uint32_t)g->nx), j = (int)((v / (uint32_t)g->nx) % (uint32_t)g->ny);
            int k = (int)(v / ((uint32_t)g->nx * (uint32_t)g->ny));
            for (int d = 0; d < 27; d++) {
                int ii = i + d % 3 - 1, jj = j + (d / 3) % 3 - 1, kk = k + d / 9 - 1;
                if (ii < 0 || jj < 0 || kk < 0 || ii >= g->nx || jj >= g->ny || kk >= g->nz)
                    continue;
                size_t w = (size_t)ii + (size_t)g->nx * ((size_t)jj + (size_t)g->ny * (size_t)kk);
                if (grid[w] == UINT32_MAX) {
                    grid[w] = root;
                    stack[top++] = (uint32_t)w;
                }
            }
        }
    }
    for (size_t t = 0; t < n; t++)
        label[t] = grid[vox[t] & ~VBC_MOUTH_BIT];
    free(grid);
    free(stack);
    free(sorted);
    return ncomp;
}

/* The device's component labels (forced on, see main) against the flood
 * fill; the analysis given them against the one whose union-find finds
 * them, table values equal; labels spoiled on one voxel are caught by the
 * host's checks (the union-find decides, the same result). Returns the
 * number of components. */
static size_t compare_components(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s,
                                 vbc_frame_out *fo)
{
    CHECK(fo->comp != NULL);
    if (!fo->comp || fo->nvoxels == 0)
        return 0;
    uint32_t *want = malloc(fo->nvoxels * sizeof *want);
    size_t ncomp = flood_labels(g, fo->voxels, fo->nvoxels, want), bad = 0;
    for (size_t t = 0; t < fo->nvoxels; t++)
        bad += want[t] != fo->comp[t];
    CHECK_INT(bad, 0);
    vbc_options opt = {2.0, 0.0, 1.0, 1, NULL};
    vbc_result r0, r1, r2;
    CHECK_INT(vbc_analyse(ctx, g, s, fo->voxels, fo->nvoxels, &opt, &r0), VB_OK);
    CHECK_INT(vbc_analyse_given(ctx, g, s, fo->voxels, NULL, fo->comp, fo->nvoxels, &opt, &r1),
              VB_OK);
    CHECK_INT(r0.device_components, 0);
    CHECK_INT(r1.device_components, 1);
    /* One voxel of the largest label's component given another label. */
    size_t spoil = 0;
    for (size_t t = 1; t < fo->nvoxels; t++)
        if (want[t] != want[0]) {
            spoil = t;
            break;
        }
    fo->comp[spoil] = want[spoil] == want[0] ? want[spoil] + 1 : want[0];
    CHECK_INT(vbc_analyse_given(ctx, g, s, fo->voxels, NULL, fo->comp, fo->nvoxels, &opt, &r2),
              VB_OK);
    CHECK_INT(r2.device_components, 0);
    fo->comp[spoil] = want[spoil];
    const vbc_result *r[2] = {&r1, &r2};
    for (int k = 0; k < 2; k++) {
        CHECK_INT(r[k]->components, r0.components);
        CHECK_INT(r[k]->components, ncomp);
        CHECK_INT(r[k]->pruned, r0.pruned);
        CHECK_INT(r[k]->nchannels, r0.nchannels);
        size_t np = 0, nl = 0, diff = 0;
        for (size_t c = 0; c < r0.nchannels && r[k]->nchannels == r0.nchannels; c++) {
            const vbc_channel *a = &r0.channels[c], *b = &r[k]->channels[c];
            diff += a->kind != b->kind || a->through != b->through || a->voxels != b->voxels ||
                    a->mouths != b->mouths || a->length != b->length ||
                    a->bottleneck != b->bottleneck || a->bottleneck_at != b->bottleneck_at ||
                    a->first_point != b->first_point || a->npoints != b->npoints ||
                    a->first_lining != b->first_lining || a->nlining != b->nlining;
            np += a->npoints;
            nl = a->first_lining + a->nlining > nl ? a->first_lining + a->nlining : nl;
        }
        CHECK_INT(diff, 0);
        for (size_t t = 0; t < np && r[k]->nchannels == r0.nchannels; t++) {
            const vbc_point *a = &r0.points[t], *b = &r[k]->points[t];
            diff += a->x != b->x || a->y != b->y || a->z != b->z || a->r != b->r || a->atom != b->atom;
        }
        for (size_t t = 0; t < nl && r[k]->nchannels == r0.nchannels; t++)
            diff += r0.lining[t] != r[k]->lining[t];
        CHECK_INT(diff, 0);
        CHECK(r0.nchannels == 0 || np > 0);
    }
    vbc_result_free(&r0);
    vbc_result_free(&r1);
    vbc_result_free(&r2);
    free(want);
    return ncomp;
}

static void compare(vb_ctx *ctx, vbc_gpu *gp, const vb_sphere_set *s, double probe, int n, int dim)
{
    vbc_grid g;
    CHECK_INT(vbc_grid_fit(ctx, s, probe, n, dim, &g), VB_OK);
    size_t nv = vbc_grid_voxels(&g);
    float *atoms = malloc(4 * s->n * sizeof(float));
    vbc_atoms_pack(&g, s, probe, atoms);
    vbc_frame_out fo;
    int rc = vbc_gpu_frame(ctx, gp, &g, atoms, s->n, probe, VBC_WANT_FLAGS | VBC_WANT_LABELS, &fo);
    CHECK_INT(rc, VB_OK);
    if (rc != VB_OK) {
        fprintf(stderr, "%s\n", vb_errmsg(ctx));
        free(atoms);
        return;
    }
    uint8_t *flags = malloc(nv);
    int *rb = malloc((size_t)vbc_rb_size(g.nx, g.ny, g.nz) * sizeof(int));
    vbc_masks_ref(&g, atoms, s->n, (const int32_t *)fo.labels, dim == 3 ? 3 : 2, rb, flags);
    size_t diff = 0;
    for (size_t v = 0; v < nv; v++)
        diff += flags[v] != fo.flags[v];
    CHECK_INT(diff, 0);
    uint32_t *list;
    size_t nl;
    CHECK_INT(vbc_flags_compact(ctx, &g, flags, &list, &nl), VB_OK);
    CHECK(nl > 0);
    CHECK_INT(fo.nvoxels, nl);
    if (fo.nvoxels == nl && nl > 0) {
        /* Sort a copy: fo.clearance stays parallel to fo.voxels. */
        uint32_t *dev = malloc(nl * sizeof *dev);
        memcpy(dev, fo.voxels, nl * sizeof *dev);
        qsort(dev, nl, sizeof *dev, cmp_u32);
        qsort(list, nl, sizeof *list, cmp_u32);
        CHECK(memcmp(list, dev, nl * sizeof *list) == 0);
        free(dev);
    }
    /* The labels are a Voronoi diagram of the atoms: a voxel holding an atom
     * centre is labelled with an atom at most a voxel farther away. */
    size_t far = 0;
    for (size_t a = 0; a < s->n; a++) {
        int i = (int)atoms[4 * a], j = (int)atoms[4 * a + 1], k = dim == 3 ? (int)atoms[4 * a + 2] : 0;
        uint32_t l = fo.labels[i + (size_t)g.nx * (j + (size_t)g.ny * k)];
        double d = sqrt(pow(atoms[4 * l] - atoms[4 * a], 2) + pow(atoms[4 * l + 1] - atoms[4 * a + 1], 2) +
                        (dim == 3 ? pow(atoms[4 * l + 2] - atoms[4 * a + 2], 2) : 0.0));
        far += l >= s->n || d > 1.8;
    }
    CHECK_INT(far, 0);
    size_t ncomp = compare_components(ctx, &g, s, &fo);
    fprintf(stderr, "%zu atoms, grid %d^%d: %zu channel voxels in %zu components\n", s->n, n, dim,
            fo.nvoxels, ncomp);
    CHECK(ncomp >= 1);
    /* Device clearances (forced on, see main) match the host's cell list to
     * float precision, and the analysis steered by them finds the same
     * channels as the one computing its own. */
    CHECK(fo.clearance != NULL);
    if (fo.clearance) {
        vbc_cells *cells;
        CHECK_INT(vbc_cells_build(ctx, s, 3.0, &cells), VB_OK);
        double worst = 0.0;
        for (size_t t = 0; t < fo.nvoxels; t++) {
            uint32_t v = fo.voxels[t] & ~VBC_MOUTH_BIT;
            double p[3] = {g.origin[0] + (v % (uint32_t)g.nx + 0.5) * g.h,
                           g.origin[1] + ((v / (uint32_t)g.nx) % (uint32_t)g.ny + 0.5) * g.h,
                           g.origin[2] + (v / ((uint32_t)g.nx * (uint32_t)g.ny) + 0.5) * g.h};
            int32_t atom;
            worst = fmax(worst, fabs(vbc_cells_clearance(cells, p, &atom) - fo.clearance[t]));
        }
        CHECK(worst < 1e-3);
        vbc_cells_free(cells);
        vbc_options opt = {2.0, 0.0, 1.0, 1, NULL};
        vbc_result r1, r2;
        CHECK_INT(vbc_analyse(ctx, &g, s, fo.voxels, fo.nvoxels, &opt, &r1), VB_OK);
        CHECK_INT(vbc_analyse_clear(ctx, &g, s, fo.voxels, fo.clearance, fo.nvoxels, &opt, &r2), VB_OK);
        CHECK_INT(r1.nchannels, r2.nchannels);
        if (r1.nchannels > 0 && r1.nchannels == r2.nchannels) {
            CHECK_NEAR(r1.channels[0].length, r2.channels[0].length, 2.0 * g.h);
            CHECK_NEAR(r1.channels[0].bottleneck, r2.channels[0].bottleneck, 1e-3 + g.h);
        }
        vbc_result_free(&r1);
        vbc_result_free(&r2);
    }
    free(list);
    free(rb);
    free(flags);
    free(atoms);
    vbc_frame_out_free(&fo);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vbg_runtime *rt = NULL;
    int rc = vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt);
    CHECK_INT(rc, VB_OK);
    if (rc != VB_OK) {
        fprintf(stderr, "no OpenCL device: %s\n", vb_errmsg(ctx));
        vb_close(ctx);
        VB_TEST_END();
    }
    vb_sphere_set *cyl = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    vb_sphere_set *shell = synth_shell(240, 9.0, 1.6);
    vb_sphere_set *flat = synth_cylinder(1, 12, 6.0, 1.6, 2.6);
    /* The default engine first (it takes the larger cases), then two others. */
    vbj_variant variants[3] = {VBJ_EXACT, VBJ_FACET, VBJ_JFA1};
    for (int t = 0; t < 3; t++) {
        vbc_gpu *gp = NULL;
        rc = vbc_gpu_open(ctx, rt, variants[t], &gp);
        CHECK_INT(rc, VB_OK);
        if (rc != VB_OK) {
            fprintf(stderr, "%s\n", vb_errmsg(ctx));
            break;
        }
        vbc_gpu_set_device_clearance(gp, 1);
        vbc_gpu_set_device_graph(gp, 1);
        compare(ctx, gp, shell, 1.0, 32, 3);
        /* The larger cases once: they test the masks, not the JFA variant. */
        if (t == 0) {
            compare(ctx, gp, cyl, 1.0, 64, 3);
            /* 2D: the disks of the z = 0 plane (the kernels ignore z). */
            compare(ctx, gp, flat, 1.0, 128, 2);
        }
        /* A grid side that is no power of two is refused. */
        vbc_grid g;
        CHECK_INT(vbc_grid_fit(ctx, cyl, 1.0, 48, 3, &g), VB_OK);
        float a4[4] = {1, 1, 1, 1};
        vbc_frame_out fo;
        CHECK_INT(vbc_gpu_frame(ctx, gp, &g, a4, 1, 1.0, 0, &fo), VB_EMISUSE);
        vbc_gpu_close(gp);
    }
    vb_spheres_free(cyl);
    vb_spheres_free(shell);
    vb_spheres_free(flat);
    vbg_runtime_close(rt);
    vb_close(ctx);
    VB_TEST_END();
}
