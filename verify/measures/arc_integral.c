/* The integrals along one arc bounding a neighbour's region of directions
 * (vbm_arc.h; the formulas at the top of stokes_cell.c).
 *
 * On the arcs of j's own cap circle z is constant and dphi the arc's angle
 * (closed form, atan rounded outward by MPFR); on the others the integral
 * runs over t = tan(angle / 2) about the arc's middle (|t| < 0.7), the
 * integrand a rational function of t (the area's and volume's quotients of
 * polynomials, the contact's a root and logs of such quotients: their
 * Taylor coefficients by linear recurrences, vbm1_rational), enclosed by
 * univariate Taylor models (vbm_series1.h) on pieces halved until each
 * meets its share of the tolerance: the area's and the volume's remainder
 * from their quotients (vbm1_rational_rest), the contact's from a model of
 * F(z(t)) / (1 - z(t)) whose parts have closed-form remainders
 * (contact_tm.c). Where an arc passes near the owner's direction e_j
 * (1 - z < NEAR_Y over a piece) the contact's F / (1 - z)
 * goes by its series in 1 - z with a proven remainder (contact_near)
 * instead of a quotient an interval cannot bound there. The contact's
 * pieces are stepped along the arc (march), the area's and volume's halved
 * (planned, piece). */
#include <math.h>
#include <string.h>

#include "vbm_arc.h"
#include "vbm_caps.h"
#include "vbm_contact_tm.h"
#include "vbm_piece.h"
#include "vbm_series1.h"

#define MAX_DEPTH 20 /* halvings of an arc's parameter range */

enum { AREA = VBM_AREA, VOL = VBM_VOL, CON = VBM_CON, NV = VBM_NV };

static double width(vbx_ia a)
{
    double d = a.hi - a.lo;
    return d == d ? d : INFINITY;
}

typedef vbm_owner owner;

static int phi_series(const owner *o, vbx_ia at, vbm_s1 *phi);

int vbm_owner_make(const vbm_atom_in *in, size_t j, vbx_ia D, vbm_owner *o)
{
    const vbm_nb *n = &in->nb[j];
    int contacts = in->contacts && n->con; /* else the face's other atom integrates it */
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
    if (!vbm_contact_g(o, vbx_ia_add(D, n->delta), &o->G1))
        return 0;
    return 1;
}

/* phi(y) = f(1 - y) with f(z) = N^2 sqrt(N + 2 delta q) / (4 q^3),
 * q = D z + delta: the contact's integrand per solid angle (F = int_z^1 f)
 * as a function of y = 1 - z; its series at `at` (a point, or an interval
 * of y holding 0, where q(0) = D + delta > 0, so that q proven non-zero is
 * proven > 0). Returns 0 when q or S = N + 2 delta q is not proven so. */
static int phi_series(const owner *o, vbx_ia at, vbm_s1 *phi)
{
    vbm_s1 y, q, S, r, q2, q3, iq3;
    vbm1_var(&y, at);
    vbm1_affine(&q, vbx_ia_neg(o->D), &y, vbx_ia_add(o->D, o->delta));
    vbm1_affine(&S, vbx_ia_add(o->delta, o->delta), &q, o->N);
    if (!vbm1_sqrt(&r, &S))
        return 0;
    vbm1_mul(&q2, &q, &q);
    vbm1_mul(&q3, &q2, &q);
    if (!vbm1_recip(&iq3, &q3))
        return 0;
    vbm1_mul(phi, &r, &iq3);
    vbm1_affine(phi, vbx_ia_div(vbx_ia_sqr(o->N), vbx_ia_point(4.0)), phi, vbx_ia_point(0.0));
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
    vbx_ia G;
    if (!vbm_contact_g(o, vbx_ia_add(vbx_ia_mul(o->D, z), o->delta), &G))
        return 0;
    *F = vbx_ia_mul(o->C, vbx_ia_sub(o->G1, G));
    return 1;
}


/* phi's Taylor coefficients at y = 0 (contact_near's h), made on the
 * arc's first piece near e_j (state 0: not yet, 1: made, -1: phi_series
 * failed). Made for every owner before (c1k --contacts: 6,283 owners,
 * 104 M instructions, for 2,052 pieces near e_j; bounding 1 - z on the
 * arc's circle instead still left 6,550 arcs). */
typedef struct phic {
    vbm_s1 phi0;
    int state;
} phic;

/* The integrands along a circle arc in t: F dphi/dt for the area, the
 * volume and (o.contacts) the contact area. */
typedef struct arcfun {
    owner o;
    vbx_ia cA0, s, sA0s, mcs, A1, A2; /* c A0, s, s^2 A0, -c s, e_j in the rotated frame */
    /* the area's and the volume's integrands as quotients of polynomials
     * in t (rational_of) */
    vbx_ia an[3], ad[5], vn[5], vd[7];
    vbx_ia Pz[3], Pq[3];          /* z = Pz / E, q = Pq / E */
    /* the contact's (contact_of): the area's integrand over 1 - z an / cd
     * (its algebraic part Rn / Rd only where contact_of needs it: alg_of) */
    vbx_ia Emz[3], cd[5]; /* ... 1 - z = Emz / E, cd = Po Emz */
    vbm_contact_rat cr; /* the contact's model (contact_tm.c): q' / q^3, S, an / cd */
    struct phic *pc;    /* phi's coefficients at y = 0: contact_near */
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
    /* 1 / (1 - z) = E / (E - Pz), so the area's integrand over 1 - z is
     * 2 Pn / (Po (E - Pz)) */
    vbx_ia Emz[3];
    for (int k = 0; k < 3; k++) {
        Emz[k] = vbx_ia_sub(E[k], Pz[k]);
        f->Emz[k] = Emz[k];
    }
    vbm1_poly_mul(f->cd, Po, 2, Emz, 2);
    /* q' / q^3 = (Pq' E - Pq E') E / Pq^3, Pq' E - Pq E' = p1 + 2 (p2 - p0) t
     * - p1 t^2 (the t^3 terms cancel: contact_tm.c); S = (N E + 2 delta Pq)
     * / E */
    vbx_ia dq[3] = {Pq[1], vbx_ia_mul(two, vbx_ia_sub(Pq[2], Pq[0])), vbx_ia_neg(Pq[1])}, Pq3[7];
    vbm1_poly_mul(f->cr.rn, dq, 2, E, 2);
    vbm1_poly_mul(Pq3, Pq2, 4, Pq, 2);
    for (int k = 0; k < 7; k++)
        f->cr.rd[k] = Pq3[k];
    for (int k = 0; k < 5; k++)
        f->cr.cd[k] = f->cd[k];
    for (int k = 0; k < 3; k++) {
        f->cr.po[k] = Po[k];
        f->cr.sd[k] = E[k];
        f->cr.an[k] = f->an[k];
        f->cr.yn[k] = Emz[k];
    }
}

/* S = N + 2 delta q = (N E + 2 delta Pq) / E; the algebraic part of G(q),
 * -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q), is sqrt(S) times
 * (delta q - S) / (2 N q^2) = -(N E + delta Pq) E / (2 N Pq^2) = Rn / Rd.
 * Made where contact_of reads them (its fallback), not for every arc
 * (c1k --contacts: 25,761 arcs, far fewer fallback series). */
static void alg_of(const arcfun *f, vbx_ia *Rn, vbx_ia *Rd)
{
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    const owner *o = &f->o;
    vbx_ia W[3], Pq2[5];
    for (int k = 0; k < 3; k++)
        W[k] = vbx_ia_neg(vbx_ia_add(vbx_ia_mul(o->N, E[k]), vbx_ia_mul(o->delta, f->Pq[k])));
    vbm1_poly_mul(Rn, W, 2, E, 2);
    vbm1_poly_mul(Pq2, f->Pq, 2, f->Pq, 2);
    vbx_ia twoN = vbx_ia_add(o->N, o->N);
    for (int k = 0; k < 5; k++)
        Rd[k] = vbx_ia_mul(twoN, Pq2[k]);
}

/* The contact's integrand C (G1 - G(q)) / (1 - z) times the area's, G as
 * vbm_contact_g's but its algebraic part one root times a rational function, to
 * the order kmax; with `last`, of *con the order kmax alone (the others
 * 0: over a piece only the remainder's order is read). Returns 0 when a
 * series cannot be bounded (the caller bounds it near e_j). */
static int contact_of(const arcfun *f, vbx_ia at, int kmax, int last, vbm_s1 *con)
{
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    const owner *o = &f->o;
    vbm_s1 S, r, R, G, u, a, q;
    /* S = N + 2 delta q from q's series (one affine map where SN / E took a
     * second rational recurrence; S = N exactly for delta = 0) */
    int dz = vbm_ia_is_zero(o->delta);
    if (dz)
        vbm1_const(&S, o->N);
    else if (vbm1_rational(&q, f->Pq, 2, E, 2, at, kmax))
        vbm1_affine(&S, vbx_ia_add(o->delta, o->delta), &q, o->N);
    else
        return 0;
    vbx_ia Rn[5], Rd[5];
    alg_of(f, Rn, Rd);
    if (!vbm1_sqrt_to(&r, &S, kmax) || !vbm1_rational(&R, Rn, 4, Rd, 4, at, kmax) ||
        !vbm1_rational(&a, f->an, 2, f->cd, 4, at, kmax))
        return 0;
    vbm1_mul_to(&G, &r, &R, kmax);
    if (!dz) { /* - delta^2 / (2 N sqrt N) log(2 |delta| q / (sqrt S + sqrt N)^2) */
        vbm_s1 lq, ls;
        vbm1_affine(&u, vbx_ia_point(1.0), &r, o->rN);
        if (!vbm1_log_to(&lq, &q, kmax) || !vbm1_log_to(&ls, &u, kmax))
            return 0;
        vbm1_affine(&u, vbx_ia_point(-2.0), &ls, o->lnd);
        vbm1_add(&u, &u, &lq);
        vbm1_affine(&u, vbx_ia_neg(o->kL), &u, vbx_ia_point(0.0));
        vbm1_add(&G, &G, &u);
    }
    vbm1_affine(&G, vbx_ia_neg(o->C), &G, vbx_ia_mul(o->C, o->G1));
    if (last) {
        vbm1_const(con, vbx_ia_point(0.0));
        con->c[kmax] = vbm1_mul_coef(&G, &a, kmax);
    } else
        vbm1_mul_to(con, &G, &a, kmax);
    return 1;
}

/* The series of the integrands f->want at `at`, coefficients up to kmax
 * (the others 0, and the values not wanted 0). Returns 1, 2 when the
 * contact's series cannot be bounded near e_j (v[CON] is then a constant:
 * its bound where `at` ranges), 0 when nothing can. */
/* 1 - z below which over a piece the contact goes by contact_near (1crn
 * --contacts, 1 thread: 0.02, 0.05, 0.1 gave 2.61, 2.33, 2.38 s of CPU;
 * without it 3.34 s) */
#define NEAR_Y 0.05

/* The contact's integrand where the arc passes near e_j (y = 1 - z in
 * [0, ybox.hi], ybox.hi < NEAR_Y, over the piece), without the division by
 * 1 - z that contact_of makes there: F(z) / (1 - z) = h(y) =
 * int_0^1 phi(y u) du = sum_{m<K} a_m y^m / (m + 1) + R(y), a_m phi's
 * Taylor coefficients at y = 0 and, by Lagrange's remainder at each u,
 * R(y) = int_0^1 phi^(K)(xi_u) / K! (y u)^K du in y^K Phi_K / (K + 1),
 * Phi_K the K-th coefficient of phi over [0, ybox.hi] (xi_u in [0, y u]).
 * *con: the series of the polynomial part times the area's integrand
 * (F dphi/dt = h(y) (1 - z) dphi/dt) at `at`, to the order kmax; *rem
 * (NULL: not wanted) that of the remainder over `at`: area y^K Phi_K /
 * (K + 1), so that the integral of the rest over the piece lies in its
 * length times *rem, and then of *con the order kmax alone (the others 0:
 * over the box vbm1_integrate_m reads only its order K). Returns 0 when a
 * series cannot be bounded. */
static int contact_near(const arcfun *f, vbx_ia at, int kmax, double yhi, vbm_s1 *con,
                        vbx_ia *rem)
{
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    const owner *o = &f->o;
    vbm_s1 y, area, h, t;
    if (f->pc->state == 0)
        f->pc->state = phi_series(o, vbx_ia_point(0.0), &f->pc->phi0) ? 1 : -1;
    const vbm_s1 *phi0 = &f->pc->phi0;
    if (f->pc->state < 0 || !vbm1_rational(&y, f->Emz, 2, E, 2, at, kmax) ||
        !vbm1_rational(&area, f->an, 2, f->ad, 4, at, kmax))
        return 0;
    vbm1_const(&h, vbx_ia_div(phi0->c[VBM1_K - 1], vbx_ia_point((double)VBM1_K)));
    for (int m = VBM1_K - 2; m >= 0; m--) { /* Horner in the series of y */
        vbm1_mul_to(&t, &h, &y, kmax);
        vbm1_affine(&h, vbx_ia_point(1.0), &t,
                    vbx_ia_div(phi0->c[m], vbx_ia_point((double)(m + 1))));
    }
    if (!rem) {
        vbm1_mul_to(con, &h, &area, kmax);
        return 1;
    }
    vbm1_const(con, vbx_ia_point(0.0));
    con->c[kmax] = vbm1_mul_coef(&h, &area, kmax);
    vbm_s1 phib;
    vbx_ia yb = {0.0, yhi}, y0 = {vbx_max(y.c[0].lo, 0.0), y.c[0].hi}; /* y >= 0 exactly */
    if (!phi_series(o, yb, &phib) || !(y0.hi <= yhi))
        return 0;
    vbx_ia yk = vbx_ia_point(1.0);
    for (int m = 0; m < VBM1_K; m++)
        yk = vbx_ia_mul(yk, y0);
    *rem = vbx_ia_mul(vbx_ia_mul(area.c[0], yk),
                      vbx_ia_div(phib.c[VBM1_K], vbx_ia_point((double)(VBM1_K + 1))));
    return 1;
}

/* The contact's integrand over t in `at`, no series: F(z) / (1 - z) = f(xi),
 * xi in [z, 1] (F = int_z^1 f), f = N^2 sqrt(S) / (4 q^3) over [z.lo, 1],
 * times the area's integrand. Returns 0 when an interval cannot bound it. */
static int contact_bound(const arcfun *f, vbx_ia at, vbx_ia *b)
{
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
    *b = vbx_ia_mul(fa, area.c[0]);
    return 1;
}

/* ... of the values `want` (bits 1 << AREA, VOL, CON); with `keep` (at a
 * point, kmax VBM1_K) the area's and the volume's moved polynomials in
 * keep[0] and keep[1], for their remainders (vbm1_rational_rest). */
static int integrand(const arcfun *f, int want, vbx_ia at, vbm_s1 *v, int kmax, int last,
                     vbm1_rat *keep)
{
    int av = want & (1 << AREA | 1 << VOL);
    if (av && keep &&
        (!vbm1_rational_keep(&v[AREA], f->an, 2, f->ad, 4, at, &keep[0]) ||
         !vbm1_rational_keep(&v[VOL], f->vn, 4, f->vd, 6, at, &keep[1])))
        return 0;
    if (av && !keep && (!vbm1_rational(&v[AREA], f->an, 2, f->ad, 4, at, kmax) ||
                        !vbm1_rational(&v[VOL], f->vn, 4, f->vd, 6, at, kmax)))
        return 0;
    if (!av) {
        vbm1_const(&v[AREA], vbx_ia_point(0.0));
        vbm1_const(&v[VOL], vbx_ia_point(0.0));
    }
    vbm1_const(&v[CON], vbx_ia_point(0.0));
    if (!f->o.contacts || !(want & 1 << CON))
        return 1;
    if (contact_of(f, at, kmax, last, &v[CON]))
        return 1;
    vbx_ia b;
    if (!contact_bound(f, at, &b))
        return 0;
    vbm1_const(&v[CON], b);
    return 2;
}

typedef struct sums {
    vbx_ia v[NV];
    size_t pieces;
} sums;

int vbm_arc_over(const vbx_ia *v, const double *tg)
{
    for (int k = 0; k < NV; k++)
        if (width(v[k]) > tg[k])
            return 1;
    return 0;
}

static int piece(const arcfun *f, double x0, double x1, const double *tg, int depth, sums *out,
                 const vbm_s1 *pre, int rpre, const vbm1_rat *prek);

/* [x0, x1] as two pieces, each to half the widths tg. */
static int halve(const arcfun *f, double x0, double x1, const double *tg, int depth, sums *out)
{
    double xc = 0.5 * (x0 + x1), half[NV];
    for (int k = 0; k < NV; k++)
        half[k] = 0.5 * tg[k];
    return piece(f, x0, xc, half, depth + 1, out, NULL, 0, NULL) &&
           piece(f, xc, x1, half, depth + 1, out, NULL, 0, NULL);
}

/* The contact alone over the piece [xc + x] as contact_tm.c's model: the
 * middle's coefficients in c[CON] and its remainder in b[CON].c[K] (the
 * other values 0). Returns 0 when the model cannot be made (then the
 * contact's series over the piece bounds the remainder). */
static int contact_model(const arcfun *f, double xc, vbx_ia x, vbm_s1 *c, vbm_s1 *b)
{
    static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
    vbm_s1 z;
    vbx_ia F0;
    if (!vbm1_rational(&z, f->Pz, 2, E, 2, vbx_ia_point(xc), 0) || !fcon(&f->o, z.c[0], &F0))
        return 0;
    for (int k = 0; k < NV; k++) {
        vbm1_const(&c[k], vbx_ia_point(0.0));
        vbm1_const(&b[k], vbx_ia_point(0.0));
    }
    return vbm_contact_tm(&f->cr, &f->o, F0, xc, x, &c[CON], &b[CON].c[VBM1_K]);
}

/* The integrals over the piece [x0, x1] of the values f->want in v[0..NV)
 * (those not wanted: any enclosure); `pre` (NULL: none) the integrand's
 * series at the middle already, rpre what integrand returned for it, prek
 * its kept polynomials, tg the widths asked (the contact near e_j takes
 * its series in 1 - z only where that remainder leaves room in tg). Returns
 * 0 when an interval cannot bound them or, with `halves` (the piece may
 * still be split), when the contact's model cannot be made. The area's
 * and the volume's remainders over the piece come from the middle's
 * series (vbm1_rational_rest), the contact's from its
 * model (contact_model) or, where that cannot be made, from its series
 * over the piece: only at MAX_DEPTH, since elsewhere the piece is halved
 * (the capsid's first 4000 balls, 1crn and 3pqr: the same bytes as trying
 * the series first, which never kept such a piece, and 1.6 % fewer
 * instructions on 1crn). */
static int piece_values(const arcfun *f, double x0, double x1, const double *tg, int halves,
                        const vbm_s1 *pre, int rpre, const vbm1_rat *prek, vbx_ia *v)
{
    double xc = 0.5 * (x0 + x1);
    vbm_s1 cs[NV], b[NV];
    vbm1_rat kc[2];
    const vbm_s1 *c = pre ? pre : cs;
    const vbm1_rat *kp = pre ? prek : kc;
    vbx_ia box = {x0, x1}, rem = vbx_ia_point(0.0);
    vbx_ia len = vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(x0));
    int near = 0, rc, rb;
    if (f->o.contacts && f->want == 1 << CON) { /* the contact alone: near e_j? */
        static const vbx_ia E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};
        vbm_s1 y;
        near = vbm1_rational(&y, f->Emz, 2, E, 2, box, 0) && y.c[0].hi < NEAR_Y;
        double yhi = near ? y.c[0].hi : 0.0;
        /* the centre and the box by the same route: both the same function */
        /* and only where the remainder of h's series leaves room: it
         * shrinks with y, not with the piece */
        if (near && contact_near(f, box, VBM1_K, yhi, &b[CON], &rem) &&
            width(vbx_ia_mul(len, rem)) <= 0.25 * tg[CON] &&
            contact_near(f, vbx_ia_point(xc), VBM1_K - 1, yhi, &cs[CON], NULL)) {
            c = cs;
            for (int k = 0; k < NV; k++)
                if (k != CON) {
                    vbm1_const(&cs[k], vbx_ia_point(0.0));
                    vbm1_const(&b[k], vbx_ia_point(0.0));
                }
        } else
            near = 0;
    }
    vbx_ia mom[VBM1_K + 1];
    vbx_ia x = {vbx_ia_sub(vbx_ia_point(x0), vbx_ia_point(xc)).lo,
                vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(xc)).hi};
    int model = !near && f->o.contacts && f->want == 1 << CON;
    if (model && contact_model(f, xc, x, cs, b)) {
        c = cs;
        rc = rb = 1;
    } else if (model && halves)
        return 0;
    else if (near)
        rc = rb = 1;
    else {
        int av = f->want & (1 << AREA | 1 << VOL);
        /* the contact's middle to the order K - 1 and its box's order K
         * alone: what vbm1_integrate_m reads of them (the area's and the
         * volume's at the middle keep every order: vbm1_rational_rest) */
        int kc_max = f->want == 1 << CON ? VBM1_K - 1 : VBM1_K;
        rc = pre ? rpre : integrand(f, f->want, vbx_ia_point(xc), cs, kc_max, 0, kc);
        rb = rc ? integrand(f, f->want & 1 << CON, box, b, VBM1_K, 1, NULL) : 0;
        for (int k = AREA; rb && av && k <= VOL; k++)
            if (!vbm1_rational_rest(&kp[k - AREA], &c[k], x, &b[k].c[VBM1_K]))
                rb = 0;
    }
    int ok = rc && rb;
    if (ok)
        vbm1_moments(xc, x0, x1, mom);
    for (int k = 0; ok && k < NV; k++) /* the contact's series is 0 without contacts */
        v[k] = k == CON && !f->o.contacts ? vbx_ia_point(0.0)
                                          : vbm1_integrate_m(&c[k], &b[k], mom);
    if (ok && near) /* the remainder of h's series over the piece */
        v[CON] = vbx_ia_add(v[CON], vbx_ia_mul(len, rem));
    if (ok && (rc == 2 || rb == 2)) /* the contact's bound over the box times its length */
        v[CON] = vbx_ia_mul(len, b[CON].c[0]);
    return ok;
}

/* The values integrated alone added to *out: vbm1_integrate_m of a zero
 * series is not exactly 0 (vbm_dotn's margin), and adding it to the others
 * would make the area and volume depend on how many contact pieces there
 * are. */
static void add_piece(const arcfun *f, const vbx_ia *v, sums *out)
{
    for (int k = 0; k < NV; k++)
        if (f->want & 1 << k)
            out->v[k] = vbx_ia_add(out->v[k], v[k]);
    out->pieces++;
}

/* The integrals over [x0, x1] to the widths tg (halved where they fall
 * short), added to *out; pre, rpre, prek as piece_values'. */
static int piece(const arcfun *f, double x0, double x1, const double *tg, int depth, sums *out,
                 const vbm_s1 *pre, int rpre, const vbm1_rat *prek)
{
    double xc = 0.5 * (x0 + x1);
    int halves = depth < MAX_DEPTH && xc > x0 && xc < x1;
    vbx_ia v[NV];
    int ok = piece_values(f, x0, x1, tg, halves, pre, rpre, prek, v);
    if (!ok && !halves)
        return 0;
    /* a piece whose box an interval cannot bound (the contact's 1 / (1 - z)
     * where the arc passes near e_j) is halved too */
    if ((!ok || vbm_arc_over(v, tg)) && halves)
        return halve(f, x0, x1, tg, depth, out);
    add_piece(f, v, out);
    return 1;
}

/* [x0, x1] (at depth `depth`) halved d times, each part by piece. */
static int descend(const arcfun *f, double x0, double x1, const double *tg, int d, int depth,
                   sums *out)
{
    double xc = 0.5 * (x0 + x1);
    if (d == 0 || !(xc > x0 && xc < x1))
        return piece(f, x0, x1, tg, depth, out, NULL, 0, NULL);
    double half[NV];
    for (int k = 0; k < NV; k++)
        half[k] = 0.5 * tg[k];
    return descend(f, x0, xc, half, d - 1, depth + 1, out) &&
           descend(f, xc, x1, half, d - 1, depth + 1, out);
}

#define PLAN_MAX 3 /* halvings planned before any piece is tried */
/* With the remainder over the piece from the coefficient's recurrence in
 * intervals, 512 (1crn, 1 thread: 54654 pieces). With the area's and the
 * volume's from the middle's series (vbm1_rational_rest), 0.1, 1, 8, 64,
 * 512 gave 31909, 32392, 35228, 40134, 48032 pieces and 2.96, 2.93, 2.98,
 * 3.09, 3.26 G instructions (callgrind; main 3.98 G). */
#define PLAN_FACTOR 1.0

/* Integrates [x0, x1] as piece does, but first halved as often as the
 * middle's series says it will need: each piece's share of tg against
 * PLAN_FACTOR |c_K| 2 h^(K+1) / (K + 1), the size of the remainder term on
 * a piece of half-width h. The halves piece would try anyway, without
 * the wider pieces it would try and drop first. Only where the pieces
 * start is chosen so; each is still proven by its own Taylor model and
 * halved further where it falls short. *est_area: the area's term above at
 * PLAN_FACTOR 1 (-1 where the series cannot be made), for march. */
static int planned(const arcfun *f, double x0, double x1, const double *tg, sums *out,
                   double *est_area)
{
    vbm_s1 c[NV];
    vbm1_rat kc[2];
    double xc = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
    int rc = integrand(f, f->want, vbx_ia_point(xc), c, VBM1_K, 0, kc), d = 0;
    double hk = 2.0 / (VBM1_K + 1) * h;
    for (int n = 0; n < VBM1_K; n++)
        hk *= h;
    *est_area = -1.0;
    for (int k = 0; rc && k < NV; k++) {
        double mag = vbx_max(fabs(c[k].c[VBM1_K].lo), fabs(c[k].c[VBM1_K].hi));
        double est = PLAN_FACTOR * mag * hk;
        if (k == AREA)
            *est_area = mag * hk;
        for (int e = 0; e < PLAN_MAX && est > tg[k]; e++, est *= 1.0 / (1 << VBM1_K))
            d = e + 1 > d ? e + 1 : d;
    }
    if (d == 0)
        return piece(f, x0, x1, tg, 0, out, rc ? c : NULL, rc, kc);
    return descend(f, x0, x1, tg, d, 0, out);
}

/* The contact alone over [x0, x1] to the width tg[CON], added to *out
 * (est_area: planned's, the first piece's length by vbm_contact_start):
 * pieces stepped along the arc by vbm_contact_step (vbm_contact_tm.h), each
 * proven by piece_values as before, each share the target left times its
 * part of the length left (what a piece leaves unused goes to the next;
 * one kept at its shortest, as piece's MAX_DEPTH, may exceed its share,
 * and the others' then fall back to half the even share). Returns 0 when
 * an interval cannot bound a piece at its shortest. */
#define STEP_MIN 0x1p-20 /* of the arc's length: piece's MAX_DEPTH */
static int march(const arcfun *f, double x0, double x1, const double *tg, double est_area,
                 sums *out)
{
    double a = x0, left = tg[CON], L = x1 - x0, lmin = (x1 - x0) * STEP_MIN;
    if (est_area >= 0.0)
        L *= vbm_contact_start(est_area / tg[CON]);
    while (a < x1) {
        double b = x1 - a <= 1.25 * L || !(a + L > a) ? x1 : a + L, xc = 0.5 * (a + b);
        double share = vbx_max(left * ((b - a) / (x1 - a)), 0.5 * tg[CON] * ((b - a) / (x1 - x0)));
        double t[NV] = {INFINITY, INFINITY, share};
        int last = b - a <= lmin || !(xc > a && xc < b);
        vbx_ia v[NV];
        int ok = piece_values(f, a, b, t, !last, NULL, 0, NULL, v);
        if (!ok && last)
            return 0;
        double rho = ok ? width(v[CON]) / share : INFINITY;
        if (!last && !(rho <= 1.0)) { /* shorter */
            L = vbx_max((b - a) * (ok ? vbm_contact_step(rho) : 0.5), lmin);
            continue;
        }
        add_piece(f, v, out);
        left -= width(v[CON]);
        L = vbx_max((b - a) * vbm_contact_step(rho), lmin);
        a = b;
    }
    return 1;
}

/* The integral from the exact end t (an interval) to the double m inside
 * it: (m - t) times the integrand somewhere in t. */
static int end_piece(const arcfun *f, vbx_ia t, double m, sums *out)
{
    vbm_s1 v[NV];
    if (!integrand(f, f->want & ~(1 << CON), t, v, 0, 0, NULL))
        return 0;
    /* the contact's by contact_bound, not its series (a root, two logs):
     * the end is a few ulps long (c1k --contacts: 8.40 -> 8.15 G) */
    if (f->o.contacts && f->want & 1 << CON && !contact_bound(f, t, &v[CON].c[0]))
        return 0;
    vbx_ia dt = vbx_ia_sub(vbx_ia_point(m), t);
    for (int k = 0; k < NV; k++)
        out->v[k] = vbx_ia_add(out->v[k], vbx_ia_mul(dt, v[k].c[0]));
    return 1;
}

int vbm_arc_integrate(const vbm_owner *o, vbm_arcrec *a, const double *tg, int again,
                      size_t *pieces)
{
    vbx_ia cm, sm;
    vbm_unit_at(0.5 * (a->tp + a->tq), &cm, &sm);
    vbx_ia t0 = vbm_half_tan(a->p[0], a->p[1], cm, sm), t1 = vbm_half_tan(a->q[0], a->q[1], cm, sm);
    if (!(t1.lo > t0.hi))
        return 0;
    sums s = {{vbx_ia_point(0.0), vbx_ia_point(0.0), vbx_ia_point(0.0)}, 0};
    arcfun f;
    phic pc = {.state = 0};
    int wantc = o->contacts;
    f.o = *o;
    f.pc = &pc;
    if (a->own) { /* z = c: F(c) times the angle 2 (atan t1 - atan t0) */
        vbx_ia ang = vbm_arc_angle(t0, t1);
        vbx_ia omz = vbx_ia_sub(vbx_ia_point(1.0), a->c), F = vbx_ia_point(0.0);
        if (wantc && !fcon(&f.o, a->c, &F))
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
    /* again: the values already within their targets stay (1crn
     * --contacts, 1 thread: the second pass integrated ~2800 arcs again,
     * mostly for a contact target the first pass could not know, and
     * redid their area and volume too) */
    int av = !again || width(a->v[AREA]) > tg[AREA] || width(a->v[VOL]) > tg[VOL];
    int con = wantc && (!again || width(a->v[CON]) > tg[CON]);
    f.want = (av ? 1 << AREA | 1 << VOL : 0) | (con ? 1 << CON : 0);
    if (!end_piece(&f, t0, m0, &s) || !end_piece(&f, t1, m1, &s))
        return 0;
    /* the area and volume on their pieces, the contact on its own (it needs
     * more): neither evaluated where only the other falls short */
    double ta[NV] = {tg[AREA], tg[VOL], INFINITY}, tc[NV] = {INFINITY, INFINITY, tg[CON]};
    f.want = 1 << AREA | 1 << VOL;
    double est_area = -1.0;
    if (av && !planned(&f, m0, m1, ta, &s, &est_area))
        return 0;
    f.want = 1 << CON;
    if (con && !march(&f, m0, m1, tc, est_area, &s))
        return 0;
    if (!av) {
        s.v[AREA] = a->v[AREA];
        s.v[VOL] = a->v[VOL];
    }
    if (!con && wantc)
        s.v[CON] = a->v[CON];
    memcpy(a->v, s.v, sizeof a->v);
    *pieces += s.pieces;
    return 1;
}

