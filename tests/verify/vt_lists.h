/* Test helper: vertex lists compared byte for byte (the certifier's output
 * must not depend on the thread count). */
#ifndef VT_LISTS_H
#define VT_LISTS_H

#include <string.h>

#include "vb_vertex.h"

/* 1 when a and b hold the same vertices: ids, points, t and status, and
 * with `with_dist` the distances too; else 0. */
static inline int vt_same_list(const vb_vertex_list *a, const vb_vertex_list *b, int with_dist)
{
    if (a->n != b->n || a->nids != b->nids)
        return 0;
    if (a->n == 0) /* empty lists may have no arrays at all */
        return 1;
    return memcmp(a->start, b->start, (a->n + 1) * sizeof *a->start) == 0 &&
           memcmp(a->ids, b->ids, a->nids * sizeof *a->ids) == 0 &&
           memcmp(a->x, b->x, a->n * sizeof *a->x) == 0 &&
           memcmp(a->y, b->y, a->n * sizeof *a->y) == 0 &&
           memcmp(a->z, b->z, a->n * sizeof *a->z) == 0 &&
           memcmp(a->t, b->t, a->n * sizeof *a->t) == 0 &&
           memcmp(a->status, b->status, a->n) == 0 &&
           (!with_dist || memcmp(a->dist, b->dist, a->n * sizeof *a->dist) == 0);
}

#endif
