/* Arc closure's merge (vbx_closure.h): the set of vertices the closure
 * added, the arrivals of forward arcs, and each phase's events merged into
 * the counts, the list, the components and the edges on the threads. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vb_parallel.h"
#include "vb_uf.h"

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


static uint64_t ahash(const vbx_akey *k)
{
    return vb_hash_mix(vb_hash_mix(vb_hash_mix(vb_hash_mix(0, k->to), k->t[0]), k->t[1]),
                       k->t[2]);
}

/* A pair sought in set a. */
typedef struct asame_arg {
    const vbx_aset *a;
    const vbx_akey *q;
} asame_arg;

static int asame(const void *key, size_t i)
{
    const asame_arg *x = key;
    const vbx_akey *e = &x->a->k[i];
    return e->to == x->q->to && e->t[0] == x->q->t[0] && e->t[1] == x->q->t[1] &&
           e->t[2] == x->q->t[2];
}

static uint64_t ahash_of(const void *arg, size_t i)
{
    const vbx_aset *a = arg;
    return ahash(&a->k[i]);
}

static int aput(vbx_aset *a, size_t to, const uint32_t t[3])
{
    vbx_akey q = {to, {t[0], t[1], t[2]}};
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

static int ahas(const vbx_aset *a, size_t to, const uint32_t t[3])
{
    vbx_akey q = {to, {t[0], t[1], t[2]}};
    asame_arg x = {a, &q};
    return vb_hash_get(&a->tab, ahash(&q), asame, &x) != SIZE_MAX;
}

/* The bit of triple t among the triples of vertex k's members (sorted, t
 * a triple of them): the combinatorial rank C(c, 3) + C(b, 2) + a of its
 * positions a < b < c; -1 when k has more than VBX_MASK_MEMBERS members. */
static int triple_bit(const vb_vertex_list *all, size_t k, const uint32_t t[3])
{
    size_t s = all->start[k], nm = all->start[k + 1] - s;
    if (nm > VBX_MASK_MEMBERS)
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
static int arrival_put(vbx_closure *cl, size_t to, const uint32_t t[3])
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

static int arrival_has(const vbx_closure *cl, size_t k, const uint32_t t[3])
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
    it->n = 0;
    it->all = all;
    return VB_OK;
}

/* Appends the edge (from, to, t, kind) to the array (*ed, *n, *cap) when
 * edges are wanted. VB_OK or VB_ENOMEM. */
static int add_tedge(int want, vbx_tedge **ed, size_t *n, size_t *cap, size_t from, size_t to,
                     const uint32_t t[3], int kind)
{
    if (!want)
        return VB_OK;
    if (VB_ARRAY_FIT(*ed, *cap, *n + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    vbx_tedge *e = &(*ed)[(*n)++];
    e->from = from;
    e->to = to;
    memcpy(e->t, t, sizeof e->t);
    e->kind = kind;
    return VB_OK;
}

static int push_tedge(vbx_closure *cl, size_t from, size_t to, const uint32_t t[3], int kind)
{
    return add_tedge(cl->want_edges, &cl->ed, &cl->ned, &cl->ed_cap, from, to, t, kind);
}

/* ---- merging a phase's events --------------------------------------------- */

static int run_tedge(vbx_mrun *m, size_t from, size_t to, const uint32_t t[3], int kind)
{
    return add_tedge(m->cl->want_edges, &m->ed, &m->ned, &m->ed_cap, from, to, t, kind);
}

/* A closed half arc whose end the tracer did not find in the round's map
 * (a vertex not listed at the round's start: new, or added in this
 * round), or a forward one arriving at a vertex of more than VBX_MASK_MEMBERS
 * members (the arrivals' hash set): merged by the ordered pass alone, so
 * vertices are added in event order. */
static int late_event(const vbx_closure *cl, const vbx_hev *e)
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
    vbx_mrun *m = (vbx_mrun *)arg + r;
    vbx_closure *cl = m->cl;
    const vbx_tphase *ph = m->ph;
    for (size_t i = m->i0; i < m->i1 && m->rc == VB_OK; i++) {
        const vbx_tracer *tr = &ph->tr[ph->who[i]];
        int late = 0, rc = VB_OK;
        for (size_t q = ph->first[i]; rc == VB_OK && q < ph->first[i] + ph->count[i]; q++) {
            const vbx_hev *e = &tr->ev[q];
            size_t k = e->from;
            if (e->kind == VBX_EV_PENDING) {
                rc = push_item(&m->pend, &m->npend, &m->pend_cap, k, e->t, VBX_IT_BACK);
                continue;
            }
            if (late_event(cl, e)) {
                late = 1;
                continue;
            }
            m->half_arcs++;
            if (e->kind == VBX_EV_REVERSED) {
                m->closed++;
                continue;
            }
            if (e->kind == VBX_EV_INF) {
                m->infinite++;
                rc = run_tedge(m, k, SIZE_MAX, e->t, VBX_TE_INF);
            } else if (e->kind == VBX_EV_LOOP) {
                m->loops++;
                rc = run_tedge(m, k, k, e->t, VBX_TE_LOOP);
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
                               e->dir == 0 ? VBX_TE_FWD : VBX_TE_BWD);
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

int vbx_closure_own(vbx_closure *cl)
{
    if (cl->all_owned)
        return VB_OK;
    vb_vertex_list copy;
    vb_vertex_list_init(&copy);
    if (vb_vertex_list_append(&copy, &cl->all) != VB_OK) {
        vb_vertex_list_free(&copy);
        return VB_ENOMEM;
    }
    cl->all = copy;
    cl->all_owned = 1;
    return VB_OK;
}

/* The late events of an item (tracer tr, events [e0, e0 + n)), in event
 * order: the end looked up among the added vertices and added when
 * new, then counted, its arrival, edge and component recorded. */
static int merge_late(vbx_closure *cl, const vbx_tracer *tr, size_t e0, size_t n)
{
    vb_arc_report *r = cl->r;
    for (size_t i = e0; i < e0 + n; i++) {
        const vbx_hev *e = &tr->ev[i];
        if (!late_event(cl, e))
            continue;
        size_t k = e->from;
        r->half_arcs++;
        size_t to = e->to, *s = NULL;
        const vbx_hend *x = to == SIZE_MAX ? &tr->ends[e->end] : NULL;
        const uint32_t *m = x ? tr->pool + x->moff : NULL;
        if (x) {
            if (!cl->tab.cap && vb_hash_fit(&cl->tab, 0, vhash_of, &cl->all) != VB_OK)
                return VB_ENOMEM;
            s = vslot(&cl->tab, &cl->all, m, x->nm, x->p);
        }
        if (s && *s) {
            to = *s - 1;
        } else if (s) {
            to = cl->all.n;
            int rc = vbx_closure_own(cl);
            if (rc == VB_OK)
                rc = vb_vertex_list_push(&cl->all, m, x->nm, x->p[0], x->p[1], x->p[2], x->p[3],
                                         0, VB_VERTEX_CERTIFIED);
            if (rc == VB_OK)
                rc = vb_vertex_list_push(&r->added, m, x->nm, x->p[0], x->p[1], x->p[2], x->p[3],
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
                       e->dir == 0 ? VBX_TE_FWD : VBX_TE_BWD) != VB_OK)
            return VB_ENOMEM;
        if (vb_uf_fit(&cl->comp, cl->all.n) != VB_OK)
            return VB_ENOMEM;
        vb_uf_join(&cl->comp, (uint32_t)k, (uint32_t)to);
    }
    return VB_OK;
}

/* Runs over [0, n) in nr contiguous ranges. */
static void cut_runs(vbx_mrun *runs, unsigned nr, vbx_closure *cl, const vbx_tphase *ph, size_t n)
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
static int fold_run(vbx_closure *cl, vbx_mrun *m)
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

int vbx_merge_phase(vbx_closure *cl, const vbx_tphase *ph, unsigned nt, vbx_mrun *runs,
                    unsigned *nrp)
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
            rc = merge_late(cl, &ph->tr[ph->who[i]], ph->first[i], ph->count[i]);
        }
        free(runs[r].late);
        runs[r].late = NULL;
    }
    return rc;
}

void vbx_free_runs(vbx_mrun *runs, unsigned nr)
{
    for (unsigned r = 0; r < nr; r++) {
        free(runs[r].ed);
        free(runs[r].pend);
        free(runs[r].late);
        runs[r].ed = NULL;
        runs[r].pend = NULL;
        runs[r].late = NULL;
        runs[r].ned = runs[r].npend = runs[r].nlate = 0;
        runs[r].ed_cap = runs[r].pend_cap = runs[r].late_cap = 0;
    }
}

/* Run r's pending arcs: those whose triple arrived at their vertex counted
 * closed, the others kept in order, in place (vb_for_fn). */
static void resolve_run(void *arg, size_t r, int tid)
{
    (void)tid;
    vbx_mrun *m = (vbx_mrun *)arg + r;
    const vbx_closure *cl = m->cl;
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

int vbx_resolve_pending(vbx_closure *cl, vbx_mrun *runs, unsigned nr, vbx_item **back,
                        size_t *nback, size_t *back_cap)
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

