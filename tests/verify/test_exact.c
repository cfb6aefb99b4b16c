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

/* Same bits as a double, NaN payloads and the sign of zero included. */
static int same_bits(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

/* One value against the bits' path, both ways. */
static size_t succ_differs(double x)
{
    return !same_bits(vbx_succ(x), vbx_succ_bits(x)) + !same_bits(vbx_pred(x), -vbx_succ_bits(-x));
}

/* vbx_succ (floating point where 2^-966 <= |x| <= DBL_MAX) is
 * vbx_succ_bits bit for bit: on the special values, on every binade's
 * first, second, last and middle doubles of both signs (the cases of the
 * proof in vbx_ia.h) from the subnormals to DBL_MAX, around the 2^-966
 * switch, and on 10^6 random bit patterns (every exponent) and 10^6
 * random doubles near 1 (the filters' own range). */
static void test_succ_paths(void)
{
    const double sp[] = {0.0, -0.0, 4.9406564584124654e-324, -4.9406564584124654e-324,
                         DBL_MIN, -DBL_MIN, DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN, -NAN,
                         0x1p-966, -0x1p-966, 0x1.fffffffffffffp-967, -0x1.fffffffffffffp-967,
                         0x1.0000000000001p-966, 1.0, -1.0, 0.1, -0.1};
    size_t bad = 0;
    for (size_t i = 0; i < sizeof sp / sizeof sp[0]; i++)
        bad += succ_differs(sp[i]);
    const double ms[] = {1.0, 1.0 + 0x1p-52, 1.0 + 0x1p-51, 1.5, 2.0 - 0x1p-52, 2.0 - 0x1p-51};
    for (int e = -1074; e <= 1023; e++)
        for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++) {
            double x = ldexp(ms[i], e);
            bad += succ_differs(x) + succ_differs(-x);
        }
    uint64_t s = 0x9e3779b97f4a7c15u;
    for (int i = 0; i < 1000000; i++) {
        vb_test_xorshift(&s);
        double x;
        memcpy(&x, &s, sizeof x);
        bad += succ_differs(x);
        bad += succ_differs((double)(s >> 11) * 0x1p-52 - 1.0);
    }
    CHECK_INT((int)bad, 0);
}

/* vb_ia_div (two divisions, picked by the signs) gives vb_ia_div4's
 * bounds (all four corners) bit for bit wherever no corner is NaN: on
 * every pair of intervals drawn from special values (zeros of both signs,
 * subnormals, DBL_MAX, infinities) and on 10^6 random ones. */
static int div_differs(vbx_ia a, vbx_ia b)
{
    double c[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
    for (int i = 0; i < 4; i++)
        if (c[i] != c[i])
            return 0;
    vb_ia q = vb_ia_div(a, b), r = vb_ia_div4(a, b);
    return !same_bits(q.lo, r.lo) || !same_bits(q.hi, r.hi);
}

static void test_div_paths(void)
{
    const double sp[] = {0.0, -0.0, 4.9406564584124654e-324, -4.9406564584124654e-324, 1.0, -1.0,
                         3.0, -0.1, DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, 0x1p-1000, -0x1p600};
    const size_t n = sizeof sp / sizeof sp[0];
    size_t bad = 0, tried = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            for (size_t k = 0; k < n; k++)
                for (size_t l = 0; l < n; l++) {
                    if (!(sp[i] <= sp[j]) || !(sp[k] <= sp[l]))
                        continue;
                    vbx_ia a = {sp[i], sp[j]}, b = {sp[k], sp[l]};
                    bad += (size_t)div_differs(a, b);
                    tried++;
                }
    uint64_t s = 0x2545f4914f6cdd1du;
    for (int i = 0; i < 1000000; i++) {
        double v[4];
        for (int m = 0; m < 4; m++) /* signed values over many binades, some exactly 0 */
            v[m] = vb_test_binades(&s, -100, 200);
        vbx_ia a = {vbx_min(v[0], v[1]), vbx_max(v[0], v[1])};
        vbx_ia b = {vbx_min(v[2], v[3]), vbx_max(v[2], v[3])};
        bad += (size_t)div_differs(a, b);
        tried++;
    }
    CHECK(tried > 1000000);
    CHECK_INT((int)bad, 0);
}

int main(void)
{
    test_div_paths();
    test_qsqrt_sign();
    test_round();
    test_intervals();
    test_succ_paths();
    VB_TEST_END();
}
