/* The next long double up and down (nextafterl(x, +-inf)) without a libm
 * call: the outward step of the certifier's 64-bit rounding path
 * (exact_numbers.c), where glibc's nextafterl took 6.8 % of the CPU of
 * `verify --arcs` on 4yvs (26,430 balls).
 *
 * Proof for the x87 80-bit extended format (LDBL_MANT_DIG 64, exponent
 * range of IEEE binary64x; the format of x86 and x86-64 long double): a
 * value is sign s, biased exponent e (15 bits) and a 64-bit significand m
 * whose top bit J is explicit.
 *   - e in 1..0x7ffe with J = 1: the normal number m 2^(e - 16446).
 *   - e = 0 with J = 0: the subnormal m 2^(-16445) (m = 0: a signed zero).
 *   - e = 0x7fff, m = 2^63: infinity; other m: NaN.
 * Arithmetic produces only these encodings (pseudo-denormals, unnormals
 * and pseudo-infinities never come out of +, *, /, sqrt, conversions).
 * For x >= 0 the value |x| = m 2^(max(e, 1) - 16446) is strictly
 * increasing in the pair (e, m) over the canonical encodings, so the next
 * magnitude up is the next canonical pair:
 *   - m < 2^64 - 1: m + 1 at the same e, except that the subnormal
 *     m = 2^63 - 1 steps to 2^63, which is the smallest normal and must
 *     be written e = 1 (same value; e = 0 with J = 1 is a pseudo-denormal);
 *   - m = 2^64 - 1: m = 2^63 at e + 1 (the binade's top, one ulp more is
 *     the next power of two); from LDBL_MAX (e = 0x7ffe) that is e = 0x7fff,
 *     m = 2^63, exactly +inf, as nextafterl gives.
 * The next magnitude down is the inverse map: m - 1, except m = 2^63 with
 * e >= 2 (m = 2^64 - 1 at e - 1) and m = 2^63 with e = 1 (the largest
 * subnormal, e = 0, m = 2^63 - 1); from the smallest subnormal m = 1 it
 * reaches m = 0, a zero of x's sign (glibc gives -0 from the negative one).
 * Signs: succ(x) for x < 0 moves the magnitude down, pred(x) = -succ(-x)
 * (negation is exact). Zeros of either sign step to +-LDBL_TRUE_MIN,
 * -inf up to -LDBL_MAX, +inf up stays +inf, NaN stays NaN: nextafterl's
 * values in every case. tests/verify/test_ldstep.c checks all this against
 * nextafterl on the edge cases and on 10^6 random encodings. Other long
 * double formats (binary128, double-double, long double = double) use
 * nextafterl. */
#ifndef VBX_LDSTEP_H
#define VBX_LDSTEP_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#if LDBL_MANT_DIG == 64 && LDBL_MAX_EXP == 16384 && LDBL_MIN_EXP == -16381 &&              \
    (defined(__x86_64__) || defined(__i386__))
#define VBX_LDSTEP_X87 1
#else
#define VBX_LDSTEP_X87 0
#endif

#if VBX_LDSTEP_X87
/* Next long double towards +inf (x itself for +inf and NaN). */
static inline long double vbx_ld_succ(long double x)
{
    const uint64_t J = (uint64_t)1 << 63;
    uint64_t m;
    uint16_t se;
    memcpy(&m, &x, sizeof m); /* little endian: significand, then sign and exponent */
    memcpy(&se, (const char *)&x + 8, sizeof se);
    unsigned e = se & 0x7fffu, neg = se >> 15;
    if (__builtin_expect(e == 0x7fffu || (e == 0 && m == 0), 0)) {
        if (e == 0)
            return 0x1p-16445L; /* LDBL_TRUE_MIN, from either zero */
        return neg && m == J ? -LDBL_MAX : x;
    }
    if (!neg) {
        if (m == UINT64_MAX) {
            m = J;
            e++;
        } else if (++m == J && e == 0) {
            e = 1;
        }
    } else {
        if (m == J && e > 0) {
            m = e == 1 ? J - 1 : UINT64_MAX;
            e--;
        } else {
            m--;
        }
    }
    se = (uint16_t)(neg << 15 | e);
    memcpy(&x, &m, sizeof m);
    memcpy((char *)&x + 8, &se, sizeof se);
    return x;
}

/* Next long double towards -inf (x itself for -inf and NaN). */
static inline long double vbx_ld_pred(long double x)
{
    return -vbx_ld_succ(-x);
}
#else
static inline long double vbx_ld_succ(long double x)
{
    return nextafterl(x, INFINITY);
}

static inline long double vbx_ld_pred(long double x)
{
    return nextafterl(x, -INFINITY);
}
#endif

#endif
