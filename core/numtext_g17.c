/* Doubles as printf's "%.17g" writes them, without printf (vb_numtext.h).
 * Formatting 17 digits through printf is most of the cost of writing
 * millions of vertex lines; the files are compared byte for byte, so the
 * text must be exactly printf's. A filter, then the exact path: numbers
 * whose "%.17g" is in fixed notation (decimal exponent X of the rounded
 * value with -4 <= X <= 16) are rounded here exactly in 128-bit integers;
 * every other number (zero, subnormal, huge, tiny, not finite) goes to
 * snprintf. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "vb_numtext.h"

/* 10^k, k = 0..20 (10^20 < 2^67). */
static const unsigned __int128 TEN[21] = {
    1ull, 10ull, 100ull, 1000ull, 10000ull, 100000ull, 1000000ull, 10000000ull,
    100000000ull, 1000000000ull, 10000000000ull, 100000000000ull, 1000000000000ull,
    10000000000000ull, 100000000000000ull, 1000000000000000ull, 10000000000000000ull,
    100000000000000000ull, 1000000000000000000ull, 10000000000000000000ull,
    (unsigned __int128)10000000000000000000ull * 10u};

#define D17 100000000000000000ull /* 10^17 */
#define D16 10000000000000000ull  /* 10^16 */

/* round(m 2^e 10^s) to the nearest integer, ties to even (printf's rounding
 * of the exact binary value in the default rounding mode). m < 2^53,
 * 0 <= s <= 20, -128 < e <= 4. Exact: m 10^s < 2^120. */
static uint64_t scaled(uint64_t m, int e, int s)
{
    unsigned __int128 p = (unsigned __int128)m * TEN[s];
    if (e >= 0)
        return (uint64_t)(p << e);
    int sh = -e;
    unsigned __int128 d = p >> sh, rem = p - (d << sh), half = (unsigned __int128)1 << (sh - 1);
    if (rem > half || (rem == half && (d & 1u)))
        d++;
    return (uint64_t)d;
}

/* 10^j as the nearest double, j = -4 .. 17 (P10[j + 4]): exact for j >= 0;
 * only a first guess of the exponent depends on them. */
static const double P10[22] = {1e-4, 1e-3, 1e-2, 1e-1, 1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,
                               1e7,  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17};

/* "00" .. "99": two digits at a time. */
static const char PAIRS[201] = "00010203040506070809101112131415161718192021222324252627282930313233"
                               "34353637383940414243444546474849505152535455565758596061626364656667"
                               "6869707172737475767778798081828384858687888990919293949596979899";

/* The 8 decimal digits of v < 10^8, zero-padded, to d[0 .. 8). */
static void digits8(uint32_t v, char *d)
{
    for (int i = 6; i >= 0; i -= 2) {
        memcpy(d + i, PAIRS + 2 * (v % 100u), 2);
        v /= 100u;
    }
}

size_t vb_format_g17(double x, char out[VB_G17_MAX])
{
    double a = fabs(x);
    /* Fixed notation needs the rounded value in [1e-4, 1e17); below 2^-60
     * or at 2^56 and above it is either exponent notation or past the
     * exact range of scaled(): printf does those. */
    if (!(a >= 0x1p-60 && a < 0x1p56))
        return (size_t)snprintf(out, VB_G17_MAX, "%.17g", x);
    /* a is normal: a = m 2^e with m = 2^52 + the stored fraction. */
    uint64_t bits;
    memcpy(&bits, &a, sizeof bits);
    int be = (int)(bits >> 52); /* the sign bit of a is 0 */
    uint64_t m = (bits & ((1ull << 52) - 1)) | (1ull << 52);
    int e = be - 1075;
    /* X = floor(log10 a), guessed and checked below: the 17 digits D must
     * lie in [10^16, 10^17) (a carry to 10^17 moves X up). With
     * 2^(k-1) <= a < 2^k (k = e + 53), X is floor((k-1) log10 2) or one
     * more; 78913 / 2^18 is log10 2 closely enough for |k| < 1000 (the
     * offset 64 keeps the shift's operand positive: a floor). */
    int X = (((e + 52) * 78913 + (64 << 18)) >> 18) - 64;
    if (X + 1 >= -4 && X + 1 <= 17 && a >= P10[X + 5])
        X++;
    uint64_t D = 0;
    for (int tries = 0; tries < 4; tries++) {
        if (X < -4 || X > 16)
            return (size_t)snprintf(out, VB_G17_MAX, "%.17g", x);
        D = scaled(m, e, 16 - X);
        if (D >= D17)
            X++;
        else if (D < D16)
            X--;
        else
            break;
    }
    if (D < D16 || D >= D17)
        return (size_t)snprintf(out, VB_G17_MAX, "%.17g", x);
    char dig[17];
    uint64_t hi = D / 100000000u; /* < 10^9 */
    dig[0] = (char)('0' + hi / 100000000u);
    digits8((uint32_t)(hi % 100000000u), dig + 1);
    digits8((uint32_t)(D % 100000000u), dig + 9);
    /* Precision 16 - X after the point, trailing zeros dropped (and the
     * point with them). */
    int last = 16;
    while (last > 0 && last > X && dig[last] == '0')
        last--;
    size_t n = 0;
    if (x < 0)
        out[n++] = '-';
    if (X >= 0) {
        memcpy(out + n, dig, (size_t)X + 1);
        n += (size_t)X + 1;
        if (last > X) {
            out[n++] = '.';
            memcpy(out + n, dig + X + 1, (size_t)(last - X));
            n += (size_t)(last - X);
        }
    } else {
        out[n++] = '0';
        out[n++] = '.';
        for (int z = 0; z < -X - 1; z++)
            out[n++] = '0';
        memcpy(out + n, dig, (size_t)last + 1);
        n += (size_t)last + 1;
    }
    out[n] = '\0';
    return n;
}

size_t vb_format_u32(uint32_t v, char out[11])
{
    char t[10];
    size_t n = 0;
    do {
        t[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    for (size_t i = 0; i < n; i++)
        out[i] = t[n - 1 - i];
    out[n] = '\0';
    return n;
}

size_t vb_format_i32(int32_t v, char out[12])
{
    if (v >= 0)
        return vb_format_u32((uint32_t)v, out);
    out[0] = '-';
    return 1 + vb_format_u32((uint32_t)0 - (uint32_t)v, out + 1);
}
