/* The integrands of the cell measures as Taylor models (vbm_piece.h). */
#include <math.h>
#include <mpfr.h>

#include "vbm_piece.h"

/* f of the ends of x for an increasing f, rounded outward by MPFR. */
static vbx_ia increasing(vbx_ia x, int (*f)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t))
{
    mpfr_t t;
    mpfr_init2(t, 53);
    vbx_ia r;
    mpfr_set_d(t, x.lo, MPFR_RNDN); /* exact: 53 bits */
    f(t, t, MPFR_RNDD);
    r.lo = mpfr_get_d(t, MPFR_RNDD);
    mpfr_set_d(t, x.hi, MPFR_RNDN);
    f(t, t, MPFR_RNDU);
    r.hi = mpfr_get_d(t, MPFR_RNDU);
    mpfr_clear(t);
    return r;
}

void vbm_ia_release(void)
{
    mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE);
}

#define ATAN_TERMS 12 /* terms of the series after two halvings (atan_of) */

/* An enclosure of atan x for a finite double x, in double intervals.
 * atan is odd: a = |x|, and for a > 1 atan a = pi/2 - atan(1/a) (1/a and
 * pi/2 each within half an ulp of their nearest double: one step outward).
 * Then y in [0, 1] halved twice, atan y = 2 atan(y / (1 + sqrt(1 + y^2)))
 * (the half angle's tangent, increasing in y, so the interval steps
 * enclose it), leaves y <= tan(pi/16) < 0.2, and atan y = y sum_{k<K}
 * (-1)^k y^(2k) / (2k + 1) + R: an alternating series whose terms fall
 * (y < 1), so |R| <= y^(2K+1) / (2K + 1) <= y 0.2^24 / 25 < 2^-60 y for
 * K = ATAN_TERMS, added as [-B, B]. About 50 interval operations where
 * MPFR's atan took ~23,000 instructions a call (c1k: the own arcs' angles
 * were 12 % of the integrals). */
static vbx_ia atan_of(double x)
{
    double a = fabs(x);
    if (a == 0.0)
        return vbx_ia_point(x);
    if (a < 0x1p-30) /* a - a^3 / 3 < atan a < a, a^3 / 3 below half an ulp of a */
        return x > 0.0 ? (vbx_ia){vbx_pred(x), x} : (vbx_ia){x, vbx_succ(x)};
    int flip = a > 1.0;
    vbx_ia y = vbx_ia_point(a), one = vbx_ia_point(1.0);
    if (flip) {
        double q = 1.0 / a;
        y = (vbx_ia){vbx_pred(q), vbx_succ(q)};
        y.lo = vbx_max(y.lo, 0.0);
    }
    for (int h = 0; h < 2; h++)
        y = vbx_ia_div(y, vbx_ia_add(one, vbx_ia_sqrt(vbx_ia_add(one, vbx_ia_sqr(y)))));
    vbx_ia s = vbx_ia_sqr(y), p = vbx_ia_point(0.0);
    for (int k = ATAN_TERMS - 1; k >= 0; k--) {
        double c = 1.0 / (double)(2 * k + 1);
        vbx_ia ck = k == 0 ? one : (vbx_ia){vbx_pred(c), vbx_succ(c)};
        if (k & 1)
            ck = vbx_ia_neg(ck);
        p = vbx_ia_add(vbx_ia_mul(p, s), ck);
    }
    double b = y.hi;
    for (int k = 0; k < 2 * ATAN_TERMS; k++)
        b = vbx_succ(b * y.hi);
    b = vbx_succ(b / (2.0 * ATAN_TERMS + 1.0));
    vbx_ia r = vbx_ia_add(vbx_ia_mul(y, p), (vbx_ia){-b, b});
    r.lo *= 4.0; /* exact: two doublings */
    r.hi *= 4.0;
    if (flip) {
        const double hpi = 1.5707963267948966; /* the double nearest pi / 2 */
        r = vbx_ia_sub((vbx_ia){vbx_pred(hpi), vbx_succ(hpi)}, r);
    }
    return x < 0.0 ? vbx_ia_neg(r) : r;
}

vbx_ia vbm_ia_atan(vbx_ia x)
{
    if (!(x.lo > -INFINITY && x.hi < INFINITY))
        return increasing(x, mpfr_atan);
    /* as vbm_ia_log: one atan at the middle m where x is narrow (the arcs'
     * angles, the patches' corners: a few ulps; below 2^-30 relative the
     * theorem's loss, second order, is below an ulp), and the mean value
     * theorem with
     * atan' = 1 / (1 + t^2) <= 1 / (1 + mn^2), mn the least |t| over x:
     * atan lo >= atan m - (m - lo) / (1 + mn^2), atan hi <= atan m +
     * (hi - m) / (1 + mn^2), each bound rounded outward */
    double m = 0.5 * x.lo + 0.5 * x.hi;
    if (x.hi - x.lo <= 0x1p-30 * vbx_max(fabs(m), 1.0) && m >= x.lo && m <= x.hi) {
        vbx_ia l = atan_of(m);
        double mn = x.lo > 0.0 ? x.lo : x.hi < 0.0 ? -x.hi : 0.0;
        double d = vbx_succ(1.0 / vbx_pred(1.0 + vbx_pred(mn * mn)));
        double d1 = vbx_succ(vbx_succ(m - x.lo) * d), d2 = vbx_succ(vbx_succ(x.hi - m) * d);
        vbx_ia r = {vbx_pred(l.lo - d1), vbx_succ(l.hi + d2)};
        return r;
    }
    vbx_ia r = {atan_of(x.lo).lo, atan_of(x.hi).hi};
    return r;
}

#define LOG_TERMS 10 /* terms of atanh: remainder below 1e-17 (log_of) */

/* An enclosure of log x for a finite double x > 0 in double intervals.
 * x = m 2^e exactly with m in [sqrt(1/2), sqrt(2)) (frexp, then one exact
 * doubling), s = (m - 1) / (m + 1) (m - 1 exact by Sterbenz), |s| <= 0.1716,
 * and log m = 2 atanh s = 2 sum_k s^(2k+1) / (2k+1): after LOG_TERMS terms
 * the rest has s's sign and magnitude at most
 * 2 |s|^(2K+1) / ((2K+1) (1 - s^2)) <= 8.2e-18 (K = LOG_TERMS), added as
 * [-B, B]. ln 2 is within half an ulp of its nearest double, 1/(2k+1)
 * within half an ulp of the quotient rounded to nearest: each one step
 * outward. About 30 interval operations where MPFR's log takes an AGM. */
static vbx_ia log_of(double x)
{
    int e;
    double m = frexp(x, &e);
    if (m < 0.70710678118654752) {
        m *= 2.0;
        e--;
    }
    vbx_ia s = vbx_ia_div(vbx_ia_point(m - 1.0), vbx_ia_add(vbx_ia_point(m), vbx_ia_point(1.0)));
    vbx_ia s2 = vbx_ia_sqr(s), p = vbx_ia_point(0.0);
    for (int k = LOG_TERMS - 1; k >= 0; k--) {
        double c = 1.0 / (double)(2 * k + 1);
        vbx_ia ck = {vbx_pred(c), vbx_succ(c)};
        if (k == 0)
            ck = vbx_ia_point(1.0);
        p = vbx_ia_add(vbx_ia_mul(p, s2), ck);
    }
    double sm = vbx_max(fabs(s.lo), fabs(s.hi)), b = 2.0 * sm;
    for (int k = 0; k < 2 * LOG_TERMS; k++)
        b = vbx_succ(b * sm);
    b = vbx_succ(b / vbx_pred((2.0 * LOG_TERMS + 1.0) * vbx_pred(1.0 - vbx_succ(s2.hi))));
    vbx_ia lm = vbx_ia_add(vbx_ia_mul(vbx_ia_add(s, s), p), (vbx_ia){-b, b});
    const double ln2 = 0.6931471805599453; /* the double nearest ln 2 */
    vbx_ia l2 = {vbx_pred(ln2), vbx_succ(ln2)};
    return vbx_ia_add(vbx_ia_mul(vbx_ia_point((double)e), l2), lm);
}

vbx_ia vbm_ia_log(vbx_ia x)
{
    if (!(x.lo > 0.0 && x.hi < INFINITY))
        return increasing(x, mpfr_log);
    /* a narrow x (the series' constant terms at a point): one log, at the
     * middle m, and the mean value theorem, log lo >= log m - (m - lo) / lo
     * and log hi <= log m + (hi - m) / m (1 / t decreasing), each bound
     * rounded outward; wider than the two logs by about ((hi - lo) / lo)^2,
     * at half the cost (1crn --contacts, 1 thread: log_of was 9 %) */
    double m = 0.5 * x.lo + 0.5 * x.hi;
    if (x.hi - x.lo <= 1e-3 * x.lo && m >= x.lo && m <= x.hi) {
        vbx_ia l = log_of(m);
        double d1 = vbx_succ(vbx_succ(m - x.lo) / x.lo), d2 = vbx_succ(vbx_succ(x.hi - m) / m);
        vbx_ia r = {vbx_pred(l.lo - d1), vbx_succ(l.hi + d2)};
        return r;
    }
    vbx_ia r = {log_of(x.lo).lo, log_of(x.hi).hi};
    return r;
}

/* The solid angle of [0, a] x [0, b] seen from the centre of the cube face
 * at distance 1: atan(a b / sqrt(1 + a^2 + b^2)). */
static vbx_ia corner(double a, double b)
{
    vbx_ia A = vbx_ia_point(a), B = vbx_ia_point(b);
    vbx_ia s = vbx_ia_sqrt(vbx_ia_add(vbx_ia_point(1.0), vbx_ia_add(vbx_ia_sqr(A), vbx_ia_sqr(B))));
    return vbm_ia_atan(vbx_ia_div(vbx_ia_mul(A, B), s));
}

vbx_ia vbm_solid_angle(double a0, double a1, double b0, double b1)
{
    vbx_ia o = vbx_ia_sub(vbx_ia_add(corner(a1, b1), corner(a0, b0)),
                          vbx_ia_add(corner(a0, b1), corner(a1, b0)));
    o.lo = vbx_max(o.lo, 0.0);
    return o;
}

int vbm_piece(const vbm_atom_in *in, int owner, const vbm_axes *ax, const vbm_ser *a,
              const vbm_ser *b, vbm_ser *vol, vbm_ser *sas, vbm_ser *con)
{
    vbm_ser q, t, s, inv;
    vbm_square(&q, a);
    vbm_square(&t, b);
    vbm_add(&q, &q, &t);
    q.c[0] = vbx_ia_add(q.c[0], vbx_ia_point(1.0));
    if (!vbm_sqrt(&s, &q))
        return 0;
    if (owner < 0) { /* r^3 / (3 s^3) and r^2 / s^3 */
        vbx_ia r2 = vbx_ia_sqr(in->r);
        vbm_mul(&t, &q, &s);
        if (!vbm_recip(&inv, &t))
            return 0;
        vbm_affine(sas, r2, &inv, vbx_ia_point(0.0));
        vbm_affine(vol, vbx_ia_div(vbx_ia_mul(r2, in->r), vbx_ia_point(3.0)), &inv,
                   vbx_ia_point(0.0));
        vbm_const(con, vbx_ia_point(0.0));
        return 1;
    }
    /* E = sigma d_w + a d_p + b d_q + delta s; N^3 / (24 E^3) and
     * N^2 sqrt(N + 2 delta E / s) / (4 E^3) */
    const vbm_nb *n = &in->nb[owner];
    vbm_ser E, e1, e2, e3, D, g;
    vbm_affine(&E, n->d[ax->p], a, vbx_ia_mul(vbx_ia_point(ax->sigma), n->d[ax->w]));
    vbm_affine(&t, n->d[ax->q], b, vbx_ia_point(0.0));
    vbm_add(&E, &E, &t);
    if (!vbm_ia_is_zero(n->delta)) { /* equal radii: E linear in a and b */
        vbm_affine(&t, n->delta, &s, vbx_ia_point(0.0));
        vbm_add(&E, &E, &t);
    }
    if (!vbm_recip(&e1, &E))
        return 0;
    vbm_square(&e2, &e1);
    vbm_mul(&e3, &e2, &e1);
    vbm_affine(vol, vbx_ia_div(vbx_ia_mul(vbx_ia_sqr(n->N), n->N), vbx_ia_point(24.0)), &e3,
               vbx_ia_point(0.0));
    vbm_const(sas, vbx_ia_point(0.0));
    if (!in->contacts) {
        vbm_const(con, vbx_ia_point(0.0));
        return 1;
    }
    if (!vbm_recip(&t, &s))
        return 0;
    vbm_mul(&D, &E, &t);
    vbm_affine(&t, vbx_ia_add(n->delta, n->delta), &D, n->N);
    if (!vbm_sqrt(&g, &t))
        return 0;
    vbm_mul(&t, &g, &e3);
    vbm_affine(con, vbx_ia_div(vbx_ia_sqr(n->N), vbx_ia_point(4.0)), &t, vbx_ia_point(0.0));
    return 1;
}

int vbm_box_integrate(const vbm_atom_in *in, int owner, const vbm_axes *ax, double a0, double a1,
                      double b0, double b1, vbx_ia *vol, vbx_ia *sas, vbx_ia *con)
{
    double ac = 0.5 * (a0 + a1), bc = 0.5 * (b0 + b1);
    double ha = 0.5 * (a1 - a0), hb = 0.5 * (b1 - b0);
    vbm_ser v[2][3];
    for (int k = 0; k < 2; k++) {
        vbx_ia A = k ? (vbx_ia){a0, a1} : vbx_ia_point(ac);
        vbx_ia B = k ? (vbx_ia){b0, b1} : vbx_ia_point(bc);
        vbm_ser a, b;
        vbm_var(&a, A, 0);
        vbm_var(&b, B, 1);
        if (!vbm_piece(in, owner, ax, &a, &b, &v[k][0], &v[k][1], &v[k][2]))
            return 0;
    }
    *vol = vbm_integrate(&v[0][0], &v[1][0], ha, hb);
    *sas = vbm_integrate(&v[0][1], &v[1][1], ha, hb);
    *con = owner >= 0 && in->contacts ? vbm_integrate(&v[0][2], &v[1][2], ha, hb)
                                      : vbx_ia_point(0.0);
    return 1;
}
