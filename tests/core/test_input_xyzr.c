/* Unit tests of the input layer, part 1: exact decimals, the XYZR reader,
 * validation (every error class by code and line, exact containment) and the
 * CLI input options. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "vb_spheres.h"
#include "input_test_util.h"

static void test_decimal(void)
{
    vb_decimal e;
    double d;
    CHECK_INT(vb_decimal_parse("17.047", 6, &e, &d), VB_OK);
    CHECK_DEC(e, 17047, -3);
    CHECK(d == 17.047);
    CHECK_INT(vb_decimal_parse("-0.500", 6, &e, &d), VB_OK);
    CHECK_DEC(e, -5, -1);
    CHECK(d == -0.5);
    CHECK_INT(vb_decimal_parse("1.0e1", 5, &e, &d), VB_OK);
    CHECK_DEC(e, 1, 1);
    CHECK(d == 10.0);
    CHECK_INT(vb_decimal_parse("-0.000", 6, &e, &d), VB_OK);
    CHECK_DEC(e, 0, 0);
    CHECK_INT(vb_decimal_parse(".5", 2, &e, &d), VB_OK);
    CHECK_DEC(e, 5, -1);
    CHECK_INT(vb_decimal_parse("+5.", 3, &e, &d), VB_OK);
    CHECK_DEC(e, 5, 0);
    CHECK_INT(vb_decimal_parse("2.5E-3", 6, &e, &d), VB_OK);
    CHECK_DEC(e, 25, -4);
    CHECK(d == 0.0025);
    /* 18 significant digits are fine, trailing zeros do not count. */
    CHECK_INT(vb_decimal_parse("12345678901234567800", 20, &e, &d), VB_OK);
    CHECK_DEC(e, 123456789012345678LL, 2);
    CHECK_INT(vb_decimal_parse("0.1234567890123456789", 21, &e, &d), VB_EINPUT_MAGNITUDE);
    CHECK_INT(vb_decimal_parse("1e400", 5, &e, &d), VB_EINPUT_MAGNITUDE);
    CHECK_INT(vb_decimal_parse("nan", 3, &e, &d), VB_EINPUT_NONFINITE);
    CHECK_INT(vb_decimal_parse("-Inf", 4, &e, &d), VB_EINPUT_NONFINITE);
    CHECK_INT(vb_decimal_parse("infinity", 8, &e, &d), VB_EINPUT_NONFINITE);
    CHECK_INT(vb_decimal_parse("1e", 2, &e, &d), VB_EINPUT_MALFORMED);
    CHECK_INT(vb_decimal_parse("0x10", 4, &e, &d), VB_EINPUT_MALFORMED);
    CHECK_INT(vb_decimal_parse("1.2.3", 5, &e, &d), VB_EINPUT_MALFORMED);
    CHECK_INT(vb_decimal_parse("-", 1, &e, &d), VB_EINPUT_MALFORMED);
    /* The length bounds the token: "1.5x" read as 3 characters is 1.5. */
    CHECK_INT(vb_decimal_parse("1.5x", 3, &e, &d), VB_OK);
    CHECK_DEC(e, 15, -1);

    vb_decimal a = {17, -1}, b = {170, -2}, c = {-2, 0}, t = {11, -2}, u = {1, -1};
    CHECK_INT(vb_decimal_cmp(a, b), 0);
    CHECK_INT(vb_decimal_cmp(c, a), -1);
    CHECK_INT(vb_decimal_cmp(t, u), 1);
    CHECK_INT(vb_decimal_cmp((vb_decimal){-11, -2}, (vb_decimal){-1, -1}), -1);
    CHECK_INT(vb_decimal_cmp((vb_decimal){1, 1}, (vb_decimal){999, -2}), 1);
    CHECK_INT(vb_decimal_cmp((vb_decimal){0, 0}, (vb_decimal){-1, -300}), 1);
}

/* vb_decimal_double and vb_decimal_parse's double (a fast path for short
 * mantissas and small exponents, strtod past it) against strtod of the
 * same value, bit for bit: random mantissas of 1 to 18 digits, exponents
 * -30 to 30 (both sides of the fast path's 2^53 and 10^22 edges), and the
 * edges themselves. */
static void test_decimal_double(void)
{
    uint64_t x = 88172645463325252ull;
    size_t bad = 0, fast = 0;
    for (int t = 0; t < 200000; t++) {
        vb_test_xorshift(&x);
        int digits = 1 + (int)(x % 18);
        int64_t m = (int64_t)((x >> 8) % 1000000000000000000ull);
        for (int k = digits; k < 18; k++)
            m /= 10;
        if (t % 3 == 0)
            m = -m;
        int32_t e10 = (int32_t)((x >> 40) % 61) - 30;
        if (t < 8) { /* the edges: 2^53 and 2^53 + 1, 10^+-22 and 10^+-23 */
            m = (int64_t)((1ull << 53) + (uint64_t)(t & 1));
            e10 = (t & 2 ? 1 : -1) * (22 + (t >> 2));
        }
        char buf[64];
        snprintf(buf, sizeof buf, "%lldE%d", (long long)m, (int)e10);
        double want = strtod(buf, NULL), got = vb_decimal_double((vb_decimal){m, e10});
        vb_decimal e;
        double d = 0.0;
        int rc = vb_decimal_parse(buf, strlen(buf), &e, &d);
        bad += memcmp(&want, &got, sizeof want) != 0;
        bad += rc == VB_OK && memcmp(&want, &d, sizeof want) != 0;
        fast += m != 0 && e10 >= -22 && e10 <= 22 && (m < 0 ? -m : m) <= (int64_t)1 << 53;
    }
    CHECK_INT(bad, 0);
    CHECK(fast > 50000);
    /* A zero keeps its text's sign. */
    vb_decimal e;
    double d = 1.0;
    CHECK_INT(vb_decimal_parse("-0.00", 5, &e, &d), VB_OK);
    CHECK(d == 0.0 && signbit(d));
}

static void test_xyzr(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_sphere_set *s = NULL;
    const char *text = "# x y z r\r\n"
                       "1.5 -2.25 3 1.70\r\n"
                       "\n"
                       "  0.1\t0.2 0.3 2.0e-1 # 17 B 42 GLY CA A .\n"
                       "10 20 30 1.2 # free-form note\n";
    CHECK_INT(read_text(ctx, "t.xyzr", text, NULL, &s), VB_OK);
    CHECK_INT(s->n, 3);
    CHECK_STR(s->source, "t.xyzr");
    CHECK_DEC(s->ex[0], 15, -1);
    CHECK_DEC(s->ey[0], -225, -2);
    CHECK_DEC(s->ez[0], 3, 0);
    CHECK_DEC(s->er[0], 17, -1);
    CHECK(s->x[0] == 1.5 && s->y[0] == -2.25 && s->z[0] == 3.0 && s->r[0] == 1.7);
    CHECK_DEC(s->er[1], 2, -1);
    CHECK(s->r[1] == 0.2);
    CHECK_INT(s->line[0], 2);
    CHECK_INT(s->line[1], 4);
    CHECK_INT(s->line[2], 5);
    CHECK(s->info != NULL);
    CHECK_INT(s->info[1].serial, 17);
    CHECK_STR(s->info[1].chain, "B");
    CHECK_INT(s->info[1].resseq, 42);
    CHECK_STR(s->info[1].resname, "GLY");
    CHECK_STR(s->info[1].name, "CA");
    CHECK_INT(s->info[1].altloc, 'A');
    CHECK_INT(s->info[1].icode, ' ');
    CHECK_STR(s->info[2].name, "");
    vb_spheres_free(s);

    /* Plain XYZR has no atom records. */
    CHECK_INT(read_text(ctx, "p", "0 0 0 1\n", NULL, &s), VB_OK);
    CHECK(s->info == NULL);
    vb_spheres_free(s);
    vb_close(ctx);
}

static const char four[] = "0 0 0 1\n3 0 0 1\n0 3 0 1\n0 0 3 1\n";

static void test_errors(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    int rc;
    rc = read_validate(ctx, "m", "0 0 0 1\n0 0 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MALFORMED, "m:2:");
    rc = read_validate(ctx, "m", "0 0 0 1\n\n1 1 1 1 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MALFORMED, "m:3:");
    rc = read_validate(ctx, "m", "0 0 0 1\n1 1 x 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MALFORMED, "m:2:");
    rc = read_validate(ctx, "n", "0 0 0 1\n1 1 1 1\n2 NaN 2 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_NONFINITE, "n:3:");
    rc = read_validate(ctx, "n", "0 0 0 inf\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_NONFINITE, "n:1:");
    rc = read_validate(ctx, "r", "0 0 0 1\n1 1 1 0.0\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_RADIUS, "r:2:");
    rc = read_validate(ctx, "r", "0 0 0 1\n1 1 1 1\n# c\n5 5 5 -1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_RADIUS, "r:4:");
    /* Duplicates are decided on the decimals: 1.50 and 1.5e0 are equal. */
    rc = read_validate(ctx, "d", "0 0 0 1\n1 2 3 1.5\n4 4 4 1\n1.0 2 3.00 1.5e0\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_DUPLICATE, "d:4:");
    CHECK(strstr(vb_errmsg(ctx), "line 2") != NULL);
    /* Three copies: the first pair met reading top down is named. */
    rc = read_validate(ctx, "d", "1 1 1 1\n0 0 0 2\n1 1 1 1\n1 1 1 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_DUPLICATE, "d:3:");
    CHECK(strstr(vb_errmsg(ctx), "line 1") != NULL);
    rc = read_validate(ctx, "e", "", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_EMPTY, "e:");
    rc = read_validate(ctx, "e", "# only a comment\n\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_EMPTY, "e:");
    o.format = VB_FMT_XYZR;
    rc = read_validate(ctx, "e", "# only a comment\n", &o, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_EMPTY, "e:");
    rc = read_validate(ctx, "f", "0 0 0 1\n3 0 0 1\n0 3 0 1\n", NULL, 4);
    CHECK_ERROR(ctx, rc, VB_EINPUT_TOOFEW, "f:");
    CHECK_INT(read_validate(ctx, "f", four, NULL, 4), VB_OK);
    rc = read_validate(ctx, "g", "0 0 0 1\n0 0 1000000001 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MAGNITUDE, "g:2:");
    rc = read_validate(ctx, "g", "0 0 0 1\n-1e9 0 0 1000000.5\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MAGNITUDE, "g:2:");
    CHECK_INT(read_validate(ctx, "g", "-1e9 1e9 0 1e6\n", NULL, 1), VB_OK);
    rc = read_validate(ctx, "g", "0 0 0 1\n0 0 0.1234567890123456789 1\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MAGNITUDE, "g:2:");
    rc = read_validate(ctx, "u", "hello world\n", NULL, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_FORMAT, "u:");
    o.max_spheres = 2;
    rc = read_validate(ctx, "l", four, &o, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_TOOLARGE, "l:3:");
    o.max_spheres = 0;
    o.model = 2;
    rc = read_validate(ctx, "x", four, &o, 1);
    CHECK_ERROR(ctx, rc, VB_EINPUT_MODEL, "x:");
    o.model = 1;
    CHECK_INT(read_validate(ctx, "x", four, &o, 1), VB_OK);
    vb_close(ctx);
}

static void test_contained(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_sphere_set *s = NULL;
    /* Sphere 1 touches sphere 0 from inside: 0.1 + 0.2 = 0.3 holds for the
     * decimals, while in doubles 0.1 + 0.2 > 0.3; only the exact test sees
     * it. Sphere 2 is a hair too large to fit; sphere 4 fits with room. */
    const char *text = "0 0 0 0.3\n"
                       "0.1 0 0 0.2\n"
                       "-0.1 0 0 0.2000000000000001\n"
                       "5 5 5 1\n"
                       "5 5 5.5 0.25\n";
    CHECK_INT(read_text(ctx, "c", text, NULL, &s), VB_OK);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    /* Touching from inside is not containment: the cell of sphere 1 is a
     * point or a segment that can end at a vertex, so it stays (W722). */
    CHECK_INT(s->contained[0], 0);
    CHECK_INT(s->contained[1], 0);
    CHECK_INT(s->contained[2], 0);
    CHECK_INT(s->contained[3], 0);
    CHECK_INT(s->contained[4], 1);
    CHECK(vb_ctx_stats(ctx)->exact_evals >= 2);
    const char *w = diag_text(diag);
    CHECK(strstr(w, "W722: c:2: sphere 1 touches sphere 0 (line 1) from inside") != NULL);
    CHECK(strstr(w, "W701: c:2:") == NULL);
    CHECK(strstr(w, "W701: c:5: sphere 4 lies inside sphere 3 (line 4)") != NULL);
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 2);
    vb_spheres_free(s);

    /* Many contained spheres: ten named, then one summary line (W702). */
    char big[4096] = "0 0 0 100\n";
    for (int i = 1; i <= 12; i++) {
        char line[64];
        snprintf(line, sizeof line, "%d 0 0 1\n", i);
        strcat(big, line);
    }
    vb_stats *st = vb_ctx_stats(ctx);
    st->warnings = 0;
    CHECK_INT(read_text(ctx, "many", big, NULL, &s), VB_OK);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    size_t count = 0;
    for (size_t i = 0; i < s->n; i++)
        count += s->contained[i];
    CHECK_INT(count, 12);
    CHECK_INT(st->warnings, 11);
    CHECK(strstr(diag_text(diag), "W702: many: 12 spheres in all lie inside another sphere") !=
          NULL);
    vb_spheres_free(s);

    /* Twelve spheres touching one from inside (six of radius 1 at 99, six
     * of radius 2 at 98 along the axes): none contained, ten named (W722),
     * one count (W723). */
    strcpy(big, "0 0 0 100\n");
    for (int i = 0; i < 12; i++) {
        char line[64];
        int r = i < 6 ? 1 : 2, a = i % 3, sg = (i / 3) % 2 ? -1 : 1;
        int d = sg * (100 - r);
        snprintf(line, sizeof line, "%d %d %d %d\n", a == 0 ? d : 0, a == 1 ? d : 0,
                 a == 2 ? d : 0, r);
        strcat(big, line);
    }
    st->warnings = 0;
    CHECK_INT(read_text(ctx, "touch", big, NULL, &s), VB_OK);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    count = 0;
    for (size_t i = 0; i < s->n; i++)
        count += s->contained[i];
    CHECK_INT(count, 0);
    CHECK_INT(st->warnings, 11);
    CHECK(strstr(diag_text(diag), "W723: touch: 12 spheres in all touch a larger sphere from inside") !=
          NULL);
    vb_spheres_free(s);
    fclose(diag);
    vb_close(ctx);
}

/* A lattice of 40^3 unit spheres plus a small sphere inside each of the
 * first 1000: the grid finds exactly those, and the number of pairs tested
 * stays proportional to n (an all-pairs test would make 2 * 10^9). */
static void test_contained_grid(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    size_t n = 40 * 40 * 40 + 1000;
    size_t len = n * 32 + 1;
    char *text = malloc(len), *p = text;
    for (int i = 0; i < 40; i++)
        for (int j = 0; j < 40; j++)
            for (int k = 0; k < 40; k++)
                p += sprintf(p, "%d %d %d 1\n", 3 * i, 3 * j, 3 * k);
    for (int t = 0; t < 1000; t++)
        p += sprintf(p, "%d.25 %d %d 0.5\n", 3 * (t % 40), 3 * (t / 40 % 40), 3 * (t / 1600));
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_read_buffer(ctx, "grid", text, (size_t)(p - text), NULL, &s), VB_OK);
    CHECK_INT(s->n, n);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    size_t count = 0;
    for (size_t i = 0; i < s->n; i++)
        count += s->contained[i];
    CHECK_INT(count, 1000);
    CHECK_INT(s->contained[64000], 1);
    /* Each sphere meets only its neighbourhood: far below n^2 / 2 tests. */
    CHECK(vb_ctx_stats(ctx)->filter_calls < 20 * n);
    vb_spheres_free(s);
    free(text);
    vb_close(ctx);
}

/* The one read-and-check call every command uses (the option parsing of
 * the CLI is tested through the command: tests/pipeline/input_options.sh). */
static void test_load(void)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_ctx *ctx = open_ctx(NULL);
    const char *path = temp_file(four);
    char path_copy[64];
    strcpy(path_copy, path);
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_load(ctx, path_copy, &ro, NULL, 4, &s), VB_OK);
    CHECK(s && s->n == 4 && s->contained && s->contained[3] == 0);
    vb_spheres_free(s);
    CHECK_ERROR(ctx, vb_spheres_load(ctx, path_copy, &ro, NULL, 5, &s), VB_EINPUT_TOOFEW, path_copy);
    CHECK(s == NULL);
    CHECK_ERROR(ctx, vb_spheres_load(ctx, path_copy, &ro, "/nonexistent/radii.txt", 4, &s), VB_EIO,
                "/nonexistent/radii.txt");
    CHECK_ERROR(ctx, vb_spheres_load(ctx, "/nonexistent/in.xyzr", &ro, NULL, 4, &s), VB_EIO,
                "/nonexistent/in.xyzr");
    remove(path_copy);
    vb_close(ctx);
}

int main(void)
{
    test_decimal();
    test_decimal_double();
    test_xyzr();
    test_errors();
    test_contained();
    test_contained_grid();
    test_load();
    VB_TEST_END();
}
