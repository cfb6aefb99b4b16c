/* The first sphere that touches along an arc of a trisector (vbx_arc.h):
 * the candidates of a provably conservative region of the arc
 * (arc_region.c says why they are complete), their roots on the curve, and
 * the positions of those roots against the arc's ends.
 *
 * Each candidate first gets the fine test (L_j > 0 over the region:
 * skipped); for the rest the roots of T + j are placed, filtered
 * (verify/exact/quad_filter.c) and exactly where the filter cannot place
 * them. A member of an end's vertex
 * has that end as one of its two roots: when exactly one root's position
 * cannot be told from that end and the other's can, the first is the end. */
#include <stdlib.h>
#include <float.h>
#include <string.h>

#include "vbx_region.h"

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
        ky.G = ky.S = ky.val = (vbx_ia){-INFINITY, INFINITY};
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
    int ls = c->qd.ok ? ops->line(&c->qd, q, &L) : VBX_QL_EXACT;
    int fs = ls == VBX_QL_LINE ? ops->prep(&L, &P) : VBX_QF_EXACT;
    if (ls == VBX_QL_LINE)
        w->cnt.exact_evals += (uint64_t)P.delta_exact;
    /* Rank < 3: the exact solver has no root either. */
    if (fs == VBX_QF_NONE || ls == VBX_QL_FLAT)
        return VB_OK;
    /* The one root of delta = 0 takes the exact path, as before. */
    if (fs == VBX_QF_EXACT || fs == VBX_QF_ONE) {
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

/* Offers the candidates already gathered in w->cand for region rg to the
 * search (the frame's own spheres, contained ones and those rg's bound
 * clears are skipped), then clears w->cand; rc is the gather's status: on
 * an error nothing is offered and rc comes back. */
static int offer_gathered(vbx_arcw *w, search *sr, vbx_region *rg, int rc)
{
    vbx_tframe *f = sr->f;
    for (size_t i = 0; rc == VB_OK && i < w->ncand; i++) {
        uint32_t j = w->cand[i];
        if (j == f->t[0] || j == f->t[1] || j == f->t[2] ||
            (w->set->contained && w->set->contained[j]))
            continue;
        w->cnt.candidates++;
        if (vbx_clear_of(w, f, rg, j))
            continue;
        rc = candidate(w, sr, j);
    }
    vbx_clear_cands(w);
    return rc;
}

/* The candidates of region rg offered to the search (see the top). */
static int scan_region(vbx_arcw *w, search *sr, vbx_region *rg)
{
    return offer_gathered(w, sr, rg, vbx_gather(w, sr->f, rg));
}

enum { TAIL_PIECES = 48, TAIL_CAP_MIN = 64, TAIL_STRIP_FROM = 2 };

/* The region of a piece of a tail from position start (an enclosure) to
 * mirrored position gb (the point P at G = sgn gb): the apex of the
 * piece's tangent triangle and P (vbx_apex_box). Enough for the search
 * below: a sphere that L_j > 0 clears at both is > 0 on the piece's open
 * arc and at P when L_j >= 0 at the piece's start, which holds at the
 * first piece's start (a certified vertex) and, for every sphere not yet
 * offered, at each later one (the previous piece's P, cleared there).
 * 1 when set, 0 when the apex cannot be bounded. */
static int tail_triangle(const vbx_tframe *f, vbx_ia start, double gb, double sgn,
                         vbx_region *rg)
{
    vbx_ia end = vbx_ia_point(sgn * gb);
    if (!vbx_apex_box(f, sgn > 0 ? start : end, sgn > 0 ? end : start, &rg->p[0]))
        return 0;
    vbx_part *p = &rg->p[1];
    p->kind = VBX_PART_BOX;
    p->S = vbx_branch_S(f, vbx_ia_point(gb < 0.0 ? -gb : gb));
    p->G = end;
    rg->n = 2;
    return 1;
}

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
        vbx_region rg;
        vbx_region_clear(&rg);
        if (!tail_triangle(f, piece ? vbx_ia_point(sgn * ga) : ev->key.G, gb, sgn, &rg))
            vbx_piece_parts(f, Sa, ga, gb, sgn, VBX_PIECE_PARTS, &rg);
        w->cnt.tail_pieces++;
        int rc = scan_region(w, sr, &rg);
        if (rc != VB_OK)
            return -rc;
        if (rg.brute)
            return 0;
        if (tp->found && (fwd ? tp->key.G.hi <= gb : -tp->key.G.lo <= gb))
            return 1;
        vbx_region tail;
        vbx_tail_from(f, gb, sgn, &tail);
        /* (most arcs end within the first pieces: the strip is tried from
         * the TAIL_STRIP_FROM-th piece on) */
        int g = piece + 1 >= TAIL_STRIP_FROM ? vbx_gather_capped(w, f, &tail, cap) : 0;
        if (g < 0)
            return -VB_ENOMEM;
        if (g > 0) {
            /* gather_capped left the candidates in w->cand: scan them as
             * scan_region would (gather is not repeated). */
            w->cnt.tail_strips++;
            rc = offer_gathered(w, sr, &tail, VB_OK);
            return rc == VB_OK ? 1 : -rc;
        }
        Sa = vbx_branch_S(f, vbx_ia_point(gb < 0.0 ? -gb : gb));
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
    vbx_region rg;
    vbx_region_clear(&rg);
    if (sr.open && vbx_apex_point(w, f, e0, e1, &rg))
        return scan_region(w, &sr, &rg);
    /* every other region is drawn in the plane's frame */
    vbx_tframe_plane(f);
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
    vbx_region_of(f, e0, e1, &rg);
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
    if (vbx_cert_round(w->ctx, c, root, xyzt, box) != VB_OK)
        return -1;
    if (!vbx_cert_defining(w->ctx, c, root, q, 4, box))
        return 0;
    int verdict;
    uint32_t intruder;
    vbx_cert_scan(w->ctx, c, root, q, 4, box, &verdict, &intruder);
    return verdict == VB_CERT_OK;
}
