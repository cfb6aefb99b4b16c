/* The envelope hull's beneath-beyond step (core/cells/cover_env_hull.c,
 * built here from its source: its steps are static) on exact grid
 * neighbours, whose lifted points lie by many on common planes and lines:
 * a point that is inside the hull or on it (its exact sign against every
 * live triangle <= 0) sees no triangle and changes nothing (the file's
 * top: "a point inside or on the hull is no vertex"); a point outside
 * (some sign > 0) is a vertex afterwards. The envelope's answer is the
 * same either way (test_cover_envelope: points on a face are collected
 * from its plane), so only the hull itself shows a point on a triangle's
 * plane taken as seeing it. The triangles an insertion replaces (found
 * by a search from a first seen one) are compared with those that every
 * live triangle's sign calls seen, on grid, random, duplicate and
 * cospherical point sets. */
#define vbq_env_hull vbq_env_hull_under_test
#include "../../core/cells/cover_env_hull.c"

#include "vb_test.h"
#include "vb_test_spheres.h"

static uint64_t rng = 0x243f6a8885a308d3ull;

/* Sphere k of s at integer point q (exact decimals, radius 1.28). */
static void put_point(vb_sphere_set *s, size_t k, const int q[3])
{
    double *col[3] = {s->x, s->y, s->z};
    vb_decimal *dec[3] = {s->ex, s->ey, s->ez};
    for (int a = 0; a < 3; a++) {
        col[a][k] = (double)q[a];
        dec[a][k] = (vb_decimal){q[a], 0};
    }
    s->r[k] = 1.28;
    s->er[k] = (vb_decimal){128, -2};
}

/* The point sets, n points each in a random order: 0 distinct points of
 * the grid {-2 .. 2}^3, spacing 2 (many on common planes, lines and
 * spheres); 1 random points of [-30, 30]^3 (general position); 2 grid
 * points where about a third repeat an earlier one (duplicates); 3 the
 * origin first, then points of the sphere x^2 + y^2 + z^2 = 50 (cospherical
 * around sphere 0, which check_set takes as the cell). */
static vb_sphere_set *point_set(size_t n, int mode)
{
    int p[125][3], np = 0;
    for (int x = -7; x <= 7; x++)
        for (int y = -7; y <= 7; y++)
            for (int z = -7; z <= 7; z++) {
                int on = mode == 3 ? x * x + y * y + z * z == 50
                                   : (x >= -2 && x <= 2 && y >= -2 && y <= 2 && z >= -2 && z <= 2);
                if (on && np < 125) {
                    int m = mode == 3 ? 1 : 2;
                    p[np][0] = m * x;
                    p[np][1] = m * y;
                    p[np][2] = m * z;
                    np++;
                }
            }
    if (mode == 3 && n > (size_t)np + 1u)
        n = (size_t)np + 1u;
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    for (size_t k = 0; k < n; k++) {
        int q[3];
        if (mode == 1) {
            for (int a = 0; a < 3; a++)
                q[a] = (int)(vb_test_xorshift(&rng) % 61u) - 30;
        } else if (mode == 2 && k > 0 && vb_test_xorshift(&rng) % 3u == 0u) {
            size_t e = (size_t)(vb_test_xorshift(&rng) % k);
            q[0] = (int)s->x[e];
            q[1] = (int)s->y[e];
            q[2] = (int)s->z[e];
        } else if (mode == 3 && k == 0) {
            q[0] = q[1] = q[2] = 0;
        } else {
            /* a fresh point of p (distinct from the earlier fresh ones) */
            int c = (int)(vb_test_xorshift(&rng) % (uint64_t)np);
            for (int a = 0; a < 3; a++) {
                q[a] = p[c][a];
                p[c][a] = p[np - 1][a];
            }
            np--;
        }
        put_point(s, k, q);
    }
    return s;
}

static long n_on, n_out, n_in, n_diff, n_seen_cmp;

/* The hull of cell `base`'s other spheres, point by point as vbq_env_hull
 * builds it, each insertion checked. */
static void check_set(const vb_sphere_set *s, vbs_u32 base)
{
    vbq_env_lab L[128];
    vbs_u32 n = 0;
    for (vbs_u32 j = 0; j < (vbs_u32)s->n; j++)
        if (j != base)
            L[n++].id = j;
    vbq_env_ctx c = {.s = s, .i = base, .n = n, .L = L};
    hull h;
    memset(&h, 0, sizeof h);
    h.c = &c;
    h.np = n + 1u;
    h.cur = HULL_NONE;
    h.edge = malloc((size_t)h.np * h.np * sizeof *h.edge);
    CHECK(h.edge && vbq_env_rows_made(&c));
    vbs_u32 used[2] = {0u, 0u};
    int st = hull_start(&h, used);
    CHECK(st == 1 || st == 0);
    int bad = 0;
    for (vbs_u32 m = 1u; st == 1 && m < n; m++) {
        if (m == used[0] || m == used[1])
            continue;
        int top = -1; /* the largest exact sign of m against a live triangle */
        unsigned char sees[4096];
        CHECK(h.nt <= sizeof sees);
        for (vbs_u32 t = 0u; t < h.nt; t++) {
            sees[t] = 0;
            if (!h.t[t].dead) {
                int v = hull_sign(&h, t, NULL, m);
                CHECK(v != 2);
                top = v > top ? v : top;
                sees[t] = v > 0;
            }
        }
        vbs_u32 nt = h.nt;
        CHECK_INT(hull_insert(&h, m), 1);
        /* the triangles replaced are exactly those m strictly sees (every
         * live one tested, as before the search from a first seen one) */
        for (vbs_u32 t = 0u; t < nt; t++)
            if (!sees[t] != !(h.t[t].dead && h.t[t].seen == h.round)) {
                bad++;
                n_diff++;
            }
        n_seen_cmp += nt;
        int is_vertex = 0;
        for (vbs_u32 t = 0u; t < h.nt; t++)
            if (!h.t[t].dead)
                is_vertex |= h.t[t].v[0] == m || h.t[t].v[1] == m || h.t[t].v[2] == m;
        if (top <= 0) {
            bad += h.nt != nt || is_vertex; /* nothing seen, nothing added */
            n_on += top == 0;
            n_in += top < 0;
        } else {
            bad += !is_vertex;
            n_out++;
        }
    }
    CHECK_INT(bad, 0);
    free(h.edge);
    free(h.t);
    free(h.vis);
    vbq_env_ctx_free(&c);
}

int main(void)
{
    for (int mode = 0; mode < 4; mode++)
        for (int rep = 0; rep < 200; rep++) {
            size_t n = 8 + (size_t)(vb_test_xorshift(&rng) % 24);
            vb_sphere_set *s = point_set(n, mode);
            n = s->n;
            check_set(s, mode == 3 ? 0u : (vbs_u32)(vb_test_xorshift(&rng) % n));
            vb_spheres_free(s);
        }
    printf("points on the hull %ld, inside %ld, outside %ld; seen sets compared on %ld "
           "triangles, %ld differ\n",
           n_on, n_in, n_out, n_seen_cmp, n_diff);
    CHECK(n_on > 100 && n_in > 100 && n_out > 100 && n_seen_cmp > 10000);
    CHECK_INT(n_diff, 0);
    VB_TEST_END();
}
