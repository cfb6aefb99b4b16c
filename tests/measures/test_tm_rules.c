/* The Taylor-model rules of series_tm.c (the product, the root, a model's
 * value over a piece) on functions whose remainders are one-signed and
 * large, so that a rule that drops part of its bound shows: the contact's
 * model (test_contact_tm) is built from these rules, but its remainders
 * are wide enough to absorb such an error on its cases.
 *
 * About xc = 0.125, over the piece x in [-h, h] (h = 0.5, 0.3), at the
 * orders k = 9 (odd: x^k < 0 for x < 0) and 10:
 *   f = t (an exact polynomial, rest 0), g = 1 / (1 - t): g(xc + x) =
 *   sum_{n<k} x^n / u^(n+1) + x^k / (u^k (u - x)), u = 1 - xc, so g's rest
 *   is 1 / (u^k (u - x)) > 0; and f g = t / (1 - t) = g - 1 has the same
 *   rest, while the product rule bounds it as Q + r_g P_f(x) with P_f(x) =
 *   xc + x changing sign over the piece (r_g P_f taken at x = 0 alone gives
 *   Q + r_g xc, above the true rest at x = -h by ~x^k / u^k, which
 *   at h = 0.5, k = 9 is 3e-3 of the value);
 *   s = (2 + 0.75 t + 0.5 t^2) / (1 + t^2), sqrt(s) and s sqrt(s);
 *   the quotients (vbm1_tm_div: the rest (r_f - Q - r_g P_h) / g(x)) t / g
 *   = t (1 - t) and 1 / g = 1 - t (rest 0, where Q = -g's last
 *   coefficient and r_g P_h = +it: either alone misses), 1 / (1 - t) (rests
 *   0 over a rest from dividing by 1 - t over the piece, not at its
 *   middle) and (s sqrt s) / s = sqrt s; the affine maps 3 - 2 g at the
 *   order k - 1 and 0.5 g - 1 at k - 3 (vbm1_tm_affine: g's higher terms
 *   and x^(k-kr) r_g as the rest); a model times a polynomial over a
 *   polynomial (vbm1_tm_mul_div_poly, the contact's last step):
 *   g (4 t - 1/2) / (1.5 + t / 2 - t^2) (num 0 at xc: r_g num(x) taken
 *   there drops the rest's main part) and g (1 - t)^2 / ((1 - t)(2 - t))
 *   = 1 / (2 - t).
 * Each model, at 41 points X of the piece: sum_{n<k} p_n X^n + X^k rest in
 * intervals, and vbm1_tm_value at the point X and over each of the 40
 * parts between the points (its contract: an enclosure of f over the
 * interval it is given, the rest taken over the whole piece), hold the
 * value from the closed form in long double (slack 1e-16 of it: long
 * double's roundings). An x^k taken >= 0 for odd k misses the value at X <
 * 0, where X^k rest is negative. The models are also narrower than a
 * bound the test knows: each rest within 2 of the true one's range
 * times 4 (a rule that widened without bound passes the first check). */
#include <math.h>
#include <stdio.h>

#include "vbm_series1.h"
#include "vb_test.h"

typedef long double ld;

static const double XC = 0.125;
static const double SN[3] = {2.0, 0.75, 0.5};

enum { F_T, F_G, F_FG, F_RS, F_SRS, F_Q1, F_Q2, F_Q3, F_Q4, F_A1, F_A3, F_P1, F_P2, NF };
static const char *const NAME[NF] = {"t",         "1/(1-t)",        "t/(1-t)",
                                     "sqrt s",    "s sqrt s",       "t / (1/(1-t))",
                                     "1 / (1-t)", "(s sqrt s) / s", "1 / (1/(1-t))",
                                     "3 - 2/(1-t) at k - 1", "0.5/(1-t) - 1 at k - 3",
                                     "(1/(1-t)) (4t-1/2) / (1.5+t/2-t^2)",
                                     "(1/(1-t)) (1-t)^2 / ((1-t)(2-t))"};

static ld exact(int w, ld t)
{
    ld s = (SN[0] + t * (SN[1] + t * SN[2])) / (1 + t * t);
    switch (w) {
    case F_T:
        return t;
    case F_Q1:
        return t * (1 - t);
    case F_Q4:
        return 1 - t;
    case F_G:
    case F_Q2:
        return 1 / (1 - t);
    case F_FG:
        return t / (1 - t);
    case F_A1:
        return 3 - 2 / (1 - t);
    case F_A3:
        return 0.5L / (1 - t) - 1;
    case F_P1:
        return (4 * t - 0.5L) / ((1 - t) * (1.5L + 0.5L * t - t * t));
    case F_P2:
        return 1 / (2 - t);
    case F_RS:
    case F_Q3:
        return sqrtl(s);
    default:
        return s * sqrtl(s);
    }
}

static int holds(vbx_ia v, ld y)
{
    double slack = 1e-16 * fabs((double)y);
    return v.lo - slack <= y && y <= v.hi + slack;
}

/* The model at the point X by its own terms: sum p_n X^n + X^k rest. */
static vbx_ia at_point(const vbm1_tm *m, int k, double X)
{
    vbx_ia x = vbx_ia_point(X), v = m->p.c[k - 1], xk = vbx_ia_point(1.0);
    for (int n = k - 2; n >= 0; n--)
        v = vbx_ia_add(vbx_ia_mul(v, x), m->p.c[n]);
    for (int n = 0; n < k; n++)
        xk = vbx_ia_mul(xk, x);
    return vbx_ia_add(v, vbx_ia_mul(xk, m->rest));
}

/* 1 when every check of the model of function w holds. */
static int check_model(const vbm1_tm *m, int w, int k, double h)
{
    int ok = 1;
    for (int i = 0; i <= 40; i++) {
        double X = -h + 2.0 * h * i / 40.0;
        ld y = exact(w, (ld)XC + X);
        vbx_ia pv = at_point(m, k, X), tv = vbm1_tm_value(m, k, vbx_ia_point(X));
        if (!holds(pv, y) || !holds(tv, y)) {
            fprintf(stderr, "  %s k %d h %g x %g: [%.17g, %.17g] / [%.17g, %.17g] miss %.20Lg\n",
                    NAME[w], k, h, X, pv.lo, pv.hi, tv.lo, tv.hi, y);
            ok = 0;
        }
        if (i == 40)
            break;
        double X1 = -h + 2.0 * h * (i + 1) / 40.0;
        vbx_ia part = {X, X1}, pt = vbm1_tm_value(m, k, part);
        if (!holds(pt, y) || !holds(pt, exact(w, (ld)XC + X1))) {
            fprintf(stderr, "  %s k %d h %g over [%g, %g]: [%.17g, %.17g] misses an end\n",
                    NAME[w], k, h, X, X1, pt.lo, pt.hi);
            ok = 0;
        }
    }
    return ok;
}

/* The true rest's range over the piece, sampled (r(x) = (f - P) / x^k at
 * 400 points off 0, in long double), and whether the model's rest lies
 * within its hull widened to 4 times its width about its middle plus 2
 * times the largest value: a bound the rules meet on these cases. */
static int check_tight(const vbm1_tm *m, int w, int k, double h)
{
    ld lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i <= 400; i++) {
        ld X = -h + 2.0L * h * i / 400.0L, p = 0, xk = 1;
        if (fabsl(X) < 1e-3L)
            continue;
        for (int n = k - 1; n >= 0; n--)
            p = p * X + vbx_ia_mid(m->p.c[n]);
        for (int n = 0; n < k; n++)
            xk *= X;
        ld r = (exact(w, (ld)XC + X) - p) / xk;
        lo = r < lo ? r : lo;
        hi = r > hi ? r : hi;
    }
    double mid = (double)(0.5L * (lo + hi)), big = (double)fmaxl(fabsl(lo), fabsl(hi));
    double span = (double)(2.0L * (hi - lo)) + 2.0 * big;
    int ok = m->rest.lo >= mid - span && m->rest.hi <= mid + span;
    if (!ok)
        fprintf(stderr, "  %s k %d h %g: rest [%.6g, %.6g] against the true [%.6Lg, %.6Lg]\n",
                NAME[w], k, h, m->rest.lo, m->rest.hi, lo, hi);
    return ok;
}

/* The thirteen models at the order k (the affine maps' lower) over [-h, h]. */
static int check_rules(int k, double h)
{
    vbx_ia one = vbx_ia_point(1.0), zero = vbx_ia_point(0.0), x = {-h, h};
    vbx_ia tn[2] = {zero, one}, td[1] = {one}, gn[1] = {one}, gd[2] = {one, vbx_ia_point(-1.0)};
    vbx_ia sn[3], sd[3] = {one, zero, one};
    for (int i = 0; i < 3; i++)
        sn[i] = vbx_ia_point(SN[i]);
    vbm1_tm m[NF];
    if (!vbm1_tm_rational(&m[F_T], tn, 1, td, 0, XC, k, x) ||
        !vbm1_tm_rational(&m[F_G], gn, 0, gd, 1, XC, k, x))
        return 0;
    vbm1_tm s;
    if (!vbm1_tm_rational(&s, sn, 2, sd, 2, XC, k, x) || !vbm1_tm_sqrt(&m[F_RS], &s, k, x))
        return 0;
    vbm1_tm_mul(&m[F_FG], &m[F_T], &m[F_G], k, x);
    vbm1_tm_mul(&m[F_SRS], &s, &m[F_RS], k, x);
    /* 1 / (1 - t) and 1 - t over the piece from their closed forms (the
     * models' values by Horner over [-0.5, 0.5] hold 0) */
    vbx_ia omt = vbx_ia_sub(one, vbx_ia_add(vbx_ia_point(XC), x)), gx = vbx_ia_div(one, omt);
    vbx_ia on[1] = {one}, ln[2] = {one, vbx_ia_point(-1.0)};
    vbm1_tm c1, lin;
    if (!vbm1_tm_rational(&c1, on, 0, td, 0, XC, k, x) ||
        !vbm1_tm_rational(&lin, ln, 1, td, 0, XC, k, x) ||
        !vbm1_tm_div(&m[F_Q1], &m[F_T], &m[F_G], gx, k, x) ||
        !vbm1_tm_div(&m[F_Q2], &c1, &lin, omt, k, x) ||
        !vbm1_tm_div(&m[F_Q3], &m[F_SRS], &s, vbm1_tm_value(&s, k, x), k, x) ||
        !vbm1_tm_div(&m[F_Q4], &c1, &m[F_G], gx, k, x))
        return 0;
    /* the affine maps (vbm1_tm_affine) at lower orders: g's terms of
     * orders kr .. k - 1 join the rest, whose x^(k-kr) r_g dropped misses */
    vbm1_tm_affine(&m[F_A1], vbx_ia_point(-2.0), &m[F_G], vbx_ia_point(3.0), k, k - 1, x);
    vbm1_tm_affine(&m[F_A3], vbx_ia_point(0.5), &m[F_G], vbx_ia_point(-1.0), k, k - 3, x);
    /* a model times a polynomial over a polynomial (vbm1_tm_mul_div_poly):
     * g (4 t - 1/2) / (1.5 + t / 2 - t^2), whose rest takes g's, and g (1 -
     * t)^2 / ((1 - t)(2 - t)) = 1 / (2 - t), where g's pole cancels and
     * the rest is 1 / (v^k (v - x)), v = 2 - xc: num's and den's high
     * orders (Q_u, Q_h) and r_g num(x) each carry part of it */
    vbx_ia n1[3] = {vbx_ia_point(-0.5), vbx_ia_point(4.0), zero}, d1[3] = {vbx_ia_point(1.5), vbx_ia_point(0.5),
                                                            vbx_ia_point(-1.0)};
    vbx_ia n2[3] = {one, vbx_ia_point(-2.0), one}, d2[3] = {vbx_ia_point(2.0), vbx_ia_point(-3.0), one};
    vbx_ia mn1[3], md1[3], mn2[3], md2[3], T = vbx_ia_add(vbx_ia_point(XC), x);
    vbm1_poly_at(mn1, n1, 1, XC);
    vbm1_poly_at(md1, d1, 2, XC);
    vbm1_poly_at(mn2, n2, 2, XC);
    vbm1_poly_at(md2, d2, 2, XC);
    vbx_ia dx2 = vbx_ia_mul(omt, vbx_ia_sub(vbx_ia_point(2.0), T));
    if (!vbm1_tm_mul_div_poly(&m[F_P1], &m[F_G], mn1, 1, md1, 2, vbm1_poly2_range(d1, T), k, x) ||
        !vbm1_tm_mul_div_poly(&m[F_P2], &m[F_G], mn2, 2, md2, 2, dx2, k, x))
        return 0;
    int ok = 1;
    for (int w = 0; w < NF; w++) {
        int kw = w == F_A1 ? k - 1 : w == F_A3 ? k - 3 : k;
        ok &= check_model(&m[w], w, kw, h);
        if (w != F_T && w != F_Q1 && w != F_Q4) /* their rests are 0 */
            ok &= check_tight(&m[w], w, kw, h);
    }
    return ok;
}

int main(void)
{
    for (int k = 9; k <= 10; k++) {
        CHECK(check_rules(k, 0.5));
        CHECK(check_rules(k, 0.3));
    }
    VB_TEST_END();
}
