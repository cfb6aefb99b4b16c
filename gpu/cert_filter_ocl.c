/* The certification filter on OpenCL (vbg_judge.h). */
#include "vbg_judge.h"

#include "vbg_buffer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct vbg_judge {
    vbg_runtime *rt;
    cl_command_queue queue;
    cl_kernel k;
    vbg_meter meter;          /* its buffers' bytes (vbg_judge_bytes_peak) */
    vbg_buf z, start, ids, cz; /* the filter of `serial` */
    uint64_t serial;
    vbg_buf quads, verdict;   /* room for their sizes' quadruples */
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

size_t vbg_judge_bytes_peak(const vbg_judge *j)
{
    return j ? j->meter.peak : 0;
}

void vbg_judge_close(vbg_judge *j)
{
    if (!j)
        return;
    vbg_buf *all[] = {&j->z, &j->start, &j->ids, &j->cz, &j->quads, &j->verdict};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        vbg_buf_release(&j->meter, all[k]);
    if (j->k)
        clReleaseKernel(j->k);
    if (j->queue)
        clReleaseCommandQueue(j->queue);
    free(j);
}

/* b made to hold host bytes p[0 .. size) (a new filter's arrays). */
static int upload(vb_ctx *ctx, vbg_judge *j, vbg_buf *b, const void *p, size_t size)
{
    vbg_buf_release(&j->meter, b);
    int rc = vbg_buf_ensure(ctx, j->rt, &j->meter, b, size, CL_MEM_READ_ONLY);
    if (rc == VB_OK && size)
        rc = vbg_check(ctx, clEnqueueWriteBuffer(j->queue, b->mem, CL_TRUE, 0, size, p, 0, NULL,
                                                 NULL),
                       "clEnqueueWriteBuffer (certification filter)");
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
    rc = vbg_buf_ensure(ctx, j->rt, &j->meter, &j->quads, n * 16, CL_MEM_READ_ONLY);
    if (rc == VB_OK)
        rc = vbg_buf_ensure(ctx, j->rt, &j->meter, &j->verdict, n, CL_MEM_WRITE_ONLY);
    if (rc != VB_OK)
        return rc;
    cl_int err = clEnqueueWriteBuffer(j->queue, j->quads.mem, CL_FALSE, 0, n * 16, q, 0, NULL,
                                      NULL);
    cl_uint nn = (cl_uint)n;
    cl_long rmax = f->g.rmax;
    cl_kernel k = j->k;
    int a = 0;
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->z.mem);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->start.mem);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->ids.mem);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->cz.mem);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.ox);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.oy);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.oz);
    err |= clSetKernelArg(k, a++, sizeof(double), &f->g.inv);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.nx);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.ny);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &f->g.nz);
    err |= clSetKernelArg(k, a++, sizeof(cl_long), &rmax);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->quads.mem);
    err |= clSetKernelArg(k, a++, sizeof(cl_uint), &nn);
    err |= clSetKernelArg(k, a++, sizeof(cl_mem), &j->verdict.mem);
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
        rc = vbg_check(ctx, clEnqueueReadBuffer(j->queue, j->verdict.mem, CL_TRUE, 0, n, verdict, 0,
                                                NULL, NULL),
                       "clEnqueueReadBuffer (verdicts)");
    /* On an error the quadruples' write (non-blocking, from q) may still be
     * pending: wait for it, so that nothing reads q once the caller has
     * judged the list on the host and freed it. */
    if (rc != VB_OK)
        clFinish(j->queue);
    return rc;
}

/* What a cover backend holds of its judge. */
typedef struct judge_slot {
    vbg_judge *j;   /* NULL: err says why */
    char err[256];
} judge_slot;

static int cover_judge(vb_ctx *ctx, vb_cover_backend *be, const vb_cert_filter *f,
                       const uint32_t (*q)[4], size_t n, uint8_t *verdict)
{
    judge_slot *js = be->judge_state;
    if (!js->j)
        return vb_error(ctx, VB_EDEVICE, NULL, 0, "%s", js->err);
    int rc = vbg_judge_run(ctx, js->j, f, q, n, verdict);
    be->judge_bytes_peak = vbg_judge_bytes_peak(js->j);
    return rc;
}

/* vb_cover_backend.judge_close. */
static void judge_detach(vb_cover_backend *be)
{
    judge_slot *js = be->judge_state;
    if (js)
        vbg_judge_close(js->j);
    free(js);
    be->judge_state = NULL;
    be->judge = NULL;
    be->judge_close = NULL;
}

void vbg_judge_attach(vb_ctx *ctx, vbg_runtime *rt, vb_cover_backend *be)
{
    int mode = vb_cert_filter_mode();
    if (!(mode == 1 || (mode < 0 && vbg_runtime_is_gpu(rt))))
        return;
    judge_slot *js = calloc(1, sizeof *js);
    vb_ctx *tctx = NULL;
    if (!js || vb_open_worker(&tctx, ctx) != VB_OK) {
        free(js);
        return;
    }
    if (vbg_judge_open(tctx, rt, &js->j) != VB_OK)
        snprintf(js->err, sizeof js->err, "%s", vb_errmsg(tctx));
    vb_close(tctx);
    be->judge_state = js;
    be->judge = cover_judge;
    be->judge_close = judge_detach;
}
