/* Host side of the sampling kernels: buffers, launches, read-back. Stage
 * times are wall clock around each stage with the queue drained, so they
 * include launch overhead. Every host-to-device write is blocking: a batch
 * that fails part way returns with nothing queued that still reads host
 * memory its caller is about to free (a queued upload of freed batch
 * buffers crashed `vertices` when a later call failed). */
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbg_sampler.h"

typedef struct ocl_buf {
    cl_mem mem;
    size_t size;
} ocl_buf;

typedef struct ocl_state {
    vbg_runtime *rt;
    cl_kernel env, vert;
    ocl_buf bases, bis, off, idx, colours, params, cand, counters;
    vbs_cand *host_cand;
    size_t host_cap;
    size_t cand_cap;          /* candidate slots on the device */
} ocl_state;

/* Makes sure buffer b holds `need` bytes (keeps the old one when it does). */
static int ensure(vb_ctx *ctx, ocl_state *st, ocl_buf *b, size_t need, cl_mem_flags flags)
{
    if (need == 0)
        need = 16;
    if (b->mem && b->size >= need)
        return VB_OK;
    if (b->mem)
        clReleaseMemObject(b->mem);
    size_t sz = need + need / 4;
    cl_int err;
    b->mem = clCreateBuffer(vbg_runtime_context(st->rt), flags, sz, NULL, &err);
    b->size = b->mem ? sz : 0;
    return vbg_check(ctx, err, "clCreateBuffer");
}

static int buf_write(vb_ctx *ctx, ocl_state *st, ocl_buf *b, const void *src, size_t n)
{
    if (ensure(ctx, st, b, n, CL_MEM_READ_ONLY))
        return VB_EDEVICE;
    if (n == 0)
        return VB_OK;
    return vbg_check(ctx,
                     clEnqueueWriteBuffer(vbg_runtime_queue(st->rt), b->mem, CL_TRUE, 0, n, src,
                                          0, NULL, NULL),
                     "clEnqueueWriteBuffer");
}

static int launch(vb_ctx *ctx, ocl_state *st, cl_kernel k, size_t n, const char *what)
{
    if (n == 0)
        return VB_OK;
    size_t local = 64, global = (n + local - 1) / local * local;
    return vbg_check(ctx,
                     clEnqueueNDRangeKernel(vbg_runtime_queue(st->rt), k, 1, NULL, &global,
                                            &local, 0, NULL, NULL),
                     what);
}

static int set_args(vb_ctx *ctx, cl_kernel k, int n, const size_t *sizes, const void **vals)
{
    for (int i = 0; i < n; i++)
        if (vbg_check(ctx, clSetKernelArg(k, (cl_uint)i, sizes[i], vals[i]), "clSetKernelArg"))
            return VB_EDEVICE;
    return VB_OK;
}

static int ocl_run_batch(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
                         vb_sampler_batch_out *out)
{
    ocl_state *st = be->state;
    cl_command_queue q = vbg_runtime_queue(st->rt);
    const vbs_params *p = &b->params;
    cl_uint S = p->samples, T = p->tiles, nb = (cl_uint)b->nbases;
    size_t rays = 6u * (size_t)S * S * b->nbases;
    size_t cells = 6u * (size_t)(S - 1) * (S - 1) * b->nbases;
    double t0 = vb_now();
    cl_uint zero[2] = {0, 0};
    if (buf_write(ctx, st, &st->bases, b->bases, b->nbases * sizeof *b->bases) ||
        buf_write(ctx, st, &st->bis, b->bis, b->nbis * sizeof *b->bis) ||
        buf_write(ctx, st, &st->off, b->tile_off, b->ntile_off * sizeof *b->tile_off) ||
        buf_write(ctx, st, &st->idx, b->tile_idx, b->ntile_idx * sizeof *b->tile_idx) ||
        buf_write(ctx, st, &st->params, p, sizeof *p) ||
        ensure(ctx, st, &st->colours, rays * sizeof(cl_uint), CL_MEM_READ_WRITE) ||
        ensure(ctx, st, &st->counters, sizeof zero, CL_MEM_READ_WRITE))
        return VB_EDEVICE;
    if (!st->cand_cap)
        st->cand_cap = 1u << 16;
    if (ensure(ctx, st, &st->cand, st->cand_cap * sizeof(vbs_cand), CL_MEM_READ_WRITE) ||
        vbg_check(ctx, clFinish(q), "upload"))
        return VB_EDEVICE;
    double t1 = vb_now();
    {
        const void *v[] = {&st->bases.mem, &st->bis.mem, &st->off.mem, &st->idx.mem,
                           &st->colours.mem, &S, &T, &nb};
        const size_t s[] = {sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem),
                            sizeof(cl_mem), sizeof S, sizeof T, sizeof nb};
        if (set_args(ctx, st->env, 8, s, v) ||
            launch(ctx, st, st->env, rays, "envelope kernel") ||
            vbg_check(ctx, clFinish(q), "envelope kernel"))
            return VB_EDEVICE;
    }
    double t2 = vb_now();
    cl_uint counters[2];
    for (;;) {
        cl_uint cap = (cl_uint)st->cand_cap;
        const void *v[] = {&st->bases.mem, &st->bis.mem, &st->off.mem, &st->idx.mem,
                           &st->colours.mem, &st->params.mem, &st->cand.mem,
                           &st->counters.mem, &cap, &nb};
        const size_t s[] = {sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem),
                            sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem),
                            sizeof cap, sizeof nb};
        if (vbg_check(ctx,
                      clEnqueueWriteBuffer(q, st->counters.mem, CL_TRUE, 0, sizeof zero, zero,
                                           0, NULL, NULL),
                      "clEnqueueWriteBuffer") ||
            set_args(ctx, st->vert, 10, s, v) ||
            launch(ctx, st, st->vert, cells, "vertices kernel") ||
            vbg_check(ctx,
                      clEnqueueReadBuffer(q, st->counters.mem, CL_TRUE, 0, sizeof counters,
                                          counters, 0, NULL, NULL),
                      "vertices kernel"))
            return VB_EDEVICE;
        if (counters[0] <= cap)
            break;
        /* More candidates than slots: grow and run the stage again. */
        st->cand_cap = (size_t)counters[0] + counters[0] / 2;
        if (ensure(ctx, st, &st->cand, st->cand_cap * sizeof(vbs_cand), CL_MEM_READ_WRITE))
            return VB_EDEVICE;
    }
    size_t n = counters[0];
    if (n > st->host_cap) {
        vbs_cand *h = realloc(st->host_cand, n * sizeof *h);
        if (!h)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (candidates)");
        st->host_cand = h;
        st->host_cap = n;
    }
    if (n && vbg_check(ctx,
                       clEnqueueReadBuffer(q, st->cand.mem, CL_TRUE, 0, n * sizeof(vbs_cand),
                                           st->host_cand, 0, NULL, NULL),
                       "read candidates"))
        return VB_EDEVICE;
    for (size_t k = 0; k < n; k++)
        if (vb_cand_vec_push(out->cand, st->host_cand + k))
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (candidates)");
    out->overflow += counters[1];
    double t3 = vb_now();
    out->times->upload += t1 - t0;
    out->times->envelope += t2 - t1;
    out->times->vertices += t3 - t2;
    return VB_OK;
}

static void release(ocl_buf *b)
{
    if (b->mem)
        clReleaseMemObject(b->mem);
    b->mem = NULL;
}

static void ocl_close(vb_sampler_backend *be)
{
    ocl_state *st = be->state;
    if (st) {
        release(&st->bases);
        release(&st->bis);
        release(&st->off);
        release(&st->idx);
        release(&st->colours);
        release(&st->params);
        release(&st->cand);
        release(&st->counters);
        if (st->env)
            clReleaseKernel(st->env);
        if (st->vert)
            clReleaseKernel(st->vert);
        free(st->host_cand);
        free(st);
    }
    free(be);
}

int vbg_sampler_open(vb_ctx *ctx, vbg_runtime *rt, vb_sampler_backend **out)
{
    *out = NULL;
    vb_sampler_backend *be = calloc(1, sizeof *be);
    ocl_state *st = calloc(1, sizeof *st);
    if (!be || !st) {
        free(be);
        free(st);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    be->state = st;
    be->close = ocl_close;
    st->rt = rt;
    cl_program pe, pv;
    cl_int err;
    int rc = vbg_program_get(ctx, rt, "sample_envelope.cl", NULL, &pe);
    if (rc == VB_OK)
        rc = vbg_program_get(ctx, rt, "vertices_newton.cl", NULL, &pv);
    if (rc == VB_OK) {
        st->env = clCreateKernel(pe, "vbs_envelope_kernel", &err);
        rc = vbg_check(ctx, err, "clCreateKernel(vbs_envelope_kernel)");
    }
    if (rc == VB_OK) {
        st->vert = clCreateKernel(pv, "vbs_vertices_kernel", &err);
        rc = vbg_check(ctx, err, "clCreateKernel(vbs_vertices_kernel)");
    }
    if (rc != VB_OK) {
        ocl_close(be);
        return rc;
    }
    be->name = "opencl";
    snprintf(be->device, sizeof be->device, "%s", vbg_runtime_device_name(rt));
    be->batch_rays = vb_sampler_batch_rays(vbg_runtime_is_gpu(rt));
    be->run_batch = ocl_run_batch;
    *out = be;
    return VB_OK;
}
