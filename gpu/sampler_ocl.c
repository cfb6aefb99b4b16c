/* Host side of the sampling kernels: buffers, launches, read-back. Stage
 * times are wall clock around each stage with the queue drained, so they
 * include launch overhead. Every host-to-device write is blocking: a batch
 * that fails part way returns with nothing queued that still reads host
 * memory its caller is about to free (a queued upload of freed batch
 * buffers crashed `vertices` when a later call failed).
 *
 * Device buffers (each made 1/4 larger than asked, kept and grown between
 * batches, counted by a meter: vbg_buffer.h, --stats device_bytes_peak), for
 * a part of B bases with S samples a side: the bases, their bisectors and
 * tile lists (part_bytes), the ray colours 4 x 6 S^2 B, the parameters, and
 * the candidates (sizeof(vbs_cand) each, first 2^16, grown to what a part
 * found): the inputs of a part within half the device layer's budget (a
 * part over it is halved), the candidates within the other half (a part
 * that finds more is halved and run again). */
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbg_buffer.h"
#include "vbg_sampler.h"

typedef struct ocl_state {
    vbg_runtime *rt;
    cl_kernel env, vert;
    vbg_buf bases, bis, off, idx, colours, params, cand, counters;
    vbs_cand *host_cand;
    size_t host_cap;
    size_t cand_cap;          /* candidate slots on the device */
    size_t budget;            /* device bytes a batch may hold (vbg_runtime_memory_budget) */
    vbg_meter meter;          /* device bytes held now and at most */
} ocl_state;

/* A part of a batch whose candidates would not fit the budget: split it. */
#define OCL_SPLIT (-1)

/* Makes sure buffer b holds `need` bytes (keeps the old one when it does;
 * a new one gets a quarter of slack). */
static int ensure(vb_ctx *ctx, ocl_state *st, vbg_buf *b, size_t need, cl_mem_flags flags)
{
    if (b->mem && b->size >= need)
        return VB_OK;
    return vbg_buf_ensure(ctx, st->rt, &st->meter, b, need + need / 4, flags);
}

static int buf_write(vb_ctx *ctx, ocl_state *st, vbg_buf *b, const void *src, size_t n)
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

/* Runs one part of a batch (all of it when it fits the budget). OCL_SPLIT,
 * with nothing added to out, when its candidates would take more than half
 * the budget and it has more than one base. */
static int run_part(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
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
    if (!st->cand_cap) {
        /* A first guess, within half the budget with ensure's slack. */
        size_t fit = st->budget / 2 / sizeof(vbs_cand) * 4 / 5;
        st->cand_cap = fit < ((size_t)1 << 16) ? (fit ? fit : 1) : (size_t)1 << 16;
    }
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
        /* More candidates than slots: grow and run the stage again, or
         * split the part when they would not fit half the budget. */
        if (b->nbases > 1 &&
            ((size_t)counters[0] + counters[0] / 2) * sizeof(vbs_cand) * 5 / 4 > st->budget / 2)
            return OCL_SPLIT;
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

/* Device bytes of bases [k0, k1) of b without their candidates: inputs and
 * ray colours, with ensure's quarter of slack. */
static size_t part_bytes(const vb_sampler_batch *b, size_t k0, size_t k1)
{
    size_t nt = (b->ntile_off - 1) / (b->nbases ? b->nbases : 1);
    size_t S = b->params.samples;
    const vbs_base *f = &b->bases[k0], *l = &b->bases[k1 - 1];
    size_t nbis = l->bis_start + l->bis_count - f->bis_start;
    size_t nidx = b->tile_off[k1 * nt] - b->tile_off[k0 * nt];
    size_t bytes = (k1 - k0) * sizeof *b->bases + nbis * sizeof *b->bis +
                   ((k1 - k0) * nt + 1 + nidx) * sizeof(uint32_t) +
                   6 * S * S * (k1 - k0) * sizeof(cl_uint);
    return bytes + bytes / 4;
}

/* Bases [k0, k1) of b as a batch of their own, offsets rebased (the
 * arrays are freed by part_free). */
typedef struct part {
    vb_sampler_batch b;
    vbs_base *bases;
    uint32_t *off, *idx;
} part;

static int part_make(const vb_sampler_batch *b, size_t k0, size_t k1, part *pt)
{
    memset(pt, 0, sizeof *pt);
    size_t nt = (b->ntile_off - 1) / b->nbases, n = k1 - k0;
    uint32_t bis0 = b->bases[k0].bis_start, idx0 = b->tile_off[k0 * nt];
    const vbs_base *l = &b->bases[k1 - 1];
    size_t nbis = l->bis_start + l->bis_count - bis0, nidx = b->tile_off[k1 * nt] - idx0;
    pt->bases = malloc(n * sizeof *pt->bases);
    pt->off = malloc((n * nt + 1) * sizeof *pt->off);
    pt->idx = malloc((nidx ? nidx : 1) * sizeof *pt->idx);
    if (!pt->bases || !pt->off || !pt->idx)
        return VB_ENOMEM;
    for (size_t k = 0; k < n; k++) {
        pt->bases[k] = b->bases[k0 + k];
        pt->bases[k].bis_start -= bis0;
        pt->bases[k].tile_start = (uint32_t)(k * nt);
    }
    for (size_t k = 0; k <= n * nt; k++)
        pt->off[k] = b->tile_off[k0 * nt + k] - idx0;
    for (size_t k = 0; k < nidx; k++)
        pt->idx[k] = b->tile_idx[idx0 + k] - bis0;
    vb_sampler_batch sub = {n, pt->bases, nbis, b->bis + bis0, n * nt + 1, pt->off, nidx,
                            pt->idx, b->params};
    pt->b = sub;
    return VB_OK;
}

static void part_free(part *pt)
{
    free(pt->bases);
    free(pt->off);
    free(pt->idx);
}

/* Bases [k0, k1) of b, halved until each part fits the device budget; the
 * candidates do not depend on how the bases are grouped. */
static int run_range(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b, size_t k0,
                     size_t k1, vb_sampler_batch_out *out)
{
    ocl_state *st = be->state;
    if (k1 - k0 > 1 && part_bytes(b, k0, k1) > st->budget / 2) {
        size_t mid = k0 + (k1 - k0) / 2;
        int rc = run_range(ctx, be, b, k0, mid, out);
        return rc ? rc : run_range(ctx, be, b, mid, k1, out);
    }
    int rc;
    if (k0 == 0 && k1 == b->nbases) {
        rc = run_part(ctx, be, b, out);
    } else {
        part pt;
        rc = part_make(b, k0, k1, &pt) ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (batch)")
                                        : run_part(ctx, be, &pt.b, out);
        part_free(&pt);
    }
    if (rc == OCL_SPLIT) {
        size_t mid = k0 + (k1 - k0) / 2;
        rc = run_range(ctx, be, b, k0, mid, out);
        return rc ? rc : run_range(ctx, be, b, mid, k1, out);
    }
    return rc;
}

static int ocl_run_batch(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
                         vb_sampler_batch_out *out)
{
    ocl_state *st = be->state;
    int rc = b->nbases ? run_range(ctx, be, b, 0, b->nbases, out) : VB_OK;
    be->device_bytes_peak = st->meter.peak;
    return rc;
}

static void ocl_close(vb_sampler_backend *be)
{
    ocl_state *st = be->state;
    if (st) {
        vbg_buf_release(&st->meter, &st->bases);
        vbg_buf_release(&st->meter, &st->bis);
        vbg_buf_release(&st->meter, &st->off);
        vbg_buf_release(&st->meter, &st->idx);
        vbg_buf_release(&st->meter, &st->colours);
        vbg_buf_release(&st->meter, &st->params);
        vbg_buf_release(&st->meter, &st->cand);
        vbg_buf_release(&st->meter, &st->counters);
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
    st->budget = vbg_runtime_memory_budget(rt);
    be->run_batch = ocl_run_batch;
    *out = be;
    return VB_OK;
}
