/* The channel frame pipeline's two backends behind one call, and the
 * fallback from OpenCL to the plain-C reference (see vbc_channel_pipe.h). */
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbc_channel_pipe.h"

struct vbc_pipe {
    vbj_variant variant;
    vbg_runtime *rt;    /* OpenCL backend (NULL on the reference) */
    vbc_gpu *gp;
    vbj_engine *ref;    /* reference JFA engine, opened on first need */
    long ocl_frames;    /* frames run on OpenCL so far */
    long fault_at;      /* vbc_pipe_inject_device_fault */
};

/* Drops the OpenCL backend; later frames run on the reference. */
static void drop_opencl(vbc_pipe *p)
{
    vbc_gpu_close(p->gp);
    vbg_runtime_close(p->rt);
    p->gp = NULL;
    p->rt = NULL;
}

static int open_ref(vb_ctx *ctx, vbc_pipe *p)
{
    return p->ref ? VB_OK : vbj_engine_open(ctx, VBG_DEVICE_REF, &p->ref);
}

static int open_opencl(vb_ctx *ctx, vbc_pipe *p, vbg_device_kind kind)
{
    int rc = vbg_runtime_open(ctx, kind, &p->rt);
    if (rc == VB_OK)
        rc = vbc_gpu_open(ctx, p->rt, p->variant, &p->gp);
    if (rc != VB_OK)
        drop_opencl(p);
    return rc;
}

int vbc_pipe_open(vb_ctx *ctx, vbg_device_kind kind, vbj_variant variant, vbc_pipe **out)
{
    *out = NULL;
    vbc_pipe *p = calloc(1, sizeof *p);
    if (!p)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel pipeline");
    p->variant = variant;
    p->fault_at = -1;
    int rc = VB_EDEVICE;
    if (kind != VBG_DEVICE_REF) {
        rc = open_opencl(ctx, p, kind);
        if (rc == VB_EDEVICE && kind == VBG_DEVICE_GPU) {
            vb_warn(ctx, 805, NULL, 0, "no usable OpenCL GPU (%s): trying the CPU device",
                    vb_errmsg(ctx));
            vb_clear_error(ctx);
            rc = open_opencl(ctx, p, VBG_DEVICE_CPU);
        }
        if (rc == VB_EDEVICE) {
            vb_warn(ctx, 804, NULL, 0, "no usable OpenCL device (%s): channels run on the "
                    "reference backend (C)", vb_errmsg(ctx));
            vb_clear_error(ctx);
        }
    }
    if (rc == VB_EDEVICE)
        rc = open_ref(ctx, p);
    if (rc != VB_OK) {
        vbc_pipe_close(p);
        return rc;
    }
    *out = p;
    return VB_OK;
}

void vbc_pipe_close(vbc_pipe *p)
{
    if (!p)
        return;
    drop_opencl(p);
    vbj_engine_close(p->ref);
    free(p);
}

const char *vbc_pipe_device_name(const vbc_pipe *p)
{
    return p->rt ? vbg_runtime_device_name(p->rt) : vbj_engine_device_name(p->ref);
}

int vbc_pipe_is_ref(const vbc_pipe *p)
{
    return p->rt == NULL;
}

void vbc_pipe_inject_device_fault(vbc_pipe *p, long frame)
{
    p->fault_at = frame;
}

/* The reference frame: JFA labels in C, the masks of core/discrete/channel_masks_ref.c
 * (bit for bit those of gpu/channels.cl), the voxel list in index order. */
static int ref_frame(vb_ctx *ctx, vbc_pipe *p, const vbc_grid *g, const float *atoms4,
                     size_t natoms, unsigned want, vbc_frame_out *out)
{
    vbj_seeds seeds;
    vbj_result jr;
    memset(&jr, 0, sizeof jr);
    uint8_t *flags = NULL;
    int *rb = NULL;
    double t0 = 1e3 * vb_now();
    int rc = vbc_frame_seeds(ctx, g, atoms4, natoms, &seeds);
    if (rc != VB_OK)
        return rc;
    double t1 = 1e3 * vb_now();
    out->ms_upload = t1 - t0;
    vbj_options jo = {p->variant, 0, VBJ_WANT_LABELS, 0};
    if ((rc = vbj_run(ctx, p->ref, &seeds, &jo, &jr)) != VB_OK)
        goto done;
    double t2 = 1e3 * vb_now();
    out->ms_jfa = t2 - t1;
    out->jfa = jr.counts;
    flags = malloc(vbc_grid_voxels(g));
    rb = malloc((size_t)vbc_rb_size(g->nx, g->ny, g->nz) * sizeof *rb);
    if (!flags || !rb) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "channel masks of %zu voxels", vbc_grid_voxels(g));
        goto done;
    }
    /* Seed indices are below VBJ_MAX_SEEDS, so the int32 view is lossless. */
    vbc_masks_ref(g, atoms4, natoms, (const int32_t *)jr.labels, g->dim == 3 ? 3 : 2, rb, flags);
    if ((rc = vbc_flags_compact(ctx, g, flags, &out->voxels, &out->nvoxels)) != VB_OK)
        goto done;
    out->ms_masks = 1e3 * vb_now() - t2;
    if (want & VBC_WANT_FLAGS) {
        out->flags = flags;
        flags = NULL;
    }
    if (want & VBC_WANT_LABELS) {
        out->labels = jr.labels;
        jr.labels = NULL;
    }
done:
    free(flags);
    free(rb);
    vbj_result_free(&jr);
    vbj_seeds_free(&seeds);
    return rc;
}

int vbc_pipe_frame(vb_ctx *ctx, vbc_pipe *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                   double probe, unsigned want, vbc_frame_out *out)
{
    memset(out, 0, sizeof *out);
    if (p->gp) {
        int rc = p->ocl_frames++ == p->fault_at
                     ? vb_error(ctx, VB_EDEVICE, NULL, 0, "injected device fault")
                     : vbc_gpu_frame(ctx, p->gp, g, atoms4, natoms, probe, want, out);
        if (rc != VB_EDEVICE)
            return rc;
        vb_warn(ctx, 806, NULL, 0, "OpenCL failed on %s (%s): this frame and the rest run on "
                "the reference backend (C)", vbg_runtime_device_name(p->rt), vb_errmsg(ctx));
        vb_clear_error(ctx);
        drop_opencl(p);
        if ((rc = open_ref(ctx, p)) != VB_OK)
            return rc;
    }
    int rc = ref_frame(ctx, p, g, atoms4, natoms, want, out);
    if (rc != VB_OK)
        vbc_frame_out_free(out);
    return rc;
}
