/* One circle's arcs inside a set of caps (vbm_caps_circle.h), the step
 * of the searches over an intersection of spherical caps (cap_search.c).
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
 * An arc inside a subset of the caps lies inside another cap when that
 * cap holds both its ends and not the one minimum of the cap's function
 * on the circle (vbm_arcs_inside). Each restriction is made once per
 * intersection and kept (restriction()). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbm_caps_circle.h"
#include "vbm_dot.h"

#define TWO_PI 6.283185307179586
#define MAX_ARC 2.5      /* longer arcs are split (their frames need |angle| < pi / 2) */
#define MAX_END_WIDTH 1e-4 /* an end this wide (near-tangent circles): undecided */


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

int vbm_circle_arcs(const vbm_cap *caps, const uint32_t *sel, size_t nsel, vbm_capwork *w,
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

/* vbm_arcs_inside (vbm_caps_circle.h): whether every cap not marked
 * `skip` (the subset the arcs were found in) holds the arcs
 * w->arc[first..narc) of circle l, all shorter than pi: P + Qc cos t + Qs sin t - h is P - h + Q cos(t - phi), whose one
 * minimum on the circle lies at the direction -(Qc, Qs); on an arc not
 * holding that direction its minimum is at an end. So a cap holding the
 * whole circle, or both ends of each arc with the direction proven
 * outside it, holds the arcs. Every cap not proven to hold them is marked
 * BAD (it joins the subset for circle l, not for the circles after it:
 * 3pqr, 1 thread, 5.45 -> 5.23 s of CPU against marking them likely for
 * the rest of the region); returns how many were. */
#define NBOUND 8 /* arcs of one circle given bounding caps (more: none) */

size_t vbm_arcs_inside(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t l,
                       size_t first, uint8_t skip)
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
        if (m == l || w->circ[m].kind == VBM_CAP_ALL || (w->state[m] & skip))
            continue;
        size_t held = 0;
        while (held < nbound && vbm_cap_holds(&w->circ[m], M[held], cr[held], sr[held]))
            held++;
        if (nbound && held == nbound)
            continue;
        uint32_t x = restriction(caps, w, l, m); /* ENOMEM: BAD, and vbm_circle_arcs tells */
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
