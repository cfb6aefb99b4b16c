/* The regions of an arc of a trisector (vbx_region.h) and the candidates
 * they give: every sphere that may touch the tangent sphere along the arc.
 *
 * Why the candidates are complete. In the (S, G) coordinates of the plane
 * (u = O + S ES + G EG) every L_j is affine, so L_j < 0 somewhere on a part
 * of the arc only if L_j < 0 somewhere on any convex region that holds that
 * part. The regions used:
 *   - a bounded arc of an open branch, between vertices v and w at
 *     positions G0 < G1: S on the branch is Sc + sqrt(k^2 G^2 + cp), a
 *     strictly convex function of G, so the arc lies below its chord and
 *     above its tangents at v and w: inside the triangle of v, w and the
 *     apex A where those tangents meet. v and w are certified vertices, so
 *     L_j(v) >= 0 and L_j(w) >= 0 for every sphere j (a sphere with L_j < 0
 *     at a point of the cone cuts that point's tangent ball; contained
 *     spheres are never candidates); an affine L_j that is also > 0 at A is
 *     > 0 on the triangle's interior, which holds the open arc. So the
 *     region is the one point A (a box enclosing it). Where the
 *     enclosures cannot separate the two slopes: the box G in [G0, G1], S
 *     between the ends' values (and the branch's Smin when G = 0 lies
 *     between them), in two parts;
 *   - a tail to infinity, G >= G1 >= 0: the branch lies between its
 *     asymptote S = Sc + k G and the parallel line through the tail's first
 *     point (the gap S - Sc - k G shrinks as G grows), a half-strip: its
 *     segment at G1 plus the recession direction D = (k, 1). L_j is >= 0 on
 *     it exactly when it is at the segment's two ends and grad L_j . D >= 0.
 *     A tail starting at G0 < 0 adds the box [G0, 0] x [Smin, S(G0)];
 *   - a closed curve, the ellipse G = bx X, S = Sc + ax Y over the unit
 *     circle X^2 + Y^2 = 1 (an affine image: tangents map to tangents):
 *     16 exact points u_k of the circle (rational, from t = tan(theta/2)
 *     in each quadrant and its rotations by 90 degrees, so neighbouring
 *     quadrants share their end points exactly) cut it into arcs that
 *     turn by less than 90 degrees; the arc from u_k to u_k+1 lies in the
 *     triangle of u_k, u_k+1 and the apex A_k = (u_k + u_k+1) / (1 + u_k .
 *     u_k+1) where their tangents meet (the circle is convex). An affine
 *     L_j that is > 0 at every u_k and A_k is > 0 on every triangle and so
 *     on the whole curve, so the region is those 32 points (boxes
 *     enclosing them). Where an enclosure is not finite: the boxes of 16
 *     slabs of G covering the whole ellipse;
 *     The same apex found in u itself (vbx_apex_point), where both ends
 *     come with the enclosures of their points u_v, u_w and of the
 *     curve's tangent directions tau_v, tau_w there (vbx_tau_of_box): the
 *     tangent lines u_v + alpha tau_v and u_w + beta tau_w lie in the
 *     plane and meet at A; in any two functionals independent on the
 *     plane (G and S: the keys' G, S and G . tau, S . tau) Cramer's rule
 *     gives alpha = (dG s_w - dS g_w) / (g_v s_w - s_v g_w), dG = G_w -
 *     G_v, dS = S_w - S_v, g = G . tau, s = S . tau, and A = u_v + alpha
 *     tau_v. Every factor is an enclosure of its exact value, so A's box
 *     holds the exact apex; the denominator must have a sign (the
 *     tangents are not parallel). A is then queried directly, and L_j(A)
 *     = W_j - 2 m_j . A, with no frame of the plane;
 *   - a bounded arc of a closed curve between vertices v and w that
 *     provably turns by less than 180 degrees: like a bounded arc of an
 *     open branch, it lies in the triangle of v, w and the apex where their
 *     tangents meet, so the region is that one point (ellipse_apex); an
 *     arc that may turn further gets the whole curve's region above.
 * L_j(u) < 0 at a point u of such a box means |c_j - p_u|^2 < (t_u + R_j)^2
 * + Q(u) with p_u = c_a + u_q, t_u = u_s - R_a, so |c_j - p_u| < |t_u| +
 * sqrt(max(Q(u), 0)) + R_j: a tangent-ball query of the certifier's index
 * (vbx_sindex.h) with radius |t| + sqrt(Q+) over the box's enclosure sees
 * every such j. grad L_j . D < 0 means m_j . D_u > 0, a half-space of
 * centres and radii: the index's hierarchy is walked with that test. Every
 * bound is an interval enclosure, so the exact frame's region lies inside
 * the one queried. Where the enclosures fail (nearly collinear centres, a
 * parabola) every sphere is a candidate. */
#include <float.h>

#include "vb_array.h"

#include "vbx_plane.h"
#include "vbx_region.h"

enum { VBX_BOUNDED_PARTS = 2, VBX_ELLIPSE_SLABS = 16, VBX_QUARTER_ARCS = 4 };

static vbx_ia ia_hull(vbx_ia a, vbx_ia b)
{
    vbx_ia r = {vbx_min(a.lo, b.lo), vbx_max(a.hi, b.hi)};
    return r;
}

static vbx_ia ia_span(double lo, double hi)
{
    vbx_ia r = {lo, hi};
    return r;
}

vbx_ia vbx_branch_S(const vbx_tframe *f, vbx_ia g)
{
    vbx_ia kg = vbx_ia_mul(f->k, g);
    return vbx_ia_add(f->Sc, vbx_ia_sqrt(vbx_ia_add(vbx_ia_sqr(kg), f->cp)));
}

void vbx_tail_from(const vbx_tframe *f, double g, double sgn, vbx_region *rg)
{
    vbx_region_clear(rg);
    double g1 = g;
    if (g < 0.0) {
        vbx_part *b = &rg->p[rg->n++];
        vbx_ia far = vbx_branch_S(f, vbx_ia_point(-g));
        b->kind = VBX_PART_BOX;
        b->S = ia_span(f->Smin.lo, vbx_max(far.hi, f->Smin.hi));
        b->G = sgn > 0 ? ia_span(g, 0.0) : ia_span(0.0, -g);
        g1 = 0.0;
    }
    vbx_part *s = &rg->p[rg->n++];
    s->kind = VBX_PART_STRIP;
    vbx_ia gi = vbx_ia_point(g1);
    vbx_ia on = vbx_branch_S(f, gi), asym = vbx_ia_add(f->Sc, vbx_ia_mul(f->k, gi));
    s->S = ia_hull(on, asym);
    s->G = vbx_ia_point(sgn * g1);
    s->D[0] = f->k;
    s->D[1] = vbx_ia_point(sgn);
}

/* The open branch's S and slope dS/dG at G (an interval of either sign):
 * S = Sc + sqrt(k^2 G^2 + cp), dS/dG = k^2 G / sqrt(k^2 G^2 + cp). */
static void branch_at(const vbx_tframe *f, vbx_ia g, vbx_ia *s, vbx_ia *slope)
{
    vbx_ia k2 = vbx_ia_sqr(f->k);
    vbx_ia root = vbx_ia_sqrt(vbx_ia_add(vbx_ia_mul(k2, vbx_ia_sqr(g)), f->cp));
    *s = vbx_ia_add(f->Sc, root);
    *slope = vbx_ia_div(vbx_ia_mul(k2, g), root);
}

int vbx_apex_box(const vbx_tframe *f, vbx_ia g0, vbx_ia g1, vbx_part *p)
{
    vbx_ia s0, s1, a, b;
    if (!(g0.hi < g1.lo) || !(g0.lo > -INFINITY) || !(g1.hi < INFINITY))
        return 0;
    branch_at(f, g0, &s0, &a);
    branch_at(f, g1, &s1, &b);
    vbx_ia den = vbx_ia_sub(b, a);
    if (!(den.lo > 0.0) || !(den.hi < INFINITY))
        return 0;
    /* S_0 + a (G - G_0) = S_1 + b (G - G_1) at
     * G_A = ((S_0 - a G_0) - (S_1 - b G_1)) / (b - a); S_A on either tangent */
    vbx_ia ga = vbx_ia_div(vbx_ia_sub(vbx_ia_sub(s0, vbx_ia_mul(a, g0)),
                                      vbx_ia_sub(s1, vbx_ia_mul(b, g1))),
                           den);
    vbx_ia sa0 = vbx_ia_add(s0, vbx_ia_mul(a, vbx_ia_sub(ga, g0)));
    vbx_ia sa1 = vbx_ia_add(s1, vbx_ia_mul(b, vbx_ia_sub(ga, g1)));
    vbx_ia sa = {vbx_max(sa0.lo, sa1.lo), vbx_min(sa0.hi, sa1.hi)};
    if (!(ga.lo > -INFINITY) || !(ga.hi < INFINITY) || !(sa.lo > -INFINITY) ||
        !(sa.hi < INFINITY) || !(sa.lo <= sa.hi))
        return 0;
    p->kind = VBX_PART_BOX;
    p->S = sa;
    p->G = ga;
    return 1;
}

/* The bounded arc between two vertices: its apex alone (see the top). */
static int apex_part(const vbx_tframe *f, const vbx_arc_end *e0, const vbx_arc_end *e1,
                     vbx_region *rg)
{
    if (!vbx_apex_box(f, e0->key.G, e1->key.G, &rg->p[0]))
        return 0;
    rg->n = 1;
    return 1;
}

/* u = (box - c_a, t + R_a) over the enclosures (vbx_key_of_box's u). */
static void u_of_box(const vbx_ia *ba, const vbx_ia box[4], vbx_ia u[4])
{
    for (int i = 0; i < 3; i++)
        u[i] = vbx_ia_sub(box[i], ba[i]);
    u[3] = vbx_ia_add(box[3], ba[3]);
}

int vbx_apex_point(const vbx_arcw *w, const vbx_tframe *f, const vbx_arc_end *e0,
                   const vbx_arc_end *e1, vbx_region *rg)
{
    if (f->kind != VBX_TRI_OPEN || e0->inf || e1->inf || !e0->box || !e0->tau || !e1->box ||
        !e1->tau)
        return 0;
    /* An open curve's S is s itself (sf = (0, 0, 0, 1)) and its G is
     * n . q (gf = (n, 0)): S . tau = tau_s exactly, G . tau a dot of 3. */
    vbx_ia g0 = vbx_ia_dot3(f->gf, e0->tau), s0 = e0->tau[3];
    vbx_ia g1 = vbx_ia_dot3(f->gf, e1->tau), s1 = e1->tau[3];
    vbx_ia den = vbx_ia_det2(g0, s0, g1, s1);
    if (!vbx_ia_sign(den))
        return 0;
    vbx_ia dG = vbx_ia_sub(e1->key.G, e0->key.G), dS = vbx_ia_sub(e1->key.S, e0->key.S);
    vbx_ia alpha = vbx_ia_div(vbx_ia_det2(dG, dS, g1, s1), den);
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_part *p = &rg->p[0];
    u_of_box(ba, e0->box, p->u);
    for (int k = 0; k < 4; k++) {
        p->u[k] = vbx_ia_add(p->u[k], vbx_ia_mul(alpha, e0->tau[k]));
        if (!(p->u[k].lo > -INFINITY) || !(p->u[k].hi < INFINITY))
            return 0;
    }
    p->kind = VBX_PART_POINT;
    rg->brute = 0;
    rg->n = 1;
    return 1;
}

/* tan(theta / 2) at theta = i pi / 8 (any increasing doubles from 0 to 1
 * would do: the points are defined from these values exactly). */
static const double quarter_t[VBX_QUARTER_ARCS] = {0.0, 0.19891236737965800, 0.41421356237309503,
                                                  0.66817863791929900};

/* The part enclosing the ellipse's image of circle point (X, Y). */
static int ellipse_part(const vbx_tframe *f, vbx_ia X, vbx_ia Y, vbx_part *p)
{
    p->kind = VBX_PART_BOX;
    p->G = vbx_ia_mul(f->bx, X);
    p->S = vbx_ia_add(f->Sc, vbx_ia_mul(f->ax, Y));
    return p->G.lo > -INFINITY && p->G.hi < INFINITY && p->S.lo > -INFINITY &&
           p->S.hi < INFINITY && p->G.lo <= p->G.hi && p->S.lo <= p->S.hi;
}

/* The closed curve's tangent polygon (see the top): 1 when set, 0 when an
 * enclosure is not finite. */
static int ellipse_polygon(const vbx_tframe *f, vbx_region *rg)
{
    enum { N = 4 * VBX_QUARTER_ARCS };
    vbx_ia X[N], Y[N], one = vbx_ia_point(1.0);
    for (int i = 0; i < VBX_QUARTER_ARCS; i++) {
        vbx_ia t = vbx_ia_point(quarter_t[i]), t2 = vbx_ia_sqr(t), d = vbx_ia_add(one, t2);
        vbx_ia c = vbx_ia_div(vbx_ia_sub(one, t2), d);
        vbx_ia s = vbx_ia_div(vbx_ia_mul(vbx_ia_point(2.0), t), d);
        /* quadrant q: (c, s) turned by q times 90 degrees */
        for (int q = 0; q < 4; q++) {
            int k = q * VBX_QUARTER_ARCS + i;
            X[k] = q == 0 ? c : q == 1 ? vbx_ia_neg(s) : q == 2 ? vbx_ia_neg(c) : s;
            Y[k] = q == 0 ? s : q == 1 ? c : q == 2 ? vbx_ia_neg(s) : vbx_ia_neg(c);
        }
    }
    rg->n = 0;
    for (int k = 0; k < N; k++) {
        int l = (k + 1) % N;
        vbx_ia xs[3] = {X[k], Y[k], one}, ys[3] = {X[l], Y[l], one};
        vbx_ia den = vb_ia_dot(xs, ys, 3);
        if (!(den.lo > 0.0))
            return 0;
        vbx_ia AX = vbx_ia_div(vbx_ia_add(X[k], X[l]), den);
        vbx_ia AY = vbx_ia_div(vbx_ia_add(Y[k], Y[l]), den);
        if (!ellipse_part(f, X[k], Y[k], &rg->p[rg->n++]) ||
            !ellipse_part(f, AX, AY, &rg->p[rg->n++]))
            return 0;
    }
    return 1;
}

/* The bounded arc of a closed curve from end e0 forward to end e1, when it
 * provably turns by less than 180 degrees: its apex alone (1), else 0. On
 * the unit circle (X, Y) = (G / bx, (S - Sc) / ax) the curve runs
 * counter-clockwise in (Y, X) (forward: from the largest S through G > 0),
 * so the forward arc from u0 to u1 turns by phi with sin phi = Y0 X1 -
 * X0 Y1; phi < 180 degrees when that is > 0, and then the tangents at u0
 * and u1 meet at (u0 + u1) / (1 + u0 . u1), the apex of the triangle that
 * holds the arc (the curve is convex; the affine image keeps tangents and
 * triangles). The ends are enclosures of the exact points, so these
 * enclose the exact apex. */
static int ellipse_apex(const vbx_tframe *f, const vbx_arc_end *e0, const vbx_arc_end *e1,
                        vbx_region *rg)
{
    vbx_ia X0 = vbx_ia_div(e0->key.G, f->bx), Y0 = vbx_ia_div(vbx_ia_sub(e0->key.S, f->Sc), f->ax);
    vbx_ia X1 = vbx_ia_div(e1->key.G, f->bx), Y1 = vbx_ia_div(vbx_ia_sub(e1->key.S, f->Sc), f->ax);
    vbx_ia one = vbx_ia_point(1.0);
    vbx_ia xt[2] = {Y0, vbx_ia_neg(X0)}, yt[2] = {X1, Y1};
    vbx_ia turn = vb_ia_dot(xt, yt, 2);
    if (!(turn.lo > 0.0))
        return 0;
    vbx_ia xs[3] = {X0, Y0, one}, ys[3] = {X1, Y1, one};
    vbx_ia den = vb_ia_dot(xs, ys, 3);
    if (!(den.lo > 0.0))
        return 0;
    vbx_ia AX = vbx_ia_div(vbx_ia_add(X0, X1), den), AY = vbx_ia_div(vbx_ia_add(Y0, Y1), den);
    if (!ellipse_part(f, AX, AY, &rg->p[0]))
        return 0;
    rg->n = 1;
    return 1;
}

void vbx_region_of(const vbx_tframe *f, const vbx_arc_end *e0, const vbx_arc_end *e1,
                   vbx_region *rg)
{
    vbx_region_clear(rg);
    if (!f->ok) {
        rg->brute = 1;
        return;
    }
    if (f->kind != VBX_TRI_OPEN && e0 != e1 && !e0->inf && !e1->inf && ellipse_apex(f, e0, e1, rg))
        return;
    if (f->kind != VBX_TRI_OPEN && ellipse_polygon(f, rg))
        return;
    if (f->kind != VBX_TRI_OPEN) {
        rg->n = 0;
        /* The curve is S = Sc +- ax sqrt(1 - G^2 / bx^2), |G| <= bx: over
         * each slab of G (breakpoints shared by neighbours, so the slabs
         * cover [-bx, bx]) the upper and the lower half lie in the boxes
         * of that enclosure. A slab where 1 - G^2 / bx^2 < 0 throughout
         * holds none of the curve. */
        double gmax = f->bx.hi;
        vbx_ia one = vbx_ia_point(1.0), bx2 = vbx_ia_sqr(f->bx);
        double g0 = -gmax;
        for (int i = 1; i <= VBX_ELLIPSE_SLABS; i++) {
            double g1 = i == VBX_ELLIPSE_SLABS ? gmax : -gmax + 2.0 * gmax * i / VBX_ELLIPSE_SLABS;
            vbx_ia G = ia_span(g0, vbx_max(g0, g1));
            g0 = vbx_max(g0, g1);
            vbx_ia r = vbx_ia_sub(one, vbx_ia_div(vbx_ia_sqr(G), bx2));
            if (!(r.hi >= 0.0))
                continue;
            r.lo = vbx_max(r.lo, 0.0);
            vbx_ia h = vbx_ia_mul(f->ax, vbx_ia_sqrt(r));
            vbx_part *up = &rg->p[rg->n++], *dn = &rg->p[rg->n++];
            up->kind = dn->kind = VBX_PART_BOX;
            up->G = dn->G = G;
            up->S = vbx_ia_add(f->Sc, h);
            dn->S = vbx_ia_sub(f->Sc, h);
        }
        if (!rg->n)
            rg->brute = 1; /* the enclosures miss the curve: cannot be */
        return;
    }
    if (!e0->inf && !e1->inf) {
        if (apex_part(f, e0, e1, rg))
            return;
        /* a bounded arc: thin boxes from e0's G to e1's (piece_parts) */
        if (!(e0->key.G.lo <= e1->key.G.hi) || !(e0->key.G.lo > -INFINITY) ||
            !(e1->key.G.hi < INFINITY)) {
            rg->brute = 1;
            return;
        }
        vbx_piece_parts(f, e0->key.S, e0->key.G.lo, e1->key.G.hi, 1.0, VBX_BOUNDED_PARTS, rg);
        return;
    }
    /* A tail: forward (e1 at infinity) from G0, or backward (e0 at
     * infinity) to G1; mirrored to g = +-G >= g0. */
    int fwd = e1->inf;
    vbx_ia G0 = fwd ? e0->key.G : vbx_ia_neg(e1->key.G);
    vbx_tail_from(f, G0.lo, fwd ? 1.0 : -1.0, rg);
}

/* u = O + S ES + G EG over intervals. */
static void u_of(const vbx_tframe *f, vbx_ia S, vbx_ia G, vbx_ia u[4])
{
    vbx_ia x[3] = {S, G, vbx_ia_point(1.0)};
    for (int k = 0; k < 4; k++) {
        vbx_ia y[3] = {f->ES[k], f->EG[k], f->O[k]};
        u[k] = vb_ia_dot(x, y, 3);
    }
}

/* Adds sphere j to the candidates once; a sphere inside another never
 * touches (the searches skip it) and is left out. */
static int push_cand(vbx_arcw *w, uint32_t j)
{
    const uint32_t *own = w->own;
    if (w->mark[j] || (w->set->contained && w->set->contained[j]) ||
        (own && ((j == own[0]) | (j == own[1]) | (j == own[2]))))
        return VB_OK;
    if (VB_ARRAY_FIT(w->cand, w->cand_cap, w->ncand + 1, 256) != VB_OK)
        return VB_ENOMEM;
    w->mark[j] = 1;
    w->cand[w->ncand++] = j;
    return VB_OK;
}

static int query_u(vbx_arcw *w, const vbx_tframe *f, const vbx_ia u[4], vbx_ia Q);

/* Q(u) = |q|^2 - s^2 over the enclosures of u. */
static vbx_ia q_of(const vbx_ia u[4])
{
    vbx_ia un[4] = {u[0], u[1], u[2], vbx_ia_neg(u[3])};
    return vb_ia_dot(un, u, 4);
}

/* Every sphere that may reach into a ball of radius |t| + sqrt(Q+) around a
 * point of the box S x G (see the top). */
static int query_box(vbx_arcw *w, const vbx_tframe *f, vbx_ia S, vbx_ia G)
{
    vbx_ia u[4];
    u_of(f, S, G, u);
    vbx_ia Q = q_of(u);
    if (f->kind == VBX_TRI_OPEN) {
        /* The same Q in the conic's form (vbx_tframe.mq): each of S and G
         * appears once, so the enclosure is tight where the sum of squares
         * over the box's enclosure of u is not; both enclose Q, keep the
         * smaller upper end. */
        vbx_ia kg = vbx_ia_mul(f->k, G);
        vbx_ia ds = vbx_ia_sub(S, f->Sc);
        vbx_ia Qc = vbx_ia_mul(f->mq, vbx_ia_sub(vbx_ia_add(vbx_ia_sqr(kg), f->cp), vbx_ia_sqr(ds)));
        if (Qc.hi < Q.hi)
            Q.hi = Qc.hi;
    }
    return query_u(w, f, u, Q);
}

/* Every sphere that may reach into a ball of radius |t| + sqrt(Q+) around a
 * point of u's box, Q an enclosure of Q(u) there (see the top). */
static int query_u(vbx_arcw *w, const vbx_tframe *f, const vbx_ia u[4], vbx_ia Q)
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_ia p[4];
    for (int k = 0; k < 3; k++)
        p[k] = vbx_ia_add(ba[k], u[k]);
    vbx_ia t = vbx_ia_sub(u[3], ba[3]);
    double at = vbx_max(-t.lo, t.hi);
    double rad = vbx_succ(at + (Q.hi > 0.0 ? vbx_succ(sqrt(Q.hi)) : 0.0));
    if (Q.hi > 0.0 && at > 0.0) {
        /* (at + Q / (2 at) + R)^2 >= (at + R)^2 + Q for R >= 0, so the walk
         * may use that radius, far smaller for a large tangent ball. */
        double r2 = vbx_succ(at + vbx_succ(vbx_succ(Q.hi / at) * 0.5));
        if (r2 < rad)
            rad = r2;
    }
    if (!(rad < INFINITY) || rad != rad)
        return 1; /* unbounded: the caller goes brute force */
    vbx_ia pb[4] = {p[0], p[1], p[2], vbx_ia_point(0.0)};
    double Qp = Q.hi > 0.0 ? Q.hi : 0.0;
    p[3] = vbx_ia_point(rad);
    const vbx_sindex *ix = &w->c->t;
    vbx_walk walk;
    vbx_walk_init(&walk, ix, p);
    /* The first, cheap test of each slot: the probe (the slot's compact
     * copy, vbx_probe_outside) proves |q - c_j| > rad + R_j over the box,
     * by a margin of a relative 2^-41 at least, so the gap from the box to
     * the centre's enclosure squared, d2 below, exceeds (rad + R_j)^2 (1 +
     * 2^-40) up to a few roundings; and (rad + R_j)^2 >= (|t| + R_j)^2 + Q+
     * (both of rad's forms above), so the sharper test would skip the
     * slot too. The candidates are the slots the sharper test keeps,
     * whichever first test runs (vbx_outside_sphere on the slot's
     * enclosures was the other, at twice the memory and four times the
     * operations). */
    vbx_probe pr;
    vbx_probe_init(&pr, ix, p);
    size_t s0, s1;
    while (vbx_walk_next(&walk, &s0, &s1))
        for (size_t s = s0; s < s1; s++) {
            if (vbx_probe_outside(&pr, &ix->mid[4 * s]))
                continue;
            /* the sharper form of the same bound: |c_j - p_u|^2 < (|t| +
             * R_j)^2 + Q+ (gap: the distance from the centre's enclosure
             * to the box's, a lower bound of |c_j - p_u|) */
            const vbx_ia *cj = &ix->box[4 * s];
            double clo[3] = {cj[0].lo, cj[1].lo, cj[2].lo}, chi[3] = {cj[0].hi, cj[1].hi, cj[2].hi};
            /* (vbx_outside_box: d2 >= |q - c|^2 (1 + u)^-5 above 2^-900,
             * and fl(d2 (1 - 2^-50)) stays below that.) The right side in
             * one bound: at >= 0, R_j >= 0 (E103) and Qp >= 0, so rhs = fl(fl(fl(at +
             * R_j)^2) + Qp) >= ((at + R_j)^2 + Qp) / (1 + u)^4, and
             * fl(rhs (1 + 2^-50)) >= rhs (1 + 2^-50)(1 - u) exceeds
             * (1 + u)^4 rhs; the term 2^-1000 covers underflow (absolute
             * errors below 2^-1074 each). */
            double d2 = vbx_gap2(clo, chi, pb);
            double tr = at + cj[3].hi, rhs = tr * tr + Qp;
            if (d2 >= 0x1p-900 && d2 <= DBL_MAX &&
                d2 * (1.0 - 0x1p-50) > rhs * (1.0 + 0x1p-50) + 0x1p-1000)
                continue;
            if (push_cand(w, ix->ids[s]) != VB_OK)
                return -1;
        }
    return 0;
}

/* Upper bound of m_j . D over the centres in [lo, hi] and radii in
 * [0, rmax] (m_j = (c_j - c_a, R_j - R_a)). */
static double half_hi(const vbx_ia *ba, const vbx_ia D[4], const double lo[3], const double hi[3],
                      double rmax)
{
    vbx_ia s = vbx_ia_point(0.0);
    for (int k = 0; k < 3; k++)
        s = vbx_ia_add(s, vbx_ia_mul(D[k], vbx_ia_sub(ia_span(lo[k], hi[k]), ba[k])));
    s = vbx_ia_add(s, vbx_ia_mul(D[3], vbx_ia_sub(ia_span(0.0, rmax), ba[3])));
    return s.hi;
}

/* Every sphere with m_j . D_u > 0 possible: 0, -1 out of memory, or 2
 * once more than cap candidates are held (the walk stops there). */
static int query_half_capped(vbx_arcw *w, const vbx_tframe *f, const vbx_ia Ddir[2], size_t cap)
{
    vbx_ia D[4];
    for (int k = 0; k < 4; k++) {
        vbx_ia y[2] = {f->ES[k], f->EG[k]};
        D[k] = vb_ia_dot(Ddir, y, 2);
    }
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    const vbx_sindex *ix = &w->c->t;
    if (!ix->n)
        return 0;
    uint32_t stack[VBX_SINDEX_STACK];
    uint32_t sp = 0;
    stack[sp++] = 0;
    while (sp) {
        const vbx_bvh_node *nd = &ix->node[stack[--sp]];
        if (!(half_hi(ba, D, nd->lo, nd->hi, nd->rmax) > 0.0))
            continue;
        if (!nd->count) {
            uint32_t i = (uint32_t)(nd - ix->node);
            stack[sp++] = nd->first;
            stack[sp++] = i + 1;
            continue;
        }
        for (uint32_t s = nd->first; s < nd->first + nd->count; s++) {
            const vbx_ia *cj = &ix->box[4 * (size_t)s];
            double lo[3] = {cj[0].lo, cj[1].lo, cj[2].lo}, hi[3] = {cj[0].hi, cj[1].hi, cj[2].hi};
            vbx_ia Dr[4] = {D[0], D[1], D[2], D[3]};
            /* one sphere: its radius enclosure instead of [0, rmax] */
            vbx_ia sum = vbx_ia_point(0.0);
            for (int k = 0; k < 3; k++)
                sum = vbx_ia_add(sum, vbx_ia_mul(Dr[k], vbx_ia_sub(ia_span(lo[k], hi[k]), ba[k])));
            sum = vbx_ia_add(sum, vbx_ia_mul(Dr[3], vbx_ia_sub(cj[3], ba[3])));
            if (sum.hi > 0.0 && push_cand(w, ix->ids[s]) != VB_OK)
                return -1;
        }
        if (w->ncand > cap)
            return 2;
    }
    return 0;
}

static int query_half(vbx_arcw *w, const vbx_tframe *f, const vbx_ia Ddir[2])
{
    return query_half_capped(w, f, Ddir, SIZE_MAX);
}

void vbx_clear_cands(vbx_arcw *w)
{
    for (size_t i = 0; i < w->ncand; i++)
        w->mark[w->cand[i]] = 0;
    w->ncand = 0;
}

int vbx_gather(vbx_arcw *w, const vbx_tframe *f, vbx_region *rg)
{
    vbx_clear_cands(w);
    /* The triple's own spheres touch everywhere along its curve: the
     * search never offers them (offer_gathered), so they are left out here
     * (three of the ~3.3 spheres a query keeps on proteins; the capped
     * gather keeps them, as they count towards its cap). */
    w->own = f->t;
    if (!rg->brute)
        for (int i = 0; i < rg->n; i++) {
            const vbx_part *p = &rg->p[i];
            int r = p->kind == VBX_PART_POINT ? query_u(w, f, p->u, q_of(p->u))
                                              : query_box(w, f, p->S, p->G);
            if (r == 0 && p->kind == VBX_PART_STRIP)
                r = query_half(w, f, p->D);
            if (r < 0)
                return VB_ENOMEM;
            if (r > 0) {
                rg->brute = 1;
                break;
            }
        }
    w->own = NULL;
    if (rg->brute) {
        vbx_clear_cands(w);
        w->cnt.brute++;
        for (size_t j = 0; j < w->set->n; j++)
            if (push_cand(w, (uint32_t)j) != VB_OK)
                return VB_ENOMEM;
    }
    return VB_OK;
}

int vbx_clear_of(const vbx_arcw *w, const vbx_tframe *f, const vbx_region *rg, uint32_t j)
{
    if (rg->brute)
        return 0;
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]], *bj = &w->c->d.box[4 * (size_t)j];
    /* L_j = W_j - 2 m_j . u with u = O + S ES + G EG: the coefficients
     * of S and G, and the rest l0 = W_j - 2 m_j . O, each one dot product
     * (vb_ia_dot); scaling by -2 is exact. At a point part, u itself takes
     * O's place: L_j(A) in one dot product, no plane frame. */
    vbx_ia m[4], x[8], y[8];
    for (int k = 0; k < 4; k++)
        m[k] = vbx_ia_sub(bj[k], ba[k]);
    int point = rg->n == 1 && rg->p[0].kind == VBX_PART_POINT;
    const vbx_ia *o = point ? rg->p[0].u : f->O;
    for (int k = 0; k < 4; k++) {
        x[k] = k < 3 ? m[k] : vbx_ia_neg(m[k]);
        y[k] = m[k];
        x[4 + k] = m[k];
        y[4 + k] = vbx_ia_make(-2.0 * o[k].hi, -2.0 * o[k].lo);
    }
    vbx_ia l0 = vb_ia_dot(x, y, 8);
    if (point)
        return l0.lo > 0.0;
    vbx_ia lS = vb_ia_dot(m, f->ES, 4), lG = vb_ia_dot(m, f->EG, 4);
    lS = vbx_ia_make(-2.0 * lS.hi, -2.0 * lS.lo);
    lG = vbx_ia_make(-2.0 * lG.hi, -2.0 * lG.lo);
    vbx_ia c[3] = {lS, lG, l0};
    for (int i = 0; i < rg->n; i++) {
        const vbx_part *p = &rg->p[i];
        vbx_ia v[3] = {p->S, p->G, vbx_ia_point(1.0)};
        if (!(vb_ia_dot(c, v, 3).lo > 0.0))
            return 0;
        if (p->kind == VBX_PART_STRIP && !(vb_ia_dot(c, p->D, 2).lo >= 0.0))
            return 0;
    }
    return 1;
}

void vbx_piece_parts(const vbx_tframe *f, vbx_ia Sa, double ga, double gb, double sgn,
                     int parts, vbx_region *rg)
{
    double g0 = ga;
    for (int i = 1; i <= parts; i++) {
        double g1 = i == parts ? gb : ga + (gb - ga) * i / parts;
        g1 = vbx_min(vbx_max(g1, g0), gb);
        vbx_part *p = &rg->p[rg->n++];
        p->kind = VBX_PART_BOX;
        vbx_ia Sb = vbx_branch_S(f, vbx_ia_point(g1 < 0.0 ? -g1 : g1));
        double slo = vbx_min(Sa.lo, Sb.lo), shi = vbx_max(Sa.hi, Sb.hi);
        if (g0 <= 0.0 && g1 >= 0.0)
            slo = vbx_min(slo, f->Smin.lo);
        p->S = ia_span(slo, shi);
        p->G = sgn > 0 ? ia_span(g0, g1) : ia_span(-g1, -g0);
        Sa = Sb;
        g0 = g1;
    }
}


int vbx_gather_capped(vbx_arcw *w, const vbx_tframe *f, const vbx_region *rg, size_t cap)
{
    vbx_clear_cands(w);
    for (int i = 0; i < rg->n; i++) {
        const vbx_part *p = &rg->p[i];
        /* the half-space first: it is the part that may be large */
        int r = p->kind == VBX_PART_STRIP ? query_half_capped(w, f, p->D, cap) : 0;
        if (r == 0)
            r = query_box(w, f, p->S, p->G);
        if (r < 0)
            return -1;
        if (r > 0 || w->ncand > cap) {
            vbx_clear_cands(w);
            return 0;
        }
    }
    return 1;
}
