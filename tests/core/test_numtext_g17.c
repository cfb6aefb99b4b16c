/* vb_format_g17 writes exactly printf's "%.17g" and vb_format_u32 "%u":
 * compared with snprintf over values of every kind the writers meet (vertex
 * coordinates, radii, exact ties of the 17-digit rounding, powers of ten and
 * their neighbours, both notations, specials) and random bit patterns. */
#include <float.h>
#include <stdint.h>

#include "vb_numtext.h"
#include "vb_test.h"

static int mismatches;

static void same(double x)
{
    char want[64], got[VB_G17_MAX];
    int nw = snprintf(want, sizeof want, "%.17g", x);
    size_t ng = vb_format_g17(x, got);
    if ((size_t)nw != ng || strcmp(want, got) != 0) {
        if (mismatches++ < 10)
            fprintf(stderr, "%a: printf '%s', vb_format_g17 '%s'\n", x, want, got);
    }
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t next(void)
{
    vb_test_xorshift(&rng);
    return rng;
}

int main(void)
{
    const double specials[] = {0.0, -0.0, 1.0, -1.0, 0.5, 0.1, 1e-4, 9.9999999999999991e-5, 1e-5,
                               1e16, 1e17, 9.9999999999999998e16, 1e17 - 16, 123456789012345678.0,
                               DBL_MIN, DBL_MIN / 4, DBL_MAX, DBL_EPSILON, INFINITY, -INFINITY, NAN,
                               80.698131147201394, -80.273703748934736, 0.38156675094778014,
                               -0.090111779360630168, 2.557976920232448};
    for (size_t i = 0; i < sizeof specials / sizeof specials[0]; i++) {
        same(specials[i]);
        same(-specials[i]);
        same(nextafter(specials[i], INFINITY));
        same(nextafter(specials[i], -INFINITY));
    }
    /* Powers of ten and their neighbours, where the exponent moves. */
    for (int k = -30; k <= 30; k++) {
        double p = pow(10.0, k);
        for (int s = -3; s <= 3; s++) {
            double v = p;
            for (int t = 0; t < (s < 0 ? -s : s); t++)
                v = nextafter(v, s < 0 ? 0.0 : INFINITY);
            same(v);
            same(-v);
        }
    }
    /* Exact ties of the 17th digit: odd m times 2^-1 .. 2^-4 near 10^15..10^17,
     * and every integer neighbourhood of 2^53 (18-digit integers). */
    for (int k = 0; k < 200000; k++) {
        uint64_t m = (next() & ((1ull << 53) - 1)) | (1ull << 52) | 1u;
        for (int e = -4; e <= 3; e++)
            same(ldexp((double)m, e));
    }
    /* Decimals as inputs give them: 3 decimals, 17 digits, scales 1e-6 .. 1e6. */
    for (int k = 0; k < 300000; k++) {
        double v = (double)(int64_t)(next() % 2000000001ull - 1000000000) / 1000.0;
        same(v);
        double w = (double)(next() >> 11) * 0x1p-53 * pow(10.0, (int)(next() % 13) - 6);
        same(w);
        same(-w);
    }
    /* Every binade of the fixed-notation path (2^-60 .. 2^56), its ends and
     * random values in it: the exponent is guessed from the binade, then
     * checked. */
    for (int e = -61; e <= 57; e++) {
        same(ldexp(1.0, e));
        same(nextafter(ldexp(1.0, e), 0.0));
        for (int k = 0; k < 3000; k++)
            same(ldexp(1.0 + (double)(next() >> 12) * 0x1p-52, e));
    }
    /* Random bit patterns over the whole range. */
    for (int k = 0; k < 300000; k++) {
        uint64_t b = next();
        double v;
        memcpy(&v, &b, sizeof v);
        same(v);
    }
    CHECK_INT(mismatches, 0);
    /* Unsigned integers. */
    const uint32_t us[] = {0u, 1u, 9u, 10u, 99u, 100u, 4294967295u, 1000000000u, 26429u};
    for (size_t i = 0; i < sizeof us / sizeof us[0]; i++) {
        char want[16], got[11];
        snprintf(want, sizeof want, "%u", (unsigned)us[i]);
        size_t n = vb_format_u32(us[i], got);
        CHECK(strcmp(want, got) == 0 && n == strlen(want));
    }
    for (int k = 0; k < 100000; k++) {
        uint32_t u = (uint32_t)next();
        char want[16], got[11];
        snprintf(want, sizeof want, "%u", (unsigned)u);
        vb_format_u32(u, got);
        if (strcmp(want, got) != 0)
            mismatches++;
    }
    CHECK_INT(mismatches, 0);
    VB_TEST_END();
}
