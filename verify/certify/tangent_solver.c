/* The tangent-sphere system, solved exactly.
 *
 * With q = p - c_base and s = t + R_base, sphere i's equation
 * |p - c_i|^2 = (t + R_i)^2 minus the base's |q|^2 = s^2 is linear:
 *     d_i . q + r_i s = W_i / 2,  d_i = c_i - c_base, r_i = R_i - R_base,
 *     W_i = |d_i|^2 - r_i^2.
 * Three independent rows leave a line u = (U + mu v) / (2 D_k) in
 * u = (q, s) space: v is the generalised cross product of the rows (its k-th
 * entry is +-D_k, the minor without column k, non-zero by the choice of k)
 * and U solves the rows with u_k = 0 (Cramer). On the cone Q(u) = |q|^2 - s^2
 * = 0 this is A mu^2 + 2 B mu + C = 0 with A = Q(v), B = Q(U, v), C = Q(U):
 * integers, so each root lies in Q(sqrt(B^2 - AC)). */
#include "vbx_exact.h"

void vbx_solver_init(vbx_solver *s, const vbx_data *d)
{
    s->d = d;
    s->slow_rounds = 0;
    s->status = VBX_SINGULAR;
    s->nroots = 0;
    s->k = -1;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 5; j++)
            mpz_init(s->m[i][j]);
    mpz_inits(s->delta, s->A, s->B, s->C, s->Dk, (mpz_ptr)0);
    for (int j = 0; j < 4; j++) {
        mpz_init(s->U[j]);
        mpz_init(s->v[j]);
    }
    for (int r = 0; r < 2; r++) {
        for (int j = 0; j < 4; j++) {
            mpz_init(s->root[r].a[j]);
            mpz_init(s->root[r].b[j]);
        }
        mpz_init(s->root[r].den);
        s->root[r].sigma = 0;
    }
    for (int j = 0; j < 6; j++)
        mpz_init(s->t[j]);
    for (int j = 0; j < 10; j++)
        mpz_init(s->minor[j]);
    for (int j = 0; j < 5; j++)
        mpz_init(s->row[j]);
}

void vbx_solver_free(vbx_solver *s)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 5; j++)
            mpz_clear(s->m[i][j]);
    mpz_clears(s->delta, s->A, s->B, s->C, s->Dk, (mpz_ptr)0);
    for (int j = 0; j < 4; j++) {
        mpz_clear(s->U[j]);
        mpz_clear(s->v[j]);
    }
    for (int r = 0; r < 2; r++) {
        for (int j = 0; j < 4; j++) {
            mpz_clear(s->root[r].a[j]);
            mpz_clear(s->root[r].b[j]);
        }
        mpz_clear(s->root[r].den);
    }
    for (int j = 0; j < 6; j++)
        mpz_clear(s->t[j]);
    for (int j = 0; j < 10; j++)
        mpz_clear(s->minor[j]);
    for (int j = 0; j < 5; j++)
        mpz_clear(s->row[j]);
}

void vbx_row(const vbx_data *d, uint32_t base, uint32_t j, mpz_t out[5], mpz_t tmp)
{
    const mpz_t *cb = &d->c[4 * (size_t)base], *cj = &d->c[4 * (size_t)j];
    for (int k = 0; k < 4; k++)
        mpz_sub(out[k], cj[k], cb[k]);
    mpz_mul(out[4], out[0], out[0]);
    mpz_addmul(out[4], out[1], out[1]);
    mpz_addmul(out[4], out[2], out[2]);
    mpz_mul(tmp, out[3], out[3]);
    mpz_sub(out[4], out[4], tmp);
}

/* 3x3 determinant of columns c0, c1, c2 of the rows m (out must not alias). */
static void det3(mpz_t out, mpz_t (*m)[5], int c0, int c1, int c2, mpz_t t)
{
    /* Expansion along the first row. */
    mpz_mul(t, m[1][c1], m[2][c2]);
    mpz_submul(t, m[1][c2], m[2][c1]);
    mpz_mul(out, m[0][c0], t);
    mpz_mul(t, m[1][c0], m[2][c2]);
    mpz_submul(t, m[1][c2], m[2][c0]);
    mpz_submul(out, m[0][c1], t);
    mpz_mul(t, m[1][c0], m[2][c1]);
    mpz_submul(t, m[1][c1], m[2][c0]);
    mpz_addmul(out, m[0][c2], t);
}

/* Lorentz form Q(x, y) = x0 y0 + x1 y1 + x2 y2 - x3 y3. */
static void lorentz(mpz_t out, mpz_t *x, mpz_t *y)
{
    mpz_mul(out, x[0], y[0]);
    mpz_addmul(out, x[1], y[1]);
    mpz_addmul(out, x[2], y[2]);
    mpz_submul(out, x[3], y[3]);
}

/* Is some 2x2 (rank 1) or 3x3 (rank 2) minor of rows 0..rank of s->m over
 * the first ncols columns non-zero? */
static int extends_rank(vbx_solver *s, int rank, int ncols)
{
    mpz_t *t1 = &s->t[0], *t2 = &s->t[1], *t3 = &s->t[2];
    if (rank == 0) {
        for (int a = 0; a < ncols; a++)
            if (mpz_sgn(s->m[0][a]))
                return 1;
        return 0;
    }
    for (int a = 0; a < ncols; a++)
        for (int b = a + 1; b < ncols; b++) {
            if (rank == 1) {
                mpz_mul(*t1, s->m[0][a], s->m[1][b]);
                mpz_submul(*t1, s->m[0][b], s->m[1][a]);
                if (mpz_sgn(*t1))
                    return 1;
                continue;
            }
            for (int c = b + 1; c < ncols; c++) {
                det3(*t2, s->m, a, b, c, *t3);
                if (mpz_sgn(*t2))
                    return 1;
            }
        }
    return 0;
}

/* The row of j relative to base over the enclosures of the input decimals.
 * In input units, not scaled: the scaled row is the exact row with columns
 * 0..3 times 10^E and column 4 times 10^2E, positive factors that change no
 * minor's sign, so a minor proven non-zero here is non-zero exactly. */
static void row_ia(const vbx_data *d, uint32_t base, uint32_t j, vbx_ia out[5])
{
    const vbx_ia *cb = &d->box[4 * (size_t)base], *cj = &d->box[4 * (size_t)j];
    for (int k = 0; k < 4; k++)
        out[k] = vbx_ia_sub(cj[k], cb[k]);
    vbx_ia w = vbx_ia_add(vbx_ia_sqr(out[0]), vbx_ia_sqr(out[1]));
    w = vbx_ia_add(w, vbx_ia_sqr(out[2]));
    out[4] = vbx_ia_sub(w, vbx_ia_sqr(out[3]));
}

static vbx_ia det2_ia(const vbx_ia m[3][5], int r0, int r1, int a, int b)
{
    return vbx_ia_sub(vbx_ia_mul(m[r0][a], m[r1][b]), vbx_ia_mul(m[r0][b], m[r1][a]));
}

/* extends_rank, filtered: 1 when some minor is proven non-zero, 0 when the
 * enclosures cannot tell (the exact test decides then). */
static int extends_rank_ia(const vbx_ia m[3][5], int rank, int ncols)
{
    for (int a = 0; a < ncols; a++) {
        if (rank == 0) {
            if (vbx_ia_sign(m[0][a]))
                return 1;
            continue;
        }
        for (int b = a + 1; b < ncols; b++) {
            if (rank == 1) {
                if (vbx_ia_sign(det2_ia(m, 0, 1, a, b)))
                    return 1;
                continue;
            }
            for (int c = b + 1; c < ncols; c++) {
                vbx_ia d = vbx_ia_mul(m[0][a], det2_ia(m, 1, 2, b, c));
                d = vbx_ia_sub(d, vbx_ia_mul(m[0][b], det2_ia(m, 1, 2, a, c)));
                d = vbx_ia_add(d, vbx_ia_mul(m[0][c], det2_ia(m, 1, 2, a, b)));
                if (vbx_ia_sign(d))
                    return 1;
            }
        }
    }
    return 0;
}

int vbx_pick_rows(vbx_solver *s, uint32_t base, const uint32_t *cand, size_t n, int ncols,
                  uint32_t rows[3])
{
    int rank = 0;
    vbx_ia m[3][5];
    for (size_t i = 0; i < n && rank < 3; i++) {
        row_ia(s->d, base, cand[i], m[rank]);
        if (!extends_rank_ia((const vbx_ia(*)[5])m, rank, ncols)) {
            /* Exact rows for the rows kept so far and this one. */
            for (int r = 0; r < rank; r++)
                vbx_row(s->d, base, rows[r], s->m[r], s->t[0]);
            vbx_row(s->d, base, cand[i], s->m[rank], s->t[0]);
            if (!extends_rank(s, rank, ncols))
                continue;
        }
        rows[rank++] = cand[i];
    }
    return rank;
}

/* Index of the minor of rows 1, 2 on columns a < b in s->minor. */
static int minor_index(int a, int b)
{
    static const int first[5] = {0, 4, 7, 9, 10}; /* minors starting at column a */
    return first[a] + (b - a - 1);
}

/* out += sign * m0[c] * (minor of rows 1, 2 on columns a, b in that order). */
static void det3_term(vbx_solver *s, mpz_t out, int sign, int c, int a, int b)
{
    if (a > b) {
        int t = a;
        a = b;
        b = t;
        sign = -sign;
    }
    if (sign > 0)
        mpz_addmul(out, s->m[0][c], s->minor[minor_index(a, b)]);
    else
        mpz_submul(out, s->m[0][c], s->minor[minor_index(a, b)]);
}

/* det3 of columns c0, c1, c2 (any order, distinct) from s->minor. */
static void det3_minors(vbx_solver *s, mpz_t out, int c0, int c1, int c2)
{
    mpz_set_ui(out, 0);
    det3_term(s, out, 1, c0, c1, c2);
    det3_term(s, out, -1, c1, c0, c2);
    det3_term(s, out, 1, c2, c0, c1);
}

/* Fills root r from numerators and denominator, making den > 0. */
static void set_root(vbx_root *r, int sigma, mpz_t den)
{
    r->sigma = sigma;
    mpz_set(r->den, den);
    if (mpz_sgn(r->den) < 0) {
        mpz_neg(r->den, r->den);
        for (int j = 0; j < 4; j++) {
            mpz_neg(r->a[j], r->a[j]);
            mpz_neg(r->b[j], r->b[j]);
        }
    }
}

int vbx_solve(vbx_solver *s, uint32_t base, const uint32_t rows[3])
{
    mpz_t *t0 = &s->t[0], *t1 = &s->t[1], *t2 = &s->t[2];
    s->base = base;
    s->nroots = 0;
    for (int i = 0; i < 3; i++) {
        s->rows[i] = rows[i];
        vbx_row(s->d, base, rows[i], s->m[i], *t0);
    }
    static const int cols[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    /* Every determinant below expands along row 0 over the 2x2 minors of
     * rows 1 and 2: ten minors computed once instead of three per det. */
    for (int a = 0, i = 0; a < 5; a++)
        for (int b = a + 1; b < 5; b++, i++) {
            mpz_mul(s->minor[i], s->m[1][a], s->m[2][b]);
            mpz_submul(s->minor[i], s->m[1][b], s->m[2][a]);
        }
    /* Kernel vector v_k = (-1)^k D_k. */
    for (int k = 0; k < 4; k++) {
        det3_minors(s, s->v[k], cols[k][0], cols[k][1], cols[k][2]);
        if (k & 1)
            mpz_neg(s->v[k], s->v[k]);
    }
    /* Free unknown: prefer s (k = 3, solving for the point given the radius);
     * otherwise the first coordinate whose minor is non-zero. */
    s->k = -1;
    if (mpz_sgn(s->v[3]))
        s->k = 3;
    else
        for (int k = 0; k < 3 && s->k < 0; k++)
            if (mpz_sgn(s->v[k]))
                s->k = k;
    if (s->k < 0)
        return s->status = VBX_SINGULAR;
    const int k = s->k;
    /* D_k is the minor v_k came from: v_k = (-1)^k D_k. */
    if (k & 1)
        mpz_neg(s->Dk, s->v[k]);
    else
        mpz_set(s->Dk, s->v[k]);
    /* Cramer with u_k = 0: U_j = det of the minor with column j <- W. */
    mpz_set_ui(s->U[k], 0);
    for (int c = 0; c < 3; c++) {
        int cc[3] = {cols[k][0], cols[k][1], cols[k][2]};
        int j = cc[c];
        cc[c] = 4;
        det3_minors(s, s->U[j], cc[0], cc[1], cc[2]);
    }
    lorentz(s->A, s->v, s->v);
    lorentz(s->B, s->U, s->v);
    lorentz(s->C, s->U, s->U);
    mpz_mul(s->delta, s->B, s->B);
    mpz_submul(s->delta, s->A, s->C);
    s->status = VBX_SOLVED;
    if (mpz_sgn(s->A) != 0) {
        int sd = mpz_sgn(s->delta);
        if (sd < 0)
            return s->status;
        /* u = (A U - B v + sigma v sqrt(delta)) / (2 D_k A) */
        mpz_mul(*t1, s->Dk, s->A);
        mpz_mul_2exp(*t1, *t1, 1);
        int nr = sd > 0 ? 2 : 1;
        for (int r = 0; r < nr; r++) {
            vbx_root *R = &s->root[r];
            int sigma = sd > 0 ? (r == 0 ? 1 : -1) : 0;
            for (int j = 0; j < 4; j++) {
                mpz_mul(R->a[j], s->A, s->U[j]);
                mpz_submul(R->a[j], s->B, s->v[j]);
                if (sigma > 0)
                    mpz_set(R->b[j], s->v[j]);
                else if (sigma < 0)
                    mpz_neg(R->b[j], s->v[j]);
                else
                    mpz_set_ui(R->b[j], 0);
            }
            set_root(R, sigma, *t1);
        }
        s->nroots = nr;
        return s->status;
    }
    if (mpz_sgn(s->B) == 0) {
        if (mpz_sgn(s->C) == 0)
            s->status = VBX_UNDETERMINED;
        return s->status;
    }
    /* Linear case: mu = -C / (2B), u = (2B U - C v) / (4 B D_k). */
    vbx_root *R = &s->root[0];
    mpz_mul_2exp(*t2, s->B, 1);
    for (int j = 0; j < 4; j++) {
        mpz_mul(R->a[j], *t2, s->U[j]);
        mpz_submul(R->a[j], s->C, s->v[j]);
        mpz_set_ui(R->b[j], 0);
    }
    mpz_mul(*t1, s->B, s->Dk);
    mpz_mul_2exp(*t1, *t1, 2);
    set_root(R, 0, *t1);
    s->nroots = 1;
    mpz_set_ui(s->delta, 0);
    return s->status;
}

int vbx_sign_tangent(vbx_solver *s, const vbx_root *r, uint32_t j)
{
    /* s + r_j = (a_s + r_j den + b_s sqrt(delta)) / den, den > 0. */
    mpz_t *t0 = &s->t[3];
    mpz_sub(*t0, s->d->c[4 * (size_t)j + 3], s->d->c[4 * (size_t)s->base + 3]);
    mpz_mul(*t0, *t0, r->den);
    mpz_add(*t0, *t0, r->a[3]);
    return vbx_sign_qsqrt(*t0, r->b[3], s->delta, s->t[4], s->t[5]);
}

int vbx_sign_power(vbx_solver *s, const vbx_root *r, uint32_t j)
{
    /* On the cone |q|^2 = s^2, so |q - d_j|^2 - (s + r_j)^2
     *   = W_j - 2 (d_j . q + r_j s): linear in u. Times den > 0:
     *   (W_j den - 2 m_j . a) - 2 (m_j . b) sqrt(delta). */
    mpz_t *row = s->row;
    mpz_t *x = &s->t[0], *y = &s->t[1];
    vbx_row(s->d, s->base, j, row, *x);
    mpz_mul(*x, row[4], r->den);
    mpz_set_ui(*y, 0);
    for (int k = 0; k < 4; k++) {
        mpz_submul(*x, row[k], r->a[k]);
        mpz_submul(*x, row[k], r->a[k]);
        mpz_submul(*y, row[k], r->b[k]);
        mpz_submul(*y, row[k], r->b[k]);
    }
    return vbx_sign_qsqrt(*x, *y, s->delta, s->t[4], s->t[5]);
}

int vbx_sign_distance(vbx_solver *s, const vbx_root *r, uint32_t j)
{
    /* |p - c_j| - (t + R_j): positive when t + R_j < 0; otherwise it has the
     * sign of the difference of squares (both sides are >= 0). */
    if (vbx_sign_tangent(s, r, j) < 0)
        return 1;
    return vbx_sign_power(s, r, j);
}

int vbx_sigma_in(vbx_solver *canon, vbx_solver *ours, const vbx_root *r)
{
    if (canon->nroots < 2)
        return 0;
    /* Our point's k-th coordinate in canon's frame, u'_k = u_k + off, gives
     * canon's parameter mu = 2 D_k u'_k / v_k = 2 (-1)^k u'_k, and the root
     * with +sqrt(delta) is the one with A mu + B > 0. Times den > 0:
     * 2(-1)^k A (a_k + off den) + B den + 2(-1)^k A b_k sqrt(delta_ours). */
    const int k = canon->k;
    const vbx_data *d = canon->d;
    mpz_t *off = &ours->t[0], *x = &ours->t[1], *y = &ours->t[2];
    if (k < 3)
        mpz_sub(*off, d->c[4 * (size_t)ours->base + k], d->c[4 * (size_t)canon->base + k]);
    else
        mpz_sub(*off, d->c[4 * (size_t)canon->base + 3], d->c[4 * (size_t)ours->base + 3]);
    mpz_mul(*x, *off, r->den);
    mpz_add(*x, *x, r->a[k]);
    mpz_mul(*x, *x, canon->A);
    mpz_mul_2exp(*x, *x, 1);
    mpz_mul(*y, r->b[k], canon->A);
    mpz_mul_2exp(*y, *y, 1);
    if (k & 1) {
        mpz_neg(*x, *x);
        mpz_neg(*y, *y);
    }
    mpz_addmul(*x, canon->B, r->den);
    return vbx_sign_qsqrt(*x, *y, ours->delta, ours->t[4], ours->t[5]);
}

int vbx_root_coords(vbx_solver *s, const vbx_root *r, double out[4], vbx_ia box[4])
{
    const vbx_data *d = s->d;
    /* t[0..3] are free scratch between the solver's calls. */
    mpz_t *num = &s->t[0], *den = &s->t[1];
    mpz_mul(*den, r->den, d->scale);
    vbx_round_common common;
    vbx_round_prepare(&common, s->delta, *den, s->t[2], s->t[3]);
    int rc = VB_OK;
    for (int k = 0; k < 4 && rc == VB_OK; k++) {
        /* x = X_base + q_x; t = s - R_base. */
        mpz_mul(*num, d->c[4 * (size_t)s->base + k], r->den);
        if (k < 3)
            mpz_add(*num, *num, r->a[k]);
        else
            mpz_sub(*num, r->a[k], *num);
        if (vbx_round_with(&common, *num, r->b[k], &out[k], &box[k].lo, &box[k].hi))
            continue;
        s->slow_rounds++;
        rc = vbx_round_mpfr(*num, r->b[k], s->delta, *den, &out[k], &box[k].lo, &box[k].hi);
    }
    return rc;
}
