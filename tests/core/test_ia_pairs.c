/* vb_ia_pairs.h's steps (both bounds in one SSE2 register, the
 * certification filter's host twin) against vb_ia_shared.h's scalar ones,
 * bit for bit: add, sub, mul, sqr and div on every pair of intervals drawn
 * from special values (zeros of both signs, subnormals, the 2^-966 switch
 * of vb_succ, DBL_MAX, infinities, NaN) and on 10^6 random ones over many
 * binades, some bounds exactly 0. Only on hosts with SSE2 (x86-64). A
 * planted change of a lane's order (vb_ia_sub_p subtracting b.lo from
 * a.lo) or of the outward step (its constant) fails it. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "vb_ia_shared.h"
#include "vb_test.h"

#if defined(__SSE2__) && !defined(VB_IA_HOST_PAIRS)
static int same_bits(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

static int same_ia(vb_ia a, vb_ia b)
{
    return same_bits(a.lo, b.lo) && same_bits(a.hi, b.hi);
}

/* The steps that differ on (a, b): 0 when none. */
static size_t pair_differs(vb_ia a, vb_ia b)
{
    return !same_ia(vb_ia_add(a, b), vb_ia_add_p(a, b)) +
           !same_ia(vb_ia_sub(a, b), vb_ia_sub_p(a, b)) +
           !same_ia(vb_ia_mul(a, b), vb_ia_mul_p(a, b)) + !same_ia(vb_ia_sqr(a), vb_ia_sqr_p(a)) +
           !same_ia(vb_ia_div(a, b), vb_ia_div_p(a, b));
}

static void test_pairs(void)
{
    const double sp[] = {0.0,      -0.0,      4.9406564584124654e-324, -4.9406564584124654e-324,
                         DBL_MIN,  0x1p-966,  -0x1.fffffffffffffp-967, 0x1p-1000,
                         1.0,      -1.0,      3.0,                     -0.1,
                         0x1p600,  -0x1p600,  DBL_MAX,                 -DBL_MAX,
                         INFINITY, -INFINITY, NAN};
    const size_t n = sizeof sp / sizeof sp[0];
    size_t bad = 0, tried = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            for (size_t k = 0; k < n; k++)
                for (size_t l = 0; l < n; l++) {
                    /* ordered bounds, and NaN bounds (unordered) too */
                    if (sp[i] > sp[j] || sp[k] > sp[l])
                        continue;
                    vb_ia a = {sp[i], sp[j]}, b = {sp[k], sp[l]};
                    bad += pair_differs(a, b);
                    tried++;
                }
    uint64_t s = 0x2545f4914f6cdd1du;
    for (int i = 0; i < 1000000; i++) {
        double v[4];
        for (int m = 0; m < 4; m++)
            v[m] = vb_test_binades(&s, -1070, 2100);
        vb_ia a = {vb_fmin(v[0], v[1]), vb_fmax(v[0], v[1])};
        vb_ia b = {vb_fmin(v[2], v[3]), vb_fmax(v[2], v[3])};
        bad += pair_differs(a, b);
        tried++;
    }
    CHECK(tried > 1000000);
    CHECK_INT((int)bad, 0);
}
#endif

int main(void)
{
#if defined(__SSE2__) && !defined(VB_IA_HOST_PAIRS)
    test_pairs();
#endif
    VB_TEST_END();
}
