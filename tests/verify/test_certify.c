/* The certifier on hand-computable configurations. Expected values were
 * derived by hand (comments) and rounded with 60-digit decimal arithmetic. */
#include "vb_test.h"
#include "vb_verify.h"
#include "vt_spheres.h"

/* Regular tetrahedron of centres (+-1, +-1, +-1) with an even number of minus
 * signs: circumcentre 0 at distance sqrt(3) from each centre. */
static const char *tetra[] = {"1", "1", "1", "1",   "1", "-1", "-1", "1",
                              "-1", "1", "-1", "1", "-1", "-1", "1", "1"};

static vb_sphere_set *tetra_with(const char *radius, const char *const *extra, size_t nextra)
{
    const char *v[4 * 8];
    for (int i = 0; i < 16; i++)
        v[i] = (i % 4 == 3) ? radius : tetra[i];
    for (size_t i = 0; i < 4 * nextra; i++)
        v[16 + i] = extra[i];
    return vt_set(4 + nextra, v);
}

static void test_tetrahedron(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s = tetra_with("1", NULL, 0);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    uint32_t ids[4] = {3, 1, 0, 2};
    double p[3] = {0.01, -0.02, 0.0};
    vb_cert_result r;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.x == 0.0 && r.y == 0.0 && r.z == 0.0);
    /* t = sqrt(3) - 1, correctly rounded. */
    CHECK(r.t == 0.7320508075688773);
    CHECK_NEAR(r.dist, sqrt(0.01 * 0.01 + 0.02 * 0.02), 1e-15);
    CHECK_INT(r.nmembers, 4);
    CHECK(r.members && r.members[0] == 0 && r.members[3] == 3);
    /* Same vertex from the same ids in another order: same key. */
    size_t key = r.key;
    uint32_t ids2[4] = {0, 1, 2, 3};
    CHECK_INT(vb_certify_candidate(ctx, c, ids2, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.key, key);
    /* Far candidate. */
    double far[3] = {5, 5, 5};
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, far, 1e-6, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_FAR);
    CHECK_NEAR(r.dist, sqrt(75.0), 1e-12);
    /* Bad ids: too few, out of range, duplicates leaving three. */
    uint32_t few[3] = {0, 1, 2}, out[4] = {0, 1, 2, 99}, dup[4] = {0, 0, 1, 2};
    CHECK_INT(vb_certify_candidate(ctx, c, few, 3, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_BAD_IDS);
    CHECK_INT(vb_certify_candidate(ctx, c, out, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_BAD_IDS);
    CHECK_INT(vb_certify_candidate(ctx, c, dup, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_BAD_IDS);
    vb_stats *st = vb_ctx_stats(ctx);
    CHECK_INT(st->candidates, 6);
    CHECK_INT(st->certified, 2);
    CHECK_INT(st->rejected, 4);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

static void test_overlap_and_intruder(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    /* Radius 2 > sqrt(3): the spheres overlap, t = sqrt(3) - 2 < 0. */
    vb_sphere_set *s = tetra_with("2", NULL, 0);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    uint32_t ids[4] = {0, 1, 2, 3};
    double p[3] = {0, 0, 0};
    vb_cert_result r;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 1e-9, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.t == -0.2679491924311227);
    vb_certifier_close(c);
    vb_spheres_free(s);

    /* A small fifth sphere at the centre intrudes; a sphere inside sphere 0
     * (contained) never joins the vertex. */
    const char *extra[] = {"0", "0", "0.1", "0.1", "1.2", "1", "1", "0.2"};
    s = tetra_with("1", extra, 2);
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_INTRUDER);
    CHECK_INT(r.intruder, 4);
    uint32_t with_contained[4] = {5, 1, 2, 3};
    CHECK_INT(vb_certify_candidate(ctx, c, with_contained, 4, p, 0.0, &r), VB_OK);
    CHECK(r.verdict == VB_CERT_INTRUDER || r.verdict == VB_CERT_NO_SOLUTION);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

static void test_cube(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s = vt_cube();
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    double p[3] = {0, 0, 0};
    vb_cert_result r;
    uint32_t q1[4] = {0, 1, 2, 4};
    CHECK_INT(vb_certify_candidate(ctx, c, q1, 4, p, 1e-9, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK_INT(r.nmembers, 8);
    CHECK(r.x == 0.0 && r.y == 0.0 && r.z == 0.0);
    CHECK(r.t == 1.2320508075688772); /* sqrt(3) - 1/2 */
    size_t key = r.key;
    uint32_t q2[4] = {7, 6, 5, 3};
    CHECK_INT(vb_certify_candidate(ctx, c, q2, 4, p, 1e-9, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK_INT(r.key, key);
    /* All eight ids at once. */
    uint32_t all[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    CHECK_INT(vb_certify_candidate(ctx, c, all, 8, p, 1e-9, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK_INT(r.key, key);
    /* A face: four cocircular equal spheres have a whole axis of tangent
     * spheres. */
    uint32_t face[4] = {0, 1, 2, 3};
    CHECK_INT(vb_certify_candidate(ctx, c, face, 4, p, 1e-9, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_UNDETERMINED);
    /* The tangent others are exactly on the sphere: the filter cannot tell. */
    vb_stats *st = vb_ctx_stats(ctx);
    CHECK(st->exact_evals > 0);
    CHECK(st->filter_failures > 0);
    CHECK(st->filter_calls > st->filter_failures);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

/* Coplanar centres (0,0,0), (4,0,0), (0,4,0) radius 1 and (3,3,0) radius 0.5:
 * p = (2, 2, z), sqrt(8 + z^2) - sqrt(2 + z^2) = 1/2 gives sqrt(8 + z^2) = 25/4,
 * z = +-sqrt(497)/4, t = 21/4: two vertices with the same members (Fig. 8). */
static void test_two_vertices(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    const char *v[] = {"0", "0", "0", "1", "4", "0", "0", "1",
                       "0", "4", "0", "1", "3", "3", "0", "0.5"};
    vb_sphere_set *s = vt_set(4, v);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    uint32_t ids[4] = {0, 1, 2, 3};
    double up[3] = {2, 2, 5.5}, down[3] = {2, 2, -5.5};
    vb_cert_result r;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, up, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.x == 2.0 && r.y == 2.0 && r.t == 5.25);
    CHECK(r.z == 5.573374202401989);
    size_t key = r.key;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, down, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.z == -5.573374202401989);
    CHECK(r.key != key);
    vb_certifier_close(c);
    vb_spheres_free(s);

    /* Radius 2 instead of 0.5: sqrt(2 + z^2) = sqrt(8 + z^2) + 1 has no
     * solution (the bisectors do not meet, Fig. 7). */
    const char *w[] = {"0", "0", "0", "1", "4", "0", "0", "1",
                       "0", "4", "0", "1", "3", "3", "0", "2"};
    s = vt_set(4, w);
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, up, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_NO_SOLUTION);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

/* Rows with r_i = dx_i make the solution line's direction (1, 0, 0, -1)
 * light-like: A = 0, one root. By hand (fractions): p = (8/3, -7/2, 2),
 * t + R_a = 29/6 for every choice of R_a. */
static void test_linear_case(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    const char *v[] = {"0", "0", "0", "2", "2", "3", "0", "4",
                       "0", "0", "4", "2", "-1", "-3", "1", "1"};
    vb_sphere_set *s = vt_set(4, v);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    uint32_t ids[4] = {0, 1, 2, 3};
    double p[3] = {2.7, -3.5, 2.0};
    vb_cert_result r;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.x == 8.0 / 3.0 && r.y == -3.5 && r.z == 2.0);
    CHECK(r.t == 17.0 / 6.0);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    CHECK_INT(out.n, 1);
    CHECK(out.n == 1 && out.t[0] == 17.0 / 6.0);
    vb_vertex_list_free(&out);
    vb_certifier_close(c);
    vb_spheres_free(s);
    /* R_a = 5 (all radii + 3): the same point, t = -1/6 < 0. */
    const char *w[] = {"0", "0", "0", "5", "2", "3", "0", "7",
                       "0", "0", "4", "5", "-1", "-3", "1", "4"};
    s = vt_set(4, w);
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.t == -1.0 / 6.0);
    vb_certifier_close(c);
    vb_spheres_free(s);
    /* Mirror (r_i = -dx_i): the single root has t + R_a = -29/6 < 0, no
     * outer tangent sphere. */
    const char *m[] = {"0", "0", "0", "5", "2", "3", "0", "3",
                       "0", "0", "4", "5", "-1", "-3", "1", "6"};
    s = vt_set(4, m);
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_NO_SOLUTION);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

/* Double root: centres (0,0,0), (6,0,0), (0,8,0) radius 1 have circumcentre
 * (3,4) at 5; a fourth sphere at (7.5,4,0) radius 0.5 fixes s = t + 1 = 5 on
 * the line x = 3, y = 4, so z^2 = 0: the two roots of Fig. 8 merge. */
static void test_double_root(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    const char *v[] = {"0", "0", "0", "1", "6", "0", "0", "1",
                       "0", "8", "0", "1", "7.5", "4", "0", "0.5"};
    vb_sphere_set *s = vt_set(4, v);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    uint32_t ids[4] = {0, 1, 2, 3};
    double p[3] = {3, 4, 0.01};
    vb_cert_result r;
    CHECK_INT(vb_certify_candidate(ctx, c, ids, 4, p, 0.1, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_OK);
    CHECK(r.x == 3.0 && r.y == 4.0 && r.z == 0.0 && r.t == 4.0);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    CHECK_INT(vb_reference(ctx, s, &out), VB_OK);
    CHECK_INT(out.n, 1);
    vb_vertex_list_free(&out);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

/* Rank-deficient ids: no point is equidistant from three collinear centres
 * (inconsistent rows), nor from four coplanar centres off one circle; four
 * cocircular ones leave a whole axis (the cube face in test_cube). */
static void test_rank_deficient(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    const char *v[] = {"0", "0", "0", "1", "3", "0", "0", "1", "7", "0", "0", "1",
                       "12", "0", "0", "1", "0", "5", "0", "1", "5", "5", "0", "1"};
    vb_sphere_set *s = vt_set(6, v);
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    double p[3] = {1, 1, 1};
    vb_cert_result r;
    uint32_t line[4] = {0, 1, 2, 3}, plane[4] = {0, 1, 4, 5};
    CHECK_INT(vb_certify_candidate(ctx, c, line, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_NO_SOLUTION);
    /* (0,0), (3,0), (0,5), (5,5): the circle through the first three has
     * centre (1.5, 2.5), and (5,5) is off it. */
    CHECK_INT(vb_certify_candidate(ctx, c, plane, 4, p, 0.0, &r), VB_OK);
    CHECK_INT(r.verdict, VB_CERT_NO_SOLUTION);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

static void test_list(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s = vt_cube();
    vb_certifier *c;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    vb_vertex_list cand, out, rej;
    vb_vertex_list_init(&cand);
    vb_vertex_list_init(&out);
    vb_vertex_list_init(&rej);
    uint32_t q1[4] = {0, 1, 2, 4}, q2[4] = {3, 5, 6, 7}, face[4] = {0, 1, 2, 3};
    vb_vertex_list_push(&cand, q1, 4, 1e-7, 0, 0, 1.2, 0, VB_VERTEX_CANDIDATE);
    vb_vertex_list_push(&cand, q2, 4, 0, 3e-7, 0, 1.2, 0, VB_VERTEX_CANDIDATE);
    vb_vertex_list_push(&cand, face, 4, 0, 0, 0, 1.2, 0, VB_VERTEX_CANDIDATE);
    CHECK_INT(vb_certify_list(ctx, c, &cand, 1e-6, &out, &rej), VB_OK);
    CHECK_INT(out.n, 1);
    CHECK_INT(out.start[1] - out.start[0], 8);
    CHECK_NEAR(out.dist[0], 3e-7, 1e-15);
    CHECK_INT(out.status[0], VB_VERTEX_CERTIFIED);
    CHECK_INT(rej.n, 1);
    CHECK_INT(rej.status[0], VB_VERTEX_REJECTED);
    vb_stats *st = vb_ctx_stats(ctx);
    CHECK_INT(st->candidates, 3);
    CHECK_INT(st->certified, 1); /* two candidates, one canonical vertex */
    CHECK_INT(st->rejected, 1);
    vb_vertex_list_free(&cand);
    vb_vertex_list_free(&out);
    vb_vertex_list_free(&rej);
    vb_certifier_close(c);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    test_tetrahedron();
    test_overlap_and_intruder();
    test_cube();
    test_two_vertices();
    test_linear_case();
    test_double_root();
    test_rank_deficient();
    test_list();
    VB_TEST_END();
}
