/* The envelope hull's beneath-beyond step (core/cells/cover_env_hull.c,
 * built here from its source: its steps are static) on exact grid
 * neighbours, whose lifted points lie by many on common planes and lines:
 * a point that is inside the hull or on it (its exact sign against every
 * live triangle <= 0) sees no triangle and changes nothing (the file's
 * top: "a point inside or on the hull is no vertex"); a point outside
 * (some sign > 0) is a vertex afterwards. The envelope's answer is the
 * same either way (test_cover_envelope: points on a face are collected
 * from its plane), so only the hull itself shows a point on a triangle's
 * plane taken as seeing it. */
#define vbq_env_hull vbq_env_hull_under_test
#include "../../core/cells/cover_env_hull.c"

#include "vb_test.h"
#include "vb_test_spheres.h"

static uint64_t rng = 0x243f6a8885a308d3ull;

/* n distinct points of the grid {-2 .. 2}^3, spacing 2, in a random order
 * (exact integer decimals, radius 1.28). */
static vb_sphere_set *grid(size_t n)
{
    int p[125][3], np = 0;
    for (int x = -2; x <= 2; x++)
        for (int y = -2; y <= 2; y++)
            for (int z = -2; z <= 2; z++, np++) {
                p[np][0] = 2 * x;
                p[np][1] = 2 * y;
                p[np][2] = 2 * z;
            }
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    for (size_t k = 0; k < n; k++) {
        int j = (int)k + (int)(vb_test_xorshift(&rng) % (uint64_t)(np - (int)k));
        double *col[3] = {s->x, s->y, s->z};
        vb_decimal *dec[3] = {s->ex, s->ey, s->ez};
        for (int a = 0; a < 3; a++) {
            int t = p[k][a];
            p[k][a] = p[j][a];
            p[j][a] = t;
            col[a][k] = (double)p[k][a];
            dec[a][k] = (vb_decimal){p[k][a], 0};
        }
        s->r[k] = 1.28;
        s->er[k] = (vb_decimal){128, -2};
    }
    return s;
}

static long n_on, n_out, n_in;

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
        for (vbs_u32 t = 0u; t < h.nt; t++)
            if (!h.t[t].dead) {
                int v = hull_sign(&h, t, NULL, m);
                CHECK(v != 2);
                top = v > top ? v : top;
            }
        vbs_u32 nt = h.nt;
        CHECK_INT(hull_insert(&h, m), 1);
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
    vbq_env_ctx_free(&c);
}

int main(void)
{
    for (int rep = 0; rep < 200; rep++) {
        size_t n = 8 + (size_t)(vb_test_xorshift(&rng) % 24);
        vb_sphere_set *s = grid(n);
        check_set(s, (vbs_u32)(vb_test_xorshift(&rng) % n));
        vb_spheres_free(s);
    }
    printf("points on the hull %ld, inside %ld, outside %ld\n", n_on, n_in, n_out);
    CHECK(n_on > 100 && n_in > 100 && n_out > 100);
    VB_TEST_END();
}
