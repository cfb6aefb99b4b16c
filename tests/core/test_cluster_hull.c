/* The decision of a tie cluster of affine rank 3 (core/cells/cluster_hull.c)
 * against a brute force in GMP: spheres tangent to one sphere with unequal
 * radii, seen from one of them; the triples it writes must be exactly those
 * whose plane supports the labels' points, found here with 5x5 determinants
 * [V_a; V_b; V_c; V_m; e] (e a random vector off the labels' hyperplane;
 * fraction-free elimination), not with the file's dropped column. Sets of
 * another rank are not decided. */
#include <gmp.h>
#include <stdint.h>
#include <stdlib.h>

#include "vb_test.h"
#include "vb_test_spheres.h"
#include "vbq_cluster.h"

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static uint32_t next(uint32_t n)
{
    vb_test_xorshift(&rng);
    return (uint32_t)(rng % n);
}

/* The sign of det[r_0; ..; r_4] (Bareiss; the rows are copied). */
static int det5_sign(mpz_t r[5][5])
{
    mpz_t a[5][5], t, prev;
    mpz_init(t);
    mpz_init_set_ui(prev, 1);
    for (int x = 0; x < 5; x++)
        for (int y = 0; y < 5; y++)
            mpz_init_set(a[x][y], r[x][y]);
    int sign = 1, zero = 0;
    for (int k = 0; k < 4 && !zero; k++) {
        int p = k;
        while (p < 5 && !mpz_sgn(a[p][k]))
            p++;
        if (p == 5) {
            zero = 1;
            break;
        }
        if (p != k) {
            for (int y = 0; y < 5; y++)
                mpz_swap(a[p][y], a[k][y]);
            sign = -sign;
        }
        for (int x = k + 1; x < 5; x++) {
            for (int y = k + 1; y < 5; y++) {
                mpz_mul(t, a[x][y], a[k][k]);
                mpz_submul(t, a[x][k], a[k][y]);
                mpz_divexact(a[x][y], t, prev);
            }
            mpz_set_ui(a[x][k], 0);
        }
        mpz_set(prev, a[k][k]);
    }
    int s = zero ? 0 : sign * mpz_sgn(a[4][4]);
    for (int x = 0; x < 5; x++)
        for (int y = 0; y < 5; y++)
            mpz_clear(a[x][y]);
    mpz_clear(t);
    mpz_clear(prev);
    return s;
}

/* Sphere k: centre (10.25, -3.7, 0.125) + q p at 10^-2 (p integer, |p| =
 * 11), radius 11 q - 9.5: tangent to the sphere of radius 9.5 there. */
static void put(vb_sphere_set *s, uint32_t k, const int p[3], int q100)
{
    const int64_t c0[3] = {1025, -370, 125};
    vb_decimal *c[3] = {s->ex, s->ey, s->ez};
    for (int a = 0; a < 3; a++)
        c[a][k] = (vb_decimal){c0[a] + (int64_t)q100 * p[a], -2};
    s->er[k] = (vb_decimal){11 * q100 - 950, -2};
}

static int cmp3(const void *x, const void *y)
{
    const uint32_t *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

int main(void)
{
    int pts[200][3], np = 0;
    for (int x = -11; x <= 11; x++)
        for (int y = -11; y <= 11; y++)
            for (int z = -11; z <= 11; z++)
                if (x * x + y * y + z * z == 121 && np < 200) {
                    pts[np][0] = x;
                    pts[np][1] = y;
                    pts[np][2] = z;
                    np++;
                }
    const int qs[4] = {100, 105, 110, 120};
    int decided = 0, facets = 0;
    for (int trial = 0; trial < 30; trial++) {
        uint32_t n = 6 + next(14), m = n + 1;
        vb_sphere_set *s = vb_test_spheres_alloc(m, 1);
        uint32_t used[64], ids[64];
        for (uint32_t k = 0; k < m; k++) {
            uint32_t p;
            int again;
            do { /* distinct points */
                p = next((uint32_t)np);
                again = 0;
                for (uint32_t j = 0; j < k; j++)
                    again |= used[j] == p;
            } while (again);
            used[k] = p;
            put(s, k, pts[p], qs[trial % 3 == 0 ? 0 : next(4)]);
        }
        for (uint32_t k = 0; k < n; k++)
            ids[k] = k + 1;
        int32_t emin = vbq_cluster_emin(s, 0, ids, n);
        uint32_t *tri = NULL;
        size_t cap = 0, nt = 0;
        int rc = vbq_cluster_hull(s, 0, ids, n, emin, &tri, &cap, &nt);
        /* equal radii (every third trial): the points lie on a plane, rank 3 */
        int equal = 1;
        for (uint32_t k = 1; k < m; k++)
            equal &= s->er[k].mant == s->er[0].mant;
        if (equal) {
            CHECK_INT(rc, 0);
        } else {
            CHECK_INT(rc, 1);
            /* the brute force */
            int64_t ci[4];
            vbq_i128 V[64][5];
            CHECK(vbq_cluster_scaled4(s, 0, emin, ci));
            for (uint32_t k = 0; k < n; k++)
                CHECK(vbq_cluster_vector(s, ids[k], emin, ci, V[k]));
            mpz_t r[5][5];
            for (int x = 0; x < 5; x++)
                for (int y = 0; y < 5; y++)
                    mpz_init(r[x][y]);
            int64_t e[5];
            for (int y = 0; y < 5; y++)
                e[y] = (int64_t)next(2000001) - 1000000;
            uint32_t *want = malloc(3 * 2000 * sizeof *want);
            size_t nw = 0;
            for (uint32_t a = 0; a < n; a++)
                for (uint32_t b = a + 1; b < n; b++)
                    for (uint32_t c = b + 1; c < n; c++) {
                        const uint32_t abc[3] = {a, b, c};
                        int pos = 0, neg = 0, indep = 0;
                        for (uint32_t q = 0; q < n; q++) {
                            if (q == a || q == b || q == c)
                                continue;
                            for (int x = 0; x < 4; x++)
                                for (int y = 0; y < 5; y++) {
                                    vbq_i128 w = x < 3 ? V[abc[x]][y] : V[q][y];
                                    mpz_set_si(r[x][y], (long)(int64_t)(w >> 32));
                                    mpz_mul_2exp(r[x][y], r[x][y], 32);
                                    mpz_add_ui(r[x][y], r[x][y], (unsigned long)(uint32_t)w);
                                }
                            for (int y = 0; y < 5; y++)
                                mpz_set_si(r[4][y], (long)e[y]);
                            int sg = det5_sign(r);
                            pos |= sg > 0;
                            neg |= sg < 0;
                            indep |= sg != 0;
                        }
                        if (indep && !(pos && neg)) {
                            want[3 * nw] = ids[a];
                            want[3 * nw + 1] = ids[b];
                            want[3 * nw + 2] = ids[c];
                            nw++;
                        }
                    }
            for (int x = 0; x < 5; x++)
                for (int y = 0; y < 5; y++)
                    mpz_clear(r[x][y]);
            qsort(want, nw, 3 * sizeof *want, cmp3);
            if (tri)
                qsort(tri, nt, 3 * sizeof *tri, cmp3);
            CHECK_INT(nt, nw);
            int same = nt == nw;
            for (size_t k = 0; same && k < 3 * nt; k++)
                same = tri[k] == want[k];
            CHECK(same);
            decided++;
            facets += (int)nt;
            free(want);
            /* one label moved off the sphere by 0.01: rank 5, not decided */
            s->ex[3].mant += 1;
            CHECK_INT(vbq_cluster_hull(s, 0, ids, n, emin, &tri, &cap, &nt), 0);
            CHECK_INT(nt, 0);
        }
        free(tri);
        vb_spheres_free(s);
    }
    CHECK(decided >= 15 && facets > 4 * decided);
    VB_TEST_END();
}
