/* Connected components of the channel voxels, their classification (channel
 * or cavity), centrelines with clearance radii, bottlenecks, lining atoms and
 * pruning: the analysis the paper left out (Sec. 4.1). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    if (L->n == L->cap) {
        size_t cap = L->cap ? 2 * L->cap : 256;
        int32_t *p = realloc(L->list, cap * sizeof *p);
        if (!p) {
            L->failed = 1;
            return;
        }
        L->list = p;
        L->cap = cap;
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

/* Grows an array of `size`-byte elements to hold at least `need`. */
static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * size);
    if (!q)
        return -1;
    *p = q;
    *cap = c;
    return 0;
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

int vbc_analyse_clear(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, size_t nvox, const vbc_options *opt, vbc_result *res)
{
    memset(res, 0, sizeof *res);
    if (nvox == 0)
        return VB_OK;
    if (nvox >= ((size_t)1 << 30))
        return vb_error(ctx, VB_EINPUT_TOOLARGE, NULL, 0, "%zu channel voxels: too many", nvox);
    int rc = VB_ENOMEM;
    vbc_graph A;
    memset(&A, 0, sizeof A);
    A.g = g;
    uint32_t *sorted = malloc(nvox * sizeof *sorted);
    uint8_t *mouth = malloc(nvox);
    uint32_t *parent = malloc(nvox * sizeof *parent);
    uint32_t *order = malloc(nvox * sizeof *order);
    size_t *cstart = malloc((nvox + 1) * sizeof *cstart);
    uint32_t *comp = malloc(nvox * sizeof *comp);
    A.dist = malloc(nvox * sizeof *A.dist);
    A.pred = malloc(nvox * sizeof *A.pred);
    A.heap = malloc(nvox * sizeof *A.heap);
    A.hpos = malloc(nvox * sizeof *A.hpos);
    A.rep = malloc(nvox * sizeof *A.rep);
    double *clear = malloc(nvox * sizeof *clear);
    int32_t *near = malloc(nvox * sizeof *near);
    lining_acc L = {calloc(s->n, sizeof(int32_t)), 0, NULL, 0, 0, 0};
    vbc_cells *cells = NULL;
    uint32_t *path = NULL;
    size_t pathcap = 0, chcap = 0, ptcap = 0;
    if (!sorted || !mouth || !parent || !order || !cstart || !comp || !A.dist || !A.pred ||
        !A.heap || !A.hpos || !A.rep || !clear || !near || !L.mark)
        goto done;
    A.clear = clear;
    if (vclear) {
        /* Sort (index, original slot) pairs so the clearances follow. */
        uint64_t *key = malloc(nvox * sizeof *key);
        if (!key)
            goto done;
        for (size_t t = 0; t < nvox; t++)
            key[t] = ((uint64_t)(vox[t] & ~VBC_MOUTH_BIT) << 32) | (uint64_t)t;
        /* Keys are distinct (the slot is in them): one sorted order on any
         * number of threads. */
        if (vb_psort(key, nvox, sizeof *key, cmp_u64, vb_threads(0)) != VB_OK) {
            free(key);
            goto done;
        }
        for (size_t t = 0; t < nvox; t++) {
            size_t from = (size_t)(key[t] & 0xffffffffu);
            sorted[t] = vox[from];
            clear[t] = vclear[from];
            near[t] = -1;
        }
        free(key);
    } else {
        memcpy(sorted, vox, nvox * sizeof *sorted);
        if (vb_psort(sorted, nvox, sizeof *sorted, cmp_u32, vb_threads(0)) != VB_OK)
            goto done;
    }
    for (size_t t = 0; t < nvox; t++) {
        mouth[t] = (sorted[t] & VBC_MOUTH_BIT) != 0;
        sorted[t] &= ~VBC_MOUTH_BIT;
        parent[t] = (uint32_t)t;
    }
    A.v = sorted;
    A.mouth = mouth;

    /* The voxel graph once (26-connectivity), then its components. The list is
     * sorted, so the neighbours of voxel v in the row at offset o = dy*nx +
     * dz*nx*ny lie at v + o - 1 .. v + o + 1, and a cursor per row offset only
     * ever moves forward: the whole graph costs a linear merge, no lookups. */
    size_t nxy = (size_t)g->nx * (size_t)g->ny, adjcap = 0, ne = 0;
    size_t cursor[9] = {0};
    A.adj_start = malloc((nvox + 1) * sizeof *A.adj_start);
    if (!A.adj_start)
        goto done;
    for (size_t t = 0; t < nvox; t++) {
        A.adj_start[t] = ne;
        uint32_t v = sorted[t];
        int i = (int)(v % (uint32_t)g->nx), j = (int)((v / (uint32_t)g->nx) % (uint32_t)g->ny);
        int k = (int)(v / nxy);
        if (grow((void **)&A.adj, &adjcap, ne + 26, sizeof *A.adj))
            goto done;
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
                    A.adj[ne++] = (uint32_t)q | ((uint32_t)(abs(dx) + abs(dy) + abs(dz)) << 30);
                    if (q > t)
                        vbc_uf_union(parent, (uint32_t)t, (uint32_t)q);
                }
            }
    }
    A.adj_start[nvox] = ne;
    A.adj_len = malloc(ne ? ne : 1);
    if (!A.adj_len)
        goto done;
    for (size_t e = 0; e < ne; e++) {
        A.adj_len[e] = (uint8_t)(A.adj[e] >> 30);
        A.adj[e] &= 0x3fffffffu;
    }
    /* Components as CSR over `order`, numbered by their lowest voxel. */
    size_t ncomp = 0;
    for (size_t t = 0; t < nvox; t++) {
        uint32_t r = vbc_uf_find(parent, (uint32_t)t);
        if (r == t)
            comp[t] = (uint32_t)ncomp++;
    }
    memset(cstart, 0, (ncomp + 1) * sizeof *cstart);
    for (size_t t = 0; t < nvox; t++)
        cstart[comp[vbc_uf_find(parent, (uint32_t)t)] + 1]++;
    for (size_t c = 0; c < ncomp; c++)
        cstart[c + 1] += cstart[c];
    for (size_t t = 0; t < nvox; t++) {
        uint32_t c = comp[vbc_uf_find(parent, (uint32_t)t)];
        order[cstart[c]++] = (uint32_t)t;
    }
    for (size_t c = ncomp; c > 0; c--)
        cstart[c] = cstart[c - 1];
    cstart[0] = 0;
    res->components = ncomp;

    if ((rc = vbc_cells_build(ctx, s, 3.0, &cells)) != VB_OK)
        goto done;
    rc = VB_ENOMEM;
    A.s = s;
    for (size_t c = 0; c < ncomp; c++) {
        const uint32_t *mem = order + cstart[c];
        size_t m = cstart[c + 1] - cstart[c];
        size_t nm = 0;
        for (size_t t = 0; t < m; t++)
            nm += mouth[mem[t]];
        int kind = nm > 0 ? VBC_CHANNEL : VBC_CAVITY;
        /* A path through m voxels is at most (m - 1) long diagonals: components
         * too small for min_length are pruned before any distance is computed
         * (most components are specks in grooves). */
        if ((kind == VBC_CAVITY && !opt->keep_cavities) ||
            (double)(m - 1) * 1.7320508075688772 * g->h < opt->min_length) {
            res->pruned++;
            continue;
        }
        for (size_t t = 0; t < m && !vclear; t++) {
            double p[3];
            vbc_voxel_centre(g, sorted[mem[t]], p);
            clear[mem[t]] = vbc_cells_clearance(cells, p, &near[mem[t]]);
        }
        uint32_t a, b;
        int through = 0;
        if (kind == VBC_CHANNEL) {
            if (vbc_channel_ends(&A, parent, mem, m, &a, &b, &through) != 0)
                goto done;
        } else {
            /* A cavity spans its extent: double sweep over plain lengths. */
            vbc_sweep(&A, mem, m, mem[0], 0);
            a = vbc_farthest(&A, mem, m);
            vbc_sweep(&A, mem, m, a, 0);
            b = vbc_farthest(&A, mem, m);
        }
        /* The centreline: the cheapest (widest) way from a to b. */
        vbc_sweep(&A, mem, m, a, 1);
        size_t np = 0;
        for (uint32_t q = b; q != UINT32_MAX; q = A.pred[q]) {
            if (grow((void **)&path, &pathcap, np + 1, sizeof *path))
                goto done;
            path[np++] = q;
        }
        size_t p0 = 0;
        for (size_t t = 0; t < res->nchannels; t++)
            p0 += res->channels[t].npoints;
        if (grow((void **)&res->points, &ptcap, p0 + np, sizeof *res->points))
            goto done;
        vbc_channel ch = {kind, kind == VBC_CAVITY ? VBC_WHY_CAVITY : through ? VBC_WHY_THROUGH : VBC_WHY_TUNNEL,
                          through, m, nm, 0.0, INFINITY, 0, p0, np, 0, 0};
        L.stamp++;
        size_t l0 = L.n;
        for (size_t t = 0; t < np; t++) {
            uint32_t q = path[np - 1 - t];
            vbc_point *pt = &res->points[p0 + t];
            double p[3];
            vbc_voxel_centre(g, sorted[q], p);
            pt->x = p[0];
            pt->y = p[1];
            pt->z = p[2];
            /* Reported radii are always the exact (double) cell-list answer. */
            if (vclear)
                pt->r = vbc_cells_clearance(cells, p, &pt->atom);
            else {
                pt->r = clear[q];
                pt->atom = near[q];
            }
            if (t > 0) {
                const vbc_point *q = pt - 1;
                ch.length += sqrt((p[0] - q->x) * (p[0] - q->x) + (p[1] - q->y) * (p[1] - q->y) +
                                  (p[2] - q->z) * (p[2] - q->z));
            }
            if (pt->r < ch.bottleneck) {
                ch.bottleneck = pt->r;
                ch.bottleneck_at = t;
            }
            vbc_cells_within(cells, p, pt->r + opt->lining_tol, lining_add, &L);
            if (L.failed)
                goto done;
        }
        if (ch.length < opt->min_length || ch.bottleneck < opt->min_radius) {
            res->pruned++;
            L.n = l0;
            continue;
        }
        if (L.n - l0 > 1)
            qsort(L.list + l0, L.n - l0, sizeof *L.list, cmp_i32);
        ch.first_lining = l0;
        ch.nlining = L.n - l0;
        if (grow((void **)&res->channels, &chcap, res->nchannels + 1, sizeof *res->channels))
            goto done;
        res->channels[res->nchannels++] = ch;
    }
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_channel);
    res->lining = L.list;
    L.list = NULL;
    rc = VB_OK;
done:
    if (rc == VB_ENOMEM)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "channel analysis of %zu voxels", nvox);
    if (rc != VB_OK)
        vbc_result_free(res);
    free(sorted);
    free(mouth);
    free(parent);
    free(order);
    free(cstart);
    free(comp);
    free(A.dist);
    free(A.pred);
    free(A.heap);
    free(A.hpos);
    free(A.rep);
    free(A.support);
    free(A.adj_start);
    free(A.adj);
    free(A.adj_len);
    free(clear);
    free(near);
    free(L.mark);
    free(L.list);
    free(path);
    vbc_cells_free(cells);
    return rc;
}

void vbc_result_free(vbc_result *res)
{
    free(res->channels);
    free(res->points);
    free(res->lining);
    memset(res, 0, sizeof *res);
}
