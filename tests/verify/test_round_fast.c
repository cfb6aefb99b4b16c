/* The MPFR-free rounding path (vbx_round_fast) against MPFR (vbx_round_mpfr):
 * every coordinate it decides must be the same double, bit for bit, and
 * near ties must fall back. */
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbx_exact.h"
#include "vt_spheres.h"

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Random integer of up to `bits` bits, sign random when `sign`. */
static void rand_z(mpz_t z, gmp_randstate_t rs, unsigned bits, int sign)
{
    mpz_urandomb(z, rs, 1 + (unsigned)gmp_urandomm_ui(rs, bits));
    if (sign && gmp_urandomm_ui(rs, 2))
        mpz_neg(z, z);
}

/* Fast and MPFR agree on random elements of Q(sqrt(D)) of the sizes the
 * solver produces (and beyond); the fast path must decide most of them. */
static void test_random_elements(void)
{
    gmp_randstate_t rs;
    gmp_randinit_default(rs);
    gmp_randseed_ui(rs, 20261122);
    mpz_t num, b, D, den;
    mpz_inits(num, b, D, den, (mpz_ptr)0);
    int n = 20000, decided = 0, differ = 0, unenclosed = 0;
    for (int i = 0; i < n; i++) {
        rand_z(num, rs, 400, 1);
        rand_z(b, rs, 200, 1);
        rand_z(D, rs, 400, 0);
        do
            rand_z(den, rs, 300, 1);
        while (mpz_sgn(den) == 0);
        double f, flo, fhi, m, mlo, mhi;
        if (!vbx_round_fast(num, b, D, den, &f, &flo, &fhi))
            continue;
        decided++;
        if (vbx_round_mpfr(num, b, D, den, &m, &mlo, &mhi) != VB_OK || !same_bits(f, m))
            differ++;
        /* Both enclose the exact value, so they overlap, and hold the result. */
        if (!(flo <= f && f <= fhi && flo <= mhi && mlo <= fhi))
            unenclosed++;
    }
    CHECK_INT(differ, 0);
    CHECK_INT(unenclosed, 0);
    CHECK(decided > n * 9 / 10);
    mpz_clears(num, b, D, den, (mpz_ptr)0);
    gmp_randclear(rs);
}

/* Random decimal string "-12.345" with `dec` decimals. */
static void rand_decimal(char *buf, size_t len, gmp_randstate_t rs, long range, int dec,
                         long minimum)
{
    long v = minimum + (long)gmp_urandomm_ui(rs, (unsigned long)range);
    int neg = v < 0;
    long a = neg ? -v : v, p = 1;
    for (int k = 0; k < dec; k++)
        p *= 10;
    snprintf(buf, len, "%s%ld.%0*ld", neg ? "-" : "", a / p, dec, a % p);
}

/* The set of n spheres from decimal strings v, a context and its exact
 * data (free with vbx_data_free, vb_close, vb_spheres_free). */
static vb_sphere_set *data_of(size_t n, const char *const *v, vb_ctx **ctx, vbx_data *d)
{
    vb_sphere_set *s = vt_set(n, v);
    CHECK_INT(vb_open(ctx, NULL), VB_OK);
    CHECK_INT(vbx_data_init(*ctx, d, s), VB_OK);
    return s;
}

/* Roots of the tangent solver on random protein-like spheres: the
 * coordinates of vbx_root_coords (fast path first) equal MPFR's bit for bit. */
static void test_random_vertices(void)
{
    gmp_randstate_t rs;
    gmp_randinit_default(rs);
    gmp_randseed_ui(rs, 7);
    enum { N = 40 };
    char str[4 * N][32];
    const char *v[4 * N];
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++)
            rand_decimal(str[4 * i + k], sizeof str[0], rs, 20000, 3, -10000);
        rand_decimal(str[4 * i + 3], sizeof str[0], rs, 800, 2, 100);
        for (int k = 0; k < 4; k++)
            v[4 * i + k] = str[4 * i + k];
    }
    vb_ctx *ctx;
    vbx_data d;
    vb_sphere_set *s = data_of(N, v, &ctx, &d);
    vbx_solver sol;
    vbx_solver_init(&sol, &d);
    mpz_t num, den;
    mpz_inits(num, den, (mpz_ptr)0);
    int coords = 0, differ = 0;
    for (int q = 0; q < 3000; q++) {
        uint32_t id[4];
        for (int k = 0; k < 4; k++)
            id[k] = (uint32_t)gmp_urandomm_ui(rs, N);
        if (id[0] == id[1] || id[0] == id[2] || id[0] == id[3] || id[1] == id[2] ||
            id[1] == id[3] || id[2] == id[3])
            continue;
        if (vbx_solve(&sol, id[0], id + 1) != VBX_SOLVED)
            continue;
        for (int r = 0; r < sol.nroots; r++) {
            const vbx_root *R = &sol.root[r];
            double out[4];
            vbx_ia box[4];
            CHECK_INT(vbx_root_coords(&sol, R, out, box), VB_OK);
            /* The same coordinates through MPFR alone. */
            mpz_mul(den, R->den, d.scale);
            for (int k = 0; k < 4; k++) {
                mpz_mul(num, d.c[4 * (size_t)id[0] + k], R->den);
                if (k < 3)
                    mpz_add(num, num, R->a[k]);
                else
                    mpz_sub(num, R->a[k], num);
                double m, lo, hi;
                CHECK_INT(vbx_round_mpfr(num, R->b[k], sol.delta, den, &m, &lo, &hi), VB_OK);
                coords++;
                differ += !same_bits(m, out[k]) || !(box[k].lo <= m && m <= box[k].hi);
            }
        }
    }
    CHECK_INT(differ, 0);
    CHECK(coords > 1000);
    /* Most coordinates must not need MPFR (the point of the fast path). */
    CHECK(sol.slow_rounds * 10 < (uint64_t)coords);
    mpz_clears(num, den, (mpz_ptr)0);
    vbx_solver_free(&sol);
    vbx_data_free(&d);
    vb_close(ctx);
    vb_spheres_free(s);
    gmp_randclear(rs);
}

/* value = (num + b sqrt(D)) / den with every integer times k (same value,
 * longer integers): rounding through vbx_round, counting MPFR calls. */
static double round_scaled(const char *num, const char *b, const char *D, const char *den,
                           unsigned long k3, int *fast, uint64_t *slow)
{
    mpz_t zn, zb, zD, zd, k;
    mpz_inits(zn, zb, zD, zd, k, (mpz_ptr)0);
    mpz_set_str(zn, num, 10);
    mpz_set_str(zb, b, 10);
    mpz_set_str(zD, D, 10);
    mpz_set_str(zd, den, 10);
    mpz_ui_pow_ui(k, 3, k3);
    mpz_mul(zn, zn, k);
    mpz_mul(zb, zb, k);
    mpz_mul(zd, zd, k);
    double out = 0.0, lo, hi, f;
    *fast = vbx_round_fast(zn, zb, zD, zd, &f, &lo, &hi);
    CHECK_INT(vbx_round(zn, zb, zD, zd, &out, &lo, &hi, slow), VB_OK);
    CHECK(lo <= out && out <= hi);
    mpz_clears(zn, zb, zD, zd, k, (mpz_ptr)0);
    return out;
}

/* Hand-made ties and near ties: the fast path must refuse them and MPFR
 * decide; values just off a tie but resolvable in 64 bits stay fast. */
static void test_near_ties(void)
{
    /* 2^53 = 9007199254740992; 1 + 2^-53 is the midpoint of 1 and 1 + 2^-52. */
    const char *two53 = "9007199254740992", *mid = "9007199254740993";
    /* 2^200 and (2^53 + 1) 2^147: the midpoint over 2^200. */
    const char *two200 = "1606938044258990275541962092341162602522202993782792835301376";
    const char *mid200 = "1606938044258990453947923680586147734807949174969684883144704";
    const double up = 1.0 + 0x1p-52, tiny = -0x1.6a09e667f3bcdp-200; /* -sqrt(2) 2^-200 */
    const char *tie_up = "1606938044258990453947923680586147734807949174969684883144705";
    const char *tie_down = "1606938044258990453947923680586147734807949174969684883144703";
    for (unsigned k3 = 0; k3 <= 60; k3 += 60) {
        uint64_t slow = 0;
        int fast;
        /* Exact tie: ties to even gives 1. */
        CHECK(same_bits(round_scaled(mid, "0", "0", two53, k3, &fast, &slow), 1.0));
        CHECK_INT(fast, 0);
        CHECK_INT((int)slow, 1);
        /* Tie + sqrt(2) 2^-200: up. Tie - sqrt(2) 2^-200: down. */
        CHECK(same_bits(round_scaled(mid200, "1", "2", two200, k3, &fast, &slow), up));
        CHECK_INT(fast, 0);
        CHECK(same_bits(round_scaled(mid200, "-1", "2", two200, k3, &fast, &slow), 1.0));
        CHECK_INT(fast, 0);
        /* Tie + 2^-200 (rational, b = 0) and tie - 2^-200. */
        CHECK(same_bits(round_scaled(tie_up, "0", "0", two200, k3, &fast, &slow), up));
        CHECK_INT(fast, 0);
        CHECK(same_bits(round_scaled(tie_down, "0", "0", two200, k3, &fast, &slow), 1.0));
        CHECK_INT(fast, 0);
        CHECK_INT((int)slow, 5);
        /* Exactly 0 goes to MPFR and is always +0, whatever the form. */
        CHECK(same_bits(round_scaled("0", "0", "5", two53, k3, &fast, &slow), 0.0));
        CHECK_INT(fast, 0);
        CHECK(same_bits(round_scaled("0", "5", "0", two53, k3, &fast, &slow), 0.0));
        CHECK_INT(fast, 0);
        /* -6 + 2 sqrt(9) = 0 exactly: an enclosure end may be -0, the output
         * is +0 (a degenerate vertex's zero must not depend on the quadruple). */
        CHECK(same_bits(round_scaled("-6", "2", "9", two53, k3, &fast, &slow), 0.0));
        CHECK_INT(fast, 0);
        CHECK_INT((int)slow, 8);
        /* Tiny values of both signs next to 0 keep their sign. */
        CHECK(same_bits(round_scaled("0", "-1", "2", two200, k3, &fast, &slow), tiny));
        CHECK(same_bits(round_scaled("-1", "0", "0", two200, k3, &fast, &slow), -0x1p-200));
        /* Tie + 2^-58: 5 bits above the tie, within 64-bit reach: fast, up. */
        CHECK(same_bits(round_scaled("9223372036854776864", "0", "0", "9223372036854775808", k3,
                                     &fast, &slow),
                        up));
        CHECK_INT(fast, 1);
        CHECK_INT((int)slow, 8);
    }
}

/* Heavy cancellation: 10^40 - sqrt(10^80 - 10^41) = 5.000...000125 (the
 * parts agree to 40 digits). The fast path must still decide, through the
 * rationalised form, and agree with MPFR. */
static void test_cancellation(void)
{
    const char *e40 = "10000000000000000000000000000000000000000";
    const char *D = "9999999999999999999999999999999999999990"
                    "0000000000000000000000000000000000000000";
    for (int sign = -1; sign <= 1; sign += 2) {
        mpz_t num, b, zD, den;
        mpz_inits(num, b, zD, den, (mpz_ptr)0);
        mpz_set_str(num, e40, 10);
        mpz_set_si(b, -1);
        mpz_set_str(zD, D, 10);
        mpz_set_si(den, sign);
        double f = 0.0, m = 1.0, lo, hi, mlo, mhi;
        CHECK_INT(vbx_round_fast(num, b, zD, den, &f, &lo, &hi), 1);
        CHECK_INT(vbx_round_mpfr(num, b, zD, den, &m, &mlo, &mhi), VB_OK);
        CHECK(same_bits(f, m));
        CHECK(same_bits(f, sign * 5.0)); /* 5 + 1.25e-40 rounds to 5 */
        /* The same value with num and b negated over -den. */
        mpz_neg(num, num);
        mpz_neg(b, b);
        mpz_neg(den, den);
        CHECK_INT(vbx_round_fast(num, b, zD, den, &f, &lo, &hi), 1);
        CHECK(same_bits(f, m));
        mpz_clears(num, b, zD, den, (mpz_ptr)0);
    }
}

/* The sphere data's enclosures (vbx_data_init: a double path for numbers
 * below 2^53, MPFR beyond) against MPFR at 53 bits directly: the nearest
 * double and the two directed ones, bit for bit, on random decimals of 0
 * to 6 digits after the point (numerators below 2^53: the double path) and
 * on a set with 30-digit decimals (every numerator past 2^53: MPFR), with
 * values that are exact doubles (0.5, -0.25, 0) among them. */
static void test_data_enclosures(void)
{
    gmp_randstate_t rs;
    gmp_randinit_default(rs);
    gmp_randseed_ui(rs, 30);
    enum { N = 400 };
    static char str[4 * N][48];
    const char *v[4 * N];
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < 4 * N; i++) {
            int dec = pass ? (i % 7 == 0 ? 30 : 1) : i % 7;
            long range = 2000000;
            if (dec > 15) {
                snprintf(str[i], sizeof str[i], "%s0.%030lu", i % 2 ? "-" : "",
                         (unsigned long)gmp_urandomm_ui(rs, 1000000000ul));
            } else {
                rand_decimal(str[i], sizeof str[i], rs, range, dec, -range / 2);
                if (dec == 0)
                    snprintf(str[i], sizeof str[i], "%ld",
                             (long)gmp_urandomm_ui(rs, 2000000) - 1000000);
            }
            if (i % 4 == 3 && str[i][0] == '-')
                memmove(str[i], str[i] + 1, strlen(str[i]));
            v[i] = str[i];
        }
        v[0] = "0.5";
        v[1] = "-0.25";
        v[2] = "0";
        vb_ctx *ctx;
        vbx_data d;
        vb_sphere_set *s = data_of(N, v, &ctx, &d);
        mpq_t q;
        mpfr_t f;
        mpq_init(q);
        mpfr_init2(f, 53);
        int differ = 0, exact = 0;
        for (size_t i = 0; i < 4 * (size_t)N; i++) {
            mpq_set_num(q, d.c[i]);
            mpq_set_den(q, d.scale);
            mpq_canonicalize(q);
            mpfr_set_q(f, q, MPFR_RNDD);
            double lo = mpfr_get_d(f, MPFR_RNDD);
            mpfr_set_q(f, q, MPFR_RNDU);
            double hi = mpfr_get_d(f, MPFR_RNDU);
            mpfr_set_q(f, q, MPFR_RNDN);
            double m = mpfr_get_d(f, MPFR_RNDN);
            differ += !same_bits(lo, d.box[i].lo) || !same_bits(hi, d.box[i].hi) ||
                      !same_bits(m, d.near[i]);
            exact += lo == hi;
        }
        CHECK_INT(differ, 0);
        CHECK(exact >= 3);
        mpfr_clear(f);
        mpq_clear(q);
        vbx_data_free(&d);
        vb_close(ctx);
        vb_spheres_free(s);
    }
    gmp_randclear(rs);
}

int main(void)
{
    test_data_enclosures();
    test_cancellation();
    test_random_elements();
    test_random_vertices();
    test_near_ties();
    VB_TEST_END();
}
