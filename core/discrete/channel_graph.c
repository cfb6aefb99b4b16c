/* The voxel graph of the channel voxels: Dijkstra sweeps (plain
 * lengths, or lengths weighted by 1/clearance^2) and voxel geometry. */
#include <math.h>
#include <stdlib.h>

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
 * from list position src; fills dist/pred for the members. Steps cost
 * vbc_path_step (channel_paths_math.h): their length, or weighted that
 * length / r^2 with r the smaller clearance of the two voxels, so the
 * cheapest path keeps to the widest way through (the cost CAVER-style tools
 * minimise). */
void vbc_sweep(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted)
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
