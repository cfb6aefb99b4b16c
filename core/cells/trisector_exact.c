/* Exact membership of a trisector point in the Voronoi edge, for triples
 * of equal radii, where the trisector is the line through the circumcentre
 * O of the three centres along n = (c_b - c_a) x (c_c - c_a): rational
 * points O + lambda n on it can be decided exactly, which topology needs
 * where a fourth sphere touches the tangent sphere within rounding (exact
 * lattices: touching, on the edge; jittered ones: cutting by 1e-18). */
#include <gmp.h>

#include "vbs_internal.h"

static void dec_to_q(mpq_t q, vb_decimal d)
{
    mpz_t p;
    mpz_init(p);
    mpq_set_si(q, (long)d.mant, 1);
    mpz_ui_pow_ui(p, 10, (unsigned long)(d.exp10 < 0 ? -d.exp10 : d.exp10));
    if (d.exp10 >= 0) {
        mpz_mul(mpq_numref(q), mpq_numref(q), p);
    } else {
        mpz_set(mpq_denref(q), p);
        mpq_canonicalize(q);
    }
    mpz_clear(p);
}

int vbs_trisector_equal_radii(const vb_sphere_set *s, const uint32_t t[3])
{
    if (!s->er)
        return s->r[t[0]] == s->r[t[1]] && s->r[t[0]] == s->r[t[2]];
    mpq_t a, b;
    mpq_inits(a, b, NULL);
    dec_to_q(a, s->er[t[0]]);
    dec_to_q(b, s->er[t[1]]);
    int eq = mpq_equal(a, b);
    dec_to_q(b, s->er[t[2]]);
    eq = eq && mpq_equal(a, b);
    mpq_clears(a, b, NULL);
    return eq;
}

/* c = a . b for 3-vectors. */
static void qdot(mpq_t c, mpq_t a[3], mpq_t b[3], mpq_t tmp)
{
    mpq_mul(c, a[0], b[0]);
    for (int k = 1; k < 3; k++) {
        mpq_mul(tmp, a[k], b[k]);
        mpq_add(c, c, tmp);
    }
}

/* Centre of sphere i, exact (from the decimals when the set has them). */
static void centre(mpq_t c[3], const vb_sphere_set *s, uint32_t i)
{
    if (s->ex) {
        dec_to_q(c[0], s->ex[i]);
        dec_to_q(c[1], s->ey[i]);
        dec_to_q(c[2], s->ez[i]);
    } else {
        mpq_set_d(c[0], s->x[i]);
        mpq_set_d(c[1], s->y[i]);
        mpq_set_d(c[2], s->z[i]);
    }
}

static void radius(mpq_t r, const vb_sphere_set *s, uint32_t i)
{
    if (s->er)
        dec_to_q(r, s->er[i]);
    else
        mpq_set_d(r, s->r[i]);
}

/* 1 when sqrt(B) < sqrt(A) + D (sphere j, at squared distance B from the
 * point, cuts the tangent sphere of squared distance A to sphere a, with
 * D = r_j - r_a). */
static int cuts(mpq_t A, mpq_t B, mpq_t D, mpq_t X, mpq_t Y)
{
    mpq_mul(Y, D, D);
    if (mpq_sgn(D) <= 0 && mpq_cmp(Y, A) >= 0)
        return 0; /* sqrt(A) + D <= 0 */
    mpq_sub(X, B, A);
    mpq_sub(X, X, Y);             /* X = B - A - D^2; cut iff X < 2 D sqrt(A) */
    mpq_mul(Y, Y, A);
    mpq_add(Y, Y, Y);
    mpq_add(Y, Y, Y);             /* Y = 4 D^2 A */
    if (mpq_sgn(D) >= 0) {
        if (mpq_sgn(X) < 0)
            return 1;
        mpq_mul(X, X, X);
        return mpq_cmp(X, Y) < 0;
    }
    if (mpq_sgn(X) >= 0)
        return 0;
    mpq_mul(X, X, X);
    return mpq_cmp(X, Y) > 0;
}

int vbs_trisector_exact_on_edge(const vb_sphere_set *s, const uint32_t t[3], const double p[3],
                                const uint32_t *cand, size_t ncand)
{
    mpq_t ca[3], u[3], v[3], n[3], w[3], P[3], tmp, uu, vv, nn, lam, A, B, D, X, Y, ra;
    for (int k = 0; k < 3; k++)
        mpq_inits(ca[k], u[k], v[k], n[k], w[k], P[k], NULL);
    mpq_inits(tmp, uu, vv, nn, lam, A, B, D, X, Y, ra, NULL);
    centre(ca, s, t[0]);
    centre(u, s, t[1]);
    centre(v, s, t[2]);
    radius(ra, s, t[0]);
    for (int k = 0; k < 3; k++) {
        mpq_sub(u[k], u[k], ca[k]);
        mpq_sub(v[k], v[k], ca[k]);
    }
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        mpq_mul(n[k], u[i], v[j]);
        mpq_mul(tmp, u[j], v[i]);
        mpq_sub(n[k], n[k], tmp);
    }
    qdot(uu, u, u, tmp);
    qdot(vv, v, v, tmp);
    qdot(nn, n, n, tmp);
    /* Circumcentre offset q = (|u|^2 (v x n) + |v|^2 (n x u)) / (2 |n|^2). */
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        mpq_mul(X, v[i], n[j]);
        mpq_mul(tmp, v[j], n[i]);
        mpq_sub(X, X, tmp);
        mpq_mul(X, X, uu);
        mpq_mul(Y, n[i], u[j]);
        mpq_mul(tmp, n[j], u[i]);
        mpq_sub(Y, Y, tmp);
        mpq_mul(Y, Y, vv);
        mpq_add(X, X, Y);
        mpq_add(tmp, nn, nn);
        mpq_div(w[k], X, tmp);
        mpq_add(w[k], w[k], ca[k]); /* w = O */
    }
    /* lambda from the double point, exactly; P = O + lambda n. */
    for (int k = 0; k < 3; k++) {
        mpq_set_d(P[k], p[k]);
        mpq_sub(P[k], P[k], w[k]);
    }
    qdot(lam, P, n, tmp);
    mpq_div(lam, lam, nn);
    for (int k = 0; k < 3; k++) {
        mpq_mul(P[k], lam, n[k]);
        mpq_add(P[k], P[k], w[k]);
        mpq_sub(u[k], P[k], ca[k]);
    }
    qdot(A, u, u, tmp);
    int on = 1;
    for (size_t m = 0; m < ncand && on; m++) {
        uint32_t j = cand[m];
        if (j == t[0] || j == t[1] || j == t[2] || (s->contained && s->contained[j]))
            continue;
        centre(v, s, j);
        for (int k = 0; k < 3; k++)
            mpq_sub(v[k], P[k], v[k]);
        qdot(B, v, v, tmp);
        radius(D, s, j);
        mpq_sub(D, D, ra);
        on = !cuts(A, B, D, X, Y);
    }
    for (int k = 0; k < 3; k++)
        mpq_clears(ca[k], u[k], v[k], n[k], w[k], P[k], NULL);
    mpq_clears(tmp, uu, vv, nn, lam, A, B, D, X, Y, ra, NULL);
    return on;
}
