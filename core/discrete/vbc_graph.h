/* Internal to the channel analysis (core/channel_*.c): the voxel graph of
 * the channel voxels of one frame and the operations the component analysis
 * runs on it. Positions are indices into the sorted voxel list. */
#ifndef VBC_GRAPH_H
#define VBC_GRAPH_H

#include "vb_uf.h"
#include "vbc_channel.h"

/* Everything the per-component work shares (one frame). */
typedef struct vbc_graph {
    const vbc_grid *g;
    const uint32_t *v;  /* sorted voxel indices, mouth bit cleared */
    const uint8_t *mouth;
    double *dist;       /* Dijkstra distances (voxel units), per position */
    uint32_t *pred;
    uint32_t *heap;     /* binary heap of positions keyed by dist, or per
                           position the next in its radix heap bucket */
    size_t heapn;
    uint32_t *hpos;     /* position of each list entry in the heap (or the
                           radix heap's link back), or UINT32_MAX */
    const double *clear; /* clearance (Å) per position, for the weighted sweep */
    uint32_t *rep;      /* per opening root: its widest mouth voxel */
    size_t *adj_start;  /* CSR adjacency: neighbours of position u are */
    uint32_t *adj;      /* adj[adj_start[u] .. adj_start[u+1]), 26-connected */
    uint8_t *adj_len;   /* per entry: 1 face, 2 edge, 3 corner neighbour */
    const vb_sphere_set *s;
    int32_t *support;   /* atoms that bound the molecule's width in every direction */
    size_t nsupport;
} vbc_graph;

/* Dijkstra over the 26-connected graph of one component (members[0..m)) from
 * position src; fills dist/pred for the members. Unweighted steps cost their
 * length (voxels), weighted ones length / r^2 with r the smaller clearance of
 * the two voxels, so the cheapest path keeps to the widest way through.
 * pred[q]: of q's neighbours that reach it at its distance, the smallest
 * (distance, position), the first a (distance, position) ordered Dijkstra
 * settles; the sweep runs on a radix heap and falls back to such a binary
 * heap where a step fails to grow a cost (channel_graph.c). */
void vbc_sweep(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted);

/* vbc_sweep until target (a member) is settled: the distances and
 * predecessors along the path from target back to src are vbc_sweep's,
 * the other members' are scratch. For the centreline, which reads that
 * path only. */
void vbc_sweep_to(vbc_graph *A, const uint32_t *members, size_t m, uint32_t src, int weighted,
                  uint32_t target);

/* The member farthest from the last sweep's source (ties to the lowest position). */
uint32_t vbc_farthest(const vbc_graph *A, const uint32_t *members, size_t m);

/* Centre of voxel index v in Å. */
void vbc_voxel_centre(const vbc_grid *g, uint32_t v, double p[3]);

/* The support atoms of A->s in A->support (once: kept while set), which
 * vbc_channel_ends measures widths over; threads sharing A's support call it
 * before they start. Returns 0, or -1 when out of memory. */
int vbc_graph_support(vbc_graph *A);

/* Ends *a, *b of the centreline of a component with mouths (core/discrete/channel_ends.c);
 * *through = 1 when they lie on opposite faces of the molecule. uf is
 * scratch over every position (its sets are reset for the members).
 * Returns 0, or -1 when out of memory. */
int vbc_channel_ends(vbc_graph *A, vb_uf *uf, const uint32_t *members, size_t m,
                     uint32_t *a, uint32_t *b, int *through);

/* vbc_channel_ends without its one sweep: *b is UINT32_MAX when the member
 * farthest from *a along the voxels (plain lengths, vbc_farthest's ties)
 * ends the line; the caller sweeps (vbc_paths.h batches them). Returns 0,
 * or -1 when out of memory. */
int vbc_channel_openings(vbc_graph *A, vb_uf *uf, const uint32_t *members, size_t m,
                         uint32_t *a, uint32_t *b, int *through);

#endif
