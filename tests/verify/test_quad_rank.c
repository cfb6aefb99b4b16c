/* The exact decisions of the quadruple filter (verify/exact/quad_rank.c):
 * the rank test of wide rows, whose 3x3 minors need 192 bits, on values
 * whose only non-zero part lies in one limb (2^64: a carry; 2^128: past
 * 128 bits; 1 under entries of 2^60) and on dependent rows near 2^61; and
 * the sign of delta on lines made so that double-double cannot tell it
 * (delta = +1 under magnitudes of 2^200), where vbx_qf_prep must not
 * answer "one root", and a line with delta exactly 0, whose one root it
 * must place at mu = -B / A. */
#include "vb_test.h"
#include "vbx_quad.h"

static void test_rank(void)
{
    const int64_t P30 = (int64_t)1 << 30, P32 = (int64_t)1 << 32, P61 = (int64_t)1 << 61;
    /* det (0, 1, 2) = 2^64: the low limb 0, the high one 1. */
    const int64_t carry[3][4] = {{P32, 0, 0, 0}, {0, P32, 0, 0}, {0, 0, 1, 0}};
    CHECK_INT(vbx_qf_rank_low(carry), 0);
    /* det (0, 1, 2) = 2^128 (2^61 2^61 2^6): 0 modulo 2^128. */
    const int64_t over[3][4] = {{P61, 0, 0, 0}, {0, P61, 0, 0}, {0, 0, 64, 0}};
    CHECK_INT(vbx_qf_rank_low(over), 0);
    /* Row 2 = row 0 + row 1 with entries near 2^60: every minor 0, though
     * its products pass 2^180. */
    int64_t dep[3][4] = {{P61 / 2 - 3, -(P61 / 2) + 7, 123456789, P61 / 4 + 11},
                         {P61 / 2 - 1001, P61 / 3, -(P61 / 2) + 5, -(P61 / 4) - 9}};
    for (int k = 0; k < 4; k++)
        dep[2][k] = dep[0][k] + dep[1][k];
    CHECK_INT(vbx_qf_rank_low((const int64_t(*)[4])dep), 1);
    /* One unit off in the radius column: only the minors with column 3
     * change, by a 2x2 minor of rows 0, 1 (non-zero). */
    dep[2][3] += 1;
    CHECK_INT(vbx_qf_rank_low((const int64_t(*)[4])dep), 0);
    /* Coplanar centres of unequal radii (rank 3 through the radius column),
     * and of equal ones (rank 2): only the second is flat. */
    const int64_t copl[3][4] = {{2 * P30, 0, 0, 0}, {0, 2 * P30, 0, 0}, {2 * P30, 2 * P30, 0, 1}};
    CHECK_INT(vbx_qf_rank_low(copl), 0);
    const int64_t square[3][4] = {{2 * P30, 0, 0, 0}, {0, 2 * P30, 0, 0}, {2 * P30, 2 * P30, 0, 0}};
    CHECK_INT(vbx_qf_rank_low(square), 1);
}

/* An exact line with v = (x, 0, 0, -d), D = d, U = (u0, u1, 0): A = x^2 -
 * d^2, B = u0 x, C = u0^2 + u1^2, delta = d^2 u0^2 - u1^2 (x^2 - d^2). All
 * below 2^53, so the double-double entries are exact. */
static void make_line(vbx_qline *L, int64_t x, int64_t d, int64_t u0, int64_t u1)
{
    const int64_t v[4] = {x, 0, 0, -d}, U[3] = {u0, u1, 0};
    for (int k = 0; k < 4; k++) {
        L->vi[k] = v[k];
        L->v[k] = vbx_dd_exact((double)v[k]);
    }
    for (int k = 0; k < 3; k++) {
        L->Ui[k] = U[k];
        L->U[k] = vbx_dd_exact((double)U[k]);
    }
    L->D = vbx_dd_exact((double)d);
    L->exact = 1;
}

static void test_delta(void)
{
    const int64_t P40 = (int64_t)1 << 40, P50 = (int64_t)1 << 50;
    vbx_qline L = {0};
    vbx_qprep P;
    /* x = u0 = 2^50, d = u1 = 1: delta = 1 under B^2 = 2^200, which
     * double-double leaves open: two roots, too close for its sqrt. */
    make_line(&L, P50, 1, P50, 1);
    CHECK_INT(vbx_qf_delta_sign(&L), 1);
    CHECK_INT(vbx_qf_prep(&L, &P), VBX_QF_EXACT);
    CHECK_INT(P.delta_exact, 1);
    /* x = 5, d = 3, u0 = 4, u1 = 3 (times 2^40): delta = 9 16 - 9 16 = 0.
     * mu = -B / A = -20 / 16, so s = -mu / 2 = 0.625. */
    make_line(&L, 5 * P40, 3 * P40, 4 * P40, 3 * P40);
    CHECK_INT(vbx_qf_delta_sign(&L), 0);
    CHECK_INT(vbx_qf_prep(&L, &P), VBX_QF_ONE);
    vbx_qroot R;
    vbx_qf_root(&P, 0, &R);
    CHECK(R.s.lo <= 0.625 && 0.625 <= R.s.hi && R.s.hi - R.s.lo < 1e-12);
    /* The same line with delta decided in double-double (u1 = 0: delta =
     * d^2 u0^2 > 0): no GMP sign. */
    make_line(&L, 5 * P40, 3 * P40, 4 * P40, 0);
    CHECK_INT(vbx_qf_prep(&L, &P), VBX_QF_TWO);
    CHECK_INT(P.delta_exact, 0);
    /* Not exact (wide rows): the double-double answer stands. */
    make_line(&L, P50, 1, P50, 1);
    L.exact = 0;
    CHECK_INT(vbx_qf_prep(&L, &P), VBX_QF_EXACT);
    CHECK_INT(P.delta_exact, 0);
}

int main(void)
{
    test_rank();
    test_delta();
    VB_TEST_END();
}
