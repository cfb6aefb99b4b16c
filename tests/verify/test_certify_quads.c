/* vb_certify_quads: every exact root of a quadruple judged, filter first.
 *
 * Hand-made quadruples with 0, 1 and 2 empty roots (filter and exact paths,
 * roots refused by t + R < 0 and by intruders, no real root), a single
 * real root with t + R < 0, degenerate vertices of degree 5 and 8 arriving
 * from several quadruples (written once with all members), misuse, and on
 * a random set: output and counters identical for every thread count, the
 * same vertices as vb_certify_list on one candidate per double root, every
 * vertex empty by brute force; a jittered crystal (rows past 128 bits,
 * near-ties) through the double-double stages; rows of rank < 3 and
 * delta = 0 decided without the solve. The corpus through the cover:
 * test_certify_quads_corpus.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h" /* vb_quad_list */
#include "vb_geom_shared.h"
#include "vb_test.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"
#include "vt_lists.h"
#include "vt_spheres.h"

/* The spheres of corpus/inputs/two_vertices_one_quadruple.xyzr. */
static const char *const two_vertices[] = {
    "5", "0", "0", "5",   "-3", "4", "0",  "5",   "-3", "-4", "0", "5", "0",  "0", "0",   "0.2",
    "0", "0", "9", "1",   "0",  "0", "-9", "1.2", "9",  "5",  "0", "1", "-9", "0", "1",   "0.8"};

typedef struct run {
    vb_vertex_list out;
    vb_stats st;
    vb_cert_quad_stats qs;
    int rc;
} run;

/* A fresh context and certifier, so the counters are this run's alone. */
static void certify(const vb_sphere_set *set, const uint32_t (*q)[4], size_t n, unsigned threads,
                    run *r)
{
    vb_ctx *ctx;
    vb_certifier *c = NULL;
    vb_vertex_list_init(&r->out);
    memset(&r->qs, 0, sizeof r->qs);
    r->rc = vb_open(&ctx, NULL);
    if (r->rc != VB_OK)
        return;
    r->rc = vb_certifier_open(ctx, set, &c);
    if (r->rc == VB_OK) {
        vb_certifier_set_threads(c, threads);
        r->rc = vb_certify_quads(ctx, c, q, n, &r->out, &r->qs);
    }
    r->st = *vb_ctx_stats(ctx);
    vb_certifier_close(c);
    vb_close(ctx);
}

static void certify1(const vb_sphere_set *set, uint32_t a, uint32_t b, uint32_t c, uint32_t d,
                     run *r)
{
    const uint32_t q[1][4] = {{a, b, c, d}};
    certify(set, q, 1, 1, r);
}

static double num(const char *s)
{
    return strtod(s, NULL);
}

static int is_ids(const vb_vertex_list *v, size_t k, const uint32_t *ids, size_t n)
{
    return v->start[k + 1] - v->start[k] == n &&
           memcmp(v->ids + v->start[k], ids, n * sizeof *ids) == 0;
}

/* Every sorted quadruple of spheres 0..m-1, in order, into all; the count. */
static size_t all_quads(uint32_t m, uint32_t (*all)[4])
{
    size_t n = 0;
    for (uint32_t a = 0; a < m; a++)
        for (uint32_t b = a + 1; b < m; b++)
            for (uint32_t c = b + 1; c < m; c++)
                for (uint32_t d = c + 1; d < m; d++) {
                    const uint32_t q[4] = {a, b, c, d};
                    memcpy(all[n++], q, sizeof q);
                }
    return n;
}

/* Every quadruple of spheres 0..m-1 (m <= 11) certified on one thread. */
static void certify_all(const vb_sphere_set *set, uint32_t m, run *r)
{
    static uint32_t all[330][4];
    size_t n = all_quads(m, all);
    certify(set, (const uint32_t(*)[4])all, n, 1, r);
}

static void test_hand_made(void)
{
    vb_sphere_set *s = vt_set(8, two_vertices);
    run r;
    const uint32_t q0123[4] = {0, 1, 2, 3};

    /* Two empty roots from one quadruple (coplanar centres: exact path). */
    certify1(s, 0, 1, 2, 3, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 2);
    CHECK_INT(r.qs.vertices, 2);
    CHECK_INT(r.qs.quads_exact, 1);
    CHECK_INT(r.st.candidates, 1);
    CHECK_INT(r.st.certified, 2);
    CHECK_INT(r.st.rejected, 0);
    if (r.out.n == 2) {
        CHECK(is_ids(&r.out, 0, q0123, 4) && is_ids(&r.out, 1, q0123, 4));
        /* Exact zeros are +0; sorted by z. */
        CHECK(r.out.x[0] == 0.0 && !signbit(r.out.x[0]) && r.out.y[0] == 0.0 &&
              !signbit(r.out.y[0]));
        CHECK(r.out.z[0] == num("-0.20416666666666666"));
        CHECK(r.out.z[1] == num("0.20416666666666666"));
        CHECK(r.out.t[0] == num("0.0041666666666666666") && r.out.t[1] == r.out.t[0]);
        CHECK(r.out.status[0] == VB_VERTEX_CERTIFIED && r.out.dist[0] == 0.0);
    }
    vb_vertex_list_free(&r.out);

    /* One empty root decided by the filter alone; the other has t + R < 0. */
    certify1(s, 0, 1, 4, 6, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 1);
    CHECK_INT(r.qs.roots_fast, 1);
    CHECK_INT(r.qs.refused_tangent, 1);
    CHECK_INT(r.qs.exact_solves, 0);
    CHECK_INT(r.st.exact_evals, 0);
    if (r.out.n == 1) {
        const uint32_t m[4] = {0, 1, 4, 6};
        CHECK(is_ids(&r.out, 0, m, 4));
        CHECK(r.out.x[0] == num("13.657741112884668"));
        CHECK(r.out.y[0] == num("27.315482225769337"));
        CHECK(r.out.z[0] == num("27.444120127200968"));
        CHECK(r.out.t[0] == num("34.677093895096341"));
    }
    vb_vertex_list_free(&r.out);

    /* One empty root whose x and y are exactly 0: the filter certifies it,
     * the rounding of the zeros goes to the exact path. */
    certify1(s, 0, 1, 2, 4, &r);
    CHECK_INT(r.out.n, 1);
    CHECK_INT(r.qs.roots_round_exact, 1);
    CHECK_INT(r.qs.exact_solves, 1);
    if (r.out.n == 1) {
        CHECK(r.out.x[0] == 0.0 && !signbit(r.out.x[0]));
        CHECK(r.out.z[0] == num("5.5384615384615383"));
        CHECK(r.out.t[0] == num("2.4615384615384617"));
    }
    vb_vertex_list_free(&r.out);

    /* No empty root: one refused by t + R < 0, one by a sphere inside,
     * both without GMP. */
    certify1(s, 0, 2, 4, 7, &r);
    CHECK_INT(r.out.n, 0);
    CHECK_INT(r.qs.refused_tangent, 1);
    CHECK_INT(r.qs.refused_intruder, 1);
    CHECK_INT(r.qs.rejected_fast, 1);
    CHECK_INT(r.st.rejected, 1);
    CHECK_INT(r.st.exact_evals, 0);
    vb_vertex_list_free(&r.out);

    /* Both real roots have t + R < 0 for a member. */
    certify1(s, 0, 1, 6, 7, &r);
    CHECK_INT(r.out.n, 0);
    CHECK_INT(r.qs.refused_tangent, 2);
    vb_vertex_list_free(&r.out);

    /* No real root at all (delta < 0, proven by the filter). */
    certify1(s, 0, 2, 3, 4, &r);
    CHECK_INT(r.out.n, 0);
    CHECK_INT(r.qs.no_root, 1);
    CHECK_INT(r.st.exact_evals, 0);
    vb_vertex_list_free(&r.out);

    /* Every quadruple of the eight spheres: the reference's seven vertices. */
    certify_all(s, 8, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 7);
    CHECK_INT(r.st.candidates, 70);
    CHECK_INT(r.st.rejected, 64);
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
}

/* A single real root (the linear case A = 0: the kernel (1, 0, 0, 1) is
 * light-like), and it has t + R < 0 for every member: refused. */
static void test_single_root_refused(void)
{
    static const char *const v[] = {"0", "0", "0", "2", "-1", "2", "0", "3",
                                    "0", "3", "0", "2", "0",  "0", "3", "2"};
    vb_sphere_set *s = vt_set(4, v);
    run r;
    certify1(s, 0, 1, 2, 3, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 0);
    CHECK_INT(r.qs.quads_exact, 1);
    CHECK_INT(r.qs.roots_exact, 1);
    CHECK_INT(r.st.rejected, 1);
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
}

/* The cube's centre touches all 8 spheres; 70 quadruples of them (and
 * each twice-listed vertex of degree 5 from corpus degree5_vertex) give
 * one vertex with all members. */
static void test_degenerate(void)
{
    vb_sphere_set *s = vt_cube();
    uint32_t all[70][4];
    size_t n = all_quads(8, all);
    run r;
    certify(s, (const uint32_t(*)[4])all, n, 1, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 1);
    CHECK_INT(r.qs.vertices, 1);
    CHECK(r.qs.duplicates >= 1);
    CHECK_INT(r.st.certified, 1);
    if (r.out.n == 1) {
        const uint32_t m[8] = {0, 1, 2, 3, 4, 5, 6, 7};
        CHECK(is_ids(&r.out, 0, m, 8));
        CHECK(r.out.x[0] == 0.0 && !signbit(r.out.x[0]) && !signbit(r.out.y[0]) &&
              !signbit(r.out.z[0]));
        /* sqrt(3) rounded, minus 0.5: exact within the binade [1, 2). */
        CHECK(r.out.t[0] == sqrt(3.0) - 0.5);
    }
    run r2;
    certify(s, (const uint32_t(*)[4])all, n, 3, &r2);
    CHECK(vt_same_list(&r.out, &r2.out, 1));
    CHECK_INT(r2.qs.duplicates, r.qs.duplicates);
    vb_vertex_list_free(&r.out);
    vb_vertex_list_free(&r2.out);
    vb_spheres_free(s);

    /* corpus degree5_vertex: spheres 0..4 touch a sphere of radius 2 at the
     * origin; its five quadruples write it once. */
    static const char *const d5[] = {
        "0",  "0",  "-3", "1",   "1.5", "-2", "0",  "0.5", "-1", "1.5", "3",  "1.5", "-2",
        "-2", "1",  "1",   "2",   "2",   "3.5", "2.5", "4",  "0",   "-2", "1",   "-4", "1",
        "-2", "1.2", "0",  "-4",  "3",   "0.9", "1",   "4",  "-1",  "1.1", "-3", "-3", "-3",
        "1.3"};
    s = vt_set(10, d5);
    const uint32_t q5[5][4] = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 3, 4}, {0, 2, 3, 4}, {1, 2, 3, 4}};
    certify(s, q5, 5, 1, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 1);
    CHECK_INT(r.qs.duplicates, 4);
    if (r.out.n == 1) {
        const uint32_t m[5] = {0, 1, 2, 3, 4};
        CHECK(is_ids(&r.out, 0, m, 5));
        CHECK(r.out.x[0] == 0.0 && r.out.y[0] == 0.0 && r.out.z[0] == 0.0 && r.out.t[0] == 2.0);
    }
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
}

/* Ties (certify_ties.c): corpus degree5_vertex moved by (1, 1, 1), whose
 * five spheres touch the ball of radius 2 at (1, 1, 1), and sphere 10
 * 10^-17 outside that ball, so quadruple 0 1 4 10 has a root 1.5e-17 from
 * the degree-5 vertex, inside its double enclosure: the two group, yet they
 * are two vertices (sphere 10 is no member of the first). The four later
 * roots of the degree-5 vertex skip their exact paths; 0 1 4 10 must not. */
static void test_ties(void)
{
    static const char *const v[] = {
        "1",  "1",  "-2", "1",   "2.5", "-1", "1",  "0.5", "0", "2.5", "4",  "1.5",
        "-1", "-1", "2",  "1",   "3",   "3",  "4.5", "2.5", "5", "1",  "-1", "1",
        "-3", "2",  "-1", "1.2", "1",   "-3", "4",  "0.9", "2", "5",   "0",  "1.1",
        "-2", "-2", "-2", "1.3", "4.00000000000000001", "1", "1", "1"};
    vb_sphere_set *s = vt_set(11, v);
    run r;
    certify_all(s, 11, &r);
    CHECK_INT(r.rc, VB_OK);
    /* The diagram's 19 vertices (vorball vertices before the ties). */
    CHECK_INT(r.out.n, 19);
    CHECK_INT(r.qs.duplicates, 4);
    CHECK_INT(r.qs.roots_tied, 4);
    const uint32_t m5[5] = {0, 1, 2, 3, 4}, m4[4] = {0, 1, 4, 10};
    size_t k5 = SIZE_MAX, k4 = SIZE_MAX;
    for (size_t k = 0; k < r.out.n; k++) {
        if (is_ids(&r.out, k, m5, 5))
            k5 = k;
        if (is_ids(&r.out, k, m4, 4))
            k4 = k;
    }
    /* Both round to (1, 1, 1), t = 2. */
    CHECK(k5 != SIZE_MAX && r.out.x[k5] == 1.0 && r.out.t[k5] == 2.0);
    CHECK(k4 != SIZE_MAX && r.out.x[k4] == 1.0 && r.out.y[k4] == 1.0 && r.out.z[k4] == 1.0 &&
          r.out.t[k4] == 2.0);
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
    /* Sphere 10 10^-17 inside the ball instead: no degree-5 vertex. Its
     * roots' scans meet touching members first (open), after which the
     * power stages no longer run (certify_qroot.c): the intruder is left
     * open, never taken as outside. As the exact reference says. */
    const char *in[44];
    memcpy(in, v, sizeof in);
    in[40] = "3.99999999999999999";
    s = vt_set(11, in);
    certify_all(s, 11, &r);
    vb_ctx *ctx;
    vb_vertex_list ref;
    vb_vertex_list_init(&ref);
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_INT(vb_reference(ctx, s, &ref), VB_OK);
    CHECK(ref.n > 0 && vt_same_list(&r.out, &ref, 1));
    for (size_t k = 0; k < r.out.n; k++)
        CHECK(r.out.start[k + 1] - r.out.start[k] == 4);
    vb_close(ctx);
    vb_vertex_list_free(&ref);
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
}

static void test_misuse(void)
{
    vb_sphere_set *s = vt_set(8, two_vertices);
    const uint32_t unsorted[1][4] = {{0, 2, 1, 3}};
    const uint32_t repeated[2][4] = {{0, 1, 2, 3}, {0, 1, 2, 3}};
    const uint32_t order[2][4] = {{0, 1, 2, 4}, {0, 1, 2, 3}};
    const uint32_t range[1][4] = {{0, 1, 2, 8}};
    run r;
    certify(s, unsorted, 1, 1, &r);
    CHECK_INT(r.rc, VB_EMISUSE);
    CHECK_INT(r.out.n, 0);
    certify(s, repeated, 2, 1, &r);
    CHECK_INT(r.rc, VB_EMISUSE);
    certify(s, order, 2, 1, &r);
    CHECK_INT(r.rc, VB_EMISUSE);
    certify(s, range, 1, 1, &r);
    CHECK_INT(r.rc, VB_EMISUSE);
    certify(s, NULL, 0, 1, &r);
    CHECK_INT(r.rc, VB_OK);
    CHECK_INT(r.out.n, 0);
    vb_spheres_free(s);
}

/* 700 spheres of a protein-like density, two decimals, from a fixed LCG. */
static vb_sphere_set *random_set(size_t n)
{
    char (*buf)[16] = malloc(4 * n * sizeof *buf);
    const char **v = malloc(4 * n * sizeof *v);
    uint64_t x = 12345;
    for (size_t i = 0; i < 4 * n; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        unsigned r = (unsigned)(x >> 33);
        if (i % 4 == 3)
            snprintf(buf[i], sizeof buf[i], "%u.%02u", 1 + r % 2, r / 7 % 100);
        else
            snprintf(buf[i], sizeof buf[i], "%u.%02u", r % 24, r / 11 % 100);
        v[i] = buf[i];
    }
    vb_sphere_set *s = vt_set(n, v);
    free(v);
    free(buf);
    return s;
}

/* Proposer-independent quadruples: each sphere with three of its 9 nearest
 * neighbours, sorted, repeats dropped (the cover has its own test). */
static int near_quads(vb_sphere_set *s, vb_quad_list *q)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return VB_ENOMEM;
    int rc = vb_spheres_validate(ctx, s, 4);
    vb_close(ctx);
    enum { K = 9 };
    size_t cap = s->n * 84 + 1; /* C(9, 3) per sphere */
    q->q = malloc(cap * sizeof *q->q);
    q->n = 0;
    for (uint32_t i = 0; rc == VB_OK && i < s->n; i++) {
        uint32_t nb[K];
        double best[K];
        int cnt = 0;
        for (uint32_t j = 0; j < s->n; j++) {
            if (j == i)
                continue;
            double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i], dz = s->z[j] - s->z[i];
            double dd = dx * dx + dy * dy + dz * dz;
            if (cnt == K && !(dd < best[K - 1]))
                continue;
            int p = cnt < K ? cnt++ : K - 1; /* full: the farthest drops out */
            while (p > 0 && best[p - 1] > dd) {
                best[p] = best[p - 1];
                nb[p] = nb[p - 1];
                p--;
            }
            best[p] = dd;
            nb[p] = j;
        }
        for (int a = 0; a < cnt; a++)
            for (int b = a + 1; b < cnt; b++)
                for (int c = b + 1; c < cnt; c++) {
                    uint32_t v[4] = {i, nb[a], nb[b], nb[c]};
                    for (int x = 1; x < 4; x++)
                        for (int y = x; y > 0 && v[y - 1] > v[y]; y--) {
                            uint32_t t = v[y];
                            v[y] = v[y - 1];
                            v[y - 1] = t;
                        }
                    memcpy(q->q[q->n++], v, sizeof v);
                }
    }
    qsort(q->q, q->n, sizeof *q->q, vb_quad_cmp);
    size_t w = q->n ? 1 : 0;
    for (size_t k = 1; k < q->n; k++)
        if (vb_quad_cmp(q->q[k], q->q[w - 1]) != 0)
            memcpy(q->q[w++], q->q[k], sizeof *q->q);
    q->n = w;
    q->cap = cap;
    return rc;
}

/* The prototype's way: vb_certify_list on one candidate per double root. */
static int old_way(const vb_sphere_set *set, const vb_quad_list *q, vb_vertex_list *out)
{
    vb_vertex_list cand;
    vb_vertex_list_init(&cand);
    int rc = VB_OK;
    for (size_t k = 0; k < q->n && rc == VB_OK; k++) {
        double s[4][4], r[2][4];
        for (int a = 0; a < 4; a++) {
            uint32_t id = q->q[k][a];
            s[a][0] = set->x[id];
            s[a][1] = set->y[id];
            s[a][2] = set->z[id];
            s[a][3] = set->r[id];
        }
        int nr = vbs_tangent_roots(s, r);
        if (nr == 0)
            rc = vb_vertex_list_push(&cand, q->q[k], 4, s[0][0], s[0][1], s[0][2], 0.0, 0.0, 0);
        for (int i = 0; i < nr && rc == VB_OK; i++)
            rc = vb_vertex_list_push(&cand, q->q[k], 4, r[i][0], r[i][1], r[i][2], r[i][3], 0.0, 0);
    }
    vb_ctx *ctx;
    vb_certifier *c = NULL;
    if (rc == VB_OK)
        rc = vb_open(&ctx, NULL);
    if (rc == VB_OK) {
        rc = vb_certifier_open(ctx, set, &c);
        if (rc == VB_OK)
            rc = vb_certify_list(ctx, c, &cand, 0.0, out, NULL);
        vb_certifier_close(c);
        vb_close(ctx);
    }
    vb_vertex_list_free(&cand);
    return rc;
}

/* Independent of the index: each vertex's members touch it and every other
 * sphere stays outside, in plain double with a tolerance. */
static int brute_empty(const vb_sphere_set *set, const vb_vertex_list *v)
{
    for (size_t k = 0; k < v->n; k++) {
        const uint32_t *m = v->ids + v->start[k];
        size_t nm = v->start[k + 1] - v->start[k], next = 0;
        for (uint32_t j = 0; j < set->n; j++) {
            double dx = v->x[k] - set->x[j], dy = v->y[k] - set->y[j], dz = v->z[k] - set->z[j];
            double g = sqrt(dx * dx + dy * dy + dz * dz) - set->r[j] - v->t[k];
            int member = next < nm && m[next] == j;
            next += member;
            if (member ? fabs(g) > 1e-9 : g < -1e-9)
                return 0;
        }
    }
    return 1;
}

static int same_stats(const vb_stats *a, const vb_stats *b)
{
    return a->filter_calls == b->filter_calls && a->filter_failures == b->filter_failures &&
           a->exact_evals == b->exact_evals && a->candidates == b->candidates &&
           a->certified == b->certified && a->rejected == b->rejected;
}

static void test_threads_and_old_way(void)
{
    vb_sphere_set *s = random_set(700);
    vb_quad_list q = {0};
    CHECK_INT(near_quads(s, &q), VB_OK);
    CHECK(q.n > 1000);
    run one, more;
    certify(s, (const uint32_t(*)[4])q.q, q.n, 1, &one);
    CHECK_INT(one.rc, VB_OK);
    CHECK(one.out.n > 1000);
    const unsigned nts[3] = {2, 3, 7};
    for (int i = 0; i < 3; i++) {
        certify(s, (const uint32_t(*)[4])q.q, q.n, nts[i], &more);
        CHECK_INT(more.rc, VB_OK);
        CHECK(vt_same_list(&one.out, &more.out, 1));
        CHECK(same_stats(&one.st, &more.st));
        CHECK(memcmp(&one.qs, &more.qs, sizeof one.qs) == 0);
        vb_vertex_list_free(&more.out);
    }
    CHECK(brute_empty(s, &one.out));
    /* The filter decides as the exact certifier does. */
    vb_vertex_list old;
    vb_vertex_list_init(&old);
    CHECK_INT(old_way(s, &q, &old), VB_OK);
    CHECK(vt_same_list(&one.out, &old, 0));
    vb_vertex_list_free(&old);
    /* Most of it without GMP. */
    CHECK(one.qs.exact_solves * 20 < one.qs.quads);
    CHECK_INT(one.qs.quads, q.n);

    /* Two calls appending to one list give the one call's list. */
    vb_ctx *ctx;
    vb_certifier *c;
    vb_vertex_list two;
    vb_vertex_list_init(&two);
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    size_t half = q.n / 2;
    CHECK_INT(vb_certify_quads(ctx, c, (const uint32_t(*)[4])q.q + half, q.n - half, &two, NULL),
              VB_OK);
    CHECK_INT(vb_certify_quads(ctx, c, (const uint32_t(*)[4])q.q, half, &two, NULL), VB_OK);
    CHECK(vt_same_list(&one.out, &two, 1));
    vb_vertex_list_free(&two);
    vb_certifier_close(c);
    vb_close(ctx);
    vb_vertex_list_free(&one.out);
    vb_quad_list_free(&q);
    vb_spheres_free(s);
}

/* An fcc block of n^3 cells (a = 3.61, r = 1.28) with every coordinate
 * moved by m 1e-12, m in [-1000, 1000] from a fixed LCG, written with 12
 * decimals: nearly cospherical holes and nearly coplanar faces, whose
 * scaled rows (about 2^42) are past the 128-bit line. */
static vb_sphere_set *jittered_fcc(unsigned n)
{
    static const int off[4][3] = {{0, 0, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 0}};
    size_t count = 4 * (size_t)n * n * n, i = 0;
    char (*buf)[32] = malloc(4 * count * sizeof *buf);
    const char **v = malloc(4 * count * sizeof *v);
    uint64_t x = 10976;
    for (unsigned a = 0; a < n; a++)
        for (unsigned b = 0; b < n; b++)
            for (unsigned c = 0; c < n; c++)
                for (int k = 0; k < 4; k++, i++) {
                    unsigned cell[3] = {a, b, c};
                    for (int d = 0; d < 3; d++) {
                        x = x * 6364136223846793005ull + 1442695040888963407ull;
                        long m = (long)((x >> 33) % 2001) - 1000;
                        /* 1.805 (a / 2) in units of 1e-12, times half-cells. */
                        long long u = (2LL * cell[d] + off[k][d]) * 1805000000000LL + m;
                        snprintf(buf[4 * i + d], sizeof buf[0], "%s%lld.%012lld", u < 0 ? "-" : "",
                                 llabs(u) / 1000000000000LL, llabs(u) % 1000000000000LL);
                        v[4 * i + d] = buf[4 * i + d];
                    }
                    v[4 * i + 3] = "1.28";
                }
    vb_sphere_set *s = vt_set(count, v);
    free(v);
    free(buf);
    return s;
}

/* Rows too wide for 128 bits take the double-double line, and the near-ties
 * the point's double box cannot place take the power (its affine form in
 * double intervals decides most, double-double the rest): every
 * quadruple of a jittered crystal is set up by the filter, and the
 * vertices are those of the exact certifier. */
static void test_wide_rows(void)
{
    vb_sphere_set *s = jittered_fcc(3);
    vb_quad_list q = {0};
    CHECK_INT(near_quads(s, &q), VB_OK);
    run one;
    certify(s, (const uint32_t(*)[4])q.q, q.n, 1, &one);
    CHECK_INT(one.rc, VB_OK);
    CHECK(one.out.n > 200);
    CHECK_INT(one.qs.quads, q.n);
    CHECK_INT(one.qs.quads_exact, 0);
    CHECK(one.qs.power_signs > 0);
    CHECK(one.qs.power_signs_dd < one.qs.power_signs);
    CHECK(one.qs.exact_solves * 20 < one.qs.quads);
    vb_vertex_list old;
    vb_vertex_list_init(&old);
    CHECK_INT(old_way(s, &q, &old), VB_OK);
    CHECK(vt_same_list(&one.out, &old, 0));
    vb_vertex_list_free(&old);
    vb_vertex_list_free(&one.out);
    vb_quad_list_free(&q);
    vb_spheres_free(s);
}

/* Rank < 3 (VBX_QL_FLAT): a square of four equal spheres has no root,
 * proven in integers with no GMP, in the 128-bit line and (12 decimals:
 * rows past 2^28) in the double-double line's rank test. Coplanar centres
 * of unequal radii are not flat (rank 3 through the radius column): their
 * two vertices (test_hand_made's 0 1 2 3, here with wide rows) must stay. */
static void test_flat(void)
{
    static const char *const sq[2][16] = {
        {"0", "0", "0", "1", "2", "0", "0", "1", "0", "2", "0", "1", "2", "2", "0", "1"},
        {"0.000000000001", "0", "0", "1", "2.000000000001", "0", "0", "1", "0.000000000001", "2",
         "0", "1", "2.000000000001", "2", "0", "1"}};
    static const char *const tw[16] = {"5.000000000001", "0", "0", "5", "-2.999999999999", "4",
                                       "0", "5", "-2.999999999999", "-4", "0", "5",
                                       "0.000000000001", "0", "0", "0.2"};
    run r;
    for (int w = 0; w < 2; w++) {
        vb_sphere_set *s = vt_set(4, sq[w]);
        certify1(s, 0, 1, 2, 3, &r);
        /* No vertex, no GMP: rejected by the rank test alone. */
        CHECK(r.rc == VB_OK && r.out.n == 0 && r.qs.flat == 1 && r.qs.rejected_fast == 1 &&
              r.st.exact_evals == 0 && r.qs.exact_solves == 0);
        vb_vertex_list_free(&r.out);
        vb_spheres_free(s);
    }
    vb_sphere_set *s = vt_set(4, tw);
    certify1(s, 0, 1, 2, 3, &r);
    CHECK_INT(r.out.n, 2);
    CHECK_INT(r.qs.flat, 0);
    CHECK_INT(r.qs.quads_exact, 1);
    if (r.out.n == 2)
        CHECK(r.out.z[1] == num("0.20416666666666666") && r.out.t[1] == r.out.t[0]);
    vb_vertex_list_free(&r.out);
    vb_spheres_free(s);
}

/* delta = 0 (VBX_QF_ONE): spheres o + q_j p_j, |p_j| = 11, radius
 * 11 q_j - 9.5 (cos78u's recipe) touch the ball of radius 9.5 about o; with
 * every p_j on the plane x = 6, which misses 0, the line of each quadruple
 * is tangent to the cone: one root, delta exactly 0, which only its GMP
 * sign proves. Four spheres: the filter certifies the root with no GMP
 * solve; five: a vertex of degree 5 whose five quadruples are ties, one
 * solved. Against the exact path (vb_certify_list on the same point). */
static void test_one_root(void)
{
    static const char *const v[20] = {"16.25", "5.3",   "2.125", "1.5",  "16.55", "-5.8",  "9.575",
                                      "2.05",  "16.85", "-13.6", "-2.075", "2.6",  "17.45", "-1.3",
                                      "-10.675", "3.7", "17.15", "3.2",  "8.175", "3.15"};
    const uint32_t q5[5][4] = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 3, 4}, {0, 2, 3, 4}, {1, 2, 3, 4}};
    for (uint32_t n = 4; n <= 5; n++) {
        vb_sphere_set *s = vt_set(n, v);
        run r;
        certify(s, q5, n == 4 ? 1 : 5, 1, &r);
        CHECK_INT(r.rc, VB_OK);
        CHECK_INT(r.out.n, 1);
        CHECK_INT(r.qs.one_root, n == 4 ? 1 : 5);
        CHECK_INT(r.qs.delta_exact, r.qs.one_root);
        CHECK_INT(r.qs.exact_solves, n == 4 ? 0 : 1);
        CHECK_INT(r.qs.roots_tied, n == 4 ? 0 : 4);
        if (r.out.n == 1) {
            const uint32_t m[5] = {0, 1, 2, 3, 4};
            CHECK(is_ids(&r.out, 0, m, n));
            CHECK(r.out.x[0] == 10.25 && r.out.y[0] == num("-3.7") && r.out.z[0] == 0.125 &&
                  r.out.t[0] == 9.5);
        }
        vb_vertex_list ex;
        vb_vertex_list_init(&ex);
        vb_quad_list ql = {(uint32_t(*)[4])q5, n == 4 ? 1 : 5, 5, NULL};
        CHECK_INT(old_way(s, &ql, &ex), VB_OK);
        CHECK(vt_same_list(&r.out, &ex, 0));
        vb_vertex_list_free(&ex);
        vb_vertex_list_free(&r.out);
        vb_spheres_free(s);
    }
}

int main(void)
{
    test_hand_made();
    test_single_root_refused();
    test_degenerate();
    test_ties();
    test_misuse();
    test_threads_and_old_way();
    test_wide_rows();
    test_flat();
    test_one_root();
    VB_TEST_END();
}
