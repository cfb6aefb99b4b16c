/* The arcs bounding an intersection of spherical caps (vbm_caps.h).
 *
 * Per cap l with a proper circle, every other cap m restricts the circle to
 * an arc (P + Qc cos t + Qs sin t >= h_m, P = c a.n_m, Qc = s e1.n_m,
 * Qs = s e2.n_m), to all of it or to nothing. The ends of the restricting
 * arcs are points of the unit circle in closed form (no angle is computed
 * exactly: cos t = g / Q, sin t = sqrt(Q^2 - g^2) / Q about the direction
 * (Qc, Qs)). They are sorted by the angles of their midpoints; two ends
 * that come next to each other closer than 3 rad are proven in that order
 * by the sign of their cross product (farther apart the order cannot be
 * wrong: every gap is wider than 4 times the widest end, an interval of at
 * most 1e-4 on the unit circle). Each cap holds the arc from its start to
 * its end, so the proven order tells which caps hold each gap between two
 * ends (counted once, then one more or one less at each end passed). The
 * gaps inside all caps are the arcs.
 *
 * Doing that for every circle against every cap costs caps^2 restrictions
 * per intersection, where only a few circles bound it (on proteins ~3 of
 * ~21). So the arcs are found against subsets of the caps and proven for
 * the rest (vbm_cap_arcs): fewer caps only add arcs, so a circle without
 * an arc inside a subset has none; and an arc inside a subset lies inside
 * another cap when that cap holds both its ends and not the one minimum of
 * the cap's function on the circle (arcs_inside). Circles the caller has
 * already solved (the bisector circles two regions of one atom share,
 * stokes_cell.c) come given: their arcs are taken as found and only the
 * others are searched. Before the search, the caps proven to hold a cap
 * around the trial intersection (cap 0 and the caps cutting most of it)
 * are rejected: they cannot touch the intersection (bound_prune). Each
 * restriction is made once per intersection and kept (restriction()).
 * vbm_cap_arcs (cap_prefilter.c) runs this search on the caps its
 * polyhedron clip cannot reject. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbm_caps.h"
#include "vbm_dot.h"

#define TWO_PI 6.283185307179586
#define MAX_ARC 2.5      /* longer arcs are split (their frames need |angle| < pi / 2) */
#define MAX_END_WIDTH 1e-4 /* an end this wide (near-tangent circles): undecided */

/* vbm_capwork.state; BAD: a cap not proven to hold the arcs of the circle
 * now done (arcs_inside), for that circle only */
enum { DONE = 1, ON_BOUNDARY = 2, QUEUED = 4, LIKELY = 8, BAD = 32, HELD = 64 };

/* Circle l's frame, made when first needed: most circles of a region only
 * restrict others (their caps) and never have a point of theirs computed
 * (or the caller gave it, vbm_cap_arcs' axes). Returns 0 when it cannot be
 * made. */
static int framed(vbm_capwork *w, size_t l)
{
    return w->circ[l].framed || vbm_circle_frame(&w->circ[l]);
}

typedef struct vbm_endpt {
    vbx_ia x, y;
    double ang;
    int start;    /* 1: entering the restricting cap (counterclockwise), 0: leaving it */
    uint32_t cap; /* the restricting cap */
    uint32_t pos; /* circle_arcs: its place counterclockwise from the widest gap */
} endpt;

typedef struct vbm_restr {
    vbx_ia P, Qc, Qs, h;
    vbx_ia g, Q2, gm, gp; /* h - P, Qc^2 + Qs^2, Q - g, Q + g (circle_arcs) */
    uint32_t cap;
} restr;


void vbm_caps_free(vbm_capwork *w)
{
    free(w->circ);
    free(w->ord);
    free(w->arc);
    free(w->sorted);
    free(w->sel);
    free(w->queue);
    free(w->state);
    free(w->bnd);
    free(w->rc);
    free(w->rslot);
    free(w->rix);
    vbm_prefilter_free(w);
    memset(w, 0, sizeof *w);
}

/* End x into ord[0..i), sorted by angle: an insertion sort as the ends
 * come, stable as the merge sort of glibc's qsort was (the same order), and
 * cheaper on the few ends of one circle; pointers to the ends where their
 * restrictions keep them move, the ends are not copied. */
static void sort_in(endpt **ord, size_t i, endpt *x)
{
    size_t k = i;
    for (; k > 0 && ord[k - 1]->ang > x->ang; k--)
        ord[k] = ord[k - 1];
    ord[k] = x;
}

static double angle_of(vbx_ia x, vbx_ia y)
{
    double t = atan2(vbx_ia_mid(y), vbx_ia_mid(x));
    return t < 0.0 ? t + TWO_PI : t;
}

static int push_arc(vbm_capwork *w, uint32_t l, const endpt *p, const endpt *q, double tq)
{
    double tp = p->ang;
    if (tq - tp > MAX_ARC) { /* split at the middle */
        endpt m = {vbx_ia_point(0.0), vbx_ia_point(0.0), 0.5 * (tp + tq), 0, VBM_NO_CAP, 0};
        vbm_unit_at(m.ang, &m.x, &m.y);
        int e = push_arc(w, l, p, &m, m.ang);
        return e < 0 ? e : push_arc(w, l, &m, q, tq);
    }
    if (VB_ARRAY_FIT(w->arc, w->cap_arc, w->narc + 1, 32) != VB_OK)
        return -1;
    vbm_arc *a = &w->arc[w->narc++];
    a->cap = l;
    a->pcap = p->cap;
    a->qcap = q->cap;
    a->p[0] = p->x;
    a->p[1] = p->y;
    a->q[0] = q->x;
    a->q[1] = q->y;
    a->tp = tp;
    a->tq = tq;
    return 0;
}

/* The restriction of circle C by a cap: inside it where P + Qc x + Qs y >= h
 * at the unit vector (x, y) of C's frame. */
static restr restrict_by(const vbm_circle *C, const vbm_cap *cap)
{
    restr r;
    r.P = vbx_ia_mul(C->c, vbm_dot3(C->a, cap->n));
    r.Qc = vbx_ia_mul(C->s, vbm_dot3(C->e1, cap->n));
    r.Qs = vbx_ia_mul(C->s, vbm_dot3(C->e2, cap->n));
    r.h = cap->h;
    return r;
}

/* 1: inside cap m at the unit vector (x, y) of the circle, -1 outside, 0
 * undecided. */
static int side(const restr *r, vbx_ia x, vbx_ia y)
{
    vbx_ia v = vbx_ia_sub(vbx_ia_add(r->P, vbx_ia_add(vbx_ia_mul(r->Qc, x), vbx_ia_mul(r->Qs, y))),
                          r->h);
    return vbx_ia_sign(v);
}

/* A restriction of circle l by cap m, kept for the intersection being
 * bounded (vbm_capwork.rc): the trial, both passes of a circle and the
 * tests of arcs against caps outside its subset ask for the same ones
 * (1crn: 262,891 made for 209,081 distinct). */
typedef struct vbm_rcache {
    restr r;
    endpt s, e;
    uint32_t l;
    uint8_t kind, ends; /* R_*; s and e made */
} rcache;

enum { R_WHOLE = 1, R_NONE, R_UNDECIDED, R_CUT };

/* Circle l's restriction by cap m: its index in w->rc, made once per
 * vbm_cap_arcs call (w->rslot[l * w->nslot + m] names it when it matches);
 * UINT32_MAX on ENOMEM. */
static uint32_t restriction(const vbm_cap *caps, vbm_capwork *w, size_t l, size_t m)
{
    uint32_t *slot = &w->rslot[l * w->nslot + m];
    if (*slot < w->nrc && w->rc[*slot].l == l && w->rc[*slot].r.cap == m)
        return *slot;
    if (VB_ARRAY_FIT(w->rc, w->cap_rc, w->nrc + 1, 64) != VB_OK)
        return UINT32_MAX;
    rcache *c = &w->rc[w->nrc];
    restr r = restrict_by(&w->circ[l], &caps[m]);
    r.g = vbx_ia_sub(r.h, r.P);
    r.Q2 = vbx_ia_add(vbx_ia_sqr(r.Qc), vbx_ia_sqr(r.Qs));
    vbx_ia Q = vbx_ia_sqrt(r.Q2);
    r.gm = vbx_ia_sub(Q, r.g);
    r.gp = vbx_ia_add(Q, r.g);
    r.cap = (uint32_t)m;
    c->r = r;
    c->l = (uint32_t)l;
    c->ends = 0;
    c->kind = r.gp.hi < 0.0   ? R_WHOLE
              : r.gm.hi < 0.0 ? R_NONE
              : !(r.gm.lo > 0.0 && r.gp.lo > 0.0 && r.Q2.lo > 0.0) ? R_UNDECIDED
                                                                    : R_CUT;
    *slot = (uint32_t)w->nrc;
    return (uint32_t)w->nrc++;
}

/* The ends of a restriction cutting its circle (c->s entering the cap,
 * c->e leaving it), kept with it. Returns 0 when one is too wide. */
static int make_ends(rcache *c)
{
    const restr *r = &c->r;
    vbx_ia rr = vbx_ia_sqrt(vbx_ia_mul(r->gm, r->gp));
    /* g and rr over Q^2 first (one division, Q2 > 0 proven) */
    vbx_ia iq = vbx_ia_div(vbx_ia_point(1.0), r->Q2);
    vbx_ia gq = vbx_ia_mul(r->g, iq), rq = vbx_ia_mul(rr, iq);
    vbx_ia cg = vbx_ia_mul(r->Qc, gq), sg = vbx_ia_mul(r->Qs, gq);
    vbx_ia cr = vbx_ia_mul(r->Qc, rq), sr = vbx_ia_mul(r->Qs, rq);
    endpt *s = &c->s, *e = &c->e;
    s->start = 1;
    e->start = 0;
    s->cap = e->cap = r->cap;
    s->x = vbx_ia_add(cg, sr);
    s->y = vbx_ia_sub(sg, cr);
    e->x = vbx_ia_sub(cg, sr);
    e->y = vbx_ia_add(cr, sg);
    for (int k = 0; k < 2; k++) {
        endpt *p = k ? e : s;
        if (!(p->x.hi - p->x.lo < MAX_END_WIDTH && p->y.hi - p->y.lo < MAX_END_WIDTH))
            return 0;
        p->ang = angle_of(p->x, p->y);
    }
    c->ends = 1;
    return 1;
}

/* The arcs of circle l inside the caps sel[0..nsel) (l itself skipped)
 * and, with keep > 0, inside the caps of the last call on circle l too:
 * its first `keep` restrictions and their ends (w->rix, w->end; w->nres
 * says how many it made) are taken as they are. With `test`, nothing is
 * pushed: returns 2 when some arc exists. Returns 1 (done, or no arc), 0
 * undecided, -1 ENOMEM. */
static int circle_arcs(const vbm_cap *caps, const uint32_t *sel, size_t nsel, vbm_capwork *w,
                       size_t l, int test, size_t keep)
{
    if (!framed(w, l))
        return 0;
    size_t nr = keep;
    int undecided = 0;
    /* every cap first: one that leaves none of the circle ends the work
     * before any cut is computed */
    for (size_t i = 0; i < nsel; i++) {
        size_t m = sel[i];
        if (m == l || w->circ[m].kind == VBM_CAP_ALL)
            continue;
        uint32_t x = restriction(caps, w, l, m);
        if (x == UINT32_MAX)
            return -1;
        const rcache *c = &w->rc[x];
        if (c->kind == R_WHOLE)
            continue; /* g < -Q: the whole circle lies in cap m */
        if (c->kind == R_NONE)
            return 1; /* g > Q: none of it */
        if (c->kind == R_UNDECIDED)
            undecided = 1;
        w->rix[nr++] = x;
    }
    if (undecided)
        return 0;
    w->nres = nr;
    /* the ends where the restrictions keep them (w->rc does not move now) */
    endpt **ord = w->ord;
    size_t ne = 0;
    for (size_t i = 0; i < nr; i++) {
        rcache *c = &w->rc[w->rix[i]];
        if (!c->ends && !make_ends(c))
            return 0;
        sort_in(ord, ne++, &c->s);
        sort_in(ord, ne++, &c->e);
    }
    if (ne == 0) { /* the whole circle: two half circles */
        if (test)
            return 2;
        endpt a = {vbx_ia_point(1.0), vbx_ia_point(0.0), 0.0, 0, VBM_NO_CAP, 0};
        endpt b = {vbx_ia_point(-1.0), vbx_ia_point(0.0), 0.5 * TWO_PI, 0, VBM_NO_CAP, 0};
        if (push_arc(w, (uint32_t)l, &a, &b, b.ang) < 0 || push_arc(w, (uint32_t)l, &b, &a, TWO_PI) < 0)
            return -1;
        return 1;
    }
    double wmax = 0.0, widest = 0.0;
    size_t ref = 0;
    for (size_t k = 0; k < ne; k++)
        wmax = vbx_max(wmax, vbx_max(ord[k]->x.hi - ord[k]->x.lo, ord[k]->y.hi - ord[k]->y.lo));
    /* indices wrap by a comparison, not `%`: a division per end in each of
     * three loops was ~1 % of the CPU (capsid, perf) */
    for (size_t k = 0; k < ne; k++) { /* the cyclic order, proven pair by pair */
        const endpt *p = ord[k], *q = ord[k + 1 < ne ? k + 1 : 0];
        double gap = (k + 1 < ne ? q->ang : q->ang + TWO_PI) - p->ang;
        if (!(gap > 4.0 * wmax + 1e-12))
            return 0;
        if (gap < 3.0) {
            vbx_ia cr = vbx_ia_sub(vbx_ia_mul(p->x, q->y), vbx_ia_mul(p->y, q->x));
            if (!(cr.lo > 0.0))
                return 0;
        }
        if (gap > widest)
            widest = gap, ref = k;
    }
    /* the caps holding the widest gap, then one more or one less at each
     * end passed (a start enters its cap, an end leaves it). Cap m holds
     * the arc from its start to its end counterclockwise, so it holds the
     * gap when, going on from the gap, its end comes before its start: a
     * consequence of the order just proven, where a sign at a point inside
     * the gap took an exact unit vector (a sine and a cosine) and an
     * interval sign per cap (3pqr, 1 thread: 4.6 M of them) */
    for (size_t k = 0, pos = ne - ref - 1; k < ne; k++, pos = pos + 1 < ne ? pos + 1 : 0)
        ord[k]->pos = (uint32_t)pos; /* (k + ne - ref - 1) mod ne */
    size_t inside = 0;
    for (size_t m = 0; m < nr; m++) {
        const rcache *c = &w->rc[w->rix[m]];
        inside += c->e.pos < c->s.pos;
    }
    for (size_t i = 0, k = ref; i < ne; i++, k = k + 1 < ne ? k + 1 : 0) { /* k = ref + i mod ne */
        const endpt *p = ord[k], *q = ord[k + 1 < ne ? k + 1 : 0];
        if (i > 0)
            inside = p->start ? inside + 1 : inside - 1;
        double tq = k + 1 < ne ? q->ang : q->ang + TWO_PI;
        if (inside == nr && test)
            return 2;
        if (inside == nr && push_arc(w, (uint32_t)l, p, q, tq) < 0)
            return -1;
    }
    return 1;
}

/* Queues cap m's circle (once). */
static void enqueue(vbm_capwork *w, uint32_t m, size_t *nq)
{
    if (m != VBM_NO_CAP && !(w->state[m] & (DONE | QUEUED))) {
        w->state[m] |= QUEUED;
        w->queue[(*nq)++] = m;
    }
}

/* The arcs back in the order of their circles (each circle's arcs stay in
 * the order found): the same list whatever order the circles were done in. */
static int order_arcs(vbm_capwork *w, size_t ncap)
{
    if (VB_ARRAY_FIT(w->sorted, w->cap_sorted, w->narc + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(w->sel, w->cap_sel, ncap + 1, 32) != VB_OK)
        return -1;
    uint32_t *at = w->sel; /* first slot of each circle's arcs */
    memset(at, 0, (ncap + 1) * sizeof *at);
    for (size_t i = 0; i < w->narc; i++)
        at[w->arc[i].cap + 1]++;
    for (size_t l = 0; l < ncap; l++)
        at[l + 1] += at[l];
    for (size_t i = 0; i < w->narc; i++)
        w->sorted[at[w->arc[i].cap]++] = w->arc[i];
    vbm_arc *t = w->arc;
    size_t c = w->cap_arc;
    w->arc = w->sorted;
    w->cap_arc = w->cap_sorted;
    w->sorted = t;
    w->cap_sorted = c;
    return 1;
}

#define NLIKELY 4 /* caps tried first: those cutting most of cap 0 */

/* How far cap m's circle keeps from cap 0's axis, theta - alpha (theta
 * the angle between the axes, alpha m's angular radius, on midpoints):
 * the larger, the more of cap 0 it cuts off. Only an order of trial,
 * decides nothing: a pseudo-angle increasing with theta - alpha over
 * [-pi, pi] from its cosine and sine (two square roots where two acos
 * were 1.7 % of 3pqr's CPU). */
static double cut_score(const vbm_capwork *w, size_t m)
{
    const vbm_circle *a = &w->circ[0], *b = &w->circ[m];
    double d = 0.0;
    for (int k = 0; k < 3; k++)
        d += vbx_ia_mid(a->a[k]) * vbx_ia_mid(b->a[k]);
    double c = vbx_ia_mid(b->c);
    d = d > 1.0 ? 1.0 : d < -1.0 ? -1.0 : d;
    c = c > 1.0 ? 1.0 : c < -1.0 ? -1.0 : c;
    double sd = sqrt(1.0 - d * d), sc = sqrt(1.0 - c * c);
    double cs = d * c + sd * sc, sn = sd * c - d * sc;
    return sn >= 0.0 ? 1.0 - cs : cs - 1.0;
}

/* The intersection S of cap 0 with the NLIKELY caps that cut most of it:
 * no arc on any of their circles inside the others proves it (and so the
 * intersection of every cap) empty: returns 2. Otherwise leaves S's arcs
 * in w->arc from the count it had (*whole = 1 when they are all there, for
 * bound_prune), queues the circles with an arc there (likely on the
 * boundary) or undecided, marks done those without (none inside all caps
 * either) and returns 1; -1 on ENOMEM. */
static int likely_boundary(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t *nq,
                           int *whole)
{
    *whole = 0;
    if (w->circ[0].kind != VBM_CAP_CIRCLE || ncap <= 2)
        return 1;
    uint32_t s[NLIKELY + 1] = {0};
    double sc[NLIKELY + 1] = {0.0};
    size_t ns = 0;
    for (size_t m = 1; m < ncap; m++) { /* the NLIKELY best, by insertion */
        if (w->circ[m].kind != VBM_CAP_CIRCLE)
            continue;
        double x = cut_score(w, m);
        size_t k = ns < NLIKELY ? ns++ : NLIKELY;
        for (; k > 0 && sc[k - 1] < x; k--) {
            if (k < NLIKELY) {
                sc[k] = sc[k - 1];
                s[k] = s[k - 1];
            }
        }
        if (k < NLIKELY) {
            sc[k] = x;
            s[k] = (uint32_t)m;
        }
    }
    for (size_t i = 0; i < ns; i++)
        w->state[s[i]] |= LIKELY;
    s[ns++] = 0;
    int empty = 1;
    *whole = 1;
    for (size_t i = 0; i < ns; i++) {
        size_t before = w->narc;
        int e = circle_arcs(caps, s, ns, w, s[i], 0, 0);
        if (e < 0)
            return e;
        if (e == 0) /* undecided: maybe arcs, and S's are not all known */
            *whole = 0;
        if (e == 0 || w->narc > before) {
            empty = 0;
            enqueue(w, s[i], nq);
        } else if (s[i] != 0)
            w->state[s[i]] |= DONE; /* no arc inside these caps: none at all */
    }
    return empty ? 2 : 1;
}

/* Whether every cap outside the subset (cap 0, the likely and the boundary
 * caps) holds the arcs w->arc[first..narc) of circle l, all shorter than
 * pi: P + Qc cos t + Qs sin t - h is P - h + Q cos(t - phi), whose one
 * minimum on the circle lies at the direction -(Qc, Qs); on an arc not
 * holding that direction its minimum is at an end. So a cap holding the
 * whole circle, or both ends of each arc with the direction proven
 * outside it, holds the arcs. Every cap not proven to hold them is marked
 * BAD (it joins the subset for circle l, not for the circles after it:
 * 3pqr, 1 thread, 5.45 -> 5.23 s of CPU against marking them likely for
 * the rest of the region); returns how many were. */
#define NBOUND 8 /* arcs of one circle given bounding caps (more: none) */

/* Rejects the caps that cannot touch the intersection: S (cap 0 and the
 * likely caps, likely_boundary) has the arcs w->arc[first..narc); a cap B
 * holding them and not -a_0 (vbm_arcs_cap) holds S, since -a_0 lies
 * outside cap 0. Every other cap holding B in its interior (vbm_cap_holds)
 * holds the intersection, which S contains, away from its circle: that
 * cap changes nothing and its circle bounds nothing, so it is marked done
 * and HELD (no circle of it searched, no arc checked against it). The
 * incremental diagram's proven rejection of the neighbours that cannot
 * touch a region, with S as the region so far (3pqr, 1 thread: 24 % of
 * the caps; 4.31 -> 4.07 s of CPU). */
static void bound_prune(vbm_capwork *w, size_t ncap, size_t first)
{
    vbx_ia M[3], P[3]; /* P = -a_0 */
    double cr;
    for (int k = 0; k < 3; k++)
        P[k] = vbx_ia_neg(w->circ[0].a[k]);
    if (w->circ[0].kind != VBM_CAP_CIRCLE ||
        VB_ARRAY_FIT(w->bnd, w->cap_bnd, 4 * (w->narc - first) + 1, 32) != VB_OK ||
        !vbm_arcs_cap(w->circ, w->arc + first, w->narc - first, P, w->bnd, M, &cr))
        return; /* no prune: the search does without it */
    vbx_ia sr = vbm_cap_sine(cr);
    for (size_t m = 1; m < ncap; m++)
        if (w->circ[m].kind == VBM_CAP_CIRCLE && !(w->state[m] & (ON_BOUNDARY | LIKELY)) &&
            vbm_cap_holds(&w->circ[m], M, cr, sr))
            w->state[m] |= DONE | HELD;
}

static size_t arcs_inside(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t l,
                          size_t first)
{
    const vbm_circle *C = &w->circ[l];
    size_t bad = 0, nbound = w->narc - first;
    /* first a cheap sufficient test: cap m holds a cap around each arc
     * (one dot product per arc, where the test below restricts the circle
     * by cap m and checks both ends: 3pqr, 1 thread, 4.78 -> 4.55 s of
     * CPU) */
    vbx_ia M[NBOUND][3], sr[NBOUND];
    double cr[NBOUND];
    if (nbound > NBOUND)
        nbound = 0;
    for (size_t i = 0; i < nbound; i++) {
        if (!vbm_arc_bound(C, &w->arc[first + i], M[i], &cr[i]))
            nbound = 0;
        else
            sr[i] = vbm_cap_sine(cr[i]);
    }
    for (size_t m = 1; m < ncap; m++) {
        if (m == l || w->circ[m].kind == VBM_CAP_ALL || (w->state[m] & (ON_BOUNDARY | LIKELY | BAD | HELD)))
            continue;
        size_t held = 0;
        while (held < nbound && vbm_cap_holds(&w->circ[m], M[held], cr[held], sr[held]))
            held++;
        if (nbound && held == nbound)
            continue;
        uint32_t x = restriction(caps, w, l, m); /* ENOMEM: BAD, and circle_arcs tells */
        if (x != UINT32_MAX && w->rc[x].r.gp.hi < 0.0)
            continue; /* the whole circle */
        const restr *r = x != UINT32_MAX ? &w->rc[x].r : NULL;
        vbx_ia dx = r ? vbx_ia_neg(r->Qc) : vbx_ia_point(0.0), dy = r ? vbx_ia_neg(r->Qs) : dx;
        for (size_t i = first; i < w->narc; i++) {
            const vbm_arc *a = &w->arc[i];
            vbx_ia c0 = vbx_ia_sub(vbx_ia_mul(a->p[0], dy), vbx_ia_mul(a->p[1], dx));
            vbx_ia c1 = vbx_ia_sub(vbx_ia_mul(dx, a->q[1]), vbx_ia_mul(dy, a->q[0]));
            if (!r || side(r, a->p[0], a->p[1]) <= 0 || side(r, a->q[0], a->q[1]) <= 0 ||
                !(c0.hi < 0.0 || c1.hi < 0.0)) {
                w->state[m] |= BAD;
                bad++;
                break;
            }
        }
    }
    return bad;
}

/* The arcs of circle l: inside the subset of caps first (cap 0, the
 * boundary's and the likely ones), then, unless every other cap is proven
 * to hold them (arcs_inside), inside the subset with the caps not proven
 * added (the subset's restrictions kept, only the added caps' made).
 * Those arcs are the arcs inside every cap: each lies in the first arcs
 * (more caps only remove points), which every cap left out holds. Where
 * the intervals cannot decide inside a subset, against every cap. */
static int circle_all(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t l)
{
    uint32_t *sel = w->sel;
    size_t first = w->narc;
    for (size_t m = 0; m < ncap; m++)
        w->state[m] &= (uint8_t)~BAD;
    size_t keep = 0;
    for (int t = 0; t < 2; t++) {
        size_t ns = 0;
        for (size_t m = 0; m < ncap; m++)
            if (t == 0 ? m == 0 || (w->state[m] & (ON_BOUNDARY | LIKELY)) : (w->state[m] & BAD))
                sel[ns++] = (uint32_t)m;
        int e = circle_arcs(caps, sel, ns, w, l, 0, keep);
        if (e < 0 || (e > 0 && (t == 1 || ns >= ncap)))
            return e;
        if (e == 0)
            break; /* undecided: every cap, of which one may exclude the circle */
        if (w->narc == first || arcs_inside(caps, ncap, w, l, first) == 0)
            return 1; /* none inside the subset, or all of them inside every cap */
        w->narc = first;
        keep = w->nres; /* the subset's restrictions stay: only the caps added are cut */
    }
    w->narc = first;
    for (size_t m = 0; m < ncap; m++)
        sel[m] = (uint32_t)m;
    return circle_arcs(caps, sel, ncap, w, l, 0, 0);
}

/* The given arcs of the known circles first in w->arc, each known circle
 * done (on the boundary when it has an arc), the caps ending its arcs
 * queued, its frame made. Returns the boundary circles so marked, SIZE_MAX
 * on ENOMEM, SIZE_MAX - 1 when a frame cannot be made. */
static size_t take_given(size_t ncap, const uint8_t *known, const vbm_arc *given, size_t ngiven,
                         vbm_capwork *w, size_t *nq)
{
    size_t nb = 0;
    for (size_t m = 0; known && m < ncap; m++)
        if (known[m])
            w->state[m] |= DONE;
    if (VB_ARRAY_FIT(w->arc, w->cap_arc, ngiven + 1, 32) != VB_OK)
        return SIZE_MAX;
    for (size_t i = 0; i < ngiven; i++) {
        if (!framed(w, given[i].cap))
            return SIZE_MAX - 1;
        w->arc[w->narc++] = given[i];
        if (!(w->state[given[i].cap] & ON_BOUNDARY)) {
            w->state[given[i].cap] |= ON_BOUNDARY;
            nb++;
        }
    }
    for (size_t i = 0; i < ngiven; i++) {
        enqueue(w, given[i].pcap, nq);
        enqueue(w, given[i].qcap, nq);
    }
    return nb;
}

int vbm_cap_arcs_all(const vbm_cap *caps, const vbm_circle *axes, size_t ncap,
                     const uint8_t *known, const vbm_arc *given, size_t ngiven, vbm_capwork *w)
{
    w->narc = 0;
    if (VB_ARRAY_FIT(w->circ, w->cap_circ, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(w->ord, w->cap_ord, 2 * ncap, 64) != VB_OK ||
        VB_ARRAY_FIT(w->sel, w->cap_sel, ncap + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(w->queue, w->cap_queue, ncap + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(w->state, w->cap_state, ncap + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(w->rix, w->cap_rix, ncap + 1, 32) != VB_OK)
        return -1;
    size_t had = w->cap_rslot;
    if (VB_ARRAY_FIT(w->rslot, w->cap_rslot, ncap * ncap + 1, 256) != VB_OK)
        return -1;
    if (w->cap_rslot != had) /* restriction() reads a slot before it is set */
        memset(w->rslot, 0, w->cap_rslot * sizeof *w->rslot);
    w->nslot = ncap;
    w->nrc = 0;
    w->ncirc = 0;
    for (size_t l = 0; l < ncap; l++) {
        if (axes)
            w->circ[l] = axes[l];
        if (axes ? axes[l].kind == 0 : !vbm_circle_axis(&caps[l], &w->circ[l]))
            return 0; /* frames are made when needed (framed) */
        if (w->circ[l].kind == VBM_CAP_NONE)
            return 1; /* empty intersection */
    }
    w->ncirc = ncap;
    /* The circles along the boundary first (cap 0's, then those whose caps
     * end an arc found), each inside every cap; then every other circle is
     * tried against the boundary's caps alone (and cap 0): no arc inside
     * those proves none inside them all (more caps only remove arcs), and
     * only a circle with an arc there is done against every cap. The arcs
     * are those of doing each circle against every cap. */
    uint32_t *sel = w->sel, *queue = w->queue;
    memset(w->state, 0, ncap);
    size_t nq = 0, head = 0, next = 0;
    enqueue(w, 0, &nq);
    size_t nb = take_given(ncap, known, given, ngiven, w, &nq);
    if (nb >= SIZE_MAX - 1)
        return nb == SIZE_MAX ? -1 : 0;
    /* with an arc given the intersection is not empty: no trial of it */
    size_t trial = w->narc;
    int whole;
    int e = likely_boundary(caps, ncap, w, &nq, &whole);
    if (e < 0)
        return e;
    if (e == 2) /* empty; with an arc given, a contradiction: to the patches */
        return ngiven ? 0 : 1;
    if (whole)
        bound_prune(w, ncap, trial);
    w->narc = trial; /* S's arcs: found again inside every cap */
    for (;;) {
        size_t l;
        int from_queue = head < nq;
        if (from_queue)
            l = queue[head++];
        else {
            while (next < ncap && (w->state[next] & DONE))
                next++;
            if (next == ncap)
                break;
            l = next;
        }
        w->state[l] |= DONE;
        if (w->circ[l].kind != VBM_CAP_CIRCLE)
            continue;
        if (!from_queue && nb > 0) {
            size_t ns = 0;
            if (!(w->state[0] & ON_BOUNDARY))
                sel[ns++] = 0;
            for (size_t m = 0; m < ncap; m++) /* in cap order: the same decisions each time */
                if (w->state[m] & ON_BOUNDARY)
                    sel[ns++] = (uint32_t)m;
            e = circle_arcs(caps, sel, ns, w, l, 1, 0);
            if (e < 0)
                return e;
            if (e == 1)
                continue; /* no arc even inside the boundary's caps */
        }
        size_t first = w->narc;
        e = circle_all(caps, ncap, w, l);
        if (e <= 0)
            return e;
        if (w->narc > first && !(w->state[l] & ON_BOUNDARY)) {
            w->state[l] |= ON_BOUNDARY;
            nb++;
        }
        for (size_t i = first; i < w->narc; i++) {
            enqueue(w, w->arc[i].pcap, &nq);
            enqueue(w, w->arc[i].qcap, &nq);
        }
    }
    return order_arcs(w, ncap);
}
