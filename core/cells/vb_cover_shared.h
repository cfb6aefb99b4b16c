/* The direction cover of a Voronoi cell of spheres: the math shared by the
 * plain-C proposer (core/cells/cover.c) and the OpenCL one (gpu/cover.cl).
 * Compiles as C11 and as OpenCL C. Names carry the prefix vbq_.
 *
 * Why a cover proves completeness. Put sphere i at the origin; a neighbour j
 * is d = c_j - c_i, delta = R_j - R_i, N = |d|^2 - delta^2 (N > 0 exactly
 * when neither sphere contains the other). The ray from c_i in unit
 * direction u meets the correct sheet of the bisector of i and j at distance
 *     s_j(u) = N / (2 (u.d + delta))     when u.d + delta > 0,
 * and never otherwise (vb_geom_shared.h derives it). So along u the nearest
 * bisector is the one with the largest
 *     f_j(u) = a_j . u + b_j,   a_j = d / N,   b_j = delta / N,
 * if that largest value is positive, and none (the ray runs to infinity)
 * otherwise. Writing f_inf = 0 for "infinity", the cell's boundary seen from
 * c_i is the upper envelope of the affine functions {f_j} and f_inf on the
 * unit sphere, and a vertex of the cell with neighbours j, k, l is a
 * direction where f_j = f_k = f_l >= every other f, with the common value
 * > 0 (a common value 0 would be a vertex at infinity).
 *
 * The cover splits the six faces of the cube [-1,1]^3 into squares (patches;
 * the directions u/|u| of a square's points). For a patch P it encloses every
 * f_j over P in [lo_j, hi_j] (rigorously: see vbq_patch_box, vbq_nb_make and
 * vbq_eval); j can be the largest anywhere in P only if hi_j >= LO(P) =
 * max(0, max_k lo_k). Every vertex of the cell in a direction of P therefore
 * has its three neighbours among the labels that survive that test, and the
 * quadruples of i with three surviving labels, solved exactly, hold every
 * vertex of the cell in P. The patches of the cover tile the sphere of
 * directions, so the union over the patches holds every vertex of the cell.
 * The decisions made here only ever drop a label whose exclusion is proven
 * by the enclosures; nothing that is uncertain is decided.
 *
 * Floating point: every enclosure below is computed in round-to-nearest
 * with its error bound written beside it; contraction into FMA is off on
 * both sides (an FMA would only shrink the error). u = 2^-53. */
#ifndef VB_COVER_SHARED_H
#define VB_COVER_SHARED_H

#include "vb_geom_shared.h"

/* A neighbour of the base sphere in the cover: f(u) = a . u + b, known to
 * within err for every unit u (|u|_inf <= 1): |a~ - a|_1 + |b~ - b| <= err
 * for the exact a, b of the input decimals. id is the sphere index. */
typedef struct vbq_nb {
    double ax, ay, az, b;
    double err;
    vbs_u32 id, pad;
} vbq_nb;
VBS_ASSERT_LAYOUT(sizeof(vbq_nb) == 48, "vbq_nb layout shared with OpenCL");

/* c in the enclosures: 2e-15 > 18 u. */
#define VBQ_C 2e-15
/* A floor for sums of non-negative terms that may underflow. */
#define VBQ_TINY 1e-300

/* ---- interval helpers (outward by one double, C and OpenCL) --------------
 * For an exact result x of +, -, *, / of doubles, round-to-nearest returns r
 * with pred(r) <= x <= succ(r) (verify/vbx_ia.h gives the proof). */
VBS_FN double vbq_up(double x)
{
    return nextafter(x, (double)INFINITY);
}

VBS_FN double vbq_down(double x)
{
    return nextafter(x, -(double)INFINITY);
}

VBS_FN void vbq_sub_ia(double alo, double ahi, double blo, double bhi, double *lo, double *hi)
{
    *lo = vbq_down(alo - bhi);
    *hi = vbq_up(ahi - blo);
}

VBS_FN void vbq_sqr_ia(double lo, double hi, double *rlo, double *rhi)
{
    double l = VBS_FABS(lo), h = VBS_FABS(hi);
    double mx = l > h ? l : h, mn = l < h ? l : h;
    *rlo = (lo <= 0.0 && hi >= 0.0) ? 0.0 : vbq_down(mn * mn);
    if (*rlo < 0.0)
        *rlo = 0.0;
    *rhi = vbq_up(mx * mx);
}

/* a / b for an interval b > 0 (callers check). */
VBS_FN void vbq_div_pos_ia(double alo, double ahi, double blo, double bhi, double *lo, double *hi)
{
    double q1 = alo / blo, q2 = alo / bhi, q3 = ahi / blo, q4 = ahi / bhi;
    double l = q1 < q2 ? q1 : q2, h = q1 > q2 ? q1 : q2;
    l = q3 < l ? q3 : l;
    h = q3 > h ? q3 : h;
    l = q4 < l ? q4 : l;
    h = q4 > h ? q4 : h;
    *lo = vbq_down(l);
    *hi = vbq_up(h);
}

/* ---- the neighbours ------------------------------------------------------ */

/* Fills nb for base (ci, Ri) and sphere j (cj, Rj), all doubles nearest to
 * the input decimals, so every exact input lies in [pred(x), succ(x)]. The
 * enclosure of a = d / N and b = delta / N is interval arithmetic from those
 * input intervals; a~, b~ are the midpoints and err the half-widths summed
 * (|u|_inf <= 1), rounded up. Returns 0 when the enclosure of N does not
 * prove N > 0 (nested or nearly nested spheres: the caller keeps j in every
 * patch), 1 otherwise. */
VBS_FN int vbq_nb_make(double cix, double ciy, double ciz, double ri, double cjx, double cjy,
                       double cjz, double rj, vbs_u32 j, vbq_nb *nb)
{
    double dlo[4], dhi[4];
    double ci[4] = {cix, ciy, ciz, ri}, cj[4] = {cjx, cjy, cjz, rj};
    for (int k = 0; k < 4; k++)
        vbq_sub_ia(vbq_down(cj[k]), vbq_up(cj[k]), vbq_down(ci[k]), vbq_up(ci[k]), &dlo[k],
                   &dhi[k]);
    double slo = 0.0, shi = 0.0;
    for (int k = 0; k < 3; k++) {
        double qlo, qhi;
        vbq_sqr_ia(dlo[k], dhi[k], &qlo, &qhi);
        slo = vbq_down(slo + qlo);
        shi = vbq_up(shi + qhi);
    }
    double rlo, rhi, nlo, nhi;
    vbq_sqr_ia(dlo[3], dhi[3], &rlo, &rhi);
    vbq_sub_ia(slo, shi, rlo, rhi, &nlo, &nhi);
    nb->id = j;
    nb->pad = 0u;
    if (!(nlo > 0.0)) {
        nb->ax = nb->ay = nb->az = nb->b = 0.0;
        nb->err = (double)INFINITY;
        return 0;
    }
    double mid[4], err = 0.0;
    for (int k = 0; k < 4; k++) {
        double lo, hi;
        vbq_div_pos_ia(dlo[k], dhi[k], nlo, nhi, &lo, &hi);
        mid[k] = 0.5 * lo + 0.5 * hi;
        /* |exact - mid| <= max(hi - mid, mid - lo), each rounded up. */
        double e1 = vbq_up(hi - mid[k]), e2 = vbq_up(mid[k] - lo);
        err = vbq_up(err + (e1 > e2 ? e1 : e2));
    }
    nb->ax = mid[0];
    nb->ay = mid[1];
    nb->az = mid[2];
    nb->b = mid[3];
    nb->err = err;
    return 1;
}

/* ---- the patches --------------------------------------------------------- */

/* Enclosing box of the directions of the square [u0,u1] x [v0,v1] on cube
 * face f (vbs_face_dir): every unit direction w of the square has
 * |w_k - m[k]| <= h[k]. Exact extremes: the face-axis component
 * +-1/sqrt(1+u^2+v^2) is extreme where u^2 + v^2 is (the square's point
 * nearest the origin, or a corner); the component u/sqrt(1+u^2+v^2) grows
 * with u and shrinks with |v|, so its extremes lie at u in {u0, u1} with v
 * in {v0, v1, clamp(0)}; likewise for v. The nine points (corners, the
 * clamped zeros on each edge, the clamped centre) hold all of them.
 * vbs_face_dir computes each component with at most 6 roundings, so within
 * 6u relative: the box is widened by 8u |x| + VBQ_TINY on each side, and m,
 * h are rounded outward. */
VBS_FN void vbq_patch_box(vbs_u32 f, double u0, double u1, double v0, double v1, double m[3],
                          double h[3])
{
    double uc = u0 > 0.0 ? u0 : (u1 < 0.0 ? u1 : 0.0);
    double vc = v0 > 0.0 ? v0 : (v1 < 0.0 ? v1 : 0.0);
    double us[3] = {u0, u1, uc}, vs[3] = {v0, v1, vc};
    double lo[3] = {2.0, 2.0, 2.0}, hi[3] = {-2.0, -2.0, -2.0};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double d[3];
            vbs_face_dir(f, us[a], vs[b], d);
            for (int k = 0; k < 3; k++) {
                lo[k] = d[k] < lo[k] ? d[k] : lo[k];
                hi[k] = d[k] > hi[k] ? d[k] : hi[k];
            }
        }
    for (int k = 0; k < 3; k++) {
        double l = lo[k] - (8.0 * 1.1102230246251565e-16 * VBS_FABS(lo[k]) + VBQ_TINY);
        double g = hi[k] + (8.0 * 1.1102230246251565e-16 * VBS_FABS(hi[k]) + VBQ_TINY);
        m[k] = 0.5 * l + 0.5 * g;
        double e1 = vbq_up(g - m[k]), e2 = vbq_up(m[k] - l);
        h[k] = e1 > e2 ? e1 : e2;
    }
}

/* Encloses f(u) = a . u + b over every unit u with |u_k - m_k| <= h_k:
 * f(u) = F + a.(u - m) + (exact - computed). With F the computed a~.m + b~,
 * |F - (a~.m + b~)| <= 4.01u G (G = |a~|.|m| + |b~|, a sum of four
 * products), |a~.(u - m)| <= |a~|.h, and the exact a, b differ from a~, b~
 * by err in total (|u|_inf <= 1). The sum R of these is computed with at
 * most 8 roundings of non-negative terms (relative 8.01u), and lo = F - R,
 * hi = F + R round once more (u (|F| + R)): R gets VBQ_C (G + |F|) and a
 * factor (1 + VBQ_C), which covers all of it. */
VBS_FN void vbq_eval(const vbq_nb *nb, const double m[3], const double h[3], double *lo,
                     double *hi)
{
    double F = ((nb->ax * m[0] + nb->ay * m[1]) + nb->az * m[2]) + nb->b;
    double aax = VBS_FABS(nb->ax), aay = VBS_FABS(nb->ay), aaz = VBS_FABS(nb->az);
    double G = ((aax * VBS_FABS(m[0]) + aay * VBS_FABS(m[1])) + aaz * VBS_FABS(m[2])) +
               VBS_FABS(nb->b);
    double R = (((aax * h[0] + aay * h[1]) + aaz * h[2]) + nb->err) +
               VBQ_C * (G + VBS_FABS(F));
    R = R * (1.0 + VBQ_C) + VBQ_TINY;
    *lo = F - R;
    *hi = F + R;
}

/* The square of a patch: level l, integer position (iu, iv) of 2^l T
 * squares per face side. Dyadic, so u0..v1 are exact doubles. */
VBS_FN void vbq_patch_square(vbs_u32 T, vbs_u32 level, vbs_u32 iu, vbs_u32 iv, double *u0,
                             double *u1, double *v0, double *v1)
{
    double side = 2.0 / ((double)T * (double)(1u << level));
    *u0 = -1.0 + side * (double)iu;
    *u1 = -1.0 + side * (double)(iu + 1u);
    *v0 = -1.0 + side * (double)iv;
    *v1 = -1.0 + side * (double)(iv + 1u);
}

#endif
