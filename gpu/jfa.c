/* Host toolbox of the OpenCL JFA backend: the engine's buffers, kernels,
 * launches and profiling events, and the dense JFA variants (kernels in
 * gpu/jfa.cl). Facet-JFA (jfa_facet.c) and the exact diagram (jfa_exact.c)
 * build on it; jfa_ocl.c puts them behind the vbj_backend table. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jfa_internal.h"

/* Pixels per work-item of the step kernels along x, y (and z in 3D), spaced
 * l apart: blocks share most neighbours, so they read fewer labels. jfa.cl
 * is built for these shapes (x shared by 2D and 3D). On an H100, 256^3 with
 * 13,573 seeds, JFA+1 took 3.45 ms with 2 x 2 x 2, 3.57 ms with 1 x 2 x 4,
 * 3.57 ms with 1 x 2 x 2, 3.69 ms with 1 x 1 x 4 and 4.41 ms with 1 x 1 x 1
 * (papers/facet-jfa-and-channels/results/jfa/kernels/). */
static const uint32_t block2[2] = {2, 4}, block3[3] = {2, 2, 2};

int vbj_engine_open_runtime(vb_ctx *ctx, vbg_runtime *rt, vbj_engine **out)
{
    *out = NULL;
    vbj_engine *e = calloc(1, sizeof *e);
    if (!e)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "jfa engine: out of memory");
    e->rt = rt;
    int rc;
    /* jfa.cl's four builds wait for their first use (vbj_cl_kernel). */
    if (rt && ((rc = vbg_program_get(ctx, rt, "facet_jfa.cl", "", &e->facet)) ||
               (rc = vbg_program_get(ctx, rt, "jfa_exact.cl", "", &e->exact)) ||
               (rc = vbg_program_get(ctx, rt, "jfa_tiles.cl", "", &e->tiles)))) {
        free(e);
        return rc;
    }
    *out = e;
    return VB_OK;
}

static void release(vbj_clbuf *b)
{
    if (b->mem)
        clReleaseMemObject(b->mem);
    b->mem = NULL;
    b->bytes = 0;
}

void vbj_engine_close(vbj_engine *e)
{
    if (!e)
        return;
    vbj_cl_recorded_ms(e); /* events of a run that failed */
    vbj_clbuf *all[] = {&e->seeds, &e->seeds_fp, &e->pairs, &e->grid[0], &e->grid[1], &e->store[0], &e->store[1],
                        &e->tmp, &e->list[0], &e->list[1], &e->counter, &e->labels,
                        &e->cells_start, &e->cells_items, &e->cells_ring0, &e->tcounters};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        release(all[i]);
    for (int i = 0; i < VBJ_NKERNELS; i++)
        if (e->kernels[i])
            clReleaseKernel(e->kernels[i]);
    free(e->events);
    /* Programs belong to the runtime's cache; the runtime to the caller. */
    free(e);
}

cl_mem vbj_engine_labels_device(const vbj_engine *e) { return e->device_labels; }

cl_event *vbj_cl_event(vbj_engine *e)
{
    if (!e->recording)
        return NULL;
    if (e->nevents == e->cap_events) {
        int cap = e->cap_events ? 2 * e->cap_events : 64;
        cl_event *ev = realloc(e->events, (size_t)cap * sizeof *ev);
        if (!ev)
            return NULL; /* the command still runs; its time goes unrecorded */
        e->events = ev;
        e->cap_events = cap;
    }
    /* A command that fails to enqueue leaves no event: the slot stays NULL. */
    e->events[e->nevents] = NULL;
    return &e->events[e->nevents++];
}

void vbj_cl_record(vbj_engine *e)
{
    e->nevents = 0;
    e->recording = 1;
}

double vbj_cl_recorded_ms(vbj_engine *e)
{
    double s = 0;
    for (int i = 0; i < e->nevents; i++) {
        if (!e->events[i])
            continue;
        s += vbg_event_seconds(e->events[i]);
        clReleaseEvent(e->events[i]);
    }
    e->nevents = 0;
    e->recording = 0;
    return s * 1e3;
}

int vbj_clbuf_reserve(vb_ctx *ctx, vbj_engine *e, vbj_clbuf *b, size_t bytes)
{
    if (bytes == 0)
        bytes = 4;
    if (b->mem && b->bytes >= bytes)
        return VB_OK;
    release(b);
    cl_int err;
    b->mem = clCreateBuffer(vbg_runtime_context(e->rt), CL_MEM_READ_WRITE, bytes, NULL, &err);
    /* The device is out of memory, not the host: VB_EDEVICE, so that the
     * caller falls back to the reference backend. */
    if (err == CL_MEM_OBJECT_ALLOCATION_FAILURE || err == CL_OUT_OF_HOST_MEMORY ||
        err == CL_INVALID_BUFFER_SIZE) {
        b->mem = NULL;
        return vb_error(ctx, VB_EDEVICE, NULL, 0, "device buffer of %zu bytes: %s", bytes,
                        err == CL_INVALID_BUFFER_SIZE ? "larger than the device allows"
                                                      : "device out of memory");
    }
    if (vbg_check(ctx, err, "clCreateBuffer")) {
        b->mem = NULL;
        return VB_EDEVICE;
    }
    b->bytes = bytes;
    return VB_OK;
}

int vbj_dist_build(int dim, uint32_t n)
{
    /* Seeds lie in [-0.5, n - 0.5) and centres in [0, n - 1] pixels: in
     * 16.16 every coordinate is below n 2^16 in magnitude (exact in a float
     * while that is <= 2^24), every difference too, and a squared distance
     * below dim n^2 2^32 (an exact integer in a double while <= 2^53). */
    if (n <= 256)
        return VBJ_JFA_FLOAT;
    return (uint64_t)dim * n * n <= ((uint64_t)1 << 21) ? 0 : VBJ_JFA_DIST64;
}

/* Work-items along an axis of q cells, blocks of b, step l (jfa.cl's
 * VBJ_ITEMS). */
static size_t items(cl_uint q, cl_uint l, uint32_t b) { return q / l >= b ? q / b : l; }

/* Whether the device takes NVIDIA's -cl-nv-* build options. The float build
 * of the step kernels is latency bound: capped at 48 registers (more
 * resident warps), JFA+1 on 256^3 with 13,573 seeds took 3.23 ms on an H100
 * instead of 3.44 (32: 3.71, 40: 3.36, 64 or more: 3.41-3.42 ms;
 * papers/facet-jfa-and-channels/results/jfa/kernels/h100_regcap/). The other
 * builds were not measured with a cap and keep the compiler's choice. */
static int has_nv_options(const vbj_engine *e)
{
    char ext[4096];
    size_t len = 0;
    if (clGetDeviceInfo(vbg_runtime_device(e->rt), CL_DEVICE_EXTENSIONS, sizeof ext - 1, ext,
                        &len) != CL_SUCCESS ||
        len >= sizeof ext)
        return 0;
    ext[len] = '\0';
    return strstr(ext, "cl_nv_compiler_options") != NULL;
}

int vbj_cl_kernel(vb_ctx *ctx, vbj_engine *e, int which, cl_kernel *out)
{
    static const char *jfa_names[VBJ_KJFA] = {"jfa_place", "jfa_step_2d", "jfa_step_3d",
                                              "jfa_count_labels", "jfa_widen",
                                              "jfa_boundary"};
    static const char *names[] = {"facet_step",  "facet_mark_refine", "facet_strip",
                                  "facet_small", "jfa_exact",         "jfa_tiles"};
    if (!e->kernels[which]) {
        const char *name;
        cl_program p;
        if (which < VBJ_K_FSTEP) {
            int b = which / VBJ_KJFA, rc;
            char opt[192];
            snprintf(opt, sizeof opt, "%s%s -DVBJ_BX=%u -DVBJ_BY=%u -DVBJ_BZ=%u -DVBJ_BY2=%u%s",
                     b & VBJ_JFA_LABEL16 ? "-DVBJ_LABEL16 " : "",
                     b & VBJ_JFA_DIST64 ? "-DVBJ_DIST64" : b & VBJ_JFA_FLOAT ? "-DVBJ_DISTF" : "",
                     block3[0], block3[1], block3[2], block2[1],
                     b & VBJ_JFA_FLOAT && has_nv_options(e) ? " -cl-nv-maxrregcount=48" : "");
            if (!e->jfa[b] && (rc = vbg_program_get(ctx, e->rt, "jfa.cl", opt, &e->jfa[b])))
                return rc;
            p = e->jfa[b];
            name = jfa_names[which % VBJ_KJFA];
        } else {
            p = which < VBJ_K_EXACT ? e->facet : which == VBJ_K_EXACT ? e->exact : e->tiles;
            name = names[which - VBJ_K_FSTEP];
        }
        cl_int err;
        e->kernels[which] = clCreateKernel(p, name, &err);
        if (vbg_check(ctx, err, name))
            return VB_EDEVICE;
    }
    *out = e->kernels[which];
    return VB_OK;
}

int vbj_cl_launch(vb_ctx *ctx, vbj_engine *e, cl_kernel k, int dims, const size_t *global,
                  const char *what)
{
    size_t g[3], l[3];
    for (int i = 0; i < dims; i++)
        if (global[i] == 0)
            return VB_OK; /* nothing left to process (e.g. every cell marked) */
    int gpu = vbg_runtime_is_gpu(e->rt);
    /* Wide along the contiguous axis so that a warp reads whole lines. */
    static const size_t want[3][3] = {{256, 1, 1}, {64, 4, 1}, {64, 4, 1}};
    for (int i = 0; i < dims; i++) {
        l[i] = want[dims - 1][i];
        while (l[i] > 1 && l[i] / 2 >= global[i])
            l[i] /= 2;
        g[i] = (global[i] + l[i] - 1) / l[i] * l[i];
    }
    cl_int err = clEnqueueNDRangeKernel(vbg_runtime_queue(e->rt), k, (cl_uint)dims, NULL, g,
                                        gpu ? l : NULL, 0, NULL, vbj_cl_event(e));
    return vbg_check(ctx, err, what) ? VB_EDEVICE : VB_OK;
}

int vbj_cl_set_args(vb_ctx *ctx, cl_kernel k, const char *what, int nargs,
                    const vbj_arg *args)
{
    for (int i = 0; i < nargs; i++) {
        cl_int err = clSetKernelArg(k, (cl_uint)i, args[i].size, args[i].ptr);
        if (err != CL_SUCCESS) {
            char w[96];
            snprintf(w, sizeof w, "%s argument %d", what, i);
            return vbg_check(ctx, err, w) ? VB_EDEVICE : VB_EINTERNAL;
        }
    }
    return VB_OK;
}

int vbj_cl_upload(vb_ctx *ctx, vbj_engine *e, vbj_clbuf *b, const void *data, size_t bytes,
                  const char *what)
{
    int rc = vbj_clbuf_reserve(ctx, e, b, bytes);
    if (rc)
        return rc;
    return vbg_check(ctx,
                     clEnqueueWriteBuffer(vbg_runtime_queue(e->rt), b->mem, CL_TRUE, 0, bytes,
                                          data, 0, NULL, NULL),
                     what)
               ? VB_EDEVICE
               : VB_OK;
}

int vbj_cl_upload_seeds(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s)
{
    size_t stride = s->dim == 3 ? 4 : 2;
    int32_t *packed = calloc(s->k * stride, sizeof *packed);
    if (!packed)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed upload: out of memory");
    for (size_t i = 0; i < s->k; i++) {
        packed[stride * i] = s->x[i];
        packed[stride * i + 1] = s->y[i];
        if (stride == 4)
            packed[stride * i + 2] = s->z[i];
    }
    size_t bytes = s->k * stride * sizeof *packed;
    int rc = vbj_clbuf_reserve(ctx, e, &e->seeds, bytes);
    if (!rc)
        rc = vbg_check(ctx,
                       clEnqueueWriteBuffer(vbg_runtime_queue(e->rt), e->seeds.mem, CL_TRUE, 0,
                                            bytes, packed, 0, NULL, NULL),
                       "seed upload")
                 ? VB_EDEVICE
                 : VB_OK;
    int build = vbj_dist_build(s->dim, s->n);
    if (!rc && build != VBJ_JFA_DIST64) {
        /* The same 16.16 integers as floats or doubles (exact: below 2^24 or
         * 2^31 in magnitude). */
        size_t fbytes = build == VBJ_JFA_FLOAT ? bytes : 2 * bytes;
        void *wide = malloc(fbytes);
        if (!wide)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "seed upload: out of memory");
        for (size_t i = 0; !rc && i < s->k * stride; i++) {
            if (build == VBJ_JFA_FLOAT)
                ((float *)wide)[i] = (float)packed[i];
            else
                ((double *)wide)[i] = packed[i];
        }
        if (!rc)
            rc = vbj_clbuf_reserve(ctx, e, &e->seeds_fp, fbytes);
        if (!rc && vbg_check(ctx,
                             clEnqueueWriteBuffer(vbg_runtime_queue(e->rt), e->seeds_fp.mem,
                                                  CL_TRUE, 0, fbytes, wide, 0, NULL, NULL),
                             "seed upload"))
            rc = VB_EDEVICE;
        free(wide);
    }
    free(packed);
    return rc;
}

int vbj_cl_jfa_kernel_index(const vbj_seeds *s, int narrow, int kernel)
{
    return ((narrow ? VBJ_JFA_LABEL16 : 0) | vbj_dist_build(s->dim, s->n)) * VBJ_KJFA + kernel;
}

int vbj_cl_upload_pairs(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t f,
                        size_t *count, uint32_t *collisions)
{
    uint32_t *pairs = NULL;
    int rc = vbj_place(ctx, s, f, &pairs, count, collisions);
    if (rc)
        return rc;
    size_t bytes = 2 * *count * sizeof *pairs;
    rc = vbj_clbuf_reserve(ctx, e, &e->pairs, bytes);
    if (!rc && vbg_check(ctx,
                         clEnqueueWriteBuffer(vbg_runtime_queue(e->rt), e->pairs.mem, CL_TRUE, 0,
                                              bytes, pairs, 0, NULL, NULL),
                         "seed placement upload"))
        rc = VB_EDEVICE;
    free(pairs);
    return rc;
}

int vbj_cl_dense(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t f, size_t npairs,
                 int narrow, const uint32_t *steps, int nsteps, vbj_counts *counts, int *which)
{
    cl_uint q = s->n / f, fc = f, d = (cl_uint)s->dim;
    size_t cells = (size_t)q * q * (d == 3 ? q : 1), esize = narrow ? 2 : 4;
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    int rc;
    if ((rc = vbj_clbuf_reserve(ctx, e, &e->grid[0], cells * esize)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->grid[1], cells * esize)))
        return rc;
    cl_uint none = VBJ_NONE;
    if (vbg_check(ctx,
                  clEnqueueFillBuffer(queue, e->grid[0].mem, &none, esize, 0, cells * esize, 0,
                                      NULL, vbj_cl_event(e)),
                  "jfa clear"))
        return VB_EDEVICE;
    cl_kernel k;
    cl_uint np = (cl_uint)npairs;
    int dist = vbj_dist_build(s->dim, s->n);
    if ((rc = vbj_cl_kernel(ctx, e, vbj_cl_jfa_kernel_index(s, narrow, VBJ_K_PLACE), &k)))
        return rc;
    vbj_arg pa[] = {VBJ_ARG(e->grid[0].mem), VBJ_ARG(e->pairs.mem), VBJ_ARG(np)};
    size_t gp = npairs;
    if ((rc = vbj_cl_set_args(ctx, k, "jfa_place", 3, pa)) ||
        (rc = vbj_cl_launch(ctx, e, k, 1, &gp, "jfa_place")))
        return rc;
    counts->threads += npairs;
    if ((rc = vbj_cl_kernel(ctx, e,
                            vbj_cl_jfa_kernel_index(s, narrow, d == 3 ? VBJ_K_STEP3 : VBJ_K_STEP2), &k)))
        return rc;
    cl_mem seeds = dist == VBJ_JFA_DIST64 ? e->seeds.mem : e->seeds_fp.mem;
    int cur = 0;
    for (int t = 0; t < nsteps; t++) {
        /* A work-item owns a block of pixels spaced l apart; when q / l is
         * below the block side, some lie past the grid. */
        cl_uint l = steps[t];
        const uint32_t *b = d == 3 ? block3 : block2;
        vbj_arg a[] = {VBJ_ARG(e->grid[cur].mem), VBJ_ARG(e->grid[1 - cur].mem),
                       VBJ_ARG(seeds),            VBJ_ARG(e->seeds.mem),
                       VBJ_ARG(q),                VBJ_ARG(fc),
                       VBJ_ARG(l)};
        size_t g[3] = {items(q, l, b[0]), items(q, l, b[1]), d == 3 ? items(q, l, b[2]) : 1};
        if ((rc = vbj_cl_set_args(ctx, k, "jfa_step", 7, a)) ||
            (rc = vbj_cl_launch(ctx, e, k, (int)d, g, "jfa_step")))
            return rc;
        cur = 1 - cur;
        counts->steps++;
        counts->step_pixels += cells;
        counts->threads += (uint64_t)g[0] * g[1] * (d == 3 ? g[2] : 1);
    }
    *which = cur;
    return VB_OK;
}

int vbj_cl_count_labels(vb_ctx *ctx, vbj_engine *e, int dim, uint32_t n, cl_mem labels,
                        uint8_t *out)
{
    size_t pixels = (size_t)n * n * (dim == 3 ? n : 1);
    vbj_clbuf *nb = &e->tmp; /* free at this point of a run */
    cl_kernel k;
    cl_uint nn = n, dd = (cl_uint)dim;
    int rc;
    if ((rc = vbj_clbuf_reserve(ctx, e, nb, pixels)) ||
        (rc = vbj_cl_kernel(ctx, e, VBJ_K_COUNT, &k))) /* build 0 */
        return rc;
    vbj_arg a[] = {VBJ_ARG(labels), VBJ_ARG(nb->mem), VBJ_ARG(nn), VBJ_ARG(dd)};
    size_t g[3] = {n, n, dim == 3 ? n : 1};
    if ((rc = vbj_cl_set_args(ctx, k, "jfa_count_labels", 4, a)) ||
        (rc = vbj_cl_launch(ctx, e, k, 3, g, "jfa_count_labels")))
        return rc;
    if (vbg_check(ctx,
                  clEnqueueReadBuffer(vbg_runtime_queue(e->rt), nb->mem, CL_TRUE, 0, pixels,
                                      out, 0, NULL, NULL),
                  "label counts download"))
        return VB_EDEVICE;
    return VB_OK;
}

int vbj_cl_count_boundary(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, int narrow, cl_mem lab,
                          vbj_counts *counts)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    cl_uint zero = 0, nn = s->n, dd = (cl_uint)s->dim, total = 0;
    size_t blocks = (s->n + VBJ_BND_B - 1) / VBJ_BND_B;
    size_t g[3] = {s->n, s->dim == 3 ? s->n : blocks, s->dim == 3 ? blocks : 1};
    cl_kernel k;
    int rc;
    if ((rc = vbj_clbuf_reserve(ctx, e, &e->counter, 4)) ||
        (rc = vbj_cl_kernel(ctx, e, vbj_cl_jfa_kernel_index(s, narrow, VBJ_K_BOUNDARY), &k)))
        return rc;
    if (vbg_check(ctx,
                  clEnqueueFillBuffer(queue, e->counter.mem, &zero, sizeof zero, 0, 4, 0, NULL,
                                      vbj_cl_event(e)),
                  "boundary counter"))
        return VB_EDEVICE;
    vbj_arg a[] = {VBJ_ARG(lab), VBJ_ARG(e->counter.mem), VBJ_ARG(nn), VBJ_ARG(dd)};
    if ((rc = vbj_cl_set_args(ctx, k, "jfa_boundary", 4, a)) ||
        (rc = vbj_cl_launch(ctx, e, k, 3, g, "jfa_boundary")))
        return rc;
    if (vbg_check(ctx,
                  clEnqueueReadBuffer(queue, e->counter.mem, CL_TRUE, 0, 4, &total, 0, NULL,
                                      NULL),
                  "boundary counter read"))
        return VB_EDEVICE;
    counts->boundary = total;
    counts->threads += g[0] * g[1] * g[2];
    return VB_OK;
}

int vbj_cl_dense_run(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, vbj_variant v, int boundary,
                     vbj_result *out, cl_mem *result)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    double t0 = 1e3 * vb_now();
    size_t npairs;
    int rc, narrow = s->k < 0xffff;
    if ((rc = vbj_cl_upload_seeds(ctx, e, s)) ||
        (rc = vbj_cl_upload_pairs(ctx, e, s, 1, &npairs, &out->counts.collisions)))
        return rc;
    double t1 = 1e3 * vb_now();
    uint32_t steps[40];
    int ns = vbj_schedule(v, s->n, steps), which = 0;
    vbj_cl_record(e);
    rc = vbj_cl_dense(ctx, e, s, 1, npairs, narrow, steps, ns, &out->counts, &which);
    if (!rc && boundary)
        rc = vbj_cl_count_boundary(ctx, e, s, narrow, e->grid[which].mem, &out->counts);
    if (!rc && vbg_check(ctx, clFinish(queue), "jfa"))
        rc = VB_EDEVICE;
    double t2 = 1e3 * vb_now();
    out->ms_gpu = vbj_cl_recorded_ms(e);
    if (rc)
        return rc;
    out->ms_kernel = t2 - t1;
    out->ms_transfer = t1 - t0;
    *result = e->grid[which].mem;
    if (!narrow)
        return VB_OK;
    cl_kernel k;
    cl_uint count = (cl_uint)out->pixels;
    if ((rc = vbj_clbuf_reserve(ctx, e, &e->labels, out->pixels * 4)) ||
        (rc = vbj_cl_kernel(ctx, e, vbj_cl_jfa_kernel_index(s, 1, VBJ_K_WIDEN), &k)))
        return rc;
    vbj_arg a[] = {VBJ_ARG(e->grid[which].mem), VBJ_ARG(e->labels.mem), VBJ_ARG(count)};
    size_t g = out->pixels;
    if ((rc = vbj_cl_set_args(ctx, k, "jfa_widen", 3, a)) ||
        (rc = vbj_cl_launch(ctx, e, k, 1, &g, "jfa_widen")))
        return rc;
    if (vbg_check(ctx, clFinish(queue), "jfa widen"))
        return VB_EDEVICE;
    out->ms_fill = 1e3 * vb_now() - t2;
    *result = e->labels.mem;
    return VB_OK;
}

