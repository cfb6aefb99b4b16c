/* Host side of the cover kernel (gpu/cover.cl): the shared input uploaded
 * once per run, per-work-item arenas sized from the device's memory, one
 * launch per batch of cells, read-back of the per-cell results and of the
 * quadruples. Every error path releases what it made and reports
 * VB_EDEVICE; the caller falls back to the host. */
#include <stdlib.h>
#include <string.h>

#include "vbg_cover.h"

typedef struct cov_buf {
    cl_mem mem;
    size_t size;
} cov_buf;

typedef struct cov_state {
    vbg_runtime *rt;
    cl_kernel k;
    int wg;                  /* 1: one work-group of 32 per cell (vbq_cover_wg) */
    cov_buf x, y, z, r, box, rmax, ids;
    cov_buf cells, nb, lab, st, q, outs, qout, counters;
    size_t workers;          /* arena slices: work-items, or work-groups with wg */
    uint32_t nb_cap, lab_cap, st_cap, q_cap;
    size_t qout_cap;         /* quadruples the output array holds */
    uint32_t *host_q;        /* read-back of the quadruples */
    size_t host_q_cap;
    vbq_env env;             /* scalars of the uploaded input */
} cov_state;

/* Arena capacities per slice: enough for almost every cell of the proteins
 * and the capsid measured (nb p99 below 10^4 there); the rest are covered on
 * the host with growing arenas. A group's slice (GPUs) is larger: there are
 * few groups. */
#define COV_NB 2048u
#define COV_LAB 8192u
#define COV_ST 256u
#define COV_Q 256u
#define COV_WG_NB 8192u
#define COV_WG_LAB 32768u
#define COV_WG_Q 512u
#define COV_WG 32u

static void release(cov_buf *b)
{
    if (b->mem)
        clReleaseMemObject(b->mem);
    b->mem = NULL;
    b->size = 0;
}

/* Makes b hold at least `need` bytes (its contents are lost when it grows). */
static int ensure(vb_ctx *ctx, cov_state *s, cov_buf *b, size_t need, cl_mem_flags flags)
{
    if (need == 0)
        need = 16;
    if (b->mem && b->size >= need)
        return VB_OK;
    release(b);
    cl_int err;
    b->mem = clCreateBuffer(vbg_runtime_context(s->rt), flags, need, NULL, &err);
    if (err != CL_SUCCESS || !b->mem) {
        b->mem = NULL;
        return vbg_check(ctx, err != CL_SUCCESS ? err : CL_OUT_OF_RESOURCES, "clCreateBuffer");
    }
    b->size = need;
    return VB_OK;
}

static int upload(vb_ctx *ctx, cov_state *s, cov_buf *b, const void *src, size_t bytes)
{
    int rc = ensure(ctx, s, b, bytes, CL_MEM_READ_ONLY);
    if (rc != VB_OK || bytes == 0)
        return rc;
    return vbg_check(ctx,
                     clEnqueueWriteBuffer(vbg_runtime_queue(s->rt), b->mem, CL_TRUE, 0, bytes,
                                          src, 0, NULL, NULL),
                     "clEnqueueWriteBuffer");
}

static int cov_begin(vb_ctx *ctx, vb_cover_backend *be, const vbq_env *env, size_t n)
{
    cov_state *s = be->state;
    s->env = *env;
    size_t nodes = 2 * (size_t)env->first;
    int rc = upload(ctx, s, &s->x, env->x, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->y, env->y, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->z, env->z, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->r, env->r, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->box, env->box, 6 * nodes * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->rmax, env->rmax, nodes * sizeof(double));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->ids, env->ids, (size_t)env->m * sizeof(uint32_t));
    size_t w = s->workers;
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->nb, w * s->nb_cap * sizeof(vbq_nb), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->lab, w * s->lab_cap * sizeof(uint32_t), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->st, (s->wg ? 1 : w) * s->st_cap * sizeof(vbq_frame),
                    CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->q, w * 4 * s->q_cap * sizeof(uint32_t), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->counters, 2 * sizeof(cl_uint), CL_MEM_READ_WRITE);
    return rc;
}

static int set_arg(vb_ctx *ctx, cl_kernel k, cl_uint i, size_t size, const void *v)
{
    return vbg_check(ctx, clSetKernelArg(k, i, size, v), "clSetKernelArg");
}

static int cov_run(vb_ctx *ctx, vb_cover_backend *be, const uint32_t *cells, size_t ncells,
                   vbq_cell_out *out, const uint32_t **quads)
{
    cov_state *s = be->state;
    cl_command_queue q = vbg_runtime_queue(s->rt);
    *quads = NULL;
    if (ncells == 0)
        return VB_OK;
    if (ncells > UINT32_MAX)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "cover batch too large");
    /* About 10 quadruples per cell on proteins: room for 24, and cells
     * beyond it are marked and covered on the host. */
    size_t want = 24 * ncells;
    if (want > s->qout_cap)
        s->qout_cap = want;
    int rc = upload(ctx, s, &s->cells, cells, ncells * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->outs, ncells * sizeof(vbq_cell_out), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->qout, 4 * s->qout_cap * sizeof(uint32_t), CL_MEM_READ_WRITE);
    cl_uint zero[2] = {0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueWriteBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof zero, zero, 0,
                                            NULL, NULL),
                       "clEnqueueWriteBuffer");
    const vbq_env *e = &s->env;
    cl_uint nc = (cl_uint)ncells, qcap = (cl_uint)s->qout_cap;
    cl_uint nbc = s->nb_cap, labc = s->lab_cap, stc = s->st_cap, qc = s->q_cap;
    cl_uint a = 0;
    cl_kernel k = s->k;
    if (rc == VB_OK)
        rc = set_arg(ctx, k, a++, sizeof(cl_mem), &s->x.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->y.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->z.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->r.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->box.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->rmax.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->ids.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->first) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->m) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->rmax_all) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->near) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->T) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->min_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->max_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->enum_max) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->cells.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->nb.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->lab.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->st.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->q.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nbc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &labc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &stc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->outs.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->qout.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qcap) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->counters.mem)
                 ? VB_EDEVICE
                 : VB_OK;
    size_t local, global;
    if (s->wg) {
        local = COV_WG;
        global = (s->workers < ncells ? s->workers : ncells) * COV_WG;
    } else {
        local = 64;
        global = s->workers < ncells ? s->workers : ncells;
        global = (global + local - 1) / local * local;
        if (global > s->workers)
            global = s->workers; /* a multiple of local by construction */
    }
    if (rc == VB_OK)
        rc = vbg_check(ctx, clEnqueueNDRangeKernel(q, k, 1, NULL, &global, &local, 0, NULL, NULL),
                       "cover kernel");
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->outs.mem, CL_TRUE, 0,
                                           ncells * sizeof(vbq_cell_out), out, 0, NULL, NULL),
                       "cover kernel");
    cl_uint counters[2] = {0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof counters,
                                           counters, 0, NULL, NULL),
                       "read counters");
    size_t nq = counters[1] < s->qout_cap ? counters[1] : s->qout_cap;
    if (rc == VB_OK && nq > s->host_q_cap) {
        uint32_t *h = realloc(s->host_q, 4 * nq * sizeof *h);
        if (!h)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (quadruples)");
        else {
            s->host_q = h;
            s->host_q_cap = nq;
        }
    }
    if (rc == VB_OK && nq)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->qout.mem, CL_TRUE, 0, 4 * nq * sizeof(uint32_t),
                                           s->host_q, 0, NULL, NULL),
                       "read quadruples");
    if (rc != VB_OK) {
        /* Nothing half-done may reach the caller. */
        clFinish(q);
        return rc;
    }
    /* The next batch gets room for what this one needed. */
    if (counters[1] > s->qout_cap)
        s->qout_cap = counters[1] + counters[1] / 4;
    *quads = s->host_q;
    return VB_OK;
}

static void cov_close(vb_cover_backend *be)
{
    if (!be)
        return;
    cov_state *s = be->state;
    if (s) {
        cov_buf *all[] = {&s->x,   &s->y,  &s->z,    &s->r,    &s->box,  &s->rmax,
                          &s->ids, &s->cells, &s->nb, &s->lab, &s->st,  &s->q,
                          &s->outs, &s->qout, &s->counters};
        for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
            release(all[k]);
        if (s->k)
            clReleaseKernel(s->k);
        free(s->host_q);
        free(s);
    }
    free(be);
}

int vbg_cover_open(vb_ctx *ctx, vbg_runtime *rt, vb_cover_backend **out)
{
    *out = NULL;
    vb_cover_backend *be = calloc(1, sizeof *be);
    cov_state *s = calloc(1, sizeof *s);
    if (!be || !s) {
        free(be);
        free(s);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    be->state = s;
    be->close = cov_close;
    s->rt = rt;
    /* GPUs run a group per cell; a CPU device (PoCL) a work-item per cell,
     * which its compiler turns into plain loops. VORBALL_COVER_KERNEL=item|group
     * overrides (tests run both on PoCL). */
    const char *kn = getenv("VORBALL_COVER_KERNEL");
    s->wg = kn && strcmp(kn, "group") == 0 ? 1 : kn && strcmp(kn, "item") == 0 ? 0
                                                : vbg_runtime_is_gpu(rt);
    s->nb_cap = s->wg ? COV_WG_NB : COV_NB;
    s->lab_cap = s->wg ? COV_WG_LAB : COV_LAB;
    s->st_cap = COV_ST;
    s->q_cap = s->wg ? COV_WG_Q : COV_Q;
    cl_program prog;
    int rc = vbg_program_get(ctx, rt, s->wg ? "cover_wg.cl" : "cover.cl", NULL, &prog);
    cl_int err = CL_SUCCESS;
    const char *kname = s->wg ? "vbq_cover_wg" : "vbq_cover_kernel";
    if (rc == VB_OK) {
        s->k = clCreateKernel(prog, kname, &err);
        rc = vbg_check(ctx, err, kname);
    }
    /* Work-items: as many as the device keeps busy, within an eighth of its
     * memory for the arenas (and never above what a batch can use). */
    cl_device_id dev = vbg_runtime_device(rt);
    cl_ulong mem = 0;
    cl_uint units = 1;
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clGetDeviceInfo(dev, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL),
                       "clGetDeviceInfo");
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clGetDeviceInfo(dev, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units, &units,
                                       NULL),
                       "clGetDeviceInfo");
    if (rc != VB_OK) {
        cov_close(be);
        return rc;
    }
    size_t arena = (size_t)s->nb_cap * sizeof(vbq_nb) + (size_t)s->lab_cap * 4 +
                   (s->wg ? 0 : (size_t)s->st_cap * sizeof(vbq_frame)) + (size_t)s->q_cap * 16;
    size_t want = s->wg ? (size_t)units * 16
                        : (vbg_runtime_is_gpu(rt) ? (size_t)units * 512 : (size_t)units * 64);
    size_t fit = (size_t)(mem / 8) / arena;
    want = want < fit ? want : fit;
    if (!s->wg)
        want = want / 64 * 64;
    if (want < (s->wg ? 1u : 64u))
        want = s->wg ? 1u : 64u;
    /* VORBALL_COVER_SLICES overrides the count (measurements). */
    const char *ws = getenv("VORBALL_COVER_SLICES");
    if (ws && atol(ws) > 0)
        want = (size_t)atol(ws);
    s->workers = want;
    be->name = "opencl";
    snprintf(be->device, sizeof be->device, "%s", vbg_runtime_device_name(rt));
    be->batch_cells = vbg_runtime_is_gpu(rt) ? 1u << 18 : 1u << 14;
    be->begin = cov_begin;
    be->run = cov_run;
    *out = be;
    return VB_OK;
}
