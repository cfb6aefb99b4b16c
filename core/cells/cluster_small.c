/* The tie cluster's rank test (vbq_cluster.h) in 128-bit integers, without
 * GMP: the exact crystals' clusters have decimals of a few digits, and the
 * GMP elimination (with a power of ten per decimal and a gcd per step) was
 * 13 % of the 10,976-ball fcc crystal's CPU time.
 *
 * Exactness: every product, sum and difference is formed with the
 * compiler's overflow-checked builtins, so each number below is the exact
 * integer or the test gives up (returns 0) and GMP answers instead. No
 * bound is assumed; a bound only says when the fast path applies: with
 * the scaled coordinates below 2^17 (fcc 10,976 at 10^-3) a vector's
 * entries are below 2^36, the 3x3 minors below 2^73 and the last test's
 * dot products below 2^112.
 *
 * The test. Let b_0, b_1, b_2 be the first independent vectors found (the
 * basis so far) and v the next. With no basis v is independent iff v != 0
 * (always: N > 0). Against b_0: iff a 2x2 minor of [b_0; v] is non-zero.
 * Against b_0, b_1: iff a 3x3 minor of [b_0; b_1; v] is non-zero (each
 * expanded along v's row with the 2x2 minors of b_0, b_1, kept). Against
 * three: the row space of B = [b_0; b_1; b_2] is the orthogonal complement
 * of B's null space, which n_1, n_2 below span, so v is independent iff
 * v . n_1 or v . n_2 is non-zero. n_g (g a column) is the generalised cross
 * product X(b_0, b_1, b_2, e_g): X_k = det[b_0; b_1; b_2; e_g; e_k], so
 * X . w = det[B; e_g; w] = 0 for w a row of B or e_g. Its entries are
 * signed 3x3 minors of B: moving columns r_0 < r_1 < r_2 (the three other
 * than g, k) to the front leaves a block triangular matrix, so X_k =
 * (-1)^inv(r_0, r_1, r_2, g, k) minor(B; r_0, r_1, r_2). With (r_0, r_1, r_2)
 * a triple of non-zero minor M and f_1, f_2 the other columns,
 * n_1 = X(.., e_{f_2}) has entry f_1 = +-M and entry f_2 = 0, n_2 =
 * X(.., e_{f_1}) the reverse: independent, so they span the null space
 * (dimension 5 - 3). */
#include <stdint.h>

#include "vbq_cluster.h"

/* *r = a x - b y + c z, exactly; 0 on overflow. */
static int comb3(vbq_i128 a, vbq_i128 x, vbq_i128 b, vbq_i128 y, vbq_i128 c, vbq_i128 z, vbq_i128 *r)
{
    vbq_i128 p, q, s;
    return vbq_cmul(a, x, &p) && vbq_cmul(b, y, &q) && vbq_cmul(c, z, &s) && vbq_csub(p, q, &p) && vbq_cadd(p, s, r);
}

/* d * 10^(d.exp10 - emin) as an int64; 0 when it does not fit. */
static int scaled(vb_decimal d, int32_t emin, int64_t *out)
{
    static const int64_t p10[19] = {1,
                                    10,
                                    100,
                                    1000,
                                    10000,
                                    100000,
                                    1000000,
                                    10000000,
                                    100000000,
                                    1000000000,
                                    10000000000,
                                    100000000000,
                                    1000000000000,
                                    10000000000000,
                                    100000000000000,
                                    1000000000000000,
                                    10000000000000000,
                                    100000000000000000,
                                    1000000000000000000};
    int64_t k = (int64_t)d.exp10 - emin;
    if (k < 0 || k > 18)
        return 0;
    return !__builtin_mul_overflow(d.mant, p10[k], out);
}

/* The decimals of sphere j scaled: x, y, z, r. */
int vbq_cluster_scaled4(const vb_sphere_set *s, uint32_t j, int32_t emin, int64_t o[4])
{
    return scaled(s->ex[j], emin, o) && scaled(s->ey[j], emin, o + 1) &&
           scaled(s->ez[j], emin, o + 2) && scaled(s->er[j], emin, o + 3);
}

int vbq_cluster_vector(const vb_sphere_set *s, uint32_t j, int32_t emin, const int64_t ci[4],
                       vbq_i128 v[5])
{
    int64_t cj[4];
    if (!vbq_cluster_scaled4(s, j, emin, cj))
        return 0;
    for (int a = 0; a < 4; a++)
        v[a] = (vbq_i128)cj[a] - (vbq_i128)ci[a]; /* |.| < 2^64: no overflow */
    vbq_i128 sq, n = 0;
    for (int a = 0; a < 4; a++) {
        if (!vbq_cmul(v[a], v[a], &sq))
            return 0;
        if (!(a < 3 ? vbq_cadd(n, sq, &n) : vbq_csub(n, sq, &n)))
            return 0;
    }
    v[4] = n;
    return 1;
}

/* The parity of the inversions of the five distinct columns c. */
static int odd5(const int c[5])
{
    int inv = 0;
    for (int a = 0; a < 5; a++)
        for (int b = a + 1; b < 5; b++)
            inv += c[a] > c[b];
    return inv & 1;
}

/* The basis so far and what the next test needs of it. */
typedef struct basis {
    vbq_i128 b[3][5];
    vbq_i128 m2[5][5];  /* 2x2 minors of b_0, b_1 on columns (a, c), a < c */
    vbq_i128 n[2][5];   /* the null space of three rows */
    int nb;
} basis;

/* The 3x3 minor of [b_0; b_1; w] on columns a < c < d. */
static int minor3(const basis *B, const vbq_i128 w[5], int a, int c, int d, vbq_i128 *r)
{
    return comb3(w[a], B->m2[c][d], w[c], B->m2[a][d], w[d], B->m2[a][c], r);
}

/* Is v independent of the basis? 1 / 0 in *ind; returns 0 on overflow. */
static int independent(const basis *B, const vbq_i128 v[5], int *ind)
{
    vbq_i128 r, p, q;
    *ind = 0;
    if (B->nb == 0) {
        for (int a = 0; a < 5; a++)
            *ind |= v[a] != 0;
        return 1;
    }
    if (B->nb == 1) {
        for (int a = 0; a < 5; a++)
            for (int c = a + 1; c < 5; c++) {
                if (!vbq_cmul(v[a], B->b[0][c], &p) || !vbq_cmul(v[c], B->b[0][a], &q) || !vbq_csub(p, q, &r))
                    return 0;
                if (r != 0) {
                    *ind = 1;
                    return 1;
                }
            }
        return 1;
    }
    if (B->nb == 2) {
        for (int a = 0; a < 5; a++)
            for (int c = a + 1; c < 5; c++)
                for (int d = c + 1; d < 5; d++) {
                    if (!minor3(B, v, a, c, d, &r))
                        return 0;
                    if (r != 0) {
                        *ind = 1;
                        return 1;
                    }
                }
        return 1;
    }
    for (int g = 0; g < 2; g++) {
        r = 0;
        for (int a = 0; a < 5; a++)
            if (!vbq_cmul(v[a], B->n[g][a], &p) || !vbq_cadd(r, p, &r))
                return 0;
        if (r != 0) {
            *ind = 1;
            return 1;
        }
    }
    return 1;
}

/* X(b_0, b_1, b_2, e_g) into x (see the head of this file). */
static int cross(const basis *B, int g, vbq_i128 x[5])
{
    for (int k = 0; k < 5; k++) {
        x[k] = 0;
        if (k == g)
            continue;
        int c[5], m = 0;
        for (int a = 0; a < 5; a++)
            if (a != g && a != k)
                c[m++] = a;
        c[3] = g;
        c[4] = k;
        vbq_i128 r;
        if (!minor3(B, B->b[2], c[0], c[1], c[2], &r))
            return 0;
        x[k] = odd5(c) ? -r : r;
    }
    return 1;
}

/* Appends the independent v; returns 0 on overflow. */
static int append(basis *B, const vbq_i128 v[5])
{
    for (int a = 0; a < 5; a++)
        B->b[B->nb][a] = v[a];
    B->nb++;
    if (B->nb == 2) {
        for (int a = 0; a < 5; a++)
            for (int c = a + 1; c < 5; c++) {
                vbq_i128 p, q;
                if (!vbq_cmul(B->b[0][a], B->b[1][c], &p) || !vbq_cmul(B->b[0][c], B->b[1][a], &q) ||
                    !vbq_csub(p, q, &B->m2[a][c]))
                    return 0;
            }
    }
    if (B->nb == 3) {
        /* a triple of columns with a non-zero minor (one exists: the rows
         * are independent); the other two columns name n_1, n_2 */
        for (int a = 0; a < 5; a++)
            for (int c = a + 1; c < 5; c++)
                for (int d = c + 1; d < 5; d++) {
                    vbq_i128 r;
                    if (!minor3(B, B->b[2], a, c, d, &r))
                        return 0;
                    if (r == 0)
                        continue;
                    int f[2], m = 0;
                    for (int e = 0; e < 5; e++)
                        if (e != a && e != c && e != d)
                            f[m++] = e;
                    return cross(B, f[1], B->n[0]) && cross(B, f[0], B->n[1]);
                }
        return 0; /* not reached: b_2 was independent */
    }
    return 1;
}

int vbq_cluster_small(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                      int32_t emin, vbq_cluster_ans *ans)
{
    int64_t ci[4];
    if (!vbq_cluster_scaled4(s, i, emin, ci))
        return 0;
    basis B;
    B.nb = 0;
    ans->decided = 1;
    for (uint32_t k = 0; k < n; k++) {
        vbq_i128 v[5];
        if (!vbq_cluster_vector(s, ids[k], emin, ci, v))
            return 0;
        /* N_j <= 0: j touches i from inside, f_j is not an affine function */
        if (v[4] <= 0) {
            ans->decided = 0;
            break;
        }
        int ind;
        if (!independent(&B, v, &ind))
            return 0;
        if (!ind)
            continue;
        if (B.nb == 3) {
            ans->decided = 0; /* affine rank >= 3 */
            break;
        }
        ans->id[B.nb] = ids[k];
        if (!append(&B, v))
            return 0;
    }
    ans->nbasis = B.nb;
    return 1;
}
