/* The vertex flow finished in the library: after the proposer and the
 * certifier (vb_vertices_run), the completion stage -- arc closure of the
 * certified list (verify/vb_arc.h), the faces and edges of the diagram
 * (exact from the traced arcs, or from the sampling's evidence), and the
 * certificate lines of the output header. `vorball vertices` and the
 * Python binding call it; they parse, call and write.
 *
 * Why here: the stage joins core/ (the run, the sampled topology) and
 * verify/ (arc closure), which never include each other; the front door is
 * the one room above both. */
#ifndef VB_COMPLETE_H
#define VB_COMPLETE_H

#include <stdio.h>

#include "vb_arc.h"
#include "vb_topology.h"
#include "vb_vertices.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What the completion does. Zero-initialise, set, then vb_completion_plan. */
typedef struct vb_completion_opts {
    int arcs;          /* trace every arc of the certified list (arc closure) */
    int topology;      /* build the faces and edges */
    unsigned threads;  /* host threads of the tracing (plan: the run's) */
    FILE *stats;       /* NULL, or where the tracing's counters go once traced
                          (vb_arc_write_stats), before its warnings */
} vb_completion_opts;

/* What the completion gives, beside the (closed) certified list. */
typedef struct vb_completion {
    char certificate[1024]; /* the header lines without '# ', '\n' between:
                               the proposer's (vb_vertices_certificate, of
                               the list before tracing) and, when traced,
                               arc closure's (vb_arc_certificate); "" when
                               nothing is proven */
    int traced;             /* 1: arcs holds the closure's counts */
    vb_arc_report arcs;     /* counts, and the vertices tracing added */
    int has_topology;       /* 1: topology is filled */
    vb_topology topology;   /* exact (arcs traced) or sampled */
} vb_completion;

/* Settles where the topology comes from, before the run: with the sampling
 * proposer and no arcs, from the sampler's evidence (the run keeps it:
 * cfg->propose.topology = 1); otherwise from arc closure (o->arcs = 1,
 * cfg->propose.topology = 0). Copies the run's threads into o->threads, and
 * sets cfg->keep_certifier = o->arcs (the closure borrows the run's
 * certifier: vb_vertices_complete) and, with arcs, cfg->part_work (the
 * closure traces the parts certified while the proposer runs) where the
 * environment's VORBALL_ARCS_EARLY=1 asks for it (off by default). Touches nothing else. */
void vb_completion_plan(vb_vertices_config *cfg, vb_completion_opts *o);

void vb_completion_init(vb_completion *c);
/* Frees what c holds; c is then as after init. NULL is allowed. */
void vb_completion_free(vb_completion *c);

/* The completion of a finished run res (after any merge of parts): warns
 * W763 when a proposer without a completeness proof had `rejected`
 * candidates refused (res->rejected.n in one process; the total over the
 * processes of a split run), writes the certificate, then with o->arcs
 * closes res->certified in place (vb_arc_complete_list: vertices found on
 * the way are certified, added and the list sorted again; it traces with
 * res->cert when the run kept the exact certifier of this set, which is
 * then closed; W766 when a half
 * arc stays undecided), and with o->topology builds the faces and edges
 * (W765 for what could not be decided). Fills *out (vb_completion_free,
 * also on error). VB_OK, VB_ENOMEM, VB_EMISUSE, or arc closure's errors
 * (vb_arc_close); nothing is written anywhere but o->stats. */
int vb_vertices_complete(vb_ctx *ctx, const vb_sphere_set *set, vb_vertices_result *res,
                         size_t rejected, const vb_completion_opts *o, vb_completion *out);

/* The whole vertex flow in one call: vb_completion_plan, vb_vertices_run
 * with the default backends, vb_vertices_complete. *res and *out are
 * filled (free both, also on error). Same returns as the two calls. */
int vb_vertices_run_complete(vb_ctx *ctx, const vb_sphere_set *set, vb_vertices_config *cfg,
                             vb_completion_opts *o, vb_vertices_result *res,
                             vb_completion *out);

#ifdef __cplusplus
}
#endif
#endif
