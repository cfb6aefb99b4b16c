/* Arc closure (vb_arc.h): the tracing loop over the vertices in rounds,
 * the lookup of the next vertex of each arc, the components and the counts
 * of the certificate, and the edges (the tracers: arc_tracer.c). */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vb_parallel.h"
#include "vb_uf.h"

#include "vb_arc.h"
#include "vbx_closure.h"

/* ---- the set of known vertices: members + rounded point -> index -------- */

/* A vertex sought: members m (nm of them) and rounded point p, against the
 * vertices of list v. */
typedef struct vkey {
    const vb_vertex_list *v;
    const uint32_t *m;
    size_t nm;
    const double *p;
} vkey;

static uint64_t vhash(const uint32_t *m, size_t nm, const double p[4])
{
    uint64_t h = nm;
    for (size_t i = 0; i < nm; i++)
        h = vb_hash_mix(h, m[i]);
    for (int k = 0; k < 4; k++) {
        uint64_t b;
        double x = p[k] == 0 ? 0.0 : p[k];
        memcpy(&b, &x, sizeof b);
        h = vb_hash_mix(h, b);
    }
    return h;
}

static int vsame(const void *key, size_t k)
{
    const vkey *q = key;
    const vb_vertex_list *v = q->v;
    size_t s = v->start[k], n = v->start[k + 1] - s;
    return n == q->nm && memcmp(v->ids + s, q->m, q->nm * sizeof *q->m) == 0 &&
           v->x[k] == q->p[0] && v->y[k] == q->p[1] && v->z[k] == q->p[2] && v->t[k] == q->p[3];
}

/* The hash of vertex k of the list arg (vb_hash_of_fn). */
static uint64_t vhash_of(const void *arg, size_t k)
{
    const vb_vertex_list *v = arg;
    double p[4];
    vbx_vertex_point(v, k, p);
    size_t s = v->start[k];
    return vhash(v->ids + s, v->start[k + 1] - s, p);
}

/* The slot of the vertex of members m and rounded point p in the table of
 * the closure's list (vb_hash_slot). */
static size_t *vslot(vb_hash *tab, const vb_vertex_list *all, const uint32_t *m, size_t nm,
                     const double p[4])
{
    vkey q = {all, m, nm, p};
    return vb_hash_slot(tab, vhash(m, nm, p), vsame, &q);
}

/* ---- arrivals: (vertex, triple) pairs reached by a forward arc ---------- */

typedef struct akey {
    size_t to;
    uint32_t t[3];
} akey;

/* The pairs in order of arrival and the table of them. */
typedef struct aset {
    akey *k;
    size_t n, cap;
    vb_hash tab;
} aset;

static uint64_t ahash(const akey *k)
{
    return vb_hash_mix(vb_hash_mix(vb_hash_mix(vb_hash_mix(0, k->to), k->t[0]), k->t[1]),
                       k->t[2]);
}

/* A pair sought in set a. */
typedef struct asame_arg {
    const aset *a;
    const akey *q;
} asame_arg;

static int asame(const void *key, size_t i)
{
    const asame_arg *x = key;
    const akey *e = &x->a->k[i];
    return e->to == x->q->to && e->t[0] == x->q->t[0] && e->t[1] == x->q->t[1] &&
           e->t[2] == x->q->t[2];
}

static uint64_t ahash_of(const void *arg, size_t i)
{
    const aset *a = arg;
    return ahash(&a->k[i]);
}

static int aput(aset *a, size_t to, const uint32_t t[3])
{
    akey q = {to, {t[0], t[1], t[2]}};
    asame_arg x = {a, &q};
    if (!a->tab.cap && vb_hash_fit(&a->tab, 0, ahash_of, a) != VB_OK)
        return VB_ENOMEM;
    size_t *s = vb_hash_slot(&a->tab, ahash(&q), asame, &x);
    if (*s)
        return VB_OK;
    if (VB_ARRAY_FIT(a->k, a->cap, a->n + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    a->k[a->n] = q;
    return vb_hash_put(&a->tab, s, a->n++, ahash_of, a);
}

static int ahas(const aset *a, size_t to, const uint32_t t[3])
{
    akey q = {to, {t[0], t[1], t[2]}};
    asame_arg x = {a, &q};
    return vb_hash_get(&a->tab, ahash(&q), asame, &x) != SIZE_MAX;
}

/* ---- the closure --------------------------------------------------------- */

/* Vertices of at most this many members keep their arrivals as bits. */
enum { MASK_MEMBERS = 6 };

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
    vb_hash tab;        /* the vertices added to all (the input's are found through
                           the map: vbx_tmap_find) */
    vb_uf comp;         /* components of the vertex-edge graph */
    aset arrived;       /* (vertex, triple) reached by a forward arc (vertices of more
                           than MASK_MEMBERS members) */
    uint32_t *amask;    /* ... per vertex of fewer: a bit per triple of its members */
    size_t amask_cap;
    vbx_tmap map;       /* the triples of the list */
    vb_arc_report *r;
} closure;

/* The bit of triple t among the triples of vertex k's members (sorted, t
 * a triple of them): the combinatorial rank C(c, 3) + C(b, 2) + a of its
 * positions a < b < c; -1 when k has more than MASK_MEMBERS members. */
static int triple_bit(const vb_vertex_list *all, size_t k, const uint32_t t[3])
{
    size_t s = all->start[k], nm = all->start[k + 1] - s;
    if (nm > MASK_MEMBERS)
        return -1;
    int pos[3], n = 0;
    for (size_t i = 0; i < nm && n < 3; i++)
        if (all->ids[s + i] == t[n])
            pos[n++] = (int)i;
    if (n < 3)
        return -1; /* not a triple of k: cannot be, kept in the set */
    return pos[2] * (pos[2] - 1) * (pos[2] - 2) / 6 + pos[1] * (pos[1] - 1) / 2 + pos[0];
}

/* Records that a forward arc of triple t arrived at vertex to. */
static int arrival_put(closure *cl, size_t to, const uint32_t t[3])
{
    int b = triple_bit(&cl->all, to, t);
    if (b < 0)
        return aput(&cl->arrived, to, t);
    if (to >= cl->amask_cap) {
        size_t old = cl->amask_cap;
        if (VB_ARRAY_FIT(cl->amask, cl->amask_cap, to + 1, 1024) != VB_OK)
            return VB_ENOMEM;
        memset(cl->amask + old, 0, (cl->amask_cap - old) * sizeof *cl->amask);
    }
    cl->amask[to] |= 1u << b;
    return VB_OK;
}

static int arrival_has(const closure *cl, size_t k, const uint32_t t[3])
{
    int b = triple_bit(&cl->all, k, t);
    if (b < 0)
        return cl->arrived.tab.cap && ahas(&cl->arrived, k, t);
    return k < cl->amask_cap && (cl->amask[k] >> b & 1);
}

static int push_item(vbx_item **v, size_t *n, size_t *cap, size_t k, const uint32_t t[3], int all)
{
    if (VB_ARRAY_FIT(*v, *cap, *n + 1, 256) != VB_OK)
        return VB_ENOMEM;
    vbx_item *it = &(*v)[(*n)++];
    it->k = k;
    memcpy(it->t, t, sizeof it->t);
    it->all = all;
    return VB_OK;
}

static int push_tedge(closure *cl, size_t from, size_t to, const uint32_t t[3], int kind)
{
    if (!cl->want_edges)
        return VB_OK;
    if (VB_ARRAY_FIT(cl->ed, cl->ed_cap, cl->ned + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    tedge *e = &cl->ed[cl->ned++];
    e->from = from;
    e->to = to;
    memcpy(e->t, t, sizeof e->t);
    e->kind = kind;
    return VB_OK;
}

/* ---- merging a phase's events --------------------------------------------- */

/* A run of the merge: items (or pending arcs) [i0, i1) on one thread; its
 * counts, edges and pending arcs, and the items with an event left to the
 * ordered pass (late_event). */
typedef struct mrun {
    closure *cl;
    const vbx_tphase *ph;
    size_t i0, i1;
    size_t half_arcs, closed, infinite, loops, undecided;
    tedge *ed;
    size_t ned, ed_cap;
    vbx_item *pend;
    size_t npend, pend_cap;
    size_t *late;
    size_t nlate, late_cap;
    int rc;
} mrun;

static int run_tedge(mrun *m, size_t from, size_t to, const uint32_t t[3], int kind)
{
    if (!m->cl->want_edges)
        return VB_OK;
    if (VB_ARRAY_FIT(m->ed, m->ed_cap, m->ned + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    tedge *e = &m->ed[m->ned++];
    e->from = from;
    e->to = to;
    memcpy(e->t, t, sizeof e->t);
    e->kind = kind;
    return VB_OK;
}

/* A closed half arc whose end the tracer did not find in the round's map
 * (a vertex not listed at the round's start: new, or added in this
 * round), or a forward one arriving at a vertex of more than MASK_MEMBERS
 * members (the arrivals' hash set): merged by the ordered pass alone, so
 * vertices are added in event order. */
static int late_event(const closure *cl, const vbx_hev *e)
{
    return e->kind == VBX_EV_CLOSED &&
           (e->to == SIZE_MAX || (e->dir == 0 && triple_bit(&cl->all, e->to, e->t) < 0));
}

/* The events of run r's items but the late ones: counts, edges, arrivals
 * (bits set atomically: an OR) and components (vb_uf_join_shared), all
 * free of order; pending arcs kept in item order (vb_for_fn). */
static void merge_run(void *arg, size_t r, int tid)
{
    (void)tid;
    mrun *m = (mrun *)arg + r;
    closure *cl = m->cl;
    const vbx_tphase *ph = m->ph;
    for (size_t i = m->i0; i < m->i1 && m->rc == VB_OK; i++) {
        const vbx_tracer *tr = &ph->tr[ph->who[i]];
        size_t k = ph->it[i].k;
        int late = 0, rc = VB_OK;
        for (size_t q = ph->first[i]; rc == VB_OK && q < ph->first[i] + ph->count[i]; q++) {
            const vbx_hev *e = &tr->ev[q];
            if (e->kind == VBX_EV_PENDING) {
                rc = push_item(&m->pend, &m->npend, &m->pend_cap, k, e->t, 0);
                continue;
            }
            if (late_event(cl, e)) {
                late = 1;
                continue;
            }
            m->half_arcs++;
            if (e->kind == VBX_EV_INF) {
                m->infinite++;
                rc = run_tedge(m, k, SIZE_MAX, e->t, TE_INF);
            } else if (e->kind == VBX_EV_LOOP) {
                m->loops++;
                rc = run_tedge(m, k, k, e->t, TE_LOOP);
            } else if (e->kind == VBX_EV_UNDECIDED) {
                m->undecided++;
            } else {
                size_t to = e->to;
                m->closed++;
                if (e->dir == 0)
                    __atomic_fetch_or(&cl->amask[to], 1u << triple_bit(&cl->all, to, e->t),
                                      __ATOMIC_RELAXED);
                /* a backward arc from k that ends at `to` is the edge that
                 * leaves `to` forward */
                rc = run_tedge(m, e->dir == 0 ? k : to, e->dir == 0 ? to : k, e->t,
                               e->dir == 0 ? TE_FWD : TE_BWD);
                vb_uf_join_shared(&cl->comp, (uint32_t)k, (uint32_t)to);
            }
        }
        if (rc == VB_OK && late)
            rc = VB_ARRAY_FIT(m->late, m->late_cap, m->nlate + 1, 64);
        if (rc == VB_OK && late)
            m->late[m->nlate++] = i;
        m->rc = rc;
    }
}

/* The late events of item k's vertex (tracer tr, events [e0, e0 + n)), in
 * event order: the end looked up among the added vertices and added when
 * new, then counted, its arrival, edge and component recorded. */
static int merge_late(closure *cl, const vbx_tracer *tr, size_t e0, size_t n, size_t k)
{
    vb_arc_report *r = cl->r;
    for (size_t i = e0; i < e0 + n; i++) {
        const vbx_hev *e = &tr->ev[i];
        if (!late_event(cl, e))
            continue;
        r->half_arcs++;
        const uint32_t *m = tr->pool + e->moff;
        size_t to = e->to, *s = NULL;
        if (to == SIZE_MAX) {
            if (!cl->tab.cap && vb_hash_fit(&cl->tab, 0, vhash_of, &cl->all) != VB_OK)
                return VB_ENOMEM;
            s = vslot(&cl->tab, &cl->all, m, e->nm, e->p);
        }
        if (s && *s) {
            to = *s - 1;
        } else if (s) {
            to = cl->all.n;
            int rc = vb_vertex_list_push(&cl->all, m, e->nm, e->p[0], e->p[1], e->p[2], e->p[3],
                                         0, VB_VERTEX_CERTIFIED);
            if (rc == VB_OK)
                rc = vb_vertex_list_push(&r->added, m, e->nm, e->p[0], e->p[1], e->p[2], e->p[3],
                                         0, VB_VERTEX_CERTIFIED);
            if (rc != VB_OK)
                return rc;
            if (vb_hash_put(&cl->tab, s, to, vhash_of, &cl->all) != VB_OK)
                return VB_ENOMEM;
        }
        r->closed++;
        if (e->dir == 0 && arrival_put(cl, to, e->t) != VB_OK)
            return VB_ENOMEM;
        if (push_tedge(cl, e->dir == 0 ? k : to, e->dir == 0 ? to : k, e->t,
                       e->dir == 0 ? TE_FWD : TE_BWD) != VB_OK)
            return VB_ENOMEM;
        if (vb_uf_fit(&cl->comp, cl->all.n) != VB_OK)
            return VB_ENOMEM;
        vb_uf_join(&cl->comp, (uint32_t)k, (uint32_t)to);
    }
    return VB_OK;
}

/* Runs over [0, n) in nr contiguous ranges. */
static void cut_runs(mrun *runs, unsigned nr, closure *cl, const vbx_tphase *ph, size_t n)
{
    for (unsigned r = 0; r < nr; r++) {
        memset(&runs[r], 0, sizeof runs[r]);
        runs[r].cl = cl;
        runs[r].ph = ph;
        runs[r].i0 = n * r / nr;
        runs[r].i1 = n * (r + 1) / nr;
    }
}

/* Run r's counts into the report, its edges to the closure's; frees the
 * run. VB_OK or VB_ENOMEM. */
static int fold_run(closure *cl, mrun *m)
{
    vb_arc_report *r = cl->r;
    r->half_arcs += m->half_arcs;
    r->closed += m->closed;
    r->infinite += m->infinite;
    r->loops += m->loops;
    r->undecided += m->undecided;
    int rc = m->rc;
    if (rc == VB_OK && m->ned) {
        rc = VB_ARRAY_FIT(cl->ed, cl->ed_cap, cl->ned + m->ned, 1024);
        if (rc == VB_OK) {
            memcpy(cl->ed + cl->ned, m->ed, m->ned * sizeof *m->ed);
            cl->ned += m->ned;
        }
    }
    free(m->ed);
    m->ed = NULL;
    return rc;
}

/* The events of the phase's n items merged: in *nr parallel runs (runs[],
 * VB_MAX_THREADS of them) for all that is free of order, then the late
 * events in item order; the pending arcs stay in the runs' lists (run
 * order then list order is item order: free them with free_runs). The
 * counts, the vertices added (and their order), the arrivals, components
 * and edges are those of merging every event one by one in item order. */
static int merge_phase(closure *cl, const vbx_tphase *ph, unsigned nt, mrun *runs, unsigned *nrp)
{
    size_t n = ph->n;
    unsigned nr = nt;
    if (nr > (n + 255) / 256)
        nr = (unsigned)((n + 255) / 256);
    if (nr < 1)
        nr = 1;
    /* the arrivals' bits and the components of every vertex listed now */
    if (cl->all.n > cl->amask_cap) {
        size_t old = cl->amask_cap;
        if (VB_ARRAY_FIT(cl->amask, cl->amask_cap, cl->all.n, 1024) != VB_OK)
            return VB_ENOMEM;
        memset(cl->amask + old, 0, (cl->amask_cap - old) * sizeof *cl->amask);
    }
    if (vb_uf_fit(&cl->comp, cl->all.n) != VB_OK)
        return VB_ENOMEM;
    cut_runs(runs, nr, cl, ph, n);
    *nrp = nr;
    vb_parallel_for(merge_run, runs, nr, (int)nr);
    int rc = VB_OK;
    for (unsigned r = 0; r < nr; r++) {
        int frc = fold_run(cl, &runs[r]);
        if (rc == VB_OK)
            rc = frc;
        for (size_t q = 0; rc == VB_OK && q < runs[r].nlate; q++) {
            size_t i = runs[r].late[q];
            rc = merge_late(cl, &ph->tr[ph->who[i]], ph->first[i], ph->count[i], ph->it[i].k);
        }
        free(runs[r].late);
        runs[r].late = NULL;
    }
    return rc;
}

static void free_runs(mrun *runs, unsigned nr)
{
    for (unsigned r = 0; r < nr; r++) {
        free(runs[r].ed);
        free(runs[r].pend);
        free(runs[r].late);
    }
}

/* Run r's pending arcs: those whose triple arrived at their vertex counted
 * closed, the others kept in order, in place (vb_for_fn). */
static void resolve_run(void *arg, size_t r, int tid)
{
    (void)tid;
    mrun *m = (mrun *)arg + r;
    const closure *cl = m->cl;
    size_t keep = 0;
    m->closed = 0;
    for (size_t i = 0; i < m->npend; i++) {
        const vbx_item *pi = &m->pend[i];
        if (arrival_has(cl, pi->k, pi->t))
            m->closed++;
        else
            m->pend[keep++] = *pi;
    }
    m->npend = keep;
}

/* The pending backward arcs of a round (in the runs of its forward phase):
 * each either the reverse of a forward arc that arrived at its vertex with
 * its triple (counted closed) or an item of *back, in item order, the runs
 * in parallel. */
static int resolve_pending(closure *cl, mrun *runs, unsigned nr, vbx_item **back, size_t *nback,
                           size_t *back_cap)
{
    vb_parallel_for(resolve_run, runs, nr, (int)nr);
    *nback = 0;
    for (unsigned r = 0; r < nr; r++) {
        cl->r->half_arcs += runs[r].closed;
        cl->r->closed += runs[r].closed;
        if (runs[r].npend &&
            VB_ARRAY_FIT(*back, *back_cap, *nback + runs[r].npend, 256) != VB_OK)
            return VB_ENOMEM;
        if (runs[r].npend)
            memcpy(*back + *nback, runs[r].pend, runs[r].npend * sizeof *runs[r].pend);
        *nback += runs[r].npend;
    }
    return VB_OK;
}

/* Runs the n items on the tracers and merges their events in vbx_item order. */
static int run_phase(closure *cl, vbx_tracer *tr, unsigned nt, const vbx_item *it, size_t n,
                     size_t base, size_t total, mrun *runs, unsigned *nr)
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
    atomic_init(&ph.next, 0);
    atomic_init(&ph.done, 0);
    ph.progress = total ? cl->ctx : NULL;
    ph.base = base;
    ph.total = total;
    int rc = VB_OK;
    vbx_rjob jobs[VB_MAX_THREADS];
    unsigned use = nt;
    if (use > (n + VBX_RCHUNK - 1) / VBX_RCHUNK)
        use = (unsigned)((n + VBX_RCHUNK - 1) / VBX_RCHUNK);
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
        double t0 = vb_now();
        vb_run_jobs(vbx_phase_work, jobs, sizeof *jobs, (int)use);
        cl->r->trace_s += vb_now() - t0;
        int bad = vb_jobs_first_error(tr, sizeof *tr, (int)use, offsetof(vbx_tracer, rc),
                                      offsetof(vbx_tracer, fail_at));
        if (bad >= 0) {
            rc = tr[bad].rc;
            if (bad != 0)
                vb_error(cl->ctx, rc, NULL, 0, "%s", vb_errmsg(tr[bad].ctx));
        }
    }
    double t1 = vb_now();
    if (rc == VB_OK)
        rc = merge_phase(cl, &ph, nt, runs, nr);
    cl->r->merge_s += vb_now() - t1;
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
static int run_rounds(closure *cl, vbx_tracer *tr, unsigned nt)
{
    size_t lo = 0;
    int rc = VB_OK;
    vbx_item *it = NULL, *back = NULL;
    size_t it_cap = 0, back_cap = 0;
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
        if (VB_ARRAY_FIT(it, it_cap, hi - lo, 256) != VB_OK) {
            rc = VB_ENOMEM;
            break;
        }
        for (size_t k = lo; k < hi; k++)
            it[nit++] = (vbx_item){k, {0, 0, 0}, 1};
        mrun runs[VB_MAX_THREADS];
        unsigned nr = 0;
        rc = run_phase(cl, tr, nt, it, nit, lo, hi, runs, &nr);
        double t1 = vb_now();
        if (rc == VB_OK)
            rc = resolve_pending(cl, runs, nr, &back, &nback, &back_cap);
        free_runs(runs, nr);
        cl->r->merge_s += vb_now() - t1;
        if (rc == VB_OK)
            rc = run_phase(cl, tr, nt, back, nback, 0, 0, runs, &nr);
        free_runs(runs, nr);
        lo = hi;
    }
    if (rc == VB_OK)
        vb_progress(cl->ctx, "arcs", cl->all.n, cl->all.n);
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
static int emit_edges(closure *cl, size_t nin, const size_t *where_added, unsigned nt,
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

/* The closure of list in on set; cert: an open certifier of set to borrow
 * (left open), or NULL to open one. */
static int close_list(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                      const vb_vertex_list *in, unsigned threads, vb_arc_report *out,
                      vb_topology_edge **edges, size_t *nedges)
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
    double t0 = vb_now();
    unsigned nt = (unsigned)vb_threads(threads);
    size_t most = in->n / 64 + 1;
    if (nt > most)
        nt = (unsigned)most;
    vbx_tracer *tr = calloc(nt, sizeof *tr);
    vb_certifier *c = cert;
    int rc = !tr ? VB_ENOMEM : c ? VB_OK : vb_certifier_open(ctx, set, &c);
    for (unsigned i = 0; rc == VB_OK && i < nt; i++) {
        tr[i].ctx = ctx;
        tr[i].c = c;
        if (i > 0) {
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
    if (rc == VB_OK)
        rc = vb_vertex_list_append(&cl.all, in); /* the tracers read points and members */
    if (rc == VB_OK)
        rc = vb_uf_fit(&cl.comp, cl.all.n);
    out->threads = nt;
    out->setup_s = vb_now() - t0;
    if (rc == VB_OK) {
        vb_progress(ctx, "arcs", 0, cl.all.n);
        rc = run_rounds(&cl, tr, nt);
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
    for (unsigned i = 0; tr && i < nt; i++) {
        if (tr[i].have_w)
            vbx_arcw_free(&tr[i].w);
        vbx_tracer_scratch(&tr[i], 0);
        free(tr[i].ev);
        free(tr[i].pool);
        if (i > 0) {
            vb_certifier_close(tr[i].c);
            if (tr[i].ctx)
                vb_close(tr[i].ctx);
        }
    }
    if (c != cert)
        vb_certifier_close(c);
    free(tr);
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
    return close_list(ctx, set, NULL, in, threads, out, NULL, NULL);
}

int vb_arc_close_edges(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier *cert,
                       const vb_vertex_list *in, unsigned threads, vb_arc_report *out,
                       vb_topology_edge **edges, size_t *nedges)
{
    return close_list(ctx, set, cert, in, threads, out, edges, nedges);
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
