/* The cell measures in one call, of a set or of a trajectory's frames
 * (vb_cells.h): validation, decimals for binary frames, the frame loop;
 * the method is verify/measures/'s. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cells.h"
#include "vb_frames_each.h"
#include "vb_measures_page.h"

int vb_cells_frame_decimals(vb_ctx *ctx, vb_sphere_set *set)
{
    if (set->ex)
        return VB_OK;
    size_t n = set->n ? set->n : 1;
    vb_decimal *e[4];
    for (int k = 0; k < 4; k++)
        e[k] = calloc(n, sizeof *e[k]);
    int bad = !e[0] || !e[1] || !e[2] || !e[3];
    const double *d[4] = {set->x, set->y, set->z, set->r};
    for (size_t i = 0; !bad && i < set->n; i++)
        for (int k = 0; k < 4 && !bad; k++) {
            /* The shortest of 15, 16, 17 significant digits that reads back
             * as the double (17 always do): the exact side sees the frame's
             * values, as Python's repr gives them for arrays. */
            char tok[40];
            double back = 0.0;
            int len = 0, prec = 15;
            do {
                len = snprintf(tok, sizeof tok, "%.*g", prec, d[k][i]);
                bad = len <= 0 || vb_decimal_parse(tok, (size_t)len, &e[k][i], &back) != 0;
            } while (!bad && back != d[k][i] && ++prec <= 17);
            bad = bad || back != d[k][i];
        }
    if (bad) {
        for (int k = 0; k < 4; k++)
            free(e[k]);
        return vb_error(ctx, VB_ENOMEM, set->source, 0,
                        "out of memory (or a coordinate without decimals) for a frame's decimals");
    }
    set->ex = e[0], set->ey = e[1], set->ez = e[2], set->er = e[3];
    return VB_OK;
}

/* A validated copy of `set` in *run (its own `contained` marks, and
 * decimals for a binary frame), or `set` itself when it is both; undone
 * by run_release. */
static int run_prepare(vb_ctx *ctx, const vb_sphere_set *set, vb_sphere_set *run)
{
    *run = *set;
    if (set->contained && set->ex)
        return VB_OK;
    run->contained = NULL;
    int rc = VB_OK;
    if (!set->ex) {
        run->ex = run->ey = run->ez = run->er = NULL;
        rc = vb_cells_frame_decimals(ctx, run);
    }
    return rc == VB_OK ? vb_spheres_validate(ctx, run, 1) : rc;
}

static void run_release(const vb_sphere_set *set, vb_sphere_set *run)
{
    if (run->contained != set->contained)
        free(run->contained);
    if (run->ex != set->ex) {
        free(run->ex);
        free(run->ey);
        free(run->ez);
        free(run->er);
    }
}

int vb_cells_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_measure_options *opt,
                 vb_cell_measures *out)
{
    memset(out, 0, sizeof *out);
    vb_sphere_set run;
    int rc = run_prepare(ctx, set, &run);
    if (rc == VB_OK)
        rc = vb_cell_measures_compute(ctx, &run, opt, out);
    run_release(set, &run);
    return rc;
}

int vb_cells_run_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_box *box,
                          const vb_measure_options *opt, vb_cell_measures *out)
{
    memset(out, 0, sizeof *out);
    int rc = vb_measure_options_check(ctx, opt);
    if (rc != VB_OK)
        return rc;
    vb_sphere_set run;
    rc = run_prepare(ctx, set, &run);
    vb_periodic_images img;
    memset(&img, 0, sizeof img);
    if (rc == VB_OK) {
        /* Two expanded balls meet only within 2 (Rmax + probe); the
         * relative margin covers the doubles of the sum (the measures test
         * each pair on exact enclosures afterwards). */
        double rmax = 0.0;
        for (size_t i = 0; i < run.n; i++)
            rmax = run.r[i] > rmax ? run.r[i] : rmax;
        const vb_periodic_image_opt io = {0.0, 1, 2.0 * (rmax + opt->probe) * (1.0 + 1e-9)};
        rc = vb_periodic_images_build_opt(ctx, &run, box, &io, &img);
    }
    if (rc == VB_OK) {
        const vb_measure_images mi = {img.n0, img.atom, (const int16_t(*)[3])img.shift};
        rc = vb_cell_measures_compute_images(ctx, img.set, opt, &mi, out);
    }
    vb_periodic_images_free(&img);
    run_release(set, &run);
    return rc;
}

typedef struct frames_job {
    vb_ctx *ctx;
    const vb_measure_options *opt;
    vb_cells_frame_fn fn;
    void *arg;
} frames_job;

static int measure_frame(void *arg, long index, int model, vb_sphere_set *s)
{
    frames_job *J = arg;
    vb_cell_measures m;
    int rc = vb_cells_run(J->ctx, s, J->opt, &m);
    if (rc == VB_OK)
        rc = J->fn(J->arg, index, model, s, &m);
    vb_cell_measures_free(&m);
    return rc;
}

int vb_cells_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                        const vb_read_options *ro, const vb_frame_range *range,
                        const vb_measure_options *opt, vb_cells_frame_fn fn, void *arg,
                        long *selected)
{
    frames_job J = {ctx, opt, fn, arg};
    return vb_frames_each(ctx, path, traj_path, ro, range, measure_frame, &J, selected);
}

int vb_cells_page_write(vb_ctx *ctx, const char *path, const char *title,
                        const vb_sphere_set *set, const vb_cell_measures *m, int contacts)
{
    int rc = vb_page_check(ctx, path);
    vb_page *page = rc == VB_OK ? vb_page_new(ctx, title, set) : NULL;
    if (rc == VB_OK && !page)
        rc = vb_errcode(ctx);
    if (rc == VB_OK)
        rc = vb_cell_measures_page_add(ctx, page, "frame 0", set, m, contacts);
    if (rc == VB_OK)
        rc = vb_page_write(page, path);
    vb_page_free(page);
    return rc;
}
