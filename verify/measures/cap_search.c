/* The searches over an intersection of spherical caps (vbm_caps.h): which
 * circles bound it and their arcs, each circle's found by
 * vbm_circle_arcs (cap_arcs.c) against a subset of the caps and proven
 * for the rest.
 *
 * Doing every circle against every cap costs caps^2 restrictions per
 * intersection, where only a few circles bound it (on proteins ~3 of
 * ~21). So the arcs are found against subsets of the caps and proven for
 * the rest: fewer caps only add arcs, so a circle without an arc inside a
 * subset has none; and an arc inside a subset lies inside another cap when
 * vbm_arcs_inside proves it. Circles the caller has already solved (the
 * bisector circles two regions of one atom share, stokes_cell.c) come
 * given: their arcs are taken as found and only the others are searched.
 *
 * vbm_cap_arcs_all chooses the subsets itself: a trial intersection
 * (cap 0 and the caps cutting most of it), then the boundary found so far;
 * before the search, the caps proven to hold a cap around the trial
 * intersection are rejected (bound_prune). vbm_cap_arcs_near is given each
 * circle's subset: its face's neighbours on the polyhedron of the caps'
 * half-spaces (cap_prefilter.c), so that no trial is made. vbm_cap_arcs
 * (cap_prefilter.c) runs one of them on the caps its polyhedron clip
 * cannot reject. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbm_caps_circle.h"

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
        int e = vbm_circle_arcs(caps, s, ns, w, s[i], 0, 0);
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

/* The arcs of circle l: inside the subset of caps first (cap 0, the
 * boundary's and the likely ones), then, unless every other cap is proven
 * to hold them (vbm_arcs_inside), inside the subset with the caps not proven
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
        int e = vbm_circle_arcs(caps, sel, ns, w, l, 0, keep);
        if (e < 0 || (e > 0 && (t == 1 || ns >= ncap)))
            return e;
        if (e == 0)
            break; /* undecided: every cap, of which one may exclude the circle */
        if (w->narc == first ||
            vbm_arcs_inside(caps, ncap, w, l, first, ON_BOUNDARY | LIKELY | BAD | HELD) == 0)
            return 1; /* none inside the subset, or all of them inside every cap */
        w->narc = first;
        keep = w->nres; /* the subset's restrictions stay: only the caps added are cut */
    }
    w->narc = first;
    for (size_t m = 0; m < ncap; m++)
        sel[m] = (uint32_t)m;
    return vbm_circle_arcs(caps, sel, ncap, w, l, 0, 0);
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
        if (!w->circ[given[i].cap].framed && !vbm_circle_frame(&w->circ[given[i].cap]))
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

/* vbm_cap_arcs' work space for caps[0..ncap) and their circles (no
 * frames); nothing searched yet. Returns 2 to search, 1 when a cap is
 * empty (so is the intersection), 0 when a circle cannot be made, -1 on
 * ENOMEM. */
static int begin(const vbm_cap *caps, const vbm_circle *axes, size_t ncap, vbm_capwork *w)
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
    memset(w->state, 0, ncap);
    return 2;
}

int vbm_cap_arcs_all(const vbm_cap *caps, const vbm_circle *axes, size_t ncap,
                     const uint8_t *known, const vbm_arc *given, size_t ngiven, vbm_capwork *w)
{
    int b = begin(caps, axes, ncap, w);
    if (b != 2)
        return b;
    /* The circles along the boundary first (cap 0's, then those whose caps
     * end an arc found), each inside every cap; then every other circle is
     * tried against the boundary's caps alone (and cap 0): no arc inside
     * those proves none inside them all (more caps only remove arcs), and
     * only a circle with an arc there is done against every cap. The arcs
     * are those of doing each circle against every cap. */
    uint32_t *sel = w->sel, *queue = w->queue;
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
            e = vbm_circle_arcs(caps, sel, ns, w, l, 1, 0);
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


/* The arcs of circle l inside cap 0 and the caps near[0..nnear) first
 * (its neighbours, vbm_cap_arcs_near), then as circle_all's second round:
 * the caps not proven to hold those arcs added; where undecided, against
 * every cap. (Cap 0 is always in the first subset: vbm_arcs_inside leaves
 * it out, as every search has it.) */
static int circle_near(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t l,
                       const uint32_t *near, size_t nnear)
{
    size_t first = w->narc, ns = 0;
    uint32_t *sel = w->sel;
    for (size_t m = 0; m < ncap; m++)
        w->state[m] &= (uint8_t)~(BAD | NEAR);
    if (l != 0) {
        w->state[0] |= NEAR;
        sel[ns++] = 0;
    }
    for (size_t i = 0; i < nnear; i++)
        if (near[i] != l && !(w->state[near[i]] & NEAR)) {
            w->state[near[i]] |= NEAR;
            sel[ns++] = near[i];
        }
    int e = vbm_circle_arcs(caps, sel, ns, w, l, 0, 0);
    if (e < 0 || (e > 0 && ns + 1 >= ncap))
        return e;
    if (e > 0) {
        if (w->narc == first || vbm_arcs_inside(caps, ncap, w, l, first, NEAR | BAD) == 0)
            return 1;
        w->narc = first;
        size_t keep = w->nres;
        ns = 0;
        for (size_t m = 0; m < ncap; m++)
            if (w->state[m] & BAD)
                sel[ns++] = (uint32_t)m;
        e = vbm_circle_arcs(caps, sel, ns, w, l, 0, keep);
        if (e != 0)
            return e;
    }
    w->narc = first;
    for (size_t m = 0; m < ncap; m++)
        sel[m] = (uint32_t)m;
    return vbm_circle_arcs(caps, sel, ncap, w, l, 0, 0);
}

int vbm_cap_arcs_near(const vbm_cap *caps, const vbm_circle *axes, size_t ncap,
                      const uint8_t *known, const vbm_arc *given, size_t ngiven,
                      const uint32_t *near_at, const uint32_t *near, vbm_capwork *w)
{
    int b = begin(caps, axes, ncap, w);
    if (b != 2)
        return b;
    size_t nq = 0;
    size_t nb = take_given(ncap, known, given, ngiven, w, &nq);
    if (nb >= SIZE_MAX - 1)
        return nb == SIZE_MAX ? -1 : 0;
    for (size_t l = 0; l < ncap; l++) {
        if ((w->state[l] & DONE) || w->circ[l].kind != VBM_CAP_CIRCLE)
            continue;
        int e = near_at ? circle_near(caps, ncap, w, l, near + near_at[l], near_at[l + 1] - near_at[l])
                        : circle_near(caps, ncap, w, l, NULL, 0);
        if (e <= 0)
            return e;
    }
    return order_arcs(w, ncap);
}
