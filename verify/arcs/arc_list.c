/* Arc closure of a list the pipeline certified (vb_arc_complete_list), the
 * certificate as a header line and its counters for --stats. */
#include <stdio.h>
#include <stdlib.h>

#include "vb_arc.h"
#include "vb_parallel.h"

static int edge_cmp(const void *pa, const void *pb)
{
    const vb_topology_edge *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->spheres[i] != b->spheres[i])
            return a->spheres[i] < b->spheres[i] ? -1 : 1;
    for (int i = 0; i < 2; i++)
        if (a->v[i] != b->v[i])
            return a->v[i] < b->v[i] ? -1 : 1;
    return 0;
}

int vb_arc_complete_list_edges(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                               vb_vertex_list *list, unsigned threads, vb_arc_report *out,
                               vb_topology_edge **edges, size_t *nedges)
{
    return vb_arc_complete_list_early(ctx, set, cert, NULL, list, threads, out, edges, nedges);
}

int vb_arc_complete_list_early(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                               const vb_arc_early *early, vb_vertex_list *list,
                               unsigned threads, vb_arc_report *out, vb_topology_edge **edges,
                               size_t *nedges)
{
    double t0 = vb_now();
    size_t *where = NULL;
    int rc = vb_arc_close_early(ctx, set, cert, early, list, threads, out, edges, nedges);
    const vb_vertex_list *a = &out->added;
    for (size_t k = 0; rc == VB_OK && k < a->n; k++)
        rc = vb_vertex_list_push(list, a->ids + a->start[k], a->start[k + 1] - a->start[k],
                                 a->x[k], a->y[k], a->z[k], a->t[k], 0, VB_VERTEX_CERTIFIED);
    if (rc == VB_OK && a->n && edges && !(where = malloc(list->n * sizeof *where)))
        rc = VB_ENOMEM;
    if (rc == VB_OK && a->n)
        rc = vb_vertex_list_sort_perm(list, where);
    for (size_t k = 0; rc == VB_OK && edges && k < *nedges; k++) {
        vb_topology_edge *e = &(*edges)[k];
        for (int i = 0; i < 2 && where; i++)
            if (e->v[i] >= 0)
                e->v[i] = (int64_t)where[e->v[i]];
        if (e->v[1] >= 0 && e->v[1] < e->v[0]) {
            int64_t s = e->v[0];
            e->v[0] = e->v[1];
            e->v[1] = s;
        }
    }
    /* edge_cmp orders by every field: the one sorted array on any number
     * of threads */
    if (rc == VB_OK && edges && *nedges &&
        vb_psort(*edges, *nedges, sizeof **edges, edge_cmp, vb_threads(threads)) != VB_OK)
        rc = VB_ENOMEM;
    free(where);
    if (rc != VB_OK && edges) {
        free(*edges);
        *edges = NULL;
        *nedges = 0;
    }
    if (rc == VB_ENOMEM)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (arc closure)");
    out->seconds = vb_now() - t0;
    return rc;
}

int vb_arc_complete_list(vb_ctx *ctx, const vb_sphere_set *set, vb_vertex_list *list,
                         unsigned threads, vb_arc_report *out)
{
    return vb_arc_complete_list_edges(ctx, set, NULL, list, threads, out, NULL, NULL);
}

void vb_arc_certificate(const vb_arc_report *r, char *buf, size_t size)
{
    snprintf(buf, size,
             "arcs: %s: %zu vertices, %zu half arcs: %zu closed at a vertex, %zu to infinity, "
             "%zu closed loops, %zu undecided; %zu vertices added by tracing; %zu connected "
             "components",
             r->undecided ? "NOT every arc closed" : "every arc closed exactly", r->vertices,
             r->half_arcs, r->closed, r->infinite, r->loops, r->undecided, r->added.n,
             r->components);
}

void vb_arc_stats(const vb_arc_report *r, vb_stat_fields *fs)
{
    vb_stat_uint(fs, "arc_half_arcs", r->half_arcs);
    vb_stat_uint(fs, "arc_closed", r->closed);
    vb_stat_uint(fs, "arc_infinite", r->infinite);
    vb_stat_uint(fs, "arc_loops", r->loops);
    vb_stat_uint(fs, "arc_undecided", r->undecided);
    vb_stat_uint(fs, "arc_added", r->added.n);
    vb_stat_uint(fs, "arc_components", r->components);
    vb_stat_uint(fs, "arc_filter_calls", r->filter_calls);
    vb_stat_uint(fs, "arc_filter_failures", r->filter_failures);
    vb_stat_uint(fs, "arc_exact_evals", r->exact_evals);
    vb_stat_uint(fs, "arc_candidates", r->candidates);
    vb_stat_real(fs, "arc_s", "%.3f", r->seconds);
    vb_stat_uint(fs, "arc_threads", r->threads);
    vb_stat_real(fs, "arc_setup_s", "%.3f", r->setup_s);
    vb_stat_real(fs, "arc_map_s", "%.3f", r->map_s);
    vb_stat_real(fs, "arc_trace_s", "%.3f", r->trace_s);
    vb_stat_real(fs, "arc_busy_s", "%.3f", r->busy_s);
    vb_stat_real(fs, "arc_merge_s", "%.3f", r->merge_s);
    vb_stat_real(fs, "arc_finish_s", "%.3f", r->finish_s);
    /* early tracing: counters only where it was on (the same lines whether
     * or not a part came before the proposer returned) */
    if (r->early_on || r->early_parts) {
        vb_stat_uint(fs, "arc_early_parts", r->early_parts);
        vb_stat_uint(fs, "arc_early_vertices", r->early_vertices);
        vb_stat_uint(fs, "arc_early_events", r->early_events);
        vb_stat_real(fs, "arc_early_s", "%.3f", r->early_s);
        vb_stat_real(fs, "arc_early_busy_s", "%.3f", r->early_busy_s);
        vb_stat_real(fs, "arc_early_take_s", "%.3f", r->early_take_s);
    }
}

void vb_arc_write_stats(FILE *f, const vb_arc_report *r)
{
    vb_stat_fields fs;
    fs.n = 0;
    vb_arc_stats(r, &fs);
    vb_stat_fields_write(f, &fs, 0);
}
