/* The channel graph's batch sweeps (core/discrete/vbc_paths.h) against the
 * per-component Dijkstra (vbc_sweep): the plain-C twin and the OpenCL
 * kernels (gpu/channel_paths.cl, on whatever device "auto" picks: PoCL in
 * CI) give the same distance bits and predecessors on random voxel sets
 * whose clearances take a few values, so that ties are everywhere (and the
 * test counts them); then whole analyses with the batches on the twin and
 * on the device against the per-component analysis, cavities kept (also
 * with one clearance past the batches' exactness bound), and engines whose
 * device fails at begin or at every batch (the twin takes over). */
#include <math.h>
#include <string.h>

#include "channel_paths_math.h"
#include "synth.h"
#include "vb_test.h"
#include "vbc_channel_gpu.h"
#include "vbc_paths.h"
#include "vbc_voxels.h"

/* A random set of voxels of an nx*ny*nz grid (each present with
 * probability p), mouth bits on about one in eight, and per voxel a
 * clearance drawn from `levels` values (0.02 lies below the path cost's
 * floor of 0.05, so it ties with 0.05). */
static size_t random_voxels(uint64_t *seed, const vbc_grid *g, double p, int levels, uint32_t *vox,
                            float *clear)
{
    static const float lv[5] = {1.0f, 0.5f, 0.05f, 0.02f, 1.5f};
    size_t n = 0;
    for (size_t v = 0; v < vbc_grid_voxels(g); v++)
        if (synth_uniform(seed) < p) {
            vox[n] = (uint32_t)v | (synth_uniform(seed) < 0.125 ? VBC_MOUTH_BIT : 0u);
            clear[n++] = lv[(int)(synth_uniform(seed) * levels) % levels];
        }
    /* Scrambled order: the analysis sorts. */
    for (size_t t = n; t > 1; t--) {
        size_t u = (size_t)(synth_uniform(seed) * (double)t) % t;
        uint32_t x = vox[t - 1];
        float c = clear[t - 1];
        vox[t - 1] = vox[u];
        clear[t - 1] = clear[u];
        vox[u] = x;
        clear[u] = c;
    }
    return n;
}

/* Voxels with two or more neighbours that reach them at their distance:
 * where the predecessor rule decides. */
static size_t count_ties(const analysis *W)
{
    size_t ties = 0;
    for (size_t q = 0; q < W->nvox; q++) {
        int k = 0;
        for (size_t e = W->A.adj_start[q]; e < W->A.adj_start[q + 1]; e++) {
            uint32_t u = W->A.adj[e];
            k += W->A.dist[q] > 0.0 && W->A.dist[q] < INFINITY &&
                 W->A.dist[u] + vbc_path_step(W->A.adj_len[e], W->clear[u], W->clear[q], 1) ==
                     W->A.dist[q];
        }
        ties += k >= 2;
    }
    return ties;
}

/* One random set: Dijkstra per component from a random member, then the
 * same sources as one batch on the twin and on the device engine E (may
 * be NULL). Returns the ties of the weighted Dijkstra. */
static size_t sweep_case(uint64_t *seed, const vbc_paths_engine *E, int n, double p, int levels)
{
    vbc_grid g = {n, n - 3, n - 5, 3, {0.0, 0.0, 0.0}, 1.0};
    size_t nv = vbc_grid_voxels(&g), ties = 0;
    uint32_t *vox = malloc(nv * sizeof *vox);
    float *vclear = malloc(nv * sizeof *vclear);
    size_t nvox = random_voxels(seed, &g, p, levels, vox, vclear);
    analysis W;
    memset(&W, 0, sizeof W);
    W.A.g = W.g = &g;
    W.nvox = nvox;
    CHECK(vbc_analysis_alloc(&W) == 0 && vbc_voxels_load(&W, vox, vclear, NULL) == 0 &&
          vbc_voxels_link(&W) == 0);
    vbc_components_group(&W);
    uint32_t *src = malloc((W.ncomp + 1) * sizeof *src);
    double *dist = malloc(nvox * sizeof *dist);
    uint32_t *pred = malloc(nvox * sizeof *pred);
    vbc_paths_graph G = {&g, W.sorted, nvox, W.clear, W.A.adj_start, W.A.adj, W.A.adj_len};
    for (int weighted = 0; weighted <= 1; weighted++) {
        for (size_t c = 0; c < W.ncomp; c++) {
            size_t m = W.cstart[c + 1] - W.cstart[c];
            const uint32_t *mem = W.order + W.cstart[c];
            src[c] = mem[(size_t)(synth_uniform(seed) * (double)m) % m];
            vbc_sweep(&W.A, mem, m, src[c], weighted);
        }
        if (weighted)
            ties = count_ties(&W);
        for (int on = 0; on < 2; on++) {
            if (on && !E)
                continue;
            vbc_paths_batch b = {src, W.ncomp, weighted, dist, pred, 0};
            memset(dist, 0, nvox * sizeof *dist);
            int rc = on ? (E->begin(E->user, &G) == VB_OK ? E->sweep(E->user, &G, &b) : -1)
                        : vbc_paths_sweep_ref(&G, &b);
            if (on && rc != -1)
                E->end(E->user);
            CHECK_INT(rc, 0);
            size_t bad_d = 0, bad_p = 0;
            for (size_t t = 0; t < nvox; t++) {
                bad_d += memcmp(&dist[t], &W.A.dist[t], sizeof(double)) != 0;
                bad_p += pred[t] != W.A.pred[t];
            }
            CHECK_INT(bad_d, 0);
            CHECK_INT(bad_p, 0);
            if (bad_d || bad_p)
                fprintf(stderr, "%s, weighted %d, %zu voxels: %zu distances, %zu predecessors differ\n",
                        on ? "device" : "twin", weighted, nvox, bad_d, bad_p);
        }
    }
    free(src);
    free(dist);
    free(pred);
    vbc_analysis_free(&W);
    free(vox);
    free(vclear);
    return ties;
}

static size_t compare_results(const vbc_result *a, const vbc_result *b)
{
    size_t diff = a->nchannels != b->nchannels || a->components != b->components ||
                  a->pruned != b->pruned;
    for (size_t c = 0; !diff && c < a->nchannels; c++) {
        const vbc_channel *x = &a->channels[c], *y = &b->channels[c];
        diff += x->kind != y->kind || x->through != y->through || x->why != y->why ||
                x->voxels != y->voxels || x->mouths != y->mouths ||
                memcmp(&x->length, &y->length, sizeof x->length) != 0 ||
                x->bottleneck != y->bottleneck || x->bottleneck_at != y->bottleneck_at ||
                x->first_point != y->first_point || x->npoints != y->npoints ||
                x->first_lining != y->first_lining || x->nlining != y->nlining;
        for (size_t t = 0; !diff && t < x->npoints; t++) {
            const vbc_point *p = &a->points[x->first_point + t], *q = &b->points[x->first_point + t];
            diff += p->x != q->x || p->y != q->y || p->z != q->z || p->r != q->r || p->atom != q->atom;
        }
        for (size_t t = 0; !diff && t < x->nlining; t++)
            diff += a->lining[x->first_lining + t] != b->lining[x->first_lining + t];
    }
    return diff;
}

/* Whole analyses of a random voxel set with its clearances given (cavities
 * kept, nothing pruned): per component, batches on the twin, batches on
 * the device. Returns the channels (and cavities) traced. */
static size_t analysis_case(vb_ctx *ctx, uint64_t *seed, const vbc_paths_engine *E, int n,
                            double p, int levels, int huge)
{
    vbc_grid g = {n, n, n, 3, {-0.5 * n, -0.5 * n, -0.5 * n}, 1.0};
    size_t nv = vbc_grid_voxels(&g);
    uint32_t *vox = malloc(nv * sizeof *vox);
    float *vclear = malloc(nv * sizeof *vclear);
    size_t nvox = random_voxels(seed, &g, p, levels, vox, vclear);
    /* A clearance so large that a weighted step may vanish beside a long
     * distance: the frame sweeps one component at a time (batches_exact). */
    if (huge)
        vclear[nvox / 2] = 1e7f;
    vb_sphere_set *s = synth_shell(60, 0.45 * n, 1.5);
    vbc_options opt = {0.0, -1e9, 1.0, 1, NULL}; /* nothing pruned */
    vbc_result r0, r1, r2;
    CHECK_INT(vbc_analyse_given(ctx, &g, s, vox, vclear, NULL, nvox, &opt, &r0), VB_OK);
    CHECK_INT(vbc_analyse_paths(ctx, &g, s, vox, vclear, NULL, nvox, &opt, vbc_paths_engine_ref(), &r1),
              VB_OK);
    CHECK_INT(compare_results(&r0, &r1), 0);
    if (E) {
        CHECK_INT(vbc_analyse_paths(ctx, &g, s, vox, vclear, NULL, nvox, &opt, E, &r2), VB_OK);
        CHECK_INT(compare_results(&r0, &r2), 0);
        vbc_result_free(&r2);
    }
    size_t traced = r0.nchannels;
    vbc_result_free(&r0);
    vbc_result_free(&r1);
    vb_spheres_free(s);
    free(vox);
    free(vclear);
    return traced;
}

/* Fault injection: an engine whose device fails at begin, or at every
 * batch; the analysis runs those batches on the twin, the same result. */
static int fault_begin(void *user, const vbc_paths_graph *G)
{
    (void)G;
    return *(int *)user == 0 ? VB_EDEVICE : VB_OK;
}

static int fault_sweep(void *user, const vbc_paths_graph *G, vbc_paths_batch *b)
{
    (void)user;
    (void)G;
    memset(b->pred, 0, G->n * sizeof *b->pred); /* spoilt output: must not be used */
    return VB_EDEVICE;
}

static void fault_end(void *user)
{
    (*(int *)user)++;
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vbg_runtime *rt = NULL;
    vbc_paths_gpu *P = NULL;
    int rc = vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt);
    if (rc == VB_OK)
        rc = vbc_paths_gpu_open(ctx, rt, &P);
    CHECK_INT(rc, VB_OK);
    if (rc != VB_OK)
        fprintf(stderr, "no OpenCL device, the twin alone: %s\n", vb_errmsg(ctx));
    const vbc_paths_engine *E = vbc_paths_gpu_engine(P);
    uint64_t seed = 33;
    size_t ties = 0, traced = 0;
    /* Dense sets (one big component with cycles everywhere) and sparse ones
     * (many small components); one clearance level (every step ties), two,
     * five. */
    static const double dens[3] = {0.75, 0.5, 0.3};
    for (int d = 0; d < 3; d++)
        for (int levels = 1; levels <= 5; levels += 2)
            ties += sweep_case(&seed, E, d == 0 ? 22 : 14, dens[d], levels);
    fprintf(stderr, "sweeps: %zu voxels reached at their distance by two or more neighbours\n", ties);
    CHECK(ties > 1000);
    for (int t = 0; t < 8; t++)
        traced += analysis_case(ctx, &seed, E, 16, t < 3 ? 0.12 : 0.3, 1 + 2 * (t % 3), t >= 6);
    fprintf(stderr, "analyses: %zu channels and cavities traced\n", traced);
    CHECK(traced > 20);
    for (int mode = 0; mode < 2; mode++) {
        int ends = mode; /* 0: begin fails; 1: begin works, every batch fails */
        vbc_paths_engine F = {&ends, fault_begin, fault_sweep, fault_end};
        CHECK(analysis_case(ctx, &seed, &F, 16, 0.2, 3, 0) > 0);
        CHECK_INT(ends, mode ? 2 : 0); /* end called once after a begin that worked */
    }
    vbc_paths_gpu_close(P);
    vbg_runtime_close(rt);
    vb_close(ctx);
    VB_TEST_END();
}
