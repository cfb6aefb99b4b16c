/* The first sphere that touches along an arc of a trisector (vbx_arc.h):
 * candidates from a provably conservative region of the arc, their roots
 * on the curve, and the positions of those roots against the arc's ends.
 *
 * Why the candidates are complete. In the (S, G) coordinates of the plane
 * (u = O + S ES + G EG) every L_j is affine, so L_j < 0 somewhere on a part
 * of the arc only if L_j < 0 somewhere on any convex region that holds that
 * part. The regions used:
 *   - a bounded arc of an open branch, between positions G0 < G1: S on the
 *     branch is Sc + sqrt(k^2 G^2 + cp), monotone on each side of G = 0, so
 *     the arc lies in the box G in [G0, G1], S between the ends' values (and
 *     the branch's Smin when G = 0 lies between them);
 *   - a tail to infinity, G >= G1 >= 0: the branch lies between its
 *     asymptote S = Sc + k G and the parallel line through the tail's first
 *     point (the gap S - Sc - k G shrinks as G grows), a half-strip: its
 *     segment at G1 plus the recession direction D = (k, 1). L_j is >= 0 on
 *     it exactly when it is at the segment's two ends and grad L_j . D >= 0.
 *     A tail starting at G0 < 0 adds the box [G0, 0] x [Smin, S(G0)];
 *   - a closed curve: the box of the whole ellipse.
 * L_j(u) < 0 at a point u of such a box means |c_j - p_u|^2 < (t_u + R_j)^2
 * + Q(u) with p_u = c_a + u_q, t_u = u_s - R_a, so |c_j - p_u| < |t_u| +
 * sqrt(max(Q(u), 0)) + R_j: a tangent-ball query of the certifier's index
 * (vbx_sindex.h) with radius |t| + sqrt(Q+) over the box's enclosure sees
 * every such j. grad L_j . D < 0 means m_j . D_u > 0, a half-space of
 * centres and radii: the index's hierarchy is walked with that test. Every
 * bound is an interval enclosure, so the exact frame's region lies inside
 * the one queried. Where the enclosures fail (nearly collinear centres, a
 * parabola) every sphere is a candidate.
 *
 * Then each candidate's fine test (L_j > 0 over the region: skipped), and
 * for the rest the roots of T + j, filtered (verify/quad_filter.c) and
 * exactly where the filter cannot place them. A member of an end's vertex
 * has that end as one of its two roots: when exactly one root's position
 * cannot be told from that end and the other's can, the first is the end. */
#include <stdlib.h>
#include <float.h>
#include <string.h>

#include "vbx_arc.h"

enum { PART_BOX = 0, PART_STRIP = 1 };

typedef struct part {
    int kind;
    vbx_ia S, G;   /* box; strip: its segment (G a point interval) */
    vbx_ia D[2];   /* strip: recession direction (dS, dG) */
} part;

typedef struct region {
    int brute;
    int n;
    part p[40];
} region;

enum { PIECE_PARTS = 4, BOUNDED_PARTS = 2, ELLIPSE_SLABS = 16 };

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

/* S on the open branch at |G| = g (g an interval >= 0). */
static vbx_ia branch_S(const vbx_tframe *f, vbx_ia g)
{
    vbx_ia kg = vbx_ia_mul(f->k, g);
    return vbx_ia_add(f->Sc, vbx_ia_sqrt(vbx_ia_add(vbx_ia_sqr(kg), f->cp)));
}

static void piece_parts(const vbx_tframe *f, vbx_ia Sa, double ga, double gb, double sgn,
                        int parts, region *rg);

/* The tail of the open branch beyond mirrored position g (a double; sgn
 * +1 forward, -1 backward): from g < 0 a box up to the branch's vertex
 * (g = 0), then the half-strip from max(g, 0) along the asymptote. */
static void tail_from(const vbx_tframe *f, double g, double sgn, region *rg)
{
    memset(rg, 0, sizeof *rg);
    double g1 = g;
    if (g < 0.0) {
        part *b = &rg->p[rg->n++];
        vbx_ia far = branch_S(f, vbx_ia_point(-g));
        b->kind = PART_BOX;
        b->S = ia_span(f->Smin.lo, vbx_max(far.hi, f->Smin.hi));
        b->G = sgn > 0 ? ia_span(g, 0.0) : ia_span(0.0, -g);
        g1 = 0.0;
    }
    part *s = &rg->p[rg->n++];
    s->kind = PART_STRIP;
    vbx_ia gi = vbx_ia_point(g1);
    vbx_ia on = branch_S(f, gi), asym = vbx_ia_add(f->Sc, vbx_ia_mul(f->k, gi));
    s->S = ia_hull(on, asym);
    s->G = vbx_ia_point(sgn * g1);
    s->D[0] = f->k;
    s->D[1] = vbx_ia_point(sgn);
}

/* The region of the arc from e0 to e1 (see the top). */
static void region_of(const vbx_tframe *f, const vbx_arc_end *e0, const vbx_arc_end *e1,
                      region *rg)
{
    memset(rg, 0, sizeof *rg);
    if (!f->ok) {
        rg->brute = 1;
        return;
    }
    if (f->kind != VBX_TRI_OPEN) {
        /* The curve is S = Sc +- ax sqrt(1 - G^2 / bx^2), |G| <= bx: over
         * each slab of G (breakpoints shared by neighbours, so the slabs
         * cover [-bx, bx]) the upper and the lower half lie in the boxes
         * of that enclosure. A slab where 1 - G^2 / bx^2 < 0 throughout
         * holds none of the curve. */
        double gmax = f->bx.hi;
        vbx_ia one = vbx_ia_point(1.0), bx2 = vbx_ia_sqr(f->bx);
        double g0 = -gmax;
        for (int i = 1; i <= ELLIPSE_SLABS; i++) {
            double g1 = i == ELLIPSE_SLABS ? gmax : -gmax + 2.0 * gmax * i / ELLIPSE_SLABS;
            vbx_ia G = ia_span(g0, vbx_max(g0, g1));
            g0 = vbx_max(g0, g1);
            vbx_ia r = vbx_ia_sub(one, vbx_ia_div(vbx_ia_sqr(G), bx2));
            if (!(r.hi >= 0.0))
                continue;
            r.lo = vbx_max(r.lo, 0.0);
            vbx_ia h = vbx_ia_mul(f->ax, vbx_ia_sqrt(r));
            part *up = &rg->p[rg->n++], *dn = &rg->p[rg->n++];
            up->kind = dn->kind = PART_BOX;
            up->G = dn->G = G;
            up->S = vbx_ia_add(f->Sc, h);
            dn->S = vbx_ia_sub(f->Sc, h);
        }
        if (!rg->n)
            rg->brute = 1; /* the enclosures miss the curve: cannot be */
        return;
    }
    if (!e0->inf && !e1->inf) {
        /* a bounded arc: thin boxes from e0's G to e1's (piece_parts) */
        if (!(e0->key.G.lo <= e1->key.G.hi) || !(e0->key.G.lo > -INFINITY) ||
            !(e1->key.G.hi < INFINITY)) {
            rg->brute = 1;
            return;
        }
        piece_parts(f, e0->key.S, e0->key.G.lo, e1->key.G.hi, 1.0, BOUNDED_PARTS, rg);
        return;
    }
    /* A tail: forward (e1 at infinity) from G0, or backward (e0 at
     * infinity) to G1; mirrored to g = +-G >= g0. */
    int fwd = e1->inf;
    vbx_ia G0 = fwd ? e0->key.G : vbx_ia_neg(e1->key.G);
    tail_from(f, G0.lo, fwd ? 1.0 : -1.0, rg);
}

/* u = O + S ES + G EG over intervals. */
static void u_of(const vbx_tframe *f, vbx_ia S, vbx_ia G, vbx_ia u[4])
{
    for (int k = 0; k < 4; k++)
        u[k] = vbx_ia_add(f->O[k], vbx_ia_add(vbx_ia_mul(S, f->ES[k]), vbx_ia_mul(G, f->EG[k])));
}

static int push_cand(vbx_arcw *w, uint32_t j)
{
    if (w->mark[j])
        return VB_OK;
    if (w->ncand == w->cand_cap) {
        size_t nc = w->cand_cap ? 2 * w->cand_cap : 256;
        uint32_t *p = realloc(w->cand, nc * sizeof *p);
        if (!p)
            return VB_ENOMEM;
        w->cand = p;
        w->cand_cap = nc;
    }
    w->mark[j] = 1;
    w->cand[w->ncand++] = j;
    return VB_OK;
}

/* Every sphere that may reach into a ball of radius |t| + sqrt(Q+) around a
 * point of the box S x G (see the top). */
static int query_box(vbx_arcw *w, const vbx_tframe *f, vbx_ia S, vbx_ia G)
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_ia u[4], p[4];
    u_of(f, S, G, u);
    for (int k = 0; k < 3; k++)
        p[k] = vbx_ia_add(ba[k], u[k]);
    vbx_ia t = vbx_ia_sub(u[3], ba[3]);
    vbx_ia Q = vbx_ia_sub(vbx_ia_add(vbx_ia_add(vbx_ia_sqr(u[0]), vbx_ia_sqr(u[1])),
                                     vbx_ia_sqr(u[2])),
                          vbx_ia_sqr(u[3]));
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
    size_t s0, s1;
    while (vbx_walk_next(&walk, &s0, &s1))
        for (size_t s = s0; s < s1; s++) {
            if (vbx_outside_sphere(&ix->box[4 * s], p))
                continue;
            /* the sharper form of the same bound: |c_j - p_u|^2 < (|t| +
             * R_j)^2 + Q+ (gap: the distance from the centre's enclosure
             * to the box's, a lower bound of |c_j - p_u|) */
            const vbx_ia *cj = &ix->box[4 * s];
            double clo[3] = {cj[0].lo, cj[1].lo, cj[2].lo}, chi[3] = {cj[0].hi, cj[1].hi, cj[2].hi};
            /* (vbx_outside_box: d2 >= |q - c|^2 (1 + u)^-5 above 2^-900,
             * and fl(d2 (1 - 2^-50)) stays below that) */
            double d2 = vbx_gap2(clo, chi, pb);
            vbx_ia tr = vbx_ia_add(vbx_ia_point(at), vbx_ia_point(cj[3].hi));
            vbx_ia rhs = vbx_ia_add(vbx_ia_sqr(tr), vbx_ia_point(Qp));
            if (d2 >= 0x1p-900 && d2 <= DBL_MAX && d2 * (1.0 - 0x1p-50) > rhs.hi)
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
    for (int k = 0; k < 4; k++)
        D[k] = vbx_ia_add(vbx_ia_mul(Ddir[0], f->ES[k]), vbx_ia_mul(Ddir[1], f->EG[k]));
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

static void clear_cands(vbx_arcw *w)
{
    for (size_t i = 0; i < w->ncand; i++)
        w->mark[w->cand[i]] = 0;
    w->ncand = 0;
}

/* Candidates of the region: VB_OK, VB_ENOMEM; sets rg->brute when a query
 * cannot be bounded. */
static int gather(vbx_arcw *w, const vbx_tframe *f, region *rg)
{
    clear_cands(w);
    if (!rg->brute)
        for (int i = 0; i < rg->n; i++) {
            const part *p = &rg->p[i];
            int r = query_box(w, f, p->S, p->G);
            if (r == 0 && p->kind == PART_STRIP)
                r = query_half(w, f, p->D);
            if (r < 0)
                return VB_ENOMEM;
            if (r > 0) {
                rg->brute = 1;
                break;
            }
        }
    if (rg->brute) {
        clear_cands(w);
        w->cnt.brute++;
        for (size_t j = 0; j < w->set->n; j++)
            if (push_cand(w, (uint32_t)j) != VB_OK)
                return VB_ENOMEM;
    }
    return VB_OK;
}

/* 1 when L_j > 0 is proven over the whole region. */
static int clear_of(const vbx_arcw *w, const vbx_tframe *f, const region *rg, uint32_t j)
{
    if (rg->brute)
        return 0;
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]], *bj = &w->c->d.box[4 * (size_t)j];
    vbx_ia m[4];
    for (int k = 0; k < 4; k++)
        m[k] = vbx_ia_sub(bj[k], ba[k]);
    vbx_ia W = vbx_ia_sub(vbx_ia_add(vbx_ia_add(vbx_ia_sqr(m[0]), vbx_ia_sqr(m[1])),
                                     vbx_ia_sqr(m[2])),
                          vbx_ia_sqr(m[3]));
    vbx_ia mES = vbx_ia_point(0.0), mEG = mES, mO = mES;
    for (int k = 0; k < 4; k++) {
        mES = vbx_ia_add(mES, vbx_ia_mul(m[k], f->ES[k]));
        mEG = vbx_ia_add(mEG, vbx_ia_mul(m[k], f->EG[k]));
        mO = vbx_ia_add(mO, vbx_ia_mul(m[k], f->O[k]));
    }
    vbx_ia two = vbx_ia_point(-2.0);
    vbx_ia lS = vbx_ia_mul(two, mES), lG = vbx_ia_mul(two, mEG);
    vbx_ia l0 = vbx_ia_add(W, vbx_ia_mul(two, mO));
    for (int i = 0; i < rg->n; i++) {
        const part *p = &rg->p[i];
        vbx_ia L = vbx_ia_add(vbx_ia_add(vbx_ia_mul(lS, p->S), vbx_ia_mul(lG, p->G)), l0);
        if (!(L.lo > 0.0))
            return 0;
        if (p->kind == PART_STRIP) {
            vbx_ia dL = vbx_ia_add(vbx_ia_mul(lS, p->D[0]), vbx_ia_mul(lG, p->D[1]));
            if (!(dL.lo >= 0.0))
                return 0;
        }
    }
    return 1;
}

static int is_member(const uint32_t *m, size_t nm, uint32_t j)
{
    size_t lo = 0, hi = nm;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (m[mid] < j)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < nm && m[lo] == j;
}

/* Makes sure end e has its exact point. */
static int need_end(vbx_arcw *w, vbx_tframe *f, vbx_arc_end *e)
{
    if (e->inf || *e->have)
        return VB_OK;
    if (!vbx_xpt_of_vertex(w, f, e->m, e->nm, e->xyzt, e->x))
        return VB_EDEGENERATE;
    *e->have = 1;
    return VB_OK;
}

/* cmp(y, e): -1, 0, 1, or 2 (undecided) when exact is 0; with exact, the
 * exact answer (or VB_EDEGENERATE as -9). */
static int cmp_end(vbx_arcw *w, vbx_tframe *f, const vbx_key *ky, const vbx_xpt *xy,
                   vbx_arc_end *e, int exact)
{
    int c = vbx_pos_cmp(w, f, ky, NULL, &e->key, NULL);
    if (c != 2 || !exact)
        return c;
    if (need_end(w, f, e) != VB_OK)
        return -9;
    return vbx_pos_cmp(w, f, ky, xy, &e->key, e->x);
}

enum { POS_OUT = 0, POS_IN = 1, POS_END = 2, POS_OPEN = 3 };

/* Where a point with comparisons c0 = cmp(y, e0), c1 = cmp(y, e1) lies
 * (either 2 = undecided). loop: e0 == e1 on a closed curve; wrap: e0 after
 * e1 on a closed curve. */
static int place(int c0, int c1, int open, int loop, int wrap)
{
    if (c0 == 0 || c1 == 0)
        return POS_END;
    if (loop)
        return c0 == 2 ? POS_OPEN : POS_IN;
    if (open || !wrap) {
        if (c0 == -1 || c1 == 1)
            return POS_OUT;
        if (c0 == 2 || c1 == 2)
            return POS_OPEN;
        return POS_IN;
    }
    if (c0 == 1 || c1 == -1)
        return POS_IN;
    if (c0 == 2 || c1 == 2)
        return POS_OPEN;
    return POS_OUT;
}

typedef struct search {
    vbx_tframe *f;
    vbx_arc_end *e0, *e1;
    int open, loop, wrap;
    vbx_touch *first, *last;
} search;

/* Solves sorted T + j exactly into w->sq; returns its number of roots (0
 * when it names none). */
static int solve_quad(vbx_arcw *w, const uint32_t t[3], uint32_t j)
{
    uint32_t q[4] = {t[0], t[1], t[2], j};

    for (int i = 1; i < 4; i++)
        for (int k = i; k > 0 && q[k - 1] > q[k]; k--) {
            uint32_t x = q[k];
            q[k] = q[k - 1];
            q[k - 1] = x;
        }
    w->cnt.exact_evals++;
    if (vbx_solve(&w->sq, q[0], q + 1) != VBX_SOLVED)
        return 0;
    return w->sq.nroots;
}

/* The exact point of touch tp (solving its quadruple again when needed). */
static int touch_exact(vbx_arcw *w, vbx_tframe *f, vbx_touch *tp)
{
    if (tp->have)
        return VB_OK;
    int nr = solve_quad(w, f->t, tp->j);
    if (tp->r >= nr)
        return vb_error(w->ctx, VB_EINTERNAL, NULL, 0,
                        "arc closure: the filter and the exact solver disagree on %u %u %u %u",
                        f->t[0], f->t[1], f->t[2], tp->j);
    vbx_xpt_of_root(w, f, &w->sq, &w->sq.root[tp->r], &tp->x);
    tp->have = 1;
    return VB_OK;
}

static void touch_set(vbx_touch *dst, uint32_t j, int r, int seg, const vbx_key *k,
                      const vbx_xpt *x)
{
    dst->found = 1;
    dst->j = j;
    dst->r = r;
    dst->seg = seg;
    dst->key = *k;
    dst->have = x != NULL;
    if (x) {
        mpz_set(dst->x.d, x->d);
        mpz_set(dst->x.den, x->den);
        for (int i = 0; i < 4; i++) {
            mpz_set(dst->x.U[i].a, x->U[i].a);
            mpz_set(dst->x.U[i].b, x->U[i].b);
        }
        mpz_set(dst->x.Gn.a, x->Gn.a);
        mpz_set(dst->x.Gn.b, x->Gn.b);
        mpz_set(dst->x.Sn.a, x->Sn.a);
        mpz_set(dst->x.Sn.b, x->Sn.b);
    }
}

/* Order of two touches along the arc: -1 (a first), 0, 1. */
static int touch_order(vbx_arcw *w, vbx_tframe *f, vbx_touch *a, vbx_touch *b)
{
    if (a->seg != b->seg)
        return a->seg < b->seg ? -1 : 1;
    int c = vbx_pos_cmp(w, f, &a->key, NULL, &b->key, NULL);
    if (c != 2)
        return c;
    int rc = touch_exact(w, f, a);
    if (rc == VB_OK)
        rc = touch_exact(w, f, b);
    if (rc != VB_OK)
        return -9;
    return vbx_pos_cmp(w, f, &a->key, &a->x, &b->key, &b->x);
}

/* Offers an inside point (j, root r) to first and last. */
static int offer(vbx_arcw *w, search *sr, uint32_t j, int r, int c0, const vbx_key *k,
                 const vbx_xpt *x)
{
    int seg = (sr->open || sr->loop || sr->wrap) && !sr->open ? (c0 == 1 ? 0 : 1) : 0;
    vbx_touch *slot[2] = {sr->first, sr->last};
    for (int s = 0; s < 2; s++) {
        vbx_touch *tp = slot[s];
        if (!tp)
            continue;
        if (tp->found) {
            vbx_touch cand;
            cand.found = 1;
            cand.j = j;
            cand.r = r;
            cand.seg = seg;
            cand.key = *k;
            cand.have = 0;
            /* the candidate's exact point lives in x (w->yx) when set */
            int o;
            if (x) {
                vbx_xpt_init(&cand.x);
                touch_set(&cand, j, r, seg, k, x);
                o = touch_order(w, sr->f, &cand, tp);
                vbx_xpt_clear(&cand.x);
            } else {
                vbx_xpt_init(&cand.x);
                o = touch_order(w, sr->f, &cand, tp);
                if (o != -9 && ((s == 0 && o < 0) || (s == 1 && o > 0)))
                    touch_set(tp, j, r, seg, k, cand.have ? &cand.x : NULL);
                vbx_xpt_clear(&cand.x);
                if (o == -9)
                    return VB_EDEGENERATE;
                continue;
            }
            if (o == -9)
                return VB_EDEGENERATE;
            if (!((s == 0 && o < 0) || (s == 1 && o > 0)))
                continue;
        }
        touch_set(tp, j, r, seg, k, x);
    }
    return VB_OK;
}

/* Exact placement of both roots of T + j. */
static int exact_roots(vbx_arcw *w, search *sr, uint32_t j)
{
    vbx_tframe *f = sr->f;
    int nr = solve_quad(w, f->t, j);
    for (int r = 0; r < nr; r++) {
        vbx_solver *s = &w->sq;
        const vbx_root *root = &s->root[r];
        /* On the trisector: t + R_a > 0 (the branch), and a touching of j:
         * t + R_j >= 0. */
        if (vbx_sign_tangent(s, root, f->t[0]) <= 0 || vbx_sign_tangent(s, root, j) < 0)
            continue;
        vbx_xpt *y = &w->yx[r];
        vbx_xpt_of_root(w, f, s, root, y);
        vbx_key ky;
        memset(&ky, 0, sizeof ky);
        ky.half = -1; /* the filter knows nothing: exact comparisons only */
        ky.G = ky.S = ky.val = ia_span(-INFINITY, INFINITY);
        int c0 = sr->e0->inf ? 1 : cmp_end(w, f, &ky, y, sr->e0, 1);
        int c1 = sr->e1->inf ? -1 : cmp_end(w, f, &ky, y, sr->e1, 1);
        if (c0 == -9 || c1 == -9)
            return VB_EDEGENERATE;
        int pl = place(c0, c1, f->kind == VBX_TRI_OPEN, sr->loop, sr->wrap);
        if (pl != POS_IN)
            continue;
        int rc = offer(w, sr, j, r, c0, &ky, y);
        if (rc != VB_OK)
            return rc;
    }
    return VB_OK;
}

/* Filtered placement of the roots of T + j; falls back to exact_roots. */
static int candidate(vbx_arcw *w, search *sr, uint32_t j)
{
    vbx_tframe *f = sr->f;
    const vb_certifier *c = w->c;
    w->cnt.root_checks++;
    uint32_t q[4] = {f->t[0], f->t[1], f->t[2], j};
    for (int i = 1; i < 4; i++)
        for (int k = i; k > 0 && q[k - 1] > q[k]; k--) {
            uint32_t x = q[k];
            q[k] = q[k - 1];
            q[k - 1] = x;
        }
    const vbx_qf_ops *ops = c->qd.ops;
    vbx_qline L;
    vbx_qprep P;
    w->cnt.filter_calls++;
    int fs = c->qd.ok && ops->line(&c->qd, q, &L) ? ops->prep(&L, &P) : VBX_QF_EXACT;
    if (fs == VBX_QF_NONE)
        return VB_OK;
    if (fs == VBX_QF_EXACT) {
        w->cnt.filter_failures++;
        return exact_roots(w, sr, j);
    }
    const vbx_ia *ba = &c->d.box[4 * (size_t)f->t[0]], *bj = &c->d.box[4 * (size_t)j];
    vbx_key ky[2];
    int c0[2], c1[2], on[2];
    for (int r = 0; r < 2; r++) {
        vbx_qroot R;
        ops->root(&P, r, &R);
        if (!ops->point(&c->qd, &L, &P, &R)) {
            w->cnt.filter_failures++;
            return exact_roots(w, sr, j);
        }
        int sa = vbx_ia_sign(vbx_ia_add(R.p[3], ba[3]));
        vbx_ia tj = vbx_ia_add(R.p[3], bj[3]);
        if (sa < 0 || tj.hi < 0.0) {
            on[r] = 0;
            continue;
        }
        if (sa == 0 || !(tj.lo >= 0.0)) {
            w->cnt.filter_failures++;
            return exact_roots(w, sr, j);
        }
        on[r] = 1;
        vbx_key_of_box(w, f, R.p, &ky[r]);
        c0[r] = sr->e0->inf ? 1 : vbx_pos_cmp(w, f, &ky[r], NULL, &sr->e0->key, NULL);
        c1[r] = sr->e1->inf ? -1 : vbx_pos_cmp(w, f, &ky[r], NULL, &sr->e1->key, NULL);
    }
    /* A member of an end's vertex: one root is that end. */
    for (int e = 0; e < 2; e++) {
        const vbx_arc_end *end = e ? sr->e1 : sr->e0;
        int *cc = e ? c1 : c0;
        if (end->inf || !is_member(end->m, end->nm, j))
            continue;
        int u0 = on[0] && cc[0] == 2, u1 = on[1] && cc[1] == 2;
        int d0 = !on[0] || cc[0] != 2, d1 = !on[1] || cc[1] != 2;
        if (u0 && d1)
            cc[0] = 0;
        else if (u1 && d0)
            cc[1] = 0;
    }
    int pl[2];
    for (int r = 0; r < 2; r++) {
        pl[r] = on[r] ? place(c0[r], c1[r], f->kind == VBX_TRI_OPEN, sr->loop, sr->wrap) : POS_OUT;
        if (pl[r] == POS_OPEN) {
            w->cnt.filter_failures++;
            return exact_roots(w, sr, j);
        }
    }
    for (int r = 0; r < 2; r++)
        if (pl[r] == POS_IN) {
            int rc = offer(w, sr, j, r, c0[r], &ky[r], NULL);
            if (rc != VB_OK)
                return rc;
        }
    return VB_OK;
}

/* The candidates of region rg offered to the search (see the top). */
static int scan_region(vbx_arcw *w, search *sr, region *rg)
{
    vbx_tframe *f = sr->f;
    int rc = gather(w, f, rg);
    for (size_t i = 0; rc == VB_OK && i < w->ncand; i++) {
        uint32_t j = w->cand[i];
        if (j == f->t[0] || j == f->t[1] || j == f->t[2] ||
            (w->set->contained && w->set->contained[j]))
            continue;
        w->cnt.candidates++;
        if (clear_of(w, f, rg, j))
            continue;
        rc = candidate(w, sr, j);
    }
    clear_cands(w);
    return rc;
}

/* The boxes of the open branch over mirrored positions g in [ga, gb] (G =
 * sgn g), `parts` of them appended to rg: each from breakpoint g_i
 * to g_i+1 (shared by neighbours, so they cover [ga, gb]), its S from the
 * branch's at g_i (Sa at ga: the start vertex's enclosure) to the
 * branch's at g_i+1, and Smin when G = 0 lies between (S depends on |G|
 * alone and grows with it). Thin boxes keep Q small over each, so the
 * tangent-ball queries stay close to the arc. */
static void piece_parts(const vbx_tframe *f, vbx_ia Sa, double ga, double gb, double sgn,
                        int parts, region *rg)
{
    double g0 = ga;
    for (int i = 1; i <= parts; i++) {
        double g1 = i == parts ? gb : ga + (gb - ga) * i / parts;
        g1 = vbx_min(vbx_max(g1, g0), gb);
        part *p = &rg->p[rg->n++];
        p->kind = PART_BOX;
        vbx_ia Sb = branch_S(f, vbx_ia_point(g1 < 0.0 ? -g1 : g1));
        double slo = vbx_min(Sa.lo, Sb.lo), shi = vbx_max(Sa.hi, Sb.hi);
        if (g0 <= 0.0 && g1 >= 0.0)
            slo = vbx_min(slo, f->Smin.lo);
        p->S = ia_span(slo, shi);
        p->G = sgn > 0 ? ia_span(g0, g1) : ia_span(-g1, -g0);
        Sa = Sb;
        g0 = g1;
    }
}


/* Candidates of a tail region when there are at most cap of them: 1 when
 * gathered (then w->cand holds them, as gather would), 0 when over the cap
 * or unbounded (nothing held), -1 out of memory. */
static int gather_capped(vbx_arcw *w, const vbx_tframe *f, const region *rg, size_t cap)
{
    clear_cands(w);
    for (int i = 0; i < rg->n; i++) {
        const part *p = &rg->p[i];
        /* the half-space first: it is the part that may be large */
        int r = p->kind == PART_STRIP ? query_half_capped(w, f, p->D, cap) : 0;
        if (r == 0)
            r = query_box(w, f, p->S, p->G);
        if (r < 0)
            return -1;
        if (r > 0 || w->ncand > cap) {
            clear_cands(w);
            return 0;
        }
    }
    return 1;
}

enum { TAIL_PIECES = 48, TAIL_CAP_MIN = 64, TAIL_STRIP_FROM = 2 };

/* An open arc from a vertex to infinity (forward: sr->e1 at infinity;
 * backward: sr->e0), searched outwards in pieces of doubling length.
 *
 * Why it finds the same first touch as one search of the whole tail: the
 * touch held after the pieces up to mirrored position gb is the first
 * among every sphere offered so far, and those include every sphere with
 * L_j <= 0 somewhere on the arc up to gb (each piece's box holds its part
 * of the arc). So when that touch provably lies at or before gb, no other
 * sphere touches earlier and it is the answer. Otherwise the search goes
 * on; after a piece whose tail beyond gb has few candidates (its
 * half-strip, as in region_of) that tail is searched whole, which decides
 * the rest. Pieces only change which spheres are looked at when, never a
 * sign: a piece that cannot be bounded falls back to the whole tail.
 * Returns 1 when decided, 0 when the caller must search the whole tail,
 * or a negative VB_ status negated. */
static int search_tail(vbx_arcw *w, search *sr)
{
    vbx_tframe *f = sr->f;
    int fwd = sr->e1->inf;
    const vbx_arc_end *ev = fwd ? sr->e0 : sr->e1;
    vbx_touch *tp = fwd ? sr->first : sr->last;
    double sgn = fwd ? 1.0 : -1.0;
    if (!tp || !f->ok || f->kind != VBX_TRI_OPEN || ev->inf)
        return 0;
    vbx_ia G0 = fwd ? ev->key.G : vbx_ia_neg(ev->key.G);
    /* First length: the vertex's tangent radius s along the plane's G
     * direction (|EG| = 1 / |n|); any positive length would do. */
    double eg = 0.0;
    for (int k = 0; k < 3; k++) {
        double m = 0.5 * (f->EG[k].lo + f->EG[k].hi);
        eg += m * m;
    }
    double step = 0.25 * ev->key.S.hi / sqrt(eg);
    if (!(step > 0.0) || !(step < INFINITY) || !(G0.lo > -INFINITY) || !(G0.hi < INFINITY))
        return 0;
    double ga = G0.lo, gb = G0.hi + step;
    vbx_ia Sa = ev->key.S;
    size_t cap = TAIL_CAP_MIN;
    for (int piece = 0; piece < TAIL_PIECES; piece++) {
        if (!(gb < INFINITY))
            return 0;
        region rg;
        memset(&rg, 0, sizeof rg);
        piece_parts(f, Sa, ga, gb, sgn, PIECE_PARTS, &rg);
        w->cnt.tail_pieces++;
        int rc = scan_region(w, sr, &rg);
        if (rc != VB_OK)
            return -rc;
        if (rg.brute)
            return 0;
        if (tp->found && (fwd ? tp->key.G.hi <= gb : -tp->key.G.lo <= gb))
            return 1;
        region tail;
        tail_from(f, gb, sgn, &tail);
        /* (most arcs end within the first pieces: the strip is tried from
         * the TAIL_STRIP_FROM-th piece on) */
        int g = piece + 1 >= TAIL_STRIP_FROM ? gather_capped(w, f, &tail, cap) : 0;
        if (g < 0)
            return -VB_ENOMEM;
        if (g > 0) {
            /* gather_capped left the candidates in w->cand: scan them as
             * scan_region would (gather is not repeated). */
            w->cnt.tail_strips++;
            for (size_t i = 0; rc == VB_OK && i < w->ncand; i++) {
                uint32_t j = w->cand[i];
                if (j == f->t[0] || j == f->t[1] || j == f->t[2] ||
                    (w->set->contained && w->set->contained[j]))
                    continue;
                w->cnt.candidates++;
                if (clear_of(w, f, &tail, j))
                    continue;
                rc = candidate(w, sr, j);
            }
            clear_cands(w);
            return rc == VB_OK ? 1 : -rc;
        }
        Sa = branch_S(f, vbx_ia_point(gb < 0.0 ? -gb : gb));
        step *= 2.0;
        ga = gb;
        gb = gb + step;
        if (cap < 1u << 20)
            cap *= 2;
    }
    return 0;
}

int vbx_arc_search(vbx_arcw *w, vbx_tframe *f, vbx_arc_end *e0, vbx_arc_end *e1,
                   vbx_touch *first, vbx_touch *last)
{
    search sr = {f, e0, e1, f->kind == VBX_TRI_OPEN, 0, 0, first, last};
    if (first)
        first->found = 0;
    if (last)
        last->found = 0;
    if (!sr.open) {
        sr.loop = e0 == e1;
        if (!sr.loop) {
            int c = vbx_pos_cmp(w, f, &e0->key, NULL, &e1->key, NULL);
            if (c == 2) {
                if (need_end(w, f, e0) != VB_OK || need_end(w, f, e1) != VB_OK)
                    return VB_EDEGENERATE;
                c = vbx_pos_cmp(w, f, &e0->key, e0->x, &e1->key, e1->x);
            }
            sr.wrap = c > 0;
        }
    }
    if (sr.open && (e0->inf || e1->inf) && !(first && last)) {
        int d = search_tail(w, &sr);
        if (d < 0)
            return -d;
        if (d > 0)
            return VB_OK;
        if (first)
            first->found = 0;
        if (last)
            last->found = 0;
    }
    region rg;
    region_of(f, e0, e1, &rg);
    return scan_region(w, &sr, &rg);
}

int vbx_touch_certify(vbx_arcw *w, vbx_tframe *f, const vbx_touch *tp, double xyzt[4])
{
    vb_certifier *c = w->c;
    uint32_t q[4] = {f->t[0], f->t[1], f->t[2], tp->j};
    for (int i = 1; i < 4; i++)
        for (int k = i; k > 0 && q[k - 1] > q[k]; k--) {
            uint32_t x = q[k];
            q[k] = q[k - 1];
            q[k - 1] = x;
        }
    if (vbx_solve(&c->sol, q[0], q + 1) != VBX_SOLVED || tp->r >= c->sol.nroots) {
        vb_error(w->ctx, VB_EINTERNAL, NULL, 0, "arc closure: quadruple %u %u %u %u has no root %d",
                 q[0], q[1], q[2], q[3], tp->r);
        return -1;
    }
    const vbx_root *root = &c->sol.root[tp->r];
    vbx_ia box[4];
    int rc = vbx_root_coords(&c->sol, root, xyzt, box);
    if (rc != VB_OK) {
        vb_error(w->ctx, rc, NULL, 0, "cannot round an exact vertex to double");
        return -1;
    }
    if (!vbx_cert_defining(w->ctx, c, root, q, 4, box))
        return 0;
    int verdict;
    uint32_t intruder;
    vbx_cert_scan(w->ctx, c, root, q, 4, box, &verdict, &intruder);
    return verdict == VB_CERT_OK;
}
