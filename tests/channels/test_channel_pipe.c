/* The channel frame pipeline's reference backend against OpenCL (PoCL in CI):
 * the same labels, flag bytes and channel voxel set, hence the same analysis,
 * for Facet-JFA and JFA+1, in 3D and 2D; and an OpenCL failure injected in the
 * middle of a run: W806, the pipe moves to the reference, and every frame
 * (the failed one rerun) still gives the reference's answer. */
#include "synth.h"
#include "vb_test.h"
#include "vbc_channel_pipe.h"
#include "vbg_runtime.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Runs frame s on pipe p; the grid and the frame output come back. */
static int run(vb_ctx *ctx, vbc_pipe *p, const vb_sphere_set *s, int n, int dim, vbc_grid *g,
               vbc_frame_out *fo)
{
    float *atoms = malloc(4 * s->n * sizeof *atoms);
    int rc = vbc_grid_fit(ctx, s, 1.0, n, dim, g);
    if (rc == VB_OK) {
        vbc_atoms_pack(g, s, 1.0, atoms);
        rc = vbc_pipe_frame(ctx, p, g, atoms, s->n, 1.0, VBC_WANT_FLAGS | VBC_WANT_LABELS, fo);
    }
    free(atoms);
    return rc;
}

/* Same voxel set (the device lists in its own order), same flags, labels and
 * analysis. Returns the number of channel voxels. */
static size_t same_frame(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s,
                         const vbc_frame_out *a, const vbc_frame_out *b)
{
    size_t nv = vbc_grid_voxels(g);
    CHECK(memcmp(a->labels, b->labels, nv * sizeof *a->labels) == 0);
    CHECK(memcmp(a->flags, b->flags, nv) == 0);
    CHECK_INT(a->nvoxels, b->nvoxels);
    if (a->nvoxels != b->nvoxels || a->nvoxels == 0)
        return a->nvoxels;
    uint32_t *x = malloc(a->nvoxels * sizeof *x), *y = malloc(a->nvoxels * sizeof *y);
    memcpy(x, a->voxels, a->nvoxels * sizeof *x);
    memcpy(y, b->voxels, a->nvoxels * sizeof *y);
    qsort(x, a->nvoxels, sizeof *x, cmp_u32);
    qsort(y, a->nvoxels, sizeof *y, cmp_u32);
    CHECK(memcmp(x, y, a->nvoxels * sizeof *x) == 0);
    free(x);
    free(y);
    vbc_options opt = {2.0, 0.0, 1.0, 1, NULL};
    vbc_result ra, rb;
    CHECK_INT(vbc_analyse(ctx, g, s, a->voxels, a->nvoxels, &opt, &ra), VB_OK);
    CHECK_INT(vbc_analyse(ctx, g, s, b->voxels, b->nvoxels, &opt, &rb), VB_OK);
    CHECK_INT(ra.nchannels, rb.nchannels);
    for (size_t t = 0; t < ra.nchannels && t < rb.nchannels; t++) {
        CHECK(ra.channels[t].length == rb.channels[t].length);
        CHECK(ra.channels[t].bottleneck == rb.channels[t].bottleneck);
        CHECK_INT(ra.channels[t].npoints, rb.channels[t].npoints);
    }
    vbc_result_free(&ra);
    vbc_result_free(&rb);
    return a->nvoxels;
}

static void compare(vb_ctx *ctx, vbc_pipe *ocl, vbc_pipe *ref, const vb_sphere_set *s, int n, int dim)
{
    vbc_grid g1, g2;
    vbc_frame_out a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    CHECK_INT(run(ctx, ocl, s, n, dim, &g1, &a), VB_OK);
    CHECK_INT(run(ctx, ref, s, n, dim, &g2, &b), VB_OK);
    CHECK(b.clearance == NULL);
    if (a.labels && b.labels)
        CHECK(same_frame(ctx, &g1, s, &a, &b) > 0);
    vbc_frame_out_free(&a);
    vbc_frame_out_free(&b);
}

/* Frames 0..3 (the cylinder shifted along x) with a device fault on frame 2. */
static void fault(vb_ctx *ctx, vbc_pipe *ref, const vb_sphere_set *cyl, FILE *diag)
{
    vbc_pipe *p;
    CHECK_INT(vbc_pipe_open(ctx, &vbg_device_layer, VB_DEVICE_AUTO, VBJ_FACET, &p), VB_OK);
    vbc_pipe_inject_device_fault(p, 2);
    uint64_t w0 = vb_ctx_stats(ctx)->warnings;
    long at = ftell(diag);
    for (int f = 0; f < 4; f++) {
        for (size_t i = 0; i < cyl->n; i++)
            cyl->x[i] += 0.37 * f;
        CHECK_INT(vbc_pipe_is_ref(p), f > 2);
        vbc_grid g1, g2;
        vbc_frame_out a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        CHECK_INT(run(ctx, p, cyl, 32, 3, &g1, &a), VB_OK);
        CHECK_INT(run(ctx, ref, cyl, 32, 3, &g2, &b), VB_OK);
        CHECK_INT(vbc_pipe_is_ref(p), f >= 2);
        if (a.labels && b.labels)
            CHECK(same_frame(ctx, &g1, cyl, &a, &b) > 0);
        vbc_frame_out_free(&a);
        vbc_frame_out_free(&b);
    }
    CHECK_STR(vbc_pipe_device_name(p), "reference (C)");
    CHECK(vb_ctx_stats(ctx)->warnings == w0 + 1);
    char line[512] = "";
    fseek(diag, at, SEEK_SET);
    CHECK(fgets(line, sizeof line, diag) != NULL);
    CHECK(strstr(line, "W806") != NULL);
    vbc_pipe_close(p);
}

int main(void)
{
    FILE *diag = tmpfile();
    vb_ctx *ctx;
    vb_config cfg = {1, diag};
    if (!diag || vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    vbc_pipe *ref = NULL, *ocl = NULL;
    CHECK_INT(vbc_pipe_open(ctx, &vbg_device_layer, VB_DEVICE_REF, VBJ_FACET, &ref), VB_OK);
    CHECK_STR(vbc_pipe_device_name(ref), "reference (C)");
    vb_sphere_set *cyl = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    vb_sphere_set *shell = synth_shell(240, 9.0, 1.6);
    vb_sphere_set *flat = synth_cylinder(1, 12, 6.0, 1.6, 2.6);
    /* The default engine first (it takes the larger cases), then two others. */
    vbj_variant variants[3] = {VBJ_EXACT, VBJ_FACET, VBJ_JFA1};
    for (int t = 0; t < 3; t++) {
        vbc_pipe *r = NULL;
        CHECK_INT(vbc_pipe_open(ctx, &vbg_device_layer, VB_DEVICE_AUTO, variants[t], &ocl), VB_OK);
        CHECK_INT(vbc_pipe_open(ctx, &vbg_device_layer, VB_DEVICE_REF, variants[t], &r), VB_OK);
        /* This test compares backends: it needs OpenCL (PoCL in CI). */
        CHECK(ocl && !vbc_pipe_is_ref(ocl));
        if (!ocl || !r || vbc_pipe_is_ref(ocl)) {
            vbc_pipe_close(r);
            break;
        }
        compare(ctx, ocl, r, shell, 32, 3);
        /* The larger cases once: they test the masks, not the JFA variant. */
        if (t == 0) {
            compare(ctx, ocl, r, cyl, 64, 3);
            compare(ctx, ocl, r, flat, 64, 2);
        }
        vbc_pipe_close(ocl);
        vbc_pipe_close(r);
        ocl = NULL;
    }
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 0);
    if (ref)
        fault(ctx, ref, cyl, diag);
    /* Both backends refuse a grid side that is no power of two alike. */
    vbc_grid g;
    CHECK_INT(vbc_grid_fit(ctx, cyl, 1.0, 48, 3, &g), VB_OK);
    float a4[4] = {1, 1, 1, 1};
    vbc_frame_out fo;
    if (ref)
        CHECK_INT(vbc_pipe_frame(ctx, ref, &g, a4, 1, 1.0, 0, &fo), VB_EMISUSE);
    vbc_pipe_close(ocl);
    vbc_pipe_close(ref);
    vb_spheres_free(cyl);
    vb_spheres_free(shell);
    vb_spheres_free(flat);
    vb_close(ctx);
    fclose(diag);
    VB_TEST_END();
}
