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
 *   volume: F = N^3 (1 - z) (D (1 + z) + 2 delta) / (48 (D z + delta)^2 (D + delta)^2).
 * On the arcs of j's own cap circle z is constant and dphi the arc's angle
 * (closed form, atan rounded outward by MPFR); on the others the integral
 * runs over t = tan(angle / 2) about the arc's middle (|t| < 0.7), the
 * integrand a rational function of t, enclosed by univariate Taylor models
 * (vbm_series1.h) on pieces halved until each meets its share of the
 * tolerance. The arrangement is decided by interval signs; where one
 * cannot be decided (tangent circles, more than three owners at a point,
 * symmetric inputs) the caller falls back to the patch integration. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vbm_caps.h"
#include "vbm_cell.h"
#include "vbm_piece.h"
#include "vbm_series1.h"

#define FLOOR_FRACTION 1e-3 /* as cell_patches.c */
#define MAX_DEPTH 20        /* halvings of an arc's parameter range */
#define FOUR_PI 12.566370614359172

typedef struct arcrec {
    uint32_t j;
    int own;                   /* the arc lies on j's cap circle */
    vbx_ia c, s, A0, A1, A2;   /* the circle, and e_j in its frame */
    vbx_ia p[2], q[2];
    double tp, tq;
    vbx_ia area, vol;          /* the arc's integrals */
} arcrec;

/* A neighbour whose cap u.e >= ca (sa = sqrt(1 - ca^2)) meets the sphere. */
typedef struct active {
    uint32_t j;
    vbx_ia e[3], ca, sa;
} active;

typedef struct stokes_work {
    vbm_capwork cw;
    vbm_cap *caps;
    arcrec *rec;
    active *act;
    vbx_ia *D;
    size_t cap_caps, cap_rec, cap_act, cap_D, nrec;
} stokes_work;

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

void vbm_stokes_free(void *p)
{
    stokes_work *w = p;
    if (!w)
        return;
    vbm_caps_free(&w->cw);
    free(w->caps);
    free(w->rec);
    free(w->act);
    free(w->D);
    free(w);
}

static vbx_ia dot3(const vbx_ia *a, const vbx_ia *b)
{
    return vbx_ia_add(vbx_ia_add(vbx_ia_mul(a[0], b[0]), vbx_ia_mul(a[1], b[1])),
                      vbx_ia_mul(a[2], b[2]));
}

static double width(vbx_ia a)
{
    double d = a.hi - a.lo;
    return d == d ? d : INFINITY;
}

/* The per-neighbour constants of the integrands. */
typedef struct owner {
    vbx_ia D, delta, K; /* K = N^3 / (48 (D + delta)^2) */
} owner;

static owner owner_of(const vbm_nb *n, vbx_ia D)
{
    owner o = {D, n->delta, vbx_ia_point(0.0)};
    vbx_ia N3 = vbx_ia_mul(vbx_ia_sqr(n->N), n->N);
    o.K = vbx_ia_div(N3, vbx_ia_mul(vbx_ia_point(48.0), vbx_ia_sqr(vbx_ia_add(D, n->delta))));
    return o;
}

/* F_vol(z) / (1 - z) = K (D (1 + z) + 2 delta) / (D z + delta)^2 */
static vbx_ia fvol_over(const owner *o, vbx_ia z)
{
    vbx_ia q = vbx_ia_add(vbx_ia_mul(o->D, z), o->delta);
    vbx_ia t = vbx_ia_add(vbx_ia_mul(o->D, vbx_ia_add(vbx_ia_point(1.0), z)),
                          vbx_ia_add(o->delta, o->delta));
    return vbx_ia_div(vbx_ia_mul(o->K, t), vbx_ia_sqr(q));
}

/* The integrands along a circle arc in t: area F dphi/dt and volume. */
typedef struct arcfun {
    owner o;
    vbx_ia cA0, s, sA0s, mcs, A1, A2; /* c A0, s, s^2 A0, -c s, e_j in the rotated frame */
} arcfun;

static int integrand(const arcfun *f, vbx_ia at, vbm_s1 *area, vbm_s1 *vol)
{
    vbm_s1 T, T2, rec, cs, sn, w, z, num, t, u, opz;
    vbm1_var(&T, at);
    vbm1_mul(&T2, &T, &T);
    T2.c[0] = vbx_ia_add(T2.c[0], vbx_ia_point(1.0));
    if (!vbm1_recip(&rec, &T2))
        return 0;
    vbm1_affine(&cs, vbx_ia_point(2.0), &rec, vbx_ia_point(-1.0)); /* (1 - T^2) / (1 + T^2) */
    vbm1_mul(&t, &T, &rec);
    vbm1_affine(&sn, vbx_ia_point(2.0), &t, vbx_ia_point(0.0)); /* 2 T / (1 + T^2) */
    vbm1_affine(&w, f->A1, &cs, vbx_ia_point(0.0));
    vbm1_affine(&t, f->A2, &sn, vbx_ia_point(0.0));
    vbm1_add(&w, &w, &t);
    vbm1_affine(&z, f->s, &w, f->cA0);
    vbm1_affine(&num, f->mcs, &w, f->sA0s);
    vbm1_mul(&t, &num, &rec);
    vbm1_affine(&num, vbx_ia_point(2.0), &t, vbx_ia_point(0.0)); /* e.(u x du/dt) */
    vbm1_affine(&opz, vbx_ia_point(1.0), &z, vbx_ia_point(1.0));
    if (!vbm1_recip(&u, &opz))
        return 0;
    vbm1_mul(area, &num, &u); /* (1 - z) dphi = num / (1 + z) */
    vbm1_affine(&t, f->o.D, &z, f->o.delta);
    if (!vbm1_recip(&u, &t))
        return 0;
    vbm1_mul(&t, &u, &u);
    vbm1_affine(&u, f->o.D, &opz, vbx_ia_add(f->o.delta, f->o.delta));
    vbm1_mul(&T, &t, &u);
    vbm1_mul(&t, &T, area);
    vbm1_affine(vol, f->o.K, &t, vbx_ia_point(0.0));
    return 1;
}

typedef struct sums {
    vbx_ia area, vol;
    size_t pieces;
    int loose;
} sums;

static int piece(const arcfun *f, double x0, double x1, double ta, double tv, int depth, sums *out)
{
    double xc = 0.5 * (x0 + x1);
    vbm_s1 ca, cv, ba, bv;
    vbx_ia box = {x0, x1};
    if (!integrand(f, vbx_ia_point(xc), &ca, &cv) || !integrand(f, box, &ba, &bv))
        return 0;
    vbx_ia a = vbm1_integrate(&ca, &ba, xc, x0, x1), v = vbm1_integrate(&cv, &bv, xc, x0, x1);
    if ((width(a) > ta || width(v) > tv) && depth < MAX_DEPTH && xc > x0 && xc < x1)
        return piece(f, x0, xc, 0.5 * ta, 0.5 * tv, depth + 1, out) &&
               piece(f, xc, x1, 0.5 * ta, 0.5 * tv, depth + 1, out);
    if (width(a) > ta || width(v) > tv)
        out->loose = 1;
    out->area = vbx_ia_add(out->area, a);
    out->vol = vbx_ia_add(out->vol, v);
    out->pieces++;
    return 1;
}

/* The integral from the exact end t (an interval) to the double m inside
 * it: (m - t) times the integrand somewhere in t. */
static int end_piece(const arcfun *f, vbx_ia t, double m, sums *out)
{
    vbm_s1 a, v;
    if (!integrand(f, t, &a, &v))
        return 0;
    vbx_ia dt = vbx_ia_sub(vbx_ia_point(m), t);
    out->area = vbx_ia_add(out->area, vbx_ia_mul(dt, a.c[0]));
    out->vol = vbx_ia_add(out->vol, vbx_ia_mul(dt, v.c[0]));
    return 1;
}

/* t = tan(angle / 2) of the unit vector (x, y) rotated by -mid. */
static vbx_ia half_tan(vbx_ia x, vbx_ia y, vbx_ia cm, vbx_ia sm)
{
    vbx_ia xr = vbx_ia_add(vbx_ia_mul(x, cm), vbx_ia_mul(y, sm));
    vbx_ia yr = vbx_ia_sub(vbx_ia_mul(y, cm), vbx_ia_mul(x, sm));
    return vbx_ia_div(yr, vbx_ia_add(vbx_ia_point(1.0), xr));
}

static int integrate_arc(const vbm_atom_in *in, const stokes_work *w, const arcrec *a, double ta,
                         double tv, sums *out)
{
    vbx_ia cm, sm;
    vbm_unit_at(0.5 * (a->tp + a->tq), &cm, &sm);
    vbx_ia t0 = half_tan(a->p[0], a->p[1], cm, sm), t1 = half_tan(a->q[0], a->q[1], cm, sm);
    if (!(t1.lo > t0.hi))
        return 0;
    owner o = owner_of(&in->nb[a->j], w->D[a->j]);
    if (a->own) { /* z = c: F(c) times the angle 2 (atan t1 - atan t0) */
        vbx_ia ang = vbx_ia_sub(vbm_ia_atan(t1), vbm_ia_atan(t0));
        ang = vbx_ia_add(ang, ang);
        vbx_ia omz = vbx_ia_sub(vbx_ia_point(1.0), a->c);
        out->area = vbx_ia_add(out->area, vbx_ia_mul(omz, ang));
        out->vol = vbx_ia_add(out->vol, vbx_ia_mul(vbx_ia_mul(omz, fvol_over(&o, a->c)), ang));
        out->pieces++;
        return 1;
    }
    arcfun f;
    f.o = o;
    f.cA0 = vbx_ia_mul(a->c, a->A0);
    f.s = a->s;
    f.sA0s = vbx_ia_mul(vbx_ia_sqr(a->s), a->A0);
    f.mcs = vbx_ia_neg(vbx_ia_mul(a->c, a->s));
    f.A1 = vbx_ia_add(vbx_ia_mul(a->A1, cm), vbx_ia_mul(a->A2, sm));
    f.A2 = vbx_ia_sub(vbx_ia_mul(a->A2, cm), vbx_ia_mul(a->A1, sm));
    double m0 = vbx_ia_mid(t0), m1 = vbx_ia_mid(t1);
    return end_piece(&f, t0, m0, out) && piece(&f, m0, m1, ta, tv, 0, out) &&
           end_piece(&f, t1, m1, out) ? 1 : 0;
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
    size_t nc = 1;
    vbx_ia sa = aj->ca.lo >= 0.0 ? aj->sa : vbx_ia_point(1.0);
    for (size_t y = 0; y < na; y++) {
        const active *ak = &w->act[y];
        if (y == x)
            continue;
        /* caps apart (angle between the axes > the sum of the radii): k
         * owns nothing in j's cap */
        vbx_ia cs = vbx_ia_sub(vbx_ia_mul(aj->ca, ak->ca), vbx_ia_mul(aj->sa, ak->sa));
        vbx_ia sn = vbx_ia_add(vbx_ia_mul(aj->sa, ak->ca), vbx_ia_mul(aj->ca, ak->sa));
        if (sn.lo > 0.0 && dot3(aj->e, ak->e).hi < cs.lo)
            continue;
        const vbm_nb *nk = &in->nb[ak->j];
        vbm_cap c;
        for (int i = 0; i < 3; i++)
            c.n[i] = vbx_ia_sub(vbx_ia_mul(nk->N, nj->d[i]), vbx_ia_mul(nj->N, nk->d[i]));
        c.h = vbx_ia_sub(vbx_ia_mul(nj->N, nk->delta), vbx_ia_mul(nk->N, nj->delta));
        /* over j's cap (u.e = z in [ca, 1], |u_perp| <= sa) u.n lies in
         * z (e.n) +- sa |n_perp| */
        vbx_ia en = dot3(aj->e, c.n);
        vbx_ia perp = vbx_ia_sqrt(vbx_ia_sub(dot3(c.n, c.n), vbx_ia_sqr(en)));
        vbx_ia spread = vbx_ia_mul(sa, perp);
        double lo = vbx_min(vbx_ia_mul(aj->ca, en).lo, en.lo) - spread.hi;
        double hi = vbx_max(vbx_ia_mul(aj->ca, en).hi, en.hi) + spread.hi;
        if (vbx_pred(lo) > c.h.hi)
            continue; /* all of j's cap is on j's side */
        if (vbx_succ(hi) < c.h.lo)
            return 0; /* none of it */
        cp[nc++] = c;
    }
    return nc;
}

/* A lower bound of |x| for x in a (0 when a holds 0). */
static double magnitude_lo(vbx_ia a)
{
    return a.lo > 0.0 ? a.lo : a.hi < 0.0 ? -a.hi : 0.0;
}

/* The volume and SAS from the arcs' integrals (in a fixed order: the same
 * bytes whatever the threads). */
static void total(const vbm_atom_in *in, const stokes_work *w, vbm_atom_out *out)
{
    vbx_ia area = vbx_ia_point(0.0), vol = vbx_ia_point(0.0);
    for (size_t i = 0; i < w->nrec; i++) {
        area = vbx_ia_add(area, w->rec[i].area);
        vol = vbx_ia_add(vol, w->rec[i].vol);
    }
    vbx_ia four_pi = {vbx_pred(FOUR_PI), vbx_succ(FOUR_PI)};
    vbx_ia ball = vbx_ia_sub(four_pi, area); /* the sphere's solid angle */
    vbx_ia r2 = vbx_ia_sqr(in->r);
    out->sas = vbx_ia_mul(r2, ball);
    out->vol = vbx_ia_add(vbx_ia_div(vbx_ia_mul(vbx_ia_mul(r2, in->r), ball), vbx_ia_point(3.0)),
                          vol);
}

int vbm_cell_stokes(const vbm_atom_in *in, vbm_scratch *sc, vbm_atom_out *out)
{
    memset(out, 0, sizeof *out);
    if (in->contacts)
        return 0;
    if (!sc->stokes && !(sc->stokes = calloc(1, sizeof(stokes_work))))
        return -1;
    stokes_work *w = sc->stokes;
    size_t m = in->nnb;
    if (!grow((void **)&w->D, &w->cap_D, m + 1, sizeof *w->D) ||
        !grow((void **)&w->act, &w->cap_act, m + 1, sizeof *w->act) ||
        !grow((void **)&w->caps, &w->cap_caps, m + 1, sizeof *w->caps))
        return -1;
    /* the neighbours whose caps meet the sphere: k < D */
    size_t na = 0;
    for (size_t j = 0; j < m; j++) {
        const vbm_nb *n = &in->nb[j];
        if (!(n->N.lo > 0.0))
            return 0;
        w->D[j] = vbx_ia_sqrt(dot3(n->d, n->d));
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
    w->nrec = 0;
    for (size_t x = 0; x < na; x++) {
        uint32_t j = w->act[x].j;
        size_t nc = region_caps(in, w, na, x);
        if (nc == 0)
            continue;
        int e = vbm_cap_arcs(w->caps, nc, &w->cw);
        if (e <= 0)
            return e;
        if (!grow((void **)&w->rec, &w->cap_rec, w->nrec + w->cw.narc, sizeof *w->rec))
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
            r->A0 = dot3(ej, C->a);
            r->A1 = dot3(ej, C->e1);
            r->A2 = dot3(ej, C->e2);
            memcpy(r->p, a->p, sizeof r->p);
            memcpy(r->q, a->q, sizeof r->q);
            r->tp = a->tp;
            r->tq = a->tq;
        }
    }
    /* every arc to a thousand times its share of the floors of the targets
     * (tolerance * max(|value|, floor), cell_patches.c), then the arcs wider
     * than their share of the targets of the values found, halved until
     * they meet it */
    double rr = in->r.hi, r3 = rr * rr * rr / 3.0;
    double fv = FLOOR_FRACTION * FOUR_PI * r3, fa = FLOOR_FRACTION * FOUR_PI * rr * rr;
    double n = (double)(w->nrec + 1);
    double ta = 1e3 * in->tolerance * vbx_min(0.5 * fa / (rr * rr), 0.25 * fv / r3) / n;
    double tv = 1e3 * in->tolerance * 0.25 * fv / n;
    sums s = {vbx_ia_point(0.0), vbx_ia_point(0.0), 0, 0};
    for (size_t i = 0; i < w->nrec; i++) {
        sums one = {vbx_ia_point(0.0), vbx_ia_point(0.0), 0, 0};
        if (!integrate_arc(in, w, &w->rec[i], ta, tv, &one))
            return 0;
        w->rec[i].area = one.area;
        w->rec[i].vol = one.vol;
        s.pieces += one.pieces;
    }
    total(in, w, out);
    double tgv = in->tolerance * vbx_max(magnitude_lo(out->vol), fv);
    double tgs = in->tolerance * vbx_max(magnitude_lo(out->sas), fa);
    ta = vbx_min(0.5 * tgs / (rr * rr), 0.25 * tgv / r3) / n;
    tv = 0.25 * tgv / n;
    for (size_t i = 0; i < w->nrec; i++) {
        arcrec *a = &w->rec[i];
        if (width(a->area) <= ta && width(a->vol) <= tv)
            continue;
        sums one = {vbx_ia_point(0.0), vbx_ia_point(0.0), 0, 0};
        if (!integrate_arc(in, w, a, ta, tv, &one))
            return 0;
        a->area = one.area;
        a->vol = one.vol;
        s.pieces += one.pieces;
    }
    total(in, w, out);
    out->patches = s.pieces;
    double mv = fabs(vbx_ia_mid(out->vol)), ms = fabs(vbx_ia_mid(out->sas));
    out->loose = width(out->vol) > in->tolerance * vbx_max(mv, fv) ||
                 width(out->sas) > in->tolerance * vbx_max(ms, fa);
    return 1;
}
