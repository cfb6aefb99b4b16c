/* Arc closure (vb_arc.h): the tracing loop over the vertices, the lookup of
 * the next vertex of each arc, and the counts of the certificate. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"

#include "vb_arc.h"
#include "vbx_arc.h"

/* ---- the set of known vertices: members + rounded point -> index -------- */

typedef struct vtable {
    vb_vertex_list *v;
    size_t *slot; /* index + 1, 0 = empty */
    size_t cap;   /* power of two */
} vtable;

static uint64_t mix(uint64_t h, uint64_t x)
{
    h ^= x + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

static uint64_t vhash(const uint32_t *m, size_t nm, const double p[4])
{
    uint64_t h = nm;
    for (size_t i = 0; i < nm; i++)
        h = mix(h, m[i]);
    for (int k = 0; k < 4; k++) {
        uint64_t b;
        double x = p[k] == 0 ? 0.0 : p[k];
        memcpy(&b, &x, sizeof b);
        h = mix(h, b);
    }
    return h;
}

static int vsame(const vb_vertex_list *v, size_t k, const uint32_t *m, size_t nm,
                 const double p[4])
{
    size_t s = v->start[k], n = v->start[k + 1] - s;
    return n == nm && memcmp(v->ids + s, m, nm * sizeof *m) == 0 && v->x[k] == p[0] &&
           v->y[k] == p[1] && v->z[k] == p[2] && v->t[k] == p[3];
}

static size_t *vfind(vtable *t, const uint32_t *m, size_t nm, const double p[4])
{
    size_t i = (size_t)vhash(m, nm, p) & (t->cap - 1);
    while (t->slot[i] && !vsame(t->v, t->slot[i] - 1, m, nm, p))
        i = (i + 1) & (t->cap - 1);
    return &t->slot[i];
}

static void vpoint(const vb_vertex_list *v, size_t k, double p[4])
{
    p[0] = v->x[k];
    p[1] = v->y[k];
    p[2] = v->z[k];
    p[3] = v->t[k];
}

static int vgrow(vtable *t)
{
    size_t cap = t->cap ? 2 * t->cap : 64;
    while (cap < 2 * (t->v->n + 1))
        cap *= 2;
    size_t *slot = calloc(cap, sizeof *slot);
    if (!slot)
        return VB_ENOMEM;
    free(t->slot);
    t->slot = slot;
    t->cap = cap;
    for (size_t k = 0; k < t->v->n; k++) {
        double p[4];
        vpoint(t->v, k, p);
        size_t s = t->v->start[k];
        *vfind(t, t->v->ids + s, t->v->start[k + 1] - s, p) = k + 1;
    }
    return VB_OK;
}

/* ---- connected components ------------------------------------------------ */

typedef struct uf {
    size_t *p, cap;
} uf;

static int uf_fit(uf *u, size_t n)
{
    if (n <= u->cap)
        return VB_OK;
    size_t cap = u->cap ? u->cap : 64;
    while (cap < n)
        cap *= 2;
    size_t *p = realloc(u->p, cap * sizeof *p);
    if (!p)
        return VB_ENOMEM;
    for (size_t i = u->cap; i < cap; i++)
        p[i] = i;
    u->p = p;
    u->cap = cap;
    return VB_OK;
}

static size_t uf_root(uf *u, size_t i)
{
    while (u->p[i] != i) {
        u->p[i] = u->p[u->p[i]];
        i = u->p[i];
    }
    return i;
}

/* ---- tracing ------------------------------------------------------------- */

/* What one half arc found: its end, and for a vertex its members (in the
 * worker's pool) and rounded point. */
enum { EV_CLOSED = 0, EV_INF = 1, EV_LOOP = 2, EV_UNDECIDED = 3 };

typedef struct hev {
    double p[4];
    size_t moff;
    uint32_t nm;
    int kind;
} hev;

/* One thread's tracer: its certifier, context and worker, and the events of
 * the vertices it traced in the current round. */
typedef struct tracer {
    vb_ctx *ctx;
    vb_certifier *c;
    vbx_arcw w;
    int have_w;
    hev *ev;
    size_t nev, ev_cap;
    uint32_t *pool;
    size_t npool, pool_cap;
    int rc;
    size_t fail_at;   /* the first vertex (in the round) whose tracing failed */
} tracer;

typedef struct round {
    tracer *tr;
    unsigned nt;
    const vb_vertex_list *all;
    size_t lo, hi;          /* the vertices of this round */
    size_t *first;          /* per vertex of the round: first event */
    uint32_t *count;        /* ... number of events */
    uint16_t *who;          /* ... the tracer that holds them */
    atomic_size_t next;     /* next chunk */
} tround;

enum { RCHUNK = 8 };

static int push_event(tracer *t, int kind, const uint32_t *m, size_t nm, const double p[4])
{
    if (t->nev == t->ev_cap) {
        size_t cap = t->ev_cap ? 2 * t->ev_cap : 256;
        hev *e = realloc(t->ev, cap * sizeof *e);
        if (!e)
            return VB_ENOMEM;
        t->ev = e;
        t->ev_cap = cap;
    }
    hev *e = &t->ev[t->nev++];
    e->kind = kind;
    e->nm = (uint32_t)nm;
    e->moff = t->npool;
    if (p)
        memcpy(e->p, p, sizeof e->p);
    if (nm) {
        if (t->npool + nm > t->pool_cap) {
            size_t cap = t->pool_cap ? 2 * t->pool_cap : 1024;
            while (cap < t->npool + nm)
                cap *= 2;
            uint32_t *q = realloc(t->pool, cap * sizeof *q);
            if (!q)
                return VB_ENOMEM;
            t->pool = q;
            t->pool_cap = cap;
        }
        memcpy(t->pool + t->npool, m, nm * sizeof *m);
        t->npool += nm;
    }
    return VB_OK;
}

/* The next vertex of arc tp of triple frame f, certified, as an event. */
static int arrive(tracer *tr, vbx_tframe *f, const vbx_touch *tp)
{
    double p[4];
    int ok = vbx_touch_certify(&tr->w, f, tp, p);
    if (ok < 0)
        return vb_errcode(tr->ctx);
    if (ok == 0) {
        /* A sphere cuts the first touching point: the arc was not an edge
         * there; the local test and the search disagree (degenerate). */
        return push_event(tr, EV_UNDECIDED, NULL, 0, NULL);
    }
    return push_event(tr, EV_CLOSED, tr->c->members, tr->c->nmembers, p);
}

/* Both arcs of triple t at a vertex (members m, rounded point p). */
static int trace_triple(tracer *tr, const uint32_t *m, size_t nm, const double p[4],
                        const vbx_ia box[4], const uint32_t t[3])
{
    vbx_arcw *w = &tr->w;
    vbx_tframe f;
    vbx_tframe_init(&f);
    int rc = vbx_tframe_setup(w, &f, t);
    if (rc != VB_OK) {
        vbx_tframe_clear(&f);
        return rc;
    }
    vbx_xpt x;
    vbx_xpt_init(&x);
    int have = 0, fwd = 0, bwd = 0;
    uint64_t extra = 0;
    vbx_touch tp;
    memset(&tp, 0, sizeof tp);
    vbx_xpt_init(&tp.x);
    if (f.kind == VBX_TRI_NONE) {
        goto done;
    }
    rc = vbx_local_arcs(w, &f, m, nm, p, box, &x, &have, &fwd, &bwd, &extra);
    if (rc == VB_EDEGENERATE) {
        rc = push_event(tr, EV_UNDECIDED, NULL, 0, NULL);
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
    ev.x = &x;
    ev.have = &have;
    vbx_key_of_box(w, &f, box, &ev.key);
    einf.inf = 1;
    int open = f.kind == VBX_TRI_OPEN;
    for (int dir = 0; dir < 2 && rc == VB_OK; dir++) {
        if (!(dir == 0 ? fwd : bwd))
            continue;
        tp.found = 0;
        tp.have = 0;
        if (dir == 0)
            rc = vbx_arc_search(w, &f, &ev, open ? &einf : &ev, &tp, NULL);
        else
            rc = vbx_arc_search(w, &f, open ? &einf : &ev, &ev, NULL, &tp);
        if (rc == VB_EDEGENERATE) {
            rc = push_event(tr, EV_UNDECIDED, NULL, 0, NULL);
            continue;
        }
        if (rc != VB_OK)
            break;
        if (!tp.found) {
            rc = push_event(tr, open ? EV_INF : EV_LOOP, NULL, 0, NULL);
            continue;
        }
        rc = arrive(tr, &f, &tp);
    }
done:
    vbx_xpt_clear(&tp.x);
    vbx_xpt_clear(&x);
    vbx_tframe_clear(&f);
    return rc;
}

/* Every arc of vertex k of the round's list, as events of tracer tr. */
static int trace_vertex(tracer *tr, const vb_vertex_list *all, size_t k)
{
    size_t s = all->start[k], nm = all->start[k + 1] - s;
    const uint32_t *m = all->ids + s;
    double p[4];
    vpoint(all, k, p);
    vbx_ia box[4];
    vbx_box_of_rounded(p, box);
    int rc = VB_OK;
    for (size_t a = 0; a < nm && rc == VB_OK; a++)
        for (size_t b = a + 1; b < nm && rc == VB_OK; b++)
            for (size_t c = b + 1; c < nm && rc == VB_OK; c++) {
                uint32_t t[3] = {m[a], m[b], m[c]};
                rc = trace_triple(tr, m, nm, p, box, t);
            }
    return rc;
}

typedef struct rjob {
    tround *r;
    unsigned index;
} rjob;

/* A thread of a round: chunks of vertices in turn; each vertex's events
 * are a function of that vertex alone (the worker keeps no state from one
 * arc to the next beyond its counters), so which thread traced it does not
 * matter. */
static void *round_work(void *arg)
{
    rjob *j = arg;
    tround *r = j->r;
    tracer *tr = &r->tr[j->index];
    size_t n = r->hi - r->lo;
    for (;;) {
        size_t c0 = atomic_fetch_add(&r->next, RCHUNK);
        if (c0 >= n || tr->rc != VB_OK)
            break;
        size_t c1 = c0 + RCHUNK < n ? c0 + RCHUNK : n;
        for (size_t i = c0; i < c1; i++) {
            r->first[i] = tr->nev;
            r->who[i] = (uint16_t)j->index;
            int rc = trace_vertex(tr, r->all, r->lo + i);
            r->count[i] = (uint32_t)(tr->nev - r->first[i]);
            if (rc != VB_OK) {
                tr->rc = rc;
                tr->fail_at = i;
                break;
            }
        }
    }
    return NULL;
}

typedef struct closure {
    vb_ctx *ctx;
    vb_vertex_list all; /* input + added, in tracing order */
    vtable tab;
    uf comp;
    vb_arc_report *r;
} closure;

/* The events of vertex k (tracer tr, events [e0, e0 + n)) into the
 * counts, the list of vertices and the components, in event order. */
static int merge_vertex(closure *cl, tracer *tr, size_t e0, size_t n, size_t k)
{
    vb_arc_report *r = cl->r;
    for (size_t i = e0; i < e0 + n; i++) {
        const hev *e = &tr->ev[i];
        r->half_arcs++;
        if (e->kind == EV_INF) {
            r->infinite++;
            continue;
        }
        if (e->kind == EV_LOOP) {
            r->loops++;
            continue;
        }
        if (e->kind == EV_UNDECIDED) {
            r->undecided++;
            continue;
        }
        const uint32_t *m = tr->pool + e->moff;
        size_t *s = vfind(&cl->tab, m, e->nm, e->p);
        size_t to;
        if (*s) {
            to = *s - 1;
        } else {
            to = cl->all.n;
            int rc = vb_vertex_list_push(&cl->all, m, e->nm, e->p[0], e->p[1], e->p[2], e->p[3],
                                         0, VB_VERTEX_CERTIFIED);
            if (rc == VB_OK)
                rc = vb_vertex_list_push(&r->added, m, e->nm, e->p[0], e->p[1], e->p[2], e->p[3],
                                         0, VB_VERTEX_CERTIFIED);
            if (rc != VB_OK)
                return rc;
            if (2 * (cl->all.n + 1) > cl->tab.cap) {
                if (vgrow(&cl->tab) != VB_OK)
                    return VB_ENOMEM;
            } else {
                *s = to + 1;
            }
        }
        r->closed++;
        if (uf_fit(&cl->comp, cl->all.n) != VB_OK)
            return VB_ENOMEM;
        size_t a = uf_root(&cl->comp, k), b = uf_root(&cl->comp, to);
        if (a != b)
            cl->comp.p[a > b ? a : b] = a < b ? a : b;
    }
    return VB_OK;
}

static void add_counters(vb_arc_report *r, const vbx_arc_counters *c)
{
    r->filter_calls += c->filter_calls;
    r->filter_failures += c->filter_failures;
    r->exact_evals += c->exact_evals;
    r->candidates += c->candidates;
}

/* Rounds: every vertex not yet traced is traced (in parallel), then the
 * events are merged in vertex order; vertices found new go to the end of
 * the list and make the next round. The list, the counts and the added
 * vertices are therefore the same on any number of threads. */
static int run_rounds(closure *cl, tracer *tr, unsigned nt)
{
    size_t lo = 0;
    int rc = VB_OK;
    while (rc == VB_OK && lo < cl->all.n) {
        size_t hi = cl->all.n, n = hi - lo;
        tround r;
        memset(&r, 0, sizeof r);
        r.tr = tr;
        r.all = &cl->all;
        r.lo = lo;
        r.hi = hi;
        r.first = malloc(n * sizeof *r.first);
        r.count = malloc(n * sizeof *r.count);
        r.who = malloc(n * sizeof *r.who);
        atomic_init(&r.next, 0);
        rjob jobs[VB_MAX_THREADS];
        unsigned use = nt;
        if (use > (n + RCHUNK - 1) / RCHUNK)
            use = (unsigned)((n + RCHUNK - 1) / RCHUNK);
        if (use < 1)
            use = 1;
        for (unsigned i = 0; i < use; i++) {
            jobs[i].r = &r;
            jobs[i].index = i;
            tr[i].nev = 0;
            tr[i].npool = 0;
            tr[i].rc = VB_OK;
            tr[i].fail_at = SIZE_MAX;
        }
        if (!r.first || !r.count || !r.who) {
            rc = vb_error(cl->ctx, VB_ENOMEM, NULL, 0, "out of memory (arc closure)");
        } else {
            vb_run_jobs(round_work, jobs, sizeof *jobs, (int)use);
            /* The first failing vertex's error, as one thread would meet it. */
            unsigned bad = 0;
            for (unsigned i = 1; i < use; i++)
                if (tr[i].fail_at < tr[bad].fail_at)
                    bad = i;
            if (tr[bad].rc != VB_OK) {
                rc = tr[bad].rc;
                if (bad != 0)
                    vb_error(cl->ctx, rc, NULL, 0, "%s", vb_errmsg(tr[bad].ctx));
            }
        }
        for (size_t i = 0; rc == VB_OK && i < n; i++)
            rc = merge_vertex(cl, &tr[r.who[i]], r.first[i], r.count[i], lo + i);
        free(r.first);
        free(r.count);
        free(r.who);
        lo = hi;
    }
    return rc;
}

int vb_arc_close(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                 unsigned threads, vb_arc_report *out)
{
    memset(out, 0, sizeof *out);
    vb_vertex_list_init(&out->added);
    closure cl;
    memset(&cl, 0, sizeof cl);
    cl.ctx = ctx;
    cl.r = out;
    vb_vertex_list_init(&cl.all);
    unsigned nt = (unsigned)vb_threads(threads);
    size_t most = in->n / 64 + 1;
    if (nt > most)
        nt = (unsigned)most;
    tracer *tr = calloc(nt, sizeof *tr);
    vb_certifier *c = NULL;
    int rc = tr ? vb_certifier_open(ctx, set, &c) : VB_ENOMEM;
    for (unsigned i = 0; rc == VB_OK && i < nt; i++) {
        tr[i].ctx = ctx;
        tr[i].c = c;
        if (i > 0) {
            tr[i].c = vbx_certifier_worker(c);
            if (!tr[i].c || vb_open(&tr[i].ctx, NULL) != VB_OK) {
                rc = VB_ENOMEM;
                break;
            }
        }
        rc = vbx_arcw_init(&tr[i].w, tr[i].ctx, tr[i].c);
        tr[i].have_w = 1;
    }
    for (size_t k = 0; rc == VB_OK && k < in->n; k++) {
        size_t s = in->start[k];
        rc = vb_vertex_list_push(&cl.all, in->ids + s, in->start[k + 1] - s, in->x[k], in->y[k],
                                 in->z[k], in->t[k], 0, VB_VERTEX_CERTIFIED);
    }
    cl.tab.v = &cl.all;
    if (rc == VB_OK)
        rc = vgrow(&cl.tab);
    if (rc == VB_OK)
        rc = uf_fit(&cl.comp, cl.all.n);
    if (rc == VB_OK)
        rc = run_rounds(&cl, tr, nt);
    if (rc == VB_OK) {
        out->vertices = cl.all.n;
        for (size_t k = 0; k < cl.all.n; k++)
            out->components += uf_root(&cl.comp, k) == k;
        for (unsigned i = 0; i < nt; i++)
            add_counters(out, &tr[i].w.cnt);
        rc = vb_vertex_list_sort(&out->added);
    }
    if (rc == VB_ENOMEM && vb_errcode(ctx) != VB_ENOMEM)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (arc closure)");
    for (unsigned i = 0; tr && i < nt; i++) {
        if (tr[i].have_w)
            vbx_arcw_free(&tr[i].w);
        free(tr[i].ev);
        free(tr[i].pool);
        if (i > 0) {
            vb_certifier_close(tr[i].c);
            if (tr[i].ctx)
                vb_close(tr[i].ctx);
        }
    }
    vb_certifier_close(c);
    free(tr);
    vb_vertex_list_free(&cl.all);
    free(cl.tab.slot);
    free(cl.comp.p);
    return rc;
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
