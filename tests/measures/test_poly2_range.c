/* A quadratic's range over an interval (vbm1_poly2_range) and a quotient
 * whose divisor's enclosure over the piece is met with it (vbm1_meet): the
 * contact's model (contact_tm.c) divides its rest by 1 - z so.
 *
 * The range: quadratics with the vertex inside T, outside it, at an end,
 * opening up and down, c2 = 0 and c2 an interval holding 0 (Horner over
 * T), with point coefficients and with each coefficient widened to an
 * interval. Every value of every quadratic whose coefficients are corners
 * of the boxes, at 401 points of T and at its vertex where that lies in T,
 * in long double, lies in the range (a range from the ends alone, or the
 * vertex's value of the wrong sign, misses it); with point coefficients and
 * c2 != 0 both ends of the range lie within 1e-12 of the sampled extremes
 * (Horner's scheme over T, which counts t twice, is wider by up to |c1 T|).
 *
 * The quotient: f = 1 / p, p = 1.1 - 2 t + t^2 (least 0.1 at t = 1, as 1 - z
 * near e_j), about xc = 0.9 over x in [-h, h], h = 0.3 and 0.4, order 10
 * (vbm1_tm_div). p's model's value over the piece by Horner holds 0 there,
 * so from it alone the model is not made; met with p's range it is, and at
 * 41 points X sum p_n X^n + X^k rest holds f(xc + X) (a meet that kept
 * either side alone, or took the hull, leaves no model). */
#include <math.h>
#include <stdio.h>

#include "vbm_series1.h"
#include "vb_test.h"

typedef long double ld;

typedef struct qcase {
    double c[3], w; /* coefficients, the relative widening of each */
    double lo, hi;  /* T */
} qcase;

static const qcase CASES[] = {
    {{1.0, -2.0, 1.1}, 0.0, 0.5, 1.5},     /* up, vertex inside */
    {{1.0, -2.0, 1.1}, 1e-9, 0.5, 1.5},    /* the same, interval coefficients */
    {{-0.3, 1.5, -2.0}, 0.0, -1.0, 1.0},   /* down, vertex inside */
    {{-0.3, 1.5, -2.0}, 1e-6, -1.0, 1.0},
    {{2.0, 0.75, 0.5}, 0.0, 0.0, 3.0},     /* vertex at -0.75, outside */
    {{2.0, 0.75, 0.5}, 1e-9, 0.0, 3.0},
    {{0.25, -1.0, 1.0}, 0.0, 0.5, 0.9},    /* vertex at the lower end */
    {{1.0, -4.0, 0.0}, 0.0, -0.5, 0.25},   /* a line: Horner */
    {{1.0, -4.0, 1e-300}, 1.0, -0.5, 0.25} /* c2 an interval holding 0 */
};

static vbx_ia widen(double v, double w)
{
    double d = fabs(v) * w;
    vbx_ia r = {v - d, v + d};
    if (w > 0.0 && d == 0.0) /* 0 widened: [-w, w] */
        r = (vbx_ia){-w, w};
    return r;
}

/* 1 when every quadratic of the case's corners lies in the range over T
 * (and, with point coefficients, the range is tight). */
static int check_range(const qcase *q)
{
    vbx_ia c[3];
    for (int i = 0; i < 3; i++)
        c[i] = widen(q->c[i], q->w);
    vbx_ia T = {q->lo, q->hi}, r = vbm1_poly2_range(c, T);
    int ok = 1;
    ld mn = INFINITY, mx = -INFINITY;
    for (int corner = 0; corner < 8; corner++) {
        ld a[3];
        for (int i = 0; i < 3; i++)
            a[i] = corner >> i & 1 ? c[i].hi : c[i].lo;
        for (int s = 0; s <= 402; s++) {
            ld t = q->lo + (ld)(q->hi - q->lo) * s / 400.0L;
            if (s > 400) { /* the vertex, where it lies in T */
                if (a[2] == 0 || s == 402)
                    continue;
                t = -a[1] / (2 * a[2]);
                if (t < q->lo || t > q->hi)
                    continue;
            }
            ld v = a[0] + t * (a[1] + t * a[2]);
            mn = v < mn ? v : mn;
            mx = v > mx ? v : mx;
            if (!(r.lo <= v && v <= r.hi)) {
                fprintf(stderr, "  c %g %g %g over [%g, %g]: %.20Lg at %.17Lg not in [%.17g, %.17g]\n",
                        q->c[0], q->c[1], q->c[2], q->lo, q->hi, v, t, r.lo, r.hi);
                ok = 0;
            }
        }
    }
    if (q->w == 0.0 && q->c[2] != 0.0) {
        ld tol = 1e-12L * (1 + fabsl(mn) + fabsl(mx));
        if (!(r.lo >= mn - tol && r.hi <= mx + tol)) {
            fprintf(stderr, "  c %g %g %g over [%g, %g]: [%.17g, %.17g] wider than [%.17Lg, %.17Lg]\n",
                    q->c[0], q->c[1], q->c[2], q->lo, q->hi, r.lo, r.hi, mn, mx);
            ok = 0;
        }
    }
    return ok;
}

static ld f_exact(ld t)
{
    return 1 / (1.1L - 2 * t + t * t);
}

/* The quotient 1 / p over [xc - h, xc + h] with p's value over the piece
 * the meet of its model's (Horner) and its range: made (and not made
 * from the model's value alone), and holding f at 41 points. */
static int check_quotient(double h)
{
    const double XC = 0.9;
    const int k = VBM1_K;
    vbx_ia one[1] = {vbx_ia_point(1.0)}, x = {-h, h};
    vbx_ia p[3] = {vbx_ia_point(1.1), vbx_ia_point(-2.0), vbx_ia_point(1.0)};
    vbm1_tm c1, y, m;
    if (!vbm1_tm_rational(&c1, one, 0, one, 0, XC, k, x) ||
        !vbm1_tm_rational(&y, p, 2, one, 0, XC, k, x))
        return 0;
    vbx_ia yh = vbm1_tm_value(&y, k, x);
    vbx_ia yx = vbm1_meet(yh, vbm1_poly2_range(p, vbx_ia_add(vbx_ia_point(XC), x)));
    if (vbm1_tm_div(&m, &c1, &y, yh, k, x)) {
        fprintf(stderr, "  h %g: Horner's p over the piece excludes 0: the case tests nothing\n", h);
        return 0;
    }
    if (!vbm1_tm_div(&m, &c1, &y, yx, k, x)) {
        fprintf(stderr, "  h %g: no model with p over the piece in [%.17g, %.17g]\n", h, yx.lo, yx.hi);
        return 0;
    }
    int ok = 1;
    for (int i = 0; i <= 40; i++) {
        double X = -h + 2.0 * h * i / 40.0;
        vbx_ia xv = vbx_ia_point(X), v = m.p.c[k - 1], xk = vbx_ia_point(1.0);
        for (int n = k - 2; n >= 0; n--)
            v = vbx_ia_add(vbx_ia_mul(v, xv), m.p.c[n]);
        for (int n = 0; n < k; n++)
            xk = vbx_ia_mul(xk, xv);
        v = vbx_ia_add(v, vbx_ia_mul(xk, m.rest));
        ld f = f_exact((ld)XC + X);
        double slack = 1e-15 * fabs((double)f);
        if (!(v.lo - slack <= f && f <= v.hi + slack)) {
            fprintf(stderr, "  h %g x %g: [%.17g, %.17g] misses %.20Lg\n", h, X, v.lo, v.hi, f);
            ok = 0;
        }
    }
    return ok;
}

int main(void)
{
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++)
        CHECK(check_range(&CASES[i]));
    CHECK(check_quotient(0.3));
    CHECK(check_quotient(0.4));
    VB_TEST_END();
}
