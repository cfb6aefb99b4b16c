/* Connected components of the channel voxels, their classification (channel
 * or cavity), centrelines with clearance radii, bottlenecks, lining atoms and
 * pruning: the analysis the paper left out (Sec. 4.1). */
#include <math.h>
#include <stdlib.h>
#include <stdatomic.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_graph.h"
#include "vbc_paths.h"
#include "vbc_pore.h"
#include "vbc_voxels.h"

typedef struct {
    int32_t *mark; /* per atom: last component stamp that listed it */
    int32_t stamp;
    int32_t *list;
    size_t n, cap;
    int failed;
} lining_acc;

/* The cell side of the analysis' cell list (A). Its two queries answer
 * whatever the walk's order: clearances are the least (distance, index),
 * lining atoms a sorted set. 5 A walks fewer cells per channel voxel than
 * 3 A (the pore stage's, whose ascent reads the walk's order): 1af6 0.25 ->
 * 0.23 s of CPU, adk_oplsaa 0.80 -> 0.74 s for 10 frames (one thread). */
#define VBC_ANALYSIS_CELL 5.0

static void lining_add(int32_t atom, void *user)
{
    lining_acc *L = user;
    if (L->mark[atom] == L->stamp)
        return;
    L->mark[atom] = L->stamp;
    if (VB_ARRAY_FIT(L->list, L->cap, L->n + 1, 256) != VB_OK) {
        L->failed = 1;
        return;
    }
    L->list[L->n++] = atom;
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

static int cmp_channel(const void *a, const void *b)
{
    const vbc_channel *x = a, *y = b;
    if (x->length != y->length)
        return x->length < y->length ? 1 : -1;
    return (x->first_point > y->first_point) - (x->first_point < y->first_point);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

int vbc_analyse(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                size_t nvox, const vbc_options *opt, vbc_result *res)
{
    return vbc_analyse_clear(ctx, g, s, vox, NULL, nvox, opt, res);
}

/* One worker thread's scratch: the graph (its own heap; the per-position
 * arrays are shared, components own disjoint positions), the path and the
 * lining atoms of the component at hand. */
typedef struct {
    vbc_graph A;
    uint32_t *path;
    size_t pathcap;
    lining_acc L;
} worker;

/* What component c gives, merged into the result in component order. */
typedef struct {
    int kept;          /* a channel (else pruned) */
    vbc_channel ch;    /* first_point and first_lining: set by the merge */
    vbc_point *pts;    /* ch.npoints */
    int32_t *lin;      /* ch.nlining, ascending */
} comp_out;

/* The ends *a, *b of the centreline of component mem[0..m) and the
 * widest (cheapest) path between them in K->path (b first), *np its
 * length. Returns 0, or -1 when out of memory. */
static int trace_path(analysis *W, worker *K, size_t c, int kind, int *through, size_t *np)
{
    vbc_graph *A = &K->A;
    const uint32_t *mem = W->order + W->cstart[c];
    size_t m = W->cstart[c + 1] - W->cstart[c];
    uint32_t a, b;
    *through = 0;
    if (W->paths) {
        /* vbc_paths_trace swept every component: its ends, A->pred set. */
        a = W->end_a[c];
        b = W->end_b[c];
        *through = W->end_through[c];
    } else if (kind == VBC_CHANNEL) {
        if (vbc_channel_ends(A, &W->uf, mem, m, &a, &b, through) != 0)
            return -1;
    } else {
        /* A cavity spans its extent: double sweep over plain lengths. */
        vbc_sweep(A, mem, m, mem[0], 0);
        a = vbc_farthest(A, mem, m);
        vbc_sweep(A, mem, m, a, 0);
        b = vbc_farthest(A, mem, m);
    }
    /* The centreline: the cheapest (widest) way from a to b (the sweep
     * stops at b: only b's path is read). */
    if (!W->paths)
        vbc_sweep_to(A, mem, m, a, 1, b);
    *np = 0;
    for (uint32_t q = b; q != UINT32_MAX; q = A->pred[q]) {
        if (VB_ARRAY_FIT(K->path, K->pathcap, *np + 1, 64) != VB_OK)
            return -1;
        K->path[(*np)++] = q;
    }
    return 0;
}

/* The points of channel ch from K->path (ch->npoints of them, into
 * o->pts): voxel centres with their radii, the length, the bottleneck and
 * the lining atoms (in K->L). Returns 0, or -1 when out of memory. */
static int channel_points(analysis *W, worker *K, vbc_channel *ch, comp_out *o)
{
    size_t np = ch->npoints;
    if (!(o->pts = malloc((np ? np : 1) * sizeof *o->pts)))
        return -1;
    K->L.stamp++;
    K->L.n = 0;
    for (size_t t = 0; t < np; t++) {
        uint32_t q = K->path[np - 1 - t];
        vbc_point *pt = &o->pts[t];
        double p[3];
        vbc_voxel_centre(W->g, W->sorted[q], p);
        pt->x = p[0];
        pt->y = p[1];
        pt->z = p[2];
        /* Reported radii are always the exact (double) cell-list answer. */
        if (W->given_clear)
            pt->r = vbc_cells_clearance(W->cells, p, &pt->atom);
        else {
            pt->r = W->clear[q];
            pt->atom = W->near[q];
        }
        if (t > 0) {
            const vbc_point *prev = pt - 1;
            ch->length += sqrt((p[0] - prev->x) * (p[0] - prev->x) + (p[1] - prev->y) * (p[1] - prev->y) +
                               (p[2] - prev->z) * (p[2] - prev->z));
        }
        if (pt->r < ch->bottleneck) {
            ch->bottleneck = pt->r;
            ch->bottleneck_at = t;
        }
        vbc_cells_within(W->cells, p, pt->r + W->opt->lining_tol, lining_add, &K->L);
        if (K->L.failed)
            return -1;
    }
    return 0;
}

/* Whether component c is pruned before any distance is computed: a cavity
 * not kept, or too small for min_length (a path through m voxels is at
 * most (m - 1) long diagonals; most components are specks in grooves).
 * *nm: its mouth voxels. */
static int pruned_early(const analysis *W, size_t c, size_t *nm)
{
    const uint32_t *mem = W->order + W->cstart[c];
    size_t m = W->cstart[c + 1] - W->cstart[c];
    *nm = 0;
    for (size_t t = 0; t < m; t++)
        *nm += W->mouth[mem[t]];
    return (*nm == 0 && !W->opt->keep_cavities) ||
           (double)(m - 1) * 1.7320508075688772 * W->g->h < W->opt->min_length;
}

/* Component c (not pruned early, nm mouth voxels, its members' clearances
 * set): traced, then pruned (too short or too narrow) or kept in *o. Touches the per-position arrays
 * of its own members only, so components run on threads at once. Returns
 * 0, or -1 when out of memory. */
static int analyse_component(analysis *W, worker *K, size_t c, size_t nm, comp_out *o)
{
    size_t m = W->cstart[c + 1] - W->cstart[c];
    const vbc_options *opt = W->opt;
    int kind = nm > 0 ? VBC_CHANNEL : VBC_CAVITY;
    int through;
    size_t np;
    if (trace_path(W, K, c, kind, &through, &np) != 0)
        return -1;
    vbc_channel ch = {kind, kind == VBC_CAVITY ? VBC_WHY_CAVITY : through ? VBC_WHY_THROUGH : VBC_WHY_TUNNEL,
                      through, m, nm, 0.0, INFINITY, 0, 0, np, 0, 0};
    if (channel_points(W, K, &ch, o) != 0)
        return -1;
    if (ch.length < opt->min_length || ch.bottleneck < opt->min_radius)
        return 0;
    if (K->L.n > 1)
        qsort(K->L.list, K->L.n, sizeof *K->L.list, cmp_i32);
    ch.nlining = K->L.n;
    if (!(o->lin = malloc((K->L.n ? K->L.n : 1) * sizeof *o->lin)))
        return -1;
    memcpy(o->lin, K->L.list, K->L.n * sizeof *o->lin);
    o->ch = ch;
    o->kept = 1;
    return 0;
}

/* The clearances of the members of the components traced (when they did
 * not come with the voxels): one slice of CLEAR_SLICE positions of `order`
 * per item, so the threads share them evenly whatever the component sizes. */
#define CLEAR_SLICE 512

typedef struct {
    analysis *W;
    const size_t *slice;  /* per slice: its first index into W->order */
    const size_t *end;    /* per slice: one past its last */
} clear_job;

static void clear_slice(void *arg, size_t i, int tid)
{
    const clear_job *J = arg;
    analysis *W = J->W;
    (void)tid;
    for (size_t k = J->slice[i]; k < J->end[i]; k++) {
        uint32_t q = W->order[k];
        double p[3];
        vbc_voxel_centre(W->g, W->sorted[q], p);
        W->clear[q] = vbc_cells_clearance(W->cells, p, &W->near[q]);
    }
}

/* Slices over the members of the components work[0..nwork) and their
 * clearances on the threads. Returns 0, or -1 when out of memory. */
static int clear_members(analysis *W, const uint64_t *work, size_t nwork, int nt)
{
    size_t ns = 0;
    for (size_t i = 0; i < nwork; i++) {
        size_t c = (size_t)(work[i] & 0xffffffffu);
        ns += (W->cstart[c + 1] - W->cstart[c] + CLEAR_SLICE - 1) / CLEAR_SLICE;
    }
    size_t *slice = malloc((2 * ns + 1) * sizeof *slice);
    if (!slice)
        return -1;
    size_t *end = slice + ns, k = 0;
    for (size_t i = 0; i < nwork; i++) {
        size_t c = (size_t)(work[i] & 0xffffffffu);
        for (size_t lo = W->cstart[c]; lo < W->cstart[c + 1]; lo += CLEAR_SLICE) {
            slice[k] = lo;
            end[k++] = lo + CLEAR_SLICE < W->cstart[c + 1] ? lo + CLEAR_SLICE : W->cstart[c + 1];
        }
    }
    clear_job J = {W, slice, end};
    vb_parallel_for(clear_slice, &J, ns, nt);
    free(slice);
    return 0;
}

/* The components the workers trace: work[0..nwork) (largest first, so the
 * long ones start early), taken in turn through `next`; the outcome of
 * each lands in its own slot, so the result is the same for any number of
 * threads and any interleaving. */
typedef struct {
    analysis *W;
    const uint64_t *work; /* component numbers (low 32 bits) */
    const size_t *nm;     /* mouth voxels per component */
    size_t nwork;
    comp_out *out;        /* per component */
    _Atomic size_t next;
    _Atomic int failed;
} comp_queue;

typedef struct {
    comp_queue *Q;
    worker K;
} comp_job;

static void *comp_worker(void *arg)
{
    comp_job *J = arg;
    comp_queue *Q = J->Q;
    for (;;) {
        size_t i = atomic_fetch_add(&Q->next, 1);
        if (i >= Q->nwork || atomic_load(&Q->failed))
            return NULL;
        size_t c = (size_t)(Q->work[i] & 0xffffffffu);
        if (analyse_component(Q->W, &J->K, c, Q->nm[c], &Q->out[c]) != 0)
            atomic_store(&Q->failed, 1);
    }
}

/* Every component: pruned early, or traced by the worker threads; then
 * merged into res in component order (points and lining atoms appended as
 * one thread taking the components in order would have). Returns 0, or -1
 * when out of memory. */
static int analyse_components(analysis *W, size_t natoms, vbc_result *res)
{
    size_t ncomp = W->ncomp, nwork = 0, chcap = 0, ptcap = 0, lcap = 0, nlin = 0;
    size_t *nm = malloc((ncomp ? ncomp : 1) * sizeof *nm);
    uint64_t *work = malloc((ncomp ? ncomp : 1) * sizeof *work);
    comp_out *out = calloc(ncomp ? ncomp : 1, sizeof *out);
    comp_job *jobs = NULL;
    int nt = 0, rc = -1, need_support = 0, ok = 1;
    comp_queue Q = {W, work, nm, 0, out, 0, 0};
    if (!nm || !work || !out)
        goto done;
    /* Largest first (the key: size complement, then component number), so
     * no two entries tie. Components number below 2^30. */
    for (size_t c = 0; c < ncomp; c++)
        if (!pruned_early(W, c, &nm[c])) {
            uint64_t m = W->cstart[c + 1] - W->cstart[c];
            work[nwork++] = ((uint64_t)(UINT32_MAX - (uint32_t)m) << 32) | (uint64_t)c;
            need_support |= nm[c] >= 2;
        }
    /* Read by every worker's vbc_channel_ends: made before they start. */
    if (need_support && vbc_graph_support(&W->A) != 0)
        goto done;
    qsort(work, nwork, sizeof *work, cmp_u64);
    Q.nwork = nwork;
    nt = vb_threads(0);
    double t0 = vb_now();
    if (!W->given_clear && clear_members(W, work, nwork, nt) != 0)
        goto done;
    double t1 = vb_now();
    res->ms_clear = 1e3 * (t1 - t0);
    if (W->paths && vbc_paths_trace(W, work, nwork, nm, nt) != 0)
        goto done;
    if ((size_t)nt > nwork)
        nt = nwork ? (int)nwork : 1;
    if (!(jobs = calloc((size_t)nt, sizeof *jobs)))
        goto done;
    for (int t = 0; t < nt; t++) {
        jobs[t].Q = &Q;
        jobs[t].K.A = W->A;
        jobs[t].K.A.heap = t == 0 ? W->A.heap : malloc((W->nvox ? W->nvox : 1) * sizeof *W->A.heap);
        jobs[t].K.L.mark = calloc(natoms ? natoms : 1, sizeof(int32_t));
        ok &= jobs[t].K.A.heap && jobs[t].K.L.mark;
    }
    if (!ok)
        goto done;
    if (nwork)
        vb_run_jobs(comp_worker, jobs, sizeof *jobs, nt);
    res->ms_trace = 1e3 * (vb_now() - t1);
    if (atomic_load(&Q.failed))
        goto done;
    size_t p0 = 0;
    for (size_t c = 0; c < ncomp; c++) {
        comp_out *o = &out[c];
        if (!o->kept) {
            res->pruned++;
            continue;
        }
        o->ch.first_point = p0;
        o->ch.first_lining = nlin;
        if (VB_ARRAY_FIT(res->points, ptcap, p0 + o->ch.npoints, 64) != VB_OK ||
            VB_ARRAY_FIT(res->lining, lcap, nlin + o->ch.nlining + 1, 256) != VB_OK ||
            VB_ARRAY_FIT(res->channels, chcap, res->nchannels + 1, 64) != VB_OK)
            goto done;
        memcpy(res->points + p0, o->pts, o->ch.npoints * sizeof *o->pts);
        memcpy(res->lining + nlin, o->lin, o->ch.nlining * sizeof *o->lin);
        p0 += o->ch.npoints;
        nlin += o->ch.nlining;
        res->channels[res->nchannels++] = o->ch;
    }
    rc = 0;
done:
    for (int t = 0; jobs && t < nt; t++) {
        if (t > 0)
            free(jobs[t].K.A.heap);
        /* The graph copies share W->A's support: vbc_analysis_free frees it. */
        free(jobs[t].K.L.mark);
        free(jobs[t].K.L.list);
        free(jobs[t].K.path);
    }
    for (size_t c = 0; out && c < ncomp; c++) {
        free(out[c].pts);
        free(out[c].lin);
    }
    free(jobs);
    free(out);
    free(work);
    free(nm);
    return rc;
}

int vbc_analyse_clear(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, size_t nvox, const vbc_options *opt, vbc_result *res)
{
    return vbc_analyse_given(ctx, g, s, vox, vclear, NULL, nvox, opt, res);
}

int vbc_analyse_given(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, const uint32_t *comp, size_t nvox,
                      const vbc_options *opt, vbc_result *res)
{
    return vbc_analyse_paths(ctx, g, s, vox, vclear, comp, nvox, opt, NULL, res);
}

int vbc_analysis_beside(void)
{
    const char *e = getenv("VORBALL_ANALYSIS_BESIDE");
    return !(e && strcmp(e, "0") == 0) && vb_threads(0) >= VBC_PORE_MIN_THREADS;
}

/* What the analysis needs of the atoms alone, the cell list and the
 * support atoms (vbc_graph_support), made beside the voxels' sort, graph
 * and components when vbc_analysis_beside(), each on a thread of its own
 * (YiiP with its lipids, 43,480 atoms, analysis_bench on one thread: the
 * voxels' steps 3.4 ms of CPU, the cells 1.5, the support atoms 3.2, one
 * after the other before any component was traced). */
typedef struct {
    vb_ctx *ctx;      /* the cells' (the support reports nothing) */
    const vb_sphere_set *s;
    analysis *W;      /* its cells or A.support only: the voxels' steps touch neither */
    int support;      /* this job makes the support atoms, else the cells */
    int rc;
} side_job;

static void *side_run(void *arg)
{
    side_job *J = arg;
    if (J->support)
        J->rc = vbc_graph_support(&J->W->A) != 0 ? VB_ENOMEM : VB_OK;
    else
        J->rc = vbc_cells_build(J->ctx, J->s, VBC_ANALYSIS_CELL, &J->W->cells);
    return NULL;
}

int vbc_analyse_paths(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, const uint32_t *comp, size_t nvox,
                      const vbc_options *opt, const vbc_paths_engine *paths, vbc_result *res)
{
    memset(res, 0, sizeof *res);
    if (nvox == 0)
        return VB_OK;
    if (nvox >= ((size_t)1 << 30))
        return vb_error(ctx, VB_EINPUT_TOOLARGE, NULL, 0, "%zu channel voxels: too many", nvox);
    analysis W;
    memset(&W, 0, sizeof W);
    W.A.g = W.g = g;
    W.A.s = s;
    W.opt = opt;
    W.nvox = nvox;
    W.given_clear = vclear != NULL;
    W.paths = paths;
    int rc = VB_ENOMEM;
    double t0 = vb_now();
    /* The cells and the support beside the voxels' steps; ctx is the
     * cells' alone until the join (the voxels' steps report nothing). */
    side_job side[2] = {{ctx, s, &W, 0, VB_OK}, {ctx, s, &W, 1, VB_OK}};
    vb_jobs sides;
    int beside = vbc_analysis_beside();
    if (beside)
        vb_jobs_start(&sides, side_run, side, sizeof *side, 2);
    int vrc = vbc_analysis_alloc(&W) != 0 || vbc_voxels_load(&W, vox, vclear, comp) != 0 ||
              vbc_voxels_link(&W) != 0;
    if (!vrc) {
        if (W.vcomp)
            vbc_components_given(&W);
        else
            vbc_components_group(&W);
    }
    double ms_voxels = 1e3 * (vb_now() - t0);
    if (beside)
        vb_jobs_join(&sides);
    if (vrc)
        goto done;
    res->device_components = W.vcomp && !W.comp_bad;
    res->components = W.ncomp;
    /* One after the other the support waits for a component that needs it. */
    if (!beside)
        side_run(&side[0]);
    if ((rc = side[0].rc) != VB_OK || (rc = side[1].rc) != VB_OK)
        goto done;
    rc = VB_ENOMEM;
    if (analyse_components(&W, s->n, res) != 0)
        goto done;
    res->ms_graph = W.ms_graph;
    res->ms_voxels = ms_voxels;
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_channel);
    rc = VB_OK;
done:
    if (rc == VB_ENOMEM)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "channel analysis of %zu voxels", nvox);
    if (rc != VB_OK)
        vbc_result_free(res);
    vbc_analysis_free(&W);
    return rc;
}

void vbc_result_free(vbc_result *res)
{
    free(res->channels);
    free(res->points);
    free(res->lining);
    memset(res, 0, sizeof *res);
}
