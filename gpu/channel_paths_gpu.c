/* Host side of gpu/channel_paths.cl: the channel graph's batch sweeps
 * (core/discrete/vbc_paths.h) on the OpenCL device of the channel pipe. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_channel_gpu.h"
#include "vbc_paths.h"

/* Rounds between two reads of the `changed` flag: 8, doubling up to 32
 * (frame 0 of adk_oplsaa: 24 and 144 rounds). Rounds after the fixed point
 * change nothing, so this only trades idle rounds for fewer waits. */
#define ROUNDS_FIRST_CHECK 8
#define ROUNDS_PER_CHECK 32

struct vbc_paths_gpu {
    vbc_paths_engine engine;
    vbg_runtime *rt;
    pthread_mutex_t lock;
    cl_kernel k_map, k_init, k_seed, k_round, k_pred;
    cl_mem map, v, clear, d0, d1, s0, s1, pred, src, changed;
    size_t map_cap, v_cap, clear_cap, d0_cap, d1_cap, s0_cap, s1_cap, pred_cap, src_cap; /* elements */
    cl_uint n;
    int nx, ny, nz;
};

static cl_int grow(vbc_paths_gpu *P, cl_mem *buf, size_t *cap, size_t need, size_t size, int *fresh)
{
    size_t before = *buf ? *cap : 0;
    cl_int err = vbc_gpu_buffer_fit(P->rt, buf, cap, need, size);
    if (fresh) /* a new buffer always has another (larger) capacity */
        *fresh = *cap != before;
    return err;
}

static cl_int launch(vbc_paths_gpu *P, cl_kernel k, size_t n)
{
    size_t lsz = 64, gsz = (n + lsz - 1) / lsz * lsz;
    return clEnqueueNDRangeKernel(vbg_runtime_queue(P->rt), k, 1, NULL, &gsz, &lsz, 0, NULL, NULL);
}

/* Sets map[v[t]] to t (set) or back to none for every position. */
static cl_int map_set(vbc_paths_gpu *P, cl_uint set)
{
    cl_int err = clSetKernelArg(P->k_map, 0, sizeof P->v, &P->v);
    err |= clSetKernelArg(P->k_map, 1, sizeof P->n, &P->n);
    err |= clSetKernelArg(P->k_map, 2, sizeof P->map, &P->map);
    err |= clSetKernelArg(P->k_map, 3, sizeof set, &set);
    return err == CL_SUCCESS ? launch(P, P->k_map, P->n) : err;
}

static cl_int upload(vbc_paths_gpu *P, const vbc_paths_graph *G)
{
    cl_command_queue q = vbg_runtime_queue(P->rt);
    size_t nv = vbc_grid_voxels(G->g);
    int fresh = 0;
    cl_int err = grow(P, &P->map, &P->map_cap, nv, sizeof(cl_uint), &fresh);
    if (err == CL_SUCCESS && fresh) { /* a new map: none everywhere, kept so between frames */
        cl_uint none = 0xffffffffu;
        err = clEnqueueFillBuffer(q, P->map, &none, sizeof none, 0, P->map_cap * sizeof(cl_uint), 0,
                                  NULL, NULL);
    }
    /* The per-position buffers: voxels, clearances, two distances, two
     * stamps, predecessors. */
    cl_mem *bufs[] = {&P->v, &P->clear, &P->d0, &P->d1, &P->s0, &P->s1, &P->pred};
    size_t *caps[] = {&P->v_cap, &P->clear_cap, &P->d0_cap, &P->d1_cap, &P->s0_cap, &P->s1_cap,
                      &P->pred_cap};
    for (int i = 0; i < 7 && err == CL_SUCCESS; i++)
        err = grow(P, bufs[i], caps[i], G->n, i >= 1 && i <= 3 ? sizeof(cl_double) : sizeof(cl_uint),
                   NULL);
    P->n = (cl_uint)G->n;
    P->nx = G->g->nx;
    P->ny = G->g->ny;
    P->nz = G->g->nz;
    if (err == CL_SUCCESS)
        err = clEnqueueWriteBuffer(q, P->v, CL_FALSE, 0, G->n * sizeof(cl_uint), G->v, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueWriteBuffer(q, P->clear, CL_FALSE, 0, G->n * sizeof(cl_double), G->clear, 0,
                                   NULL, NULL);
    if (err == CL_SUCCESS)
        err = map_set(P, 1);
    return err == CL_SUCCESS ? clFinish(q) : err;
}

static int paths_begin(void *user, const vbc_paths_graph *G)
{
    vbc_paths_gpu *P = user;
    if (G->n == 0 || G->n >= 0xffffffffu)
        return VB_EDEVICE;
    pthread_mutex_lock(&P->lock);
    if (upload(P, G) != CL_SUCCESS) {
        pthread_mutex_unlock(&P->lock);
        return VB_EDEVICE;
    }
    return VB_OK;
}

static void paths_end(void *user)
{
    vbc_paths_gpu *P = user;
    /* The map back to none for the next frame; a failure here leaves stale
     * positions, so the next frame builds a fresh map. */
    if (map_set(P, 0) != CL_SUCCESS || clFinish(vbg_runtime_queue(P->rt)) != CL_SUCCESS) {
        clReleaseMemObject(P->map);
        P->map = NULL;
        P->map_cap = 0;
    }
    pthread_mutex_unlock(&P->lock);
}

/* Sets the common arguments of the round and predecessor kernels. */
static cl_int graph_args(vbc_paths_gpu *P, cl_kernel k, cl_int weighted)
{
    cl_int a = 0, err = clSetKernelArg(k, a++, sizeof P->v, &P->v);
    err |= clSetKernelArg(k, a++, sizeof P->n, &P->n);
    err |= clSetKernelArg(k, a++, sizeof P->map, &P->map);
    err |= clSetKernelArg(k, a++, sizeof P->clear, &P->clear);
    err |= clSetKernelArg(k, a++, sizeof P->nx, &P->nx);
    err |= clSetKernelArg(k, a++, sizeof P->ny, &P->ny);
    err |= clSetKernelArg(k, a++, sizeof P->nz, &P->nz);
    err |= clSetKernelArg(k, a++, sizeof weighted, &weighted);
    return err;
}

static cl_int run_batch(vbc_paths_gpu *P, vbc_paths_batch *b)
{
    cl_command_queue q = vbg_runtime_queue(P->rt);
    cl_uint nsrc = (cl_uint)b->nsrc;
    cl_int weighted = b->weighted != 0;
    cl_int err = grow(P, &P->src, &P->src_cap, b->nsrc, sizeof(cl_uint), NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueWriteBuffer(q, P->src, CL_TRUE, 0, b->nsrc * sizeof(cl_uint), b->src, 0, NULL,
                                   NULL);
    err |= clSetKernelArg(P->k_init, 0, sizeof P->n, &P->n);
    err |= clSetKernelArg(P->k_init, 1, sizeof P->d0, &P->d0);
    err |= clSetKernelArg(P->k_init, 2, sizeof P->d1, &P->d1);
    err |= clSetKernelArg(P->k_init, 3, sizeof P->s0, &P->s0);
    err |= clSetKernelArg(P->k_init, 4, sizeof P->s1, &P->s1);
    err |= clSetKernelArg(P->k_seed, 0, sizeof P->src, &P->src);
    err |= clSetKernelArg(P->k_seed, 1, sizeof nsrc, &nsrc);
    err |= clSetKernelArg(P->k_seed, 2, sizeof P->d0, &P->d0);
    err |= clSetKernelArg(P->k_seed, 3, sizeof P->d1, &P->d1);
    err |= clSetKernelArg(P->k_seed, 4, sizeof P->s0, &P->s0);
    err |= clSetKernelArg(P->k_seed, 5, sizeof P->s1, &P->s1);
    err |= graph_args(P, P->k_round, weighted);
    err |= clSetKernelArg(P->k_round, 13, sizeof P->changed, &P->changed);
    if (err == CL_SUCCESS)
        err = launch(P, P->k_init, P->n);
    if (err == CL_SUCCESS)
        err = launch(P, P->k_seed, nsrc);
    cl_mem in = P->d0, out = P->d1, sprev = P->s0, snext = P->s1;
    cl_uint changed = 1;
    size_t rounds = 0;
    int group = ROUNDS_FIRST_CHECK;
    while (err == CL_SUCCESS && changed) {
        if (rounds > (size_t)P->n + ROUNDS_PER_CHECK)
            return CL_INVALID_VALUE; /* distances that never settle: a broken device */
        cl_uint zero = 0;
        err = clEnqueueFillBuffer(q, P->changed, &zero, sizeof zero, 0, sizeof zero, 0, NULL, NULL);
        for (int r = 0; r < group && err == CL_SUCCESS; r++) {
            cl_uint round = (cl_uint)++rounds;
            err = clSetKernelArg(P->k_round, 8, sizeof in, &in);
            err |= clSetKernelArg(P->k_round, 9, sizeof out, &out);
            err |= clSetKernelArg(P->k_round, 10, sizeof sprev, &sprev);
            err |= clSetKernelArg(P->k_round, 11, sizeof snext, &snext);
            err |= clSetKernelArg(P->k_round, 12, sizeof round, &round);
            if (err == CL_SUCCESS)
                err = launch(P, P->k_round, P->n);
            cl_mem t = in;
            in = out;
            out = t;
            t = sprev;
            sprev = snext;
            snext = t;
        }
        if (err == CL_SUCCESS)
            err = clEnqueueReadBuffer(q, P->changed, CL_TRUE, 0, sizeof changed, &changed, 0, NULL,
                                      NULL);
        group = 2 * group < ROUNDS_PER_CHECK ? 2 * group : ROUNDS_PER_CHECK;
    }
    b->rounds = rounds;
    /* `in` holds the last round's distances: the fixed point. */
    if (err == CL_SUCCESS) {
        err = graph_args(P, P->k_pred, weighted);
        err |= clSetKernelArg(P->k_pred, 8, sizeof in, &in);
        err |= clSetKernelArg(P->k_pred, 9, sizeof P->pred, &P->pred);
    }
    if (err == CL_SUCCESS)
        err = launch(P, P->k_pred, P->n);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(q, in, CL_FALSE, 0, (size_t)P->n * sizeof(cl_double), b->dist, 0,
                                  NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(q, P->pred, CL_TRUE, 0, (size_t)P->n * sizeof(cl_uint), b->pred, 0,
                                  NULL, NULL);
    return err;
}

static int paths_sweep(void *user, const vbc_paths_graph *G, vbc_paths_batch *b)
{
    (void)G;
    return run_batch(user, b) == CL_SUCCESS ? VB_OK : VB_EDEVICE;
}

int vbc_paths_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbc_paths_gpu **out)
{
    *out = NULL;
    vbc_paths_gpu *P = calloc(1, sizeof *P);
    if (!P)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel paths");
    P->rt = rt;
    pthread_mutex_init(&P->lock, NULL);
    P->engine = (vbc_paths_engine){P, paths_begin, paths_sweep, paths_end};
    cl_program prog;
    int rc = vbg_program_get(ctx, rt, "channel_paths.cl", NULL, &prog);
    if (rc != VB_OK) {
        vbc_paths_gpu_close(P);
        return rc;
    }
    static const char *const names[] = {"vbc_paths_map", "vbc_paths_init", "vbc_paths_seed",
                                        "vbc_paths_round", "vbc_paths_pred"};
    cl_kernel *ks[] = {&P->k_map, &P->k_init, &P->k_seed, &P->k_round, &P->k_pred};
    cl_int err = CL_SUCCESS;
    for (size_t i = 0; i < 5 && err == CL_SUCCESS; i++)
        *ks[i] = clCreateKernel(prog, names[i], &err);
    if (err == CL_SUCCESS)
        P->changed = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_WRITE, sizeof(cl_uint), NULL,
                                    &err);
    if ((rc = vbg_check(ctx, err, "channel path kernels")) != VB_OK) {
        vbc_paths_gpu_close(P);
        return rc;
    }
    *out = P;
    return VB_OK;
}

const vbc_paths_engine *vbc_paths_gpu_engine(const vbc_paths_gpu *P)
{
    return P ? &P->engine : NULL;
}

void vbc_paths_gpu_close(vbc_paths_gpu *P)
{
    if (!P)
        return;
    cl_kernel ks[] = {P->k_map, P->k_init, P->k_seed, P->k_round, P->k_pred};
    for (size_t i = 0; i < 5; i++)
        if (ks[i])
            clReleaseKernel(ks[i]);
    cl_mem bufs[] = {P->map, P->v, P->clear, P->d0, P->d1, P->s0, P->s1, P->pred, P->src, P->changed};
    for (size_t i = 0; i < 10; i++)
        if (bufs[i])
            clReleaseMemObject(bufs[i]);
    pthread_mutex_destroy(&P->lock);
    free(P);
}
