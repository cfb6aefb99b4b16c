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

typedef struct {
    int32_t *mark; /* per atom: last component stamp that listed it */
    int32_t stamp;
    int32_t *list;
    size_t n, cap;
    int failed;
} lining_acc;

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

/* The analysis of one frame's channel voxels: the voxel graph and its
 * scratch, shared by the steps below. */
typedef struct {
    vbc_graph A;
    const vbc_grid *g;
    const vbc_options *opt;
    size_t nvox;
    uint32_t *sorted;   /* voxel indices, ascending, mouth bit cleared */
    uint8_t *mouth;
    vb_uf uf;           /* union-find, then scratch of vbc_channel_ends */
    uint32_t *order;    /* positions grouped by component */
    size_t *cstart;     /* component c holds order[cstart[c] .. cstart[c + 1]) */
    uint32_t *comp;
    size_t ncomp;
    double *clear;      /* clearance per position (given, or computed per component) */
    int32_t *near;
    int given_clear;    /* the clearances came with the voxels */
    uint32_t *vcomp;    /* given component labels per position (voxel indices), or NULL */
    int comp_bad;       /* a given label failed a check: the union-find decides */
    vbc_cells *cells;
} analysis;

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

static void analysis_free(analysis *W)
{
    free(W->sorted);
    free(W->mouth);
    vb_uf_free(&W->uf);
    free(W->order);
    free(W->cstart);
    free(W->comp);
    free(W->A.dist);
    free(W->A.pred);
    free(W->A.heap);
    free(W->A.hpos);
    free(W->A.rep);
    free(W->A.support);
    free(W->A.adj_start);
    free(W->A.adj);
    free(W->A.adj_len);
    free(W->clear);
    free(W->near);
    free(W->vcomp);
    vbc_cells_free(W->cells);
}

/* The per-position arrays. Returns 0, or -1 when out of memory. */
static int analysis_alloc(analysis *W)
{
    size_t n = W->nvox;
    W->sorted = malloc(n * sizeof *W->sorted);
    W->mouth = malloc(n);
    int uf_ok = vb_uf_fit(&W->uf, n) == VB_OK;
    W->order = malloc(n * sizeof *W->order);
    W->cstart = malloc((n + 1) * sizeof *W->cstart);
    W->comp = malloc(n * sizeof *W->comp);
    W->A.dist = malloc(n * sizeof *W->A.dist);
    W->A.pred = malloc(n * sizeof *W->A.pred);
    W->A.heap = malloc(n * sizeof *W->A.heap);
    W->A.hpos = malloc(n * sizeof *W->A.hpos);
    W->A.rep = malloc(n * sizeof *W->A.rep);
    W->A.adj_start = malloc((n + 1) * sizeof *W->A.adj_start);
    W->clear = malloc(n * sizeof *W->clear);
    W->near = malloc(n * sizeof *W->near);
    W->A.clear = W->clear;
    return W->sorted && W->mouth && uf_ok && W->order && W->cstart && W->comp && W->A.dist &&
                   W->A.pred && W->A.heap && W->A.hpos && W->A.rep && W->A.adj_start &&
                   W->clear && W->near
               ? 0
               : -1;
}

/* Sorts key[0..n) by bits 32 and up (distinct voxel indices below 2^31),
 * least significant digit first, 11 bits a pass, as many passes as the
 * largest index needs; tmp holds n keys. Linear where the comparison
 * sort was n log n, and the one order on any number of threads. */
#define DIGIT_BITS 11

static void sort_by_index(uint64_t *key, uint64_t *tmp, size_t n)
{
    uint64_t top = 0;
    for (size_t t = 0; t < n; t++)
        top |= key[t] >> 32;
    for (int sh = 32; sh < 64 && (top >> (sh - 32)) != 0; sh += DIGIT_BITS) {
        size_t cnt[(1u << DIGIT_BITS) + 1];
        memset(cnt, 0, sizeof cnt);
        for (size_t t = 0; t < n; t++)
            cnt[((key[t] >> sh) & ((1u << DIGIT_BITS) - 1)) + 1]++;
        for (size_t d = 0; d < (1u << DIGIT_BITS); d++)
            cnt[d + 1] += cnt[d];
        for (size_t t = 0; t < n; t++)
            tmp[cnt[(key[t] >> sh) & ((1u << DIGIT_BITS) - 1)]++] = key[t];
        memcpy(key, tmp, n * sizeof *key);
    }
}

/* The voxels in increasing index order (with their given clearances, when
 * vclear is not NULL, and labels, when comp is not NULL), the mouth bit
 * split off, each its own union-find root. Returns 0, or -1 when out of
 * memory. */
static int load_voxels(analysis *W, const uint32_t *vox, const float *vclear,
                       const uint32_t *comp)
{
    size_t nvox = W->nvox;
    if (comp && !(W->vcomp = malloc(nvox * sizeof *W->vcomp)))
        return -1;
    /* (index, original slot) pairs, so the clearances and labels follow. */
    uint64_t *key = malloc(2 * nvox * sizeof *key);
    if (!key)
        return -1;
    for (size_t t = 0; t < nvox; t++)
        key[t] = ((uint64_t)(vox[t] & ~VBC_MOUTH_BIT) << 32) | (uint64_t)t;
    sort_by_index(key, key + nvox, nvox);
    for (size_t t = 0; t < nvox; t++) {
        size_t from = (size_t)(key[t] & 0xffffffffu);
        W->sorted[t] = vox[from];
        if (vclear) {
            W->clear[t] = vclear[from];
            W->near[t] = -1;
        }
        if (comp)
            W->vcomp[t] = comp[from];
    }
    free(key);
    for (size_t t = 0; t < nvox; t++) {
        W->mouth[t] = (W->sorted[t] & VBC_MOUTH_BIT) != 0;
        W->sorted[t] &= ~VBC_MOUTH_BIT;
        W->uf.p[t] = (uint32_t)t;
    }
    W->A.v = W->sorted;
    W->A.mouth = W->mouth;
    return 0;
}

/* One slice [lo, hi) of the voxel list linked (link_voxels): its edges
 * in adj (slice 0 writes W->A.adj itself), the degree of position t in
 * W->A.adj_start[t + 1]. */
typedef struct {
    analysis *W;
    size_t lo, hi;
    uint32_t *adj;
    size_t ne, cap;
    int failed, bad;
} link_job;

/* The first position of the sorted list whose index is at least x. */
static size_t lower_bound(const uint32_t *sorted, size_t n, int64_t x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if ((int64_t)sorted[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The list is sorted, so the neighbours of voxel v in the row at offset
 * o = dy*nx + dz*nx*ny lie at v + o - 1 .. v + o + 1, and a cursor per row
 * offset only ever moves forward: a slice costs a linear merge after one
 * binary search per row for its start. */
static void *link_slice(void *arg)
{
    link_job *J = arg;
    analysis *W = J->W;
    const vbc_grid *g = W->g;
    const uint32_t *sorted = W->sorted;
    size_t nvox = W->nvox, nxy = (size_t)g->nx * (size_t)g->ny;
    size_t cursor[9];
    if (J->lo >= J->hi)
        return NULL;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            cursor[(dz + 1) * 3 + dy + 1] =
                lower_bound(sorted, nvox, (int64_t)sorted[J->lo] + (int64_t)dy * g->nx +
                                              (int64_t)dz * (int64_t)nxy - 1);
    for (size_t t = J->lo; t < J->hi; t++) {
        size_t e0 = J->ne;
        uint32_t v = sorted[t];
        int i = (int)(v % (uint32_t)g->nx), j = (int)((v / (uint32_t)g->nx) % (uint32_t)g->ny);
        int k = (int)(v / nxy);
        if (VB_ARRAY_FIT(J->adj, J->cap, J->ne + 26, 64) != VB_OK) {
            J->failed = 1;
            return NULL;
        }
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++) {
                size_t *cur = &cursor[(dz + 1) * 3 + dy + 1];
                int jj = j + dy, kk = k + dz;
                int64_t base = (int64_t)v + (int64_t)dy * g->nx + (int64_t)dz * (int64_t)nxy;
                while (*cur < nvox && (int64_t)sorted[*cur] < base - 1)
                    (*cur)++;
                if (jj < 0 || kk < 0 || jj >= g->ny || kk >= g->nz)
                    continue;
                size_t q = *cur;
                for (int dx = -1; dx <= 1; dx++) {
                    int ii = i + dx;
                    int64_t target = base + dx;
                    while (q < nvox && (int64_t)sorted[q] < target)
                        q++;
                    if ((dx | dy | dz) == 0 || ii < 0 || ii >= g->nx || q >= nvox ||
                        (int64_t)sorted[q] != target)
                        continue;
                    /* The step length code rides in the top two bits until the split below. */
                    J->adj[J->ne++] = (uint32_t)q | ((uint32_t)(abs(dx) + abs(dy) + abs(dz)) << 30);
                    if (q > t && W->vcomp && W->vcomp[t] != W->vcomp[q])
                        J->bad = 1;
                }
            }
        W->A.adj_start[t + 1] = J->ne - e0;
    }
    return NULL;
}

/* The voxel graph once (26-connectivity) as CSR adjacency with the step
 * length of each edge, on slices of the list over the threads, joined in
 * slice order (the same arrays on any number of threads); without given
 * labels its components joined in the union-find (roots are each set's
 * smallest position, whatever the order of the unions). Returns 0, or -1
 * when out of memory. */
static int link_voxels(analysis *W)
{
    vbc_graph *A = &W->A;
    size_t nvox = W->nvox, adjcap = 0;
    int nt = vb_threads(0), failed = 0;
    /* Slices of at least 4096 voxels: below, a thread costs more than it saves. */
    if ((size_t)nt > nvox / 4096)
        nt = nvox / 4096 > 1 ? (int)(nvox / 4096) : 1;
    link_job jobs[VB_MAX_THREADS];
    for (int t = 0; t < nt; t++)
        jobs[t] = (link_job){W, nvox * (size_t)t / (size_t)nt, nvox * (size_t)(t + 1) / (size_t)nt,
                             NULL, 0, 0, 0, 0};
    vb_run_jobs(link_slice, jobs, sizeof *jobs, nt);
    size_t ne = 0;
    for (int t = 0; t < nt; t++) {
        failed |= jobs[t].failed;
        W->comp_bad |= jobs[t].bad;
        ne += jobs[t].ne;
    }
    if (!failed) {
        A->adj = jobs[0].adj;
        adjcap = jobs[0].cap;
        jobs[0].adj = NULL;
        failed = VB_ARRAY_FIT(A->adj, adjcap, ne ? ne : 1, 64) != VB_OK;
    }
    size_t at = jobs[0].ne;
    for (int t = 1; t < nt; t++) {
        if (!failed)
            memcpy(A->adj + at, jobs[t].adj, jobs[t].ne * sizeof *A->adj);
        at += jobs[t].ne;
        free(jobs[t].adj);
    }
    free(jobs[0].adj);
    if (failed)
        return -1;
    A->adj_start[0] = 0;
    for (size_t t = 0; t < nvox; t++)
        A->adj_start[t + 1] += A->adj_start[t];
    A->adj_len = malloc(ne ? ne : 1);
    if (!A->adj_len)
        return -1;
    for (size_t e = 0; e < ne; e++) {
        A->adj_len[e] = (uint8_t)(A->adj[e] >> 30);
        A->adj[e] &= 0x3fffffffu;
    }
    if (!W->vcomp)
        for (size_t t = 0; t < nvox; t++)
            for (size_t e = A->adj_start[t]; e < A->adj_start[t + 1]; e++)
                if (A->adj[e] > t)
                    vb_uf_join(&W->uf, (uint32_t)t, A->adj[e]);
    return 0;
}

static int cmp_u32_plain(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static void group_components(analysis *W);

/* Whether every group of group_components is connected: a breadth-first
 * walk from its first member over the edges (which link_voxels found
 * within one label) reaches all of it. hpos and heap are scratch here
 * (the sweeps set them again). */
static int groups_connected(analysis *W)
{
    vbc_graph *A = &W->A;
    for (size_t t = 0; t < W->nvox; t++)
        A->hpos[t] = 0;
    for (size_t c = 0; c < W->ncomp; c++) {
        size_t m = W->cstart[c + 1] - W->cstart[c], head = 0, n = 0;
        uint32_t first = W->order[W->cstart[c]];
        A->heap[n++] = first;
        A->hpos[first] = 1;
        while (head < n) {
            uint32_t u = A->heap[head++];
            for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1]; e++)
                if (!A->hpos[A->adj[e]]) {
                    A->hpos[A->adj[e]] = 1;
                    A->heap[n++] = A->adj[e];
                }
        }
        if (n != m)
            return 0;
    }
    return 1;
}

/* The union-find's parents from the given labels (each position hangs
 * below its label's position), after link_voxels found them equal across
 * every edge, then grouped. A label that is no listed voxel, is larger
 * than its voxel or is not its own voxel's label, or a group that is not
 * connected (one label on two pieces) fails; the union-find is then built
 * from the edges instead, the host's answer. */
static void given_components(analysis *W)
{
    size_t nvox = W->nvox;
    for (size_t t = 0; t < nvox && !W->comp_bad; t++) {
        uint32_t r = W->vcomp[t];
        const uint32_t *at = bsearch(&r, W->sorted, nvox, sizeof r, cmp_u32_plain);
        size_t pr = at ? (size_t)(at - W->sorted) : nvox;
        if (!at || pr > t || W->vcomp[pr] != r)
            W->comp_bad = 1;
        else
            W->uf.p[t] = (uint32_t)pr;
    }
    if (!W->comp_bad) {
        group_components(W);
        if (groups_connected(W))
            return;
        W->comp_bad = 1;
    }
    const vbc_graph *A = &W->A;
    for (size_t t = 0; t < nvox; t++)
        W->uf.p[t] = (uint32_t)t;
    for (size_t t = 0; t < nvox; t++)
        for (size_t e = A->adj_start[t]; e < A->adj_start[t + 1]; e++)
            if (A->adj[e] > t)
                vb_uf_join(&W->uf, (uint32_t)t, A->adj[e]);
    group_components(W);
}

/* The components of the union-find as CSR over `order`, numbered by their
 * lowest voxel. */
static void group_components(analysis *W)
{
    size_t nvox = W->nvox, ncomp = 0;
    uint32_t *comp = W->comp;
    size_t *cstart = W->cstart;
    for (size_t t = 0; t < nvox; t++) {
        uint32_t r = vb_uf_root(&W->uf, (uint32_t)t);
        if (r == t)
            comp[t] = (uint32_t)ncomp++;
    }
    memset(cstart, 0, (ncomp + 1) * sizeof *cstart);
    for (size_t t = 0; t < nvox; t++)
        cstart[comp[vb_uf_root(&W->uf, (uint32_t)t)] + 1]++;
    for (size_t c = 0; c < ncomp; c++)
        cstart[c + 1] += cstart[c];
    for (size_t t = 0; t < nvox; t++) {
        uint32_t c = comp[vb_uf_root(&W->uf, (uint32_t)t)];
        W->order[cstart[c]++] = (uint32_t)t;
    }
    for (size_t c = ncomp; c > 0; c--)
        cstart[c] = cstart[c - 1];
    cstart[0] = 0;
    W->ncomp = ncomp;
}

/* The ends *a, *b of the centreline of component mem[0..m) and the
 * widest (cheapest) path between them in K->path (b first), *np its
 * length. Returns 0, or -1 when out of memory. */
static int trace_path(analysis *W, worker *K, const uint32_t *mem, size_t m, int kind,
                      int *through, size_t *np)
{
    vbc_graph *A = &K->A;
    uint32_t a, b;
    *through = 0;
    if (kind == VBC_CHANNEL) {
        if (vbc_channel_ends(A, &W->uf, mem, m, &a, &b, through) != 0)
            return -1;
    } else {
        /* A cavity spans its extent: double sweep over plain lengths. */
        vbc_sweep(A, mem, m, mem[0], 0);
        a = vbc_farthest(A, mem, m);
        vbc_sweep(A, mem, m, a, 0);
        b = vbc_farthest(A, mem, m);
    }
    /* The centreline: the cheapest (widest) way from a to b. */
    vbc_sweep(A, mem, m, a, 1);
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
    const uint32_t *mem = W->order + W->cstart[c];
    size_t m = W->cstart[c + 1] - W->cstart[c];
    const vbc_options *opt = W->opt;
    int kind = nm > 0 ? VBC_CHANNEL : VBC_CAVITY;
    int through;
    size_t np;
    if (trace_path(W, K, mem, m, kind, &through, &np) != 0)
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
    if (!W->given_clear && clear_members(W, work, nwork, nt) != 0)
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
        /* The graph copies share W->A's support: analysis_free frees it. */
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
    int rc = VB_ENOMEM;
    if (analysis_alloc(&W) != 0 || load_voxels(&W, vox, vclear, comp) != 0 ||
        link_voxels(&W) != 0)
        goto done;
    if (W.vcomp)
        given_components(&W);
    else
        group_components(&W);
    res->device_components = W.vcomp && !W.comp_bad;
    res->components = W.ncomp;
    if ((rc = vbc_cells_build(ctx, s, 3.0, &W.cells)) != VB_OK)
        goto done;
    rc = VB_ENOMEM;
    if (analyse_components(&W, s->n, res) != 0)
        goto done;
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_channel);
    rc = VB_OK;
done:
    if (rc == VB_ENOMEM)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "channel analysis of %zu voxels", nvox);
    if (rc != VB_OK)
        vbc_result_free(res);
    analysis_free(&W);
    return rc;
}

void vbc_result_free(vbc_result *res)
{
    free(res->channels);
    free(res->points);
    free(res->lining);
    memset(res, 0, sizeof *res);
}
