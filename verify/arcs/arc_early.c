/* Early tracing (vb_arc.h): the forward arcs of certified parts traced
 * while the proposer still runs, and the closure's taking of their events
 * (vbx_early_take), every index and end looked up in the final list.
 *
 * Why the closure's report does not change: a half arc that a part
 * decided ends where the diagram says (its end's exact point and members,
 * infinity, or a loop), whichever map bounded its search (vbx_tmap_update:
 * a map that lacks vertices costs searches, never a wrong end). A backward
 * arc the part closed by reversal leans on another vertex of the part and
 * is taken as pending. The closure takes the events of each vertex of its
 * list from the first part that traced it, unless one of that vertex's
 * half arcs was undecided there (it is then traced again on the whole
 * list, as without parts): every vertex of the list is traced exactly once
 * either way, and the merge (arc_merge.c) counts, adds and joins the same
 * events. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"

#include "vbx_closure.h"

int vb_arc_early_open(vb_ctx *owner, const vb_sphere_set *set, vb_certifier *cert,
                      unsigned threads, vb_arc_early **out)
{
    (void)set; /* the certifier's own: its exact input and index */
    *out = NULL;
    vb_arc_early *e = calloc(1, sizeof *e);
    if (!e)
        return VB_ENOMEM;
    e->owner = owner;
    e->nt = (unsigned)vb_threads(threads);
    int rc = vbx_tracers_open(owner, cert, e->nt, 0, &e->block, &e->tr);
    if (rc != VB_OK) {
        vb_arc_early_free(e);
        return rc;
    }
    *out = e;
    return VB_OK;
}

void vb_arc_early_free(vb_arc_early *e)
{
    if (!e)
        return;
    vbx_tracers_free(e->block, e->tr, e->nt, 0);
    for (size_t p = 0; p < e->nparts; p++) {
        vb_vertex_list_free(&e->parts[p].v);
        free(e->parts[p].first);
        free(e->parts[p].count);
        free(e->parts[p].who);
    }
    free(e->parts);
    free(e->it);
    free(e->map.e);
    free(e->map.off);
    free(e);
}

int vb_arc_early_part(vb_ctx *ctx, vb_arc_early *e, const vb_vertex_list *part)
{
    if (!part->n)
        return VB_OK;
    double t0 = vb_now();
    if (VB_ARRAY_FIT(e->parts, e->cap, e->nparts + 1, 8) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (early arcs)");
    vbx_epart *ep = &e->parts[e->nparts];
    memset(ep, 0, sizeof *ep);
    vb_vertex_list_init(&ep->v);
    /* counted once it holds what it allocated: freed with e on any return */
    e->nparts++;
    int rc = vb_vertex_list_append(&ep->v, part);
    if (rc == VB_OK)
        rc = vbx_tmap_update(&e->map, &ep->v, e->nt);
    if (rc == VB_OK)
        rc = vbx_tmap_items(&e->map, e->nt, &e->it, &ep->nit, &e->it_cap);
    size_t n = ep->nit;
    if (rc == VB_OK && n) {
        ep->first = malloc(n * sizeof *ep->first);
        ep->count = malloc(n * sizeof *ep->count);
        ep->who = malloc(n * sizeof *ep->who);
        if (!ep->first || !ep->count || !ep->who)
            rc = VB_ENOMEM;
    }
    if (rc != VB_OK) {
        ep->nit = 0; /* nothing traced: the closure takes no item of it */
        return vb_error(ctx, rc, NULL, 0, "out of memory (early arcs)");
    }
    vbx_tphase ph;
    memset(&ph, 0, sizeof ph);
    ph.tr = e->tr;
    ph.all = &ep->v;
    ph.it = e->it;
    ph.n = n;
    ph.first = ep->first;
    ph.count = ep->count;
    ph.who = ep->who;
    /* the tracers' events accumulate over the parts (first[] indexes
     * them) */
    for (unsigned i = 0; i < e->nt; i++)
        e->tr[i].map = &e->map;
    int bad = vbx_phase_run(&ph, e->nt, 1);
    e->wall_s += vb_now() - t0;
    if (bad >= 0) {
        ep->nit = 0;
        return vb_error(ctx, e->tr[bad].rc, NULL, 0, "%s", vb_errmsg(e->tr[bad].ctx));
    }
    return VB_OK;
}

/* ---- taking the events into the closure -------------------------------- */

/* Per part: the row of the final list of each of its vertices (SIZE_MAX:
 * not there), found through the final map (vb_for_fn over the parts'
 * vertices in ranges). */
typedef struct rowjob {
    const vbx_closure *cl;
    const vbx_epart *ep;
    size_t *row;
    size_t nrun;
} rowjob;

static void find_rows(void *arg, size_t r, int tid)
{
    (void)tid;
    const rowjob *j = arg;
    const vb_vertex_list *v = &j->ep->v;
    size_t a = v->n * r / j->nrun, b = v->n * (r + 1) / j->nrun;
    for (size_t k = a; k < b; k++) {
        size_t s = v->start[k], nm = v->start[k + 1] - s;
        double p[4];
        vbx_vertex_point(v, k, p);
        /* a vertex has at least four members: its first triple is in the map */
        j->row[k] = nm >= 3 ? vbx_tmap_find(&j->cl->map, &j->cl->all, v->ids + s, v->ids + s,
                                            nm, p)
                            : SIZE_MAX;
    }
}

/* Event e of part ep (traced by tr) in the final list's rows (row: the
 * part's), appended to the holder h. VB_OK or VB_ENOMEM. */
static int take_event(const vbx_closure *cl, const vbx_epart *ep, const vbx_tracer *tr,
                      const size_t *row, const vbx_hev *e, vbx_tracer *h)
{
    if (VB_ARRAY_FIT(h->ev, h->ev_cap, h->nev + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    vbx_hev *o = &h->ev[h->nev++];
    *o = *e;
    o->from = row[e->from];
    o->end = SIZE_MAX;
    /* A backward arc that the part closed by reversal (arc_tracer.c) leans
     * on the forward arc of another of its vertices, which the final list
     * may lack (then nothing else would find that vertex): pending again,
     * it is closed by an arrival in the final list or traced. */
    if (e->kind == VBX_EV_REVERSED)
        o->kind = VBX_EV_PENDING;
    if (e->kind != VBX_EV_CLOSED)
        return VB_OK;
    const uint32_t *m;
    size_t nm;
    double p[4];
    if (e->to != SIZE_MAX) { /* a vertex of the part: its row, if it has one */
        if (row[e->to] != SIZE_MAX) {
            o->to = row[e->to];
            return VB_OK;
        }
        size_t s = ep->v.start[e->to];
        m = ep->v.ids + s;
        nm = ep->v.start[e->to + 1] - s;
        vbx_vertex_point(&ep->v, e->to, p);
    } else {
        const vbx_hend *x = &tr->ends[e->end];
        m = tr->pool + x->moff;
        nm = x->nm;
        memcpy(p, x->p, sizeof p);
    }
    size_t k = vbx_tmap_find(&cl->map, &cl->all, e->t, m, nm, p);
    if (k != SIZE_MAX) {
        o->to = k;
        return VB_OK;
    }
    return vbx_keep_end(h, o, m, nm, p); /* not listed: a late event (added) */
}

void vbx_eset_free(vbx_eset *s)
{
    vbx_tracers_free(s->block, s->tr, s->tr ? 1 : 0, 1);
    free(s->first);
    free(s->count);
    free(s->who);
    free(s->done);
    memset(s, 0, sizeof *s);
}

int vbx_early_take(vbx_closure *cl, const vb_arc_early *early, unsigned nt, vbx_eset *s)
{
    double t0 = vb_now();
    memset(s, 0, sizeof *s);
    size_t n = cl->all.n, nitems = 0, most = 0;
    for (size_t p = 0; p < early->nparts; p++) {
        nitems += early->parts[p].nit;
        if (early->parts[p].v.n > most)
            most = early->parts[p].v.n;
    }
    /* the holder: a tracer block of one, none of its workers opened */
    s->block = calloc(sizeof(vbx_tracer) + _Alignof(vbx_tracer), 1);
    s->done = calloc(n ? n : 1, 1);
    s->first = malloc((nitems ? nitems : 1) * sizeof *s->first);
    s->count = malloc((nitems ? nitems : 1) * sizeof *s->count);
    s->who = calloc(nitems ? nitems : 1, sizeof *s->who);
    size_t *row = malloc((most ? most : 1) * sizeof *row);
    unsigned char *undecided = malloc(most ? most : 1);
    /* owner[k]: 1 + the part whose events vertex k takes (0: none) */
    uint32_t *owner = calloc(n ? n : 1, sizeof *owner);
    int rc = s->block && s->done && s->first && s->count && s->who && row && undecided && owner
                 ? VB_OK
                 : VB_ENOMEM;
    if (rc == VB_OK)
        s->tr = (vbx_tracer *)(s->block + (_Alignof(vbx_tracer) -
                                           (uintptr_t)s->block % _Alignof(vbx_tracer)));
    vbx_tracer *h = s->tr;
    size_t nrun = nt ? nt : 1;
    for (size_t p = 0; rc == VB_OK && p < early->nparts; p++) {
        const vbx_epart *ep = &early->parts[p];
        rowjob j = {cl, ep, row, nrun};
        vb_parallel_for(find_rows, &j, nrun, (int)nt);
        /* a vertex with an undecided half arc here is traced again */
        memset(undecided, 0, ep->v.n);
        for (size_t i = 0; i < ep->nit; i++) {
            const vbx_tracer *tr = &early->tr[ep->who[i]];
            for (size_t q = ep->first[i]; q < ep->first[i] + ep->count[i]; q++)
                if (tr->ev[q].kind == VBX_EV_UNDECIDED)
                    undecided[tr->ev[q].from] = 1;
        }
        for (size_t k = 0; k < ep->v.n; k++)
            if (row[k] != SIZE_MAX && !undecided[k] && !owner[row[k]]) {
                owner[row[k]] = (uint32_t)(p + 1);
                s->done[row[k]] = 1;
                cl->r->early_vertices++;
            }
        for (size_t i = 0; rc == VB_OK && i < ep->nit; i++) {
            const vbx_tracer *tr = &early->tr[ep->who[i]];
            size_t e0 = h->nev;
            for (size_t q = ep->first[i]; rc == VB_OK && q < ep->first[i] + ep->count[i]; q++) {
                const vbx_hev *e = &tr->ev[q];
                size_t k = row[e->from];
                if (k == SIZE_MAX || owner[k] != p + 1)
                    continue;
                rc = take_event(cl, ep, tr, row, e, h);
            }
            if (rc == VB_OK && h->nev > e0) {
                s->first[s->n] = e0;
                s->count[s->n] = (uint32_t)(h->nev - e0);
                s->n++;
            }
        }
    }
    cl->r->early_events = h ? h->nev : 0;
    cl->r->early_parts = early->nparts;
    cl->r->early_s = early->wall_s;
    for (unsigned i = 0; i < early->nt; i++) {
        cl->r->early_busy_s += early->tr[i].busy;
        cl->r->filter_calls += early->tr[i].w.cnt.filter_calls;
        cl->r->filter_failures += early->tr[i].w.cnt.filter_failures;
        cl->r->exact_evals += early->tr[i].w.cnt.exact_evals;
        cl->r->candidates += early->tr[i].w.cnt.candidates;
    }
    free(row);
    free(undecided);
    free(owner);
    cl->r->early_take_s = vb_now() - t0;
    return rc;
}
