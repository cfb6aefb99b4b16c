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
 *           sqrt(N + 2 delta q) / q^3 in closed form (g_of, a log for
 *           delta != 0).
 * On the arcs of j's own cap circle z is constant and dphi the arc's angle
 * (closed form, atan rounded outward by MPFR); on the others the integral
 * runs over t = tan(angle / 2) about the arc's middle (|t| < 0.7), the
 * integrand a rational function of t (the area's and volume's quotients of
 * polynomials, the contact's a root and logs of such quotients: their
 * Taylor coefficients by linear recurrences, vbm1_rational), enclosed by
 * univariate Taylor models (vbm_series1.h) on pieces halved until each
 * meets its share of the tolerance. The arrangement is decided by interval signs; where one
 * cannot be decided (tangent circles, more than three owners at a point,
 * symmetric inputs) the caller falls back to the patch integration. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_array.h"
#include "vbm_caps.h"
#include "vbm_cell.h"
#include "vbm_piece.h"
#include "vbm_series1.h"
#include "vbm_share.h"

#define FLOOR_FRACTION 1e-3 /* as cell_patches.c */
#define MAX_DEPTH 20        /* halvings of an arc's parameter range */
#define FOUR_PI 12.566370614359172

typedef struct arcrec {
    uint32_t j;
    int own;                   /* the arc lies on j's cap circle */
    vbx_ia c, s, A0, A1, A2;   /* the circle, and e_j in its frame */
    vbx_ia p[2], q[2];
    double tp, tq;
    vbx_ia v[3];               /* the arc's integrals: area, volume, contact */
} arcrec;

/* A neighbour whose cap u.e >= ca (sa = sqrt(1 - ca^2)) meets the sphere. */
typedef struct active {
    uint32_t j;
    vbx_ia e[3], ca, sa;
} active;

typedef struct stokes_work {
    vbm_capwork cw;
    vbm_share share;   /* the bisector arcs two regions share */
    vbm_cap *caps;
    uint32_t *capact;  /* per cap of a region: its active neighbour */
    arcrec *rec;
    active *act;
    vbx_ia *D, *con;   /* per neighbour: |d|, the contact */
    uint32_t *narcs;   /* per neighbour: its arcs */
    size_t cap_caps, cap_capact, cap_rec, cap_act, cap_D, cap_con, cap_narcs, nrec;
} stokes_work;

void vbm_stokes_free(void *p)
{
    stokes_work *w = p;
    if (!w)
        return;
    vbm_caps_free(&w->cw);
    vbm_share_free(&w->share);
    free(w->caps);
    free(w->capact);
    free(w->rec);
    free(w->act);
    free(w->D);
    free(w->con);
    free(w->narcs);
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
    vbx_ia D, delta, N, K; /* K = N^3 / (48 (D + delta)^2) */
    vbx_ia rN, hN, kL, lnd; /* sqrt N, 1 / (2 N), delta^2 / (2 N sqrt N), log (2 |delta|) */
    vbx_ia C, G1;           /* N^2 / (4 D), G(D + delta) */
    int contacts;
} owner;

static int g_of(const owner *o, const vbm_s1 *q, vbm_s1 *G);

static int owner_of(const vbm_nb *n, vbx_ia D, int contacts, owner *o)
{
    memset(o, 0, sizeof *o);
    o->D = D;
    o->delta = n->delta;
    o->N = n->N;
    vbx_ia N3 = vbx_ia_mul(vbx_ia_sqr(n->N), n->N);
    o->K = vbx_ia_div(N3, vbx_ia_mul(vbx_ia_point(48.0), vbx_ia_sqr(vbx_ia_add(D, n->delta))));
    o->contacts = contacts;
    if (!contacts)
        return 1;
    o->rN = vbx_ia_sqrt(n->N);
    o->hN = vbx_ia_div(vbx_ia_point(0.5), n->N);
    o->kL = vbx_ia_mul(vbx_ia_sqr(n->delta), vbx_ia_div(o->hN, o->rN));
    if (!vbm_ia_is_zero(n->delta)) {
        vbx_ia ad = n->delta.lo > 0.0 ? n->delta : vbx_ia_neg(n->delta);
        if (!(ad.lo > 0.0))
            return 0;
        o->lnd = vbm_ia_log(vbx_ia_add(ad, ad));
    }
    o->C = vbx_ia_div(vbx_ia_sqr(n->N), vbx_ia_mul(vbx_ia_point(4.0), D));
    vbm_s1 q, G;
    vbm1_const(&q, vbx_ia_add(D, n->delta));
    if (!g_of(o, &q, &G))
        return 0;
    o->G1 = G.c[0];
    return 1;
}

/* G(q) = -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q)
 *        - delta^2 / (2 N sqrt N) log |(sqrt S - sqrt N) / (sqrt S + sqrt N)|,
 * S = N + 2 delta q: a primitive of sqrt(S) / q^3 (the log's argument as
 * 2 |delta| q / (sqrt S + sqrt N)^2, q > 0; no log term for delta = 0). */
static int g_of(const owner *o, const vbm_s1 *q, vbm_s1 *G)
{
    vbm_s1 S, r, iq, t, u;
    vbm1_affine(&S, vbx_ia_add(o->delta, o->delta), q, o->N);
    if (!vbm1_sqrt(&r, &S) || !vbm1_recip(&iq, q))
        return 0;
    vbm1_mul(&t, &r, &iq);                      /* sqrt S / q */
    vbm1_mul(&u, &t, &S);
    vbm1_mul(G, &u, &iq);                       /* S^(3/2) / q^2 */
    vbm1_affine(G, vbx_ia_neg(o->hN), G, vbx_ia_point(0.0));
    vbm1_affine(&u, vbx_ia_mul(o->delta, o->hN), &t, vbx_ia_point(0.0));
    vbm1_add(G, G, &u);
    if (vbm_ia_is_zero(o->delta))
        return 1;
    vbm_s1 lq, ls;
    vbm1_affine(&u, vbx_ia_point(1.0), &r, o->rN);
    if (!vbm1_log(&lq, q) || !vbm1_log(&ls, &u))
        return 0;
    vbm1_affine(&u, vbx_ia_point(-2.0), &ls, o->lnd);
    vbm1_add(&u, &u, &lq);
    vbm1_affine(&u, vbx_ia_neg(o->kL), &u, vbx_ia_point(0.0));
    vbm1_add(G, G, &u);
    return 1;
}

/* F_vol(z) / (1 - z) = K (D (1 + z) + 2 delta) / (D z + delta)^2 */
static vbx_ia fvol_over(const owner *o, vbx_ia z)
{
    vbx_ia q = vbx_ia_add(vbx_ia_mul(o->D, z), o->delta);
    vbx_ia t = vbx_ia_add(vbx_ia_mul(o->D, vbx_ia_add(vbx_ia_point(1.0), z)),
                          vbx_ia_add(o->delta, o->delta));
    return vbx_ia_div(vbx_ia_mul(o->K, t), vbx_ia_sqr(q));
}

/* F_con(z) = C (G(D + delta) - G(D z + delta)) at a constant z. */
static int fcon(const owner *o, vbx_ia z, vbx_ia *F)
{
    vbm_s1 q, G;
    vbm1_const(&q, vbx_ia_add(vbx_ia_mul(o->D, z), o->delta));
    if (!g_of(o, &q, &G))
        return 0;
    *F = vbx_ia_mul(o->C, vbx_ia_sub(o->G1, G.c[0]));
    return 1;
}

enum { AREA, VOL, CON, NV }; /* the values integrated along an arc */

/* The integrands along a circle arc in t: F dphi/dt for the area, the
 * volume and (o.contacts) the contact area. */
typedef struct arcfun {
    owner o;
    vbx_ia cA0, s, sA0s, mcs, A1, A2; /* c A0, s, s^2 A0, -c s, e_j in the rotated frame */
    /* the area's and the volume's integrands as quotients of polynomials
     * in t (rational_of) */
    vbx_ia an[3], ad[5], vn[5], vd[7];
    vbx_ia Pz[3], Pq[3];          /* z = Pz / E, q = Pq / E */
    /* the contact's (contact_of): S = SN / E, the algebraic part of G(q)
     * sqrt(S) Rn / Rd, the area's integrand over 1 - z an / cd */
    vbx_ia SN[3], Rn[5], Rd[5], cd[5];
    int want; /* the values integrated now: bits 1 << AREA, VOL, CON */
} arcfun;

/* With E = 1 + t^2, cos = (1 - t^2) / E and sin = 2 t / E, so
 *   z = Pz / E, 1 + z = Po / E, q = D z + delta = Pq / E,
 *   e.(u x du/dt) = 2 Pn / E^2 (Pz, Po, Pq, Pn quadratics in t), and
 *   area integrand   (1 - z) dphi/dt = 2 Pn / (E Po),
 *   volume integrand K (D (1 + z) + 2 delta) / q^2 times that
 *                    = 2 K Pn (D Po + 2 delta E) / (Pq^2 Po). */
static void rational_of(arcfun *f)
{
    const owner *o = &f->o;
    vbx_ia sA1 = vbx_ia_mul(f->s, f->A1), sA2 = vbx_ia_mul(f->s, f->A2);
    vbx_ia mA1 = vbx_ia_mul(f->mcs, f->A1), mA2 = vbx_ia_mul(f->mcs, f->A2);
    vbx_ia one = vbx_ia_point(1.0), two = vbx_ia_point(2.0), dd = vbx_ia_add(o->delta, o->delta);
    vbx_ia E[3] = {one, vbx_ia_point(0.0), one};
    vbx_ia Pz[3] = {vbx_ia_add(sA1, f->cA0), vbx_ia_mul(two, sA2), vbx_ia_sub(f->cA0, sA1)};
    vbx_ia Pn[3] = {vbx_ia_add(mA1, f->sA0s), vbx_ia_mul(two, mA2), vbx_ia_sub(f->sA0s, mA1)};
    vbx_ia Po[3], Pq[3], Pv[3], Pq2[5], t[5];
    for (int k = 0; k < 3; k++) {
        Po[k] = vbx_ia_add(E[k], Pz[k]);
        Pq[k] = vbx_ia_add(vbx_ia_mul(o->D, Pz[k]), vbx_ia_mul(o->delta, E[k]));
        Pv[k] = vbx_ia_add(vbx_ia_mul(o->D, Po[k]), vbx_ia_mul(dd, E[k]));
        f->an[k] = vbx_ia_mul(two, Pn[k]);
        f->Pz[k] = Pz[k];
        f->Pq[k] = Pq[k];
    }
    vbm1_poly_mul(f->ad, E, 2, Po, 2);
    vbm1_poly_mul(t, Pn, 2, Pv, 2);
    vbx_ia k2 = vbx_ia_mul(two, o->K);
    for (int k = 0; k < 5; k++)
        f->vn[k] = vbx_ia_mul(k2, t[k]);
    vbm1_poly_mul(Pq2, Pq, 2, Pq, 2);
    vbm1_poly_mul(f->vd, Pq2, 4, Po, 2);
    if (!o->contacts)
        return;
    /* S = N + 2 delta q = (N E + 2 delta Pq) / E; the algebraic part of
     * G(q), -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q), is sqrt(S) times
     * (delta q - S) / (2 N q^2) = -(N E + delta Pq) E / (2 N Pq^2); and
     * 1 / (1 - z) = E / (E - Pz), so the area's integrand over 1 - z is
     * 2 Pn / (Po (E - Pz)) */
    vbx_ia W[3], Emz[3];
    for (int k = 0; k < 3; k++) {
        f->SN[k] = vbx_ia_add(vbx_ia_mul(o->N, E[k]), vbx_ia_mul(dd, Pq[k]));
        W[k] = vbx_ia_neg(vbx_ia_add(vbx_ia_mul(o->N, E[k]), vbx_ia_mul(o->delta, Pq[k])));
        Emz[k] = vbx_ia_sub(E[k], Pz[k]);
    }
    vbm1_poly_mul(f->Rn, W, 2, E, 2);
    vbx_ia twoN = vbx_ia_add(o->N, o->N);
    for (int k = 0; k < 5; k++)
        f->Rd[k] = vbx_ia_mul(twoN, Pq2[k]);
    vbm1_poly_mul(f->cd, Po, 2, Emz, 2);
}

/* The contact's integrand C (G1 - G(q)) / (1 - z) times the area's, G as
 * g_of's but its algebraic part one root times a rational function.
 * Returns 0 when a series cannot be bounded (the caller bounds it near
 * e_j). */
static int contact_of(const arcfun *f, vbx_ia at, int kmax, vbm_s1 *con)
{
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    const owner *o = &f->o;
    vbm_s1 S, r, R, G, u, a;
    if (!vbm1_rational(&S, f->SN, 2, E, 2, at, kmax) || !vbm1_sqrt(&r, &S) ||
        !vbm1_rational(&R, f->Rn, 4, f->Rd, 4, at, kmax) ||
        !vbm1_rational(&a, f->an, 2, f->cd, 4, at, kmax))
        return 0;
    vbm1_mul(&G, &r, &R);
    if (!vbm_ia_is_zero(o->delta)) { /* - delta^2 / (2 N sqrt N) log(2 |delta| q / (sqrt S + sqrt N)^2) */
        vbm_s1 q, lq, ls;
        vbm1_affine(&u, vbx_ia_point(1.0), &r, o->rN);
        if (!vbm1_rational(&q, f->Pq, 2, E, 2, at, kmax) || !vbm1_log(&lq, &q) ||
            !vbm1_log(&ls, &u))
            return 0;
        vbm1_affine(&u, vbx_ia_point(-2.0), &ls, o->lnd);
        vbm1_add(&u, &u, &lq);
        vbm1_affine(&u, vbx_ia_neg(o->kL), &u, vbx_ia_point(0.0));
        vbm1_add(&G, &G, &u);
    }
    vbm1_affine(&G, vbx_ia_neg(o->C), &G, vbx_ia_mul(o->C, o->G1));
    vbm1_mul(con, &G, &a);
    return 1;
}

/* The series of the integrands f->want at `at`, coefficients up to kmax
 * (the others 0, and the values not wanted 0). Returns 1, 2 when the
 * contact's series cannot be bounded near e_j (v[CON] is then a constant:
 * its bound where `at` ranges), 0 when nothing can. */
static int integrand(const arcfun *f, vbx_ia at, vbm_s1 *v, int kmax)
{
    int av = f->want & (1 << AREA | 1 << VOL);
    if (av && (!vbm1_rational(&v[AREA], f->an, 2, f->ad, 4, at, kmax) ||
               !vbm1_rational(&v[VOL], f->vn, 4, f->vd, 6, at, kmax)))
        return 0;
    if (!av) {
        vbm1_const(&v[AREA], vbx_ia_point(0.0));
        vbm1_const(&v[VOL], vbx_ia_point(0.0));
    }
    vbm1_const(&v[CON], vbx_ia_point(0.0));
    if (!f->o.contacts || !(f->want & 1 << CON))
        return 1;
    if (contact_of(f, at, kmax, &v[CON]))
        return 1;
    /* near e_j: F(z) / (1 - z) = f(xi), xi in [z, 1] */
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    vbm_s1 z;
    if (!vbm1_rational(&z, f->Pz, 2, E, 2, at, 0))
        return 0;
    vbx_ia Z = {z.c[0].lo, 1.0};
    vbx_ia qz = vbx_ia_add(vbx_ia_mul(f->o.D, Z), f->o.delta);
    vbx_ia S = vbx_ia_add(f->o.N, vbx_ia_mul(vbx_ia_add(f->o.delta, f->o.delta), qz));
    vbx_ia fa = vbx_ia_div(vbx_ia_mul(vbx_ia_sqr(f->o.N), vbx_ia_sqrt(S)),
                           vbx_ia_mul(vbx_ia_point(4.0), vbx_ia_mul(vbx_ia_sqr(qz), qz)));
    vbm_s1 area; /* the area's integrand here, whether wanted or not */
    if (!vbm1_rational(&area, f->an, 2, f->ad, 4, at, 0))
        return 0;
    vbm1_const(&v[CON], vbx_ia_mul(fa, area.c[0]));
    return 2;
}

typedef struct sums {
    vbx_ia v[NV];
    size_t pieces;
} sums;

static int over(const vbx_ia *v, const double *tg)
{
    for (int k = 0; k < NV; k++)
        if (width(v[k]) > tg[k])
            return 1;
    return 0;
}

/* The integrals over [x0, x1] to the widths tg (halved where they fall
 * short), added to *out; `pre` (NULL: none) the integrand's series at the
 * middle already, rpre what integrand returned for it. */
static int piece(const arcfun *f, double x0, double x1, const double *tg, int depth, sums *out,
                 const vbm_s1 *pre, int rpre)
{
    double xc = 0.5 * (x0 + x1);
    vbm_s1 cs[NV], b[NV];
    const vbm_s1 *c = pre ? pre : cs;
    vbx_ia box = {x0, x1}, v[NV];
    int rc = pre ? rpre : integrand(f, vbx_ia_point(xc), cs, VBM1_K);
    int rb = rc ? integrand(f, box, b, VBM1_K) : 0;
    int ok = rc && rb;
    vbx_ia mom[VBM1_K + 1];
    if (ok)
        vbm1_moments(xc, x0, x1, mom);
    for (int k = 0; ok && k < NV; k++) /* the contact's series is 0 without contacts */
        v[k] = k == CON && !f->o.contacts ? vbx_ia_point(0.0)
                                          : vbm1_integrate_m(&c[k], &b[k], mom);
    if (ok && (rc == 2 || rb == 2)) /* the contact's bound over the box times its length */
        v[CON] = vbx_ia_mul(vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(x0)), b[CON].c[0]);
    if (!ok && !(depth < MAX_DEPTH && xc > x0 && xc < x1))
        return 0;
    /* a piece whose box an interval cannot bound (the contact's 1 / (1 - z)
     * where the arc passes near e_j) is halved too */
    if ((!ok || over(v, tg)) && depth < MAX_DEPTH && xc > x0 && xc < x1) {
        double half[NV];
        for (int k = 0; k < NV; k++)
            half[k] = 0.5 * tg[k];
        return piece(f, x0, xc, half, depth + 1, out, NULL, 0) &&
               piece(f, xc, x1, half, depth + 1, out, NULL, 0);
    }
    for (int k = 0; k < NV; k++)
        out->v[k] = vbx_ia_add(out->v[k], v[k]);
    out->pieces++;
    return 1;
}

/* [x0, x1] (at depth `depth`) halved d times, each part by piece. */
static int descend(const arcfun *f, double x0, double x1, const double *tg, int d, int depth,
                   sums *out)
{
    double xc = 0.5 * (x0 + x1);
    if (d == 0 || !(xc > x0 && xc < x1))
        return piece(f, x0, x1, tg, depth, out, NULL, 0);
    double half[NV];
    for (int k = 0; k < NV; k++)
        half[k] = 0.5 * tg[k];
    return descend(f, x0, xc, half, d - 1, depth + 1, out) &&
           descend(f, xc, x1, half, d - 1, depth + 1, out);
}

#define PLAN_MAX 3 /* halvings planned before any piece is tried */
/* 1crn, 1 thread: factors 2, 8, 64, 512 gave 54633, 54633, 54521, 54654
 * pieces and 0.56, 0.56, 0.55, 0.53 s of CPU (piece alone: 0.60 s) */
#define PLAN_FACTOR 512.0

/* Integrates [x0, x1] as piece does, but first halved as often as the
 * middle's series says it will need: each piece's share of tg against
 * PLAN_FACTOR |c_K| 2 h^(K+1) / (K + 1), the size of the remainder term on
 * a piece of half-width h (the remainder's width comes from c_K over the
 * whole piece, where it varies and the intervals overestimate it: far
 * wider than at the middle). The halves piece would try anyway, without
 * the wider pieces it would try and drop first. Only where the pieces
 * start is chosen so; each is still proven by its own Taylor model and
 * halved further where it falls short. */
static int planned(const arcfun *f, double x0, double x1, const double *tg, sums *out)
{
    vbm_s1 c[NV];
    double xc = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
    int rc = integrand(f, vbx_ia_point(xc), c, VBM1_K), d = 0;
    double hk = 2.0 / (VBM1_K + 1) * h;
    for (int n = 0; n < VBM1_K; n++)
        hk *= h;
    for (int k = 0; rc && k < NV; k++) {
        double mag = vbx_max(fabs(c[k].c[VBM1_K].lo), fabs(c[k].c[VBM1_K].hi));
        double est = PLAN_FACTOR * mag * hk;
        for (int e = 0; e < PLAN_MAX && est > tg[k]; e++, est *= 1.0 / (1 << VBM1_K))
            d = e + 1 > d ? e + 1 : d;
    }
    if (d == 0)
        return piece(f, x0, x1, tg, 0, out, rc ? c : NULL, rc);
    return descend(f, x0, x1, tg, d, 0, out);
}

/* The integral from the exact end t (an interval) to the double m inside
 * it: (m - t) times the integrand somewhere in t. */
static int end_piece(const arcfun *f, vbx_ia t, double m, sums *out)
{
    vbm_s1 v[NV];
    if (!integrand(f, t, v, 0)) /* 2: v[CON].c[0] a bound as well */
        return 0;
    vbx_ia dt = vbx_ia_sub(vbx_ia_point(m), t);
    for (int k = 0; k < NV; k++)
        out->v[k] = vbx_ia_add(out->v[k], vbx_ia_mul(dt, v[k].c[0]));
    return 1;
}

/* t = tan(angle / 2) of the unit vector (x, y) rotated by -mid. */
static vbx_ia half_tan(vbx_ia x, vbx_ia y, vbx_ia cm, vbx_ia sm)
{
    vbx_ia xr = vbx_ia_add(vbx_ia_mul(x, cm), vbx_ia_mul(y, sm));
    vbx_ia yr = vbx_ia_sub(vbx_ia_mul(y, cm), vbx_ia_mul(x, sm));
    return vbx_ia_div(yr, vbx_ia_add(vbx_ia_point(1.0), xr));
}

/* The arc's integrals to the widths tg into a->v. Returns 0 when an
 * interval cannot bound them. */
static int integrate_arc(const vbm_atom_in *in, const stokes_work *w, arcrec *a, const double *tg,
                         size_t *pieces)
{
    vbx_ia cm, sm;
    vbm_unit_at(0.5 * (a->tp + a->tq), &cm, &sm);
    vbx_ia t0 = half_tan(a->p[0], a->p[1], cm, sm), t1 = half_tan(a->q[0], a->q[1], cm, sm);
    if (!(t1.lo > t0.hi))
        return 0;
    sums s = {{vbx_ia_point(0.0), vbx_ia_point(0.0), vbx_ia_point(0.0)}, 0};
    arcfun f;
    if (!owner_of(&in->nb[a->j], w->D[a->j], in->contacts, &f.o))
        return 0;
    if (a->own) { /* z = c: F(c) times the angle 2 (atan t1 - atan t0) */
        vbx_ia ang = vbx_ia_sub(vbm_ia_atan(t1), vbm_ia_atan(t0));
        ang = vbx_ia_add(ang, ang);
        vbx_ia omz = vbx_ia_sub(vbx_ia_point(1.0), a->c), F = vbx_ia_point(0.0);
        if (in->contacts && !fcon(&f.o, a->c, &F))
            return 0;
        a->v[AREA] = vbx_ia_mul(omz, ang);
        a->v[VOL] = vbx_ia_mul(vbx_ia_mul(omz, fvol_over(&f.o, a->c)), ang);
        a->v[CON] = vbx_ia_mul(F, ang);
        ++*pieces;
        return 1;
    }
    f.cA0 = vbx_ia_mul(a->c, a->A0);
    f.s = a->s;
    f.sA0s = vbx_ia_mul(vbx_ia_sqr(a->s), a->A0);
    f.mcs = vbx_ia_neg(vbx_ia_mul(a->c, a->s));
    f.A1 = vbx_ia_add(vbx_ia_mul(a->A1, cm), vbx_ia_mul(a->A2, sm));
    f.A2 = vbx_ia_sub(vbx_ia_mul(a->A2, cm), vbx_ia_mul(a->A1, sm));
    rational_of(&f);
    double m0 = vbx_ia_mid(t0), m1 = vbx_ia_mid(t1);
    f.want = 1 << AREA | 1 << VOL | 1 << CON;
    if (!end_piece(&f, t0, m0, &s) || !end_piece(&f, t1, m1, &s))
        return 0;
    /* the area and volume on their pieces, the contact on its own (it needs
     * more): neither evaluated where only the other falls short */
    double ta[NV] = {tg[AREA], tg[VOL], INFINITY}, tc[NV] = {INFINITY, INFINITY, tg[CON]};
    f.want = 1 << AREA | 1 << VOL;
    if (!planned(&f, m0, m1, ta, &s))
        return 0;
    f.want = 1 << CON;
    if (in->contacts && !planned(&f, m0, m1, tc, &s))
        return 0;
    memcpy(a->v, s.v, sizeof a->v);
    *pieces += s.pieces;
    return 1;
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
        w->capact[nc] = (uint32_t)y;
        cp[nc++] = c;
    }
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
 * and SAS shares of tv and ts, each contact's share of tc[j] (or, with
 * tc NULL, of fa); `scale` multiplies every target. Returns 0 when an
 * interval cannot bound an arc. */
static int integrate_arcs(const vbm_atom_in *in, stokes_work *w, double tv, double ts, double fa,
                          double scale, size_t *pieces)
{
    double rr = in->r.hi, r3 = rr * rr * rr / 3.0, n = (double)(w->nrec + 1);
    double tg[NV];
    tg[AREA] = scale * vbx_min(0.5 * ts / (rr * rr), 0.25 * tv / r3) / n;
    tg[VOL] = scale * 0.25 * tv / n;
    for (size_t i = 0; i < w->nrec; i++) {
        arcrec *a = &w->rec[i];
        uint32_t j = a->j;
        double tc = in->tolerance * vbx_max(scale > 1.0 ? 0.0 : magnitude_lo(w->con[j]), fa);
        tg[CON] = in->contacts ? scale * 0.5 * tc / (double)(w->narcs[j] + 1) : INFINITY;
        if (scale <= 1.0 && !over(a->v, tg))
            continue;
        if (!integrate_arc(in, w, a, tg, pieces))
            return 0;
    }
    return 1;
}

/* out->pairs: the contacts with hi > 0. Returns 0 on ENOMEM. */
static int pairs(const vbm_atom_in *in, const stokes_work *w, vbm_atom_out *out)
{
    size_t np = 0;
    for (size_t j = 0; j < in->nnb; j++)
        np += w->narcs[j] && w->con[j].hi > 0.0;
    if (!np)
        return 1;
    out->pairs = malloc(np * sizeof *out->pairs);
    if (!out->pairs)
        return 0;
    for (size_t j = 0; j < in->nnb; j++)
        if (w->narcs[j] && w->con[j].hi > 0.0) {
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
    if (VB_ARRAY_FIT(w->D, w->cap_D, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->act, w->cap_act, m + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(w->caps, w->cap_caps, m + 1, 64) != VB_OK ||
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
    sort_active(w->act, na);
    /* the regions in order, each bisector circle's arcs found for the
     * first of its two regions and given to the second (vbm_share.h) */
    w->nrec = 0;
    vbm_share_reset(&w->share);
    for (size_t x = 0; x < na; x++) {
        uint32_t j = w->act[x].j;
        size_t nc = region_caps(in, w, na, x);
        if (nc == 0) {
            if (vbm_share_pending(&w->share, (uint32_t)x))
                return 0; /* arcs of a region proven empty: leave it to the patches */
            continue;
        }
        int e = vbm_share_given(&w->share, (uint32_t)x, w->capact, nc, na);
        if (e <= 0)
            return e;
        e = vbm_cap_arcs(w->caps, nc, w->share.known, w->share.given, w->share.ngiven, &w->cw);
        if (e <= 0)
            return e;
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
            r->A0 = dot3(ej, C->a);
            r->A1 = dot3(ej, C->e1);
            r->A2 = dot3(ej, C->e2);
            memcpy(r->p, a->p, sizeof r->p);
            memcpy(r->q, a->q, sizeof r->q);
            r->tp = a->tp;
            r->tq = a->tq;
        }
    }
    /* every arc to a hundred times its share of the floors of the targets
     * (tolerance * max(|value|, floor), cell_patches.c), then the arcs wider
     * than their share of the targets of the values found, halved until
     * they meet it */
    double rr = in->r.hi, r3 = rr * rr * rr / 3.0;
    double fv = FLOOR_FRACTION * FOUR_PI * r3, fa = FLOOR_FRACTION * FOUR_PI * rr * rr;
    size_t pieces = 0;
    contacts(in, w); /* the arc counts */
    if (!integrate_arcs(in, w, in->tolerance * fv, in->tolerance * fa, fa, 100, &pieces))
        return 0;
    total(in, w, out);
    contacts(in, w);
    double tgv = in->tolerance * vbx_max(magnitude_lo(out->vol), fv);
    double tgs = in->tolerance * vbx_max(magnitude_lo(out->sas), fa);
    if (!integrate_arcs(in, w, tgv, tgs, fa, 1.0, &pieces))
        return 0;
    total(in, w, out);
    contacts(in, w);
    out->patches = pieces;
    double mv = fabs(vbx_ia_mid(out->vol)), ms = fabs(vbx_ia_mid(out->sas));
    out->loose = width(out->vol) > in->tolerance * vbx_max(mv, fv) ||
                 width(out->sas) > in->tolerance * vbx_max(ms, fa);
    for (size_t j = 0; in->contacts && j < in->nnb; j++)
        if (w->narcs[j] &&
            width(w->con[j]) > in->tolerance * vbx_max(fabs(vbx_ia_mid(w->con[j])), fa))
            out->loose = 1;
    if (in->contacts && !pairs(in, w, out))
        return -1;
    return 1;
}
