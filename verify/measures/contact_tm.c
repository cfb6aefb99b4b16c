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
 *   con(t) = F(z(t)) a(t),  F(z) = C (G1 - G(q)),  a = an / cd
 * (stokes_cell.c, arc_integral.c). G is a primitive of sqrt(S) / q^3,
 * S = N + 2 delta q, so along the arc
 *   d/dt F(z(t)) = -C sqrt(S) q' / q^3 = -C sqrt(S(t)) rho(t),
 *   rho = q' / q^3 = (Pq' E - Pq E') E / Pq^3,
 * where Pq' E - Pq E' = p1 + 2 (p2 - p0) t - p1 t^2 (Pq = p0 + p1 t + p2 t^2:
 * the t^3 terms cancel exactly, written so), and S = (N E + 2 delta Pq) / E:
 * rho, S and a are rational functions of t, each a Taylor model about the
 * piece's middle xc with a remainder from closed forms (vbm1_tm,
 * series_tm.c: rational functions, roots, products), and
 * - F(z(xc + x)) = F0 + int_0^x phi, phi = -C sqrt(S) rho, whose model
 *   at the order K - 1 is P_phi(s) + s^(K-1) r_phi(s): the integral of
 *   P_phi's terms is exact and int_0^x s^(K-1) r_phi(s) ds = r_phi(xi) x^K / K (s^(K-1) has
 *   one sign between 0 and x, r_phi is continuous: the mean value theorem
 *   for integrals), so F's model has the order K with the rest r_phi / K.
 * The true coefficients lie in the computed intervals and every bound above
 * is an interval evaluation over the piece of the true functions' formulas
 * (inclusion-isotone), so *rest encloses the true remainder. Everything
 * is smooth on the piece where the checks hold: Pq^3, cd and E, B of each
 * rational, sqrt(S) + T and S proven away from 0 over it (q keeps the sign
 * it has at xc, where F0's logs proved it > 0). */
#include "vbm_contact_tm.h"
#include "vbm_piece.h"

int vbm_contact_tm(const vbm_contact_rat *p, const vbm_owner *o, vbx_ia F0, double xc, vbx_ia x,
                   vbm_s1 *c, vbx_ia *rest)
{
    const int K = VBM1_K, k1 = VBM1_K - 1;
    vbm1_tm rho, rs, phi, F, a, con;
    if (!vbm1_tm_rational(&rho, p->rn, 4, p->rd, 6, xc, k1, x))
        return 0;
    if (vbm_ia_is_zero(o->delta)) { /* S = N exactly */
        vbm1_const(&rs.p, o->rN);
        rs.rest = vbx_ia_point(0.0);
    } else {
        vbm1_tm s;
        if (!vbm1_tm_rational(&s, p->sn, 2, p->sd, 2, xc, k1, x) || !vbm1_tm_sqrt(&rs, &s, k1, x))
            return 0;
    }
    vbm1_tm_mul(&phi, &rho, &rs, k1, x);
    vbx_ia mC = vbx_ia_neg(o->C);
    vbm1_const(&F.p, F0);
    for (int n = 1; n < K; n++)
        F.p.c[n] = vbx_ia_div(vbx_ia_mul(mC, phi.p.c[n - 1]), vbx_ia_point((double)n));
    F.rest = vbx_ia_div(vbx_ia_mul(mC, phi.rest), vbx_ia_point((double)K));
    if (!vbm1_tm_rational(&a, p->an, 2, p->cd, 4, xc, K, x))
        return 0;
    vbm1_tm_mul(&con, &F, &a, K, x);
    *c = con.p;
    *rest = con.rest;
    return 1;
}
