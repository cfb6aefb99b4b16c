/* The tie cluster's rank test (core/cells/vbq_cluster.h): the checked
 * 128-bit path must give GMP's answer (decided, rank, the same first
 * independent labels in list order) on clusters of every kind, and give
 * way to GMP where its numbers do not fit; the modular proof of rank >= 4
 * (cluster_modp.c) must find every list GMP leaves undecided here and
 * claim no cluster. */
#include <stdint.h>

#include "vb_test.h"
#include "vb_test_spheres.h"
#include "vbq_cluster.h"

static uint64_t rng = 88172645463325252ull;
static int modp_proved; /* lists vbq_cluster_modp proved of rank >= 4 */

static uint32_t next(uint32_t n)
{
    vb_test_xorshift(&rng);
    return (uint32_t)(rng % n);
}

/* Sphere k: centre p * 10^e + the shift (10.25, -3.7, 0.125), radius r. */
static void put(vb_sphere_set *s, size_t k, const int64_t p[3], int32_t e, int64_t r)
{
    /* the shift in units of 10^e (e <= -3) */
    int64_t sc = 1;
    for (int32_t a = e; a < -3; a++)
        sc *= 10;
    const int64_t sh[3] = {10250 * sc, -3700 * sc, 125 * sc};
    vb_decimal *c[3] = {s->ex, s->ey, s->ez};
    for (int a = 0; a < 3; a++)
        c[a][k] = (vb_decimal){p[a] + sh[a], e};
    s->er[k] = (vb_decimal){r, e};
}

/* Both paths on base i and labels ids; checks they agree. Returns the
 * answer (small's when it fit); *fit says whether it did. */
static vbq_cluster_ans both(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                            int *fit)
{
    int32_t emin = vbq_cluster_emin(s, i, ids, n);
    vbq_cluster_ans g, f;
    vbq_cluster_gmp(s, i, ids, n, emin, &g);
    *fit = vbq_cluster_small(s, i, ids, n, emin, &f);
    /* rank 4 modulo p proves GMP's decided = 0; it proves nothing else */
    int modp = vbq_cluster_modp(s, i, ids, n, emin);
    if (modp)
        CHECK_INT(g.decided, 0);
    modp_proved += modp;
    if (!*fit)
        return g;
    CHECK_INT(f.decided, g.decided);
    if (f.decided && g.decided) {
        CHECK_INT(f.nbasis, g.nbasis);
        for (int r = 0; r < f.nbasis && r < g.nbasis; r++)
            CHECK_INT(f.id[r], g.id[r]);
    }
    return f;
}

/* Labels: a random order of 1 .. m-1 (sphere 0 is the base), at most n. */
static uint32_t labels(uint32_t m, uint32_t *ids, uint32_t n)
{
    for (uint32_t k = 0; k + 1 < m; k++)
        ids[k] = k + 1;
    for (uint32_t k = m - 2; k > 0; k--) {
        uint32_t j = next(k + 1), t = ids[k];
        ids[k] = ids[j];
        ids[j] = t;
    }
    return m - 1 < n ? m - 1 : n;
}

int main(void)
{
    enum { M = 200 };
    uint32_t ids[M];
    int fit, count[4] = {0, 0, 0, 0}; /* rank <= 2, rank 3, undecided, not fit */

    /* (a) equal balls centred on one sphere through the base's centre:
     * the vectors (D, 0, |D|^2 = 2 m.D) span three dimensions, decided
     * with three labels; (b) on a circle through it: two. */
    for (int trial = 0; trial < 200; trial++) {
        vb_sphere_set *s = vb_test_spheres_alloc(M, 1);
        /* integer points of x^2 + y^2 + z^2 = 11^2 (121 = 9^2+6^2+2^2 ...) */
        int64_t pts[200][3];
        uint32_t np = 0;
        for (int x = -11; x <= 11; x++)
            for (int y = -11; y <= 11; y++)
                for (int z = -11; z <= 11; z++)
                    if (x * x + y * y + z * z == 121 && (trial % 2 == 0 || z == 0) && np < 200) {
                        pts[np][0] = x;
                        pts[np][1] = y;
                        pts[np][2] = z;
                        np++;
                    }
        int64_t unit = 1000 + next(9000); /* spacing in thousandths */
        uint32_t b = next(np), m = 1;     /* a random point as the base */
        for (uint32_t k = 0; k < np; k++) {
            int64_t p[3] = {pts[k][0] * unit, pts[k][1] * unit, pts[k][2] * unit};
            put(s, k == b ? 0 : m++, p, -3, 1500);
        }
        uint32_t n = labels(np, ids, M);
        uint32_t want = 6 + next(40);
        n = n < want ? n : want;
        vbq_cluster_ans a = both(s, 0, ids, n, &fit);
        CHECK(fit);
        CHECK_INT(a.decided, 1);
        CHECK_INT(a.nbasis, trial % 2 == 0 ? 3 : 2);
        CHECK_INT(modp_proved, 0);
        count[a.nbasis == 3 ? 1 : 0]++;
        vb_spheres_free(s);
    }

    /* (c) random balls: rank 4, undecided; (d) one label touching the
     * base from inside (N = 0): undecided; with a few decimals more (up to
     * 12) both still agree. */
    for (int trial = 0; trial < 300; trial++) {
        vb_sphere_set *s = vb_test_spheres_alloc(40, 1);
        int32_t e = -3 - (int32_t)(trial % 10);
        int64_t sc = 1;
        for (int32_t a = e; a < -3; a++)
            sc *= 10;
        for (uint32_t k = 0; k < 40; k++) {
            int64_t p[3] = {(int64_t)next(20000) * sc + next(1000), (int64_t)next(20000) * sc,
                            (int64_t)next(20000) * sc};
            put(s, k, p, e, (1000 + next(1000)) * sc);
        }
        if (trial % 3 == 0) { /* sphere 5 inside the base, touching it */
            int64_t p[3] = {s->ex[0].mant - 10250 * sc + 500 * sc, s->ey[0].mant + 3700 * sc,
                            s->ez[0].mant - 125 * sc};
            s->er[0].mant = 2000 * sc;
            put(s, 5, p, e, 1500 * sc);
        }
        uint32_t n = labels(40, ids, 39);
        vbq_cluster_ans a = both(s, 0, ids, n, &fit);
        CHECK(fit || e < -5); /* 2^24 and more: the last test overflows */
        CHECK_INT(a.decided, 0);
        CHECK_INT(modp_proved, trial + 1); /* rank 5 of random balls: proved */
        count[2]++;
        vb_spheres_free(s);
    }

    /* (e) numbers past 128 bits: 18-digit coordinates, or exponents 20
     * apart; GMP answers (and agrees where the small path still fits). */
    {
        vb_sphere_set *s = vb_test_spheres_alloc(8, 1);
        for (uint32_t k = 0; k < 8; k++) {
            int64_t p[3] = {(int64_t)next(1000000) * 1000000000000ll + next(1000),
                            (int64_t)next(1000000) * 1000000000000ll,
                            (int64_t)next(1000000) * 1000000000000ll};
            put(s, k, p, -3, 1000);
        }
        for (uint32_t k = 0; k < 7; k++)
            ids[k] = k + 1;
        vbq_cluster_ans a = both(s, 0, ids, 7, &fit);
        CHECK(!fit);
        CHECK_INT(a.decided, 0);
        count[3]++;
        s->ex[3] = (vb_decimal){1, 17}; /* 10^17 at exponent 20 below the rest */
        s->ex[0].exp10 = -3;
        a = both(s, 0, ids, 7, &fit);
        CHECK(!fit);
        vb_spheres_free(s);
    }
    /* (f) 15-digit decimals (past the 128-bit path): (a)'s cluster at
     * 10^-15 is one (GMP: rank 3, no modular proof), and the same points
     * jittered in their last digits, as sc16_j12 is, are not (rank 5:
     * proved modulo p, GMP agrees). */
    for (int jit = 0; jit < 2; jit++) {
        vb_sphere_set *s = vb_test_spheres_alloc(M, 1);
        uint32_t m = 0;
        for (int x = -11; x <= 11; x++)
            for (int y = -11; y <= 11; y++)
                for (int z = -11; z <= 11; z++)
                    if (x * x + y * y + z * z == 121 && m < M) {
                        int64_t u = 1234567890123ll; /* 1.234... at 10^-12 */
                        int64_t p[3] = {x * u, y * u, z * u};
                        for (int a = 0; a < 3 && jit; a++)
                            p[a] += (int64_t)next(2001) - 1000;
                        put(s, m++, p, -15, 1500000000000000ll);
                    }
        uint32_t n = labels(m, ids, 30);
        int before = modp_proved;
        vbq_cluster_ans a = both(s, 0, ids, n, &fit);
        CHECK(!fit);
        CHECK_INT(a.decided, jit ? 0 : 1);
        CHECK_INT(modp_proved - before, jit);
        if (!jit)
            CHECK_INT(a.nbasis, 3);
        vb_spheres_free(s);
    }
    /* every kind was met */
    CHECK(count[0] > 50 && count[1] > 50 && count[2] == 300 && count[3] == 1);
    VB_TEST_END();
}
