/* Connected components of the channel voxels, their classification (channel
 * or cavity), centrelines with clearance radii, bottlenecks, lining atoms and
 * pruning: the analysis the paper left out (Sec. 4.1). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_channel.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a & ~VBC_MOUTH_BIT, y = *(const uint32_t *)b & ~VBC_MOUTH_BIT;
    return (x > y) - (x < y);
}

static uint32_t uf_find(uint32_t *parent, uint32_t a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

static void uf_union(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    /* The smaller root wins so component ids do not depend on visiting order. */
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* Everything the per-component work shares. */
typedef struct {
    const vbc_grid *g;
    const uint32_t *v;  /* sorted voxel indices, mouth bit cleared */
    const uint8_t *mouth;
    double *dist;       /* Dijkstra distances (voxel units), per position */
    uint32_t *pred;
    uint32_t *heap;     /* binary heap of positions keyed by dist */
    size_t heapn;
    uint32_t *hpos;     /* position of each list entry in the heap, or UINT32_MAX */
    const double *clear; /* clearance (Å) per position, for the weighted sweep */
    uint32_t *rep;      /* per opening root: its widest mouth voxel */
    size_t *adj_start;  /* CSR adjacency: neighbours of position u are */
    uint32_t *adj;      /* adj[adj_start[u] .. adj_start[u+1]), 26-connected */
    uint8_t *adj_len;   /* per entry: 1 face, 2 edge, 3 corner neighbour */
    const vb_sphere_set *s;
    int32_t *support;   /* atoms that bound the molecule's width in every direction */
    size_t nsupport;
} ana;

static void heap_swap(ana *A, size_t a, size_t b)
{
    uint32_t t = A->heap[a];
    A->heap[a] = A->heap[b];
    A->heap[b] = t;
    A->hpos[A->heap[a]] = (uint32_t)a;
    A->hpos[A->heap[b]] = (uint32_t)b;
}

static int heap_less(const ana *A, size_t a, size_t b)
{
    double da = A->dist[A->heap[a]], db = A->dist[A->heap[b]];
    return da < db || (da == db && A->heap[a] < A->heap[b]);
}

static void heap_up(ana *A, size_t i)
{
    while (i > 0 && heap_less(A, i, (i - 1) / 2)) {
        heap_swap(A, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
}

static void heap_down(ana *A, size_t i)
{
    for (;;) {
        size_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < A->heapn && heap_less(A, l, m))
            m = l;
        if (r < A->heapn && heap_less(A, r, m))
            m = r;
        if (m == i)
            return;
        heap_swap(A, i, m);
        i = m;
    }
}

/* Smallest clearance used in the path cost, so a voxel touching an atom still
 * has a finite (if huge) cost. */
#define MIN_CLEAR 0.05

/* Dijkstra over the 26-connected voxel graph of one component (members[0..m))
 * from list position src; fills dist/pred for the members. Unweighted steps
 * cost their length; weighted ones length / r^2 with r the smaller clearance
 * of the two voxels, so the cheapest path keeps to the widest way through
 * (the cost CAVER-style tools minimise). */
static void sweep(ana *A, const uint32_t *members, size_t m, uint32_t src, int weighted)
{
    static const double w[4] = {0.0, 1.0, 1.4142135623730951, 1.7320508075688772};
    for (size_t t = 0; t < m; t++) {
        A->dist[members[t]] = INFINITY;
        A->pred[members[t]] = UINT32_MAX;
        A->hpos[members[t]] = UINT32_MAX;
    }
    A->dist[src] = 0.0;
    A->heapn = 0;
    A->heap[A->heapn] = src;
    A->hpos[src] = (uint32_t)A->heapn++;
    while (A->heapn > 0) {
        uint32_t u = A->heap[0];
        heap_swap(A, 0, A->heapn - 1);
        A->heapn--;
        A->hpos[u] = UINT32_MAX - 1; /* settled */
        heap_down(A, 0);
        for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1]; e++) {
            uint32_t q = A->adj[e];
            if (A->hpos[q] == UINT32_MAX - 1)
                continue;
            double step = w[A->adj_len[e]];
            if (weighted) {
                double r = fmax(fmin(A->clear[u], A->clear[q]), MIN_CLEAR);
                step /= r * r;
            }
            double nd = A->dist[u] + step;
            if (nd < A->dist[q]) {
                A->dist[q] = nd;
                A->pred[q] = u;
                if (A->hpos[q] == UINT32_MAX) {
                    A->heap[A->heapn] = q;
                    A->hpos[q] = (uint32_t)A->heapn++;
                }
                heap_up(A, A->hpos[q]);
            }
        }
    }
}

/* The member farthest from the last sweep's source (ties to the lowest position). */
static uint32_t farthest(const ana *A, const uint32_t *members, size_t m)
{
    uint32_t best = members[0];
    for (size_t t = 1; t < m; t++)
        if (A->dist[members[t]] > A->dist[best])
            best = members[t];
    return best;
}

static void voxel_centre(const vbc_grid *g, uint32_t v, double p[3])
{
    size_t nxy = (size_t)g->nx * (size_t)g->ny;
    p[0] = g->origin[0] + ((double)(v % (uint32_t)g->nx) + 0.5) * g->h;
    p[1] = g->origin[1] + ((double)((v / (uint32_t)g->nx) % (uint32_t)g->ny) + 0.5) * g->h;
    p[2] = g->origin[2] + ((double)(v / nxy) + 0.5) * g->h;
}

/* A pair of openings counts as "through" the molecule when they are at
 * least this fraction of the molecule's width apart along the line joining
 * them: two mouths of a pore on opposite faces, not two openings of one
 * vestibule or of one groove. */
#define THROUGH_RATIO 0.6

/* Width of the molecule along unit vector u, from its support atoms. */
static double width_along(const ana *A, const double u[3])
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t t = 0; t < A->nsupport; t++) {
        int32_t i = A->support[t];
        double c = A->s->x[i] * u[0] + A->s->y[i] * u[1] + A->s->z[i] * u[2];
        lo = fmin(lo, c - A->s->r[i]);
        hi = fmax(hi, c + A->s->r[i]);
    }
    return hi - lo;
}

static int through_pair(const ana *A, uint32_t ra, uint32_t rb)
{
    double pa[3], pb[3], u[3];
    voxel_centre(A->g, A->v[ra], pa);
    voxel_centre(A->g, A->v[rb], pb);
    double d = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                    (pa[2] - pb[2]) * (pa[2] - pb[2]));
    if (d == 0.0)
        return 0;
    for (int k = 0; k < 3; k++)
        u[k] = (pb[k] - pa[k]) / d;
    return d >= THROUGH_RATIO * width_along(A, u);
}

typedef struct {
    double c;
    uint32_t pos;
} by_clear;

static int cmp_by_clear(const void *x, const void *y)
{
    const by_clear *a = x, *b = y;
    if (a->c != b->c)
        return a->c < b->c ? 1 : -1;
    return (a->pos > b->pos) - (a->pos < b->pos);
}

/* The widest pair of openings that lies through the molecule: voxels enter by
 * decreasing clearance (a maximum spanning forest, as in Kruskal); the first
 * union that joins two openings forming a through pair decides, and the
 * clearance at that moment is the best bottleneck any path between them can
 * have. Returns 1 with *a, *b set, 0 when no pair is through, -1 on ENOMEM. */
static int widest_through(ana *A, uint32_t *parent, const uint32_t *members, size_t m,
                          const uint32_t *reps, size_t k, uint32_t *a, uint32_t *b)
{
    by_clear *S = malloc(m * sizeof *S);
    uint32_t *head = malloc(m * sizeof *head), *tail = malloc(m * sizeof *tail);
    uint32_t *next = malloc(k * sizeof *next);
    int found = 0;
    if (!S || !head || !tail || !next) {
        found = -1;
        goto out;
    }
    /* Positions are global; index the scratch by order in `members` via pred. */
    for (size_t t = 0; t < m; t++) {
        S[t].c = A->clear[members[t]];
        S[t].pos = members[t];
        A->pred[members[t]] = (uint32_t)t;   /* local index */
        A->hpos[members[t]] = 0;             /* not yet added */
        head[t] = tail[t] = UINT32_MAX;
    }
    for (size_t r = 0; r < k; r++) {
        uint32_t l = A->pred[reps[r]];
        head[l] = tail[l] = (uint32_t)r;
        next[r] = UINT32_MAX;
    }
    qsort(S, m, sizeof *S, cmp_by_clear);
    for (size_t t = 0; t < m && !found; t++) {
        uint32_t u = S[t].pos;
        A->hpos[u] = 1;
        parent[u] = u;
        for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1] && !found; e++) {
            uint32_t q = A->adj[e];
            if (!A->hpos[q])
                continue;
            uint32_t ru = uf_find(parent, u), rq = uf_find(parent, (uint32_t)q);
            if (ru == rq)
                continue;
            uint32_t lu = A->pred[ru], lq = A->pred[rq];
            for (uint32_t x = head[lu]; x != UINT32_MAX && !found; x = next[x])
                for (uint32_t y = head[lq]; y != UINT32_MAX && !found; y = next[y])
                    if (through_pair(A, reps[x], reps[y])) {
                        *a = reps[x < y ? x : y];
                        *b = reps[x < y ? y : x];
                        found = 1;
                    }
            uf_union(parent, ru, rq);
            uint32_t root = uf_find(parent, ru), lr = A->pred[root], lo = root == ru ? lq : lu;
            /* Concatenate the opening lists into the surviving root's. */
            if (head[lo] != UINT32_MAX) {
                if (head[lr] == UINT32_MAX) {
                    head[lr] = head[lo];
                } else {
                    next[tail[lr]] = head[lo];
                }
                tail[lr] = tail[lo];
                head[lo] = tail[lo] = UINT32_MAX;
            }
        }
    }
out:
    free(S);
    free(head);
    free(tail);
    free(next);
    return found;
}

/* Atoms extreme along any of SUPPORT_DIRS directions (Fibonacci sphere):
 * the width of the molecule along a direction is then measured over these
 * few atoms instead of all. *out is malloc'ed. */
#define SUPPORT_DIRS 64

static int support_atoms(const vb_sphere_set *s, int32_t **out, size_t *count)
{
    int32_t *list = malloc(2 * SUPPORT_DIRS * sizeof *list);
    if (!list)
        return -1;
    size_t n = 0;
    for (int d = 0; d < SUPPORT_DIRS; d++) {
        double z = 1.0 - (2.0 * d + 1.0) / SUPPORT_DIRS, r = sqrt(1.0 - z * z);
        double u[3] = {r * cos(2.39996322972865332 * d), r * sin(2.39996322972865332 * d), z};
        int32_t lo = 0, hi = 0;
        double vlo = INFINITY, vhi = -INFINITY;
        for (size_t i = 0; i < s->n; i++) {
            double c = s->x[i] * u[0] + s->y[i] * u[1] + s->z[i] * u[2];
            if (c - s->r[i] < vlo) {
                vlo = c - s->r[i];
                lo = (int32_t)i;
            }
            if (c + s->r[i] > vhi) {
                vhi = c + s->r[i];
                hi = (int32_t)i;
            }
        }
        list[n++] = lo;
        list[n++] = hi;
    }
    *out = list;
    *count = n;
    return 0;
}

/* Ends of the centreline of a component with mouths. Mouth voxels that touch
 * each other form one opening, represented by its widest voxel. The line
 * joins the widest pair of openings through the molecule (a pore: its two
 * mouths; *through = 1); failing that the two openings farthest apart, or,
 * with a single opening, the opening and the member farthest along the
 * voxels (a dead-end tunnel). Returns 0, or -1 when out of memory. */
static int channel_ends(ana *A, uint32_t *parent, const uint32_t *members, size_t m, uint32_t *a,
                        uint32_t *b, int *through)
{
    *through = 0;
    for (size_t t = 0; t < m; t++) {
        parent[members[t]] = members[t];
        A->rep[members[t]] = UINT32_MAX;
    }
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (!A->mouth[u])
            continue;
        for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1]; e++)
            if (A->mouth[A->adj[e]])
                uf_union(parent, u, A->adj[e]);
    }
    /* The widest voxel of each opening, kept at the opening's root. */
    size_t k = 0;
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (!A->mouth[u])
            continue;
        uint32_t r = uf_find(parent, u);
        if (A->rep[r] == UINT32_MAX) {
            k++;
            A->rep[r] = u;
        } else if (A->clear[u] > A->clear[A->rep[r]]) {
            A->rep[r] = u;
        }
    }
    uint32_t *reps = malloc(k * sizeof *reps);
    if (!reps)
        return -1;
    k = 0;
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (A->mouth[u] && parent[u] == u)
            reps[k++] = A->rep[u];
    }
    if (k >= 2 && !A->support && support_atoms(A->s, &A->support, &A->nsupport) != 0) {
        free(reps);
        return -1;
    }
    int w = k >= 2 ? widest_through(A, parent, members, m, reps, k, a, b) : 0;
    if (w < 0) {
        free(reps);
        return -1;
    }
    if (w == 1) {
        *through = 1;
        free(reps);
        return 0;
    }
    /* No through pair: the farthest pair of openings (ties to the lowest). */
    uint32_t ba = reps[0], bb = UINT32_MAX;
    double best = -1.0;
    for (size_t x = 0; x < k; x++) {
        double px[3];
        voxel_centre(A->g, A->v[reps[x]], px);
        for (size_t y = x + 1; y < k; y++) {
            double py[3];
            voxel_centre(A->g, A->v[reps[y]], py);
            double d = (px[0] - py[0]) * (px[0] - py[0]) + (px[1] - py[1]) * (px[1] - py[1]) +
                       (px[2] - py[2]) * (px[2] - py[2]);
            if (d > best) {
                best = d;
                ba = reps[x];
                bb = reps[y];
            }
        }
    }
    free(reps);
    if (bb == UINT32_MAX) {
        sweep(A, members, m, ba, 0);
        bb = farthest(A, members, m);
    }
    *a = ba;
    *b = bb;
    return 0;
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
    ana A;
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
        qsort(key, nvox, sizeof *key, cmp_u64);
        for (size_t t = 0; t < nvox; t++) {
            size_t from = (size_t)(key[t] & 0xffffffffu);
            sorted[t] = vox[from];
            clear[t] = vclear[from];
            near[t] = -1;
        }
        free(key);
    } else {
        memcpy(sorted, vox, nvox * sizeof *sorted);
        qsort(sorted, nvox, sizeof *sorted, cmp_u32);
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
                        uf_union(parent, (uint32_t)t, (uint32_t)q);
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
        uint32_t r = uf_find(parent, (uint32_t)t);
        if (r == t)
            comp[t] = (uint32_t)ncomp++;
    }
    memset(cstart, 0, (ncomp + 1) * sizeof *cstart);
    for (size_t t = 0; t < nvox; t++)
        cstart[comp[uf_find(parent, (uint32_t)t)] + 1]++;
    for (size_t c = 0; c < ncomp; c++)
        cstart[c + 1] += cstart[c];
    for (size_t t = 0; t < nvox; t++) {
        uint32_t c = comp[uf_find(parent, (uint32_t)t)];
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
            voxel_centre(g, sorted[mem[t]], p);
            clear[mem[t]] = vbc_cells_clearance(cells, p, &near[mem[t]]);
        }
        uint32_t a, b;
        int through = 0;
        if (kind == VBC_CHANNEL) {
            if (channel_ends(&A, parent, mem, m, &a, &b, &through) != 0)
                goto done;
        } else {
            /* A cavity spans its extent: double sweep over plain lengths. */
            sweep(&A, mem, m, mem[0], 0);
            a = farthest(&A, mem, m);
            sweep(&A, mem, m, a, 0);
            b = farthest(&A, mem, m);
        }
        /* The centreline: the cheapest (widest) way from a to b. */
        sweep(&A, mem, m, a, 1);
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
        vbc_channel ch = {kind, through, m, nm, 0.0, INFINITY, 0, p0, np, 0, 0};
        L.stamp++;
        size_t l0 = L.n;
        for (size_t t = 0; t < np; t++) {
            uint32_t q = path[np - 1 - t];
            vbc_point *pt = &res->points[p0 + t];
            double p[3];
            voxel_centre(g, sorted[q], p);
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
