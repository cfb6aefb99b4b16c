/* The exact reference against hand-computed configurations and against an
 * independent brute force written here in long double (Gaussian elimination
 * with pivoting, then the quadratic in t, then every other sphere). */
#include <stdint.h>

#include "vb_test.h"
#include "vb_verify.h"
#include "vt_spheres.h"

typedef long double ld;

typedef struct bf_vertex {
    uint32_t ids[4];
    ld p[3], t;
} bf_vertex;

/* Brute force over all quadruples. Returns the number of vertices written to
 * out (at most cap); *close counts decisions within eps of a tie, which would
 * make the long double answer unreliable (the test data avoid them). */
static size_t brute_force(const vb_sphere_set *s, bf_vertex *out, size_t cap, size_t *close)
{
    const ld eps = 1e-9L;
    size_t nv = 0;
    *close = 0;
    for (uint32_t a = 0; a < s->n; a++)
        for (uint32_t b = a + 1; b < s->n; b++)
            for (uint32_t c = b + 1; c < s->n; c++)
                for (uint32_t d = c + 1; d < s->n; d++) {
                    uint32_t q[4] = {a, b, c, d};
                    ld ca[3] = {s->x[a], s->y[a], s->z[a]}, ra = s->r[a];
                    /* Row m: (c_m - c_a) . p + (R_m - R_a) t = rhs_m; p = p0 + t p1. */
                    ld M[3][5];
                    for (int m = 0; m < 3; m++) {
                        uint32_t j = q[m + 1];
                        ld cj[3] = {s->x[j], s->y[j], s->z[j]}, rj = s->r[j];
                        ld rhs = 0.0L;
                        for (int k = 0; k < 3; k++) {
                            M[m][k] = cj[k] - ca[k];
                            rhs += cj[k] * cj[k] - ca[k] * ca[k];
                        }
                        rhs -= rj * rj - ra * ra;
                        M[m][3] = rhs / 2.0L;
                        M[m][4] = -(rj - ra);
                    }
                    /* Gaussian elimination with partial pivoting on two right-hand sides. */
                    int singular = 0;
                    for (int col = 0; col < 3 && !singular; col++) {
                        int piv = col;
                        for (int r = col + 1; r < 3; r++)
                            if (fabsl(M[r][col]) > fabsl(M[piv][col]))
                                piv = r;
                        if (fabsl(M[piv][col]) < 1e-12L) {
                            singular = 1;
                            break;
                        }
                        for (int k = 0; k < 5; k++) {
                            ld tmp = M[col][k];
                            M[col][k] = M[piv][k];
                            M[piv][k] = tmp;
                        }
                        for (int r = 0; r < 3; r++) {
                            if (r == col)
                                continue;
                            ld f = M[r][col] / M[col][col];
                            for (int k = col; k < 5; k++)
                                M[r][k] -= f * M[col][k];
                        }
                    }
                    if (singular)
                        continue;
                    ld p0[3], p1[3];
                    for (int k = 0; k < 3; k++) {
                        p0[k] = M[k][3] / M[k][k];
                        p1[k] = M[k][4] / M[k][k];
                    }
                    /* |p0 + t p1 - c_a|^2 = (t + R_a)^2. */
                    ld A = -1.0L, B = -ra, C = -ra * ra;
                    for (int k = 0; k < 3; k++) {
                        ld e = p0[k] - ca[k];
                        A += p1[k] * p1[k];
                        B += e * p1[k];
                        C += e * e;
                    }
                    ld disc = B * B - A * C;
                    if (disc < 0.0L || fabsl(A) < 1e-12L)
                        continue;
                    for (int sg = -1; sg <= 1; sg += 2) {
                        ld t = (-B + sg * sqrtl(disc)) / A;
                        ld p[3];
                        for (int k = 0; k < 3; k++)
                            p[k] = p0[k] + t * p1[k];
                        int ok = 1;
                        for (int m = 0; m < 4; m++)
                            if (t + s->r[q[m]] < -eps)
                                ok = 0;
                        for (uint32_t o = 0; o < s->n && ok; o++) {
                            if (o == a || o == b || o == c || o == d)
                                continue;
                            ld dx = p[0] - s->x[o], dy = p[1] - s->y[o], dz = p[2] - s->z[o];
                            ld g = sqrtl(dx * dx + dy * dy + dz * dz) - s->r[o] - t;
                            if (fabsl(g) < eps)
                                (*close)++;
                            if (g < 0.0L)
                                ok = 0;
                        }
                        if (ok && nv < cap) {
                            bf_vertex *v = &out[nv++];
                            for (int m = 0; m < 4; m++)
                                v->ids[m] = q[m];
                            for (int k = 0; k < 3; k++)
                                v->p[k] = p[k];
                            v->t = t;
                        }
                    }
                }
    return nv;
}

/* Deterministic pseudo-random decimals (an LCG; no libc rand). */
static uint64_t lcg_state;
static unsigned lcg(unsigned mod)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)((lcg_state >> 33) % mod);
}

static vb_sphere_set *random_set(size_t n, unsigned rmin_cents, unsigned rspan_cents,
                                 uint64_t seed, char *buf, const char **v)
{
    lcg_state = seed;
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            char *s = buf + (4 * i + k) * 16;
            unsigned m = lcg(10000);
            snprintf(s, 16, "%u.%03u", m / 1000, m % 1000);
            v[4 * i + k] = s;
        }
        char *s = buf + (4 * i + 3) * 16;
        unsigned r = rmin_cents + lcg(rspan_cents);
        snprintf(s, 16, "%u.%02u", r / 100, r % 100);
        v[4 * i + 3] = s;
    }
    return vt_set(n, v);
}

/* Every reference vertex matches one brute-force vertex (same four ids, same
 * point to 1e-9) and the counts agree. */
static void compare_with_brute_force(size_t n, unsigned rmin, unsigned rspan, uint64_t seed)
{
    char buf[4 * 32 * 16];
    const char *v[4 * 32];
    vb_sphere_set *s = random_set(n, rmin, rspan, seed, buf, v);
    bf_vertex bf[2048];
    size_t close = 0;
    size_t nbf = brute_force(s, bf, 2048, &close);
    CHECK_INT(close, 0);
    CHECK(nbf >= 2 * n); /* a real diagram, not an empty comparison */
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    CHECK_INT(out.n, nbf);
    size_t matched = 0, negative_t = 0;
    for (size_t k = 0; k < out.n; k++) {
        if (out.start[k + 1] - out.start[k] != 4)
            continue;
        const uint32_t *ids = out.ids + out.start[k];
        for (size_t i = 0; i < nbf; i++) {
            if (memcmp(bf[i].ids, ids, sizeof bf[i].ids) != 0)
                continue;
            ld dx = bf[i].p[0] - out.x[k], dy = bf[i].p[1] - out.y[k], dz = bf[i].p[2] - out.z[k];
            if (sqrtl(dx * dx + dy * dy + dz * dz) < 1e-9L && fabsl(bf[i].t - out.t[k]) < 1e-9L) {
                matched++;
                break;
            }
        }
        if (out.t[k] < 0.0)
            negative_t++;
    }
    CHECK_INT(matched, nbf);
    if (rmin >= 150)
        CHECK(negative_t > 0); /* overlapping spheres give t < 0 */
    vb_stats *st = vb_ctx_stats(ctx);
    CHECK_INT(st->certified, out.n);
    CHECK(st->rejected > 0 && st->rejected < st->candidates);
    vb_vertex_list_free(&out);
    vb_close(ctx);
    vb_spheres_free(s);
}

/* The certifier and the reference agree: every reference vertex certifies
 * from its ids; random quadruples certify only onto reference vertices. */
static void certifier_agrees(size_t n, unsigned rmin, unsigned rspan, uint64_t seed)
{
    char buf[4 * 32 * 16];
    const char *v[4 * 32];
    vb_sphere_set *s = random_set(n, rmin, rspan, seed, buf, v);
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_vertex_list ref;
    vb_vertex_list_init(&ref);
    CHECK_INT(vb_reference(ctx, s, &ref), VB_OK);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    size_t ok = 0, keys_distinct = 1, errors = 0;
    size_t *keys = calloc(ref.n ? ref.n : 1, sizeof *keys);
    for (size_t k = 0; k < ref.n; k++) {
        vb_cert_result r;
        double p[3] = {ref.x[k] + 1e-8, ref.y[k], ref.z[k]};
        errors += vb_certify_candidate(ctx, c, ref.ids + ref.start[k], 4, p, 1e-6, &r) != VB_OK;
        if (r.verdict == VB_CERT_OK && r.x == ref.x[k] && r.y == ref.y[k] && r.z == ref.z[k] &&
            r.t == ref.t[k])
            ok++;
        keys[k] = r.key;
        for (size_t i = 0; i < k; i++)
            if (keys[i] == r.key)
                keys_distinct = 0;
    }
    CHECK_INT(ok, ref.n);
    CHECK_INT(keys_distinct, 1);
    free(keys);
    /* Random quadruples near random points. */
    size_t certified = 0, onto_reference = 0;
    lcg_state = seed * 977 + 1;
    for (int trial = 0; trial < 400; trial++) {
        uint32_t ids[4];
        for (int i = 0; i < 4; i++)
            ids[i] = lcg((unsigned)n);
        double p[3] = {lcg(10000) / 1000.0, lcg(10000) / 1000.0, lcg(10000) / 1000.0};
        vb_cert_result r;
        errors += vb_certify_candidate(ctx, c, ids, 4, p, 0.0, &r) != VB_OK;
        if (r.verdict != VB_CERT_OK)
            continue;
        certified++;
        for (size_t k = 0; k < ref.n; k++)
            if (ref.x[k] == r.x && ref.y[k] == r.y && ref.z[k] == r.z && ref.t[k] == r.t &&
                ref.start[k + 1] - ref.start[k] == r.nmembers &&
                memcmp(ref.ids + ref.start[k], r.members, r.nmembers * sizeof *r.members) == 0)
                onto_reference++;
    }
    CHECK_INT(onto_reference, certified);
    CHECK(certified > 0);
    CHECK_INT(errors, 0);
    vb_certifier_close(c);
    vb_vertex_list_free(&ref);
    vb_close(ctx);
    vb_spheres_free(s);
}

static void test_cube_reference(void)
{
    vb_sphere_set *s = vt_cube();
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    /* One vertex of degree 8 at the centre; nothing else is bounded or empty. */
    CHECK_INT(out.n, 1);
    CHECK_INT(out.start[1], 8);
    CHECK(out.x[0] == 0.0 && out.y[0] == 0.0 && out.z[0] == 0.0);
    CHECK(out.t[0] == 1.2320508075688772);
    /* Every tangent sphere beyond the solved four needs the exact path. */
    CHECK(vb_ctx_stats(ctx)->exact_evals > 0);
    CHECK(vb_ctx_stats(ctx)->filter_failures > 0);
    vb_vertex_list_free(&out);
    vb_close(ctx);
    vb_spheres_free(s);
}

static void test_two_and_contained(void)
{
    const char *v[] = {"0", "0", "0", "1", "4", "0", "0", "1",
                       "0", "4", "0", "1", "3", "3", "0", "0.5"};
    vb_sphere_set *s = vt_set(4, v);
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    /* Fig. 8: one quadruple, two vertices (z = -+sqrt(497)/4), sorted by z. */
    CHECK_INT(out.n, 2);
    CHECK(out.z[0] == -5.573374202401989 && out.z[1] == 5.573374202401989);
    CHECK(out.t[0] == 5.25 && out.t[1] == 5.25);
    vb_vertex_list_free(&out);
    vb_spheres_free(s);

    /* Tetrahedron plus a sphere inside sphere 0: the contained sphere is in
     * no vertex. */
    const char *w[] = {"1",  "1", "1",  "1", "1",  "-1", "-1", "1", "-1",  "1",
                       "-1", "1", "-1", "-1", "1", "1",  "1.2", "1", "1", "0.2"};
    s = vt_set(5, w);
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    int contained_member = 0;
    for (size_t i = 0; i < out.nids; i++)
        if (out.ids[i] == 4)
            contained_member = 1;
    CHECK_INT(contained_member, 0);
    CHECK(out.n >= 1);
    CHECK(out.x[0] == 0.0 && out.t[0] == 0.7320508075688773);
    vb_vertex_list_free(&out);
    vb_close(ctx);
    vb_spheres_free(s);
}

int main(void)
{
    test_cube_reference();
    test_two_and_contained();
    /* Separate spheres, then overlapping ones (t < 0 vertices). */
    compare_with_brute_force(14, 50, 100, 1);
    compare_with_brute_force(18, 50, 100, 7);
    compare_with_brute_force(24, 30, 60, 11);
    compare_with_brute_force(16, 150, 200, 3);
    compare_with_brute_force(20, 180, 150, 5);
    certifier_agrees(10, 50, 100, 21);
    certifier_agrees(12, 150, 200, 23);
    VB_TEST_END();
}
