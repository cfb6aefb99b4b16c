/* One atom's constrained cell measured over the boundaries of the regions
 * of directions its neighbours own (vbm_cell_stokes, vbm_cell.h).
 *
 * With r = Ri + probe, neighbour j (d = cj - ci, D = |d|, delta, N as in
 * vbm_nb) owns the directions
 *   Omega_j = {u.d >= k_j} and, for every other neighbour k whose cap meets
 *             the sphere, {N_k (u.d_j + delta_j) >= N_j (u.d_k + delta_k)},
 * an intersection of spherical caps (t_j <= r and t_j <= t_k; where
 * u.d_k + delta_k <= 0 the second holds by itself), bounded by circle arcs
 * (vbm_cap_arcs). The ball's sphere owns the rest, so
 *   SAS = r^2 (4 pi - sum_j |Omega_j|),
 *   volume = r^3 (4 pi - sum_j |Omega_j|) / 3 + sum_j int_{Omega_j} t_j^3 / 3.
 * Each integrand f depends on z = u.e (e = d / D) alone, so with
 * F(z) = int_z^1 f (F(1) = 0: F(z) dphi is smooth at e, and -e lies outside
 * the cap u.d >= k_j > -D) Stokes' theorem gives
 *   int_{Omega_j} f domega = sum over the arcs of int F(z) dphi,
 * phi the azimuth about e, dphi = e.(u x du) / (1 - z^2):
 *   area:   F = 1 - z,
 *   volume: F = N^3 (1 - z) (D (1 + z) + 2 delta) / (48 (D z + delta)^2 (D + delta)^2),
 *   contact (the face's area element t^2 sqrt(N + 2 delta q) / q per
 *   domega, q = D z + delta = N / (2 t), see cell_patches.c):
 *           F = N^2 / (4 D) (G(D + delta) - G(q)), G a primitive of
 *           sqrt(N + 2 delta q) / q^3 in closed form (vbm_contact_g, a log for
 *           delta != 0).
 * The integrals along each arc: arc_integral.c (vbm_arc_integrate). The
 * arrangement is decided by interval signs; where one
 * cannot be decided (tangent circles, more than three owners at a point,
 * symmetric inputs) the caller falls back to the patch integration. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_array.h"
#include "vbm_arc.h"
#include "vbm_caps.h"
#include "vbm_caps_cut.h"
#include "vbm_dot.h"
#include "vbm_cell.h"
#include "vbm_share.h"
#include "vb_measures.h"

#define FLOOR_FRACTION 1e-3 /* as cell_patches.c */
/* The first pass's contact targets: this many times each arc's share of
 * the floor (the area and volume: 100 times). A contact is mostly below
 * 100 floors (~0.11 A^2 for a carbon), so 100 left ~13 % of the arcs to a
 * second pass with --contacts (1crn, 1 thread: 30 gave 150712 pieces
 * against 158572 at 100, 152448 at 10, 167765 at 1). */
#define CON_FIRST_SCALE 30.0
#define FOUR_PI 12.566370614359172

typedef vbm_arcrec arcrec;
enum { AREA = VBM_AREA, VOL = VBM_VOL, CON = VBM_CON, NV = VBM_NV };

/* A neighbour whose cap u.e >= ca (sa = sqrt(1 - ca^2)) meets the sphere. */
typedef struct active {
    uint32_t j;
    vbx_ia e[3], ca, sa;
} active;

/* The bisector cap of two active neighbours y < z, kept for both regions
 * (region_caps): n = N_z d_y - N_y d_z, h = N_y delta_z - N_z delta_y
 * (y's cap against z; z's is exactly its negation) and n.n. Its circle
 * lies apart (stokes_work.paxis): the scan reads these 80 bytes of every
 * pair, the circle only of the pairs a region keeps. */
typedef struct paircap {
    vbx_ia n[3], h, nn;
} paircap;

typedef struct stokes_work {
    vbm_capwork cw;
    paircap *pair;     /* per pair y < z of the active neighbours, at pair_at(na, y, z) */
    vbm_circle *paxis; /* per pair: y's cap's circle, framed once a region framed it
                        * (kind 0: undecided) */
    uint8_t *pstate;   /* per pair: 0 not made yet, 1 the two caps apart, 2 made, 3 and its axis */
    vbm_share share;   /* the bisector arcs two regions share */
    vbm_cap *caps;
    vbm_circle *axes;  /* per cap of a region: its circle, no frame (the pair's) */
    uint32_t *capact;  /* per cap of a region: its active neighbour */
    arcrec *rec;
    active *act;
    vbx_ia *D, *con;   /* per neighbour: |d|, the contact */
    uint32_t *narcs;   /* per neighbour: its arcs */
    size_t cap_pstate, cap_caps, cap_axes, cap_capact, cap_rec, cap_act, cap_D, cap_con, cap_narcs, cap_pair, cap_paxis, nrec;
} stokes_work;

void vbm_stokes_free(void *p)
{
    stokes_work *w = p;
    if (!w)
        return;
    vbm_caps_free(&w->cw);
    vbm_share_free(&w->share);
    free(w->caps);
    free(w->axes);
    free(w->pair);
    free(w->paxis);
    free(w->pstate);
    free(w->capact);
    free(w->rec);
    free(w->act);
    free(w->D);
    free(w->con);
    free(w->narcs);
    free(w);
}


/* The pairs y < z of na active neighbours row by row (y's row holds z =
 * y + 1 .. na - 1): na (na - 1) / 2 entries, where the square table
 * (until stop 54) had na^2 with half never used. Region x's scan reads
 * its row after the diagonal in order and the rows above it one entry
 * each. */
static size_t pair_at(size_t na, size_t y, size_t z)
{
    return y * (2 * na - y - 1) / 2 + (z - y - 1);
}

/* The index of the pair of active neighbours x != y. */
static size_t pair_of(size_t na, size_t x, size_t y)
{
    return x < y ? pair_at(na, x, y) : pair_at(na, y, x);
}

/* vbx_ia_mul(a, b) bit for bit, by vbm_ia_mul_point where b is a point
 * (exact differences of coordinates and radii mostly are): its corners
 * a.lo b, a.hi b each come twice, and the least (greatest) of x, x, y, y
 * is that of x, y under vbx_min (vbx_max), as vbm_ia_mul_point takes it
 * (IEEE products commute). */
static vbx_ia mul_by(vbx_ia a, vbx_ia b)
{
    return b.lo == b.hi ? vbm_ia_mul_point(b.lo, a) : vbx_ia_mul(a, b);
}

static double width(vbx_ia a)
{
    double d = a.hi - a.lo;
    return d == d ? d : INFINITY;
}

/* The bisector cap of active neighbours y < z for both their regions: the
 * caps apart (the angle between the axes beyond the sum of the radii: the
 * test is symmetric), *state 1; else n, h and n.n, *state 2. The same
 * interval operations either region made before, once (negating an
 * interval difference is exact: z's cap is y's negated bit for bit). */
static void pair_cap(const vbm_atom_in *in, const stokes_work *w, size_t y, size_t z, paircap *pc,
                     uint8_t *state)
{
    const active *ay = &w->act[y], *az = &w->act[z];
    /* most pairs that meet are proven to at a point first (vbm_caps_cut.h:
     * the interval test would fail there; the same state) */
    if (!vbm_caps_meet_fast(ay->e, ay->ca, ay->sa, az->e, az->ca, az->sa) &&
        vbm_caps_apart(ay->e, ay->ca, ay->sa, az->e, az->ca, az->sa)) {
        *state = 1;
        return;
    }
    const vbm_nb *ny = &in->nb[ay->j], *nz = &in->nb[az->j];
    for (int i = 0; i < 3; i++)
        pc->n[i] = vbx_ia_sub(mul_by(nz->N, ny->d[i]), mul_by(ny->N, nz->d[i]));
    pc->h = vbx_ia_sub(mul_by(ny->N, nz->delta), mul_by(nz->N, ny->delta));
    pc->nn = vbm_dot3(pc->n, pc->n);
    *state = 2;
}

/* The circle of the complementary cap (-n, -h) exactly: |n| is the same
 * and n.n - h^2's factors swap, so its axis and cosine are negated bit for
 * bit, its sine the same, ALL and NONE swap, and its frame (made from the
 * negated axis) is (-e1, e2) (test_share_arcs checks it on 2000 caps). */
static void circle_negated(const vbm_circle *a, vbm_circle *b)
{
    for (int k = 0; k < 3; k++) {
        b->a[k] = vbx_ia_neg(a->a[k]);
        b->e1[k] = vbx_ia_neg(a->e1[k]);
        b->e2[k] = a->e2[k];
    }
    b->c = vbx_ia_neg(a->c);
    b->s = a->s;
    b->kind = a->kind == VBM_CAP_ALL ? VBM_CAP_NONE : a->kind == VBM_CAP_NONE ? VBM_CAP_ALL : a->kind;
    b->framed = a->framed;
}

/* The frames region x's search made (w->cw.circ) kept with their pairs for
 * the other region of each (nc caps, w->capact). */
static void keep_frames(stokes_work *w, size_t na, size_t x, size_t nc)
{
    for (size_t c = 1; c < nc && c < w->cw.ncirc; c++) {
        size_t y = w->capact[c], pk = pair_of(na, x, y);
        vbm_circle *ax = &w->paxis[pk];
        if (w->pstate[pk] != 3 || ax->framed || !w->cw.circ[c].framed)
            continue;
        if (x < y)
            *ax = w->cw.circ[c];
        else
            circle_negated(&w->cw.circ[c], ax);
    }
}

/* The caps of Omega_j: j's own, then those of the other active neighbours
 * that may cut it. Returns the count, 0 when Omega_j is proven empty. */
static size_t region_caps(const vbm_atom_in *in, stokes_work *w, size_t na, size_t x)
{
    const active *aj = &w->act[x];
    const vbm_nb *nj = &in->nb[aj->j];
    vbm_cap *cp = w->caps;
    for (int k = 0; k < 3; k++)
        cp[0].n[k] = nj->d[k];
    cp[0].h = nj->k;
    w->capact[0] = (uint32_t)x;
    size_t nc = 1;
    vbx_ia sa = aj->ca.lo >= 0.0 ? aj->sa : vbx_ia_point(1.0), sa2 = vbx_ia_sqr(sa);
    /* the others from the largest cap down (sort_active: smallest first):
     * the cap that proves Omega_j empty is mostly a large one (c1k: 9,772
     * of the 14,646 proofs in the last 40 % of the order), so the scan ends
     * sooner; the caps kept are put back in index order below, and which
     * cap proves it empty does not change that it is: the same caps, the
     * same bits */
    for (size_t y = na; y-- > 0;) {
        if (y == x)
            continue;
        size_t pk = pair_of(na, x, y);
        paircap *pc = &w->pair[pk];
        uint8_t *st = &w->pstate[pk];
        if (*st == 0)
            pair_cap(in, w, x < y ? x : y, x < y ? y : x, pc, st);
        if (*st == 1)
            continue; /* caps apart: k owns nothing in j's cap */
        vbm_cap c; /* j's cap against k: the pair's, negated when j comes second */
        for (int i = 0; i < 3; i++)
            c.n[i] = x < y ? pc->n[i] : vbx_ia_neg(pc->n[i]);
        c.h = x < y ? pc->h : vbx_ia_neg(pc->h);
        /* all of j's cap on j's side, none of it, or kept (vbm_cut_test;
         * most caps kept are proven so at a point first, the same
         * decision: vbm_caps_cut.h) */
        int cut = vbm_cut_keep_fast(aj->e, aj->ca, sa2, c.n, c.h, pc->nn)
                      ? 0
                      : vbm_cut_test(aj->e, aj->ca, sa2, c.n, c.h, pc->nn);
        if (cut == 1)
            continue; /* all of j's cap is on j's side */
        if (cut == 2)
            return 0; /* none of it */
        w->capact[nc] = (uint32_t)y;
        cp[nc++] = c;
    }
    for (size_t a = 1, b = nc - 1; a < b; a++, b--) {
        vbm_cap t = cp[a];
        uint32_t ta = w->capact[a];
        cp[a] = cp[b];
        cp[b] = t;
        w->capact[a] = w->capact[b];
        w->capact[b] = ta;
    }
    /* the kept caps' circles, made once the region is not proven empty
     * (14,646 of c1k's 31,568 regions are, often after caps were kept):
     * each pair's for the first region that keeps it, the same bits */
    for (size_t c = 1; c < nc; c++) {
        size_t y = w->capact[c], pk = pair_of(na, x, y);
        vbm_circle *ax = &w->paxis[pk];
        if (w->pstate[pk] == 2) {
            const paircap *pc = &w->pair[pk];
            vbm_cap cy = {{pc->n[0], pc->n[1], pc->n[2]}, pc->h};
            if (!vbm_circle_axis_nn(&cy, pc->nn, ax)) /* nn = vbm_dot3(n, n): the same bits */
                ax->kind = 0;
            w->pstate[pk] = 3;
        }
        if (x < y)
            w->axes[c] = *ax;
        else
            circle_negated(ax, &w->axes[c]);
    }
    if (!vbm_circle_axis(&cp[0], &w->axes[0]))
        w->axes[0].kind = 0;
    return nc;
}

/* The volume and SAS from the arcs' integrals (in a fixed order: the same
 * bytes whatever the threads). */
static void total(const vbm_atom_in *in, const stokes_work *w, vbm_atom_out *out)
{
    vbx_ia area = vbx_ia_point(0.0), vol = vbx_ia_point(0.0);
    for (size_t i = 0; i < w->nrec; i++) {
        area = vbx_ia_add(area, w->rec[i].v[AREA]);
        vol = vbx_ia_add(vol, w->rec[i].v[VOL]);
    }
    vbx_ia four_pi = {vbx_pred(FOUR_PI), vbx_succ(FOUR_PI)};
    vbx_ia ball = vbx_ia_sub(four_pi, area); /* the sphere's solid angle */
    vbx_ia r2 = vbx_ia_sqr(in->r);
    out->sas = vbx_ia_mul(r2, ball);
    out->vol = vbx_ia_add(vbx_ia_div(vbx_ia_mul(vbx_ia_mul(r2, in->r), ball), vbx_ia_point(3.0)),
                          vol);
}

/* The contact of each neighbour: the sum of its arcs' (w->con, w->narcs). */
static void contacts(const vbm_atom_in *in, stokes_work *w)
{
    for (size_t j = 0; j < in->nnb; j++) {
        w->con[j] = vbx_ia_point(0.0);
        w->narcs[j] = 0;
    }
    for (size_t i = 0; i < w->nrec; i++) {
        uint32_t j = w->rec[i].j;
        w->con[j] = vbx_ia_add(w->con[j], w->rec[i].v[CON]);
        w->narcs[j]++;
    }
}

/* Lower bound of |x| for x in a (0 when a holds 0). */
static double magnitude_lo(vbx_ia a)
{
    return a.lo > 0.0 ? a.lo : a.hi < 0.0 ? -a.hi : 0.0;
}

/* Integrates every arc (again) whose widths exceed the targets: volume
 * and SAS shares of tv and ts, each contact's share of its target
 * (tolerance times the larger of its value, in the second pass, and its
 * floor, vbm_contact_floor); `scale` multiplies every target. Returns 0
 * when an interval cannot bound an arc. */
static int integrate_arcs(const vbm_atom_in *in, stokes_work *w, double tv, double ts,
                          double scale, size_t *pieces)
{
    double rr = in->r.hi, r3 = rr * rr * rr / 3.0, n = (double)(w->nrec + 1);
    double tg[NV];
    tg[AREA] = scale * vbx_min(0.5 * ts / (rr * rr), 0.25 * tv / r3) / n;
    tg[VOL] = scale * 0.25 * tv / n;
    vbm_owner o; /* the last region's constants: its arcs come one after another */
    uint32_t oj = UINT32_MAX;
    for (size_t i = 0; i < w->nrec; i++) {
        arcrec *a = &w->rec[i];
        uint32_t j = a->j;
        double tc = in->tolerance * vbx_max(scale > 1.0 ? 0.0 : magnitude_lo(w->con[j]),
                                            vbm_contact_floor(in, j));
        double cs = scale > 1.0 ? CON_FIRST_SCALE : scale;
        tg[CON] = in->contacts && in->nb[j].con ? cs * 0.5 * tc / (double)(w->narcs[j] + 1)
                                                : INFINITY;
        if (scale <= 1.0 && !vbm_arc_over(a->v, tg))
            continue;
        if (j != oj && !vbm_owner_make(in, j, w->D[j], &o))
            return 0;
        oj = j;
        if (!vbm_arc_integrate(&o, a, tg, scale <= 1.0, pieces))
            return 0;
    }
    return 1;
}

/* out->pairs: the contacts with hi > 0. Returns 0 on ENOMEM. */
static int pairs(const vbm_atom_in *in, const stokes_work *w, vbm_atom_out *out)
{
    size_t np = 0;
    for (size_t j = 0; j < in->nnb; j++)
        np += in->nb[j].con && w->narcs[j] && w->con[j].hi > 0.0;
    if (!np)
        return 1;
    out->pairs = malloc(np * sizeof *out->pairs);
    if (!out->pairs)
        return 0;
    for (size_t j = 0; j < in->nnb; j++)
        if (in->nb[j].con && w->narcs[j] && w->con[j].hi > 0.0) {
            vbm_pair p = {(uint32_t)j, w->con[j]};
            out->pairs[out->npairs++] = p;
        }
    return 1;
}

/* Whether active a comes before b: the smaller cap first (cos of its
 * angular radius larger, on midpoints), then the lower neighbour index. */
static int act_before(const active *a, const active *b)
{
    double x = vbx_ia_mid(a->ca), y = vbx_ia_mid(b->ca);
    return x != y ? x > y : a->j < b->j;
}

/* The regions bounded smallest cap first (insertion sort: a fixed order
 * whatever the threads). Small caps are the ones most often proven empty
 * (likely_boundary, cheaply), and an empty region's circles are then known
 * to hold no arc for every region after it (vbm_share.h): fewer circles
 * searched there. Only the order of work and of the sums changes (1crn,
 * 1 thread: 0.49 s of CPU; neighbour order 0.52 s, largest cap first
 * 0.56 s). */
static void sort_active(active *act, size_t na)
{
    for (size_t i = 1; i < na; i++) {
        active t = act[i];
        size_t k = i;
        for (; k > 0 && act_before(&t, &act[k - 1]); k--)
            act[k] = act[k - 1];
        act[k] = t;
    }
}

int vbm_cell_stokes(const vbm_atom_in *in, vbm_scratch *sc, vbm_atom_out *out)
{
    memset(out, 0, sizeof *out);
    if (!sc->stokes && !(sc->stokes = calloc(1, sizeof(stokes_work))))
        return -1;
    stokes_work *w = sc->stokes;
    size_t m = in->nnb;
    double t0 = in->clock ? vb_now() : 0.0;
    if (VB_ARRAY_FIT(w->D, w->cap_D, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->act, w->cap_act, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->caps, w->cap_caps, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->axes, w->cap_axes, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->capact, w->cap_capact, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->con, w->cap_con, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->narcs, w->cap_narcs, m + 1, 64) != VB_OK)
        return -1;
    /* the neighbours whose caps meet the sphere: k < D */
    size_t na = 0;
    for (size_t j = 0; j < m; j++) {
        const vbm_nb *n = &in->nb[j];
        if (!(n->N.lo > 0.0))
            return 0;
        w->D[j] = vbx_ia_sqrt(vbm_dot3(n->d, n->d));
        vbx_ia g = vbx_ia_sub(w->D[j], n->k);
        if (g.hi < 0.0)
            continue;
        if (!(g.lo > 0.0))
            return 0;
        active *a = &w->act[na++];
        a->j = (uint32_t)j;
        for (int k = 0; k < 3; k++)
            a->e[k] = vbx_ia_div(n->d[k], w->D[j]);
        a->ca = vbx_ia_div(n->k, w->D[j]);
        a->sa = vbx_ia_sqrt(vbx_ia_sub(vbx_ia_point(1.0), vbx_ia_sqr(a->ca)));
    }
    sort_active(w->act, na);
    size_t npair = na * (na - (na > 0)) / 2;
    if (VB_ARRAY_FIT(w->pair, w->cap_pair, npair + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->paxis, w->cap_paxis, npair + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->pstate, w->cap_pstate, npair + 1, 64) != VB_OK)
        return -1;
    memset(w->pstate, 0, npair);
    /* the regions in order, each bisector circle's arcs found for the
     * first of its two regions and given to the second (vbm_share.h) */
    w->nrec = 0;
    vbm_share_reset(&w->share);
    for (size_t x = 0; x < na; x++) {
        uint32_t j = w->act[x].j;
        size_t nc = region_caps(in, w, na, x);
        t0 = vbm_lap(in->clock, VB_CELL_CAPS, t0);
        if (nc == 0) {
            if (vbm_share_pending(&w->share, (uint32_t)x))
                return 0; /* arcs of a region proven empty: leave it to the patches */
            continue;
        }
        int e = vbm_share_given(&w->share, (uint32_t)x, w->capact, nc, na);
        if (e <= 0)
            return e;
        e = vbm_cap_arcs(w->caps, w->axes, nc, w->share.known, w->share.given, w->share.ngiven, &w->cw);
        if (e <= 0)
            return e;
        keep_frames(w, na, x, nc);
        if (vbm_share_keep(&w->share, (uint32_t)x, w->capact, w->cw.arc, w->cw.narc) < 0)
            return -1;
        if (VB_ARRAY_FIT(w->rec, w->cap_rec, w->nrec + w->cw.narc, 64) != VB_OK)
            return -1;
        const vbx_ia *ej = w->act[x].e;
        for (size_t i = 0; i < w->cw.narc; i++) {
            const vbm_arc *a = &w->cw.arc[i];
            const vbm_circle *C = &w->cw.circ[a->cap];
            arcrec *r = &w->rec[w->nrec++];
            r->j = j;
            r->own = a->cap == 0;
            r->c = C->c;
            r->s = C->s;
            r->A0 = vbm_dot3(ej, C->a);
            r->A1 = vbm_dot3(ej, C->e1);
            r->A2 = vbm_dot3(ej, C->e2);
            memcpy(r->p, a->p, sizeof r->p);
            memcpy(r->q, a->q, sizeof r->q);
            r->tp = a->tp;
            r->tq = a->tq;
            for (int k = 0; k < NV; k++) /* contacts() counts arcs before any is integrated */
                r->v[k] = vbx_ia_point(0.0);
        }
        t0 = vbm_lap(in->clock, VB_CELL_ARRANGE, t0);
    }
    /* every arc to a hundred times its share of the floors of the targets
     * (tolerance * max(|value|, floor), cell_patches.c), then the arcs wider
     * than their share of the targets of the values found, halved until
     * they meet it */
    double rr = in->r.hi, r3 = rr * rr * rr / 3.0;
    double fv = FLOOR_FRACTION * FOUR_PI * r3, fa = FLOOR_FRACTION * FOUR_PI * rr * rr;
    size_t pieces = 0;
    contacts(in, w); /* the arc counts */
    if (!integrate_arcs(in, w, in->tolerance * fv, in->tolerance * fa, 100, &pieces))
        return 0;
    total(in, w, out);
    contacts(in, w);
    double tgv = in->tolerance * vbx_max(magnitude_lo(out->vol), fv);
    double tgs = in->tolerance * vbx_max(magnitude_lo(out->sas), fa);
    if (!integrate_arcs(in, w, tgv, tgs, 1.0, &pieces))
        return 0;
    total(in, w, out);
    contacts(in, w);
    out->patches = pieces;
    double mv = fabs(vbx_ia_mid(out->vol)), ms = fabs(vbx_ia_mid(out->sas));
    out->loose = width(out->vol) > in->tolerance * vbx_max(mv, fv) ||
                 width(out->sas) > in->tolerance * vbx_max(ms, fa);
    for (size_t j = 0; in->contacts && j < in->nnb; j++)
        if (in->nb[j].con && w->narcs[j] &&
            width(w->con[j]) >
                in->tolerance * vbx_max(fabs(vbx_ia_mid(w->con[j])), vbm_contact_floor(in, j)))
            out->loose = 1;
    if (in->contacts && !pairs(in, w, out))
        return -1;
    vbm_lap(in->clock, VB_CELL_INTEGRALS, t0);
    return 1;
}
