/* The tracers of arc closure (vbx_closure.h): the arcs of one vertex or
 * one triple traced to their ends, as events, on one thread each. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"

#include "vbx_closure.h"

static int push_event(vbx_tracer *t, int kind, const uint32_t tri[3], int dir, size_t to)
{
    if (VB_ARRAY_FIT(t->ev, t->ev_cap, t->nev + 1, 256) != VB_OK)
        return VB_ENOMEM;
    vbx_hev *e = &t->ev[t->nev++];
    e->kind = (unsigned char)kind;
    e->from = t->from;
    e->to = to;
    e->end = SIZE_MAX;
    e->dir = (unsigned char)dir;
    memcpy(e->t, tri, sizeof e->t);
    return VB_OK;
}

/* The end of the last event, a vertex the round's map does not hold: its
 * members m (nm) and rounded point p, which the merge looks up and adds. */
int vbx_keep_end(vbx_tracer *t, vbx_hev *ev, const uint32_t *m, size_t nm, const double p[4])
{
    if (VB_ARRAY_FIT(t->ends, t->ends_cap, t->nends + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(t->pool, t->pool_cap, t->npool + nm, 1024) != VB_OK)
        return VB_ENOMEM;
    vbx_hend *x = &t->ends[t->nends];
    memcpy(x->p, p, sizeof x->p);
    x->moff = t->npool;
    x->nm = nm;
    memcpy(t->pool + t->npool, m, nm * sizeof *m);
    t->npool += nm;
    ev->to = SIZE_MAX;
    ev->end = t->nends++;
    return VB_OK;
}

static int push_end(vbx_tracer *t, const uint32_t *m, size_t nm, const double p[4])
{
    return vbx_keep_end(t, &t->ev[t->nev - 1], m, nm, p);
}

/* The next vertex of arc tp of triple frame f, certified, as an event
 * (with its index when the round's map of list lst holds it, else with
 * its members and point). */
static int arrive(vbx_tracer *tr, const vb_vertex_list *lst, vbx_tframe *f, const vbx_touch *tp,
                  int dir)
{
    double p[4];
    int ok = vbx_touch_certify(&tr->w, f, tp, p);
    if (ok < 0)
        return vb_errcode(tr->ctx);
    if (ok == 0) {
        /* A sphere cuts the first touching point: the arc was not an edge
         * there; the local test and the search disagree (degenerate). */
        return push_event(tr, VBX_EV_UNDECIDED, f->t, dir, SIZE_MAX);
    }
    const uint32_t *m = tr->c->members;
    size_t nm = tr->c->nmembers;
    size_t to = tr->map ? vbx_tmap_find(tr->map, lst, f->t, m, nm, p) : SIZE_MAX;
    int rc = push_event(tr, VBX_EV_CLOSED, f->t, dir, to);
    if (rc == VB_OK && to == SIZE_MAX)
        rc = push_end(tr, m, nm, p);
    return rc;
}

/* The forward arc of a triple's curve from vertex k (end ev) when the list
 * holds another vertex u of the same triple: u is the nearest one ahead
 * (on a closed curve, the nearest after the wrap when none is ahead
 * before it), and the open arc between them is searched (a bounded
 * region, far smaller than a tail's or the whole closed curve's). Returns
 * 2 with *to = u when no sphere touches inside (then the arc ends at u,
 * which the list holds, certified), 1 when one does (*tp, the first), 0
 * when there is no such u or positions cannot be told by the filter (the
 * caller searches the tail or the whole curve), or -status. */
static int forward_to_known(vbx_tracer *tr, const vb_vertex_list *all, vbx_tframe *f,
                            vbx_arc_end *ev, size_t k, vbx_touch *tp, size_t *to)
{
    if (!tr->map || !tr->map->n)
        return 0;
    /* a VBX_IT_TRIPLE item's vertices are the map's entries of f's triple,
     * their keys computed on this frame already */
    size_t lo = tr->glo, hi = tr->glo + tr->ng;
    if (!tr->ng)
        vbx_tmap_range(tr->map, f->t, &lo, &hi);
    vbx_arcw *w = &tr->w;
    int closed = f->kind != VBX_TRI_OPEN;
    /* [0]: the nearest ahead of ev; [1] (closed): the first of the curve
     * behind ev, where the arc ends after the wrap when nothing is ahead */
    size_t bests[2] = {SIZE_MAX, SIZE_MAX}, ibests[2] = {0, 0};
    vbx_key kbests[2];
    for (size_t i = lo; i < hi; i++) {
        size_t u = tr->map->e[i].k;
        if (u == k)
            continue;
        vbx_key ku;
        if (tr->ng) {
            ku = tr->gkey[i - lo];
        } else {
            double pu[4];
            vbx_vertex_point(all, u, pu);
            vbx_ia bu[4];
            vbx_box_of_rounded(pu, bu);
            vbx_key_of_box(w, f, bu, &ku);
        }
        int c = vbx_pos_cmp(w, f, &ev->key, NULL, &ku, NULL);
        if (c == 2)
            return 0;
        if (c >= 0 && !closed)
            continue;
        int side = c > 0;
        if (bests[side] != SIZE_MAX) {
            int c2 = vbx_pos_cmp(w, f, &ku, NULL, &kbests[side], NULL);
            if (c2 == 2 || c2 == 0)
                return 0;
            if (c2 > 0)
                continue;
        }
        bests[side] = u;
        ibests[side] = i - lo;
        kbests[side] = ku;
    }
    int side = bests[0] == SIZE_MAX;
    size_t best = bests[side];
    if (best == SIZE_MAX)
        return 0;
    vbx_key kbest = kbests[side];
    double pu[4];
    vbx_vertex_point(all, best, pu);
    vbx_xpt *xu = &tr->xu;
    int have = 0;
    vbx_arc_end eu = {0};
    eu.key = kbest;
    eu.m = all->ids + all->start[best];
    eu.nm = all->start[best + 1] - all->start[best];
    eu.xyzt = pu;
    eu.x = xu;
    eu.have = &have;
    if (tr->ng) {
        eu.box = tr->gbox + 4 * ibests[side];
        eu.tau = tr->gtau + 4 * ibests[side];
    }
    tp->found = 0;
    tp->have = 0;
    int rc = vbx_arc_search(w, f, ev, &eu, tp, NULL);
    if (rc == VB_EDEGENERATE)
        return 0;
    if (rc != VB_OK)
        return -rc;
    if (tp->found)
        return 1;
    *to = best;
    return 2;
}

/* The arcs of triple t (frame f, set up) at vertex k (members m, rounded
 * point p, its box, and its key and tangent (vbx_tau_of_box) on f when
 * known, else NULL): with all, the forward arc traced and the backward one
 * pending; else the backward arc traced. */
static int trace_at(vbx_tracer *tr, const vb_vertex_list *lst, size_t k, const uint32_t *m,
                    size_t nm, const double p[4], const vbx_ia box[4], const vbx_key *key,
                    const vbx_ia *tau, vbx_tframe *f, const uint32_t t[3], int all)
{
    vbx_arcw *w = &tr->w;
    int rc = VB_OK;
    tr->from = k;
    /* the tracer's points, reused (set before they are read) */
    vbx_xpt *x = &tr->x;
    int have = 0, fwd = 0, bwd = 0;
    uint64_t extra = 0;
    vbx_touch *tp = &tr->tp;
    tp->found = 0;
    tp->have = 0;
    if (f->kind == VBX_TRI_NONE) {
        goto done;
    }
    rc = vbx_local_arcs(w, f, m, nm, p, box, tau, x, &have, &fwd, &bwd, &extra);
    if (rc == VB_EDEGENERATE) {
        rc = all ? push_event(tr, VBX_EV_UNDECIDED, t, 0, SIZE_MAX) : VB_OK;
        goto done;
    }
    if (rc != VB_OK)
        goto done;
    if (extra) {
        /* Spheres beyond T carry the same curve: trace it for the triple of
         * the three smallest ids only. */
        size_t ix = 0;
        for (size_t i = 0; i < nm; i++) {
            if (m[i] == t[0] || m[i] == t[1] || m[i] == t[2])
                continue;
            if (ix < 64 && (extra >> ix & 1) && m[i] < t[2])
                goto done;
            ix++;
        }
    }
    vbx_arc_end ev = {0}, einf = {0};
    ev.m = m;
    ev.nm = nm;
    ev.xyzt = p;
    ev.x = x;
    ev.have = &have;
    ev.box = box;
    ev.tau = tau;
    if (key)
        ev.key = *key;
    else
        vbx_key_of_box(w, f, box, &ev.key);
    einf.inf = 1;
    int open = f->kind == VBX_TRI_OPEN;
    /* (the searches complete the plane frame where their region needs it) */
    for (int dir = 0; dir < 2 && rc == VB_OK; dir++) {
        if (!(dir == 0 ? fwd : bwd) || (dir == 0 && !all))
            continue;
        if (dir == 1 && all) {
            rc = push_event(tr, VBX_EV_PENDING, t, 1, SIZE_MAX);
            continue;
        }
        tp->found = 0;
        tp->have = 0;
        if (dir == 0) {
            size_t to = SIZE_MAX;
            int sc = forward_to_known(tr, lst, f, &ev, k, tp, &to);
            if (sc < 0) {
                rc = -sc;
                break;
            }
            if (sc == 2) {
                rc = push_event(tr, VBX_EV_CLOSED, t, 0, to);
                continue;
            }
            if (sc == 1) {
                rc = arrive(tr, lst, f, tp, dir);
                continue;
            }
            tp->found = 0;
            tp->have = 0;
        }
        if (dir == 0)
            rc = vbx_arc_search(w, f, &ev, open ? &einf : &ev, tp, NULL);
        else
            rc = vbx_arc_search(w, f, open ? &einf : &ev, &ev, NULL, tp);
        if (rc == VB_EDEGENERATE) {
            rc = push_event(tr, VBX_EV_UNDECIDED, t, dir, SIZE_MAX);
            continue;
        }
        if (rc != VB_OK)
            break;
        if (!tp->found) {
            rc = push_event(tr, open ? VBX_EV_INF : VBX_EV_LOOP, t, dir, SIZE_MAX);
            continue;
        }
        rc = arrive(tr, lst, f, tp, dir);
    }
done:
    return rc;
}

/* The tracer's frame set up for triple t. */
static int frame_of(vbx_tracer *tr, const uint32_t t[3], vbx_tframe **f)
{
    *f = &tr->f;
    vbx_tframe_reset(*f);
    return vbx_tframe_setup_local(&tr->w, *f, t);
}

/* The arcs of triple t at vertex k (trace_at), its frame set up first. */
static int trace_triple(vbx_tracer *tr, const vb_vertex_list *lst, size_t k, const uint32_t *m,
                        size_t nm, const double p[4], const vbx_ia box[4], const uint32_t t[3],
                        int all)
{
    vbx_tframe *f;
    int rc = frame_of(tr, t, &f);
    return rc == VB_OK ? trace_at(tr, lst, k, m, nm, p, box, NULL, NULL, f, t, all) : rc;
}

void vbx_tracer_scratch(vbx_tracer *t, int on)
{
    if (on && !t->have_scratch) {
        vbx_tframe_init(&t->f);
        vbx_xpt_init(&t->x);
        vbx_xpt_init(&t->xu);
        memset(&t->tp, 0, sizeof t->tp);
        vbx_xpt_init(&t->tp.x);
        t->have_scratch = 1;
    } else if (!on && t->have_scratch) {
        vbx_tframe_clear(&t->f);
        vbx_xpt_clear(&t->x);
        vbx_xpt_clear(&t->xu);
        vbx_xpt_clear(&t->tp.x);
        t->have_scratch = 0;
    }
}

/* A VBX_IT_TRIPLE item: the triple's frame once, then its arcs at each
 * vertex of the map that holds it. Every forward arc of the triple that
 * ends at a listed vertex is among this item's events (the map holds all
 * the round's vertices of the triple, and such an end is found in it), so
 * a backward arc is settled here when one of them reached its vertex:
 * what run_rounds' arrivals would settle, without the pending record. */
static int trace_group(vbx_tracer *tr, const vb_vertex_list *all, const vbx_item *it)
{
    const vbx_tent *e = tr->map->e + it->k;
    vbx_tframe *f;
    size_t e0 = tr->nev;
    int rc = frame_of(tr, e->t, &f);
    if (rc == VB_OK && (VB_ARRAY_FIT(tr->gkey, tr->gkey_cap, it->n, 16) != VB_OK ||
                        VB_ARRAY_FIT(tr->gbox, tr->gbox_cap, 4 * (size_t)it->n, 64) != VB_OK ||
                        VB_ARRAY_FIT(tr->gtau, tr->gtau_cap, 4 * (size_t)it->n, 64) != VB_OK))
        rc = VB_ENOMEM;
    if (rc != VB_OK || f->kind == VBX_TRI_NONE)
        return rc; /* no curve: no arcs, no events (trace_at) */
    /* each vertex's box, key and tangent once: its own local test and
     * search's start, and a candidate end of the others'
     * (forward_to_known) */
    for (uint32_t i = 0; i < it->n; i++) {
        double p[4];
        vbx_vertex_point(all, e[i].k, p);
        vbx_box_of_rounded(p, tr->gbox + 4 * (size_t)i);
        vbx_key_of_box(&tr->w, f, tr->gbox + 4 * (size_t)i, &tr->gkey[i]);
        vbx_tau_of_box(&tr->w, f, tr->gbox + 4 * (size_t)i, tr->gtau + 4 * (size_t)i);
    }
    tr->glo = it->k;
    tr->ng = it->n;
    for (uint32_t i = 0; rc == VB_OK && i < it->n; i++) {
        size_t k = e[i].k, s = all->start[k];
        if (tr->skip && tr->skip[k])
            continue;
        double p[4];
        vbx_vertex_point(all, k, p);
        rc = trace_at(tr, all, k, all->ids + s, all->start[k + 1] - s, p, tr->gbox + 4 * (size_t)i,
                      &tr->gkey[i], tr->gtau + 4 * (size_t)i, f, e->t, 1);
    }
    tr->ng = 0;
    for (size_t a = e0; rc == VB_OK && a < tr->nev; a++) {
        vbx_hev *pa = &tr->ev[a];
        if (pa->kind != VBX_EV_PENDING)
            continue;
        for (size_t b = e0; b < tr->nev; b++) {
            const vbx_hev *fb = &tr->ev[b];
            if (fb->kind == VBX_EV_CLOSED && fb->dir == 0 && fb->to == pa->from) {
                pa->kind = VBX_EV_REVERSED;
                break;
            }
        }
    }
    return rc;
}

/* One vbx_item, as events of vbx_tracer tr. */
static int trace_item(vbx_tracer *tr, const vb_vertex_list *all, const vbx_item *it)
{
    if (it->all == VBX_IT_TRIPLE)
        return trace_group(tr, all, it);
    size_t k = it->k, s = all->start[k], nm = all->start[k + 1] - s;
    const uint32_t *m = all->ids + s;
    double p[4];
    vbx_vertex_point(all, k, p);
    vbx_ia box[4];
    vbx_box_of_rounded(p, box);
    if (it->all == VBX_IT_BACK)
        return trace_triple(tr, all, k, m, nm, p, box, it->t, 0);
    int rc = VB_OK;
    for (size_t a = 0; a < nm && rc == VB_OK; a++)
        for (size_t b = a + 1; b < nm && rc == VB_OK; b++)
            for (size_t c = b + 1; c < nm && rc == VB_OK; c++) {
                uint32_t t[3] = {m[a], m[b], m[c]};
                rc = trace_triple(tr, all, k, m, nm, p, box, t, 1);
            }
    return rc;
}

/* A thread of a phase: chunks of items in turn; each vbx_item's events are a
 * function of that vbx_item alone (the worker keeps no state from one arc to
 * the next beyond its counters), so which thread traced it does not
 * matter. */
void *vbx_phase_work(void *arg)
{
    vbx_rjob *j = arg;
    vbx_tphase *ph = j->ph;
    vbx_tracer *tr = &ph->tr[j->index];
    double t0 = vb_thread_cpu_now();
    for (;;) {
        size_t c0 = atomic_fetch_add(&ph->next, VBX_RCHUNK);
        if (c0 >= ph->n || tr->rc != VB_OK)
            break;
        size_t c1 = c0 + VBX_RCHUNK < ph->n ? c0 + VBX_RCHUNK : ph->n;
        for (size_t i = c0; i < c1; i++) {
            ph->first[i] = tr->nev;
            ph->who[i] = (uint16_t)j->index;
            int rc = trace_item(tr, ph->all, &ph->it[i]);
            ph->count[i] = (uint32_t)(tr->nev - ph->first[i]);
            if (rc != VB_OK) {
                tr->rc = rc;
                tr->fail_at = i;
                break;
            }
        }
        if (ph->progress) {
            size_t d = atomic_fetch_add(&ph->done, c1 - c0) + (c1 - c0);
            vb_progress(ph->progress, "arcs", ph->base + ph->span * d / ph->n, ph->total);
        }
    }
    tr->busy += vb_thread_cpu_now() - t0;
    return NULL;
}

int vbx_tracers_open(vb_ctx *ctx, vb_certifier *c, unsigned nt, int lend0, char **block,
                     vbx_tracer **trp)
{
    char *b = calloc(nt * sizeof(vbx_tracer) + _Alignof(vbx_tracer), 1);
    vbx_tracer *tr = NULL;
    if (b)
        tr = (vbx_tracer *)(b + (_Alignof(vbx_tracer) - (uintptr_t)b % _Alignof(vbx_tracer)));
    *block = b;
    *trp = tr;
    int rc = tr ? VB_OK : VB_ENOMEM;
    for (unsigned i = 0; rc == VB_OK && i < nt; i++) {
        tr[i].ctx = ctx;
        tr[i].c = c;
        if (i > 0 || !lend0) {
            tr[i].ctx = NULL;
            tr[i].c = vbx_certifier_worker(c);
            if (!tr[i].c || vb_open_worker(&tr[i].ctx, ctx) != VB_OK) {
                rc = VB_ENOMEM;
                break;
            }
        }
        rc = vbx_arcw_init(&tr[i].w, tr[i].ctx, tr[i].c);
        tr[i].have_w = 1;
        vbx_tracer_scratch(&tr[i], 1);
    }
    return rc;
}

void vbx_tracers_free(char *block, vbx_tracer *tr, unsigned nt, int lend0)
{
    for (unsigned i = 0; tr && i < nt; i++) {
        if (tr[i].have_w)
            vbx_arcw_free(&tr[i].w);
        vbx_tracer_scratch(&tr[i], 0);
        free(tr[i].ev);
        free(tr[i].ends);
        free(tr[i].pool);
        free(tr[i].gkey);
        free(tr[i].gbox);
        free(tr[i].gtau);
        if (i > 0 || !lend0) {
            vb_certifier_close(tr[i].c);
            if (tr[i].ctx)
                vb_close(tr[i].ctx);
        }
    }
    free(block);
}

int vbx_phase_run(vbx_tphase *ph, unsigned nt, int keep_events)
{
    vbx_rjob jobs[VB_MAX_THREADS];
    size_t n = ph->n;
    unsigned use = nt;
    if (use > (n + VBX_RCHUNK - 1) / VBX_RCHUNK)
        use = (unsigned)((n + VBX_RCHUNK - 1) / VBX_RCHUNK);
    if (use < 1)
        use = 1;
    atomic_init(&ph->next, 0);
    atomic_init(&ph->done, 0);
    for (unsigned i = 0; i < use; i++) {
        jobs[i].ph = ph;
        jobs[i].index = i;
        vbx_tracer *t = &ph->tr[i];
        if (!keep_events)
            t->nev = t->nends = t->npool = 0;
        t->rc = VB_OK;
        t->fail_at = SIZE_MAX;
    }
    if (n)
        vb_run_jobs(vbx_phase_work, jobs, sizeof *jobs, (int)use);
    return vb_jobs_first_error(ph->tr, sizeof *ph->tr, (int)use, offsetof(vbx_tracer, rc),
                               offsetof(vbx_tracer, fail_at));
}
