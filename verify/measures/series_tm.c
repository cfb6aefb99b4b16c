/* Univariate Taylor models with a remainder over an interval
 * (vbm_series1.h's vbm1_tm): products, roots and rational functions.
 *
 * A model of f at the order k about the point xc is f(xc + x) =
 * sum_{n<k} p_n x^n + x^k r(x): p_n enclose f's Taylor coefficients at xc
 * and `rest` encloses r(x) for x in the piece less xc (an interval holding
 * 0). Every bound below is an interval evaluation over the piece of the
 * true functions' formulas, inclusion-isotone, so each rest encloses the
 * true remainder:
 * - a rational function num / den: vbm1_rational_rest_to, r = M / B
 *   exactly (vbm_series1.h);
 * - v f + w at an order kr <= k: f = P_f,<kr + x^kr (sum_{kr<=n<k} p_n
 *   x^(n-kr) + x^(k-kr) r_f), the bracket by Horner's scheme over the piece;
 * - a product f g: f g = P_f P_g + x^k (r_f g + r_g P_f), and P_f P_g =
 *   [P_f P_g]_{<k} + x^k Q (the orders k .. 2k - 2 over x^k), so r = Q +
 *   r_f g + r_g P_f, g over the piece its own model's value;
 * - sqrt(s), s = P_s + x^k r_s: with T the Taylor polynomial of sqrt(s),
 *   [T^2]_{<k} = P_s (the low orders of a product read the low orders
 *   alone), so s - T^2 = x^k (r_s - Q_T), Q_T = (T^2 - [T^2]_{<k}) / x^k,
 *   and s - T^2 = (sqrt(s) - T)(sqrt(s) + T): where sqrt(s) + T > 0 over
 *   the piece, r = (r_s - Q_T) / (sqrt(s) + T);
 * - a quotient h = f / g: P_h by the recurrence g_0 p_n = f_n - sum_{i=1..n}
 *   g_i p_(n-i), so that [P_g P_h]_{<k} = P_f and P_g P_h = P_f + x^k Q
 *   (Q = high(P_g, P_h)); then g (h - P_h) = f - g P_h = x^k (r_f - Q - r_g
 *   P_h), and where g has no zero over the piece r = (r_f - Q - r_g
 *   P_h(x)) / g(x). No pole of 1 / g off the real line enters the rest:
 *   where f and g vanish together (the contact's F and 1 - z at z = 1)
 *   h's model is as good as h is smooth;
 * - f num / den, num and den polynomials (degrees dn, dd < k) with no rest:
 *   u = f num = [P_f num]_{<k} + x^k (Q_u + r_f num(x)), Q_u the orders
 *   k .. k + dn - 1 of P_f num over x^k; P_h by the recurrence den_0 p_n =
 *   u_n - sum_{i=1..min(n,dd)} den_i p_(n-i), so den P_h = P_u + x^k Q_h
 *   (Q_h the orders k .. k + dd - 1 of den P_h over x^k), and
 *   den (h - P_h) = u - den P_h = x^k (r_u - Q_h): where den has no zero
 *   over the piece, r = (r_u - Q_h) / den(x). The quotient rule's argument
 *   with r_g = 0: a polynomial divisor is its own model, so no r_g P_h term
 *   and a recurrence of dd terms, not n. */
#include "vbm_dot.h"
#include "vbm_series1.h"

/* sum_{i<n} c_i x^i by Horner's scheme. */
static vbx_ia horner(const vbx_ia *c, int n, vbx_ia x)
{
    vbx_ia v = c[n - 1];
    for (int i = n - 2; i >= 0; i--)
        v = vbx_ia_add(vbx_ia_mul(v, x), c[i]);
    return v;
}

/* An enclosure of x^k over x: [0, m^k] (k even) or [-m^k, m^k], m = |x|'s
 * largest value, m^k rounded up. */
static vbx_ia pow_k(vbx_ia x, int k)
{
    vbx_ia m = vbx_ia_point(vbx_max(-x.lo, x.hi)), p = vbx_ia_point(1.0);
    for (int i = 0; i < k; i++)
        p = vbx_ia_mul(p, m);
    vbx_ia r = {k % 2 ? -p.hi : 0.0, p.hi};
    return r;
}

vbx_ia vbm1_tm_value(const vbm1_tm *f, int k, vbx_ia x)
{
    return vbx_ia_add(horner(f->p.c, k, x), vbx_ia_mul(pow_k(x, k), f->rest));
}

/* (P_f P_g - [P_f P_g]_{<k}) / x^k over x: the orders k .. 2k - 2 of the
 * product of two polynomials of degree k - 1 (i + j = n, i, j < k). */
static vbx_ia high(const vbm_s1 *f, const vbm_s1 *g, int k, vbx_ia x)
{
    vbx_ia h[VBM1_K];
    if (k < 2)
        return vbx_ia_point(0.0);
    for (int n = k; n <= 2 * k - 2; n++)
        h[n - k] = vbm_dotn(&f->c[n - k + 1], 1, &g->c[k - 1], -1, 2 * k - 1 - n);
    return horner(h, k - 1, x);
}

void vbm1_tm_mul(vbm1_tm *r, const vbm1_tm *f, const vbm1_tm *g, int k, vbx_ia x)
{
    vbx_ia q = high(&f->p, &g->p, k, x);
    vbx_ia rg = vbx_ia_mul(f->rest, vbm1_tm_value(g, k, x));
    vbx_ia gp = vbx_ia_mul(g->rest, horner(f->p.c, k, x));
    r->rest = vbx_ia_add(q, vbx_ia_add(rg, gp));
    vbm1_mul_to(&r->p, &f->p, &g->p, k - 1);
}

int vbm1_tm_rational(vbm1_tm *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, double xc,
                     int k, vbx_ia x)
{
    vbm1_rat keep;
    int km = k > 1 ? k - 1 : 1; /* the rest reads r_(k-1) at the most; kmax 0 moves nothing */
    if (!vbm1_rational_keep_to(&r->p, num, dn, den, dd, vbx_ia_point(xc), km, &keep) ||
        !vbm1_rational_rest_to(&keep, &r->p, k, x, &r->rest))
        return 0;
    for (int n = k; n <= VBM1_K; n++)
        r->p.c[n] = vbx_ia_point(0.0);
    return 1;
}

/* the identity at the top of the file */
void vbm1_tm_affine(vbm1_tm *r, vbx_ia v, const vbm1_tm *f, vbx_ia w, int k, int kr, vbx_ia x)
{
    vbx_ia hi[VBM1_K + 1];
    for (int n = kr; n < k; n++)
        hi[n - kr] = f->p.c[n];
    hi[k - kr] = f->rest;
    vbm1_affine(&r->p, v, &f->p, w);
    for (int n = kr; n <= VBM1_K; n++)
        r->p.c[n] = vbx_ia_point(0.0);
    r->rest = vbx_ia_mul(v, horner(hi, k - kr + 1, x));
}

/* the identity at the top of the file */
int vbm1_tm_div(vbm1_tm *r, const vbm1_tm *f, const vbm1_tm *g, vbx_ia gx, int k, vbx_ia x)
{
    vbx_ia g0 = g->p.c[0];
    if (!(g0.lo > 0.0 || g0.hi < 0.0) || !(gx.lo > 0.0 || gx.hi < 0.0))
        return 0;
    r->p.c[0] = vbx_ia_div(f->p.c[0], g0);
    for (int n = 1; n < k; n++) /* p_n = (f_n - sum_{i=1..n} g_i p_(n-i)) / g_0 */
        r->p.c[n] = vbx_ia_div(
            vbx_ia_sub(f->p.c[n], vbm_dotn(&g->p.c[1], 1, &r->p.c[n - 1], -1, n)), g0);
    for (int n = k; n <= VBM1_K; n++)
        r->p.c[n] = vbx_ia_point(0.0);
    vbx_ia num = vbx_ia_sub(f->rest, vbx_ia_add(high(&g->p, &r->p, k, x),
                                               vbx_ia_mul(g->rest, horner(r->p.c, k, x))));
    r->rest = vbx_ia_div(num, gx);
    return 1;
}

/* the identity at the top of the file */
int vbm1_tm_sqrt(vbm1_tm *r, const vbm1_tm *s, int k, vbx_ia x)
{
    vbx_ia sv = vbm1_tm_value(s, k, x);
    if (!(sv.lo > 0.0) || !vbm1_sqrt_to(&r->p, &s->p, k - 1))
        return 0;
    vbx_ia den = vbx_ia_add(vbx_ia_sqrt(sv), horner(r->p.c, k, x));
    if (!(den.lo > 0.0))
        return 0;
    r->rest = vbx_ia_div(vbx_ia_sub(s->rest, high(&r->p, &r->p, k, x)), den);
    return 1;
}

/* sum_{m<d} x^m sum_{i=m+1..d} a_i p_(k+m-i): the orders k .. k + d - 1 of
 * the polynomial a (degree d) times P (degree k - 1) over x^k, over x. */
static vbx_ia high_poly(const vbx_ia *a, int d, const vbx_ia *p, int k, vbx_ia x)
{
    vbx_ia h[VBM1_POLY];
    if (d < 1)
        return vbx_ia_point(0.0);
    for (int m = 0; m < d; m++)
        h[m] = vbm_dotn(&a[m + 1], 1, &p[k - 1], -1, d - m);
    return horner(h, d, x);
}

/* the identity at the top of the file */
int vbm1_tm_mul_div_poly(vbm1_tm *r, const vbm1_tm *f, const vbx_ia *num, int dn,
                         const vbx_ia *den, int dd, vbx_ia dx, int k, vbx_ia x)
{
    vbx_ia d0 = den[0], u[VBM1_K];
    if (!(d0.lo > 0.0 || d0.hi < 0.0) || !(dx.lo > 0.0 || dx.hi < 0.0))
        return 0;
    for (int n = 0; n < k; n++) /* u_n = sum_{i<=min(n,dn)} num_i f_(n-i) */
        u[n] = vbm_dotn(num, 1, &f->p.c[n], -1, (n < dn ? n : dn) + 1);
    vbx_ia ru = vbx_ia_add(high_poly(num, dn, f->p.c, k, x),
                           vbx_ia_mul(f->rest, horner(num, dn + 1, x)));
    vbx_ia id0 = vbx_ia_div(vbx_ia_point(1.0), d0); /* s / d0 lies in s [1 / d0] */
    r->p.c[0] = vbx_ia_mul(u[0], id0);
    for (int n = 1; n < k; n++)
        r->p.c[n] = vbx_ia_mul(
            vbx_ia_sub(u[n], vbm_dotn(&den[1], 1, &r->p.c[n - 1], -1, n < dd ? n : dd)), id0);
    for (int n = k; n <= VBM1_K; n++)
        r->p.c[n] = vbx_ia_point(0.0);
    r->rest = vbx_ia_div(vbx_ia_sub(ru, high_poly(den, dd, r->p.c, k, x)), dx);
    return 1;
}
