/* The voxel graph of the channel voxels: Dijkstra sweeps (plain
 * lengths, or lengths weighted by 1/clearance^2) and voxel geometry. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_paths_math.h"
#include "vbc_graph.h"

static void heap_swap(vbc_graph *A, size_t a, size_t b)
{
    uint32_t t = A->heap[a];
    A->heap[a] = A->heap[b];
    A->heap[b] = t;
    A->hpos[A->heap[a]] = (uint32_t)a;
    A->hpos[A->heap[b]] = (uint32_t)b;
}

static int heap_less(const vbc_graph *A, size_t a, size_t b)
{
    double da = A->dist[A->heap[a]], db = A->dist[A->heap[b]];
    return da < db || (da == db && A->heap[a] < A->heap[b]);
}

static void heap_up(vbc_graph *A, size_t i)
{
    while (i > 0 && heap_less(A, i, (i - 1) / 2)) {
        heap_swap(A, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
}

static void heap_down(vbc_graph *A, size_t i)
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

/* Dijkstra over the 26-connected voxel graph of one component (members[0..m))
 * from list position src on a binary heap in (distance, position) order;
 * fills dist/pred for the members. Steps cost vbc_path_step
 * (channel_paths_math.h): their length, or weighted that length / r^2 with
 * r the smaller clearance of the two voxels, so the cheapest path keeps to
 * the widest way through (the cost CAVER-style tools minimise). The
 * definition of vbc_sweep's bytes; radix_sweep gives them faster where
 * every step grows the cost. */
static void heap_sweep(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted,
                       uint32_t target)
{
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
        if (u == target)
            return;
        heap_down(A, 0);
        for (size_t e = A->adj_start[u]; e < A->adj_start[u + 1]; e++) {
            uint32_t q = A->adj[e];
            if (A->hpos[q] == UINT32_MAX - 1)
                continue;
            double nd = A->dist[u] + vbc_path_step(A->adj_len[e], A->clear[u], A->clear[q], weighted);
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

/* The radix heap's states in hpos (positions are below 2^30): */
#define RH_OUT UINT32_MAX           /* never queued */
#define RH_DONE (UINT32_MAX - 1)    /* settled */
#define RH_HEAD 0x80000000u         /* | b: first of bucket b; else the previous entry */
#define RH_BUCKETS 65

static uint64_t key_of(double d)
{
    uint64_t k;
    memcpy(&k, &d, sizeof k);
    return k; /* d >= 0: the bits order as the values */
}

/* The bucket of key k while the last key taken is `last` (k >= last): 0
 * for k == last, else one past the highest bit where they differ. */
static int bucket_of(uint64_t k, uint64_t last)
{
    return k == last ? 0 : 64 - __builtin_clzll(k ^ last);
}

/* busy: bit b - 1 set when bucket b (1..64) holds an entry, so a pop finds
 * the lowest such bucket with one count of trailing zeros instead of a
 * walk over the empty ones (bucket 0 is read from first[0]). low[b]: the
 * least key pushed into bucket b since it was last empty, a lower bound
 * of its keys (an entry moved out by a decrease leaves it lower), so a
 * pop need not walk the bucket's list for its least key first. */
typedef struct {
    uint32_t first[RH_BUCKETS];
    uint64_t low[RH_BUCKETS];
    uint64_t last, busy;
} radix_heap;

static void rh_push(vbc_graph *A, radix_heap *H, uint32_t q)
{
    uint64_t k = key_of(A->dist[q]);
    int b = bucket_of(k, H->last);
    uint32_t f = H->first[b];
    H->low[b] = k < H->low[b] ? k : H->low[b];
    A->heap[q] = f; /* next, by position */
    if (f != RH_OUT)
        A->hpos[f] = q;
    A->hpos[q] = RH_HEAD | (uint32_t)b;
    H->first[b] = q;
    if (b > 0)
        H->busy |= (uint64_t)1 << (b - 1);
}

static void rh_unlink(vbc_graph *A, radix_heap *H, uint32_t q)
{
    uint32_t p = A->hpos[q], nx = A->heap[q];
    if (p & RH_HEAD) {
        uint32_t b = p & ~RH_HEAD;
        H->first[b] = nx;
        if (nx == RH_OUT && b > 0) {
            H->busy &= ~((uint64_t)1 << (b - 1));
            H->low[b] = UINT64_MAX;
        }
    } else {
        A->heap[p] = nx;
    }
    if (nx != RH_OUT)
        A->hpos[nx] = p;
}

/* The entry of least distance (any of a tie), or RH_OUT when empty. */
static uint32_t rh_pop(vbc_graph *A, radix_heap *H)
{
    while (H->first[0] == RH_OUT) {
        if (!H->busy)
            return RH_OUT;
        int b = 1 + __builtin_ctzll(H->busy);
        /* Every key of bucket b shares its bits above b - 1 with the old
         * last, as low[b] does, and is at least low[b]: with it as the
         * new last each moves to a lower bucket (to bucket 0 where it
         * equals it; none may, when the least key pushed there has moved
         * out: the next lowest bucket is taken then). Entries still come
         * out by nondecreasing key, each equal to the last. */
        H->last = H->low[b];
        uint32_t q = H->first[b];
        H->first[b] = RH_OUT;
        H->low[b] = UINT64_MAX;
        H->busy &= ~((uint64_t)1 << (b - 1));
        while (q != RH_OUT) {
            uint32_t nx = A->heap[q];
            rh_push(A, H, q);
            q = nx;
        }
    }
    uint32_t u = H->first[0];
    rh_unlink(A, H, u);
    return u;
}

/* Dijkstra on a radix heap over the bits of the distances (they come out
 * nondecreasing), ties taken in any order and pred[q] kept by
 * vbc_path_pred_before: the smallest (distance, position) among the
 * neighbours that reach q at its distance, the voxel heap_sweep settles
 * first among them (vbc_paths.h). That holds while every step taken grows
 * the cost, fl(d + step) > d: then no voxel settles at the distance of one
 * that reaches it. Returns 1, or 0 when a step did not grow a cost (a
 * clearance past 2^26 of the floor, or a path cost near 2^52 steps): the
 * caller sweeps on the binary heap instead. */
static int radix_sweep(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted,
                       uint32_t target)
{
    radix_heap H;
    for (int b = 0; b < RH_BUCKETS; b++) {
        H.first[b] = RH_OUT;
        H.low[b] = UINT64_MAX;
    }
    H.last = H.busy = 0;
    for (size_t t = 0; t < m; t++) {
        A->dist[members[t]] = INFINITY;
        A->pred[members[t]] = UINT32_MAX;
        A->hpos[members[t]] = RH_OUT;
    }
    /* vbc_path_step's lengths by code, read from a table: the code varies
     * edge to edge, and a branch on it mispredicts (perf: the sweep's
     * hottest instructions). The same constants, so the same costs. */
    static const double len_of[4] = {0.0, 1.0, VBC_PATH_LEN_EDGE, VBC_PATH_LEN_CORNER};
    A->dist[src] = 0.0;
    rh_push(A, &H, src);
    /* The graph's arrays in locals: read through A, every store to dist,
     * pred or hpos (which may alias A as far as C knows) reloads them
     * (perf: the edge loop's loads of A->adj_len and A->clear). */
    const size_t *adj_start = A->adj_start;
    const uint32_t *adj = A->adj;
    const uint8_t *adj_len = A->adj_len;
    const double *clear = A->clear;
    double *dist = A->dist;
    uint32_t *pred = A->pred, *hpos = A->hpos;
    for (uint32_t u; (u = rh_pop(A, &H)) != RH_OUT;) {
        double du = dist[u], cu = clear[u];
        hpos[u] = RH_DONE;
        if (u == target)
            return 1;
        for (size_t e = adj_start[u], end = adj_start[u + 1]; e < end; e++) {
            uint32_t q = adj[e];
            uint32_t hq = hpos[q];
            if (hq == RH_DONE)
                continue;
            double step = len_of[adj_len[e] & 3];
            double nd = du + (weighted ? vbc_path_weigh(step, cu, clear[q]) : step);
            if (!(nd > du))
                return 0;
            if (nd < dist[q]) {
                dist[q] = nd;
                pred[q] = u;
                if (hq != RH_OUT)
                    rh_unlink(A, &H, q);
                rh_push(A, &H, q);
            } else if (nd == dist[q] && vbc_path_pred_before(du, u, dist[pred[q]], pred[q])) {
                pred[q] = u;
            }
        }
    }
    return 1;
}

/* Dijkstra from src over component members[0..m) (vbc_graph.h): the radix
 * heap's sweep, or the binary heap's where it cannot vouch for the bytes;
 * both stop once target is settled (UINT32_MAX: never). */
static void sweep_until(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted,
                        uint32_t target)
{
    if (!radix_sweep(A, members, m, src, weighted, target))
        heap_sweep(A, members, m, src, weighted, target);
}

void vbc_sweep(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted)
{
    sweep_until(A, members, m, src, weighted, UINT32_MAX);
}

/* vbc_sweep stopped once target is settled: every voxel settled before it
 * (its path's among them) has its final distance and predecessor, for a
 * voxel's predecessor never changes after it settles. */
void vbc_sweep_to(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted,
                  uint32_t target)
{
    sweep_until(A, members, m, src, weighted, target);
}

/* The member farthest from the last sweep's source (ties to the lowest position). */
uint32_t vbc_farthest(const vbc_graph *A, const uint32_t *members, size_t m)
{
    uint32_t best = members[0];
    for (size_t t = 1; t < m; t++)
        if (A->dist[members[t]] > A->dist[best])
            best = members[t];
    return best;
}

void vbc_voxel_centre(const vbc_grid *g, uint32_t v, double p[3])
{
    size_t nxy = (size_t)g->nx * (size_t)g->ny;
    p[0] = g->origin[0] + ((double)(v % (uint32_t)g->nx) + 0.5) * g->h;
    p[1] = g->origin[1] + ((double)((v / (uint32_t)g->nx) % (uint32_t)g->ny) + 0.5) * g->h;
    p[2] = g->origin[2] + ((double)(v / nxy) + 0.5) * g->h;
}
