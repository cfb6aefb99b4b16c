/* The geometry of caps and their circles (vbm_caps.h): a circle's axis and
 * frame, exact unit vectors at an angle, half-angle tangents and arc angles
 * (arc_integral.c's), and caps bounding arcs. */
#include <math.h>

#include "vbm_caps.h"
#include "vbm_dot.h"
#include "vbm_piece.h"

static void cross3(const vbx_ia *a, const vbx_ia *b, vbx_ia *r)
{
    r[0] = vbx_ia_sub(vbx_ia_mul(a[1], b[2]), vbx_ia_mul(a[2], b[1]));
    r[1] = vbx_ia_sub(vbx_ia_mul(a[2], b[0]), vbx_ia_mul(a[0], b[2]));
    r[2] = vbx_ia_sub(vbx_ia_mul(a[0], b[1]), vbx_ia_mul(a[1], b[0]));
}

/* vbm_circle_of without the frame (kind, a, c and s). */
int vbm_circle_axis(const vbm_cap *cp, vbm_circle *c)
{
    return vbm_circle_axis_nn(cp, vbm_dot3(cp->n, cp->n), c);
}

int vbm_circle_axis_nn(const vbm_cap *cp, vbx_ia n2, vbm_circle *c)
{
    c->framed = 0;
    vbx_ia nn = vbx_ia_sqrt(n2);
    vbx_ia lo = vbx_ia_sub(nn, cp->h), hi = vbx_ia_add(nn, cp->h);
    if (lo.hi < 0.0) {
        c->kind = VBM_CAP_NONE;
        return 1;
    }
    if (hi.hi < 0.0) {
        c->kind = VBM_CAP_ALL;
        return 1;
    }
    if (!(lo.lo > 0.0 && hi.lo > 0.0 && nn.lo > 0.0))
        return 0;
    c->kind = VBM_CAP_CIRCLE;
    /* times one enclosure of 1 / |n| (it holds the exact reciprocal, so
     * each product holds the exact quotient): one division where five took
     * twenty */
    vbx_ia inn = vbx_ia_div(vbx_ia_point(1.0), nn);
    for (int k = 0; k < 3; k++)
        c->a[k] = vbx_ia_mul(cp->n[k], inn);
    c->c = vbx_ia_mul(cp->h, inn);
    c->s = vbx_ia_mul(vbx_ia_sqrt(vbx_ia_mul(lo, hi)), inn);
    return 1;
}

/* The frame e1, e2 of a circle whose axis is set. Returns 0 when the
 * intervals cannot normalise it. */
int vbm_circle_frame(vbm_circle *c)
{
    /* e1 = a x f / |a x f| with f the axis least along a (chosen on
     * midpoints: any fixed f gives an exact frame) */
    int f = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(vbx_ia_mid(c->a[k])) < fabs(vbx_ia_mid(c->a[f])))
            f = k;
    vbx_ia fv[3] = {vbx_ia_point(0.0), vbx_ia_point(0.0), vbx_ia_point(0.0)}, t[3];
    fv[f] = vbx_ia_point(1.0);
    cross3(c->a, fv, t);
    vbx_ia tn = vbx_ia_sqrt(vbm_dot3(t, t));
    if (!(tn.lo > 0.0))
        return 0;
    for (int k = 0; k < 3; k++)
        c->e1[k] = vbx_ia_div(t[k], tn);
    cross3(c->a, c->e1, c->e2);
    c->framed = 1;
    return 1;
}

int vbm_circle_of(const vbm_cap *cp, vbm_circle *c)
{
    return vbm_circle_axis(cp, c) && (c->kind != VBM_CAP_CIRCLE || vbm_circle_frame(c));
}

void vbm_unit_at(double t, vbx_ia *x, vbx_ia *y)
{
    vbx_ia cx = vbx_ia_point(cos(t)), sy = vbx_ia_point(sin(t));
    vbx_ia n = vbx_ia_sqrt(vbx_ia_add(vbx_ia_sqr(cx), vbx_ia_sqr(sy)));
    *x = vbx_ia_div(cx, n);
    *y = vbx_ia_div(sy, n);
}

/* A cap around an arc of circle C (c, s its cosine and sine, the arc from
 * angle tp to tq <= tp + 2.6 and its ends p, q): its centre *M, the point
 * of C at the angle (tp + tq) / 2, and the cosine of its angular radius
 * rho, *cr: every point u(t) of the arc has u(t).M = c^2 + s^2 cos(t - tm)
 * with |t - tm| at most the larger of the ends' (< pi), so u(t).M is at
 * least the smaller of p.M and q.M. Returns 0 when that lower bound is not
 * proven > -1 (rho >= pi: no use). */
int vbm_arc_bound(const vbm_circle *C, const vbm_arc *a, vbx_ia *M, double *cr)
{
    vbx_ia mx, my;
    vbm_unit_at(0.5 * (a->tp + a->tq), &mx, &my);
    vbx_ia c2 = vbx_ia_sqr(C->c), s2 = vbx_ia_sqr(C->s);
    vbx_ia dp = vbx_ia_add(vbx_ia_mul(mx, a->p[0]), vbx_ia_mul(my, a->p[1]));
    vbx_ia dq = vbx_ia_add(vbx_ia_mul(mx, a->q[0]), vbx_ia_mul(my, a->q[1]));
    double lo = vbx_min(vbx_ia_add(c2, vbx_ia_mul(s2, dp)).lo,
                        vbx_ia_add(c2, vbx_ia_mul(s2, dq)).lo);
    for (int k = 0; k < 3; k++)
        M[k] = vbx_ia_add(vbx_ia_mul(C->c, C->a[k]),
                          vbx_ia_mul(C->s, vbx_ia_add(vbx_ia_mul(mx, C->e1[k]),
                                                      vbx_ia_mul(my, C->e2[k]))));
    *cr = lo;
    return lo > -1.0;
}

/* Whether cap m holds the cap of centre M and angular radius rho (cos rho
 * >= cr): angle(M, a_m) + rho < alpha_m, alpha_m m's angular radius. That
 * asks alpha_m - rho in [0, pi] (cos alpha_m = c_m < cr proves rho <
 * alpha_m; both are at most pi) and then cos angle(M, a_m) = M.a_m >
 * cos(alpha_m - rho) = c_m cos rho + s_m sin rho (s_m, sin rho >= 0),
 * whose right side is bounded over every cos rho in [cr, 1] in intervals
 * (sinr = vbm_cap_sine(cr), made once per cap B). */
vbx_ia vbm_cap_sine(double cr)
{
    vbx_ia cosr = {cr, 1.0};
    return vbx_ia_sqrt(vbx_ia_sub(vbx_ia_point(1.0), vbx_ia_sqr(cosr)));
}

int vbm_cap_holds(const vbm_circle *cm, const vbx_ia *M, double cr, vbx_ia sinr)
{
    vbx_ia cosr = {cr, 1.0};
    if (!(cm->c.hi < cr))
        return 0;
    vbx_ia rhs = vbx_ia_add(vbx_ia_mul(cm->c, cosr), vbx_ia_mul(cm->s, sinr));
    return vbm_dot3(M, cm->a).lo > rhs.hi;
}

/* The bounding cap of arcs (vbm_caps.h): a cap B = {u : u.M >= cr}
 * holding each arc's bounding cap (vbm_arc_bound: centre M_i, cos rho_i >=
 * cr_i): every point of arc i lies within theta_i + rho_i of M, theta_i the
 * angle between M and M_i, so u.M >= cos(theta_i + rho_i) when that sum is
 * below pi (cos theta_i > -cos rho_i), >= cl cr_i - sqrt(1 - cl^2)
 * sqrt(1 - cr_i^2) with cos theta_i >= cl. Then a set whose boundary lies
 * on the arcs and which misses a point P outside B (P.M < cr) lies in B:
 * its part outside B would be open and closed in B's complement, a
 * connected set holding P, and not all of it. */
int vbm_arcs_cap(const vbm_circle *circ, const vbm_arc *arc, size_t n, const vbx_ia *out,
                 vbx_ia *tmp, vbx_ia *M, double *cr)
{
    if (n == 0)
        return 0;
    vbx_ia *Mi = tmp;
    double *cri = (double *)(void *)(Mi + 3 * n), c[3] = {0.0, 0.0, 0.0};
    for (size_t i = 0; i < n; i++) {
        if (!vbm_arc_bound(&circ[arc[i].cap], &arc[i], Mi + 3 * i, &cri[i]))
            return 0;
        for (int k = 0; k < 3; k++)
            c[k] += vbx_ia_mid(Mi[3 * i + k]);
    }
    /* the centre: the arcs' middles' mean, normalised in intervals (they
     * hold the exact unit vector c / |c|) */
    vbx_ia cv[3] = {vbx_ia_point(c[0]), vbx_ia_point(c[1]), vbx_ia_point(c[2])};
    vbx_ia cn = vbx_ia_sqrt(vbm_dot3(cv, cv)), one = vbx_ia_point(1.0);
    if (!(cn.lo > 0.0))
        return 0;
    vbx_ia icn = vbx_ia_div(one, cn);
    for (int k = 0; k < 3; k++)
        M[k] = vbx_ia_mul(cv[k], icn);
    double lo = 1.0;
    for (size_t i = 0; i < n; i++) {
        double cl = vbm_dot3(M, Mi + 3 * i).lo;
        vbx_ia ca = vbx_ia_point(cl > 1.0 ? 1.0 : cl), ri = vbx_ia_point(cri[i]);
        if (!(vbx_ia_add(ca, ri).lo > 0.0))
            return 0;
        vbx_ia sl = vbx_ia_sqrt(vbx_ia_sub(one, vbx_ia_sqr(ca)));
        vbx_ia sr = vbx_ia_sqrt(vbx_ia_sub(one, vbx_ia_sqr(ri)));
        double b = vbx_ia_sub(vbx_ia_mul(ca, ri), vbx_ia_mul(sl, sr)).lo;
        if (!(b > -1.0))
            return 0;
        lo = vbx_min(lo, b);
    }
    *cr = lo;
    return vbm_dot3(out, M).hi < lo; /* the point outside B */
}

vbx_ia vbm_half_tan(vbx_ia x, vbx_ia y, vbx_ia cm, vbx_ia sm)
{
    vbx_ia xr = vbx_ia_add(vbx_ia_mul(x, cm), vbx_ia_mul(y, sm));
    vbx_ia yr = vbx_ia_sub(vbx_ia_mul(y, cm), vbx_ia_mul(x, sm));
    return vbx_ia_div(yr, vbx_ia_add(vbx_ia_point(1.0), xr));
}

/* where 1 + t0 t1 > 0 is proven (|t| < 0.73 on arcs shorter than 2.6 rad,
 * so always there) 2 atan((t1 - t0) / (1 + t0 t1)), one MPFR atan where the
 * difference took two (1crn, 1 thread: they were 5 % of the CPU) */
vbx_ia vbm_arc_angle(vbx_ia t0, vbx_ia t1)
{
    vbx_ia den = vbx_ia_add(vbx_ia_point(1.0), vbx_ia_mul(t0, t1)), ang;
    if (den.lo > 0.0)
        ang = vbm_ia_atan(vbx_ia_div(vbx_ia_sub(t1, t0), den));
    else
        ang = vbx_ia_sub(vbm_ia_atan(t1), vbm_ia_atan(t0));
    return vbx_ia_add(ang, ang);
}
