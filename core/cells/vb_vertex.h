/* Vertex lists: candidates from the samplers and certified canonical vertices.
 *
 * One struct serves both: a vertex is a sorted list of sphere ids (4 or more),
 * a point (x, y, z), a tangent radius t, a status and, for certified vertices,
 * the distance between the candidate and the exact point. Ids are stored CSR
 * style: vertex k owns ids[start[k] .. start[k+1]). */
#ifndef VB_VERTEX_H
#define VB_VERTEX_H

#include "vb.h"

#ifdef __cplusplus
extern "C" {
#endif

enum vb_vertex_status {
    VB_VERTEX_CANDIDATE = 0,  /* not yet judged */
    VB_VERTEX_CERTIFIED = 1,  /* exact certifier proved it */
    VB_VERTEX_REJECTED = 2    /* exact certifier refused it */
};

typedef struct vb_vertex_list {
    size_t n, cap;            /* vertices */
    size_t nids, ids_cap;     /* ids in use */
    size_t *start;            /* n + 1 offsets into ids */
    uint32_t *ids;
    double *x, *y, *z, *t;    /* for certified vertices: exact value rounded to nearest (MPFR) */
    double *dist;             /* candidate-to-exact distance; 0 for the reference */
    uint8_t *status;          /* enum vb_vertex_status */
} vb_vertex_list;

/* Initialises an empty list (no allocation). */
void vb_vertex_list_init(vb_vertex_list *v);

/* Frees the arrays and re-initialises. */
void vb_vertex_list_free(vb_vertex_list *v);

/* Appends a vertex; ids need not be sorted (they are sorted on insert).
 * Returns VB_OK or VB_ENOMEM. */
int vb_vertex_list_push(vb_vertex_list *v, const uint32_t *ids, size_t nids, double x,
                        double y, double z, double t, double dist, int status);

/* Sorts into canonical order: by id list (lexicographic, shorter first on a
 * common prefix), then x, y, z, t. Returns VB_OK or VB_ENOMEM. */
int vb_vertex_list_sort(vb_vertex_list *v);

#ifdef __cplusplus
}
#endif
#endif
