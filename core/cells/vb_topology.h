/* Cell topology from the sampling pipeline: face adjacency and Voronoi edges
 * between certified vertices (`vorball vertices --topology FILE`). */
#ifndef VB_TOPOLOGY_H
#define VB_TOPOLOGY_H

#include <stdio.h>

#include "vb_proposer.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_topology_edge {
    int64_t v[2];          /* rows of the certified vertex list; v[1] = -1: to infinity */
    uint32_t spheres[3];   /* the three spheres whose faces meet along the edge (sorted) */
} vb_topology_edge;

typedef struct vb_topology {
    uint32_t *faces;       /* pairs i < j sharing a face */
    size_t nfaces;
    vb_topology_edge *edges;
    size_t nedges, edges_cap;
    size_t sampled;        /* edge lines whose triple the two-colour test saw (Sec. 4) */
    size_t unresolved;     /* sampling: trisectors whose edges could not be paired: more
                              than two vertices where doubles find no trisector curve, or
                              a closed edge through a single vertex; exact: vertices whose
                              faces could not be decided (their edges' pairs are used) */
    int exact;             /* 1: from arc closure (vb_arc_topology in verify/arcs/vb_arc.h):
                              edges are the traced arcs, faces decided exactly */
    size_t undecided;      /* exact: half arcs arc closure could not trace */
} vb_topology;

void vb_topology_init(vb_topology *t);
void vb_topology_free(vb_topology *t);

/* Joins the sampler's evidence with the canonical certified vertices of
 * `set` (as written, same row order): faces, and the edges along the
 * trisector of every triple of a vertex. Allocates into *out (free with
 * vb_topology_free). Returns VB_OK or VB_ENOMEM. */
int vb_topology_build(vb_ctx *ctx, const vb_sphere_set *set, const vb_topology_evidence *ev,
                      const vb_vertex_list *vx, vb_topology *out);

/* Writes the faces and edges as tab-separated lines; the header says where
 * they come from (t->exact). An exact edge line is one Voronoi edge (where
 * more than three spheres share it, the triple of its three smallest ids),
 * v1 = v2 a closed loop; a sampled edge line is one per triple whose faces
 * meet along the edge. VB_OK or VB_EIO. */
int vb_topology_write(vb_ctx *ctx, FILE *f, const vb_topology *t);

#ifdef __cplusplus
}
#endif
#endif
