/* Arc closure: exact completeness evidence for a list of certified vertices.
 *
 * Every Voronoi vertex v of spheres M (|M| >= 4) has, for each triple T of
 * M, up to two arcs of T's trisector leaving it (decided exactly from the
 * signs of the other members' L_j along the curve's tangent: verify/arcs/vbx_arc.h).
 * Along each arc the first sphere j beyond T that touches the moving tangent
 * sphere is found from a provably conservative set of candidates, positions
 * compared by the filter and in Q(sqrt(delta)) where it cannot tell
 * (verify/arcs/arc_search.c). That point is the next vertex: it is certified
 * exactly and looked up in the list; a vertex not in the list is added and
 * traced in turn. An arc with no touching sphere runs to infinity (open
 * branch) or closes on itself (closed curve). A forward arc is first
 * searched up to the nearest listed vertex of its triple ahead, and a
 * backward arc that reverses a forward arc traced to its vertex is closed
 * by that search (verify/arcs/arc_closure.c says why both are exact).
 *
 * What a run with nothing added and nothing undecided proves: the list is
 * closed under the edges of the diagram, i.e. it holds every vertex of each
 * connected component of the vertex-edge graph that it meets. It does not
 * prove that a component with no vertex in the list does not exist. */
#ifndef VB_ARC_H
#define VB_ARC_H

#include <stdio.h>

#include "vb_stat_field.h"
#include "vb_topology.h"
#include "vb_verify.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_arc_report {
    size_t vertices;        /* vertices traced: the input's and those added */
    size_t half_arcs;       /* arcs leaving a vertex (each finite arc counts from both ends) */
    size_t closed;          /* half arcs that end at a certified vertex */
    size_t infinite;        /* half arcs to infinity */
    size_t loops;           /* half arcs of a closed curve that return to their vertex */
    size_t undecided;       /* half arcs not traced (a degenerate point: VB_EDEGENERATE) */
    size_t components;      /* connected components of the vertex-edge graph */
    vb_vertex_list added;   /* certified vertices found by tracing, not in the input (sorted) */
    uint64_t filter_calls, filter_failures, exact_evals, candidates;
    double seconds;         /* vb_arc_complete_list: wall time of the closure */
    /* wall seconds of the closure's phases: the list's copy, the tracers
     * and the certifier unless one is lent (setup), the triples' map of each
     * round (map: parallel), the tracing (trace: parallel; busy: the
     * tracers' summed CPU seconds inside it), merging the events and
     * resolving the pending arcs (merge: parallel, vertices added in order
     * on one thread) and components, sorting and edges (finish) */
    double setup_s, map_s, trace_s, busy_s, merge_s, finish_s;
    unsigned threads;       /* tracers used */
    /* early tracing (vb_arc_early): the parts traced while the proposer
     * ran, the list's vertices whose arcs came from them and those half
     * arcs' events; the wall and summed CPU seconds of that tracing (before
     * the closure), and the seconds the closure spent taking its events */
    size_t early_parts, early_vertices, early_events;
    int early_on;           /* 1: early tracing was on (its counters printed, zero or not) */
    double early_s, early_busy_s, early_take_s;
} vb_arc_report;

/* Arcs traced early: certified parts of the list traced while the
 * proposer still runs (on host threads that would wait for the device),
 * their events kept until the closure of the whole list. */
typedef struct vb_arc_early vb_arc_early;

/* An early tracer of set on `threads` host threads (0: VORBALL_THREADS or
 * the online CPUs), its tracers on workers of cert (an open certifier of
 * set, borrowed: close *out before it) and of owner's context. VB_OK or
 * VB_ENOMEM (*out NULL). */
int vb_arc_early_open(vb_ctx *owner, const vb_sphere_set *set, vb_certifier *cert,
                      unsigned threads, vb_arc_early **out);

/* Traces the forward arcs of every vertex of `part` (certified vertices,
 * sorted, each once: as vb_arc_close's `in`; copied) and keeps their
 * events: each end is a rounded point and members, nothing of it is
 * looked up but in the final list (vb_arc_close_early). Errors are set on
 * ctx. VB_OK, VB_ENOMEM, VB_EINTERNAL. */
int vb_arc_early_part(vb_ctx *ctx, vb_arc_early *e, const vb_vertex_list *part);

/* Frees e (NULL allowed). */
void vb_arc_early_free(vb_arc_early *e);

/* Traces every arc of every vertex of `in` and of every vertex found on the
 * way, in rounds on up to `threads` host threads (0: VORBALL_THREADS or the
 * online CPUs); the report does not depend on their number. `in` must hold certified vertices,
 * each once: sorted ids of all their spheres, x y z t the exact vertex
 * rounded to nearest, as vorball writes them (the status is ignored; a
 * vertex that is not one gives undecided arcs or wrong closures, so judge a
 * foreign file first: vb_verify_arcs). Fills *out (free with
 * vb_arc_report_free, also on error). Returns VB_OK when the closure ran to
 * the end (see vb_arc_report_complete), VB_ENOMEM, VB_EINTERNAL. */
int vb_arc_close(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                 unsigned threads, vb_arc_report *out);

/* vb_arc_close, tracing with cert when it is not NULL (an open certifier of
 * set, e.g. the vertex pipeline's: borrowed, left open; the closure takes
 * only its exact input and spatial index, which depend on set alone, and
 * its scratch, never a verdict of the run that opened it), and every
 * Voronoi edge it traced once into *edges
 * (*nedges of them; malloc'd, free() it; NULL on error): its triple (the
 * three smallest ids where more spheres share the curve), v[0] its start
 * and v[1] its end in the curve's forward direction, as rows of `in` and
 * then, from in->n on, rows of out->added (sorted); v[1] = -1: the edge
 * runs to infinity; v[0] = v[1]: a closed loop through one vertex. The
 * order (by start, triple, kind of record, end) is the same on any number
 * of threads. A half arc left undecided records nothing, so the edges are all
 * of the diagram's at the traced vertices exactly when r->undecided == 0. */
int vb_arc_close_edges(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                       const vb_vertex_list *in, unsigned threads, vb_arc_report *out,
                       vb_topology_edge **edges, size_t *nedges);

/* vb_arc_close_edges taking the early events of `early` (NULL: none; its
 * certifier must be cert's) for the vertices of `in` that a part traced:
 * each vertex, end and arrival is looked up in `in` itself, an end not
 * there is a vertex added (and traced) as any other; the vertices no part
 * traced, and any whose early half arcs were not all decided, are traced
 * here. The report, edges and added vertices are those of
 * vb_arc_close_edges (edges: NULL for none). Same returns. */
int vb_arc_close_early(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                       const vb_arc_early *early, const vb_vertex_list *in, unsigned threads,
                       vb_arc_report *out, vb_topology_edge **edges, size_t *nedges);

/* 1 when every arc was traced and no vertex was added. */
int vb_arc_report_complete(const vb_arc_report *r);

void vb_arc_report_free(vb_arc_report *r);

/* Closes the certified list `list` of a pipeline run in place: vb_arc_close
 * on it, then the vertices found on the way (certified exactly) appended
 * and the list sorted canonically again. *out keeps the counts and the
 * added vertices (free with vb_arc_report_free, also on error). Same
 * returns as vb_arc_close. */
int vb_arc_complete_list(vb_ctx *ctx, const vb_sphere_set *set, vb_vertex_list *list,
                         unsigned threads, vb_arc_report *out);

/* vb_arc_complete_list that also gives the traced edges (vb_arc_close_edges)
 * with their ends as rows of the closed, sorted list; finite edges with
 * v[0] < v[1], all sorted by (triple, v[0], v[1]); cert as in
 * vb_arc_close_edges (NULL: its own). Same returns. */
int vb_arc_complete_list_edges(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                               vb_vertex_list *list, unsigned threads, vb_arc_report *out,
                               vb_topology_edge **edges, size_t *nedges);

/* vb_arc_complete_list_edges through vb_arc_close_early (early NULL: the
 * same). Same returns. */
int vb_arc_complete_list_early(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                               const vb_arc_early *early, vb_vertex_list *list,
                               unsigned threads, vb_arc_report *out, vb_topology_edge **edges,
                               size_t *nedges);

/* The exact topology of a closed list (`vorball vertices --topology`):
 * edges the traced arcs (from vb_arc_complete_list_edges on `list`; the
 * array is taken over), faces the sphere pairs that share a face at a
 * vertex of `list`: all six pairs of a vertex of four spheres; at a vertex
 * of more, the pairs (i, j) whose contact directions u_i, u_j (unit vectors
 * from the vertex to the centres) are joined by an edge of the convex hull
 * of all the members' directions, decided exactly in Q(sqrt(delta)) (the
 * local cells at a vertex are the normal fan of that hull). A vertex whose
 * exact point cannot be identified counts in out->unresolved and gives the
 * pairs of its edges' triples. Fills *out (vb_topology_free), out->exact =
 * 1. VB_OK, VB_ENOMEM. */
int vb_arc_topology(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *list,
                    vb_topology_edge *edges, size_t nedges, const vb_arc_report *r,
                    vb_topology *out);

/* The certificate as one header line ("arcs: ...", no newline) into buf. */
void vb_arc_certificate(const vb_arc_report *r, char *buf, size_t size);

/* Appends the counts, the tracing predicates' filter/exact counters and
 * the stage's seconds to fs (vb_stat_field.h), as the lines `vorball
 * vertices --arcs --stats` prints. */
void vb_arc_stats(const vb_arc_report *r, vb_stat_fields *fs);

/* Writes vb_arc_stats' table to f, one "name<TAB>value" line each. */
void vb_arc_write_stats(FILE *f, const vb_arc_report *r);

/* The certificate as text: one "NAME: missing vertex IDS at X Y Z t T" line
 * per added vertex, then "NAME: arcs: ..." with the counts. VB_OK or VB_EIO. */
int vb_arc_write_text(vb_ctx *ctx, FILE *f, const char *name, const vb_arc_report *r);

#ifdef __cplusplus
}
#endif
#endif
