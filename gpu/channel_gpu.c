/* Host side of gpu/channels.cl: buffers, launches and the JFA hand-off. */
#include <stdlib.h>
#include <string.h>

#include "channel_math.h"
#include "jfa_internal.h"
#include "vb_parallel.h"
#include "vbc_channel_gpu.h"
#include "vbc_paths.h"
#include "vbc_walls.h"

struct vbc_gpu {
    vbg_runtime *rt;
    vbj_engine *jfa;
    vbj_variant variant;
    cl_kernel k_atomic, k_rays, k_classify, k_clear;
    cl_kernel k_cc_seed, k_cc_hook, k_cc_jump, k_cc_gather;
    cl_mem atoms, flags, rb, list, count, clear, cc, comp, changed;
    size_t atoms_cap, voxels_cap, rb_cap, list_cap, clear_cap, cc_cap, comp_cap; /* elements */
    int device_clearance; /* see vbc_gpu_set_device_clearance */
    int device_graph;     /* see vbc_gpu_set_device_graph */
};

/* The pipe's eight kernels, in the order vbc_gpu_open names them. */
static void kernels(vbc_gpu *p, cl_kernel *ks[8])
{
    cl_kernel *all[8] = {&p->k_atomic,  &p->k_rays,    &p->k_classify, &p->k_clear,
                         &p->k_cc_seed, &p->k_cc_hook, &p->k_cc_jump,  &p->k_cc_gather};
    memcpy(ks, all, sizeof all);
}

int vbc_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbj_variant variant, vbc_gpu **out)
{
    *out = NULL;
    vbc_gpu *p = calloc(1, sizeof *p);
    if (!p)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel pipeline");
    p->rt = rt;
    p->variant = variant;
    cl_program prog;
    int rc = vbg_program_get(ctx, rt, "channels.cl", NULL, &prog);
    if (rc == VB_OK)
        rc = vbj_engine_open_runtime(ctx, rt, &p->jfa);
    if (rc != VB_OK) {
        vbc_gpu_close(p);
        return rc;
    }
    /* The kernels of channels.cl, in the order of kernels(). */
    static const char *const names[] = {"vbc_atomic_mask", "vbc_ray_bounds",
                                        "vbc_classify_voxels", "vbc_clearance", "vbc_cc_seed",
                                        "vbc_cc_hook", "vbc_cc_jump", "vbc_cc_gather"};
    cl_kernel *ks[8];
    kernels(p, ks);
    cl_int err = CL_SUCCESS;
    for (size_t i = 0; i < sizeof names / sizeof names[0] && err == CL_SUCCESS; i++)
        *ks[i] = clCreateKernel(prog, names[i], &err);
    if (err == CL_SUCCESS)
        p->changed = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_WRITE, sizeof(cl_uint),
                                    NULL, &err);
    if (err == CL_SUCCESS)
        p->count = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_WRITE, sizeof(cl_uint), NULL,
                                  &err);
    if ((rc = vbg_check(ctx, err, "channel kernels")) != VB_OK) {
        vbc_gpu_close(p);
        return rc;
    }
    *out = p;
    return VB_OK;
}

void vbc_gpu_close(vbc_gpu *p)
{
    if (!p)
        return;
    cl_kernel *ks[8];
    kernels(p, ks);
    for (size_t i = 0; i < 8; i++)
        if (*ks[i])
            clReleaseKernel(*ks[i]);
    cl_mem bufs[] = {p->atoms, p->flags, p->rb, p->list, p->count, p->clear, p->cc, p->comp,
                     p->changed};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        if (bufs[i])
            clReleaseMemObject(bufs[i]);
    vbj_engine_close(p->jfa);
    free(p);
}

void vbc_gpu_set_device_clearance(vbc_gpu *p, int mode)
{
    p->device_clearance = mode;
}

void vbc_gpu_set_device_graph(vbc_gpu *p, int mode)
{
    p->device_graph = mode;
}

/* Whether this frame's clearances are computed on the device:
 * VORBALL_DEVICE_CLEARANCE (0 never, 1 always) over the mode of
 * vbc_gpu_set_device_clearance. With 1 a CPU device runs the host analysis
 * a GPU run does (the clearances given), for its clocks. */
static int clearance_on_device(const vbc_gpu *p)
{
    const char *e = getenv("VORBALL_DEVICE_CLEARANCE");
    if (e && (strcmp(e, "0") == 0 || strcmp(e, "1") == 0))
        return e[0] == '1';
    return p->device_clearance > 0 || (p->device_clearance == 0 && vbg_runtime_is_gpu(p->rt));
}

/* Whether this frame's components run on the device: VORBALL_DEVICE_GRAPH
 * (0 never, 1 always) over the mode of vbc_gpu_set_device_graph. */
static int graph_on_device(const vbc_gpu *p)
{
    const char *e = getenv("VORBALL_DEVICE_GRAPH");
    if (e && (strcmp(e, "0") == 0 || strcmp(e, "1") == 0))
        return e[0] == '1';
    return p->device_graph > 0 || (p->device_graph == 0 && vbg_runtime_is_gpu(p->rt));
}

cl_int vbc_gpu_buffer_fit(vbg_runtime *rt, cl_mem *buf, size_t *cap, size_t need, size_t size)
{
    if (*buf && *cap >= need)
        return CL_SUCCESS;
    if (*buf)
        clReleaseMemObject(*buf);
    size_t c = need + need / 2 + 16;
    cl_int err;
    *buf = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_WRITE, c * size, NULL, &err);
    *cap = err == CL_SUCCESS ? c : 0;
    if (err != CL_SUCCESS)
        *buf = NULL;
    return err;
}

static cl_int ensure(vbc_gpu *p, cl_mem *buf, size_t *cap, size_t need, size_t size)
{
    return vbc_gpu_buffer_fit(p->rt, buf, cap, need, size);
}

/* The classification pass: resets the counter, launches, reads the count. */
static cl_int classify(vbc_gpu *p, cl_mem labels, const vbc_grid *g, int min_labels, cl_uint *count)
{
    cl_command_queue q = vbg_runtime_queue(p->rt);
    cl_uint zero = 0, cap = (cl_uint)p->list_cap;
    /* Blocking: `zero` lives on this stack frame, which an error below leaves. */
    cl_int err = clEnqueueWriteBuffer(q, p->count, CL_TRUE, 0, sizeof zero, &zero, 0, NULL, NULL);
    cl_int a = 0;
    err |= clSetKernelArg(p->k_classify, a++, sizeof labels, &labels);
    err |= clSetKernelArg(p->k_classify, a++, sizeof p->flags, &p->flags);
    err |= clSetKernelArg(p->k_classify, a++, sizeof p->rb, &p->rb);
    err |= clSetKernelArg(p->k_classify, a++, sizeof g->nx, &g->nx);
    err |= clSetKernelArg(p->k_classify, a++, sizeof g->ny, &g->ny);
    err |= clSetKernelArg(p->k_classify, a++, sizeof g->nz, &g->nz);
    err |= clSetKernelArg(p->k_classify, a++, sizeof min_labels, &min_labels);
    err |= clSetKernelArg(p->k_classify, a++, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_classify, a++, sizeof p->count, &p->count);
    err |= clSetKernelArg(p->k_classify, a++, sizeof cap, &cap);
    if (err != CL_SUCCESS)
        return err;
    size_t gs[3] = {(size_t)g->nx, (size_t)g->ny, (size_t)g->nz};
    err = clEnqueueNDRangeKernel(q, p->k_classify, 3, NULL, gs, NULL, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(q, p->count, CL_TRUE, 0, sizeof *count, count, 0, NULL, NULL);
    return err;
}

/* Clearance of the listed voxels on the device, read back into out. */
static cl_int clearance(vbc_gpu *p, const vbc_grid *g, size_t natoms, double probe, cl_uint count,
                        vbc_frame_out *out)
{
    cl_command_queue q = vbg_runtime_queue(p->rt);
    cl_int err = ensure(p, &p->clear, &p->clear_cap, count, sizeof(cl_float));
    cl_uint na = (cl_uint)natoms;
    cl_float pg = (cl_float)(probe / g->h), h = (cl_float)g->h;
    size_t lsz = 64, gsz = ((size_t)count + lsz - 1) / lsz * lsz;
    cl_int a = 0;
    err |= clSetKernelArg(p->k_clear, a++, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_clear, a++, sizeof count, &count);
    err |= clSetKernelArg(p->k_clear, a++, sizeof p->atoms, &p->atoms);
    err |= clSetKernelArg(p->k_clear, a++, sizeof na, &na);
    err |= clSetKernelArg(p->k_clear, a++, sizeof g->nx, &g->nx);
    err |= clSetKernelArg(p->k_clear, a++, sizeof g->ny, &g->ny);
    err |= clSetKernelArg(p->k_clear, a++, sizeof pg, &pg);
    err |= clSetKernelArg(p->k_clear, a++, sizeof h, &h);
    err |= clSetKernelArg(p->k_clear, a++, sizeof p->clear, &p->clear);
    err |= clSetKernelArg(p->k_clear, a++, lsz * 4 * sizeof(cl_float), NULL);
    if (err != CL_SUCCESS)
        return err;
    err = clEnqueueNDRangeKernel(q, p->k_clear, 1, NULL, &gsz, &lsz, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return err;
    out->clearance = malloc((size_t)count * sizeof *out->clearance);
    if (!out->clearance)
        return CL_OUT_OF_HOST_MEMORY;
    return clEnqueueReadBuffer(q, p->clear, CL_TRUE, 0, (size_t)count * sizeof(cl_float),
                               out->clearance, 0, NULL, NULL);
}

/* Launches kernel k over n work-items (rounded up to groups of 64). */
static cl_int launch(vbc_gpu *p, cl_kernel k, size_t n)
{
    size_t lsz = 64, gsz = (n + lsz - 1) / lsz * lsz;
    return clEnqueueNDRangeKernel(vbg_runtime_queue(p->rt), k, 1, NULL, &gsz, &lsz, 0, NULL, NULL);
}

/* The components of the listed voxels on the device (channels.cl's
 * vbc_cc_*): per listed voxel, the smallest voxel index of its component,
 * read back into out->comp. Rounds of hooking and jumping until no label
 * falls: at most as many as the longest path in a component, and never
 * more than count + 1 (each round with a change lowers some label). */
static cl_int components(vbc_gpu *p, const vbc_grid *g, cl_uint count, vbc_frame_out *out)
{
    cl_command_queue q = vbg_runtime_queue(p->rt);
    size_t nv = vbc_grid_voxels(g);
    cl_int err = ensure(p, &p->cc, &p->cc_cap, nv, sizeof(cl_uint));
    if (err == CL_SUCCESS)
        err = ensure(p, &p->comp, &p->comp_cap, count, sizeof(cl_uint));
    cl_uint off = 0xffffffffu, changed = 1;
    if (err == CL_SUCCESS)
        err = clEnqueueFillBuffer(q, p->cc, &off, sizeof off, 0, nv * sizeof(cl_uint), 0, NULL,
                                  NULL);
    err |= clSetKernelArg(p->k_cc_seed, 0, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_cc_seed, 1, sizeof count, &count);
    err |= clSetKernelArg(p->k_cc_seed, 2, sizeof p->cc, &p->cc);
    cl_int a = 0;
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof count, &count);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof p->cc, &p->cc);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof g->nx, &g->nx);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof g->ny, &g->ny);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof g->nz, &g->nz);
    err |= clSetKernelArg(p->k_cc_hook, a++, sizeof p->changed, &p->changed);
    err |= clSetKernelArg(p->k_cc_jump, 0, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_cc_jump, 1, sizeof count, &count);
    err |= clSetKernelArg(p->k_cc_jump, 2, sizeof p->cc, &p->cc);
    err |= clSetKernelArg(p->k_cc_gather, 0, sizeof p->list, &p->list);
    err |= clSetKernelArg(p->k_cc_gather, 1, sizeof count, &count);
    err |= clSetKernelArg(p->k_cc_gather, 2, sizeof p->cc, &p->cc);
    err |= clSetKernelArg(p->k_cc_gather, 3, sizeof p->comp, &p->comp);
    if (err == CL_SUCCESS)
        err = launch(p, p->k_cc_seed, count);
    for (cl_uint round = 0; err == CL_SUCCESS && changed; round++) {
        if (round > count)
            return CL_INVALID_VALUE; /* labels that never settle: a broken device */
        cl_uint zero = 0;
        err = clEnqueueWriteBuffer(q, p->changed, CL_TRUE, 0, sizeof zero, &zero, 0, NULL, NULL);
        if (err == CL_SUCCESS)
            err = launch(p, p->k_cc_hook, count);
        if (err == CL_SUCCESS)
            err = launch(p, p->k_cc_jump, count);
        if (err == CL_SUCCESS)
            err = clEnqueueReadBuffer(q, p->changed, CL_TRUE, 0, sizeof changed, &changed, 0, NULL,
                                      NULL);
    }
    if (err == CL_SUCCESS)
        err = launch(p, p->k_cc_gather, count);
    if (err != CL_SUCCESS)
        return err;
    out->comp = malloc((size_t)count * sizeof *out->comp);
    if (!out->comp)
        return CL_OUT_OF_HOST_MEMORY;
    return clEnqueueReadBuffer(q, p->comp, CL_TRUE, 0, (size_t)count * sizeof(cl_uint), out->comp,
                               0, NULL, NULL);
}

int vbc_gpu_frame(vb_ctx *ctx, vbc_gpu *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                  double probe, unsigned want, vbc_frame_out *out)
{
    memset(out, 0, sizeof *out);
    cl_command_queue q = vbg_runtime_queue(p->rt);
    size_t nv = vbc_grid_voxels(g);
    size_t nrb = (size_t)vbc_rb_size(g->nx, g->ny, g->nz);
    int rc = VB_OK;
    vbj_seeds seeds = {0};
    vbj_result jr;
    memset(&jr, 0, sizeof jr);

    double t0 = 1e3 * vb_now();
    if ((rc = vbc_frame_seeds(ctx, g, atoms4, natoms, &seeds)) != VB_OK)
        return rc;
    cl_int err = ensure(p, &p->atoms, &p->atoms_cap, natoms, 4 * sizeof(float));
    if (err == CL_SUCCESS)
        err = ensure(p, &p->flags, &p->voxels_cap, nv, 1);
    if (err == CL_SUCCESS)
        err = ensure(p, &p->rb, &p->rb_cap, nrb, sizeof(cl_int));
    if (err == CL_SUCCESS)
        err = ensure(p, &p->list, &p->list_cap, 1024, sizeof(cl_uint));
    if (err == CL_SUCCESS)
        err = clEnqueueWriteBuffer(q, p->atoms, CL_TRUE, 0, natoms * 4 * sizeof(float), atoms4, 0,
                                   NULL, NULL);
    if ((rc = vbg_check(ctx, err, "channel upload")) != VB_OK)
        goto done;

    if ((rc = vbg_check(ctx, clFinish(q), "channel upload")) != VB_OK)
        goto done;
    double t1 = 1e3 * vb_now();
    out->ms_upload = t1 - t0;
    vbj_options jo = {p->variant, 0, 0, 0};
    jr.dim = seeds.dim;
    jr.n = seeds.n;
    jr.pixels = (size_t)seeds.n * seeds.n * (seeds.dim == 3 ? seeds.n : 1);
    if ((rc = vbj_cl_run(ctx, p->jfa, &seeds, &jo,
                         VBJ_WANT_DEVICE | ((want & VBC_WANT_LABELS) ? VBJ_WANT_LABELS : 0),
                         &jr)) != VB_OK)
        goto done;
    cl_mem labels = vbj_engine_labels_device(p->jfa);
    if (!labels) {
        rc = vb_error(ctx, VB_EINTERNAL, NULL, 0, "JFA engine kept no device labels");
        goto done;
    }
    double t2 = 1e3 * vb_now();
    out->ms_jfa = t2 - t1;
    out->jfa = jr.counts;

    cl_uchar zero = 0;
    err = clEnqueueFillBuffer(q, p->flags, &zero, 1, 0, nv, 0, NULL, NULL);
    err |= clSetKernelArg(p->k_atomic, 0, sizeof p->atoms, &p->atoms);
    err |= clSetKernelArg(p->k_atomic, 1, sizeof p->flags, &p->flags);
    err |= clSetKernelArg(p->k_atomic, 2, sizeof g->nx, &g->nx);
    err |= clSetKernelArg(p->k_atomic, 3, sizeof g->ny, &g->ny);
    err |= clSetKernelArg(p->k_atomic, 4, sizeof g->nz, &g->nz);
    if (err == CL_SUCCESS) {
        size_t lsz = 64, gsz = natoms * lsz;
        err = clEnqueueNDRangeKernel(q, p->k_atomic, 1, NULL, &gsz, &lsz, 0, NULL, NULL);
    }
    for (int axis = 0; axis < 3 && err == CL_SUCCESS; axis++) {
        size_t gs[2] = {(size_t)(axis == 0 ? g->ny : g->nx), (size_t)(axis == 2 ? g->ny : g->nz)};
        err |= clSetKernelArg(p->k_rays, 0, sizeof p->flags, &p->flags);
        err |= clSetKernelArg(p->k_rays, 1, sizeof p->rb, &p->rb);
        err |= clSetKernelArg(p->k_rays, 2, sizeof g->nx, &g->nx);
        err |= clSetKernelArg(p->k_rays, 3, sizeof g->ny, &g->ny);
        err |= clSetKernelArg(p->k_rays, 4, sizeof g->nz, &g->nz);
        err |= clSetKernelArg(p->k_rays, 5, sizeof axis, &axis);
        if (err == CL_SUCCESS)
            err = clEnqueueNDRangeKernel(q, p->k_rays, 2, NULL, gs, NULL, 0, NULL, NULL);
    }
    int min_labels = g->dim == 3 ? 3 : 2;
    cl_uint count = 0;
    if (err == CL_SUCCESS)
        err = classify(p, labels, g, min_labels, &count);
    if (err == CL_SUCCESS && count > p->list_cap) {
        /* The list overflowed: grow it and classify again (the pass is idempotent). */
        err = ensure(p, &p->list, &p->list_cap, count, sizeof(cl_uint));
        if (err == CL_SUCCESS)
            err = classify(p, labels, g, min_labels, &count);
    }
    if ((rc = vbg_check(ctx, err, "channel masks")) != VB_OK)
        goto done;
    if (count > 0) {
        out->voxels = malloc((size_t)count * sizeof *out->voxels);
        if (!out->voxels) {
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "channel voxel list (%u)", count);
            goto done;
        }
        err = clEnqueueReadBuffer(q, p->list, CL_TRUE, 0, (size_t)count * sizeof(cl_uint),
                                  out->voxels, 0, NULL, NULL);
        out->nvoxels = count;
        /* A GPU does the clearances in a blink; a CPU device is better
         * served by the host's cell list, so it leaves them to the analysis. */
        if (err == CL_SUCCESS && clearance_on_device(p))
            err = clearance(p, g, natoms, probe, count, out);
        if (err == CL_SUCCESS && graph_on_device(p))
            err = components(p, g, count, out);
    }
    if (err == CL_SUCCESS && (want & VBC_WANT_FLAGS)) {
        out->flags = malloc(nv);
        if (!out->flags) {
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "flag volume");
            goto done;
        }
        err = clEnqueueReadBuffer(q, p->flags, CL_TRUE, 0, nv, out->flags, 0, NULL, NULL);
    }
    if ((rc = vbg_check(ctx, err, "channel download")) != VB_OK)
        goto done;
    out->ms_masks = 1e3 * vb_now() - t2;
    if (want & VBC_WANT_LABELS) {
        out->labels = jr.labels;
        jr.labels = NULL;
    }
done:
    vbj_result_free(&jr);
    vbj_seeds_free(&seeds);
    if (rc != VB_OK)
        vbc_frame_out_free(out);
    return rc;
}

/* ---- the engine table (vbc_channel_pipe.h) ---- */

/* The engine's state: the pipeline, and the batch sweeps when asked for. */
typedef struct {
    vbc_gpu *gpu;
    vbc_paths_gpu *paths;
    vbc_walls_gpu *walls;
} engine_state;

static int engine_frame(vb_ctx *ctx, vbc_engine *e, const vbc_grid *g, const float *atoms4,
                        size_t natoms, double probe, unsigned want, vbc_frame_out *out)
{
    return vbc_gpu_frame(ctx, ((engine_state *)e->state)->gpu, g, atoms4, natoms, probe, want, out);
}


static void engine_close(vbc_engine *e)
{
    engine_state *st = e->state;
    vbc_gpu_close(st->gpu);
    vbc_paths_gpu_close(st->paths);
    vbc_walls_gpu_close(st->walls);
    free(st);
    free(e);
}

int vbg_channels_open(vb_ctx *ctx, vbg_runtime *rt, vbj_variant variant, vbc_engine **out)
{
    *out = NULL;
    vbc_engine *e = calloc(1, sizeof *e);
    engine_state *st = calloc(1, sizeof *st);
    if (!e || !st) {
        free(e);
        free(st);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel pipeline");
    }
    int rc = vbc_gpu_open(ctx, rt, variant, &st->gpu);
    /* The sweep kernels are built only for runs that ask for them (on a CPU
     * device only when forced: the twin costs it less). */
    int paths = vbc_paths_mode();
    if (rc == VB_OK && (paths == 2 || (paths == 1 && vbg_runtime_is_gpu(rt))))
        rc = vbc_paths_gpu_open(ctx, rt, &st->paths);
    /* The verdict's rasters likewise (vbc_walls_mode). */
    int walls = vbc_walls_mode();
    if (rc == VB_OK && (walls == 2 || (walls == 1 && vbg_runtime_is_gpu(rt))))
        rc = vbc_walls_gpu_open(ctx, rt, &st->walls);
    if (rc != VB_OK) {
        vbc_paths_gpu_close(st->paths);
        vbc_gpu_close(st->gpu);
        free(st);
        free(e);
        return rc;
    }
    e->state = st;
    e->paths = vbc_paths_gpu_engine(st->paths);
    e->walls = vbc_walls_gpu_engine(st->walls);
    e->name = "opencl";
    snprintf(e->device, sizeof e->device, "%s", vbg_runtime_device_name(rt));
    e->frame = engine_frame;
    e->close = engine_close;
    *out = e;
    return VB_OK;
}
