/* The exact envelope decision of a stalled near-tie chain
 * (vbq_envelope_decide, core/cells/cover_envelope.c), both its ways (every
 * owned triple; the convex hull, cover_env_hull.c), against a brute force
 * in exact rationals: for every owned triple, the point of the patch's face
 * where the three labels tie (a 2x2 system solved in GMP rationals), and
 * whether it lies in the square, has a positive value and no label above
 * it. Near-tied sets (a jittered face ball: its in-plane neighbours tie
 * with infinity at the outward normal to 1e-10), exactly tied ones (the
 * same without the jitter: the exact signs must decide them) and random
 * ones, over the four patches that meet at the normal and others. */
#include <gmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "vb_cover.h"
#include "vb_test.h"
#include "vb_test_spheres.h"

#define NMAX 64
#define GRID_REPS 60

/* Sphere k at the decimals mant * 10^exp (coordinates) and radius 1.28. */
static void put(vb_sphere_set *s, size_t k, const int64_t m[3], int32_t exp10)
{
    double *col[3] = {s->x, s->y, s->z};
    vb_decimal *dec[3] = {s->ex, s->ey, s->ez};
    for (int a = 0; a < 3; a++) {
        char buf[64];
        snprintf(buf, sizeof buf, "%lldE%d", (long long)m[a], (int)exp10);
        col[a][k] = strtod(buf, NULL);
        dec[a][k] = (vb_decimal){m[a], exp10};
    }
    s->r[k] = 1.28;
    s->er[k] = (vb_decimal){128, -2};
}

static void dec_q(mpq_t q, vb_decimal d)
{
    mpz_t p;
    mpz_init(p);
    mpz_set_si(p, (long)d.mant);
    mpq_set_z(q, p);
    mpz_ui_pow_ui(p, 10, (unsigned long)(d.exp10 < 0 ? -d.exp10 : d.exp10));
    mpq_t t;
    mpq_init(t);
    mpq_set_z(t, p);
    if (d.exp10 < 0)
        mpq_div(q, q, t);
    else
        mpq_mul(q, q, t);
    mpq_clear(t);
    mpz_clear(p);
}

/* Brute force: the sorted quadruples (4 ids each) of cell `base` in the
 * square of face f; returns their number. */
static int brute(const vb_sphere_set *s, uint32_t base, const uint32_t *ids, int n, uint32_t f,
                 double u0, double u1, double v0, double v1, uint32_t *out)
{
    mpq_t a[NMAX][3], c[3], t, w[3], val, vm, M[2][3], det, sq, tq, bq[4];
    const vb_decimal *dec[3] = {s->ex, s->ey, s->ez};
    for (int x = 0; x < 3; x++) {
        mpq_init(c[x]);
        mpq_init(w[x]);
        dec_q(c[x], dec[x][base]);
    }
    mpq_inits(t, val, vm, det, sq, tq, NULL);
    for (int x = 0; x < 4; x++)
        mpq_init(bq[x]);
    mpq_set_d(bq[0], u0);
    mpq_set_d(bq[1], u1);
    mpq_set_d(bq[2], v0);
    mpq_set_d(bq[3], v1);
    for (int r = 0; r < 2; r++)
        for (int x = 0; x < 3; x++)
            mpq_init(M[r][x]);
    for (int j = 0; j < n; j++) {
        mpq_t N;
        mpq_init(N);
        for (int x = 0; x < 3; x++) {
            mpq_init(a[j][x]);
            dec_q(a[j][x], dec[x][ids[j]]);
            mpq_sub(a[j][x], a[j][x], c[x]);
            mpq_mul(t, a[j][x], a[j][x]);
            mpq_add(N, N, t);
        }
        for (int x = 0; x < 3; x++)
            mpq_div(a[j][x], a[j][x], N);
        mpq_clear(N);
    }
    uint32_t ax = f / 2u, au = (ax + 1u) % 3u, av = (ax + 2u) % 3u;
    int sgn = (f & 1u) ? -1 : 1, nq = 0;
    for (int j = 0; j < n; j++)
        for (int k = j + 1; k < n; k++)
            for (int l = k + 1; l < n; l++) {
                if (ids[j] <= base || ids[k] <= base || ids[l] <= base)
                    continue;
                /* (a_k - a_j) . (sgn e_ax + s e_u + t e_v) = 0, same for l:
                 * M[r] = (coef s, coef t, -constant) */
                const int o[2] = {k, l};
                for (int r = 0; r < 2; r++) {
                    mpq_sub(M[r][0], a[o[r]][au], a[j][au]);
                    mpq_sub(M[r][1], a[o[r]][av], a[j][av]);
                    mpq_sub(M[r][2], a[j][ax], a[o[r]][ax]);
                    if (sgn < 0)
                        mpq_neg(M[r][2], M[r][2]);
                }
                mpq_mul(det, M[0][0], M[1][1]);
                mpq_mul(t, M[0][1], M[1][0]);
                mpq_sub(det, det, t);
                if (mpq_sgn(det) == 0)
                    continue;
                mpq_mul(sq, M[0][2], M[1][1]);
                mpq_mul(t, M[0][1], M[1][2]);
                mpq_sub(sq, sq, t);
                mpq_div(sq, sq, det);
                mpq_mul(tq, M[0][0], M[1][2]);
                mpq_mul(t, M[0][2], M[1][0]);
                mpq_sub(tq, tq, t);
                mpq_div(tq, tq, det);
                if (mpq_cmp(sq, bq[0]) < 0 || mpq_cmp(sq, bq[1]) > 0 || mpq_cmp(tq, bq[2]) < 0 ||
                    mpq_cmp(tq, bq[3]) > 0)
                    continue;
                mpq_set_si(w[ax], sgn, 1);
                mpq_set(w[au], sq);
                mpq_set(w[av], tq);
                mpq_set_ui(val, 0, 1);
                for (int x = 0; x < 3; x++) {
                    mpq_mul(t, a[j][x], w[x]);
                    mpq_add(val, val, t);
                }
                if (mpq_sgn(val) <= 0)
                    continue;
                int beaten = 0;
                for (int m = 0; m < n && !beaten; m++) {
                    mpq_set_ui(vm, 0, 1);
                    for (int x = 0; x < 3; x++) {
                        mpq_mul(t, a[m][x], w[x]);
                        mpq_add(vm, vm, t);
                    }
                    beaten = mpq_cmp(vm, val) > 0;
                }
                if (beaten)
                    continue;
                uint32_t v[4] = {base, ids[j], ids[k], ids[l]};
                for (int x = 2; x < 4; x++)
                    for (int y = x; y > 1 && v[y - 1] > v[y]; y--) {
                        uint32_t z = v[y];
                        v[y] = v[y - 1];
                        v[y - 1] = z;
                    }
                for (int x = 0; x < 4; x++)
                    out[4 * nq + x] = v[x];
                nq++;
            }
    for (int j = 0; j < n; j++)
        for (int x = 0; x < 3; x++)
            mpq_clear(a[j][x]);
    for (int x = 0; x < 3; x++) {
        mpq_clear(c[x]);
        mpq_clear(w[x]);
    }
    for (int r = 0; r < 2; r++)
        for (int x = 0; x < 3; x++)
            mpq_clear(M[r][x]);
    for (int x = 0; x < 4; x++)
        mpq_clear(bq[x]);
    mpq_clears(t, val, vm, det, sq, tq, NULL);
    return nq;
}

static int cmp_quad(const void *p, const void *q)
{
    const uint32_t *a = p, *b = q;
    for (int x = 0; x < 4; x++)
        if (a[x] != b[x])
            return a[x] < b[x] ? -1 : 1;
    return 0;
}

static long n_cases, n_quads, n_exact, n_filtered, n_hull_exact;

/* The decision for cell `base` over every other sphere of s on patch (f,
 * level, iu, iv) of T = 2, against the brute force. */
static void check_patch(const vb_sphere_set *s, uint32_t base, uint32_t f, uint32_t level,
                        uint64_t iu, uint64_t iv)
{
    static vbq_nb nb[NMAX];
    static uint32_t lab[NMAX], q[4 * 4096], want[4 * 40000], ids[NMAX];
    int n = 0;
    for (uint32_t j = 0; j < s->n; j++) {
        if (j == base)
            continue;
        CHECK(vbq_nb_make(s->x[base], s->y[base], s->z[base], s->r[base], s->x[j], s->y[j],
                          s->z[j], s->r[j], j, &nb[n]) == 1);
        lab[n] = (uint32_t)n;
        ids[n] = j;
        n++;
    }
    vbq_env e = {0};
    e.T = 2u;
    e.tmax = (double)INFINITY;
    e.host = s;
    vbq_arena ar = {0};
    ar.nb = nb;
    ar.lab = lab;
    ar.q = q;
    ar.nb_cap = ar.lab_cap = NMAX;
    ar.q_cap = 4096;
    vbq_cell_out o = {0};
    vbq_frame fr = {0};
    fr.f = f;
    fr.level = level;
    fr.iu = iu;
    fr.iv = iv;
    fr.len = (uint32_t)n;
    double u0, u1, v0, v1;
    vbq_patch_square(2u, level, iu, iv, &u0, &u1, &v0, &v1);
    int nw = brute(s, base, ids, n, f, u0, u1, v0, v1, want);
    qsort(want, (size_t)nw, 4 * sizeof *want, cmp_quad);
    /* both ways (every owned triple; the hull), each against the brute
     * force; the triples' way last, its list kept for the filter's check */
    uint32_t exact = 0;
    for (int way = VBQ_ENV_HULL; way >= VBQ_ENV_TRIPLES; way--) {
        o = (vbq_cell_out){0};
        int rc = vbq_envelope_decide(&e, &ar, &o, base, &fr, 0u, (uint32_t)n, way, &exact);
        CHECK_INT(rc, 1);
        CHECK_INT(o.nq, nw);
        int same = (int)o.nq == nw;
        for (int k = 0; same && k < 4 * nw; k++)
            same = q[k] == want[k];
        CHECK(same);
        if (!same)
            fprintf(stderr, "  %s: cell %u face %u level %u (%llu, %llu): %u quadruples, brute %d\n",
                    way == VBQ_ENV_HULL ? "hull" : "triples", base, f, level,
                    (unsigned long long)iu, (unsigned long long)iv, o.nq, nw);
        n_hull_exact += way == VBQ_ENV_HULL ? exact : 0u;
    }
    /* the kernels' double filter alone: when it decides, the same list */
    static uint32_t q2[4 * 4096];
    vbq_arena a2 = ar;
    a2.q = q2;
    vbq_cell_out o2 = {0};
    int rf = vbq_envelope_filter(&e, &a2, &o2, base, &fr, 0u, (uint32_t)n);
    CHECK(rf == 1 || rf == 2);
    if (rf == 1) {
        CHECK_INT(o2.nq, o.nq);
        CHECK(memcmp(q2, q, 4 * sizeof *q * o.nq) == 0);
        n_filtered++;
    }
    n_cases++;
    n_quads += nw;
    n_exact += exact;
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static int64_t rnd(int64_t lo, int64_t hi)
{
    vb_test_xorshift(&rng);
    return lo + (int64_t)(rng % (uint64_t)(hi - lo + 1));
}

/* A face ball of an fcc (001) face: the base at the origin, its in-plane
 * neighbours (z = 0) of two shells and the layer below, every coordinate
 * moved by jit * 1e-12 * uniform[-1000, 1000] (jit 0: exact ties). The base
 * is sphere `nlow` (the first nlow spheres, smaller ids, are not owned). */
static vb_sphere_set *face_ball(int jit, uint32_t *base)
{
    static const int pts[][3] = {
        {0, 0, 0},       {1805, 1805, 0},   {-1805, 1805, 0}, {1805, -1805, 0},
        {-1805, -1805, 0}, {3610, 0, 0},    {-3610, 0, 0},    {0, 3610, 0},
        {0, -3610, 0},   {3610, 3610, 0},   {-3610, 3610, 0}, {5415, 1805, 0},
        {1805, 5415, 0}, {-5415, -1805, 0}, {1805, 0, -1805}, {-1805, 0, -1805},
        {0, 1805, -1805}, {0, -1805, -1805}, {0, 0, -3610},   {3610, 1805, -1805}};
    size_t n = sizeof pts / sizeof pts[0];
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    /* order: spheres 1, 2 (not owned), then the base, then the rest */
    uint32_t order[sizeof pts / sizeof pts[0]];
    order[0] = 1;
    order[1] = 2;
    order[2] = 0;
    for (size_t k = 3; k < n; k++)
        order[k] = (uint32_t)k;
    for (size_t k = 0; k < n; k++) {
        const int *p = pts[order[k]];
        int64_t m[3];
        for (int a = 0; a < 3; a++)
            m[a] = (int64_t)p[a] * 1000000000ll + (jit ? rnd(-1000, 1000) : 0);
        put(s, k, m, -12);
    }
    *base = 2;
    return s;
}

/* An exact crystal's neighbours: n distinct points of the simple cubic
 * grid {-2 .. 2}^3 (spacing 2, integer coordinates) in a random order,
 * the base among them. Their lifted points a_j = d_j / |d_j|^2 lie by
 * many on common planes (the grid points on a sphere through the base's
 * centre), and the hull meets points exactly on a triangle's plane, which
 * do not see it (a point on the plane outside the face must not replace
 * that triangle by a flipped cone). */
static vb_sphere_set *grid_set(size_t n, uint32_t *base)
{
    int64_t pts[125][3];
    int np = 0;
    for (int x = -2; x <= 2; x++)
        for (int y = -2; y <= 2; y++)
            for (int z = -2; z <= 2; z++) {
                pts[np][0] = 2 * x;
                pts[np][1] = 2 * y;
                pts[np][2] = 2 * z;
                np++;
            }
    for (int k = 0; k < np; k++) { /* shuffle */
        int j = k + (int)rnd(0, np - 1 - k);
        for (int a = 0; a < 3; a++) {
            int64_t t = pts[k][a];
            pts[k][a] = pts[j][a];
            pts[j][a] = t;
        }
    }
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    for (size_t k = 0; k < n; k++)
        put(s, k, pts[k], 0);
    *base = (uint32_t)rnd(0, (int64_t)n / 3);
    return s;
}

int main(void)
{
    /* exact grid neighbours: every face at the root, random deeper patches */
    long ex_grid = n_hull_exact;
    for (int rep = 0; rep < GRID_REPS; rep++) {
        uint32_t base;
        vb_sphere_set *s = grid_set(10 + (size_t)rnd(0, 8), &base);
        for (uint32_t f = 0; f < 6; f++)
            check_patch(s, base, f, 0u, (uint64_t)rnd(0, 1), (uint64_t)rnd(0, 1));
        vb_spheres_free(s);
    }
    CHECK(n_hull_exact > ex_grid); /* the grid's ties took the hull's exact signs */
    /* the face ball, jittered (seeds) and exact: the four patches at the
     * normal (+z face, level 6: u0 or u1 = 0), a deep one, the root */
    for (int rep = 0; rep < 6; rep++) {
        uint32_t base;
        vb_sphere_set *s = face_ball(rep < 5, &base);
        long ex0 = n_exact;
        for (uint64_t iu = 63; iu <= 64; iu++)
            for (uint64_t iv = 63; iv <= 64; iv++)
                check_patch(s, base, 4u, 6u, iu, iv);
        check_patch(s, base, 4u, 30u, (uint64_t)1 << 30, (uint64_t)1 << 30);
        check_patch(s, base, 4u, 0u, 1u, 1u);
        for (uint32_t f = 0; f < 6; f++)
            check_patch(s, base, f, 1u, 1u, 2u);
        if (rep == 5)
            CHECK(n_exact > ex0); /* the exact ties took exact signs */
        vb_spheres_free(s);
    }
    /* random equal spheres, three decimals, random patches */
    for (int rep = 0; rep < 40; rep++) {
        size_t n = 10 + (size_t)rnd(0, 12);
        vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
        for (size_t k = 0; k < n; k++) {
            int64_t m[3] = {rnd(-4000, 4000), rnd(-4000, 4000), rnd(-4000, 4000)};
            put(s, k, m, -3);
        }
        uint32_t base = (uint32_t)rnd(0, (int64_t)n / 2);
        for (int p = 0; p < 6; p++) {
            uint32_t level = (uint32_t)rnd(0, 3);
            uint64_t side = (uint64_t)2 << level;
            check_patch(s, base, (uint32_t)rnd(0, 5), level, (uint64_t)rnd(0, (int64_t)side - 1),
                        (uint64_t)rnd(0, (int64_t)side - 1));
        }
        vb_spheres_free(s);
    }
    printf("%ld patches (%ld decided by the double filter alone), %ld quadruples, %ld exact signs "
           "(the hull's way: %ld)\n",
           n_cases, n_filtered, n_quads, n_exact, n_hull_exact);
    CHECK(n_hull_exact > 0); /* the hull met ties its filter could not place */
    CHECK(n_quads > 0);
    CHECK(n_filtered > 0 && n_filtered < n_cases);
    VB_TEST_END();
}
