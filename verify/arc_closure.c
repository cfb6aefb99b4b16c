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

/* ---- arrivals: (vertex, triple) pairs reached by a forward arc ---------- */

typedef struct akey {
    size_t to; /* index + 1, 0 = empty */
    uint32_t t[3];
} akey;

typedef struct aset {
    akey *slot;
    size_t cap, n; /* cap a power of two */
} aset;

static size_t ahash(const aset *a, size_t to, const uint32_t t[3])
{
    uint64_t h = mix(mix(mix(mix(0, to), t[0]), t[1]), t[2]);
    return (size_t)h & (a->cap - 1);
}

static akey *afind(aset *a, size_t to, const uint32_t t[3])
{
    size_t i = ahash(a, to, t);
    while (a->slot[i].to && !(a->slot[i].to == to + 1 && a->slot[i].t[0] == t[0] &&
                              a->slot[i].t[1] == t[1] && a->slot[i].t[2] == t[2]))
        i = (i + 1) & (a->cap - 1);
    return &a->slot[i];
}

static int aput(aset *a, size_t to, const uint32_t t[3])
{
    if (2 * (a->n + 1) > a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 1024;
        akey *old = a->slot;
        size_t ocap = a->cap;
        a->slot = calloc(cap, sizeof *a->slot);
        if (!a->slot) {
            a->slot = old;
            return VB_ENOMEM;
        }
        a->cap = cap;
        for (size_t i = 0; i < ocap; i++)
            if (old[i].to)
                *afind(a, old[i].to - 1, old[i].t) = old[i];
        free(old);
    }
    akey *k = afind(a, to, t);
    if (!k->to) {
        k->to = to + 1;
        memcpy(k->t, t, sizeof k->t);
        a->n++;
    }
    return VB_OK;
}

static int ahas(aset *a, size_t to, const uint32_t t[3])
{
    return a->cap && afind(a, to, t)->to != 0;
}

/* ---- the vertices of each triple ------------------------------------------ */

/* (triple, vertex) for every triple of every vertex of the list, sorted:
 * where a forward arc is likely to end (run_rounds: the next vertex along a
 * triple's curve is one that holds the triple). */
typedef struct tent {
    uint32_t t[3];
    uint32_t k;
} tent;

typedef struct tmap {
    tent *e;
    size_t n, cap;
    size_t done;  /* vertices entered */
} tmap;

static int tent_cmp(const void *pa, const void *pb)
{
    const tent *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

/* Enters the vertices [m->done, all->n) and sorts again. VB_OK, VB_ENOMEM
 * (the map is then emptied). A map that lacks vertices costs searches,
 * never a wrong end: the bounded search of forward_to_known proves its end
 * whichever listed vertex it is given (a nearer vertex is found inside). */
static int tmap_update(tmap *m, const vb_vertex_list *all, unsigned nt)
{
    for (size_t k = m->done; k < all->n; k++) {
        size_t s = all->start[k], nm = all->start[k + 1] - s;
        const uint32_t *id = all->ids + s;
        for (size_t a = 0; a < nm; a++)
            for (size_t b = a + 1; b < nm; b++)
                for (size_t c = b + 1; c < nm; c++) {
                    if (m->n == m->cap) {
                        size_t cap = m->cap ? 2 * m->cap : 4096;
                        tent *e = realloc(m->e, cap * sizeof *e);
                        if (!e) {
                            m->n = 0;
                            return VB_ENOMEM;
                        }
                        m->e = e;
                        m->cap = cap;
                    }
                    tent *e = &m->e[m->n++];
                    e->t[0] = id[a];
                    e->t[1] = id[b];
                    e->t[2] = id[c];
                    e->k = (uint32_t)k;
                }
    }
    m->done = all->n;
    /* tent_cmp is a total order (the vertex breaks ties): the same array on
     * any number of threads */
    if (vb_psort(m->e, m->n, sizeof *m->e, tent_cmp, (int)nt) != VB_OK) {
        m->n = 0;
        return VB_ENOMEM;
    }
    return VB_OK;
}

/* The entries of triple t: [*lo, *hi). */
static void tmap_range(const tmap *m, const uint32_t t[3], size_t *lo, size_t *hi)
{
    tent key = {{t[0], t[1], t[2]}, 0};
    size_t a = 0, b = m->n;
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        if (tent_cmp(&m->e[mid], &key) < 0)
            a = mid + 1;
        else
            b = mid;
    }
    *lo = a;
    while (a < m->n && m->e[a].t[0] == t[0] && m->e[a].t[1] == t[1] && m->e[a].t[2] == t[2])
        a++;
    *hi = a;
}

/* ---- tracing ------------------------------------------------------------- */

/* What one half arc found: its end, and for a vertex its members (in the
 * worker's pool) and rounded point; EV_PENDING: a backward arc left for
 * later (see run_rounds). */
enum { EV_CLOSED = 0, EV_INF = 1, EV_LOOP = 2, EV_UNDECIDED = 3, EV_PENDING = 4 };

typedef struct hev {
    double p[4];
    size_t moff;
    uint32_t nm;
    uint32_t t[3];
    int kind, dir;
} hev;

/* One thread's tracer: its certifier, context and worker, and the events of
 * the items it traced in the current phase. */
typedef struct tracer {
    const tmap *map;        /* the list's triples (NULL: no shortcut) */
    vb_ctx *ctx;
    vb_certifier *c;
    vbx_arcw w;
    int have_w;
    hev *ev;
    size_t nev, ev_cap;
    uint32_t *pool;
    size_t npool, pool_cap;
    int rc;
    size_t fail_at;   /* the first item (in the phase) whose tracing failed */
} tracer;

/* An item of a phase: every triple of vertex k (forward arcs traced,
 * backward ones left pending), or the backward arc of triple t alone. */
typedef struct item {
    size_t k;
    uint32_t t[3];
    int all;
} item;

typedef struct tphase {
    tracer *tr;
    const vb_vertex_list *all;
    const item *it;
    size_t n;
    size_t *first;          /* per item: first event */
    uint32_t *count;        /* ... number of events */
    uint16_t *who;          /* ... the tracer that holds them */
    atomic_size_t next;     /* next chunk */
} tphase;

enum { RCHUNK = 8 };

static int push_event(tracer *t, int kind, const uint32_t tri[3], int dir, const uint32_t *m,
                      size_t nm, const double p[4])
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
    e->dir = dir;
    memcpy(e->t, tri, sizeof e->t);
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
static int arrive(tracer *tr, vbx_tframe *f, const vbx_touch *tp, int dir)
{
    double p[4];
    int ok = vbx_touch_certify(&tr->w, f, tp, p);
    if (ok < 0)
        return vb_errcode(tr->ctx);
    if (ok == 0) {
        /* A sphere cuts the first touching point: the arc was not an edge
         * there; the local test and the search disagree (degenerate). */
        return push_event(tr, EV_UNDECIDED, f->t, dir, NULL, 0, NULL);
    }
    return push_event(tr, EV_CLOSED, f->t, dir, tr->c->members, tr->c->nmembers, p);
}

/* The arcs of triple t at a vertex (members m, rounded point p): with all,
 * the forward arc traced and the backward one pending; else the backward
 * arc traced. */
/* The forward arc of an open branch from vertex k (end ev) when the list
 * holds a vertex u of the same triple ahead of it: the open arc between
 * them is searched (a bounded region, far smaller than the tail's). Returns
 * 2 with *to = u when no sphere touches inside (then the arc ends at u,
 * which the list holds, certified), 1 when one does (*tp, the first), 0
 * when there is no such u or positions cannot be told by the filter (the
 * caller searches the tail), or -status. */
static int forward_to_known(tracer *tr, const vb_vertex_list *all, vbx_tframe *f,
                            vbx_arc_end *ev, size_t k, vbx_touch *tp, size_t *to)
{
    if (!tr->map || !tr->map->n)
        return 0;
    size_t lo, hi;
    tmap_range(tr->map, f->t, &lo, &hi);
    vbx_arcw *w = &tr->w;
    size_t best = SIZE_MAX;
    vbx_key kbest;
    for (size_t i = lo; i < hi; i++) {
        size_t u = tr->map->e[i].k;
        if (u == k)
            continue;
        double pu[4];
        vpoint(all, u, pu);
        vbx_ia bu[4];
        vbx_box_of_rounded(pu, bu);
        vbx_key ku;
        vbx_key_of_box(w, f, bu, &ku);
        int c = vbx_pos_cmp(w, f, &ev->key, NULL, &ku, NULL);
        if (c == 2)
            return 0;
        if (c >= 0)
            continue;
        if (best != SIZE_MAX) {
            int c2 = vbx_pos_cmp(w, f, &ku, NULL, &kbest, NULL);
            if (c2 == 2 || c2 == 0)
                return 0;
            if (c2 > 0)
                continue;
        }
        best = u;
        kbest = ku;
    }
    if (best == SIZE_MAX)
        return 0;
    double pu[4];
    vpoint(all, best, pu);
    vbx_xpt xu;
    vbx_xpt_init(&xu);
    int have = 0;
    vbx_arc_end eu = {0};
    eu.key = kbest;
    eu.m = all->ids + all->start[best];
    eu.nm = all->start[best + 1] - all->start[best];
    eu.xyzt = pu;
    eu.x = &xu;
    eu.have = &have;
    tp->found = 0;
    tp->have = 0;
    int rc = vbx_arc_search(w, f, ev, &eu, tp, NULL);
    vbx_xpt_clear(&xu);
    if (rc == VB_EDEGENERATE)
        return 0;
    if (rc != VB_OK)
        return -rc;
    if (tp->found)
        return 1;
    *to = best;
    return 2;
}

static int trace_triple(tracer *tr, const vb_vertex_list *lst, size_t k, const uint32_t *m,
                        size_t nm, const double p[4], const vbx_ia box[4], const uint32_t t[3],
                        int all)
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
        rc = all ? push_event(tr, EV_UNDECIDED, t, 0, NULL, 0, NULL) : VB_OK;
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
        if (!(dir == 0 ? fwd : bwd) || (dir == 0 && !all))
            continue;
        if (dir == 1 && all) {
            rc = push_event(tr, EV_PENDING, t, 1, NULL, 0, NULL);
            continue;
        }
        tp.found = 0;
        tp.have = 0;
        if (dir == 0 && open) {
            size_t to;
            int sc = forward_to_known(tr, lst, &f, &ev, k, &tp, &to);
            if (sc < 0) {
                rc = -sc;
                break;
            }
            if (sc == 2) {
                double pu[4];
                vpoint(lst, to, pu);
                size_t s0 = lst->start[to];
                rc = push_event(tr, EV_CLOSED, t, 0, lst->ids + s0, lst->start[to + 1] - s0, pu);
                continue;
            }
            if (sc == 1) {
                rc = arrive(tr, &f, &tp, dir);
                continue;
            }
            tp.found = 0;
            tp.have = 0;
        }
        if (dir == 0)
            rc = vbx_arc_search(w, &f, &ev, open ? &einf : &ev, &tp, NULL);
        else
            rc = vbx_arc_search(w, &f, open ? &einf : &ev, &ev, NULL, &tp);
        if (rc == VB_EDEGENERATE) {
            rc = push_event(tr, EV_UNDECIDED, t, dir, NULL, 0, NULL);
            continue;
        }
        if (rc != VB_OK)
            break;
        if (!tp.found) {
            rc = push_event(tr, open ? EV_INF : EV_LOOP, t, dir, NULL, 0, NULL);
            continue;
        }
        rc = arrive(tr, &f, &tp, dir);
    }
done:
    vbx_xpt_clear(&tp.x);
    vbx_xpt_clear(&x);
    vbx_tframe_clear(&f);
    return rc;
}

/* One item, as events of tracer tr. */
static int trace_item(tracer *tr, const vb_vertex_list *all, const item *it)
{
    size_t k = it->k, s = all->start[k], nm = all->start[k + 1] - s;
    const uint32_t *m = all->ids + s;
    double p[4];
    vpoint(all, k, p);
    vbx_ia box[4];
    vbx_box_of_rounded(p, box);
    if (!it->all)
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

typedef struct rjob {
    tphase *ph;
    unsigned index;
} rjob;

/* A thread of a phase: chunks of items in turn; each item's events are a
 * function of that item alone (the worker keeps no state from one arc to
 * the next beyond its counters), so which thread traced it does not
 * matter. */
static void *phase_work(void *arg)
{
    rjob *j = arg;
    tphase *ph = j->ph;
    tracer *tr = &ph->tr[j->index];
    for (;;) {
        size_t c0 = atomic_fetch_add(&ph->next, RCHUNK);
        if (c0 >= ph->n || tr->rc != VB_OK)
            break;
        size_t c1 = c0 + RCHUNK < ph->n ? c0 + RCHUNK : ph->n;
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
    }
    return NULL;
}

/* A traced edge (vb_arc_close_edges), oriented forward along its curve:
 * from its start to its end (vertex indices of closure.all), with the kind
 * of half arc that recorded it. */
enum { TE_FWD = 0, TE_BWD = 1, TE_INF = 2, TE_LOOP = 3 };

typedef struct tedge {
    size_t from, to; /* to: SIZE_MAX for infinity */
    uint32_t t[3];
    int kind;
} tedge;

typedef struct closure {
    vb_ctx *ctx;
    tedge *ed;          /* NULL unless edges are wanted */
    size_t ned, ed_cap;
    int want_edges;
    vb_vertex_list all; /* input + added, in tracing order */
    vtable tab;
    uf comp;
    aset arrived;       /* (vertex, triple) reached by a forward arc */
    tmap map;           /* the triples of the list */
    item *pend;         /* backward arcs left pending in this round */
    size_t npend, pend_cap;
    vb_arc_report *r;
} closure;

static int push_item(item **v, size_t *n, size_t *cap, size_t k, const uint32_t t[3], int all)
{
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 256;
        item *p = realloc(*v, c * sizeof *p);
        if (!p)
            return VB_ENOMEM;
        *v = p;
        *cap = c;
    }
    item *it = &(*v)[(*n)++];
    it->k = k;
    memcpy(it->t, t, sizeof it->t);
    it->all = all;
    return VB_OK;
}

static int push_tedge(closure *cl, size_t from, size_t to, const uint32_t t[3], int kind)
{
    if (!cl->want_edges)
        return VB_OK;
    if (cl->ned == cl->ed_cap) {
        size_t cap = cl->ed_cap ? 2 * cl->ed_cap : 1024;
        tedge *p = realloc(cl->ed, cap * sizeof *p);
        if (!p)
            return VB_ENOMEM;
        cl->ed = p;
        cl->ed_cap = cap;
    }
    tedge *e = &cl->ed[cl->ned++];
    e->from = from;
    e->to = to;
    memcpy(e->t, t, sizeof e->t);
    e->kind = kind;
    return VB_OK;
}

/* The events of item k's vertex (tracer tr, events [e0, e0 + n)) into the
 * counts, the list of vertices, the components and the arrivals, in event
 * order; pending arcs to cl->pend. */
static int merge_events(closure *cl, tracer *tr, size_t e0, size_t n, size_t k)
{
    vb_arc_report *r = cl->r;
    for (size_t i = e0; i < e0 + n; i++) {
        const hev *e = &tr->ev[i];
        if (e->kind == EV_PENDING) {
            if (push_item(&cl->pend, &cl->npend, &cl->pend_cap, k, e->t, 0) != VB_OK)
                return VB_ENOMEM;
            continue;
        }
        r->half_arcs++;
        if (e->kind == EV_INF) {
            r->infinite++;
            if (push_tedge(cl, k, SIZE_MAX, e->t, TE_INF) != VB_OK)
                return VB_ENOMEM;
            continue;
        }
        if (e->kind == EV_LOOP) {
            r->loops++;
            if (push_tedge(cl, k, k, e->t, TE_LOOP) != VB_OK)
                return VB_ENOMEM;
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
        if (e->dir == 0 && aput(&cl->arrived, to, e->t) != VB_OK)
            return VB_ENOMEM;
        /* a backward arc from k that ends at `to` is the edge that leaves
         * `to` forward */
        if (push_tedge(cl, e->dir == 0 ? k : to, e->dir == 0 ? to : k, e->t,
                       e->dir == 0 ? TE_FWD : TE_BWD) != VB_OK)
            return VB_ENOMEM;
        if (uf_fit(&cl->comp, cl->all.n) != VB_OK)
            return VB_ENOMEM;
        size_t a = uf_root(&cl->comp, k), b = uf_root(&cl->comp, to);
        if (a != b)
            cl->comp.p[a > b ? a : b] = a < b ? a : b;
    }
    return VB_OK;
}

/* Runs the n items on the tracers and merges their events in item order. */
static int run_phase(closure *cl, tracer *tr, unsigned nt, const item *it, size_t n)
{
    if (!n)
        return VB_OK;
    tphase ph;
    memset(&ph, 0, sizeof ph);
    ph.tr = tr;
    ph.all = &cl->all;
    ph.it = it;
    ph.n = n;
    ph.first = malloc(n * sizeof *ph.first);
    ph.count = malloc(n * sizeof *ph.count);
    ph.who = malloc(n * sizeof *ph.who);
    atomic_init(&ph.next, 0);
    int rc = VB_OK;
    rjob jobs[VB_MAX_THREADS];
    unsigned use = nt;
    if (use > (n + RCHUNK - 1) / RCHUNK)
        use = (unsigned)((n + RCHUNK - 1) / RCHUNK);
    if (use < 1)
        use = 1;
    for (unsigned i = 0; i < use; i++) {
        jobs[i].ph = &ph;
        jobs[i].index = i;
        tr[i].nev = 0;
        tr[i].npool = 0;
        tr[i].rc = VB_OK;
        tr[i].fail_at = SIZE_MAX;
    }
    if (!ph.first || !ph.count || !ph.who) {
        rc = VB_ENOMEM;
    } else {
        vb_run_jobs(phase_work, jobs, sizeof *jobs, (int)use);
        /* The first failing item's error, as one thread would meet it. */
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
        rc = merge_events(cl, &tr[ph.who[i]], ph.first[i], ph.count[i], it[i].k);
    free(ph.first);
    free(ph.count);
    free(ph.who);
    return rc;
}

/* Rounds: every vertex not yet traced has its forward arcs traced (in
 * parallel), the events merged in vertex order; then each backward arc is
 * either the reverse of a forward arc already traced that arrived at its
 * vertex with its triple (the forward search proved the open arc between
 * the two vertices free of touching spheres, so the backward search would
 * end at that arc's start: counted closed without a search), or traced
 * itself, in a second parallel phase. Vertices found new go to the end of
 * the list and make the next round. The list, the counts and the added
 * vertices are therefore the same on any number of threads. */
static int run_rounds(closure *cl, tracer *tr, unsigned nt)
{
    size_t lo = 0;
    int rc = VB_OK;
    item *it = NULL, *back = NULL;
    size_t it_cap = 0, back_cap = 0;
    while (rc == VB_OK && lo < cl->all.n) {
        size_t hi = cl->all.n, nit = 0, nback = 0;
        /* the map is read by every thread of the round: built before it */
        const tmap *map = tmap_update(&cl->map, &cl->all, nt) == VB_OK ? &cl->map : NULL;
        for (unsigned i = 0; i < nt; i++)
            tr[i].map = map;
        static const uint32_t none[3] = {0, 0, 0};
        for (size_t k = lo; rc == VB_OK && k < hi; k++)
            rc = push_item(&it, &nit, &it_cap, k, none, 1);
        cl->npend = 0;
        if (rc == VB_OK)
            rc = run_phase(cl, tr, nt, it, nit);
        for (size_t i = 0; rc == VB_OK && i < cl->npend; i++) {
            const item *pi = &cl->pend[i];
            if (ahas(&cl->arrived, pi->k, pi->t)) {
                cl->r->half_arcs++;
                cl->r->closed++;
            } else {
                rc = push_item(&back, &nback, &back_cap, pi->k, pi->t, 0);
            }
        }
        if (rc == VB_OK)
            rc = run_phase(cl, tr, nt, back, nback);
        lo = hi;
    }
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
    const tedge *a = pa, *b = pb;
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
static int emit_edges(closure *cl, size_t nin, const size_t *where_added,
                      vb_topology_edge **edges, size_t *nedges)
{
    if (cl->ned)
        qsort(cl->ed, cl->ned, sizeof *cl->ed, tedge_cmp);
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
            const tedge *e = &cl->ed[i];
            if (e->kind == TE_FWD) {
                have_fwd = 1;
                fwd_to = e->to;
            } else if (e->kind == TE_BWD && have_fwd && e->to == fwd_to) {
                continue;
            } else if (e->kind == TE_LOOP) {
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

static int close_list(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                      unsigned threads, vb_arc_report *out, vb_topology_edge **edges,
                      size_t *nedges)
{
    memset(out, 0, sizeof *out);
    vb_vertex_list_init(&out->added);
    closure cl;
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
        if (edges && !(where = malloc((out->added.n ? out->added.n : 1) * sizeof *where)))
            rc = VB_ENOMEM;
        if (rc == VB_OK)
            rc = vb_vertex_list_sort_perm(&out->added, where);
        if (rc == VB_OK && edges)
            rc = emit_edges(&cl, in->n, where, edges, nedges);
    }
    free(where);
    free(cl.ed);
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
    free(cl.arrived.slot);
    free(cl.pend);
    free(cl.map.e);
    return rc;
}

int vb_arc_close(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                 unsigned threads, vb_arc_report *out)
{
    return close_list(ctx, set, in, threads, out, NULL, NULL);
}

int vb_arc_close_edges(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                       unsigned threads, vb_arc_report *out, vb_topology_edge **edges,
                       size_t *nedges)
{
    return close_list(ctx, set, in, threads, out, edges, nedges);
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
