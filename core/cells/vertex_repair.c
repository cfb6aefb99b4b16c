/* The repair rounds of the vertex pipeline (vbv_certify.h): candidates the
 * certifier refused because a sphere cuts their tangent sphere sit next to
 * vertices with that sphere, so the quadruples with the intruder swapped in
 * are certified, for a few rounds (jittered lattices, nearly degenerate
 * protein vertices). Moved out of vertices.c, which orchestrates. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_sampler.h"
#include "vbv_certify.h"

/* Sorted quadruples already handed to the certifier. */
typedef struct quads {
    uint32_t *q;
    size_t n, cap;
} quads;

static int quads_add(quads *s, const vb_vertex_list *v)
{
    for (size_t k = 0; k < v->n; k++) {
        if (v->start[k + 1] - v->start[k] != 4)
            continue;
        s->q = vb_array_grow(s->q, &s->cap, s->n + 1, 4 * sizeof *s->q, 1024);
        if (s->cap < s->n + 1)
            return VB_ENOMEM;
        memcpy(s->q + 4 * s->n++, v->ids + v->start[k], 4 * sizeof *s->q);
    }
    if (s->n)
        qsort(s->q, s->n, 4 * sizeof *s->q, vb_quad_cmp);
    return VB_OK;
}

/* Appends src to dst and makes dst canonical again (sorted, exact repeats
 * dropped: the same canonical vertex). */
static int merge_certified(vb_vertex_list *dst, const vb_vertex_list *src)
{
    int rc = vb_vertex_list_append(dst, src);
    return rc == VB_OK ? vb_vertex_list_canonical(dst, NULL) : rc;
}

int vbv_vertices_repair(vb_ctx *ctx, const vb_sphere_set *set, const vb_certifier_ops *ops,
                        void *cert, vb_vertices_result *res)
{
    quads seen = {0};
    vb_vertex_list todo, next, ok, bad;
    vb_vertex_list_init(&todo);
    vb_vertex_list_init(&next);
    vb_vertex_list_init(&ok);
    vb_vertex_list_init(&bad);
    int rc = quads_add(&seen, &res->proposal.candidates);
    for (size_t k = 0; rc == VB_OK && k < res->rejected.n; k++)
        rc = vb_vertex_list_push(&todo, res->rejected.ids + res->rejected.start[k],
                                 res->rejected.start[k + 1] - res->rejected.start[k],
                                 res->rejected.x[k], res->rejected.y[k], res->rejected.z[k],
                                 res->rejected.t[k], 0.0, VB_VERTEX_CANDIDATE);
    for (int round = 0; rc == VB_OK && round < 4 && todo.n > 0; round++) {
        vb_vertex_list swaps;
        vb_vertex_list_init(&swaps);
        for (size_t k = 0; rc == VB_OK && k < todo.n; k++) {
            const uint32_t *ids = todo.ids + todo.start[k];
            if (todo.start[k + 1] - todo.start[k] != 4)
                continue;
            double p[4] = {todo.x[k], todo.y[k], todo.z[k], todo.t[k]};
            uint32_t intruder;
            rc = ops->intruder(ctx, cert, ids, p, &intruder);
            if (rc == VB_OK && intruder != UINT32_MAX)
                rc = vb_sampler_swap_candidates(set, ids, intruder, p, &swaps);
        }
        /* Keep the swaps not certified before. */
        for (size_t k = 0; rc == VB_OK && k < swaps.n; k++) {
            const uint32_t *q = swaps.ids + swaps.start[k];
            if (seen.n && bsearch(q, seen.q, seen.n, 4 * sizeof *seen.q, vb_quad_cmp))
                continue;
            rc = vb_vertex_list_push(&next, q, 4, swaps.x[k], swaps.y[k], swaps.z[k], swaps.t[k],
                                     0.0, VB_VERTEX_CANDIDATE);
        }
        vb_vertex_list_free(&swaps);
        if (rc == VB_OK)
            rc = quads_add(&seen, &next);
        if (rc == VB_OK)
            rc = ops->certify_list(ctx, cert, &next, &ok, &bad);
        if (rc == VB_OK)
            rc = merge_certified(&res->certified, &ok);
        res->repaired_candidates += next.n;
        vb_vertex_list_free(&todo);
        todo = bad;
        vb_vertex_list_init(&bad);
        vb_vertex_list_free(&next);
        vb_vertex_list_free(&ok);
    }
    vb_vertex_list_free(&todo);
    free(seen.q);
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (repair)");
    return rc;
}
