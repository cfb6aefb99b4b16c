/* Arc closure (vb_arc.h): the tracing loop over the vertices in rounds,
 * the counts of the certificate and the edges (the tracers: arc_tracer.c;
 * the merge of their events, the added vertices and the arrivals:
 * arc_merge.c). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vb_parallel.h"
#include "vb_uf.h"

#include "vb_arc.h"
#include "vbx_closure.h"

/* Runs the n items on the tracers and merges their events in vbx_item order. */
static int run_phase(vbx_closure *cl, vbx_tracer *tr, unsigned nt, const vbx_item *it, size_t n,
                     size_t base, size_t span, size_t total, vbx_mrun *runs, unsigned *nr)
{
    *nr = 0;
    if (!n)
        return VB_OK;
    vbx_tphase ph;
    memset(&ph, 0, sizeof ph);
    ph.tr = tr;
    ph.all = &cl->all;
    ph.it = it;
    ph.n = n;
    ph.first = malloc(n * sizeof *ph.first);
    ph.count = malloc(n * sizeof *ph.count);
    ph.who = malloc(n * sizeof *ph.who);
    ph.progress = total ? cl->ctx : NULL;
    ph.base = base;
    ph.span = span;
    ph.total = total;
    int rc = VB_OK;
    if (!ph.first || !ph.count || !ph.who) {
        rc = VB_ENOMEM;
    } else {
        double t0 = vb_now();
        int bad = vbx_phase_run(&ph, nt, 0);
        cl->r->trace_s += vb_now() - t0;
        if (bad >= 0) {
            rc = tr[bad].rc;
            if (bad != 0)
                vb_error(cl->ctx, rc, NULL, 0, "%s", vb_errmsg(tr[bad].ctx));
        }
    }
    double t1 = vb_now();
    if (rc == VB_OK)
        rc = vbx_merge_phase(cl, &ph, nt, runs, nr);
    cl->r->merge_s += vb_now() - t1;
    free(ph.first);
    free(ph.count);
    free(ph.who);
    return rc;
}

/* Rounds: every vertex not yet traced has its forward arcs traced (in
 * parallel; the first round triple by triple, the next ones vertex by
 * vertex), the events merged in item order; then each backward arc is
 * either the reverse of a forward arc already traced that arrived at its
 * vertex with its triple (the forward search proved the open arc between
 * the two vertices free of touching spheres, so the backward search would
 * end at that arc's start: counted closed without a search), or traced
 * itself, in a second parallel phase. Vertices found new go to the end of
 * the list and make the next round. The list, the counts and the added
 * vertices are therefore the same on any number of threads. */
/* The items of the first round that hold a vertex that s leaves to trace
 * (s->done 0), in order, in place. */
static size_t keep_untraced(const vbx_closure *cl, const vbx_eset *s, vbx_item *it, size_t n)
{
    size_t keep = 0;
    for (size_t i = 0; i < n; i++) {
        const vbx_tent *e = cl->map.e + it[i].k;
        for (uint32_t j = 0; j < it[i].n; j++)
            if (!s->done[e[j].k]) {
                it[keep++] = it[i];
                break;
            }
    }
    return keep;
}

/* Merges the early events of s (vbx_early_take) as a phase after the
 * round's first (its runs from runs[*nr] on; *nr counts them too). */
static int merge_early(vbx_closure *cl, const vbx_eset *s, unsigned nt, vbx_mrun *runs,
                       unsigned *nr)
{
    if (!s->n)
        return VB_OK;
    vbx_tphase ph;
    memset(&ph, 0, sizeof ph);
    ph.tr = s->tr;
    ph.all = &cl->all;
    ph.n = s->n;
    ph.first = s->first;
    ph.count = s->count;
    ph.who = s->who;
    unsigned more = 0;
    double t0 = vb_now();
    int rc = vbx_merge_phase(cl, &ph, nt, runs + *nr, &more);
    cl->r->merge_s += vb_now() - t0;
    *nr += more;
    return rc;
}

static int run_rounds(vbx_closure *cl, vbx_tracer *tr, unsigned nt, const vb_arc_early *early)
{
    size_t lo = 0;
    int rc = VB_OK;
    vbx_item *it = NULL, *back = NULL;
    size_t it_cap = 0, back_cap = 0;
    vbx_eset es;
    memset(&es, 0, sizeof es);
    while (rc == VB_OK && lo < cl->all.n) {
        size_t hi = cl->all.n, nit = 0, nback = 0;
        /* the map is read by every thread of the round: built before it */
        double t0 = vb_now();
        rc = vbx_tmap_update(&cl->map, &cl->all, nt);
        cl->r->map_s += vb_now() - t0;
        if (rc != VB_OK)
            break;
        for (unsigned i = 0; i < nt; i++)
            tr[i].map = &cl->map;
        /* The first round (the whole map) by triple, each triple's frame
         * set up once for all its vertices; the next rounds (vertices found
         * new) by vertex. */
        if (lo == 0) {
            rc = vbx_tmap_items(&cl->map, nt, &it, &nit, &it_cap);
            if (rc == VB_OK && early && early->nparts)
                rc = vbx_early_take(cl, early, nt, &es);
            if (rc == VB_OK && es.done) {
                nit = keep_untraced(cl, &es, it, nit);
                for (unsigned i = 0; i < nt; i++)
                    tr[i].skip = es.done;
            }
        } else if (VB_ARRAY_FIT(it, it_cap, hi - lo, 256) != VB_OK) {
            rc = VB_ENOMEM;
        } else {
            for (size_t k = lo; k < hi; k++)
                it[nit++] = (vbx_item){k, {0, 0, 0}, 0, VBX_IT_VERTEX};
        }
        if (rc != VB_OK)
            break;
        /* the round's first phase and, in the first round, the early
         * events: their pending arcs resolved together */
        vbx_mrun runs[2 * VB_MAX_THREADS];
        unsigned nr = 0;
        rc = run_phase(cl, tr, nt, it, nit, lo, hi - lo, hi, runs, &nr);
        for (unsigned i = 0; i < nt; i++)
            tr[i].skip = NULL;
        if (rc == VB_OK && es.done)
            rc = merge_early(cl, &es, nt, runs, &nr);
        vbx_eset_free(&es);
        double t1 = vb_now();
        if (rc == VB_OK)
            rc = vbx_resolve_pending(cl, runs, nr, &back, &nback, &back_cap);
        vbx_free_runs(runs, nr);
        nr = 0;
        cl->r->merge_s += vb_now() - t1;
        if (rc == VB_OK)
            rc = run_phase(cl, tr, nt, back, nback, 0, 0, 0, runs, &nr);
        vbx_free_runs(runs, nr);
        lo = hi;
    }
    if (rc == VB_OK)
        vb_progress(cl->ctx, "arcs", cl->all.n, cl->all.n);
    for (unsigned i = 0; i < nt; i++)
        tr[i].skip = NULL;
    vbx_eset_free(&es);
    free(it);
    free(back);
    if (rc == VB_ENOMEM)
        vb_error(cl->ctx, VB_ENOMEM, NULL, 0, "out of memory (arc closure)");
    return rc;
}

static void add_counters(vb_arc_report *r, const vbx_arc_counters *c)
{
    r->filter_calls += c->filter_calls;
    r->filter_failures += c->filter_failures;
    r->exact_evals += c->exact_evals;
    r->candidates += c->candidates;
}

static int tedge_cmp(const void *pa, const void *pb)
{
    const vbx_tedge *a = pa, *b = pb;
    if (a->from != b->from)
        return a->from < b->from ? -1 : 1;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    if (a->kind != b->kind)
        return a->kind < b->kind ? -1 : 1;
    return (a->to > b->to) - (a->to < b->to);
}

/* Each edge once, its ends as rows of in and then of the sorted added list
 * (where_added: tracing order -> sorted row). A finite edge was recorded by
 * the forward half arc at its start, and again by the backward half arc at
 * its end unless that one was closed by the shortcut (run_rounds): the
 * forward half arc of a vertex and triple is unique, so a backward record
 * is dropped exactly when the forward record of its start and triple ends
 * where it does. Two edges of one closed curve between the same two
 * vertices leave them forward from different starts and stay two. Both
 * half arcs of a closed loop record it: kept once. The half arcs to
 * infinity of a vertex and triple, one each way, are two edges. */
static int emit_edges(vbx_closure *cl, size_t nin, const size_t *where_added, unsigned nt,
                      vb_topology_edge **edges, size_t *nedges)
{
    /* tedge_cmp is a total order: the one sorted array on any nt */
    if (vb_psort(cl->ed, cl->ned, sizeof *cl->ed, tedge_cmp, (int)nt) != VB_OK)
        return VB_ENOMEM;
    vb_topology_edge *o = malloc((cl->ned ? cl->ned : 1) * sizeof *o);
    if (!o)
        return VB_ENOMEM;
    size_t n = 0;
    for (size_t g = 0; g < cl->ned;) {
        size_t h = g;
        while (h < cl->ned && cl->ed[h].from == cl->ed[g].from &&
               memcmp(cl->ed[h].t, cl->ed[g].t, sizeof cl->ed[g].t) == 0)
            h++;
        size_t fwd_to = SIZE_MAX;
        int have_fwd = 0, have_loop = 0;
        for (size_t i = g; i < h; i++) {
            const vbx_tedge *e = &cl->ed[i];
            if (e->kind == VBX_TE_FWD) {
                have_fwd = 1;
                fwd_to = e->to;
            } else if (e->kind == VBX_TE_BWD && have_fwd && e->to == fwd_to) {
                continue;
            } else if (e->kind == VBX_TE_LOOP) {
                if (have_loop)
                    continue;
                have_loop = 1;
            }
            size_t a = e->from, b = e->to;
            o[n].v[0] = (int64_t)(a < nin ? a : nin + where_added[a - nin]);
            o[n].v[1] = b == SIZE_MAX ? -1 : (int64_t)(b < nin ? b : nin + where_added[b - nin]);
            memcpy(o[n].spheres, e->t, sizeof e->t);
            n++;
        }
        g = h;
    }
    *edges = o;
    *nedges = n;
    return VB_OK;
}

/* The closure of list in on set; cert: an open certifier of set to borrow
 * (left open), or NULL to open one. */
static int close_list(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                      const vb_arc_early *early, const vb_vertex_list *in, unsigned threads,
                      vb_arc_report *out, vb_topology_edge **edges, size_t *nedges)
{
    memset(out, 0, sizeof *out);
    vb_vertex_list_init(&out->added);
    vbx_closure cl;
    memset(&cl, 0, sizeof cl);
    cl.ctx = ctx;
    cl.r = out;
    cl.want_edges = edges != NULL;
    size_t *where = NULL;
    if (edges) {
        *edges = NULL;
        *nedges = 0;
    }
    vb_vertex_list_init(&cl.all);
    double t0 = vb_now();
    unsigned nt = (unsigned)vb_threads(threads);
    size_t most = in->n / 64 + 1;
    if (nt > most)
        nt = (unsigned)most;
    /* the tracers inside one zeroed block (calloc: the allocation fault
     * tests reach it), tracer 0 on ctx and the certifier */
    char *tr_block = NULL;
    vbx_tracer *tr = NULL;
    vb_certifier *c = cert;
    int rc = c ? VB_OK : vb_certifier_open(ctx, set, &c);
    if (rc == VB_OK)
        rc = vbx_tracers_open(ctx, c, nt, 1, &tr_block, &tr);
    cl.all = *in; /* lent: copied only when a vertex is added (vbx_closure_own) */
    if (rc == VB_OK)
        rc = vb_uf_fit(&cl.comp, cl.all.n);
    out->threads = nt;
    out->setup_s = vb_now() - t0;
    if (rc == VB_OK) {
        vb_progress(ctx, "arcs", 0, cl.all.n);
        rc = run_rounds(&cl, tr, nt, early);
    }
    double t1 = vb_now();
    if (rc == VB_OK) {
        out->vertices = cl.all.n;
        for (size_t k = 0; k < cl.all.n; k++) /* a root is its own parent */
            out->components += cl.comp.p[k] == k;
        for (unsigned i = 0; i < nt; i++)
            add_counters(out, &tr[i].w.cnt);
        if (edges && !(where = malloc((out->added.n ? out->added.n : 1) * sizeof *where)))
            rc = VB_ENOMEM;
        if (rc == VB_OK)
            rc = vb_vertex_list_sort_perm(&out->added, where);
        if (rc == VB_OK && edges)
            rc = emit_edges(&cl, in->n, where, nt, edges, nedges);
        for (unsigned i = 0; i < nt; i++)
            out->busy_s += tr[i].busy;
    }
    out->finish_s = vb_now() - t1;
    free(where);
    free(cl.ed);
    if (rc == VB_ENOMEM && vb_errcode(ctx) != VB_ENOMEM)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (arc closure)");
    vbx_tracers_free(tr_block, tr, nt, 1);
    if (c != cert)
        vb_certifier_close(c);
    if (cl.all_owned)
        vb_vertex_list_free(&cl.all);
    vb_hash_free(&cl.tab);
    vb_uf_free(&cl.comp);
    vb_hash_free(&cl.arrived.tab);
    free(cl.arrived.k);
    free(cl.amask);
    free(cl.map.e);
    free(cl.map.off);
    return rc;
}

int vb_arc_close(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                 unsigned threads, vb_arc_report *out)
{
    return close_list(ctx, set, NULL, NULL, in, threads, out, NULL, NULL);
}

int vb_arc_close_edges(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                       const vb_vertex_list *in, unsigned threads, vb_arc_report *out,
                       vb_topology_edge **edges, size_t *nedges)
{
    return close_list(ctx, set, cert, NULL, in, threads, out, edges, nedges);
}

int vb_arc_close_early(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                       const vb_arc_early *early, const vb_vertex_list *in, unsigned threads,
                       vb_arc_report *out, vb_topology_edge **edges, size_t *nedges)
{
    return close_list(ctx, set, cert, early, in, threads, out, edges, nedges);
}

int vb_arc_report_complete(const vb_arc_report *r)
{
    return r->undecided == 0 && r->added.n == 0;
}

void vb_arc_report_free(vb_arc_report *r)
{
    vb_vertex_list_free(&r->added);
    memset(r, 0, sizeof *r);
    vb_vertex_list_init(&r->added);
}
