/* The inline outward steps of the certifier's rounding (vbx_ldstep.h for
 * long double, vbx_succ/vbx_pred of vbx_ia.h for double) against libm's
 * nextafterl/nextafter, bit for bit: the edge cases (zeros, subnormals, the
 * subnormal/normal border, binade tops, the largest finite, infinities,
 * NaN) and 10^6 random encodings of each format. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "vb_test.h"
#include "vbx_ia.h"
#include "vbx_ldstep.h"

static uint64_t rng = 0x9e3779b97f4a7c15u;

/* splitmix64: a fixed sequence, so a failure is reproducible. */
static uint64_t next64(void)
{
    uint64_t z = (rng += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* Same value and same sign (the bytes that carry the value; NaN: both NaN). */
static int same_ld(long double a, long double b)
{
    if (isnan(a) || isnan(b))
        return isnan(a) && isnan(b);
    return memcmp(&a, &b, LDBL_MANT_DIG == 64 ? 10 : sizeof a) == 0;
}

static int same_d(double a, double b)
{
    if (isnan(a) || isnan(b))
        return isnan(a) && isnan(b);
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Number of disagreements of both steps with nextafterl at x and -x. */
static int ld_misses(long double x)
{
    int bad = 0;
    for (int s = 0; s < 2; s++, x = -x) {
        bad += !same_ld(vbx_ld_succ(x), nextafterl(x, INFINITY));
        bad += !same_ld(vbx_ld_pred(x), nextafterl(x, -INFINITY));
    }
    return bad;
}

static int d_misses(double x)
{
    int bad = 0;
    for (int s = 0; s < 2; s++, x = -x) {
        bad += !same_d(vbx_succ(x), nextafter(x, INFINITY));
        bad += !same_d(vbx_pred(x), nextafter(x, -INFINITY));
    }
    return bad;
}

#if VBX_LDSTEP_X87
/* The x87 encoding sign | e (15 bits) | m (64 bits, explicit J bit). */
static long double ld_make(unsigned neg, unsigned e, uint64_t m)
{
    long double x = 0.0L;
    uint16_t se = (uint16_t)(neg << 15 | e);
    memcpy(&x, &m, sizeof m);
    memcpy((char *)&x + 8, &se, sizeof se);
    return x;
}

/* A canonical encoding (the ones arithmetic produces): J set for e > 0,
 * clear for e = 0. */
static long double ld_canonical(unsigned neg, unsigned e, uint64_t m)
{
    const uint64_t J = (uint64_t)1 << 63;
    return ld_make(neg, e, e ? m | J : m & ~J);
}

/* Values around the places where the step changes binade or class. */
static void test_ld_edges(void)
{
    const uint64_t J = (uint64_t)1 << 63;
    const unsigned es[] = {0, 1, 2, 3, 0x3ffe, 0x3fff, 0x4000, 0x7ffc, 0x7ffd, 0x7ffe};
    const uint64_t ms[] = {0, 1, 2, J - 2, J - 1, J, J + 1, J + 2, UINT64_MAX - 1, UINT64_MAX};
    int bad = 0;
    for (size_t i = 0; i < sizeof es / sizeof *es; i++)
        for (size_t k = 0; k < sizeof ms / sizeof *ms; k++)
            bad += ld_misses(ld_canonical(0, es[i], ms[k]));
    CHECK_INT(bad, 0);
    /* The named values, and that they are what the encodings say. */
    CHECK(vbx_ld_succ(0.0L) == 0x1p-16445L && vbx_ld_succ(-0.0L) == 0x1p-16445L);
    CHECK(vbx_ld_pred(0.0L) == -0x1p-16445L && vbx_ld_pred(-0.0L) == -0x1p-16445L);
    CHECK(vbx_ld_succ(-0x1p-16445L) == 0.0L && signbit(vbx_ld_succ(-0x1p-16445L)));
    CHECK(vbx_ld_pred(0x1p-16445L) == 0.0L && !signbit(vbx_ld_pred(0x1p-16445L)));
    CHECK(vbx_ld_succ(LDBL_MIN - 0x1p-16445L) == LDBL_MIN);
    CHECK(vbx_ld_pred(LDBL_MIN) == LDBL_MIN - 0x1p-16445L);
    CHECK(vbx_ld_succ(1.0L) == 1.0L + 0x1p-63L && vbx_ld_pred(1.0L) == 1.0L - 0x1p-64L);
    CHECK(vbx_ld_succ(2.0L - 0x1p-63L) == 2.0L);
    CHECK(vbx_ld_succ(LDBL_MAX) == INFINITY && vbx_ld_pred(-LDBL_MAX) == -INFINITY);
    CHECK(vbx_ld_pred((long double)INFINITY) == LDBL_MAX);
    CHECK(vbx_ld_succ(-(long double)INFINITY) == -LDBL_MAX);
    CHECK(vbx_ld_succ((long double)INFINITY) == INFINITY);
    CHECK(vbx_ld_pred(-(long double)INFINITY) == -INFINITY);
    CHECK(isnan(vbx_ld_succ((long double)NAN)) && isnan(vbx_ld_pred((long double)NAN)));
    CHECK_INT(ld_misses(0.0L) + ld_misses(INFINITY) + ld_misses(NAN), 0);
}

/* 10^6 random canonical encodings: a third of them with an exponent and a
 * significand drawn from the edges, the rest uniform over every class
 * (e = 0x7fff gives infinities and NaNs). */
static void test_ld_random(void)
{
    const uint64_t J = (uint64_t)1 << 63;
    const uint64_t edge_m[] = {0, 1, J - 1, J, J + 1, UINT64_MAX};
    int bad = 0;
    for (int i = 0; i < 1000000; i++) {
        uint64_t r = next64(), m = next64();
        unsigned e = (unsigned)(r & 0x7fff), neg = (unsigned)(r >> 15) & 1;
        unsigned kind = (unsigned)(r >> 16) % 3;
        if (kind == 0) {
            m = edge_m[(r >> 20) % 6];
            e = (unsigned)((r >> 24) % 4);
            e = (r >> 28) & 1 ? e : 0x7fff - e;
        }
        bad += ld_misses(ld_canonical(neg, e, m));
    }
    CHECK_INT(bad, 0);
}
#endif

static void test_d_random(void)
{
    int bad = 0;
    const double edges[] = {0.0, 4.9406564584124654e-324, DBL_MIN, DBL_MIN - 4.9406564584124654e-324,
                            1.0, 2.0, DBL_MAX, INFINITY, NAN};
    for (size_t i = 0; i < sizeof edges / sizeof *edges; i++)
        bad += d_misses(edges[i]);
    for (int i = 0; i < 1000000; i++) {
        uint64_t b = next64();
        double x;
        /* Half of them with the exponent at its ends (subnormals, near
         * overflow, infinities and NaN). */
        if (i & 1)
            b = (b & 0x800fffffffffffffu) | ((b >> 52) & 1 ? 0x7fe0000000000000u : 0) |
                ((b >> 53) & 1 ? 0x0010000000000000u : 0);
        memcpy(&x, &b, sizeof x);
        bad += d_misses(x);
    }
    CHECK_INT(bad, 0);
}

/* Values the rounding path meets: quotients and square roots of random
 * integers, stepped both ways. */
static void test_ld_computed(void)
{
    int bad = 0;
    for (int i = 0; i < 100000; i++) {
        long double a = (long double)next64(), b = (long double)(next64() | 1);
        bad += ld_misses(a / b) + ld_misses(sqrtl(a)) + ld_misses(a * b * 0x1p-16400L);
    }
    CHECK_INT(bad, 0);
}

int main(void)
{
#if VBX_LDSTEP_X87
    test_ld_edges();
    test_ld_random();
#endif
    test_ld_computed();
    test_d_random();
    VB_TEST_END();
}
