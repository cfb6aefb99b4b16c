/* The two exact decisions of the quadruple filter that double-double
 * cannot make (see vbx_quad.h): a line of rank < 3, and delta = 0.
 *
 * Both arise on exact crystals and cospherical input, where the exact value
 * is 0 and no enclosure, however narrow, excludes 0. Both are decided here
 * exactly, without the exact solve: the rank in fixed-width integers, the
 * sign of delta in GMP integers from the line's exact 128-bit v and U. */
#include <gmp.h>

#include "vbx_quad.h"

/* A signed 192-bit integer h 2^64 + l, 0 <= l < 2^64: wide enough for a
 * 3x3 minor of entries below 2^62 (three products below 2^62 * 2^125). */
typedef struct wide {
    vbx_i128 h;
    uint64_t l;
} wide;

/* w += x M for |x| < 2^62, |M| < 2^125: with M = Mh 2^64 + Ml (Mh the
 * arithmetic shift, |Mh| < 2^61; 0 <= Ml < 2^64), x Mh < 2^123 and
 * x Ml < 2^126 are exact in 128 bits; the low sum l + x Ml < 2^127 too,
 * and its high part carries into h, which stays below 2^125 for three
 * terms. */
static void wide_addmul(wide *w, int64_t x, vbx_i128 M)
{
    int64_t mh = (int64_t)(M >> 64);
    uint64_t ml = (uint64_t)M;
    vbx_i128 lo = (vbx_i128)w->l + (vbx_i128)x * (vbx_i128)ml;
    w->h += (vbx_i128)x * mh + (lo >> 64);
    w->l = (uint64_t)lo;
}

/* The 3x3 minor of m's columns c0 < c1 < c2 is exactly 0? Expanded along
 * row 0 over the 2x2 minors of rows 1, 2 (|M| < 2 * 2^124). */
static int minor_zero(const int64_t m[3][4], int c0, int c1, int c2)
{
    const int c[3] = {c0, c1, c2};
    wide w = {0, 0};
    for (int i = 0; i < 3; i++) {
        int a = c[(i + 1) % 3], b = c[(i + 2) % 3];
        /* The cofactor of m[0][c[i]]: the cyclic order keeps its sign. */
        vbx_i128 M = (vbx_i128)m[1][a] * m[2][b] - (vbx_i128)m[1][b] * m[2][a];
        wide_addmul(&w, m[0][c[i]], M);
    }
    return w.h == 0 && w.l == 0;
}

int vbx_qf_rank_low(const int64_t m[3][4])
{
    return minor_zero(m, 0, 1, 2) && minor_zero(m, 1, 2, 3) && minor_zero(m, 0, 2, 3) &&
           minor_zero(m, 0, 1, 3);
}

/* out = x (any 128-bit value; unsigned long holds 64 bits on the targets,
 * checked below). */
static void mpz_of_i128(mpz_t out, vbx_i128 x)
{
    unsigned __int128 u = x < 0 ? -(unsigned __int128)x : (unsigned __int128)x;
    mpz_set_ui(out, (unsigned long)(uint64_t)(u >> 64));
    mpz_mul_2exp(out, out, 64);
    mpz_add_ui(out, out, (unsigned long)(uint64_t)u);
    if (x < 0)
        mpz_neg(out, out);
}

_Static_assert(sizeof(unsigned long) == 8, "mpz_of_i128 needs a 64-bit unsigned long");

int vbx_qf_delta_sign(const vbx_qline *L)
{
    mpz_t v[4], U[3], A, B, C;
    for (int k = 0; k < 4; k++) {
        mpz_init(v[k]);
        mpz_of_i128(v[k], L->vi[k]);
    }
    for (int k = 0; k < 3; k++) {
        mpz_init(U[k]);
        mpz_of_i128(U[k], L->Ui[k]);
    }
    mpz_inits(A, B, C, (mpz_ptr)0);
    /* The Lorentz forms of tangent_solver.c with U_3 = 0. */
    mpz_mul(A, v[0], v[0]);
    mpz_addmul(A, v[1], v[1]);
    mpz_addmul(A, v[2], v[2]);
    mpz_submul(A, v[3], v[3]);
    mpz_mul(B, U[0], v[0]);
    mpz_addmul(B, U[1], v[1]);
    mpz_addmul(B, U[2], v[2]);
    mpz_mul(C, U[0], U[0]);
    mpz_addmul(C, U[1], U[1]);
    mpz_addmul(C, U[2], U[2]);
    mpz_mul(B, B, B);
    mpz_submul(B, A, C);
    int sg = mpz_sgn(B);
    mpz_clears(A, B, C, (mpz_ptr)0);
    for (int k = 0; k < 4; k++)
        mpz_clear(v[k]);
    for (int k = 0; k < 3; k++)
        mpz_clear(U[k]);
    return sg;
}
