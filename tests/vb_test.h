/* Minimal test harness: CHECK macros count passes and failures; VB_TEST_END
 * prints the closing "N passed, N failed" line and returns the exit code. */
#ifndef VB_TEST_H
#define VB_TEST_H
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int vb_test_passed, vb_test_failed;

/* The tests' one pseudo-random step: Marsaglia's xorshift64 (13, 7, 17) on
 * *s (never 0), returned; the same seed gives the same sequence anywhere. */
static inline uint64_t vb_test_xorshift(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

/* A double uniform in [lo, hi) from the next step of *s (53 random bits). */
static inline double vb_test_uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (double)(vb_test_xorshift(s) >> 11) * 0x1p-53;
}

/* A signed double from the next step of *s over binades lo .. lo + span - 1,
 * exactly 0 one time in 16 (interval arithmetic's random operands). */
static inline double vb_test_binades(uint64_t *s, int lo, int span)
{
    vb_test_xorshift(s);
    return (*s & 15) == 0 ? 0.0 : ldexp((double)(*s >> 11) * 0x1p-53 - 0.5, (int)(*s % (uint64_t)span) + lo);
}

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (cond) {                                                                  \
            vb_test_passed++;                                                        \
        } else {                                                                     \
            vb_test_failed++;                                                        \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                            \
    } while (0)

#define CHECK_INT(a, b)                                                                    \
    do {                                                                                   \
        long long va_ = (long long)(a), vb_ = (long long)(b);                              \
        if (va_ == vb_) {                                                                  \
            vb_test_passed++;                                                              \
        } else {                                                                           \
            vb_test_failed++;                                                              \
            fprintf(stderr, "%s:%d: %s == %lld, expected %s == %lld\n", __FILE__, __LINE__, \
                    #a, va_, #b, vb_);                                                     \
        }                                                                                  \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                  \
    do {                                                                                       \
        double va_ = (a), vb_ = (b);                                                           \
        if (fabs(va_ - vb_) <= (tol)) {                                                        \
            vb_test_passed++;                                                                  \
        } else {                                                                               \
            vb_test_failed++;                                                                  \
            fprintf(stderr, "%s:%d: %s = %.17g, expected %.17g (tol %g)\n", __FILE__, __LINE__, \
                    #a, va_, vb_, (double)(tol));                                              \
        }                                                                                      \
    } while (0)

#define CHECK_STR(a, b)                                                                        \
    do {                                                                                       \
        const char *va_ = (a), *vb_ = (b);                                                     \
        if (va_ && vb_ && strcmp(va_, vb_) == 0) {                                             \
            vb_test_passed++;                                                                  \
        } else {                                                                               \
            vb_test_failed++;                                                                  \
            fprintf(stderr, "%s:%d: %s = \"%s\", expected \"%s\"\n", __FILE__, __LINE__, #a,   \
                    va_ ? va_ : "(null)", vb_ ? vb_ : "(null)");                               \
        }                                                                                      \
    } while (0)

/* The whole file at path, NUL-terminated (malloc'ed), or NULL. */
static inline char *vb_test_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = n >= 0 ? malloc((size_t)n + 1) : NULL;
    size_t got = b ? fread(b, 1, (size_t)n, f) : 0;
    if (b)
        b[got] = '\0';
    fclose(f);
    return b;
}

#define VB_TEST_END()                                                        \
    do {                                                                     \
        printf("%d passed, %d failed\n", vb_test_passed, vb_test_failed);    \
        return vb_test_failed ? 1 : (vb_test_passed ? 0 : 1);               \
    } while (0)
#endif
