/* CPU ms of the pore stage's two costly steps on one frame (issue 33): the
 * sweep along the frame's pore axis (vbc_pore_sweep, ended by the
 * molecular mask as the stage ends it, vbc_mask_outside) and the verdict on the swept pore
 * (vbc_pore_judge, stopping at VBC_PORE_MIN_BURIED as the stage does), each
 * R times on this thread (VORBALL_THREADS=1 for one thread's cost; the
 * verdict floods its planes on threads from 4). The axis is the one the
 * frame's pore stage finds (vbc_frame_run, reference pipe). Prints the
 * median and the minimum of this thread's CPU ms of each, and checksums of
 * the pore (points and radii, their bits) and of the verdict (walled
 * planes, buried length, its run), so that two builds can be compared on
 * the same frame. Built against one checkout's build:
 *   cc -O2 -std=c11 -D_DEFAULT_SOURCE -I CHECKOUT/core -I CHECKOUT/core/discrete \
 *      -I CHECKOUT/core/input -I BUILD/core pore_bench.c BUILD/core/libvb_core.a \
 *      -lgmp -lmpfr -lm -lpthread -lz -o pore_bench   (the libraries libvb_core needs)
 * usage: pore_bench INPUT [GRID [R]]   (default 128, 20) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb.h"
#include "vb_parallel.h"
#include "vb_spheres.h"
#include "vbc_channels_config.h"
#include "vbc_frame.h"
#include "vbc_pore.h"
#include "vbc_pore_frame.h"

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

static unsigned long long mix(unsigned long long h, double x)
{
    unsigned long long u;
    memcpy(&u, &x, sizeof u);
    return (h ^ u) * 1099511628211ull;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: pore_bench INPUT [GRID [R]]\n");
        return 2;
    }
    int n = argc > 2 ? atoi(argv[2]) : 128, R = argc > 3 ? atoi(argv[3]) : 20;
    vb_ctx *ctx;
    vb_sphere_set *s;
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vbc_grid g;
    vbc_pipe *pipe;
    vbc_channels_config cfg;
    char err[200];
    vbc_channels_defaults(&cfg);
    if (vbc_channels_check(&cfg, err, sizeof err) != 0)
        return 1;
    if (vb_open(&ctx, NULL) != VB_OK || vb_spheres_read_file(ctx, argv[1], &ro, &s) != VB_OK ||
        vbc_grid_fit(ctx, s, cfg.probe, n, 3, &g) != VB_OK ||
        vbc_pipe_open(ctx, NULL, VB_DEVICE_REF, VBJ_EXACT, &pipe) != VB_OK) {
        fprintf(stderr, "pore_bench: %s\n", vb_errmsg(ctx));
        return 1;
    }
    vbc_frame f;
    memset(&f, 0, sizeof f);
    if (vbc_frame_run(ctx, pipe, &g, s, cfg.probe, 0, &cfg.opt, &f) != VB_OK ||
        f.axis.source == VBC_AXIS_NONE) {
        fprintf(stderr, "pore_bench: no pore axis (%s)\n", vb_errmsg(ctx));
        return 1;
    }
    vbc_cells *cells;
    if (vbc_cells_build(ctx, s, 3.0, &cells) != VB_OK)
        return 1;
    vbc_mask_view M = {&f.grid, f.out.flags};
    double *sw = malloc((size_t)R * sizeof *sw), *ju = malloc((size_t)R * sizeof *ju);
    unsigned long long hp = 0, hv = 0;
    size_t npts = 0, walled = 0;
    for (int k = 0; k < R; k++) {
        vbc_pore p;
        double t0 = cpu_ms();
        if (vbc_pore_sweep(ctx, cells, s, &f.axis, &cfg.pore.sweep, vbc_mask_outside, &M, &p) != VB_OK)
            return 1;
        double t1 = cpu_ms();
        vbc_pore_verdict v;
        if (vbc_pore_judge(cells, &p, VBC_PORE_MIN_BURIED, &v) != 0)
            return 1;
        ju[k] = cpu_ms() - t1;
        sw[k] = t1 - t0;
        hp = 14695981039346656037ull;
        for (size_t q = 0; q < p.n; q++) {
            hp = mix(hp, p.pts[q].x);
            hp = mix(hp, p.pts[q].y);
            hp = mix(hp, p.pts[q].z);
            hp = mix(hp, p.pts[q].r);
        }
        hv = mix(mix(mix(mix(14695981039346656037ull, (double)v.walled), v.buried), (double)v.run_lo),
                 (double)v.run_hi);
        npts = p.n;
        walled = v.walled;
        vbc_pore_free(&p);
    }
    qsort(sw, (size_t)R, sizeof *sw, cmp_d);
    qsort(ju, (size_t)R, sizeof *ju, cmp_d);
    printf("%s grid %d atoms %zu axis %s planes %zu walled %zu pore %016llx verdict %016llx"
           " sweep_cpu_ms median %.3f min %.3f verdict_cpu_ms median %.3f min %.3f\n",
           argv[1], n, s->n, vbc_axis_source_name(f.axis.source), npts, walled, hp, hv, sw[R / 2],
           sw[0], ju[R / 2], ju[0]);
    vbc_cells_free(cells);
    vbc_frame_free(&f);
    vbc_pipe_close(pipe);
    vb_spheres_free(s);
    free(sw);
    free(ju);
    vb_close(ctx);
    return 0;
}
