/* The channel analysis's ends and sweeps as batches over every component of
 * a frame (vbc_paths_trace, vbc_voxels.h): the openings per component on
 * host threads, then three waves of sweeps on the paths engine (a device,
 * or the twin of vbc_paths.h), each over every component that needs one:
 *   1  plain, from a cavity's first member (its first end is the farthest
 *      member) and from a channel's one opening (the farthest member ends it);
 *   2  plain, from a cavity's first end (the farthest member ends it);
 *   3  weighted, from every first end: the centrelines' predecessors. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "channel_paths_math.h"
#include "vb_parallel.h"
#include "vbc_paths.h"
#include "vbc_voxels.h"

typedef struct {
    analysis *W;
    const uint64_t *work;
    const size_t *nm;
    _Atomic int failed;
} ends_job;

static void ends_one(void *arg, size_t i, int tid)
{
    ends_job *J = arg;
    analysis *W = J->W;
    size_t c = (size_t)(J->work[i] & 0xffffffffu);
    const uint32_t *mem = W->order + W->cstart[c];
    size_t m = W->cstart[c + 1] - W->cstart[c];
    int through = 0;
    (void)tid;
    W->end_a[c] = W->end_b[c] = UINT32_MAX;
    if (J->nm[c] > 0 && vbc_channel_openings(&W->A, &W->uf, mem, m, &W->end_a[c], &W->end_b[c],
                                             &through) != 0)
        atomic_store(&J->failed, 1);
    W->end_through[c] = (uint8_t)through;
}

/* Whether the batches are sure to give Dijkstra's bytes on this frame
 * (vbc_paths.h): every folded cost d must grow by every step s, which holds
 * while d < 2^52 s. Steps are at least 1 / R^2 (R the largest clearance,
 * at least the 0.05 floor; plain steps at least 1) and at most
 * sqrt(3) / 0.05^2 < 693, so every d is below 693 n for n voxels. A frame
 * past the bound (R^2 n > 1.4e12, e.g. 100 A clearances with 10^8 voxels)
 * runs its sweeps one component at a time. */
static int batches_exact(const analysis *W, const uint64_t *work, size_t nwork)
{
    double R = VBC_PATH_MIN_CLEAR;
    /* The components traced: the others' clearances were never computed. */
    for (size_t i = 0; i < nwork; i++) {
        size_t c = (size_t)(work[i] & 0xffffffffu);
        for (size_t k = W->cstart[c]; k < W->cstart[c + 1]; k++)
            R = W->clear[W->order[k]] > R ? W->clear[W->order[k]] : R;
    }
    double R2 = R * R > 1.0 ? R * R : 1.0;
    return 693.0 * (double)W->nvox * R2 < 4503599627370496.0; /* 2^52 */
}

/* One batch on the engine, or on the twin when it has none or fails; one
 * Dijkstra per component (c[i] the component of src[i]) when the batches
 * are not sure to match it. */
static int sweep(analysis *W, const vbc_paths_graph *G, int on_device, const uint32_t *src,
                 const uint32_t *comp, size_t nsrc, int weighted, int exact)
{
    vbc_paths_batch b = {src, nsrc, weighted, W->A.dist, W->A.pred, 0};
    if (nsrc == 0)
        return 0;
    if (!exact) {
        for (size_t i = 0; i < nsrc; i++)
            vbc_sweep(&W->A, W->order + W->cstart[comp[i]], W->cstart[comp[i] + 1] - W->cstart[comp[i]],
                      src[i], weighted);
        return 0;
    }
    if (on_device && W->paths->sweep && W->paths->sweep(W->paths->user, G, &b) == VB_OK)
        return 0;
    return vbc_paths_sweep_ref(G, &b);
}

int vbc_paths_trace(analysis *W, const uint64_t *work, size_t nwork, const size_t *nm, int nt)
{
    double t0 = vb_now();
    size_t nc = W->ncomp ? W->ncomp : 1;
    uint32_t *src = malloc(2 * (nwork ? nwork : 1) * sizeof *src), *comp = src + nwork;
    W->end_a = malloc(nc * sizeof *W->end_a);
    W->end_b = malloc(nc * sizeof *W->end_b);
    W->end_through = malloc(nc);
    if (!src || !W->end_a || !W->end_b || !W->end_through) {
        free(src);
        return -1;
    }
    ends_job J = {W, work, nm, 0};
    vb_parallel_for(ends_one, &J, nwork, nt);
    vbc_paths_graph G = {W->g,          W->sorted,   W->nvox,      W->clear,
                         W->A.adj_start, W->A.adj,   W->A.adj_len};
    int rc = atomic_load(&J.failed) ? -1 : 0, exact = batches_exact(W, work, nwork);
    int on_device = rc == 0 && exact && nwork > 0 && W->paths->begin(W->paths->user, &G) == VB_OK;
    for (int wave = 1; wave <= 3 && rc == 0; wave++) {
        size_t ns = 0;
        for (size_t i = 0; i < nwork; i++) {
            size_t c = (size_t)(work[i] & 0xffffffffu);
            const uint32_t *mem = W->order + W->cstart[c];
            comp[ns] = (uint32_t)c;
            if (wave == 1 && nm[c] == 0)
                src[ns++] = mem[0];
            else if ((wave == 1 && nm[c] > 0 && W->end_b[c] == UINT32_MAX) ||
                     (wave == 2 && nm[c] == 0) || wave == 3)
                src[ns++] = W->end_a[c];
        }
        rc = sweep(W, &G, on_device, src, comp, ns, wave == 3, exact);
        for (size_t i = 0; i < nwork && rc == 0 && wave < 3; i++) {
            size_t c = (size_t)(work[i] & 0xffffffffu);
            const uint32_t *mem = W->order + W->cstart[c];
            size_t m = W->cstart[c + 1] - W->cstart[c];
            if (wave == 1 && nm[c] == 0)
                W->end_a[c] = vbc_farthest(&W->A, mem, m);
            else if ((wave == 1 && nm[c] > 0 && W->end_b[c] == UINT32_MAX) || (wave == 2 && nm[c] == 0))
                W->end_b[c] = vbc_farthest(&W->A, mem, m);
        }
    }
    if (on_device)
        W->paths->end(W->paths->user);
    free(src);
    W->ms_graph = 1e3 * (vb_now() - t0);
    return rc;
}
