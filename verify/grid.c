/* Uniform grid over sphere centres (see vbx_grid.h for why it is conservative). */
#include <math.h>
#include <stdlib.h>

#include "vbx_grid.h"

/* Cells per axis are capped so the grid stays small for elongated inputs. */
#define VBX_GRID_MAX_AXIS 256

static int axis_index(const vbx_grid *g, int k, double x)
{
    double f = floor((x - g->x0[k]) / g->h);
    /* Comparisons in double before the cast: NaN and huge values clamp. */
    if (!(f >= 0.0))
        return 0;
    if (f >= (double)(g->nc[k] - 1))
        return g->nc[k] - 1;
    return (int)f;
}

int vbx_grid_build(vbx_grid *g, const double *xyz, size_t n)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], xyz[4 * i + k]);
            hi[k] = fmax(hi[k], xyz[4 * i + k]);
        }
    double ext = 0.0;
    for (int k = 0; k < 3; k++) {
        g->x0[k] = n ? lo[k] : 0.0;
        ext = fmax(ext, n ? hi[k] - lo[k] : 0.0);
    }
    /* About two centres per cell for a compact cloud. */
    double side = ext / cbrt((double)(n ? n : 1) / 2.0);
    if (!(side > 0.0))
        side = 1.0;
    g->h = side;
    size_t ncell = 1;
    for (int k = 0; k < 3; k++) {
        double cells = n ? floor((hi[k] - lo[k]) / side) + 1.0 : 1.0;
        g->nc[k] = cells > VBX_GRID_MAX_AXIS ? VBX_GRID_MAX_AXIS : (int)cells;
        ncell *= (size_t)g->nc[k];
    }
    g->start = calloc(ncell + 1, sizeof *g->start);
    g->ids = malloc((n ? n : 1) * sizeof *g->ids);
    size_t *cellof = malloc((n ? n : 1) * sizeof *cellof);
    if (!g->start || !g->ids || !cellof) {
        free(cellof);
        vbx_grid_free(g);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        size_t c = vbx_grid_cell(g, axis_index(g, 0, xyz[4 * i]), axis_index(g, 1, xyz[4 * i + 1]),
                                 axis_index(g, 2, xyz[4 * i + 2]));
        cellof[i] = c;
        g->start[c + 1]++;
    }
    for (size_t c = 0; c < ncell; c++)
        g->start[c + 1] += g->start[c];
    for (size_t i = 0; i < n; i++)
        g->ids[g->start[cellof[i]]++] = (uint32_t)i;
    /* start[c] now points at the end of cell c: shift back by one cell. */
    for (size_t c = ncell; c > 0; c--)
        g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    free(cellof);
    return 0;
}

void vbx_grid_free(vbx_grid *g)
{
    free(g->start);
    free(g->ids);
    g->start = NULL;
    g->ids = NULL;
}

void vbx_grid_range(const vbx_grid *g, const double blo[3], const double bhi[3], int lo[3],
                    int hi[3])
{
    /* A NaN bound (an overflowed enclosure) scans the whole axis. */
    for (int k = 0; k < 3; k++) {
        lo[k] = isnan(blo[k]) ? 0 : axis_index(g, k, blo[k]);
        hi[k] = isnan(bhi[k]) ? g->nc[k] - 1 : axis_index(g, k, bhi[k]);
    }
}
