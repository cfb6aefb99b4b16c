/* The certification filter on OpenCL (vbg_judge.h). */
#include "vbg_judge.h"

#include <stdlib.h>
#include <string.h>

struct vbg_judge {
    vbg_runtime *rt;
    cl_command_queue queue;
    cl_kernel k;
    cl_mem z, start, ids, cz; /* the filter of `serial` */
    uint64_t serial;
    cl_mem quads, verdict;  /* room for cap quadruples */
    size_t cap;
};

int vbg_judge_open(vb_ctx *ctx, vbg_runtime *rt, vbg_judge **out)
{
    *out = NULL;
    vbg_judge *j = calloc(1, sizeof *j);
    if (!j)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    j->rt = rt;
    cl_program prog;
    cl_int err = CL_SUCCESS;
    int rc = vbg_program_get(ctx, rt, "cert_filter.cl", NULL, &prog);
    if (rc == VB_OK) {
        j->k = clCreateKernel(prog, "vbd_judge_kernel", &err);
        rc = vbg_check(ctx, err, "vbd_judge_kernel");
    }
    if (rc == VB_OK) {
        j->queue = clCreateCommandQueue(vbg_runtime_context(rt), vbg_runtime_device(rt), 0, &err);
        rc = vbg_check(ctx, err, "clCreateCommandQueue (certification filter)");
    }
    if (rc != VB_OK) {
        vbg_judge_close(j);
        return rc;
    }
    *out = j;
    return VB_OK;
}

static void release(cl_mem *m)
{
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
}

void vbg_judge_close(vbg_judge *j)
{
    if (!j)
        return;
    release(&j->z);
    release(&j->start);
    release(&j->ids);
    release(&j->cz);
    release(&j->quads);
    release(&j->verdict);
    if (j->k)
        clReleaseKernel(j->k);
    if (j->queue)
        clReleaseCommandQueue(j->queue);
    free(j);
}

/* A read-only buffer holding a copy of host bytes p[0 .. size). */
static int upload(vb_ctx *ctx, vbg_judge *j, cl_mem *m, const void *p, size_t size)
{
    cl_int err;
    release(m);
    *m = clCreateBuffer(vbg_runtime_context(j->rt), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                        size ? size : 1, (void *)p, &err);
    return vbg_check(ctx, err, "clCreateBuffer (certification filter)");
}

static int fit(vb_ctx *ctx, vbg_judge *j, size_t n)
{
    if (n <= j->cap)
        return VB_OK;
    release(&j->quads);
    release(&j->verdict);
    j->cap = 0;
    cl_int err;
    cl_context c = vbg_runtime_context(j->rt);
    j->quads = clCreateBuffer(c, CL_MEM_READ_ONLY, n * 16, NULL, &err);
    int rc = vbg_check(ctx, err, "clCreateBuffer (quadruples)");
    if (rc == VB_OK) {
        j->verdict = clCreateBuffer(c, CL_MEM_WRITE_ONLY, n, NULL, &err);
        rc = vbg_check(ctx, err, "clCreateBuffer (verdicts)");
    }
    if (rc == VB_OK)
        j->cap = n;
    return rc;
}

int vbg_judge_run(vb_ctx *ctx, vbg_judge *j, const vb_cert_filter *f, const uint32_t (*q)[4],
                  size_t n, uint8_t *verdict)
{
    if (n == 0)
        return VB_OK;
    if (n > 0xffffffffu)
        return vb_error(ctx, VB_EDEVICE, NULL, 0, "%zu quadruples in one list", n);
    int rc = VB_OK;
    if (j->serial != f->serial) {
        j->serial = 0;
        rc = upload(ctx, j, &j->z, f->z, 4 * f->n * sizeof *f->z);
        if (rc == VB_OK)
            rc = upload(ctx, j, &j->start, f->cell_start, (f->ncells + 1) * sizeof *f->cell_start);
        if (rc == VB_OK)
            rc = upload(ctx, j, &j->ids, f->cell_ids, f->n * sizeof *f->cell_ids);
        if (rc == VB_OK)
            rc = upload(ctx, j, &j->cz, f->cell_z, 4 * f->n * sizeof *f->cell_z);
        if (rc != VB_OK)
            return rc;
        j->serial = f->serial;
    }
    rc = fit(ctx, j, n);
    if (rc != VB_OK)
        return rc;
    cl_int err = clEnqueueWriteBuffer(j->queue, j->quads, CL_FALSE, 0, n * 16, q, 0, NULL, NULL);
    cl_uint nn = (cl_uint)n;
    cl_long rmax = f->g.rmax;
    cl_kernel k = j->k;
    int a = 0;
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->z);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->start);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->ids);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->cz);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.ox);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.oy);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.oz);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.inv);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.nx);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.ny);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.nz);
    err |= clSetKernelArg(k, a++, sizeof(cl_long), &rmax);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->quads);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &nn);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->verdict);
    rc = vbg_check(ctx, err, "certification filter arguments");
    /* Groups of 64 named, not left to the runtime: PoCL compiles a kernel
     * for each group size, which it would otherwise choose by n (1.3 s of
     * CPU for every new size on the 2-core machine). */
    size_t global = (n + 63) / 64 * 64, local = 64;
    if (rc == VB_OK)
        rc = vbg_check(ctx, clEnqueueNDRangeKernel(j->queue, k, 1, NULL, &global, &local, 0, NULL,
                                                   NULL),
                       "vbd_judge_kernel");
    if (rc == VB_OK)
        rc = vbg_check(ctx, clEnqueueReadBuffer(j->queue, j->verdict, CL_TRUE, 0, n, verdict, 0,
                                                NULL, NULL),
                       "clEnqueueReadBuffer (verdicts)");
    return rc;
}
