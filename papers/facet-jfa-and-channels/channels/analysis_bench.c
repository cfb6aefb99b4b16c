/* CPU ms of the channel analysis of one frame as a GPU run's host gets it
 * (issue 33): the voxels of the reference engine, each with a float
 * clearance and the label of its component (its smallest voxel index, as
 * the device's labels), analysed R times by vbc_analyse_given on this
 * thread (VORBALL_THREADS=1 for one thread's cost). Prints the median and
 * the minimum of this thread's CPU ms and of the wall ms (with more
 * threads the wall is the latency, the CPU only the calling thread's), and
 * a checksum of the result (points, radii, lining
 * counts), so two builds can be compared on the same frame. Built against one checkout's build:
 *   cc -O2 -std=c11 -D_DEFAULT_SOURCE -I CHECKOUT/core -I CHECKOUT/core/discrete \
 *      -I CHECKOUT/core/input -I BUILD/core analysis_bench.c BUILD/core/libvb_core.a \
 *      -lgmp -lmpfr -lm -lpthread -lz -o analysis_bench   (the libraries libvb_core needs)
 * usage: analysis_bench INPUT [GRID [R]]   (default 128, 20) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb.h"
#include "vb_parallel.h"
#include "vb_spheres.h"
#include "vbc_channel.h"
#include "vbc_channel_pipe.h"

static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static uint32_t root(uint32_t *p, uint32_t i)
{
    while (p[i] != i)
        i = p[i] = p[p[i]];
    return i;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: analysis_bench INPUT [GRID [R]]\n");
        return 2;
    }
    int n = argc > 2 ? atoi(argv[2]) : 128, R = argc > 3 ? atoi(argv[3]) : 20;
    vb_ctx *ctx;
    vb_sphere_set *s;
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vbc_grid g;
    vbc_engine *e;
    vbc_frame_out out;
    if (vb_open(&ctx, NULL) != VB_OK || vb_spheres_read_file(ctx, argv[1], &ro, &s) != VB_OK ||
        vbc_grid_fit(ctx, s, 1.4, n, 3, &g) != VB_OK || vbc_engine_ref_open(ctx, VBJ_EXACT, &e) != VB_OK) {
        fprintf(stderr, "analysis_bench: %s\n", vb_errmsg(ctx));
        return 1;
    }
    float *a4 = malloc(4 * s->n * sizeof *a4);
    vbc_atoms_pack(&g, s, 1.4, a4);
    if (e->frame(ctx, e, &g, a4, s->n, 1.4, 0, &out) != VB_OK)
        return 1;
    size_t nv = out.nvoxels, nxyz = vbc_grid_voxels(&g);
    /* Clearances as floats; labels by a union-find over the 26 neighbours. */
    vbc_cells *cells;
    if (vbc_cells_build(ctx, s, 5.0, &cells) != VB_OK)
        return 1;
    float *clear = malloc(nv * sizeof *clear);
    uint32_t *lab = malloc(nv * sizeof *lab), *at = malloc(nxyz * sizeof *at), *p = malloc(nv * sizeof *p);
    memset(at, 0xff, nxyz * sizeof *at);
    for (size_t t = 0; t < nv; t++) {
        uint32_t v = out.voxels[t] & ~VBC_MOUTH_BIT;
        double c[3] = {g.origin[0] + ((double)(v % (uint32_t)g.nx) + 0.5) * g.h,
                       g.origin[1] + ((double)((v / (uint32_t)g.nx) % (uint32_t)g.ny) + 0.5) * g.h,
                       g.origin[2] + ((double)(v / ((uint32_t)g.nx * (uint32_t)g.ny)) + 0.5) * g.h};
        int32_t atom;
        clear[t] = (float)vbc_cells_clearance(cells, c, &atom);
        at[v] = (uint32_t)t;
        p[t] = (uint32_t)t;
    }
    long nx = g.nx, ny = g.ny, nz = g.nz;
    for (size_t t = 0; t < nv; t++) {
        long v = (long)(out.voxels[t] & ~VBC_MOUTH_BIT), x = v % nx, y = v / nx % ny, z = v / (nx * ny);
        for (long dz = -1; dz <= 1; dz++)
            for (long dy = -1; dy <= 1; dy++)
                for (long dx = -1; dx <= 1; dx++) {
                    long X = x + dx, Y = y + dy, Z = z + dz;
                    if (X < 0 || Y < 0 || Z < 0 || X >= nx || Y >= ny || Z >= nz)
                        continue;
                    uint32_t q = at[(Z * ny + Y) * nx + X];
                    if (q == UINT32_MAX)
                        continue;
                    uint32_t a = root(p, (uint32_t)t), b = root(p, q);
                    /* The root: the smaller voxel index. */
                    uint32_t va = out.voxels[a] & ~VBC_MOUTH_BIT, vb = out.voxels[b] & ~VBC_MOUTH_BIT;
                    if (a != b)
                        p[va < vb ? b : a] = va < vb ? a : b;
                }
    }
    for (size_t t = 0; t < nv; t++)
        lab[t] = out.voxels[root(p, (uint32_t)t)] & ~VBC_MOUTH_BIT;
    vbc_options opt = {5.0, 0.0, 1.0, 0, NULL};
    double *ms = malloc((size_t)R * sizeof *ms), *wall = malloc((size_t)R * sizeof *wall);
    unsigned long long sum = 0;
    size_t nch = 0, comps = 0;
    int dev = 0;
    for (int k = 0; k < R; k++) {
        vbc_result res;
        double t0 = cpu_ms(), w0 = vb_now();
        if (vbc_analyse_given(ctx, &g, s, out.voxels, clear, lab, nv, &opt, &res) != VB_OK)
            return 1;
        ms[k] = cpu_ms() - t0;
        wall[k] = 1e3 * (vb_now() - w0);
        sum = 0;
        for (size_t c = 0; c < res.nchannels; c++)
            sum = sum * 1000003u + res.channels[c].npoints * 31u + res.channels[c].nlining;
        size_t np = res.nchannels ? res.channels[res.nchannels - 1].first_point +
                                        res.channels[res.nchannels - 1].npoints
                                  : 0;
        for (size_t q = 0; q < np; q++) {
            unsigned long long u;
            memcpy(&u, &res.points[q].r, sizeof u);
            sum = sum * 1099511628211ull ^ u;
        }
        nch = res.nchannels;
        comps = res.components;
        dev = res.device_components;
        vbc_result_free(&res);
    }
    qsort(ms, (size_t)R, sizeof *ms, cmp_d);
    qsort(wall, (size_t)R, sizeof *wall, cmp_d);
    printf("%s grid %d atoms %zu voxels %zu components %zu (device labels %s) channels %zu sum %016llx"
           " cpu_ms median %.3f min %.3f wall_ms median %.3f min %.3f\n",
           argv[1], n, s->n, nv, comps, dev ? "kept" : "REFUSED", nch, sum, ms[R / 2], ms[0], wall[R / 2],
           wall[0]);
    return 0;
}
