/* The contact's Taylor model over a piece (contact_tm.c) against the
 * integrand in long double from its closed form: for an arc of z(t) =
 * Pz / E (E = 1 + t^2), q = D z + delta, the contact's integrand is
 * F(z(t)) an(t) / cd(t), F(z) = C (G(D + delta) - G(q)) with
 *   G(q) = -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q)
 *          - delta^2 / (2 N sqrt N) log |(sqrt S - sqrt N) / (sqrt S + sqrt N)|,
 * S = N + 2 delta q, C = N^2 / (4 D) (stokes_cell.c). On wide pieces
 * (half-width 0.4, where x^K rest is ~1e-6 of the value) and narrow ones,
 * for delta = 0 and delta != 0, the model sum_{n<K} c_n x^n + x^K rest,
 * evaluated in intervals at 41 points of the piece, holds the long double
 * value (slack 1e-16 of it: long double's roundings); the same with the
 * area's integrand an / ad = 1 - z, where con = F (the model's F / (1 - z)
 * times 1 - z); and the models of sqrt(S) and S sqrt(S)
 * alone against sqrtl; and an arc passing near e_j (PZ2: 1 - z down to 0.01 / E,
 * where 1 / (1 - z) has poles 0.14 off the arc). The model's own
 * polynomials (q' / q^3, S, an / cd) are made here from Pz, D and delta. */
#include <math.h>
#include <stdio.h>

#include "vbm_contact_tm.h"
#include "vbm_series1.h"
#include "vb_test.h"

typedef long double ld;

static const double PZ1[3] = {0.625, 0.125, 0.375}; /* z(0) = 0.625, z(+-inf) = 0.375 */
/* an arc passing near e_j: 1 - z = (0.03 - 0.2 t + 0.5 t^2) / E, least 0.01 / E at t = 0.2
 * (complex zeros at 0.2 +- 0.141i), 0.03 at t = 0: cd varies by a factor ~2 over a piece of
 * half-width 0.05 there, so a rest divided by cd at the middle, not over the piece, shows */
static const double PZ2[3] = {0.97, 0.2, 0.5};
static const double *PZ = PZ1;
static const double AN[3] = {0.5, 0.25, -0.125};

static ld poly(const double *p, int d, ld t)
{
    ld v = p[d];
    for (int k = d - 1; k >= 0; k--)
        v = v * t + p[k];
    return v;
}

static ld G(ld q, ld N, ld delta)
{
    ld S = N + 2 * delta * q, rS = sqrtl(S), rN = sqrtl(N);
    ld g = -S * rS / (2 * N * q * q) + delta * rS / (2 * N * q);
    if (delta != 0)
        g -= delta * delta / (2 * N * rN) * logl(fabsl((rS - rN) / (rS + rN)));
    return g;
}

/* F(z(t)) an(t) / cd(t), cd = (E + Pz)(E - Pz) (the area's integrand
 * 2 Pn / (E Po) over 1 - z = (E - Pz) / E); with `fonly`, F(z(t)) */
static ld con(ld t, ld D, ld delta, int fonly)
{
    ld N = D * D - delta * delta, E = 1 + t * t, pz = poly(PZ, 2, t);
    ld z = pz / E, F = N * N / (4 * D) * (G(D + delta, N, delta) - G(D * z + delta, N, delta));
    return fonly ? F : F * poly(AN, 2, t) / ((E + pz) * (E - pz));
}

static vbx_ia pt(double v)
{
    return vbx_ia_point(v);
}

/* The model over [xc - h, xc + h]; 1 when every sample holds the value. */
static int check(double D, double delta, double xc, double h, int fonly)
{
    vbx_ia one = pt(1.0), E[3] = {one, pt(0.0), one}, Pz[3], Pq[3], dq[3], Pq2[5], Po[3], Emz[3];
    vbm_contact_rat p;
    vbx_ia iD = pt(D), idl = pt(delta), N = vbx_ia_sub(vbx_ia_sqr(iD), vbx_ia_sqr(idl));
    for (int k = 0; k < 3; k++) {
        Pz[k] = pt(PZ[k]);
        Pq[k] = vbx_ia_add(vbx_ia_mul(iD, Pz[k]), vbx_ia_mul(idl, E[k]));
        Po[k] = vbx_ia_add(E[k], Pz[k]);
        Emz[k] = vbx_ia_sub(E[k], Pz[k]);
        p.an[k] = pt(AN[k]);
        p.sd[k] = E[k];
        p.yn[k] = Emz[k];
    }
    /* q' / q^3 = (Pq' E - Pq E') E / Pq^3 */
    dq[0] = Pq[1];
    dq[1] = vbx_ia_mul(pt(2.0), vbx_ia_sub(Pq[2], Pq[0]));
    dq[2] = vbx_ia_neg(Pq[1]);
    vbm1_poly_mul(p.rn, dq, 2, E, 2);
    vbm1_poly_mul(Pq2, Pq, 2, Pq, 2);
    vbm1_poly_mul(p.rd, Pq2, 4, Pq, 2);
    for (int k = 0; k < 3; k++) /* the area's integrand an / (E Po) */
        p.po[k] = fonly ? (k ? pt(0.0) : one) : Po[k];
    for (int k = 0; fonly && k < 3; k++) /* an / (E po) = (1 - z): con = F */
        p.an[k] = Emz[k];
    vbm1_poly_mul(p.cd, p.po, 2, Emz, 2);
    vbm_owner o = {0};
    o.D = iD;
    o.delta = idl;
    o.N = N;
    o.rN = vbx_ia_sqrt(N);
    o.C = vbx_ia_div(vbx_ia_sqr(N), vbx_ia_mul(pt(4.0), iD));
    ld Nl = (ld)D * D - (ld)delta * delta, tc = xc, Ec = 1 + tc * tc;
    ld Fc = Nl * Nl / (4 * (ld)D) *
            (G(D + (ld)delta, Nl, delta) - G(D * (poly(PZ, 2, tc) / Ec) + delta, Nl, delta));
    double fc = (double)Fc, sl = 1e-15 * fabs(fc);
    vbx_ia F0 = {fc - sl, fc + sl};
    vbm_s1 c;
    vbx_ia rest, x = {-h, h};
    if (!vbm_contact_tm(&p, &o, F0, xc, x, &c, &rest)) {
        fprintf(stderr, "  no model at D %g delta %g xc %g h %g\n", D, delta, xc, h);
        return 0;
    }
    int ok = 1;
    double most = 0.0;
    for (int i = 0; i <= 40; i++) {
        double xs = -h + 2.0 * h * i / 40.0;
        vbx_ia X = pt(xs), v = c.c[VBM1_K - 1], xk = one;
        for (int n = VBM1_K - 2; n >= 0; n--)
            v = vbx_ia_add(vbx_ia_mul(v, X), c.c[n]);
        for (int n = 0; n < VBM1_K; n++)
            xk = vbx_ia_mul(xk, X);
        v = vbx_ia_add(v, vbx_ia_mul(xk, rest));
        ld y = con((ld)xc + xs, D, delta, fonly);
        double slack = 1e-16 * fabs((double)y);
        double r = fabs(xs) > 0.0 ? fabs(xs * xs * xs * xs * xs * xs * xs * xs * xs * xs) *
                                        fmax(fabs(rest.lo), fabs(rest.hi)) / fabs((double)y)
                                  : 0.0;
        most = fmax(most, r);
        if (!(v.lo - slack <= y && y <= v.hi + slack)) {
            fprintf(stderr, "  D %g delta %g xc %g x %g: [%.17g, %.17g] misses %.20Lg\n", D, delta,
                    xc, xs, v.lo, v.hi, y);
            ok = 0;
        }
    }
    fprintf(stderr, "  D %g delta %g xc %g h %g%s: remainder term up to %.3g of the value\n", D,
            delta, xc, h, fonly ? " (F alone)" : "", most);
    return ok;
}

/* The models of sqrt(S) and of S sqrt(S) (vbm1_tm_sqrt, vbm1_tm_mul; S =
 * SN / (1 + t^2), the order k) over [xc - h, xc + h] hold the long double
 * values at 41 points. */
static int check_root(double xc, double h, int k)
{
    static const double SN[3] = {2.0, 0.75, 0.5};
    vbx_ia one = pt(1.0), E[3] = {one, pt(0.0), one}, S3[3], x = {-h, h};
    for (int i = 0; i < 3; i++)
        S3[i] = pt(SN[i]);
    vbm1_tm s, r, sr;
    if (!vbm1_tm_rational(&s, S3, 2, E, 2, xc, k, x) || !vbm1_tm_sqrt(&r, &s, k, x))
        return 0;
    vbm1_tm_mul(&sr, &s, &r, k, x);
    int ok = 1;
    for (int i = 0; i <= 40; i++) {
        double xs = -h + 2.0 * h * i / 40.0;
        ld t = (ld)xc + xs, S = poly(SN, 2, t) / (1 + t * t);
        ld want[2] = {sqrtl(S), S * sqrtl(S)};
        const vbm1_tm *m[2] = {&r, &sr};
        for (int w = 0; w < 2; w++) {
            vbx_ia X = pt(xs), v = m[w]->p.c[k - 1], xk = one;
            for (int n = k - 2; n >= 0; n--)
                v = vbx_ia_add(vbx_ia_mul(v, X), m[w]->p.c[n]);
            for (int n = 0; n < k; n++)
                xk = vbx_ia_mul(xk, X);
            v = vbx_ia_add(v, vbx_ia_mul(xk, m[w]->rest));
            double slack = 1e-16 * fabs((double)want[w]);
            if (!(v.lo - slack <= want[w] && want[w] <= v.hi + slack)) {
                fprintf(stderr, "  %s xc %g x %g k %d: [%.17g, %.17g] misses %.20Lg\n",
                        w ? "S sqrt S" : "sqrt S", xc, xs, k, v.lo, v.hi, want[w]);
                ok = 0;
            }
        }
    }
    return ok;
}

/* vbm_contact_start: the whole arc where the area's term is small beside
 * the target, at most half of it above 2^-18, then vbm_contact_step of
 * 2^13 r (its 2^(j/4) steps, clamped at j = -8). */
static int check_start(void)
{
    static const double r[7] = {0.0, 0x1p-30, 0x1p-18, 0x1p-17, 0x1p-10, 1.0, 0x1p10};
    static const double want[7] = {1.0, 1.0, 1.0, 0.5, 0.5, 0.35355339059327379, 0.25};
    int ok = 1;
    for (int i = 0; i < 7; i++)
        if (vbm_contact_start(r[i]) != want[i]) {
            fprintf(stderr, "  vbm_contact_start(%g) = %.17g, not %.17g\n", r[i],
                    vbm_contact_start(r[i]), want[i]);
            ok = 0;
        }
    return ok && vbm_contact_start(NAN) == 1.0;
}

/* vbm_contact_step_at: a missed piece (rho > 1, or not made) is always
 * retried at most 0.75 of its length at any margin, so march, which takes
 * the rest of the arc once it is within 1.25 lengths, cannot give the same
 * piece again (without the cap: 2^-1/4 at safety 1, rho just above 1);
 * a kept piece (rho <= 1) at the rule's factor, uncapped (rho 1 and 1/2:
 * 2^-1/4); and the in-use margin's factors as before (2^(j/4), j the
 * largest with 2^(K j / 4) <= 2^(e-1), 2^(e-1) <= 0.25 / rho < 2^e). */
static int check_step(void)
{
    static const double safety[6] = {0.125, 0.25, 0.35, 0.5, 1.0, 4.0};
    int ok = 1;
    for (int s = 0; s < 6; s++)
        for (int i = 0; i <= 400; i++) {
            double rho = i == 400 ? INFINITY : 1.0 + ldexp(1.0, -52 + i / 8) * (1 + i % 8);
            double f = vbm_contact_step_at(rho, safety[s]);
            if (!(f > 0.0 && 1.25 * f < 1.0)) {
                fprintf(stderr, "  step_at(%.17g, %g) = %.17g: a retry may repeat the piece\n",
                        rho, safety[s], f);
                ok = 0;
            }
        }
    static const double rho[6] = {1.0, 0.5, 0x1p-10, 1.5, 0x1p20, NAN};
    static const double want[6] = {0.84089641525371450, 0.84089641525371450,
                                    1.681792830507429, 0.70710678118654757, 0.25, 0.25};
    for (int i = 0; i < 6; i++)
        if (vbm_contact_step(rho[i]) != want[i]) {
            fprintf(stderr, "  vbm_contact_step(%g) = %.17g, not %.17g\n", rho[i],
                    vbm_contact_step(rho[i]), want[i]);
            ok = 0;
        }
    return ok && vbm_contact_step(0.0) == 4.0;
}

int main(void)
{
    CHECK(check_start());
    CHECK(check_step());
    for (int k = 4; k <= VBM1_K; k += 3) {
        CHECK(check_root(0.2, 0.5, k));
        CHECK(check_root(-0.4, 0.1, k));
    }
    const double deltas[5] = {0.0, 0.15, -0.25, 1.2, -1.0};
    for (int k = 0; k < 5; k++)
        for (int fonly = 0; fonly < 2; fonly++) {
            CHECK(check(3.0, deltas[k], 0.1, 0.4, fonly));
            CHECK(check(3.0, deltas[k], -0.3, 0.25, fonly));
            CHECK(check(2.5, deltas[k], 0.05, 0.05, fonly));
        }
    PZ = PZ2;
    for (int k = 0; k < 5; k++)
        for (int fonly = 0; fonly < 2; fonly++) {
            CHECK(check(3.0, deltas[k], 0.05, 0.05, fonly));
            CHECK(check(3.0, deltas[k], 0.35, 0.1, fonly));
        }
    VB_TEST_END();
}
