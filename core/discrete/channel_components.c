/* Connected components of the channel voxels, their classification (channel
 * or cavity), centrelines with clearance radii, bottlenecks, lining atoms and
 * pruning: the analysis the paper left out (Sec. 4.1). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_graph.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a & ~VBC_MOUTH_BIT, y = *(const uint32_t *)b & ~VBC_MOUTH_BIT;
    return (x > y) - (x < y);
}

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
    lining_acc L;
    vbc_cells *cells;
    uint32_t *path;
    size_t pathcap, chcap, ptcap;
} analysis;

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
    free(W->L.mark);
    free(W->L.list);
    free(W->path);
    vbc_cells_free(W->cells);
}

/* The per-position arrays. Returns 0, or -1 when out of memory. */
static int analysis_alloc(analysis *W, size_t natoms)
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
    W->L.mark = calloc(natoms, sizeof(int32_t));
    W->A.clear = W->clear;
    return W->sorted && W->mouth && uf_ok && W->order && W->cstart && W->comp && W->A.dist &&
                   W->A.pred && W->A.heap && W->A.hpos && W->A.rep && W->A.adj_start &&
                   W->clear && W->near && W->L.mark
               ? 0
               : -1;
}

/* The voxels in increasing index order (with their given clearances, when
 * vclear is not NULL), the mouth bit split off, each its own union-find
 * root. Returns 0, or -1 when out of memory. */
static int load_voxels(analysis *W, const uint32_t *vox, const float *vclear,
                       const uint32_t *comp)
{
    size_t nvox = W->nvox;
    if (comp && !(W->vcomp = malloc(nvox * sizeof *W->vcomp)))
        return -1;
    if (vclear || comp) {
        /* Sort (index, original slot) pairs so the clearances follow. */
        uint64_t *key = malloc(nvox * sizeof *key);
        if (!key)
            return -1;
        for (size_t t = 0; t < nvox; t++)
            key[t] = ((uint64_t)(vox[t] & ~VBC_MOUTH_BIT) << 32) | (uint64_t)t;
        /* Keys are distinct (the slot is in them): one sorted order on any
         * number of threads. */
        if (vb_psort(key, nvox, sizeof *key, cmp_u64, vb_threads(0)) != VB_OK) {
            free(key);
            return -1;
        }
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
    } else {
        memcpy(W->sorted, vox, nvox * sizeof *W->sorted);
        if (vb_psort(W->sorted, nvox, sizeof *W->sorted, cmp_u32, vb_threads(0)) != VB_OK)
            return -1;
    }
    for (size_t t = 0; t < nvox; t++) {
        W->mouth[t] = (W->sorted[t] & VBC_MOUTH_BIT) != 0;
        W->sorted[t] &= ~VBC_MOUTH_BIT;
        W->uf.p[t] = (uint32_t)t;
    }
    W->A.v = W->sorted;
    W->A.mouth = W->mouth;
    return 0;
}

/* The voxel graph once (26-connectivity) as CSR adjacency with the step
 * length of each edge, its components joined in the union-find. The list is
 * sorted, so the neighbours of voxel v in the row at offset o = dy*nx +
 * dz*nx*ny lie at v + o - 1 .. v + o + 1, and a cursor per row offset only
 * ever moves forward: the whole graph costs a linear merge, no lookups.
 * Returns 0, or -1 when out of memory. */
static int link_voxels(analysis *W)
{
    const vbc_grid *g = W->g;
    vbc_graph *A = &W->A;
    const uint32_t *sorted = W->sorted;
    size_t nvox = W->nvox, nxy = (size_t)g->nx * (size_t)g->ny, adjcap = 0, ne = 0;
    size_t cursor[9] = {0};
    for (size_t t = 0; t < nvox; t++) {
        A->adj_start[t] = ne;
        uint32_t v = sorted[t];
        int i = (int)(v % (uint32_t)g->nx), j = (int)((v / (uint32_t)g->nx) % (uint32_t)g->ny);
        int k = (int)(v / nxy);
        if (VB_ARRAY_FIT(A->adj, adjcap, ne + 26, 64) != VB_OK)
            return -1;
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
                    A->adj[ne++] = (uint32_t)q | ((uint32_t)(abs(dx) + abs(dy) + abs(dz)) << 30);
                    if (q > t && !W->vcomp)
                        vb_uf_join(&W->uf, (uint32_t)t, (uint32_t)q);
                    else if (q > t && W->vcomp[t] != W->vcomp[q])
                        W->comp_bad = 1;
                }
            }
    }
    A->adj_start[nvox] = ne;
    A->adj_len = malloc(ne ? ne : 1);
    if (!A->adj_len)
        return -1;
    for (size_t e = 0; e < ne; e++) {
        A->adj_len[e] = (uint8_t)(A->adj[e] >> 30);
        A->adj[e] &= 0x3fffffffu;
    }
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
 * widest (cheapest) path between them in W->path (b first), *np its
 * length. Returns 0, or -1 when out of memory. */
static int trace_path(analysis *W, const uint32_t *mem, size_t m, int kind, int *through,
                      size_t *np)
{
    vbc_graph *A = &W->A;
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
        if (VB_ARRAY_FIT(W->path, W->pathcap, *np + 1, 64) != VB_OK)
            return -1;
        W->path[(*np)++] = q;
    }
    return 0;
}

/* The points of channel ch from W->path (ch->npoints of them, from
 * ch->first_point on): voxel centres with their radii, the length, the
 * bottleneck and the lining atoms (appended to W->L). Returns 0, or -1
 * when out of memory. */
static int channel_points(analysis *W, vbc_result *res, vbc_channel *ch)
{
    size_t np = ch->npoints, p0 = ch->first_point;
    if (VB_ARRAY_FIT(res->points, W->ptcap, p0 + np, 64) != VB_OK)
        return -1;
    W->L.stamp++;
    for (size_t t = 0; t < np; t++) {
        uint32_t q = W->path[np - 1 - t];
        vbc_point *pt = &res->points[p0 + t];
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
        vbc_cells_within(W->cells, p, pt->r + W->opt->lining_tol, lining_add, &W->L);
        if (W->L.failed)
            return -1;
    }
    return 0;
}

/* Component c: classified, pruned (too small, a cavity not kept, too short
 * or too narrow) or traced and appended to res. Returns 0, or -1 when out
 * of memory. */
static int analyse_component(analysis *W, size_t c, vbc_result *res)
{
    const uint32_t *mem = W->order + W->cstart[c];
    size_t m = W->cstart[c + 1] - W->cstart[c];
    const vbc_options *opt = W->opt;
    size_t nm = 0;
    for (size_t t = 0; t < m; t++)
        nm += W->mouth[mem[t]];
    int kind = nm > 0 ? VBC_CHANNEL : VBC_CAVITY;
    /* A path through m voxels is at most (m - 1) long diagonals: components
     * too small for min_length are pruned before any distance is computed
     * (most components are specks in grooves). */
    if ((kind == VBC_CAVITY && !opt->keep_cavities) ||
        (double)(m - 1) * 1.7320508075688772 * W->g->h < opt->min_length) {
        res->pruned++;
        return 0;
    }
    for (size_t t = 0; t < m && !W->given_clear; t++) {
        double p[3];
        vbc_voxel_centre(W->g, W->sorted[mem[t]], p);
        W->clear[mem[t]] = vbc_cells_clearance(W->cells, p, &W->near[mem[t]]);
    }
    int through;
    size_t np;
    if (trace_path(W, mem, m, kind, &through, &np) != 0)
        return -1;
    size_t p0 = 0;
    for (size_t t = 0; t < res->nchannels; t++)
        p0 += res->channels[t].npoints;
    vbc_channel ch = {kind, kind == VBC_CAVITY ? VBC_WHY_CAVITY : through ? VBC_WHY_THROUGH : VBC_WHY_TUNNEL,
                      through, m, nm, 0.0, INFINITY, 0, p0, np, 0, 0};
    size_t l0 = W->L.n;
    if (channel_points(W, res, &ch) != 0)
        return -1;
    if (ch.length < opt->min_length || ch.bottleneck < opt->min_radius) {
        res->pruned++;
        W->L.n = l0;
        return 0;
    }
    if (W->L.n - l0 > 1)
        qsort(W->L.list + l0, W->L.n - l0, sizeof *W->L.list, cmp_i32);
    ch.first_lining = l0;
    ch.nlining = W->L.n - l0;
    if (VB_ARRAY_FIT(res->channels, W->chcap, res->nchannels + 1, 64) != VB_OK)
        return -1;
    res->channels[res->nchannels++] = ch;
    return 0;
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
    if (analysis_alloc(&W, s->n) != 0 || load_voxels(&W, vox, vclear, comp) != 0 ||
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
    for (size_t c = 0; c < W.ncomp; c++)
        if (analyse_component(&W, c, res) != 0)
            goto done;
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_channel);
    res->lining = W.L.list;
    W.L.list = NULL;
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
