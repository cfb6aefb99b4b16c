/* Patches cut by one curve: the SAS circle of one neighbour (ball | j) or
 * the Voronoi edge of two (j | k), each of the form
 *   F(a, b) = l0 + la a + lb b - kappa s = 0,  s = sqrt(1 + a^2 + b^2).
 * Where F is monotone in b over the patch and its root b*(a) stays strictly
 * inside (b0, b1), the two parts {b0 < b < b*(a)} and {b*(a) < b < b1} are
 * mapped onto the box [a0, a1] x [0, 1] by b = b0 + (b*(a) - b0) tau (and
 * likewise above), Jacobian b*(a) - b0, and integrated by the Taylor
 * models of vbm_series.h: the integrand is smooth there, so the error
 * shrinks as a high power of the patch size instead of the h^2 of the
 * jump. b*(a) is the root of the squared equation
 *   (lb^2 - kappa^2) b^2 + 2 l lb b + l^2 - kappa^2 (1 + a^2) = 0,  l = l0 + la a,
 * on the branch where l + lb b has kappa's sign (the other branch solves
 * l + lb b = -kappa s): that sign, checked over the whole box, proves the
 * branch is F's root; kappa exactly 0 makes F linear in b. */
#include <math.h>
#include <stdlib.h>

#include "vbm_piece.h"

static int ia_sign(vbx_ia a)
{
    return a.lo > 0.0 ? 1 : a.hi < 0.0 ? -1 : 0;
}

static vbx_ia ia_hull(vbx_ia a, vbx_ia b)
{
    return (vbx_ia){vbx_min(a.lo, b.lo), vbx_max(a.hi, b.hi)};
}

/* The root b*(a) as a series in a (variable 0) at A. eps picks the branch. */
static int root_series(const vbm_curve *cv, vbx_ia A, int eps, int linear, vbm_ser *root,
                       vbm_ser *lin)
{
    vbm_ser a, l, t, u, disc;
    vbm_var(&a, A, 0);
    vbm_affine(&l, cv->la, &a, cv->l0);
    if (linear) { /* l + lb b = 0 */
        vbm_affine(root, vbx_ia_div(vbx_ia_point(-1.0), cv->lb), &l, vbx_ia_point(0.0));
    } else {
        /* the discriminant (lb l)^2 - aq (l^2 - kappa^2 (1 + a^2)) is
         * kappa^2 (l^2 + aq (1 + a^2)): taken in that form, without the
         * cancelling (lb l)^2 terms that would widen it across 0 */
        vbx_ia k2 = vbx_ia_sqr(cv->kappa), aq = vbx_ia_sub(vbx_ia_sqr(cv->lb), k2);
        /* |kappa| (its sign is proven before a root is sought) */
        vbx_ia ak = cv->kappa.lo > 0.0 ? cv->kappa : vbx_ia_neg(cv->kappa);
        vbm_ser bq;
        vbm_affine(&bq, cv->lb, &l, vbx_ia_point(0.0));
        vbm_square(&disc, &l);
        vbm_square(&t, &a);
        vbm_affine(&t, aq, &t, aq);
        vbm_add(&disc, &disc, &t);
        if (!vbm_sqrt(&u, &disc))
            return 0;
        vbm_affine(&u, vbx_ia_mul(vbx_ia_point((double)eps), ak), &u, vbx_ia_point(0.0));
        vbm_sub(&u, &u, &bq);
        vbm_affine(root, vbx_ia_div(vbx_ia_point(1.0), aq), &u, vbx_ia_point(0.0));
    }
    /* l + lb b* (kappa's sign on the true branch) */
    vbm_affine(&t, cv->lb, root, vbx_ia_point(0.0));
    vbm_add(lin, &l, &t);
    return 1;
}

static int cut_one(const vbm_atom_in *in, const vbm_axes *ax, const vbm_curve *cv, double a0,
                   double a1, double b0, double b1, vbx_ia out[4])
{
    vbx_ia A = {a0, a1}, B = {b0, b1};
    vbx_ia s = vbx_ia_sqrt(vbx_ia_add(vbx_ia_point(1.0), vbx_ia_add(vbx_ia_sqr(A), vbx_ia_sqr(B))));
    int mono = ia_sign(vbx_ia_sub(cv->lb, vbx_ia_mul(cv->kappa, vbx_ia_div(B, s))));
    int linear = cv->kappa.lo == 0.0 && cv->kappa.hi == 0.0, ks = ia_sign(cv->kappa);
    if (!mono || (!linear && !ks))
        return 0;
    if (!linear && !ia_sign(vbx_ia_sub(vbx_ia_sqr(cv->lb), vbx_ia_sqr(cv->kappa))))
        return 0;
    int eps = 0;
    vbm_ser root[2], lin;
    for (int e = -1; e <= 1 && !eps; e += 2) {
        if (!root_series(cv, A, e, linear, &root[1], &lin))
            continue;
        /* the root's range over [a0, a1]: from its ends where it is
         * monotone (the derivative's sign proven over the box), far tighter
         * than the box evaluation */
        vbx_ia range = root[1].c[0];
        if (ia_sign(root[1].c[VBM_IDX(1, 0)]) != 0) {
            vbm_ser r0, r1, l2;
            if (root_series(cv, vbx_ia_point(a0), e, linear, &r0, &l2) &&
                root_series(cv, vbx_ia_point(a1), e, linear, &r1, &l2))
                range = (vbx_ia){vbx_max(range.lo, vbx_min(r0.c[0].lo, r1.c[0].lo)),
                                 vbx_min(range.hi, vbx_max(r0.c[0].hi, r1.c[0].hi))};
        }
        if (!(range.lo > b0 && range.hi < b1))
            continue;
        if (!linear && ia_sign(lin.c[0]) != ks)
            continue;
        eps = e;
    }
    if (!eps)
        return 0;
    double ac = 0.5 * (a0 + a1), ha = 0.5 * (a1 - a0);
    /* F increases with b: below the curve F < 0 (neg owns), above F > 0 */
    int below = mono > 0 ? cv->neg : cv->pos, above = mono > 0 ? cv->pos : cv->neg;
    for (int k = 0; k < 4; k++)
        out[k] = vbx_ia_point(0.0);
    for (int part = 0; part < 2; part++) {
        int owner = part ? above : below;
        vbm_ser m[2][3];
        for (int k = 0; k < 2; k++) {
            vbx_ia Ak = k ? A : vbx_ia_point(ac), Tk = k ? (vbx_ia){0.0, 1.0} : vbx_ia_point(0.5);
            vbm_ser a, tau, rt, jac, b, t, v[3];
            if (!root_series(cv, Ak, eps, linear, &rt, &lin))
                return 0;
            vbm_var(&a, Ak, 0);
            vbm_var(&tau, Tk, 1);
            if (part == 0) { /* b = b0 + (b* - b0) tau */
                vbm_affine(&jac, vbx_ia_point(1.0), &rt, vbx_ia_point(-b0));
                vbm_mul(&t, &jac, &tau);
                vbm_affine(&b, vbx_ia_point(1.0), &t, vbx_ia_point(b0));
            } else { /* b = b* + (b1 - b*) tau */
                vbm_affine(&jac, vbx_ia_point(-1.0), &rt, vbx_ia_point(b1));
                vbm_mul(&t, &jac, &tau);
                vbm_add(&b, &t, &rt);
            }
            if (!vbm_piece(in, owner, ax, &a, &b, &v[0], &v[1], &v[2]))
                return 0;
            for (int i = 0; i < 3; i++)
                vbm_mul(&m[k][i], &v[i], &jac);
        }
        out[0] = vbx_ia_add(out[0], vbm_integrate(&m[0][0], &m[1][0], ha, 0.5));
        out[1] = vbx_ia_add(out[1], vbm_integrate(&m[0][1], &m[1][1], ha, 0.5));
        if (owner >= 0 && in->contacts) {
            int slot = owner == cv->pos ? 2 : 3;
            out[slot] = vbx_ia_add(out[slot], vbm_integrate(&m[0][2], &m[1][2], ha, 0.5));
        }
    }
    return 1;
}

/* The a in (a0, a1) where the curve meets the side b = bc: roots of
 * F(a, bc) = 0 squared, (la^2 - kappa^2) a^2 + 2 m la a + m^2 - kappa^2 c
 * = 0 with m = l0 + lb bc, c = 1 + bc^2, in double at the midpoints of the
 * coefficients (only where to split: the pieces are proven apart). */
static int side_roots(const vbm_curve *cv, double bc, double a0, double a1, double *x)
{
    double l0 = vbx_ia_mid(cv->l0), la = vbx_ia_mid(cv->la), lb = vbx_ia_mid(cv->lb);
    double k = vbx_ia_mid(cv->kappa), m = l0 + lb * bc, c = 1.0 + bc * bc;
    double qa = la * la - k * k, qb = 2.0 * m * la, qc = m * m - k * k * c;
    double r[2];
    int n = 0;
    if (fabs(qa) <= 1e-14 * (la * la + k * k)) {
        if (qb != 0.0)
            r[n++] = -qc / qb;
    } else {
        double disc = qb * qb - 4.0 * qa * qc;
        if (disc < 0.0)
            return 0;
        double sq = sqrt(disc), t = -0.5 * (qb + (qb < 0.0 ? -sq : sq));
        if (t != 0.0)
            r[n++] = qc / t;
        r[n++] = t / qa;
    }
    int m2 = 0;
    for (int i = 0; i < n; i++)
        if (r[i] > a0 && r[i] < a1)
            x[m2++] = r[i];
    return m2;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

/* The sliver [a0, a1] x [b0, b1] around an exit: each point is owned by pos
 * or neg, so each value lies in area x the hull of both owners' integrand
 * ranges over the box (SAS and contacts with 0 for the other owner). */
static int sliver(const vbm_atom_in *in, const vbm_axes *ax, const vbm_curve *cv, double a0,
                  double a1, double b0, double b1, vbx_ia out[4])
{
    vbm_ser a, b, v[3];
    vbm_var(&a, (vbx_ia){a0, a1}, 0);
    vbm_var(&b, (vbx_ia){b0, b1}, 1);
    vbx_ia area = vbx_ia_mul(vbx_ia_sub(vbx_ia_point(a1), vbx_ia_point(a0)),
                             vbx_ia_sub(vbx_ia_point(b1), vbx_ia_point(b0)));
    vbx_ia hull[4];
    for (int side = 0; side < 2; side++) {
        int owner = side ? cv->neg : cv->pos;
        if (!vbm_piece(in, owner, ax, &a, &b, &v[0], &v[1], &v[2]))
            return 0;
        for (int i = 0; i < 2; i++)
            hull[i] = side ? ia_hull(hull[i], v[i].c[0]) : v[i].c[0];
        hull[2 + side] = owner >= 0 && in->contacts ? ia_hull(v[2].c[0], vbx_ia_point(0.0))
                                                    : vbx_ia_point(0.0);
    }
    hull[1] = ia_hull(hull[1], vbx_ia_point(0.0)); /* the owner that is not the ball */
    for (int i = 0; i < 4; i++)
        out[i] = vbx_ia_add(out[i], vbx_ia_mul(area, hull[i]));
    return 1;
}

/* The curve leaves the patch through a side b = b0 or b = b1: the patch is
 * cut into strips in a at those exits, with slivers of half-width e around
 * them; a strip where F has one sign is integrated whole (its owner's
 * Taylor model), one that the curve crosses by cut_one. */
static int cut_clipped(const vbm_atom_in *in, const vbm_axes *ax, const vbm_curve *cv, double a0,
                       double a1, double b0, double b1, vbx_ia out[4])
{
    double x[4];
    int nx = side_roots(cv, b0, a0, a1, x);
    nx += side_roots(cv, b1, a0, a1, x + nx);
    if (nx == 0)
        return 0;
    qsort(x, (size_t)nx, sizeof *x, cmp_double);
    double e = 0x1p-24 * (a1 - a0);
    for (int k = 0; k < 4; k++)
        out[k] = vbx_ia_point(0.0);
    double lo = a0;
    for (int i = 0; i <= nx; i++) {
        /* the strip [lo, hi], then the sliver [hi, next lo] */
        double hi = i < nx ? vbx_max(lo, x[i] - e) : a1;
        double nlo = i < nx ? vbx_min(a1, x[i] + e) : a1;
        while (i + 1 < nx && x[i + 1] - e <= nlo) /* exits closer than 2 e: one sliver */
            nlo = vbx_min(a1, x[++i] + e);
        if (hi > lo) {
            vbx_ia A = {lo, hi}, B = {b0, b1}, r[4];
            vbx_ia s = vbx_ia_sqrt(
                vbx_ia_add(vbx_ia_point(1.0), vbx_ia_add(vbx_ia_sqr(A), vbx_ia_sqr(B))));
            int sg = vbm_curve_sign(cv, A, B, s);
            if (sg) {
                int owner = sg > 0 ? cv->pos : cv->neg;
                if (!vbm_box_integrate(in, owner, ax, lo, hi, b0, b1, &r[0], &r[1], &r[2]))
                    return 0;
                r[3] = r[2];
                r[sg > 0 ? 3 : 2] = vbx_ia_point(0.0);
            } else if (!cut_one(in, ax, cv, lo, hi, b0, b1, r)) {
                return 0;
            }
            for (int k = 0; k < 4; k++)
                out[k] = vbx_ia_add(out[k], r[k]);
        }
        if (nlo > hi && !sliver(in, ax, cv, hi, nlo, b0, b1, out))
            return 0;
        lo = nlo;
    }
    return 1;
}

int vbm_cut_integrate(const vbm_atom_in *in, const vbm_axes *ax, const vbm_curve *cv, double a0,
                      double a1, double b0, double b1, vbx_ia *vol, vbx_ia *sas, vbx_ia *con_pos,
                      vbx_ia *con_neg)
{
    vbx_ia out[4];
    /* the curve as a = a*(b): swap the roles of a and b */
    vbm_axes sw = {ax->w, ax->q, ax->p, ax->sigma};
    vbm_curve cs = *cv;
    cs.la = cv->lb;
    cs.lb = cv->la;
    int ok = cut_one(in, ax, cv, a0, a1, b0, b1, out) ||
             cut_one(in, &sw, &cs, b0, b1, a0, a1, out) ||
             cut_clipped(in, ax, cv, a0, a1, b0, b1, out) ||
             cut_clipped(in, &sw, &cs, b0, b1, a0, a1, out);
    if (!ok)
        return 0;
    *vol = out[0];
    *sas = out[1];
    *con_pos = out[2];
    *con_neg = out[3];
    return 1;
}
