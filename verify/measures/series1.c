/* Univariate Taylor models in interval arithmetic (vbm_series1.h). */
#include "vbm_dot.h"
#include "vbm_piece.h"
#include "vbm_series1.h"

void vbm1_const(vbm_s1 *f, vbx_ia v)
{
    for (int k = 0; k <= VBM1_K; k++)
        f->c[k] = vbx_ia_point(0.0);
    f->c[0] = v;
}

void vbm1_var(vbm_s1 *f, vbx_ia at)
{
    vbm1_const(f, at);
    f->c[1] = vbx_ia_point(1.0);
}

void vbm1_affine(vbm_s1 *r, vbx_ia v, const vbm_s1 *f, vbx_ia w)
{
    if (v.lo == v.hi) /* a point (the contact's 1 and -2): the same bounds */
        for (int k = 0; k <= VBM1_K; k++)
            r->c[k] = vbm_ia_mul_point(v.lo, f->c[k]);
    else
        for (int k = 0; k <= VBM1_K; k++)
            r->c[k] = vbx_ia_mul(v, f->c[k]);
    r->c[0] = vbx_ia_add(r->c[0], w);
}

void vbm1_add(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g)
{
    for (int k = 0; k <= VBM1_K; k++)
        r->c[k] = vbx_ia_add(f->c[k], g->c[k]);
}

void vbm1_sub(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g)
{
    for (int k = 0; k <= VBM1_K; k++)
        r->c[k] = vbx_ia_sub(f->c[k], g->c[k]);
}

_Static_assert(VBM1_K + 1 <= VBM_DOT_MAX, "the convolutions' terms within vbm_dotn's proof");

/* sum over k in [from, to] of f_k g_(n-k), one rounding bound per end
 * (vbm_dotn: 1crn --contacts, 1 thread, the per-operation roundings of
 * these sums were most of vbm1_mul, the run's largest function) */
static vbx_ia conv(const vbm_s1 *f, const vbm_s1 *g, int n, int from, int to)
{
    return vbm_dotn(&f->c[from], 1, &g->c[n - from], -1, to - from + 1);
}

/* r_n = 0 for n in (kmax, VBM1_K]: the orders a caller does not read
 * (vbm_series1.h's *_to) */
static void zero_above(vbm_s1 *r, int kmax)
{
    for (int n = kmax + 1; n <= VBM1_K; n++)
        r->c[n] = vbx_ia_point(0.0);
}

void vbm1_mul_to(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g, int kmax)
{
    for (int n = 0; n <= kmax; n++)
        r->c[n] = conv(f, g, n, 0, n);
    zero_above(r, kmax);
}

void vbm1_mul(vbm_s1 *r, const vbm_s1 *f, const vbm_s1 *g)
{
    vbm1_mul_to(r, f, g, VBM1_K);
}

vbx_ia vbm1_mul_coef(const vbm_s1 *f, const vbm_s1 *g, int n)
{
    return conv(f, g, n, 0, n);
}

/* f r = 1: r_n = -(sum_{k=1..n} f_k r_(n-k)) / f_0, the division a product
 * with r_0, an enclosure of 1 / f_0 (as vbm1_rational does; the same for
 * vbm1_sqrt and vbm1_log below: 1crn --contacts, 1 thread, their interval
 * divisions were a fifth of their time) */
int vbm1_recip_to(vbm_s1 *r, const vbm_s1 *f, int kmax)
{
    vbx_ia f0 = f->c[0];
    if (!(f0.lo > 0.0 || f0.hi < 0.0))
        return 0;
    r->c[0] = vbx_ia_div(vbx_ia_point(1.0), f0);
    for (int n = 1; n <= kmax; n++)
        r->c[n] = vbx_ia_mul(vbx_ia_neg(conv(f, r, n, 1, n)), r->c[0]);
    zero_above(r, kmax);
    return 1;
}

int vbm1_recip(vbm_s1 *r, const vbm_s1 *f)
{
    return vbm1_recip_to(r, f, VBM1_K);
}

/* An enclosure of 1 / n: the quotient rounded to nearest, one step each way. */
static vbx_ia inv_int(int n)
{
    double q = 1.0 / (double)n;
    vbx_ia r = {vbx_pred(q), vbx_succ(q)};
    return r;
}

/* r r = f: r_n = (f_n - sum_{k=1..n-1} r_k r_(n-k)) / (2 r_0), the sum's
 * symmetric terms once and doubled (exactly: a power of two) and its middle
 * term a square, as vbm_square does for the series in two variables: half
 * the products, and the square's enclosure no wider than the product's
 * (1crn --contacts, 1 thread: vbm1_sqrt was 9.8 % of the CPU). */
int vbm1_sqrt(vbm_s1 *r, const vbm_s1 *f)
{
    return vbm1_sqrt_to(r, f, VBM1_K);
}

int vbm1_sqrt_to(vbm_s1 *r, const vbm_s1 *f, int kmax)
{
    if (!(f->c[0].lo > 0.0))
        return 0;
    r->c[0] = vbx_ia_sqrt(f->c[0]);
    vbx_ia two_r0 = vbx_ia_add(r->c[0], r->c[0]);
    vbx_ia inv = vbx_ia_div(vbx_ia_point(1.0), two_r0);
    for (int n = 1; n <= kmax; n++) {
        vbx_ia s = conv(r, r, n, 1, (n - 1) / 2);
        s.lo *= 2.0;
        s.hi *= 2.0;
        if (n % 2 == 0)
            s = vbx_ia_add(s, vbx_ia_sqr(r->c[n / 2]));
        r->c[n] = vbx_ia_mul(vbx_ia_sub(f->c[n], s), inv);
    }
    zero_above(r, kmax);
    return 1;
}

/* f r' = f': n r_n f_0 = n f_n - sum_{k=1..n-1} k r_k f_(n-k); each
 * k r_k enclosed once (kr), not once per n: the same bounds, a third of
 * the multiplications (1crn --contacts, 1 thread: vbm1_log was 13 % of
 * the CPU). */
int vbm1_log(vbm_s1 *r, const vbm_s1 *f)
{
    return vbm1_log_to(r, f, VBM1_K);
}

int vbm1_log_to(vbm_s1 *r, const vbm_s1 *f, int kmax)
{
    vbx_ia f0 = f->c[0], kr[VBM1_K + 1];
    if (!(f0.lo > 0.0))
        return 0;
    r->c[0] = vbm_ia_log(f0);
    vbx_ia if0 = vbx_ia_div(vbx_ia_point(1.0), f0);
    for (int n = 1; n <= kmax; n++) {
        vbx_ia s = vbm_dotn(&kr[1], 1, &f->c[n - 1], -1, n - 1);
        vbx_ia num = vbx_ia_sub(f->c[n], vbx_ia_mul(s, inv_int(n)));
        r->c[n] = vbx_ia_mul(num, if0);
        kr[n] = vbm_ia_mul_point((double)n, r->c[n]);
    }
    zero_above(r, kmax);
    return 1;
}

void vbm1_moments(double xc, double x0, double x1, vbx_ia *m)
{
    /* integral over [x0 - xc, x1 - xc] of x^n: (b^(n+1) - a^(n+1)) / (n + 1) */
    vbx_ia a = vbx_ia_sub(vbx_ia_point(x0), vbx_ia_point(xc));
    vbx_ia b = vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(xc));
    vbx_ia pa = a, pb = b;
    for (int n = 0; n <= VBM1_K; n++) {
        m[n] = vbx_ia_div(vbx_ia_sub(pb, pa), vbx_ia_point((double)(n + 1)));
        pa = vbx_ia_mul(pa, a);
        pb = vbx_ia_mul(pb, b);
    }
}

vbx_ia vbm1_integrate_m(const vbm_s1 *centre, const vbm_s1 *box, const vbx_ia *m)
{
    /* the remainder c_K(xi) x^K: x^K >= 0 (K even), so its integral lies
     * in the hull of c_K over the box times that of x^K */
    return vbx_ia_add(vbm_dotn(centre->c, 1, m, 1, VBM1_K), vbx_ia_mul(box->c[VBM1_K], m[VBM1_K]));
}
