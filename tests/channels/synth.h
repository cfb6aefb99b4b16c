/* Synthetic molecules with known channels for the channel tests:
 *   a cylinder of atoms (rings around the z axis): one straight channel;
 *   a closed spherical shell: one cavity, no channel.
 * Plus an exact nearest-centre labelling by brute force (small grids only). */
#ifndef VBC_TEST_SYNTH_H
#define VBC_TEST_SYNTH_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test_spheres.h"
#include "vbc_channel.h"

/* A reproducible uniform number in [0, 1) (a 64-bit LCG on *seed). */
static inline double synth_uniform(uint64_t *seed)
{
    *seed = *seed * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*seed >> 11) / 9007199254740992.0;
}

/* `rings` rings of `per` atoms of radius r on a circle of radius rc around the
 * z axis, rings `dz` apart and staggered by half a step, centred on z = 0.
 * Clearance on the axis: hypot(rc, 0) - r = rc - r at the ring heights. */
static inline vb_sphere_set *synth_cylinder(int rings, int per, double rc, double r, double dz)
{
    vb_sphere_set *s = vb_test_spheres_alloc((size_t)rings * (size_t)per, 0);
    const double pi = 3.14159265358979323846;
    for (int k = 0; k < rings; k++)
        for (int a = 0; a < per; a++) {
            size_t i = (size_t)k * (size_t)per + (size_t)a;
            double phi = 2.0 * pi * (a + 0.5 * (k % 2)) / per;
            s->x[i] = rc * cos(phi);
            s->y[i] = rc * sin(phi);
            s->z[i] = (k - 0.5 * (rings - 1)) * dz;
            s->r[i] = r;
        }
    return s;
}

/* n atoms of radius r on a sphere of radius rs (Fibonacci lattice). */
static inline vb_sphere_set *synth_shell(int n, double rs, double r)
{
    vb_sphere_set *s = vb_test_spheres_alloc((size_t)n, 0);
    const double golden = 2.39996322972865332;
    for (int i = 0; i < n; i++) {
        double zz = 1.0 - 2.0 * (i + 0.5) / n, rr = sqrt(1.0 - zz * zz);
        s->x[i] = rs * rr * cos(golden * i);
        s->y[i] = rs * rr * sin(golden * i);
        s->z[i] = rs * zz;
        s->r[i] = r;
    }
    return s;
}

/* Nearest centre of every voxel (ties to the lowest index), in grid units. */
static inline void synth_labels(const vbc_grid *g, const float *atoms4, size_t natoms, int32_t *labels)
{
    size_t v = 0;
    for (int k = 0; k < g->nz; k++)
        for (int j = 0; j < g->ny; j++)
            for (int i = 0; i < g->nx; i++, v++) {
                double best = INFINITY;
                int32_t arg = 0;
                for (size_t a = 0; a < natoms; a++) {
                    double dx = i + 0.5 - atoms4[4 * a], dy = j + 0.5 - atoms4[4 * a + 1];
                    double dz = k + 0.5 - atoms4[4 * a + 2];
                    double d2 = dx * dx + dy * dy + dz * dz;
                    if (d2 < best) {
                        best = d2;
                        arg = (int32_t)a;
                    }
                }
                labels[v] = arg;
            }
}

#endif
