/* Periodic vertices frame by frame (vb_periodic_frames.h). */
#include "vb_periodic_frames.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cells.h"
#include "vb_default.h"
#include "vb_frames_each.h"

typedef struct job {
    vb_ctx *ctx;
    const char *name;
    const vb_box *box;
    const vb_vertices_config *cfg;    /* vertices */
    vb_periodic_frame_fn fn;
    const vb_measure_options *opt;    /* or cells */
    vb_cells_frame_fn cells_fn;
    void *arg;
} job;

/* An XTC (or single-precision TRR) frame stores each coordinate as a float
 * in nm (XTC: an integer over the precision, 5.202 nm, rounded to float);
 * read as Angstrom it is ten times that float. Its decimal is the shortest
 * one that reads back to the float (as the frame's box, frame_box.c), in
 * Angstrom: 52.02, not the 17 digits of the float's binary value, whose
 * images would need more than 18 digits beside the box's decimals (E107).
 * The set's doubles become those decimals' nearest doubles. Frames whose
 * coordinates are not all ten times a float keep vb_cells_frame_decimals'
 * decimals of their doubles. VB_OK or VB_ENOMEM. */
static int float_frame_decimals(vb_ctx *ctx, vb_sphere_set *s)
{
    int had = s->ex != NULL;
    int rc = vb_cells_frame_decimals(ctx, s);
    double *d[3] = {s->x, s->y, s->z};
    for (size_t i = 0; rc == VB_OK && !had && i < s->n; i++)
        for (int k = 0; k < 3; k++)
            if ((double)(float)(d[k][i] / 10.0) * 10.0 != d[k][i])
                return VB_OK;
    vb_decimal *e[3] = {s->ex, s->ey, s->ez};
    for (size_t i = 0; rc == VB_OK && !had && i < s->n; i++)
        for (int k = 0; k < 3; k++) {
            float f = (float)(d[k][i] / 10.0);
            char tok[32];
            int len = 0;
            for (int p = 1; p <= 9; p++) {
                len = snprintf(tok, sizeof tok, "%.*g", p, (double)f);
                if ((float)strtod(tok, NULL) == f)
                    break;
            }
            vb_decimal dec;
            double back;
            if (vb_decimal_parse(tok, (size_t)len, &dec, &back) != 0)
                return VB_OK; /* keep the decimals of the doubles */
            if (dec.mant != 0)
                dec.exp10 += 1; /* nm to Angstrom, exactly */
            e[k][i] = dec;
            d[k][i] = vb_decimal_double(dec);
        }
    return rc;
}

/* The frame's box (*b: the job's or the frame's) and its decimals: VB_OK,
 * VB_EINPUT_BOX naming the frame without a box, VB_ENOMEM. */
static int frame_ready(job *J, long index, vb_sphere_set *s, const vb_box **b)
{
    *b = J->box ? J->box : s->box;
    if (!*b)
        return vb_error(J->ctx, VB_EINPUT_BOX, J->name, 0,
                        "--periodic: frame %ld carries no box: give --box", index);
    return float_frame_decimals(J->ctx, s);
}

static int one_frame(void *arg, long index, int model, vb_sphere_set *s)
{
    job *J = arg;
    const vb_box *b;
    int rc = frame_ready(J, index, s, &b);
    if (rc != VB_OK)
        return rc;
    vb_periodic_result res;
    vb_periodic_result_init(&res);
    rc = vb_periodic_vertices_run(J->ctx, s, b, J->cfg, vb_default_backends(), &res);
    if (rc == VB_OK)
        rc = J->fn(J->arg, index, model, s, b, &res);
    vb_periodic_result_free(&res);
    return rc;
}

int vb_periodic_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                           const vb_read_options *ro, const vb_frame_range *range,
                           const vb_box *box, const vb_vertices_config *cfg,
                           vb_periodic_frame_fn fn, void *arg, long *selected)
{
    job J = {ctx, traj_path ? traj_path : path, box, cfg, fn, NULL, NULL, arg};
    return vb_frames_each(ctx, path, traj_path, ro, range, one_frame, &J, selected);
}

static int cells_frame(void *arg, long index, int model, vb_sphere_set *s)
{
    job *J = arg;
    const vb_box *b;
    int rc = frame_ready(J, index, s, &b);
    if (rc != VB_OK)
        return rc;
    vb_cell_measures m;
    rc = vb_cells_run_periodic(J->ctx, s, b, J->opt, &m);
    if (rc == VB_OK)
        rc = J->cells_fn(J->arg, index, model, s, &m);
    vb_cell_measures_free(&m);
    return rc;
}

int vb_cells_run_frames_periodic(vb_ctx *ctx, const char *path, const char *traj_path,
                                 const vb_read_options *ro, const vb_frame_range *range,
                                 const vb_box *box, const vb_measure_options *opt,
                                 vb_cells_frame_fn fn, void *arg, long *selected)
{
    job J = {ctx, traj_path ? traj_path : path, box, NULL, NULL, opt, fn, arg};
    return vb_frames_each(ctx, path, traj_path, ro, range, cells_frame, &J, selected);
}
