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

/* vb_vertex_list_sort, and where[k] (v->n entries, may be NULL) the new row
 * of the vertex that was row k. Returns VB_OK or VB_ENOMEM (v unchanged). */
int vb_vertex_list_sort_perm(vb_vertex_list *v, size_t *where);

/* Appends the vertices of nparts (at most 64) sorted lists to out in
 * canonical order (vb_vertex_list_sort's), a merge that writes a repeat
 * once: an entry with the same members, point and t as the one written
 * before it (one exact vertex of degree > 4 certified in two lists);
 * *dropped (may be NULL) gets their number. VB_OK, VB_ENOMEM (out may then
 * hold part of them) or VB_EMISUSE (more than 64 lists). */
int vb_vertex_list_merge(vb_vertex_list *out, const vb_vertex_list *parts, size_t nparts,
                         size_t *dropped);

/* Appends every vertex of src to dst as it is (no sorting). VB_OK or
 * VB_ENOMEM (dst may then hold part of src). */
int vb_vertex_list_append(vb_vertex_list *dst, const vb_vertex_list *src);

/* Makes v canonical: sorted (vb_vertex_list_sort), exact repeats dropped.
 * A repeat has the same members and the same point and t as the entry
 * before it: the one exact vertex reached twice (through two quadruples of
 * a vertex of degree > 4, by a repair round, or by two processes that
 * certified parts of one input); the first in v's order is kept. *dropped
 * (may be NULL) gets the number dropped. VB_OK, or VB_ENOMEM with v
 * holding the same vertices (perhaps sorted). */
int vb_vertex_list_canonical(vb_vertex_list *v, size_t *dropped);

/* A list as bytes, for another process of the same build and byte order
 * (MPI ranks): *buf (malloc'd, the caller frees) gets *len bytes. VB_OK or
 * VB_ENOMEM. */
int vb_vertex_list_pack(const vb_vertex_list *v, unsigned char **buf, size_t *len);

/* Appends the vertices of a vb_vertex_list_pack buffer to v. VB_OK,
 * VB_ENOMEM, or VB_EINTERNAL (message in ctx) when buf is not such a
 * buffer (wrong size, offsets out of order). */
int vb_vertex_list_unpack(vb_ctx *ctx, const unsigned char *buf, size_t len, vb_vertex_list *v);

#ifdef __cplusplus
}
#endif
#endif
