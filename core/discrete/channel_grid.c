/* Fitting the channel grid around a molecule and packing atoms in grid units. */
#include <math.h>

#include "vbc_channel.h"

/* Empty voxels kept on each side of the grown spheres: the first and last
 * voxel of every axis ray are then outside the atomic mask. */
#define VBC_MARGIN 2

int vbc_grid_fit(vb_ctx *ctx, const vb_sphere_set *s, double probe, int n, int dim,
                 vbc_grid *out)
{
    if (n < 8 || n > 1024)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "grid size %d outside 8..1024", n);
    if (dim != 2 && dim != 3)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "dimension %d is not 2 or 3", dim);
    if (!(probe >= 0.0) || !isfinite(probe))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "probe radius must be >= 0");
    if (!s || s->n == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, s && s->source ? s->source : NULL, 0,
                        "no atoms to fit a grid around");
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->n; i++) {
        double c[3] = {s->x[i], s->y[i], s->z[i]};
        double r = s->r[i] + probe;
        for (int a = 0; a < 3; a++) {
            lo[a] = fmin(lo[a], c[a] - r);
            hi[a] = fmax(hi[a], c[a] + r);
        }
    }
    double extent = 0.0;
    for (int a = 0; a < dim; a++)
        extent = fmax(extent, hi[a] - lo[a]);
    if (!(extent > 0.0) || !isfinite(extent))
        return vb_error(ctx, VB_EINPUT_MAGNITUDE, NULL, 0, "molecule extent %g cannot be gridded",
                        extent);
    out->dim = dim;
    out->nx = out->ny = n;
    out->nz = dim == 3 ? n : 1;
    out->h = extent / (double)(n - 2 * VBC_MARGIN);
    for (int a = 0; a < 3; a++) {
        int na = a == 0 ? out->nx : a == 1 ? out->ny : out->nz;
        out->origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * na * out->h;
    }
    return VB_OK;
}

void vbc_atoms_pack(const vbc_grid *g, const vb_sphere_set *s, double probe, float *out4)
{
    for (size_t i = 0; i < s->n; i++) {
        out4[4 * i + 0] = (float)((s->x[i] - g->origin[0]) / g->h);
        out4[4 * i + 1] = (float)((s->y[i] - g->origin[1]) / g->h);
        out4[4 * i + 2] = g->dim == 3 ? (float)((s->z[i] - g->origin[2]) / g->h) : 0.5f;
        out4[4 * i + 3] = (float)((s->r[i] + probe) / g->h);
    }
}
