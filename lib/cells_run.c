/* The cell measures in one call, of a set or of a trajectory's frames
 * (vb_cells.h): validation, decimals for binary frames, the frame loop;
 * the method is verify/measures/'s. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cells.h"

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

int vb_cells_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_measure_options *opt,
                 vb_cell_measures *out)
{
    memset(out, 0, sizeof *out);
    if (set->contained && set->ex)
        return vb_cell_measures_compute(ctx, set, opt, out);
    vb_sphere_set run = *set;
    run.contained = NULL;
    int rc = VB_OK;
    if (!set->ex) {
        run.ex = run.ey = run.ez = run.er = NULL;
        rc = vb_cells_frame_decimals(ctx, &run);
    }
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, &run, 1);
    if (rc == VB_OK)
        rc = vb_cell_measures_compute(ctx, &run, opt, out);
    free(run.contained);
    if (!set->ex && run.ex) {
        free(run.ex);
        free(run.ey);
        free(run.ez);
        free(run.er);
    }
    return rc;
}

int vb_cells_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                        const vb_read_options *ro, const vb_frame_range *range,
                        const vb_measure_options *opt, vb_cells_frame_fn fn, void *arg,
                        long *selected)
{
    vb_frame_source *F = NULL;
    long index = 0, done = 0;
    int rc = vb_frame_source_open(ctx, path, traj_path, ro, &F);
    while (rc == VB_OK && (range->end < 0 || index < range->end)) {
        vb_sphere_set *s = NULL;
        int model = 0;
        rc = vb_frame_source_next(ctx, F, &s, &model);
        if (rc != VB_OK || !s)
            break;
        if (vb_frame_range_has(range, index)) {
            vb_cell_measures m;
            rc = vb_cells_run(ctx, s, opt, &m);
            if (rc == VB_OK)
                rc = fn(arg, index, model, s, &m);
            vb_cell_measures_free(&m);
            done++;
        }
        vb_spheres_free(s);
        index++;
    }
    vb_frame_source_close(F);
    if (selected)
        *selected = done;
    if (rc == VB_OK && done == 0)
        rc = vb_error(ctx, VB_EINPUT_MODEL, traj_path ? traj_path : path, 0,
                      "no frame selected (--frames / --model)");
    return rc;
}
