/* The contact's integrand along an arc over a piece as a Taylor model with
 * a remainder from closed forms (vbm_contact_tm.h).
 *
 * Why: the contact's remainder over a piece came from its series over the
 * whole piece (a root, two logs and three rational recurrences in
 * intervals), whose widths grow with every order: on 1crn --contacts the
 * order-K coefficient's interval over a piece was e^14.9 times (geometric
 * mean) the hull of its values at 33 points of the piece, and the pieces
 * were halved until the box was narrow, not until the remainder was small.
 *
 * The model. Along the arc (t = tan(angle / 2), E = 1 + t^2) z = Pz / E and
 * q = D z + delta = Pq / E, and the contact's integrand is
 *   con(t) = H(t) a(t),  H = F(z(t)) / (1 - z(t)),  F(z) = C (G1 - G(q)),
 *   a = an / ad = (1 - z) dphi/dt, the area's integrand
 * (stokes_cell.c, arc_integral.c). G is a primitive of sqrt(S) / q^3,
 * S = N + 2 delta q, so along the arc
 *   d/dt F(z(t)) = -C sqrt(S) q' / q^3 = -C sqrt(S(t)) rho(t),
 *   rho = q' / q^3 = (Pq' E - Pq E') E / Pq^3,
 * where Pq' E - Pq E' = p1 + 2 (p2 - p0) t - p1 t^2 (Pq = p0 + p1 t + p2 t^2:
 * the t^3 terms cancel exactly, written so): rho, y = 1 - z and a are
 * rational functions of t, each a Taylor model about the piece's middle xc
 * with a remainder from closed forms (vbm1_tm, series_tm.c: rational
 * functions, roots, products), S = N + 2 delta ((D + delta) - D y) is y's
 * model mapped (the order K - 1 with the rest y_(K-1) + x r_y; until stop
 * 51's cont52 it was a fourth rational, (N E + 2 delta Pq) / E), and
 * - F(z(xc + x)) = F0 + int_0^x phi, phi = -C sqrt(S) rho, whose model
 *   at the order K - 1 is P_phi(s) + s^(K-1) r_phi(s): the integral of
 *   P_phi's terms is exact and int_0^x s^(K-1) r_phi(s) ds = r_phi(xi) x^K / K (s^(K-1) has
 *   one sign between 0 and x, r_phi is continuous: the mean value theorem
 *   for integrals), so F's model has the order K with the rest r_phi / K;
 * - con = F a / y = F an / cd, y = 1 - z = Emz / E, a = an / (E Po), cd =
 *   Po Emz (polynomials of t, moved to xc: no rest), by the quotient rule
 *   with a polynomial divisor (vbm1_tm_mul_div_poly, series_tm.c): its rest
 *   is divided by cd's range over the piece (Horner's value met with the
 *   product of Po's and Emz's ranges over T, vbm1_poly2_range), proven
 *   > 0. F and y vanish together at z = 1, so con is smooth where 1 / y
 *   has poles: at the complex zeros of Emz, off the arc but near it where
 *   the arc passes near e_j. Stop 50 took con = F (an / cd) with the
 *   rational's rest M / B, which carried those poles ((h / distance)^K);
 *   stop 51 (cont51) H = F / y with y a rational model, times a's model
 *   (c1k's kept contact pieces 71,298 -> 53,738); stop 53 (contm54) the
 *   same function with cd a polynomial: no model of y or a, no product
 *   (c1k: ~36 k -> ~15 k instructions a try, by callgrind).
 * The true coefficients lie in the computed intervals and every bound above
 * is an interval evaluation over the piece of the true functions' formulas
 * (inclusion-isotone), so *rest encloses the true remainder. Everything
 * is smooth on the piece where the checks hold: Pq^3, cd and E, B of each
 * rational, sqrt(S) + T, S and y proven away from 0 over it (q keeps the sign
 * it has at xc, where F0's logs proved it > 0). */
#include <math.h>

#include "vbm_contact_tm.h"
#include "vbm_dot.h"
#include "vbm_piece.h"

/* v f + w for a constant f, as vbm1_affine's constant term (a point v by
 * vbm_ia_mul_point, the same bounds as vbx_ia_mul's). */
static vbx_ia affine0(vbx_ia v, vbx_ia f, vbx_ia w)
{
    return vbx_ia_add(v.lo == v.hi ? vbm_ia_mul_point(v.lo, f) : vbx_ia_mul(v, f), w);
}

/* a b as vbm1_mul_to's constant term (vbm_dotn of one term). */
static vbx_ia mul0(vbx_ia a, vbx_ia b)
{
    return vbm_dotn(&a, 1, &b, -1, 1);
}

/* G(q) = -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q)
 *        - delta^2 / (2 N sqrt N) log |(sqrt S - sqrt N) / (sqrt S + sqrt N)|,
 * S = N + 2 delta q: a primitive of sqrt(S) / q^3 (the log's argument as
 * 2 |delta| q / (sqrt S + sqrt N)^2, q > 0, one log: until stop 52 two, of
 * q and of sqrt S + sqrt N; no log term for delta = 0), at a constant q.
 * The constant terms of the order-0 series (vbm1_sqrt_to, _recip_to,
 * _mul_to, _affine, _add) it took until stop 53, operation for operation
 * (the same bounds), without their K orders of zeros: F0 at every contact
 * try's middle (arc_owner.c's vbm_owner_fcon; vbm_contact_tm.h). */
int vbm_contact_g(const vbm_owner *o, vbx_ia q, vbx_ia *G)
{
    vbx_ia zero = vbx_ia_point(0.0);
    vbx_ia S = affine0(vbx_ia_add(o->delta, o->delta), q, o->N);
    if (!(S.lo > 0.0) || !(q.lo > 0.0))
        return 0;
    vbx_ia r = vbx_ia_sqrt(S), iq = vbx_ia_div(vbx_ia_point(1.0), q);
    vbx_ia t = mul0(r, iq); /* sqrt S / q */
    vbx_ia g = mul0(mul0(t, S), iq); /* S^(3/2) / q^2 */
    g = affine0(vbx_ia_neg(o->hN), g, zero);
    g = vbx_ia_add(g, affine0(vbx_ia_mul(o->delta, o->hN), t, zero));
    if (!vbm_ia_is_zero(o->delta)) {
        vbx_ia sn = vbx_ia_add(r, o->rN);
        vbx_ia l = vbx_ia_add(vbm_ia_log(vbx_ia_div(q, vbx_ia_sqr(sn))), o->lnd);
        g = vbx_ia_add(g, vbx_ia_mul(vbx_ia_neg(o->kL), l));
    }
    *G = g;
    return 1;
}

int vbm_contact_tm(const vbm_contact_rat *p, const vbm_owner *o, vbx_ia F0, double xc, vbx_ia x,
                   vbm_s1 *c, vbx_ia *rest)
{
    const int K = VBM1_K, k1 = VBM1_K - 1;
    vbm1_tm rho, phi, F, con;
    if (!vbm1_tm_rational(&rho, p->rn, 4, p->rd, 6, xc, k1, x))
        return 0;
    if (vbm_ia_is_zero(o->delta)) { /* S = N exactly: phi's root a constant */
        for (int n = 0; n <= VBM1_K; n++)
            phi.p.c[n] = vbx_ia_mul(o->rN, rho.p.c[n]);
        phi.rest = vbx_ia_mul(o->rN, rho.rest);
    } else { /* S = N + 2 delta q, q = D z + delta = (D + delta) - D y: y's
              * model mapped at the order K - 1 (vbm1_tm_affine), as
              * vbm_owner_phi's (arc_owner.c), one rational less a piece */
        vbm1_tm y, q, s, rs;
        if (!vbm1_tm_rational(&y, p->yn, 2, p->sd, 2, xc, K, x))
            return 0;
        vbm1_tm_affine(&q, vbx_ia_neg(o->D), &y, vbx_ia_add(o->D, o->delta), K, k1, x);
        vbm1_tm_affine(&s, vbx_ia_add(o->delta, o->delta), &q, o->N, k1, k1, x);
        if (!vbm1_tm_sqrt(&rs, &s, k1, x))
            return 0;
        vbm1_tm_mul(&phi, &rho, &rs, k1, x);
    }
    vbx_ia mC = vbx_ia_neg(o->C);
    vbm1_const(&F.p, F0);
    for (int n = 1; n < K; n++)
        F.p.c[n] = vbx_ia_div(vbx_ia_mul(mC, phi.p.c[n - 1]), vbx_ia_point((double)n));
    F.rest = vbx_ia_div(vbx_ia_mul(mC, phi.rest), vbx_ia_point((double)K));
    /* con = F an / cd, cd = po yn = Po Emz = E^2 (1 + z) (1 - z): the
     * quotient rule with a polynomial divisor (series_tm.c). F and 1 - z
     * vanish together at z = 1, so the quotient is as smooth as F / (1 - z)
     * there, and the rest is divided by cd's real range over the piece: no
     * pole of 1 / cd off the arc enters it (until stop 53, F / y by the
     * quotient rule with y = 1 - z a rational model, then times an / ad,
     * one more rational and product: ~36 k instructions a try on c1k) */
    vbx_ia an[3], cd[5], T = vbx_ia_add(vbx_ia_point(xc), x);
    vbm1_poly_at(an, p->an, 2, xc);
    vbm1_poly_at(cd, p->cd, 4, xc);
    /* cd over the piece: Horner over x met with the product of its two
     * quadratic factors' ranges over T (t once each; stop 52 found the
     * Horner value of 1 - z alone held 0 on 6,477 of c1k's 68,684 tries) */
    vbx_ia cdx = vbx_ia_add(vbx_ia_mul(cd[4], x), cd[3]);
    for (int n = 2; n >= 0; n--)
        cdx = vbx_ia_add(vbx_ia_mul(cdx, x), cd[n]);
    cdx = vbm1_meet(cdx, vbx_ia_mul(vbm1_poly2_range(p->po, T), vbm1_poly2_range(p->yn, T)));
    if (!vbm1_tm_mul_div_poly(&con, &F, an, 2, cd, 4, cdx, K, x))
        return 0;
    *c = con.p;
    *rest = con.rest;
    return 1;
}

/* The contact's pieces along an arc (arc_march.c) are stepped,
 * not halved. The model's remainder term on a piece of length L grows as
 * L^(K+1) and the piece's share of the target as L, so a piece whose width
 * w came out at the ratio rho = w / share tells the length that would have
 * met its share: L rho^(-1/K). Halving a piece that misses leaves each half
 * at ~rho / 1024, and a piece that meets its share is never made longer:
 * on c1k --contacts (the capsid's first 1000 balls) stop 50's kept contact
 * pieces spread evenly in log2(w / share) from -1 to -13, and its plan
 * cost a series of the contact at each arc's middle. Here the next length
 * is the last's times 2^(j/4), the largest j in -8..8 with 2^(j K / 4) <=
 * STEP_SAFETY / rho (rho's binary exponent: no libm, the same pieces on
 * every machine), and a piece that misses is tried again shorter by the
 * same rule. Only where pieces end follows from it, never a bound. */
#define STEP_SAFETY 0.25
/* A piece that missed (rho > 1) is tried again at most this part of its
 * length. march takes the whole rest of the arc once it is within 1.25
 * lengths; a retry factor >= 0.8 could then give the same piece again and
 * loop (seen at STEP_SAFETY 0.5 on c1k, stop 52). At 0.75 the retry is at
 * most 0.9375 of the rest, so each miss shortens the piece; at STEP_SAFETY
 * 0.25 the rule's factor for rho > 1 is at most 2^-1/2 and the cap never
 * acts (the same pieces). */
#define RETRY_CAP 0.75

double vbm_contact_step(double rho)
{
    return vbm_contact_step_at(rho, STEP_SAFETY);
}

double vbm_contact_step_at(double rho, double safety)
{
    static const double q[4] = {1.0, 1.189207115002721, 1.4142135623730951, 1.681792830507429};
    int j = 8;
    if (!(rho < INFINITY))
        j = -8;
    else if (rho > 0.0) {
        int e;
        frexp(safety / rho, &e); /* 2^(e-1) <= safety / rho < 2^e */
        int num = 4 * (e - 1);         /* the largest j with j K / 4 <= e - 1 */
        j = num >= 0 ? num / VBM1_K : -((-num + VBM1_K - 1) / VBM1_K);
        j = j < -8 ? -8 : j > 8 ? 8 : j;
    }
    int e = j >= 0 ? j / 4 : -((-j + 3) / 4);
    double f = ldexp(q[j - 4 * e], e);
    return !(rho <= 1.0) && f > RETRY_CAP ? RETRY_CAP : f;
}

/* The first piece: the whole arc, unless the area's term |c_K| 2 h^(K+1) /
 * (K + 1) at the arc's middle over the contact's target (r) exceeds
 * START_SHORT: then at most half the arc, by vbm_contact_step of
 * START_RHO r as if that were the whole arc's rho. On c1k --contacts
 * (stop 51) 13,038 of the 25,818 arcs' first tries missed; by r's binary
 * exponent they missed at 2^-18 to 2^-9 in 20 to 95 % of arcs and at 2^-9
 * and above in 99 %, and the first tries that met their share had
 * log2 rho - log2 r at 13 to 14 (median) at every exponent (the contact's
 * integrand per area is the area's times a factor of order 1; its model's
 * rest is wider than the series' term). The tries fell 79,355 -> 68,685,
 * the pieces rose 149,963 -> 150,774; START_SHORT 2^-20, 2^-16 or 2^-14,
 * START_RHO 2^12 or 2^14, the cap 0.35, 0.71 or 1: 68,577 to 71,194 tries. */
#define START_SHORT 0x1p-18
#define START_RHO 0x1p13

double vbm_contact_start(double r)
{
    if (!(r > START_SHORT))
        return 1.0;
    double q = vbm_contact_step(START_RHO * r);
    return q < 0.5 ? q : 0.5;
}
