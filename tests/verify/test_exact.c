/* Exact arithmetic units: signs in Q(sqrt(D)), correct rounding, intervals. */
#include "vb_test.h"
#include "vbx_exact.h"

/* sign(a + b sqrt(D)) from decimal strings. */
static int qsign(const char *a, const char *b, const char *D)
{
    mpz_t za, zb, zD, t1, t2;
    mpz_inits(za, zb, zD, t1, t2, (mpz_ptr)0);
    mpz_set_str(za, a, 10);
    mpz_set_str(zb, b, 10);
    mpz_set_str(zD, D, 10);
    int s = vbx_sign_qsqrt(za, zb, zD, t1, t2);
    mpz_clears(za, zb, zD, t1, t2, (mpz_ptr)0);
    return s;
}

static void test_qsqrt_sign(void)
{
    CHECK_INT(qsign("3", "-1", "9"), 0);  /* 3 - 3 */
    CHECK_INT(qsign("3", "-1", "8"), 1);  /* 3 - 2.83 */
    CHECK_INT(qsign("3", "-1", "10"), -1); /* 3 - 3.16 */
    CHECK_INT(qsign("-3", "1", "10"), 1);
    CHECK_INT(qsign("-3", "1", "8"), -1);
    CHECK_INT(qsign("-3", "-1", "8"), -1); /* same signs */
    CHECK_INT(qsign("0", "-2", "5"), -1);
    CHECK_INT(qsign("0", "0", "5"), 0);
    CHECK_INT(qsign("7", "5", "0"), 1);    /* D = 0: b does not count */
    CHECK_INT(qsign("-7", "5", "0"), -1);
    /* Near zero: 10^20 - sqrt(10^40 - 1) = 5e-21 > 0, and 0 in double. */
    CHECK_INT(qsign("100000000000000000000", "-1", "9999999999999999999999999999999999999999"), 1);
    CHECK_INT(qsign("-100000000000000000000", "1", "10000000000000000000000000000000000000001"), 1);
    CHECK_INT(qsign("100000000000000000000", "-1", "10000000000000000000000000000000000000001"), -1);
    /* (1 + sqrt 2)^2 = 3 + 2 sqrt 2: 3 + 2 sqrt 2 - (2 sqrt 2 + 3) with D=8 as sqrt(8)=2 sqrt 2. */
    CHECK_INT(qsign("-3", "1", "8"), -1);
    /* 99 sqrt(2) vs 140: 99^2 * 2 = 19602 > 140^2 = 19600. */
    CHECK_INT(qsign("-140", "99", "2"), 1);
    CHECK_INT(qsign("140", "-99", "2"), -1);
}

static double qround(const char *num, const char *b, const char *D, const char *den, double *lo,
                     double *hi, int *rc)
{
    mpz_t zn, zb, zD, zd;
    mpz_inits(zn, zb, zD, zd, (mpz_ptr)0);
    mpz_set_str(zn, num, 10);
    mpz_set_str(zb, b, 10);
    mpz_set_str(zD, D, 10);
    mpz_set_str(zd, den, 10);
    double out = 0.0;
    *rc = vbx_round(zn, zb, zD, zd, &out, lo, hi, NULL);
    mpz_clears(zn, zb, zD, zd, (mpz_ptr)0);
    return out;
}

static void test_round(void)
{
    double lo, hi;
    int rc;
    /* 1 + sqrt(2) = 2.41421356237309504880...: nearest double. */
    double v = qround("1", "1", "2", "1", &lo, &hi, &rc);
    CHECK_INT(rc, VB_OK);
    CHECK(v == 2.414213562373095);
    CHECK(lo <= v && v <= hi && hi - lo < 1e-15);
    /* Negative denominator swaps the enclosure: -(1 + sqrt 2) / 2. */
    v = qround("1", "1", "2", "-2", &lo, &hi, &rc);
    CHECK(v == -1.2071067811865475);
    CHECK(lo <= v && v <= hi);
    /* Ties to even: 1 + 2^-53 is the midpoint of 1 and 1 + 2^-52 -> 1;
     * 1 + 3 * 2^-53 is the midpoint of 1 + 2^-52 and 1 + 2^-51 -> the even one. */
    v = qround("9007199254740993", "0", "0", "9007199254740992", &lo, &hi, &rc);
    CHECK_INT(rc, VB_OK);
    CHECK(v == 1.0);
    v = qround("9007199254740995", "0", "0", "9007199254740992", &lo, &hi, &rc);
    CHECK(v == 1.0 + 4.0 * 0x1p-53);
    /* Just above the midpoint (irrational): (2^53 + 1 + sqrt(2)/10^30)/2^53 rounds up. */
    v = qround("9007199254740993000000000000000", "1", "2", "9007199254740992000000000000000",
               &lo, &hi, &rc);
    CHECK_INT(rc, VB_OK);
    CHECK(v == 1.0 + 0x1p-52);
    /* 1/3 is no double: nearest is 0.3333333333333333. */
    v = qround("1", "0", "0", "3", &lo, &hi, &rc);
    CHECK(v == 1.0 / 3.0);
    CHECK(lo < hi);
}

static void test_intervals(void)
{
    /* 0.1 + 0.2 in double is 0.30000000000000004; the enclosure must contain
     * both that sum's exact value and stay within two ulps. */
    vbx_ia a = vbx_ia_point(0.1), b = vbx_ia_point(0.2);
    vbx_ia s = vbx_ia_add(a, b);
    CHECK(s.lo < 0.30000000000000004 && s.hi > 0.30000000000000004);
    CHECK(s.hi - s.lo < 2e-16);
    /* Products across zero and squares. */
    vbx_ia m = vbx_ia_mul((vbx_ia){-2.0, 3.0}, (vbx_ia){-5.0, 1.0});
    CHECK(m.lo <= -15.0 && m.hi >= 10.0 && m.lo > -15.0001 && m.hi < 10.0001);
    vbx_ia q = vbx_ia_sqr((vbx_ia){-2.0, 3.0});
    CHECK(q.lo == 0.0 && q.hi >= 9.0);
    CHECK_INT(vbx_ia_sign((vbx_ia){-1e-300, 1e-300}), 0);
    CHECK_INT(vbx_ia_sign(vbx_ia_div(vbx_ia_point(1.0), vbx_ia_point(3.0))), 1);
    /* Division by an interval containing 0 gives everything. */
    vbx_ia d = vbx_ia_div(vbx_ia_point(1.0), (vbx_ia){-1.0, 1.0});
    CHECK(d.lo == -INFINITY && d.hi == INFINITY);
    /* Neighbours: succ/pred at zero, subnormals, sign changes and infinity. */
    CHECK(vbx_succ(0.0) == 4.9406564584124654e-324);
    CHECK(vbx_pred(0.0) == -4.9406564584124654e-324);
    CHECK(vbx_succ(-4.9406564584124654e-324) == 0.0);
    CHECK(vbx_succ(1.0) == 1.0 + 0x1p-52);
    CHECK(vbx_pred(1.0) == 1.0 - 0x1p-53);
    CHECK(vbx_succ(-1.0) == -1.0 + 0x1p-53);
    CHECK(vbx_pred(INFINITY) == DBL_MAX);
    CHECK(vbx_succ(DBL_MAX) == INFINITY);
    CHECK(vbx_succ(INFINITY) == INFINITY);
}

int main(void)
{
    test_qsqrt_sign();
    test_round();
    test_intervals();
    VB_TEST_END();
}
