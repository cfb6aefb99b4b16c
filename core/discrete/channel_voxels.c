/* The channel analysis's voxel stage (vbc_voxels.h): the voxels sorted by
 * a radix sort, linked into the 26-connected voxel graph on slices over the
 * threads, and grouped into connected components (given labels checked, or
 * the union-find's). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_radix.h"
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
    vbc_radix_sort(key, NULL, key + nvox, NULL, nvox, 32);
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
 * in adj and their step length codes in len (slice 0's become W->A's),
 * the degree of position t in W->A.adj_start[t + 1]. */
typedef struct {
    analysis *W;
    size_t lo, hi;
    uint32_t *adj;
    uint8_t *len;
    size_t ne, cap, lcap;
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

#define NO_VOXEL UINT32_MAX

/* Three z-planes of the grid, each (nx + 2) (ny + 2) entries with a border
 * of one, that hold the list position of every listed voxel of their
 * slab and NO_VOXEL elsewhere: slab s in plane (s + 1) % 3, so slabs k - 1,
 * k, k + 1 sit side by side while slab k links, and a plane is refilled as
 * the slab below leaves. Neighbours are then 26 loads at fixed offsets. */
typedef struct {
    uint32_t *plane[3];
    size_t row;                  /* nx + 2 */
} slab_planes;

/* Voxels of slab k of the list: positions [*a, *b). */
static void slab_range(const analysis *W, int64_t k, size_t *a, size_t *b)
{
    size_t nxy = (size_t)W->g->nx * (size_t)W->g->ny;
    *a = lower_bound(W->sorted, W->nvox, k * (int64_t)nxy);
    *b = lower_bound(W->sorted, W->nvox, (k + 1) * (int64_t)nxy);
}

/* The plane entry of each voxel of positions [a, b) of slab k, into at[]
 * (b - a of them): rows found by stepping, as the list ascends, so no
 * division per voxel. */
static void slab_entries(const analysis *W, const slab_planes *P, int64_t k, size_t a, size_t b,
                         size_t *at)
{
    size_t nx = (size_t)W->g->nx, base = (size_t)k * nx * (size_t)W->g->ny, row0 = 0, j = 0;
    for (size_t t = a; t < b; t++) {
        size_t in = W->sorted[t] - base;
        while (in >= row0 + nx) {
            row0 += nx;
            j++;
        }
        at[t - a] = (in - row0 + 1) + (j + 1) * P->row;
    }
}

/* Writes the positions of slab k into its plane (set) or clears them;
 * at is scratch for the slab's voxels. */
static void slab_mark(const analysis *W, slab_planes *P, int64_t k, int set, size_t *at)
{
    if (k < 0 || k >= W->g->nz)
        return;
    size_t a, b;
    uint32_t *pl = P->plane[(k + 1) % 3];
    slab_range(W, k, &a, &b);
    slab_entries(W, P, k, a, b, at);
    for (size_t t = a; t < b; t++)
        pl[at[t - a]] = set ? (uint32_t)t : NO_VOXEL;
}

/* The 26 neighbours of slice [lo, hi) by direct loads from the planes, in
 * increasing position order (dz, dy, dx), written unconditionally and
 * kept where a voxel is there; room for 26 more edges is made once a
 * slab. */
static void *link_slice(void *arg)
{
    link_job *J = arg;
    analysis *W = J->W;
    const vbc_grid *g = W->g;
    const uint32_t *sorted = W->sorted;
    size_t nx = (size_t)g->nx, nxy = nx * (size_t)g->ny;
    if (J->lo >= J->hi)
        return NULL;
    slab_planes P;
    P.row = nx + 2;
    size_t psize = P.row * ((size_t)g->ny + 2);
    /* Three planes, then the plane entries of one slab's voxels. */
    uint32_t *mem = malloc(3 * psize * sizeof *mem);
    size_t *at = malloc(nxy * sizeof *at);
    /* Channel voxels have 8 to 9 neighbours on average (adk_oplsaa's 10
     * frames 7.9-8.7, 1af6 9.0): room for 12 a voxel at first spares the
     * doublings. */
    if (!mem || !at || VB_ARRAY_FIT(J->adj, J->cap, 12 * (J->hi - J->lo), 64) != VB_OK ||
        VB_ARRAY_FIT(J->len, J->lcap, 12 * (J->hi - J->lo), 64) != VB_OK) {
        free(mem);
        free(at);
        J->failed = 1;
        return NULL;
    }
    memset(mem, 0xff, 3 * psize * sizeof *mem); /* NO_VOXEL */
    for (int p = 0; p < 3; p++)
        P.plane[p] = mem + (size_t)p * psize;
    int64_t k0 = (int64_t)(sorted[J->lo] / nxy), k1 = (int64_t)(sorted[J->hi - 1] / nxy);
    slab_mark(W, &P, k0 - 1, 1, at);
    slab_mark(W, &P, k0, 1, at);
    size_t t = J->lo;
    for (int64_t k = k0; k <= k1; k++) {
        slab_mark(W, &P, k - 2, 0, at);
        slab_mark(W, &P, k + 1, 1, at);
        const uint32_t *pz[3] = {P.plane[k % 3], P.plane[(k + 1) % 3], P.plane[(k + 2) % 3]};
        size_t a, b;
        slab_range(W, k, &a, &b);
        if (b > J->hi)
            b = J->hi;
        if (VB_ARRAY_FIT(J->adj, J->cap, J->ne + 26 * (b - t), 64) != VB_OK ||
            VB_ARRAY_FIT(J->len, J->lcap, J->ne + 26 * (b - t), 64) != VB_OK) {
            J->failed = 1;
            break;
        }
        uint32_t *adj = J->adj;
        uint8_t *el = J->len;
        size_t a0 = t;
        slab_entries(W, &P, k, t, b, at);
        for (; t < b; t++) {
            size_t e0 = J->ne, ne = J->ne;
            ptrdiff_t c = (ptrdiff_t)at[t - a0];
            /* Nine rows of three, unrolled: the loads do not wait on a table. */
            for (int dz = 0; dz < 3; dz++)
                for (int dy = 0; dy < 3; dy++) {
                    const uint32_t *r = pz[dz] + c + (dy - 1) * (ptrdiff_t)P.row;
                    uint8_t l0 = (uint8_t)((dz != 1) + (dy != 1));
                    uint32_t q0 = r[-1], q1 = r[0], q2 = r[1];
                    adj[ne] = q0;
                    el[ne] = l0 + 1;
                    ne += q0 != NO_VOXEL;
                    if (l0) {
                        adj[ne] = q1;
                        el[ne] = l0;
                        ne += q1 != NO_VOXEL;
                    }
                    adj[ne] = q2;
                    el[ne] = l0 + 1;
                    ne += q2 != NO_VOXEL;
                }
            if (W->vcomp) {
                /* Every edge from both ends, without a branch on which end
                 * is the later (it mispredicts): the same verdict. */
                uint32_t lt = W->vcomp[t], differ = 0;
                for (size_t e = e0; e < ne; e++)
                    differ |= W->vcomp[adj[e]] ^ lt;
                J->bad |= differ != 0;
            }
            J->ne = ne;
            W->A.adj_start[t + 1] = ne - e0;
        }
    }
    free(mem);
    free(at);
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
    size_t nvox = W->nvox, adjcap = 0, lencap = 0;
    int nt = vb_threads(0), failed = 0;
    /* Slices of at least 4096 voxels: below, a thread costs more than it saves. */
    if ((size_t)nt > nvox / 4096)
        nt = nvox / 4096 > 1 ? (int)(nvox / 4096) : 1;
    link_job jobs[VB_MAX_THREADS];
    for (int t = 0; t < nt; t++)
        jobs[t] = (link_job){W, nvox * (size_t)t / (size_t)nt, nvox * (size_t)(t + 1) / (size_t)nt,
                             NULL, NULL, 0, 0, 0, 0, 0};
    vb_run_jobs(link_slice, jobs, sizeof *jobs, nt);
    size_t ne = 0;
    for (int t = 0; t < nt; t++) {
        failed |= jobs[t].failed;
        W->comp_bad |= jobs[t].bad;
        ne += jobs[t].ne;
    }
    if (!failed) {
        A->adj = jobs[0].adj;
        A->adj_len = jobs[0].len;
        adjcap = jobs[0].cap;
        lencap = jobs[0].lcap;
        jobs[0].adj = NULL;
        jobs[0].len = NULL;
        failed = VB_ARRAY_FIT(A->adj, adjcap, ne ? ne : 1, 64) != VB_OK ||
                 VB_ARRAY_FIT(A->adj_len, lencap, ne ? ne : 1, 64) != VB_OK;
    }
    size_t at = jobs[0].ne;
    for (int t = 1; t < nt; t++) {
        if (!failed) {
            memcpy(A->adj + at, jobs[t].adj, jobs[t].ne * sizeof *A->adj);
            memcpy(A->adj_len + at, jobs[t].len, jobs[t].ne);
        }
        at += jobs[t].ne;
        free(jobs[t].adj);
        free(jobs[t].len);
    }
    free(jobs[0].adj);
    free(jobs[0].len);
    if (failed)
        return -1;
    A->adj_start[0] = 0;
    for (size_t t = 0; t < nvox; t++)
        A->adj_start[t + 1] += A->adj_start[t];
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

/* Whether every group of vbc_components_group is connected. Edges join
 * one label only (vbc_voxels_link checked) and a group's first member,
 * its label's voxel, is its smallest position (vbc_components_given
 * checked). Each other member with a smaller neighbour hangs below the
 * smallest one (the first entry of its adjacency row, which ascends by
 * position: link_slice): trees of real edges, whose roots are the first
 * member and the dips of the shape in position order (members without a
 * smaller neighbour). A group with one root is connected at one load a
 * member; otherwise its edges, each from its smaller end, join the roots'
 * trees (a union-find in hpos, scratch here: the sweeps set it again)
 * until one is left, or the group is not connected. */
static int groups_connected(analysis *W)
{
    vbc_graph *A = &W->A;
    vb_uf uf = {A->hpos, W->nvox, 0}; /* the parents in hpos's room (not freed here) */
    uint32_t *P = uf.p;
    for (size_t c = 0; c < W->ncomp; c++) {
        const uint32_t *mem = W->order + W->cstart[c];
        size_t m = W->cstart[c + 1] - W->cstart[c], roots = 0;
        for (size_t t = 0; t < m; t++) {
            uint32_t u = mem[t];
            size_t e0 = A->adj_start[u];
            if (t > 0 && e0 < A->adj_start[u + 1] && A->adj[e0] < u) {
                P[u] = A->adj[e0];
            } else {
                P[u] = u;
                roots++;
            }
        }
        for (size_t t = 0; t < m && roots > 1; t++) {
            uint32_t u = mem[t];
            for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1] && roots > 1; e++) {
                if (A->adj[e] < u)
                    continue;
                uint32_t a = vb_uf_root(&uf, u), b = vb_uf_root(&uf, A->adj[e]);
                if (a != b) {
                    vb_uf_join(&uf, a, b);
                    roots--;
                }
            }
        }
        if (roots > 1)
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
    size_t nvox = W->nvox, pr = nvox;
    uint32_t last = 0;
    /* The positions of the labels met last, by a hash of the label (a
     * voxel's label is mostly one met a row or a plane before). */
    enum { MEMO = 256 };
    uint32_t memo_label[MEMO];
    size_t memo_at[MEMO];
    for (int k = 0; k < MEMO; k++)
        memo_at[k] = SIZE_MAX;
    for (size_t t = 0; t < nvox && !W->comp_bad; t++) {
        uint32_t r = W->vcomp[t];
        /* Runs of voxels share a label: the search only where it changes,
         * and not for a label remembered (the list's indices are
         * distinct, so the answer is the same). */
        if (t == 0 || r != last) {
            unsigned h = (unsigned)((r * 2654435761u) >> 24) % MEMO;
            if (memo_at[h] != SIZE_MAX && memo_label[h] == r) {
                pr = memo_at[h];
            } else {
                const uint32_t *at = bsearch(&r, W->sorted, nvox, sizeof r, cmp_u32_plain);
                pr = at ? (size_t)(at - W->sorted) : nvox;
                memo_label[h] = r;
                memo_at[h] = pr;
            }
            last = r;
        }
        if (pr == nvox || pr > t || W->vcomp[pr] != r)
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
