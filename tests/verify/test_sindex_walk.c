/* The spatial index's walk (verify/certify/vbx_sindex.h) misses no sphere:
 * over a random cloud (a jittered lattice, so the grid's rows run, and a few far
 * spheres, so large balls take the hierarchy) and random query boxes, every
 * slot that the per-sphere test vbx_outside_sphere cannot clear lies in a
 * run the walk returns (the grid's rows are cut by gaps taken from its
 * per-cell tables). Also counts that both the grid and the hierarchy were
 * walked. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbx_sindex.h"

static double unit(uint64_t *s)
{
    return (double)(vb_test_xorshift(s) >> 11) * 0x1p-53;
}

/* A cloud of n spheres like a protein's: a jittered lattice of spacing 3
 * (16 a side), radii 1..2, and every 200th sphere far out. */
static void cloud(uint64_t *s, size_t n, vbx_ia *box, double *near)
{
    for (size_t i = 0; i < n; i++) {
        double far = i % 200 == 199 ? 500.0 : 0.0;
        double c[3] = {3.0 * (double)(i % 16) + unit(s) + far, 3.0 * (double)(i / 16 % 16) + unit(s),
                       3.0 * (double)(i / 256) + unit(s)};
        double r = 1.0 + unit(s);
        for (int k = 0; k < 3; k++) {
            box[4 * i + k] = vbx_ia_point(c[k]);
            near[4 * i + k] = c[k];
        }
        box[4 * i + 3] = vbx_ia_point(r);
        near[4 * i + 3] = r;
    }
}

int main(void)
{
    enum { N = 4000, QUERIES = 3000 };
    uint64_t seed = 0x2545f4914f6cdd1du;
    vbx_ia *box = malloc(4 * N * sizeof *box);
    double *near = malloc(4 * N * sizeof *near);
    unsigned char *seen = malloc(N);
    CHECK(box && near && seen);
    if (!box || !near || !seen)
        VB_TEST_END();
    cloud(&seed, N, box, near);
    vbx_sindex ix;
    CHECK_INT(vbx_sindex_build(&ix, box, near, N), 0);
    size_t grid = 0, bvh = 0, missed = 0, kept = 0;
    for (int q = 0; q < QUERIES; q++) {
        /* a box around a point near a random sphere, of random width, and a
         * tangent radius mostly small (grid), sometimes large (hierarchy) */
        size_t j = (size_t)(unit(&seed) * N) % N;
        double w = q % 3 == 0 ? 0.0 : 0.5 * unit(&seed);
        double t = q % 10 == 0 ? 20.0 + 30.0 * unit(&seed) : 3.0 * unit(&seed);
        vbx_ia p[4];
        for (int k = 0; k < 3; k++) {
            double c = near[4 * j + k] + 8.0 * (unit(&seed) - 0.5);
            p[k] = vbx_ia_make(c, c + w);
        }
        p[3] = vbx_ia_make(t, t + w);
        memset(seen, 0, N);
        vbx_walk walk;
        vbx_walk_init(&walk, &ix, p);
        grid += walk.grid;
        bvh += !walk.grid;
        size_t s0, s1;
        while (vbx_walk_next(&walk, &s0, &s1))
            for (size_t s = s0; s < s1; s++)
                seen[s] = 1;
        for (size_t s = 0; s < N; s++) {
            if (vbx_outside_sphere(&ix.box[4 * s], p))
                continue;
            kept++;
            missed += !seen[s];
        }
    }
    CHECK_INT(missed, 0);
    CHECK(kept > (size_t)QUERIES);
    CHECK(grid > (size_t)QUERIES / 2);
    CHECK(bvh > 0);
    printf("queries %d: grid %zu, hierarchy %zu; kept %zu, missed %zu\n", QUERIES, grid, bvh,
           kept, missed);
    vbx_sindex_free(&ix);
    free(box);
    free(near);
    free(seen);
    VB_TEST_END();
}
