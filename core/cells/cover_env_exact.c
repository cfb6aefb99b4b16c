/* The exact signs of the envelope decision (core/cells/vbq_env_exact.h;
 * the argument and the rows are in cover_envelope.c's top comment): each
 * sign first from doubles with a proven bound, then exactly, in checked
 * 128-bit integers where the numbers fit (an exact crystal's ties, whose
 * signs are 0, are decided there), else in GMP. */
#include <gmp.h>
#include <math.h>
#include <stdlib.h>

#include "vb_cover_shared.h"
#include "vb_decimal_mpz.h"
#include "vbq_cluster.h"
#include "vbq_env_exact.h"

/* The common exponent of the decimals of the base and the labels. */
static int32_t env_emin(const vbq_env_ctx *c)
{
    const vb_decimal *col[3] = {c->s->ex, c->s->ey, c->s->ez};
    int32_t emin = col[0][c->i].exp10;
    for (vbs_u32 k = 0; k <= c->n; k++) {
        vbs_u32 j = k < c->n ? c->L[k].id : c->i;
        for (int a = 0; a < 3; a++)
            if (col[a][j].exp10 < emin)
                emin = col[a][j].exp10;
    }
    return emin;
}

/* fn (mpz_init or mpz_clear) on every integer of the context but the rows. */
static void env_ctx_each(vbq_env_ctx *c, void (*fn)(mpz_ptr))
{
    for (int a = 0; a < 4; a++) {
        fn(c->X.q[a]);
        fn(c->C[a]);
    }
    for (int a = 0; a < 6; a++)
        fn(c->m2[a]);
    fn(c->X.t);
    fn(c->acc);
}

/* The integer rows (N_j, D_j) of the labels of the patch (see the top) in
 * GMP, and their doubles rd unless made already. */
static int env_rows_mpz(vbq_env_ctx *c)
{
    vbq_env_rows *X = &c->X;
    if (!c->zinit) {
        env_ctx_each(c, mpz_init);
        c->zinit = 1;
    }
    vbs_u32 n = c->n;
    const vb_decimal *col[3] = {c->s->ex, c->s->ey, c->s->ez};
    int32_t emin = env_emin(c);
    X->n = n;
    X->row = malloc((size_t)(n + 1) * sizeof *X->row);
    if (!X->row)
        return 0;
    if (!X->made && !(X->rd = malloc((size_t)(n + 1) * sizeof *X->rd))) {
        free(X->row);
        X->row = NULL;
        return 0;
    }
    mpz_t ci[3];
    for (int a = 0; a < 3; a++)
        mpz_init(ci[a]);
    for (int a = 0; a < 3; a++)
        vb_decimal_to_mpz(ci[a], col[a][c->i], emin, X->t);
    for (vbs_u32 k = 0; k <= n; k++) {
        for (int a = 0; a < 4; a++)
            mpz_init(X->row[k][a]);
        if (k == n) {
            mpz_set_ui(X->row[k][0], 1);
            continue;
        }
        for (int a = 0; a < 3; a++) {
            vb_decimal_to_mpz(X->row[k][a + 1], col[a][c->L[k].id], emin, X->t);
            mpz_sub(X->row[k][a + 1], X->row[k][a + 1], ci[a]);
            mpz_addmul(X->row[k][0], X->row[k][a + 1], X->row[k][a + 1]);
        }
    }
    if (!X->made)
        for (vbs_u32 k = 0; k <= n; k++)
            for (int a = 0; a < 4; a++)
                X->rd[k][a] = mpz_get_d(X->row[k][a]);
    for (int a = 0; a < 3; a++)
        mpz_clear(ci[a]);
    X->made = X->zmade = 1;
    return 1;
}

/* d * 10^(d.exp10 - emin) in *x (emin <= d.exp10); 0 when it does not
 * fit in 128 bits. */
static int env_scaled(vb_decimal d, int32_t emin, vbq_i128 *x)
{
    *x = d.mant;
    int fits = 1;
    for (int32_t e = emin; e < d.exp10 && fits; e++)
        fits = vbq_cmul(*x, 10, x);
    return fits;
}

/* The rows' doubles rd without GMP where the integers fit in 128 bits:
 * the decimals scaled in checked products, D_j and N_j = |D_j|^2 exact,
 * each converted once (to nearest: within u relative, inside the 2u the
 * filters take). Else the GMP rows give them. 0: no memory. */
static int env_rows_doubles(vbq_env_ctx *c)
{
    vbq_env_rows *X = &c->X;
    vbs_u32 n = c->n;
    const vb_decimal *col[3] = {c->s->ex, c->s->ey, c->s->ez};
    int32_t emin = env_emin(c);
    X->n = n;
    X->rd = malloc((size_t)(n + 1) * sizeof *X->rd);
    if (!X->rd)
        return 0;
    X->ri = malloc((size_t)(n + 1) * sizeof *X->ri);
    if (!X->ri) {
        free(X->rd);
        X->rd = NULL;
        return 0;
    }
    vbq_i128 ci[3];
    int fits = 1;
    for (int a = 0; a < 3 && fits; a++)
        fits = env_scaled(col[a][c->i], emin, &ci[a]);
    for (vbs_u32 k = 0; k < n && fits; k++) {
        vbq_i128 x, N = 0, t;
        for (int a = 0; a < 3 && fits; a++) {
            fits = env_scaled(col[a][c->L[k].id], emin, &x) && vbq_csub(x, ci[a], &x) &&
                   vbq_cmul(x, x, &t) && vbq_cadd(N, t, &N);
            X->ri[k][a + 1] = x;
            X->rd[k][a + 1] = (double)x;
        }
        X->ri[k][0] = N;
        X->rd[k][0] = (double)N;
    }
    if (!fits) {
        free(X->rd);
        free(X->ri);
        X->rd = NULL;
        X->ri = NULL;
        return env_rows_mpz(c);
    }
    X->ri[n][0] = 1;
    X->ri[n][1] = X->ri[n][2] = X->ri[n][3] = 0;
    X->rd[n][0] = 1.0;
    X->rd[n][1] = X->rd[n][2] = X->rd[n][3] = 0.0;
    X->made = X->ifits = 1;
    return 1;
}

static void env_rows_free(vbq_env_rows *X)
{
    if (X->zmade)
        for (vbs_u32 k = 0; k <= X->n; k++)
            for (int a = 0; a < 4; a++)
                mpz_clear(X->row[k][a]);
    free(X->row);
    free(X->rd);
    free(X->ri);
}

/* m2 index of the column pair (a, b), a < b; the pairs; the columns of C_x */
static const int mi[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
static const int pr[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
static const int cols[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

/* The cofactors of env_tri_make in doubles, from the rows' doubles rd
 * (|rd - R| <= 2u |R|: mpz_get_d truncates, env_rows_doubles rounds), without GMP: f_x with
 * |f_x - C_x| <= fe_x. Why: C_x is a sum of six signed products of three
 * row entries; each computed term carries at most five roundings (the
 * product and the difference of m2, the product by row j, two additions:
 * gamma_5 <= 5.01u) and the inputs' errors (1 + 2u)^3 - 1 <= 6.01u, so
 * |f_x - C_x| <= 11.02u P_x (1 + 2u)^3 with P_x the sum of the six terms'
 * magnitudes; P_x is computed from the same doubles with at most five
 * roundings of non-negative terms, and fe_x = 16u P^_x covers all of it.
 * Overflow: coordinates below 2^63 at the common exponent give N below
 * 2^128, C below 2^260 and R0 . C below 2^390, far from the doubles' range;
 * larger rows (exponents far apart) may give infinities, and a non-finite
 * bound (or a NaN) fails the filter: the integers decide. */
void vbq_env_cofactors(const vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l, double f[4],
                       double fe[4])
{
    const double *rk = c->X.rd[k], *rl = c->X.rd[l], *rj = c->X.rd[j];
    double m2[6], a2[6];
    for (int p = 0; p < 6; p++) {
        double x = rk[pr[p][0]] * rl[pr[p][1]], y = rk[pr[p][1]] * rl[pr[p][0]];
        m2[p] = x - y;
        a2[p] = fabs(x) + fabs(y);
    }
    for (int x = 0; x < 4; x++) {
        int a = cols[x][0], b = cols[x][1], d = cols[x][2];
        double v = rj[a] * m2[mi[b][d]] - rj[b] * m2[mi[a][d]] + rj[d] * m2[mi[a][b]];
        double g = fabs(rj[a]) * a2[mi[b][d]] + fabs(rj[b]) * a2[mi[a][d]] +
                   fabs(rj[d]) * a2[mi[a][b]];
        f[x] = x & 1 ? -v : v;
        fe[x] = 16.0 * VBQ_U * g;
    }
}

static void env_tri_fast(vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l)
{
    vbq_env_cofactors(c, j, k, l, c->f, c->fe);
    c->fast_made = 1;
}

/* The cofactors of rows j, k, l along the first row of det4[R0; j; k; l]:
 * C_x = (-1)^x det3(the three rows without column x), each det3 expanded
 * along row j over the 2x2 minors of rows k, l. */
static void env_tri_make(vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l)
{
    mpz_t *rk = c->X.row[k], *rl = c->X.row[l], *rj = c->X.row[j];
    for (int p = 0; p < 6; p++) {
        mpz_mul(c->m2[p], rk[pr[p][0]], rl[pr[p][1]]);
        mpz_submul(c->m2[p], rk[pr[p][1]], rl[pr[p][0]]);
    }
    for (int x = 0; x < 4; x++) {
        int a = cols[x][0], b = cols[x][1], d = cols[x][2];
        mpz_mul(c->C[x], rj[a], c->m2[mi[b][d]]);
        mpz_submul(c->C[x], rj[b], c->m2[mi[a][d]]);
        mpz_addmul(c->C[x], rj[d], c->m2[mi[a][b]]);
        if (x & 1)
            mpz_neg(c->C[x], c->C[x]);
        c->c[x] = mpz_get_d(c->C[x]);
    }
    c->tri_made = 1;
}

/* The scale 2^p that makes a Q row's components integers: a non-zero
 * component is M 2^(ex - 53) with M = f 2^53 an integer (frexp), so p =
 * max(53 - ex) (they are 0, +-1 and +-u0); ex[a] is component a's
 * exponent. */
static int env_q_scale(const double *q, int ex[3])
{
    int p = 0;
    for (int a = 0; a < 3; a++) {
        (void)frexp(q[a], &ex[a]);
        if (q[a] != 0.0 && 53 - ex[a] > p)
            p = 53 - ex[a];
    }
    return p;
}

/* env_tri_make in checked 128-bit integers from the rows ri: 0 when a
 * number does not fit (GMP decides). */
static int env_tri_i128(vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l)
{
    const vbq_i128 *rk = c->X.ri[k], *rl = c->X.ri[l], *rj = c->X.ri[j];
    vbq_i128 m2[6], x, y;
    for (int p = 0; p < 6; p++)
        if (!vbq_cmul(rk[pr[p][0]], rl[pr[p][1]], &x) || !vbq_cmul(rk[pr[p][1]], rl[pr[p][0]], &y) ||
            !vbq_csub(x, y, &m2[p]))
            return 0;
    for (int t = 0; t < 4; t++) {
        int a = cols[t][0], b = cols[t][1], d = cols[t][2];
        vbq_i128 v, w;
        if (!vbq_cmul(rj[a], m2[mi[b][d]], &v) || !vbq_cmul(rj[b], m2[mi[a][d]], &w) ||
            !vbq_csub(v, w, &v) || !vbq_cmul(rj[d], m2[mi[a][b]], &w) || !vbq_cadd(v, w, &v))
            return 0;
        c->ci[t] = t & 1 ? -v : v;
    }
    return 1;
}

/* Row R0 in 128-bit integers: label m's, or 2^p q (env_q_scale); 0 when
 * it does not fit. */
static int env_r0_i128(const vbq_env_ctx *c, const double *q, vbs_u32 m, vbq_i128 r[4])
{
    if (!q) {
        for (int a = 0; a < 4; a++)
            r[a] = c->X.ri[m][a];
        return 1;
    }
    int ex[3], p = env_q_scale(q, ex);
    r[0] = 0;
    for (int a = 0; a < 3; a++) {
        int sh = ex[a] - 53 + p, e;
        r[a + 1] = 0;
        if (q[a] == 0.0)
            continue;
        vbq_i128 M = (int64_t)ldexp(frexp(q[a], &e), 53);
        if (sh > 70 || !vbq_cmul(M, (vbq_i128)1 << sh, &r[a + 1]))
            return 0;
    }
    return 1;
}

/* r . C in checked 128-bit integers. */
static int env_dot_i128(const vbq_i128 r[4], const vbq_i128 C[4], vbq_i128 *out)
{
    vbq_i128 acc = 0, t;
    for (int a = 0; a < 4; a++)
        if (!vbq_cmul(r[a], C[a], &t) || !vbq_cadd(acc, t, &acc))
            return 0;
    *out = acc;
    return 1;
}

int vbq_env_rows_made(vbq_env_ctx *c)
{
    return c->X.made || env_rows_doubles(c);
}

/* Row R0 in doubles: (0, q), or label m's (infinity's for m = n). */
static void env_r0(const vbq_env_ctx *c, const double *q, vbs_u32 m, double r[4])
{
    if (q) {
        r[0] = 0.0;
        for (int a = 0; a < 3; a++)
            r[a + 1] = q[a];
    } else {
        for (int a = 0; a < 4; a++)
            r[a] = c->X.rd[m][a];
    }
}

/* The exact sign of det[X; a_k - a_j; a_l - a_j] with X = a_m - a_j (m a
 * label, or n for infinity: a = 0) when q is NULL, else X = q (exact
 * doubles): -sign(R0 . C) (see the top). First in doubles: the factors are
 * within 2u relative of the integers (mpz_get_d truncates; q is exact, and
 * the positive scale 2^p of its row is left out), the four products and
 * their sum add at most 4.01u, so 16u of the sum of the magnitudes is
 * ample; then in integers. Returns 2 when it cannot be decided (no
 * memory). */
int vbq_env_sign_exact(vbq_env_ctx *c, const double *q, vbs_u32 m, vbs_u32 j, vbs_u32 k, vbs_u32 l)
{
    c->exact_calls++;
    if (!vbq_env_rows_made(c))
        return 2;
    double r[4];
    env_r0(c, q, m, r);
    /* First from the cofactors' doubles (env_tri_fast, vbq_env_sign_rows),
     * then the exact cofactors. */
    if (!c->fast_made)
        env_tri_fast(c, j, k, l);
    int sg = vbq_env_sign_rows(r, c->f, c->fe);
    if (sg)
        return sg;
    if (c->X.ifits) {
        if (!c->tri_i)
            c->tri_i = env_tri_i128(c, j, k, l) ? 1 : -1;
        vbq_i128 r0[4], acc;
        if (c->tri_i == 1 && env_r0_i128(c, q, m, r0) && env_dot_i128(r0, c->ci, &acc))
            return acc > 0 ? -1 : (acc < 0 ? 1 : 0);
    }
    if (!c->X.zmade && !env_rows_mpz(c))
        return 2;
    if (!c->tri_made)
        env_tri_make(c, j, k, l);
    double v = 0.0, g = 0.0;
    for (int a = 0; a < 4; a++) {
        v += r[a] * c->c[a];
        g += fabs(r[a] * c->c[a]);
    }
    double b = 16.0 * VBQ_U * g * (1.0 + 1e-12) + VBQ_TINY;
    if (isfinite(g) && (v > b || v < -b))
        return v > b ? -1 : 1;
    mpz_t *r0;
    if (q) {
        /* 2^p q in integers (env_q_scale) */
        int ex[3], p = env_q_scale(q, ex);
        double f[3];
        for (int a = 0; a < 3; a++)
            f[a] = frexp(q[a], &ex[a]);
        for (int a = 0; a < 3; a++) {
            mpz_set_d(c->X.q[a + 1], ldexp(f[a], 53));
            if (q[a] != 0.0)
                mpz_mul_2exp(c->X.q[a + 1], c->X.q[a + 1], (mp_bitcnt_t)(ex[a] - 53 + p));
        }
        mpz_set_ui(c->X.q[0], 0);
        r0 = c->X.q;
    } else {
        r0 = c->X.row[m];
    }
    mpz_mul(c->acc, r0[0], c->C[0]);
    for (int a = 1; a < 4; a++)
        mpz_addmul(c->acc, r0[a], c->C[a]);
    return -mpz_sgn(c->acc);
}


void vbq_env_ctx_free(vbq_env_ctx *c)
{
    env_rows_free(&c->X);
    if (c->zinit)
        env_ctx_each(c, mpz_clear);
}
