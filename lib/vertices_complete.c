/* The completion stage of the vertex flow (vb_complete.h). */
#include "vb_complete.h"

#include <stdlib.h>
#include <string.h>

#include "vb_default.h"
#include "vb_diag.h"

/* Early tracing as the run's part work (vb_part_work), on the exact
 * certifier only (no work on another). */
static int early_open(vb_ctx *owner, const vb_sphere_set *set, const vb_certifier_ops *ops,
                      void *cert, unsigned threads, void **state)
{
    *state = NULL;
    if (ops != &vb_exact_certifier)
        return VB_OK;
    vb_arc_early *e = NULL;
    int rc = vb_arc_early_open(owner, set, cert, threads, &e);
    *state = e;
    return rc;
}

static int early_part(vb_ctx *ctx, void *state, const vb_vertex_list *part)
{
    return vb_arc_early_part(ctx, state, part);
}

static void early_close(void *state)
{
    vb_arc_early_free(state);
}

static const vb_part_work early_arcs = {early_open, early_part, early_close};

/* The early events when the run kept them with the exact certifier of
 * this set (the tracers' workers are that certifier's), else NULL. */
static const vb_arc_early *kept_early(const vb_vertices_result *res, const vb_certifier *cert)
{
    return cert && res->part_ops == &early_arcs ? res->part_state : NULL;
}

void vb_completion_plan(vb_vertices_config *cfg, vb_completion_opts *o)
{
    o->threads = cfg->propose.threads;
    if (o->topology) {
        /* Faces and edges come from arc closure, or with the sampling
         * proposer alone from its evidence (which the sampler then keeps). */
        int sampled = !o->arcs && cfg->proposer && strcmp(cfg->proposer, "sampling") == 0;
        cfg->propose.topology = sampled;
        if (!sampled)
            o->arcs = 1;
    }
    /* Arc closure borrows the run's certifier instead of building another
     * on the same set (vb_vertices_complete). */
    cfg->keep_certifier = o->arcs;
    /* ... and, with VORBALL_ARCS_EARLY=1, traces the parts certified while
     * the proposer runs, on host threads that wait for the device. Off by
     * default: on an H100 (stop 53, results/h100_stop53.txt, run 2) the
     * 211,440-atom tiling's --arcs took 3.41-3.73 s early against 2.88 s
     * after the run and 2.97-3.14 s at the session's start, because most of
     * its certification comes after the cover (part_work_after_s 0.67-0.86
     * s) and a part searched against its own vertices runs more unbounded
     * searches (filter calls 28.7 M against 20.2 M). */
    const char *ea = getenv("VORBALL_ARCS_EARLY");
    cfg->part_work = o->arcs && ea && strcmp(ea, "1") == 0 ? &early_arcs : NULL;
}

void vb_completion_init(vb_completion *c)
{
    memset(c, 0, sizeof *c);
    vb_vertex_list_init(&c->arcs.added);
    vb_topology_init(&c->topology);
}

void vb_completion_free(vb_completion *c)
{
    if (!c)
        return;
    vb_arc_report_free(&c->arcs);
    vb_topology_free(&c->topology);
    vb_completion_init(c);
}

/* The faces and edges: exact from the traced edges (taken over), else from
 * the sampling's evidence; W765 for what could not be decided. */
static int build_topology(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertices_result *res,
                          vb_topology_edge *edges, size_t nedges, vb_completion *out)
{
    vb_topology *topo = &out->topology;
    int rc = out->traced
                 ? vb_arc_topology(ctx, set, &res->certified, edges, nedges, &out->arcs, topo)
                 : vb_topology_build(ctx, set, &res->proposal.topo, &res->certified, topo);
    if (rc != VB_OK)
        return rc;
    out->has_topology = 1;
    if (topo->unresolved && topo->exact)
        vb_warn(ctx, VB_W_TOPO_UNPAIRED, NULL, 0,
                "%zu vertex(es) whose faces could not be decided exactly (the pairs of "
                "their edges' triples are written)", topo->unresolved);
    else if (topo->unresolved)
        vb_warn(ctx, VB_W_TOPO_UNPAIRED, NULL, 0,
                "%zu trisector(s) whose edges could not be paired (no trisector curve for "
                "the triple in doubles, or a closed edge through one vertex)",
                topo->unresolved);
    return VB_OK;
}

/* The run's certifier when it kept the exact one of this very set
 * (vb_vertices_config.keep_certifier), else NULL: arc closure opens its own.
 * What the closure takes from it is the exact input and the spatial index,
 * a function of the set alone; the run's verdicts stay in res. */
static vb_certifier *kept_certifier(const vb_sphere_set *set, const vb_vertices_result *res)
{
    return res->cert && res->cert_ops == &vb_exact_certifier && res->cert_set == set
               ? res->cert
               : NULL;
}

/* The kept certifier closed once the closure is done with it (the early
 * tracers on it first). */
static void release_certifier(vb_vertices_result *res)
{
    if (res->part_state && res->part_ops)
        res->part_ops->close(res->part_state);
    res->part_state = NULL;
    res->part_ops = NULL;
    if (res->cert && res->cert_ops)
        res->cert_ops->close(res->cert);
    res->cert = NULL;
    res->cert_ops = NULL;
    res->cert_set = NULL;
}

int vb_vertices_complete(vb_ctx *ctx, const vb_sphere_set *set, vb_vertices_result *res,
                         size_t rejected, const vb_completion_opts *o, vb_completion *out)
{
    vb_completion_init(out);
    if (vb_ctx_check(ctx) != VB_OK || !set || !res || !o)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "vb_vertices_complete: NULL argument");
    /* A cover's refused roots are quadruples that hold no vertex: expected,
     * and no warning. */
    if (rejected && !res->proposal.complete)
        vb_warn(ctx, VB_W_CERT_REJECTED, NULL, 0, "the certifier rejected %zu candidate(s)",
                rejected);
    /* The proposer's line speaks of the list it certified, before tracing. */
    char *note = out->certificate;
    size_t size = sizeof out->certificate;
    vb_vertices_certificate(res, note, size);
    vb_topology_edge *edges = NULL;
    size_t nedges = 0;
    if (o->arcs) {
        vb_certifier *kc = kept_certifier(set, res);
        int rc = vb_arc_complete_list_early(ctx, set, kc, kept_early(res, kc), &res->certified,
                                            o->threads, &out->arcs, o->topology ? &edges : NULL,
                                            &nedges);
        release_certifier(res);
        if (rc != VB_OK)
            return rc;
        out->arcs.early_on = res->part_work_on && kc;
        out->traced = 1;
        size_t used = strlen(note);
        if (used && used + 1 < size)
            note[used++] = '\n';
        vb_arc_certificate(&out->arcs, note + used, size - used);
        if (o->stats)
            vb_arc_write_stats(o->stats, &out->arcs);
        if (out->arcs.undecided)
            vb_warn(ctx, VB_W_ARCS_UNDECIDED, NULL, 0,
                    "%zu half arc(s) could not be traced exactly: the list is not proven "
                    "closed under the edges of the diagram", out->arcs.undecided);
    }
    return o->topology ? build_topology(ctx, set, res, edges, nedges, out) : VB_OK;
}

int vb_vertices_run_complete(vb_ctx *ctx, const vb_sphere_set *set, vb_vertices_config *cfg,
                             vb_completion_opts *o, vb_vertices_result *res,
                             vb_completion *out)
{
    vb_completion_init(out);
    vb_completion_plan(cfg, o);
    int rc = vb_vertices_run_default(ctx, set, cfg, res);
    return rc == VB_OK ? vb_vertices_complete(ctx, set, res, res->rejected.n, o, out) : rc;
}
