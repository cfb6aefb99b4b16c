/* Host side of gpu/channel_walls.cl: the pore verdict's rasters
 * (core/discrete/vbc_walls.h) on the OpenCL device of the channel pipe,
 * on a queue of their own (the pore stage of one frame runs while the
 * next frame's masks fill the pipe's queue). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_channel_gpu.h"
#include "vbc_walls.h"

struct vbc_walls_gpu {
    vbc_walls_engine engine;
    vbg_runtime *rt;
    cl_command_queue q;
    pthread_mutex_t lock;
    cl_kernel k;
    cl_mem atoms, start, planes, half, word0, blocked, unsure;
    size_t atoms_cap, start_cap, planes_cap, half_cap, word0_cap, blocked_cap, unsure_cap;
};

/* The buffers of one call, filled; the kernel launched; the words read. */
static cl_int raster(vbc_walls_gpu *W, const vbc_walls_input *in, vbc_walls_raster *out)
{
    size_t words = in->word0[in->nplanes];
    cl_mem *bufs[] = {&W->atoms, &W->start, &W->planes, &W->half, &W->word0, &W->blocked,
                      &W->unsure};
    size_t *caps[] = {&W->atoms_cap, &W->start_cap, &W->planes_cap, &W->half_cap,
                      &W->word0_cap, &W->blocked_cap, &W->unsure_cap};
    size_t need[] = {4 * in->natoms, in->ncells + 1, 4 * in->nplanes, in->nplanes,
                     in->nplanes + 1, words, words};
    size_t size[] = {sizeof(cl_float), sizeof(cl_ulong), sizeof(cl_float), sizeof(cl_int),
                     sizeof(cl_ulong), sizeof(cl_uint), sizeof(cl_uint)};
    const void *src[] = {in->atoms, in->start, in->planes, in->half, in->word0};
    cl_int err = CL_SUCCESS;
    for (int i = 0; i < 7 && err == CL_SUCCESS; i++)
        err = vbc_gpu_buffer_fit(W->rt, bufs[i], caps[i], need[i], size[i]);
    for (int i = 0; i < 5 && err == CL_SUCCESS; i++)
        err = clEnqueueWriteBuffer(W->q, *bufs[i], CL_FALSE, 0, need[i] * size[i], src[i], 0, NULL,
                                   NULL);
    cl_int dim[3] = {in->dim[0], in->dim[1], in->dim[2]};
    cl_float4 a = {{in->a[0], in->a[1], in->a[2], 0.0f}}, b = {{in->b[0], in->b[1], in->b[2], 0.0f}};
    cl_uint np = (cl_uint)in->nplanes;
    cl_uint k = 0;
    err |= clSetKernelArg(W->k, k++, sizeof W->atoms, &W->atoms);
    err |= clSetKernelArg(W->k, k++, sizeof W->start, &W->start);
    for (int d = 0; d < 3; d++)
        err |= clSetKernelArg(W->k, k++, sizeof dim[d], &dim[d]);
    const cl_float f[5] = {in->inv_cell, in->reach, in->far2, in->bound, in->pixel};
    for (int i = 0; i < 5; i++)
        err |= clSetKernelArg(W->k, k++, sizeof f[i], &f[i]);
    err |= clSetKernelArg(W->k, k++, sizeof a, &a);
    err |= clSetKernelArg(W->k, k++, sizeof b, &b);
    err |= clSetKernelArg(W->k, k++, sizeof W->planes, &W->planes);
    err |= clSetKernelArg(W->k, k++, sizeof W->half, &W->half);
    err |= clSetKernelArg(W->k, k++, sizeof W->word0, &W->word0);
    err |= clSetKernelArg(W->k, k++, sizeof np, &np);
    err |= clSetKernelArg(W->k, k++, sizeof W->blocked, &W->blocked);
    err |= clSetKernelArg(W->k, k++, sizeof W->unsure, &W->unsure);
    size_t lsz = 64, gsz = (words + lsz - 1) / lsz * lsz;
    if (err == CL_SUCCESS)
        err = clEnqueueNDRangeKernel(W->q, W->k, 1, NULL, &gsz, &lsz, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(W->q, W->blocked, CL_FALSE, 0, words * sizeof(cl_uint),
                                  out->blocked, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(W->q, W->unsure, CL_FALSE, 0, words * sizeof(cl_uint),
                                  out->unsure, 0, NULL, NULL);
    /* The writes read the caller's arrays until the queue is done with them. */
    cl_int fin = clFinish(W->q);
    return err != CL_SUCCESS ? err : fin;
}

static int walls_raster(void *user, const vbc_walls_input *in, vbc_walls_raster *out)
{
    vbc_walls_gpu *W = user;
    if (in->nplanes == 0 || in->natoms == 0 || in->word0[in->nplanes] >= 0xffffffffu)
        return VB_EDEVICE;
    pthread_mutex_lock(&W->lock);
    cl_int err = raster(W, in, out);
    pthread_mutex_unlock(&W->lock);
    return err == CL_SUCCESS ? VB_OK : VB_EDEVICE;
}

int vbc_walls_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbc_walls_gpu **out)
{
    *out = NULL;
    vbc_walls_gpu *W = calloc(1, sizeof *W);
    if (!W)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "pore verdict rasters");
    W->rt = rt;
    pthread_mutex_init(&W->lock, NULL);
    cl_program prog;
    int rc = vbg_program_get(ctx, rt, "channel_walls.cl", NULL, &prog);
    cl_int err = CL_SUCCESS;
    if (rc == VB_OK) {
        W->k = clCreateKernel(prog, "vbc_walls_raster", &err);
        if (err == CL_SUCCESS)
            W->q = clCreateCommandQueue(vbg_runtime_context(rt), vbg_runtime_device(rt), 0, &err);
        rc = vbg_check(ctx, err, "pore verdict kernel");
    }
    if (rc != VB_OK) {
        vbc_walls_gpu_close(W);
        return rc;
    }
    W->engine.user = W;
    W->engine.raster = walls_raster;
    *out = W;
    return VB_OK;
}

const vbc_walls_engine *vbc_walls_gpu_engine(const vbc_walls_gpu *W)
{
    return W ? &W->engine : NULL;
}

void vbc_walls_gpu_close(vbc_walls_gpu *W)
{
    if (!W)
        return;
    cl_mem bufs[] = {W->atoms, W->start, W->planes, W->half, W->word0, W->blocked, W->unsure};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        if (bufs[i])
            clReleaseMemObject(bufs[i]);
    if (W->k)
        clReleaseKernel(W->k);
    if (W->q)
        clReleaseCommandQueue(W->q);
    pthread_mutex_destroy(&W->lock);
    free(W);
}
