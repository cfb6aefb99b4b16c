/* Rational functions of one variable as Taylor models (vbm_series1.h): the
 * integrands along a circle arc are quotients of low-degree polynomials in
 * t = tan(angle / 2) (stokes_cell.c), so their coefficients follow from a
 * linear recurrence instead of series products and reciprocals. */
#include "vbm_dot.h"
#include "vbm_series1.h"

/* vbm1_rational_rest: the numerator's degree below K, so that A has no
 * term of x^K or above */
_Static_assert(VBM1_POLY < VBM1_K, "vbm1_rational_rest needs deg num < VBM1_K");
_Static_assert(VBM1_POLY + 1 <= VBM_DOT_MAX, "the sums within vbm_dotn's proof");

void vbm1_poly_mul(vbx_ia *r, const vbx_ia *f, int df, const vbx_ia *g, int dg)
{
    for (int n = 0; n <= df + dg; n++) {
        int k0 = n > dg ? n - dg : 0, k1 = n < df ? n : df;
        r[n] = vbm_dotn(&f[k0], 1, &g[n - k0], -1, k1 - k0 + 1);
    }
}

/* q(x) = p(at + x): Horner's scheme on the series of at + x, each step
 * r <- r (at + x) + p_k (synthetic division), exact in interval terms. */
static void shift(vbx_ia *q, const vbx_ia *p, int d, vbx_ia at)
{
    for (int n = 0; n <= d; n++)
        q[n] = vbx_ia_point(0.0);
    q[0] = p[d];
    if (at.lo == at.hi) { /* a point: the same bounds, fewer operations */
        for (int k = d - 1; k >= 0; k--) {
            for (int n = d - k; n >= 1; n--)
                q[n] = vbx_ia_add(vbm_ia_mul_point(at.lo, q[n]), q[n - 1]);
            q[0] = vbx_ia_add(vbm_ia_mul_point(at.lo, q[0]), p[k]);
        }
        return;
    }
    for (int k = d - 1; k >= 0; k--) {
        for (int n = d - k; n >= 1; n--)
            q[n] = vbx_ia_add(vbx_ia_mul(at, q[n]), q[n - 1]);
        q[0] = vbx_ia_add(vbx_ia_mul(at, q[0]), p[k]);
    }
}

void vbm1_poly_at(vbx_ia *q, const vbx_ia *p, int d, double xc)
{
    shift(q, p, d, vbx_ia_point(xc));
}

/* p(at) alone: Horner's scheme. */
static vbx_ia value(const vbx_ia *p, int d, vbx_ia at);

/* The identity in vbm_series1.h's contract: for each real quadratic p with
 * coefficients in c[0..2] its range over T is the hull of p(T.lo), p(T.hi)
 * and, where c2 != 0 and its vertex v = -c1 / (2 c2) lies in T, p(v) = c0 -
 * c1^2 / (4 c2); p(T.lo) and p(T.hi) lie in the interval evaluations at
 * the points, v in V and p(v) in the interval value of c0 - c1^2 / (4 c2)
 * (each coefficient once), so where V misses T no p's vertex lies in T. */
vbx_ia vbm1_poly2_range(const vbx_ia *c, vbx_ia T)
{
    if (!(c[2].lo > 0.0 || c[2].hi < 0.0))
        return value(c, 2, T);
    vbx_ia pl = value(c, 2, vbx_ia_point(T.lo)), ph = value(c, 2, vbx_ia_point(T.hi));
    vbx_ia r = {vbx_min(pl.lo, ph.lo), vbx_max(pl.hi, ph.hi)}, c2 = vbx_ia_add(c[2], c[2]);
    vbx_ia v = vbx_ia_neg(vbx_ia_div(c[1], c2));
    if (v.hi >= T.lo && v.lo <= T.hi) {
        vbx_ia e = vbx_ia_sub(c[0], vbx_ia_div(vbx_ia_sqr(c[1]), vbx_ia_add(c2, c2)));
        r.lo = vbx_min(r.lo, e.lo);
        r.hi = vbx_max(r.hi, e.hi);
    }
    return r;
}

/* Two enclosures of one quantity: their common part (both hold it). */
vbx_ia vbm1_meet(vbx_ia a, vbx_ia b)
{
    vbx_ia r = {vbx_max(a.lo, b.lo), vbx_min(a.hi, b.hi)};
    return r;
}

static vbx_ia value(const vbx_ia *p, int d, vbx_ia at)
{
    vbx_ia v = p[d];
    for (int k = d - 1; k >= 0; k--)
        v = vbx_ia_add(vbx_ia_mul(at, v), p[k]);
    return v;
}

static int rational(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, vbx_ia at,
                    int kmax, vbx_ia *a, vbx_ia *b);

int vbm1_rational(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, vbx_ia at,
                  int kmax)
{
    vbx_ia a[VBM1_POLY + 1], b[VBM1_POLY + 1];
    return rational(r, num, dn, den, dd, at, kmax, a, b);
}

int vbm1_rational_keep(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd,
                       vbx_ia at, vbm1_rat *keep)
{
    return vbm1_rational_keep_to(r, num, dn, den, dd, at, VBM1_K, keep);
}

int vbm1_rational_keep_to(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd,
                          vbx_ia at, int kmax, vbm1_rat *keep)
{
    keep->dd = dd;
    keep->dn = dn;
    return rational(r, num, dn, den, dd, at, kmax, keep->a, keep->b);
}

int vbm1_rational_rest(const vbm1_rat *keep, const vbm_s1 *r, vbx_ia x, vbx_ia *g)
{
    return vbm1_rational_rest_to(keep, r, VBM1_K, x, g);
}

int vbm1_rational_rest_to(const vbm1_rat *keep, const vbm_s1 *r, int k, vbx_ia x, vbx_ia *g)
{
    int dd = keep->dd;
    const vbx_ia *b = keep->b;
    vbx_ia m[VBM1_POLY + 1];
    if (dd > k || keep->dn >= k) /* m_j reads r_(k-dd) .. r_(k-1); A has no x^k */
        return 0;
    for (int j = 0; j < dd; j++)
        m[j] = vbx_ia_neg(vbm_dotn(&b[j + 1], 1, &r->c[k - 1], -1, dd - j));
    vbx_ia M = vbx_ia_point(0.0), B = b[dd];
    for (int j = dd - 1; j >= 0; j--) {
        M = vbx_ia_add(vbx_ia_mul(x, M), m[j]);
        B = vbx_ia_add(vbx_ia_mul(x, B), b[j]);
    }
    if (!(B.lo > 0.0 || B.hi < 0.0))
        return 0;
    *g = vbx_ia_div(M, B);
    return 1;
}

static int rational(vbm_s1 *r, const vbx_ia *num, int dn, const vbx_ia *den, int dd, vbx_ia at,
                    int kmax, vbx_ia *a, vbx_ia *b)
{
    if (kmax == 0) {
        a[0] = value(num, dn, at);
        b[0] = value(den, dd, at);
    } else {
        shift(a, num, dn, at);
        shift(b, den, dd, at);
    }
    vbx_ia b0 = b[0];
    if (!(b0.lo > 0.0 || b0.hi < 0.0))
        return 0;
    /* times an enclosure of 1 / b0 (one division, not one per coefficient:
     * s / b0 lies in s [1 / b0]) */
    vbx_ia ib0 = vbx_ia_div(vbx_ia_point(1.0), b0);
    for (int n = 0; n <= kmax; n++) { /* the sum with one rounding bound per end (vbm_dotn) */
        vbx_ia s = n ? vbm_dotn(&b[1], 1, &r->c[n - 1], -1, n < dd ? n : dd) : vbx_ia_point(0.0);
        s = n <= dn ? vbx_ia_sub(a[n], s) : vbx_ia_neg(s);
        r->c[n] = vbx_ia_mul(s, ib0);
    }
    for (int n = kmax + 1; n <= VBM1_K; n++)
        r->c[n] = vbx_ia_point(0.0);
    return 1;
}
