/* The channel analysis's voxel stage (vbc_voxels.h): the voxels sorted by
 * a radix sort, linked into the 26-connected voxel graph on slices over the
 * threads, and grouped into connected components (given labels checked, or
 * the union-find's). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_voxels.h"

void vbc_analysis_free(analysis *W)
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
    free(W->end_a);
    free(W->end_b);
    free(W->end_through);
    vbc_cells_free(W->cells);
}

/* The per-position arrays. Returns 0, or -1 when out of memory. */
int vbc_analysis_alloc(analysis *W)
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
    W->clear = calloc(n ? n : 1, sizeof *W->clear); /* zero where never computed (uploaded whole) */
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
int vbc_voxels_load(analysis *W, const uint32_t *vox, const float *vclear,
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

/* One slice [lo, hi) of the voxel list linked (vbc_voxels_link): its edges
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
int vbc_voxels_link(analysis *W)
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

void vbc_components_group(analysis *W);

/* Whether every group of vbc_components_group is connected: a breadth-first
 * walk from its first member over the edges (which vbc_voxels_link found
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
 * below its label's position), after vbc_voxels_link found them equal across
 * every edge, then grouped. A label that is no listed voxel, is larger
 * than its voxel or is not its own voxel's label, or a group that is not
 * connected (one label on two pieces) fails; the union-find is then built
 * from the edges instead, the host's answer. */
void vbc_components_given(analysis *W)
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
        vbc_components_group(W);
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
    vbc_components_group(W);
}

/* The components of the union-find as CSR over `order`, numbered by their
 * lowest voxel. */
void vbc_components_group(analysis *W)
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
