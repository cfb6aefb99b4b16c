/* Internals of the closure loop (arc_closure.c), its tracers
 * (arc_tracer.c) and its merge (arc_merge.c): the vertices of each triple,
 * what one half arc found, a thread's tracer, the phases of a round and the
 * closure's state. */
#ifndef VBX_CLOSURE_H
#define VBX_CLOSURE_H

#include <stdatomic.h>

#include "vb_hash.h"
#include "vb_uf.h"
#include "vb_vertex.h"

#include "vb_arc.h"
#include "vbx_arc.h"

/* The rounded point (x, y, z, t) of vertex k of a list. */
static inline void vbx_vertex_point(const vb_vertex_list *v, size_t k, double p[4])
{
    p[0] = v->x[k];
    p[1] = v->y[k];
    p[2] = v->z[k];
    p[3] = v->t[k];
}

/* ---- the vertices of each triple (arc_triples.c) -------------------------- */

/* (triple, vertex) for every triple of every vertex of the list, sorted:
 * where a forward arc is likely to end (the next vertex along a triple's
 * curve is one that holds the triple). */
typedef struct vbx_tent {
    uint32_t t[3];
    uint32_t k;
} vbx_tent;

typedef struct vbx_tmap {
    vbx_tent *e;
    size_t n, cap;
    size_t *off; /* entries of first sphere i: [off[i], off[i + 1]), i < noff */
    size_t noff;
} vbx_tmap;

/* Builds the map of every vertex of all anew (on nt threads, the same
 * array on any number). VB_OK, VB_ENOMEM (the map is then emptied). A
 * map that lacks vertices costs searches, never a wrong end: the bounded
 * search of the tracer proves its end whichever listed vertex it is given
 * (a nearer vertex is found inside). */
int vbx_tmap_update(vbx_tmap *m, const vb_vertex_list *all, unsigned nt);

/* The entries of triple t: [*lo, *hi). */
void vbx_tmap_range(const vbx_tmap *m, const uint32_t t[3], size_t *lo, size_t *hi);

/* The vertex of the map's list all that holds triple t and has members
 * ids[0..nm) and rounded point p (compared exactly, as the closure's table
 * does), or SIZE_MAX when the map has none. */
size_t vbx_tmap_find(const vbx_tmap *m, const vb_vertex_list *all, const uint32_t t[3],
                     const uint32_t *ids, size_t nm, const double p[4]);

/* ---- tracing (arc_tracer.c) ---------------------------------------------- */

/* What one half arc found: its end, and for a vertex that the round's map
 * does not hold its members and rounded point (vbx_hend, the only ones the
 * merge reads: vbx_merge_phase's late events); VBX_EV_PENDING: a backward arc left for
 * later (see run_rounds in arc_closure.c); VBX_EV_REVERSED: a backward arc
 * that is the reverse of a forward arc of its triple traced to its vertex
 * in the same item (closed without a search, as run_rounds closes a
 * pending one that such an arc reached). */
enum {
    VBX_EV_CLOSED = 0,
    VBX_EV_INF = 1,
    VBX_EV_LOOP = 2,
    VBX_EV_UNDECIDED = 3,
    VBX_EV_PENDING = 4,
    VBX_EV_REVERSED = 5
};

typedef struct vbx_hev {
    size_t from; /* the vertex the half arc leaves */
    size_t to;   /* VBX_EV_CLOSED: the end's index in the list when the tracer
                    found it there (vbx_tmap_find), else SIZE_MAX */
    size_t end;  /* VBX_EV_CLOSED with to == SIZE_MAX: its vbx_hend in the
                    tracer's ends */
    uint32_t t[3];
    unsigned char kind, dir;
} vbx_hev;

/* The end of a closed half arc that the round's map does not hold: its
 * rounded point and its members (nm of them from moff in the tracer's
 * pool). */
typedef struct vbx_hend {
    double p[4];
    size_t moff;
    size_t nm;
} vbx_hend;

/* One thread's tracer: its certifier, context and worker, and the events of
 * the items it traced in the current phase. Aligned to a cache line (and so
 * a whole number of lines long): the tracers lie side by side in one array,
 * and a tracer writes its last fields (glo, ng) for every item while the
 * next thread's tracer reads its first ones (map, c) in every operation. */
typedef struct vbx_tracer {
    _Alignas(64) const vbx_tmap *map; /* the list's triples (NULL: no shortcut) */
    vb_ctx *ctx;
    vb_certifier *c;
    vbx_arcw w;
    int have_w;
    vbx_hev *ev;
    size_t nev, ev_cap;
    vbx_hend *ends;
    size_t nends, ends_cap;
    uint32_t *pool;
    size_t npool, pool_cap;
    int rc;
    size_t fail_at; /* the first item (in the phase) whose tracing failed */
    double busy;    /* CPU seconds spent in phases (vbx_phase_work), summed */
    /* scratch of one triple's tracing, initialised once (vbx_tracer_scratch) */
    vbx_tframe f;
    vbx_xpt x, xu;
    vbx_touch tp;
    int have_scratch;
    size_t from; /* the vertex being traced (vbx_hev.from) */
    /* a VBX_IT_TRIPLE item's vertices (map entries [glo, glo + ng)): their
     * keys on the item's frame and the enclosures of their points (4
     * each), computed once (trace_group) */
    vbx_key *gkey;
    vbx_ia *gbox, *gtau;   /* 4 per vertex of the group: its box, and the tangent there */
    size_t glo, ng, gkey_cap, gbox_cap, gtau_cap;
    /* NULL, or per vertex of the list: 1 where a VBX_IT_TRIPLE item leaves
     * the vertex untraced (its arcs were traced early: arc_early.c); it
     * still bounds the others' searches */
    const unsigned char *skip;
} vbx_tracer;

/* nt tracers at their alignment inside one zeroed block (*block, to free
 * with vbx_tracers_free), each with its arc worker and scratch: tracer 0
 * on ctx and c themselves when lend0, every other one (all of them when
 * !lend0) on a worker context of ctx and a worker of c. *tr is NULL only
 * when the block could not be allocated. VB_OK or VB_ENOMEM (what was
 * opened is then still freed by vbx_tracers_free). */
int vbx_tracers_open(vb_ctx *ctx, vb_certifier *c, unsigned nt, int lend0, char **block,
                     vbx_tracer **tr);

/* Frees what vbx_tracers_open(..., lend0, block, tr) opened (tr may be
 * NULL). */
void vbx_tracers_free(char *block, vbx_tracer *tr, unsigned nt, int lend0);

/* Initialises (on) or clears (!on) tracer t's scratch. */
void vbx_tracer_scratch(vbx_tracer *t, int on);

/* An item of a phase: every triple of vertex k (all = VBX_IT_VERTEX:
 * forward arcs traced, backward ones left pending), the backward arc of
 * triple t at vertex k alone (VBX_IT_BACK), or a triple of the round's map
 * at every vertex that holds it (VBX_IT_TRIPLE: its n entries from map
 * entry k on, in map order; as VBX_IT_VERTEX for that triple at each, the
 * triple's frame set up once). */
enum { VBX_IT_BACK = 0, VBX_IT_VERTEX = 1, VBX_IT_TRIPLE = 2 };

typedef struct vbx_item {
    size_t k;
    uint32_t t[3];
    uint32_t n;
    int all;
} vbx_item;

/* The items of the round's map m: one VBX_IT_TRIPLE per triple, in map
 * order (found on nt threads) into *it (*n of them, *cap allocated). VB_OK
 * or VB_ENOMEM. */
int vbx_tmap_items(const vbx_tmap *m, unsigned nt, vbx_item **it, size_t *n, size_t *cap);

/* A phase: items taken in chunks by the tracers; each item's events stay
 * in the tracer that traced it (who, first, count). */
typedef struct vbx_tphase {
    vbx_tracer *tr;
    const vb_vertex_list *all;
    const vbx_item *it;
    size_t n;
    size_t *first;      /* per item: first event */
    uint32_t *count;    /* ... number of events */
    uint16_t *who;      /* ... the tracer that holds them */
    atomic_size_t next; /* next chunk */
    vb_ctx *progress;   /* NULL, or where "arcs" progress goes: base + span *
                           items done / n */
    size_t base, span, total; /* of total (vb_progress) */
    atomic_size_t done; /* items traced so far */
} vbx_tphase;

/* Items a tracer takes at a time. */
enum { VBX_RCHUNK = 8 };

/* Runs phase ph (its items, tracers ph->tr: their status reset, their
 * events emptied unless keep_events, else appended to) on up to nt
 * threads (vbx_phase_work). Returns the index of the tracer with the
 * first failure (vb_jobs_first_error), or -1. */
int vbx_phase_run(vbx_tphase *ph, unsigned nt, int keep_events);

/* The end (members m, nm of them, and rounded point p) of event ev
 * appended to tracer t's ends (ev->end; ev->to = SIZE_MAX). VB_OK or
 * VB_ENOMEM. */
int vbx_keep_end(vbx_tracer *t, vbx_hev *ev, const uint32_t *m, size_t nm, const double p[4]);

/* The job of one thread of a phase (vb_run_jobs). */
typedef struct vbx_rjob {
    vbx_tphase *ph;
    unsigned index;
} vbx_rjob;

/* A thread of a phase (arg: a vbx_rjob): chunks of items in turn, each
 * item's events appended to the job's tracer; stops at the first failure
 * (the tracer's rc and fail_at). Each item's events are a function of that
 * item alone, so which thread traced it does not matter. */
void *vbx_phase_work(void *arg);

/* ---- the closure's state (arc_closure.c) and its merge (arc_merge.c) ----- */

/* Arrivals: (vertex, triple) pairs reached by a forward arc. */
typedef struct vbx_akey {
    size_t to;
    uint32_t t[3];
} vbx_akey;

/* The pairs in order of arrival and the table of them. */
typedef struct vbx_aset {
    vbx_akey *k;
    size_t n, cap;
    vb_hash tab;
} vbx_aset;

/* Vertices of at most this many members keep their arrivals as bits. */
enum { VBX_MASK_MEMBERS = 6 };

/* A traced edge (vb_arc_close_edges), oriented forward along its curve:
 * from its start to its end (vertex indices of closure.all), with the kind
 * of half arc that recorded it. */
enum { VBX_TE_FWD = 0, VBX_TE_BWD = 1, VBX_TE_INF = 2, VBX_TE_LOOP = 3 };

typedef struct vbx_tedge {
    size_t from, to; /* to: SIZE_MAX for infinity */
    uint32_t t[3];
    int kind;
} vbx_tedge;

/* The closure of one list: what the rounds built so far. */
typedef struct vbx_closure {
    vb_ctx *ctx;
    vbx_tedge *ed;      /* NULL unless edges are wanted */
    size_t ned, ed_cap;
    int want_edges;
    vb_vertex_list all; /* input + added, in tracing order: the input's arrays
                           themselves until a vertex is added (all_owned 0), a copy
                           from then on (vbx_closure_own) */
    int all_owned;
    vb_hash tab;        /* the vertices added to all (the input's are found through
                           the map: vbx_tmap_find) */
    vb_uf comp;         /* components of the vertex-edge graph */
    vbx_aset arrived;   /* (vertex, triple) reached by a forward arc (vertices of more
                           than VBX_MASK_MEMBERS members) */
    uint32_t *amask;    /* ... per vertex of fewer: a bit per triple of its members */
    size_t amask_cap;
    vbx_tmap map;       /* the triples of the list */
    vb_arc_report *r;
} vbx_closure;

/* Makes cl->all a list of the closure's own (a copy of the input it was
 * lent) before a vertex is added to it. VB_OK or VB_ENOMEM. */
int vbx_closure_own(vbx_closure *cl);

/* A run of the merge: items (or pending arcs) [i0, i1) on one thread; its
 * counts, edges and pending arcs, and the items with an event left to the
 * ordered pass (late_event). */
typedef struct vbx_mrun {
    vbx_closure *cl;
    const vbx_tphase *ph;
    size_t i0, i1;
    size_t half_arcs, closed, infinite, loops, undecided;
    vbx_tedge *ed;
    size_t ned, ed_cap;
    vbx_item *pend;
    size_t npend, pend_cap;
    size_t *late;
    size_t nlate, late_cap;
    int rc;
} vbx_mrun;

/* The events of the phase's n items merged: in *nr parallel runs (runs[],
 * VB_MAX_THREADS of them) for all that is free of order, then the late
 * events in item order; the pending arcs stay in the runs' lists (run
 * order then list order is item order: free them with vbx_free_runs). The
 * counts, the vertices added (and their order), the arrivals, components
 * and edges are those of merging every event one by one in item order.
 * VB_OK or VB_ENOMEM. */
int vbx_merge_phase(vbx_closure *cl, const vbx_tphase *ph, unsigned nt, vbx_mrun *runs,
                    unsigned *nr);

/* The pending backward arcs of a round (in the runs of its forward phase):
 * each either the reverse of a forward arc that arrived at its vertex with
 * its triple (counted closed) or an item of *back, in item order, the runs
 * in parallel. VB_OK or VB_ENOMEM. */
int vbx_resolve_pending(vbx_closure *cl, vbx_mrun *runs, unsigned nr, vbx_item **back,
                        size_t *nback, size_t *back_cap);

/* ---- early tracing (arc_early.c) ---------------------------------------- */

/* One part traced early: its vertices (a copy) and its phase's items,
 * whose events stay in the early tracers (who, first, count; indices of
 * the part's list). */
typedef struct vbx_epart {
    vb_vertex_list v;
    size_t nit;
    size_t *first;
    uint32_t *count;
    uint16_t *who;
} vbx_epart;

struct vb_arc_early {
    vb_ctx *owner;
    unsigned nt;
    char *block;
    vbx_tracer *tr; /* every one on workers of the lent certifier */
    vbx_tmap map;   /* of the part in work */
    vbx_item *it;
    size_t it_cap;
    vbx_epart *parts;
    size_t nparts, cap;
    double wall_s;
};

/* The early events that the closure takes for the first round of the
 * list cl->all (whose map cl->map is built): a phase of their own (one
 * holder, tr; items in the parts' order) with every index one of cl->all,
 * the ends not in cl->all as vbx_hend (late events), and done[k] = 1 for
 * each vertex of cl->all whose arcs they hold (the first part that traced
 * it, none of its half arcs undecided). */
typedef struct vbx_eset {
    vbx_tracer *tr; /* ev, ends, pool only */
    char *block;
    size_t n;
    size_t *first;
    uint32_t *count;
    uint16_t *who;
    unsigned char *done;
} vbx_eset;

/* Fills *s from early for cl (cl->map built on cl->all); the counts of
 * early work go to cl->r. VB_OK or VB_ENOMEM. */
int vbx_early_take(vbx_closure *cl, const vb_arc_early *early, unsigned nt, vbx_eset *s);

void vbx_eset_free(vbx_eset *s);

/* Frees what runs[0 .. nr) hold; they hold nothing then (a second call
 * frees nothing). */
void vbx_free_runs(vbx_mrun *runs, unsigned nr);

#endif
