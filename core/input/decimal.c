/* Exact decimals: the text of a number kept as mant * 10^exp10, beside the
 * double strtod makes of the same text. Parsing our own grammar first means
 * strtod never sees hex floats, "nan(...)" or locale surprises. */
#include "vb_spheres.h"
#include "vb_decimal_mpz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exponents beyond this are absurd for coordinates and would make the exact
 * rationals of verify/ needlessly large; they are reported as magnitude errors. */
#define VBI_MAX_EXP10 340
/* A decimal token longer than this is not a coordinate anyone wrote by hand
 * or by a structure writer; bounding it keeps strtod's copy on the stack. */
#define VBI_MAX_TOKEN 127

static int is_nonfinite_word(const char *t, size_t n)
{
    if (n > 0 && (t[0] == '+' || t[0] == '-')) {
        t++;
        n--;
    }
    /* Every word starts with n or i: a digit or a point is no word. */
    if (n == 0 || ((t[0] | 0x20) != 'n' && (t[0] | 0x20) != 'i'))
        return 0;
    static const char *const words[] = {"nan", "inf", "infinity"};
    for (size_t w = 0; w < 3; w++) {
        size_t k = strlen(words[w]);
        if (n < k)
            continue;
        size_t i = 0;
        while (i < k && (t[i] | 0x20) == words[w][i])
            i++;
        /* "nan(...)" is a NaN too; any other tail is just malformed text. */
        if (i == k && (n == k || (w == 0 && t[k] == '(')))
            return 1;
    }
    return 0;
}

/* mant x 10^exp10 correctly rounded without strtod, where that is one
 * rounding (Clinger's fast path): |mant| <= 2^53 is an exact double, and
 * so is 10^k for k <= 22 (5^22 < 2^53), so the product or quotient of the
 * two is rounded once, to nearest as strtod rounds; 1 and *out, else 0
 * (the caller asks strtod). mant 0 is left to the caller (the sign of a
 * zero is the text's). */
static int fast_double(int64_t mant, int32_t exp10, double *out)
{
    static const double p10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const int64_t lim = (int64_t)1 << 53;
    if (mant == 0 || mant > lim || mant < -lim || exp10 > 22 || exp10 < -22)
        return 0;
    *out = exp10 >= 0 ? (double)mant * p10[exp10] : (double)mant / p10[-exp10];
    return 1;
}

int vb_decimal_parse(const char *tok, size_t len, vb_decimal *out, double *d)
{
    if (len == 0)
        return VB_EINPUT_MALFORMED;
    if (is_nonfinite_word(tok, len))
        return VB_EINPUT_NONFINITE;
    if (len > VBI_MAX_TOKEN)
        return VB_EINPUT_MAGNITUDE;

    size_t i = 0;
    int neg = 0;
    if (tok[i] == '+' || tok[i] == '-')
        neg = tok[i++] == '-';
    /* Significant digits, without leading zeros, and the decimal exponent of
     * the last digit kept. */
    char digits[VBI_MAX_TOKEN + 1];
    size_t nd = 0, nseen = 0;
    long exp = 0;
    int seen_point = 0;
    for (; i < len; i++) {
        char c = tok[i];
        if (c == '.' && !seen_point) {
            seen_point = 1;
        } else if (c >= '0' && c <= '9') {
            nseen++;
            if (nd > 0 || c != '0')
                digits[nd++] = c;
            if (seen_point)
                exp--;
        } else {
            break;
        }
    }
    if (nseen == 0)
        return VB_EINPUT_MALFORMED;
    if (i < len && (tok[i] == 'e' || tok[i] == 'E')) {
        i++;
        int eneg = 0;
        if (i < len && (tok[i] == '+' || tok[i] == '-'))
            eneg = tok[i++] == '-';
        size_t start = i;
        long e = 0;
        for (; i < len && tok[i] >= '0' && tok[i] <= '9'; i++)
            if (e < 100000)
                e = e * 10 + (tok[i] - '0');
        if (i == start)
            return VB_EINPUT_MALFORMED;
        exp += eneg ? -e : e;
    }
    if (i != len)
        return VB_EINPUT_MALFORMED;

    /* Trailing zeros move into the exponent, so equal values compare equal
     * field by field. */
    while (nd > 0 && digits[nd - 1] == '0') {
        nd--;
        exp++;
    }
    if (nd > 18)
        return VB_EINPUT_MAGNITUDE;
    int64_t m = 0;
    for (size_t k = 0; k < nd; k++)
        m = m * 10 + (digits[k] - '0');
    if (m == 0) {
        exp = 0;
    } else if (exp > VBI_MAX_EXP10 || exp < -VBI_MAX_EXP10 ||
               exp + (long)nd - 1 > VBI_MAX_EXP10 || exp + (long)nd - 1 < -VBI_MAX_EXP10) {
        return VB_EINPUT_MAGNITUDE;
    }
    out->mant = neg ? -m : m;
    out->exp10 = (int32_t)exp;
    if (d && !fast_double(out->mant, out->exp10, d)) {
        char buf[VBI_MAX_TOKEN + 1];
        memcpy(buf, tok, len);
        buf[len] = '\0';
        *d = strtod(buf, NULL);
    }
    return VB_OK;
}

static int digit_count(int64_t m)
{
    int n = 1;
    while (m >= 10) {
        m /= 10;
        n++;
    }
    return n;
}

/* Compares |a| and |b| for nonzero mantissas of the same sign. */
static int cmp_magnitude(int64_t am, int32_t ae, int64_t bm, int32_t be)
{
    int an = digit_count(am), bn = digit_count(bm);
    /* Position of the leading digit decides unless equal. */
    long al = (long)ae + an, bl = (long)be + bn;
    if (al != bl)
        return al < bl ? -1 : 1;
    /* Same leading position: pad the shorter mantissa to the longer one's
     * digit count; both stay <= 18 digits, inside int64. */
    while (an < bn) {
        am *= 10;
        an++;
    }
    while (bn < an) {
        bm *= 10;
        bn++;
    }
    return am < bm ? -1 : am > bm;
}

int vb_decimal_cmp(vb_decimal a, vb_decimal b)
{
    int sa = (a.mant > 0) - (a.mant < 0), sb = (b.mant > 0) - (b.mant < 0);
    if (sa != sb)
        return sa < sb ? -1 : 1;
    if (sa == 0)
        return 0;
    /* -INT64_MAX..INT64_MAX: 18 digits never reach INT64_MIN. */
    int c = cmp_magnitude(a.mant < 0 ? -a.mant : a.mant, a.exp10,
                          b.mant < 0 ? -b.mant : b.mant, b.exp10);
    return sa > 0 ? c : -c;
}

void vb_decimal_to_mpz(mpz_t z, vb_decimal d, int32_t emin, mpz_t tmp)
{
    mpz_set_si(z, (long)d.mant);
    if (d.exp10 > emin) {
        mpz_ui_pow_ui(tmp, 10, (unsigned long)(d.exp10 - emin));
        mpz_mul(z, z, tmp);
    }
}

double vb_decimal_double(vb_decimal d)
{
    double v;
    if (fast_double(d.mant, d.exp10, &v))
        return v;
    char buf[48];
    snprintf(buf, sizeof buf, "%lldE%d", (long long)d.mant, (int)d.exp10);
    return strtod(buf, NULL);
}

void vb_decimal_format(vb_decimal d, char *out, size_t size)
{
    char digits[24], buf[64];
    unsigned long long m = d.mant < 0 ? 0ull - (unsigned long long)d.mant : (unsigned long long)d.mant;
    int len = snprintf(digits, sizeof digits, "%llu", m), e = d.exp10, k = 0;
    if (d.mant < 0)
        buf[k++] = '-';
    if (d.mant == 0) {
        buf[k++] = '0';
    } else if (e >= 0) { /* digits, then e zeros */
        for (int j = 0; j < len && k < 40; j++)
            buf[k++] = digits[j];
        for (int j = 0; j < e && k < 60; j++)
            buf[k++] = '0';
    } else if (-e < len) { /* a point inside the digits */
        for (int j = 0; j < len; j++) {
            if (j == len + e)
                buf[k++] = '.';
            buf[k++] = digits[j];
        }
    } else { /* 0.000digits */
        buf[k++] = '0';
        buf[k++] = '.';
        for (int j = 0; j < -e - len && k < 40; j++)
            buf[k++] = '0';
        for (int j = 0; j < len; j++)
            buf[k++] = digits[j];
    }
    buf[k] = '\0';
    snprintf(out, size, "%s", buf);
}
