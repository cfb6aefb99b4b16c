/* Univariate Taylor models in interval arithmetic: the quadrature of the
 * boundary integrals of the cell measures (stokes_cell.c).
 *
 * A vbm_s1 holds the Taylor coefficients c_n = f^(n) / n!, n <= VBM1_K, of a
 * function f(x), each as an interval (vbx_ia.h: every operation rounded
 * outward). As in vbm_series.h the recurrences below compute them as
 * functions of the expansion point, so the same calls give enclosures of
 * the coefficients at a point or, with the variable's constant term an
 * interval, at every point of that interval. Taylor's theorem with
 * Lagrange's remainder gives f(xc + x) = sum_{n<K} c_n(xc) x^n + c_K(xi) x^K
 * with xi between xc and xc + x; vbm1_integrate_m integrates both parts. */
#ifndef VBM_SERIES1_H
#define VBM_SERIES1_H

#include "vbx_ia.h"

/* K: the order of the remainder term (even: x^K >= 0). */
#define VBM1_K 10

typedef struct vbm_s1 {
    vbx_ia c[VBM1_K + 1];
} vbm_s1;

/* f = v (a constant). */
void vbm1_const(vbm_s1 *f, vbx_ia v);

/* f = the variable expanded at `at` (a point, or an interval: the box). */
void vbm1_var(vbm_s1 *f, vbx_ia at);

/* r = v f + w (r may alias f); r = f + g, r = f - g (r may alias f or g). */
void vbm1_affine(vbm_s1 *r, vbx_ia v, const vbm_s1 *f, vbx_ia w);
void vbm1_add(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g);
void vbm1_sub(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g);

/* r = f g (r must not alias f or g). */
void vbm1_mul(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g);

/* The n-th coefficient of f g alone (0 <= n <= VBM1_K), the same
 * enclosure vbm1_mul gives it. */
vbx_ia vbm1_mul_coef(const vbm_s1 *f, const vbm_s1 *g, int n);

/* r = 1 / f (r must not alias f). Returns 0 when f's constant term may be
 * 0 (r unspecified then). */
int vbm1_recip(vbm_s1 *r, const vbm_s1 *f);

/* r = sqrt(f) (r must not alias f). Returns 0 unless f's constant term is
 * proven > 0. */
int vbm1_sqrt(vbm_s1 *r, const vbm_s1 *f);

/* r = log(f) (r must not alias f), the constant term's log rounded outward
 * by MPFR (vbm_ia_log). Returns 0 unless f's constant term is proven > 0. */
int vbm1_log(vbm_s1 *r, const vbm_s1 *f);

/* vbm1_mul, vbm1_recip, vbm1_sqrt and vbm1_log to the order kmax
 * (0 <= kmax <= VBM1_K): coefficients 0..kmax the same enclosures, bit
 * for bit (each depends on the lower ones only), the others set to 0.
 * A value (kmax 0) or a series whose top order is not read costs what
 * it uses, not VBM1_K orders of zeros (the contact's ends and own arcs,
 * its series at pieces' middles: arc_fun.c). */
void vbm1_mul_to(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g, int kmax);
int vbm1_recip_to(vbm_s1 *r, const vbm_s1 *f, int kmax);
int vbm1_sqrt_to(vbm_s1 *r, const vbm_s1 *f, int kmax);
int vbm1_log_to(vbm_s1 *r, const vbm_s1 *f, int kmax);

/* An enclosure of the integral of f over [x0, x1] in two steps, for
 * several functions over one interval: m[0..VBM1_K] the enclosures of the
 * integrals of (x - xc)^n over [x0, x1] (vbm1_moments), then the integral
 * from them, `centre` holding f's coefficients at xc (x0 <= xc <= x1) and
 * `box` their enclosures over [x0, x1]. */
void vbm1_moments(double xc, double x0, double x1, vbx_ia *m);
vbx_ia vbm1_integrate_m(const vbm_s1 *centre, const vbm_s1 *box, const vbx_ia *m);

/* Polynomials in one variable with interval coefficients, p[k] the
 * coefficient of x^k, degree at most VBM1_POLY (series_rat.c). */
#define VBM1_POLY 8

/* r = f g, of degrees df and dg (df + dg <= VBM1_POLY; r must not alias
 * f or g): every coefficient an enclosure of the exact product's. */
void vbm1_poly_mul(vbx_ia *r, const vbx_ia *f, int df, const vbx_ia *g, int dg);

/* q(x) = p(xc + x) (degree d <= VBM1_POLY; q must not alias p): every
 * coefficient an enclosure of the exact moved polynomial's, by the same
 * steps vbm1_rational moves its num and den with (Horner's scheme). */
void vbm1_poly_at(vbx_ia *q, const vbx_ia *p, int d, double xc);

/* The Taylor coefficients c_0 .. c_kmax (kmax <= VBM1_K; the others
 * set to 0) at `at` (a point, or an interval: the box) of the rational
 * function num(x) / den(x), degrees dn and dd <= VBM1_POLY:
 * both polynomials moved to `at` by Horner's scheme in intervals, then
 * r_n = (num_n - sum_{k=1..dd} den_k r_(n-k)) / den_0, a constant number
 * of interval operations per coefficient where vbm1_recip and vbm1_mul
 * take n. Returns 0 when den(at) may be 0 (r unspecified then). */
int vbm1_rational(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, vbx_ia at,
                  int kmax);

/* num and den moved to a point xc (vbm1_rational's first step), kept for
 * vbm1_rational_rest. */
typedef struct vbm1_rat {
    vbx_ia a[VBM1_POLY + 1], b[VBM1_POLY + 1];
    int dn, dd;
} vbm1_rat;

/* vbm1_rational at the point `at` with kmax = VBM1_K, keeping the moved
 * polynomials in *keep. */
int vbm1_rational_keep(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd,
                       vbx_ia at, vbm1_rat *keep);

/* vbm1_rational_keep to the order kmax (1 <= kmax <= VBM1_K; the others 0):
 * coefficients 0..kmax its enclosures bit for bit (each depends on the
 * lower ones), for a model at the order k, whose rest reads r_(k-dd) ..
 * r_(k-1) (vbm1_rational_rest_to; kmax = k - 1). */
int vbm1_rational_keep_to(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd,
                          vbx_ia at, int kmax, vbm1_rat *keep);

/* The remainder of the Taylor polynomial of f = num / den at the point xc
 * (r from vbm1_rational_keep, which left *keep): with A, B the polynomials
 * moved to xc, f(xc + x) = sum_{n<K} r_n x^n + x^K M(x) / B(x) exactly,
 * M(x) = sum_{j<dd} m_j x^j, m_j = -sum_{k=j+1..dd} b_k r_(K+j-k) (the
 * coefficients of x^n, n < K, in A - B sum r_n x^n vanish by the
 * recurrence, and deg A < K). *g: an enclosure of M(x) / B(x) over x in
 * `x` (the piece less xc), so that the remainder's integral over the piece
 * lies in *g times that of x^K (x^K >= 0): in place of the K-th
 * coefficient over the piece, whose recurrence in intervals widens with
 * every order. Returns 0 when B may vanish over `x`. */
int vbm1_rational_rest(const vbm1_rat *keep, const vbm_s1 *r, vbx_ia x, vbx_ia *g);

/* vbm1_rational_rest at the order k (deg num < k, dd <= k <= VBM1_K):
 * f(xc + x) = sum_{n<k} r_n x^n + x^k M(x) / B(x), m_j = -sum_{i=j+1..dd}
 * b_i r_(k+j-i), by the same argument; *g encloses M / B over `x`. Returns
 * 0 when B may vanish there, dd > k or dn >= k. */
int vbm1_rational_rest_to(const vbm1_rat *keep, const vbm_s1 *r, int k, vbx_ia x, vbx_ia *g);

/* An enclosure of c[0] + c[1] t + c[2] t^2 over t in T (c intervals): the
 * values at T's ends and at the vertex where it may lie in T, each
 * coefficient once (Horner's scheme over T, which counts t twice, where c[2]
 * may be 0). The proof above the code (series_rat.c). */
vbx_ia vbm1_poly2_range(const vbx_ia *c, vbx_ia T);

/* The meet of two enclosures of one quantity (lo > hi where they miss:
 * then one of them is wrong). */
vbx_ia vbm1_meet(vbx_ia a, vbx_ia b);

/* A Taylor model of f at the order k (1 <= k <= VBM1_K) about a point xc,
 * over a piece xc + x, x in an interval holding 0 (series_tm.c):
 * f(xc + x) = sum_{n<k} p.c[n] x^n + x^k r(x), p.c[n] enclosing f's Taylor
 * coefficients at xc (p.c[k..VBM1_K] = 0) and rest enclosing r(x) over the
 * piece: a remainder from closed forms, not from f's series over the
 * piece, whose recurrences in intervals widen with every order. */
typedef struct vbm1_tm {
    vbm_s1 p;
    vbx_ia rest;
} vbm1_tm;

/* An enclosure of f over the piece (x): the polynomial by Horner's scheme
 * plus x^k times the rest. */
vbx_ia vbm1_tm_value(const vbm1_tm *f, int k, vbx_ia x);

/* r = f g at the order k (r must not alias f or g). */
void vbm1_tm_mul(vbm1_tm *r, const vbm1_tm *f, const vbm1_tm *g, int k, vbx_ia x);

/* r = num / den (degrees dn < k, dd <= k) at the order k about the point
 * xc. Returns 0 when den may vanish at xc or over the piece. */
int vbm1_tm_rational(vbm1_tm *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, double xc,
                     int k, vbx_ia x);

/* r = f / g at the order k (r must not alias f or g), gx an enclosure of
 * g over the piece (the caller's, as tight as it has: the rest is divided
 * by it). Returns 0 unless g's constant term and gx exclude 0. */
int vbm1_tm_div(vbm1_tm *r, const vbm1_tm *f, const vbm1_tm *g, vbx_ia gx, int k, vbx_ia x);

/* r = v f + w at the order kr (1 <= kr <= k) from f at the order k (r must
 * not alias f): the terms of orders kr .. k - 1 join the rest,
 * r's rest = v (sum_{kr<=n<k} f_n x^(n-kr) + x^(k-kr) f's rest) over x. */
void vbm1_tm_affine(vbm1_tm *r, vbx_ia v, const vbm1_tm *f, vbx_ia w, int k, int kr, vbx_ia x);

/* r = f num / den at the order k (r must not alias f), num and den
 * polynomials already moved to the model's point (vbm1_poly_at) of degrees
 * dn, dd < k, dd <= VBM1_POLY, no rest of their own; dx an enclosure of den
 * over the piece (the caller's, as tight as it has: the rest is divided by
 * it). Returns 0 unless den's constant term and dx exclude 0. */
int vbm1_tm_mul_div_poly(vbm1_tm *r, const vbm1_tm *f, const vbx_ia *num, int dn,
                         const vbx_ia *den, int dd, vbx_ia dx, int k, vbx_ia x);

/* r = sqrt(s) at the order k (r must not alias s). Returns 0 unless s and
 * sqrt(s) + its Taylor polynomial are proven > 0 over the piece. */
int vbm1_tm_sqrt(vbm1_tm *r, const vbm1_tm *s, int k, vbx_ia x);

#endif
