/* The contact's integrand where an arc passes near the owner's direction
 * e_j (1 - z < VBM_NEAR_Y over a piece): its series in y = 1 - z with a
 * proven remainder, instead of the quotient by 1 - z that an interval
 * cannot bound there. */
#include "vbm_arcfun.h"

/* The contact's integrand where the arc passes near e_j (y = 1 - z in
 * [0, ybox.hi], ybox.hi < VBM_NEAR_Y, over the piece), without the division by
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
int vbm_arcfun_near(const vbm_arcfun *f, vbx_ia at, int kmax, double yhi, vbm_s1 *con,
                    vbx_ia *rem)
{
    const vbm_owner *o = &f->o;
    vbm_s1 y, area, h, t;
    if (f->pc->state == 0)
        f->pc->state = vbm_owner_phi(o, vbx_ia_point(0.0), &f->pc->phi0) ? 1 : -1;
    const vbm_s1 *phi0 = &f->pc->phi0;
    if (f->pc->state < 0 || !vbm1_rational(&y, f->Emz, 2, vbm_arc_E, 2, at, kmax) ||
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
    if (!vbm_owner_phi(o, yb, &phib) || !(y0.hi <= yhi))
        return 0;
    vbx_ia yk = vbx_ia_point(1.0);
    for (int m = 0; m < VBM1_K; m++)
        yk = vbx_ia_mul(yk, y0);
    *rem = vbx_ia_mul(vbx_ia_mul(area.c[0], yk),
                      vbx_ia_div(phib.c[VBM1_K], vbx_ia_point((double)(VBM1_K + 1))));
    return 1;
}
