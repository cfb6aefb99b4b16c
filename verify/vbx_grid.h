/* A uniform grid over sphere centres for the emptiness scans of verify/.
 *
 * Conservative by monotonicity: a sphere sits in the cell of the nearest
 * double of its exact centre, and a cell index is floor((x - x0) / h) clamped,
 * computed in round-to-nearest. Every step is monotone non-decreasing in x,
 * and so is rounding an exact value to nearest. Hence when an exact centre
 * lies in a box [L, H] with double ends, its nearest double does too
 * (RN(L) = L), and its cell lies between the cells of L and H: scanning those
 * cells sees every sphere whose exact centre is in the box. */
#ifndef VBX_GRID_H
#define VBX_GRID_H

#include <stddef.h>
#include <stdint.h>

typedef struct vbx_grid {
    double x0[3], h;   /* origin and cell side */
    int nc[3];         /* cells per axis */
    size_t *start;     /* CSR: cell c holds ids[start[c] .. start[c+1]) */
    uint32_t *ids;
} vbx_grid;

/* Builds the grid over the n centres given as nearest doubles (xyz[4*i+k],
 * k < 3; stride 4 to read vbx_data.near). Returns 0, or -1 when out of memory. */
int vbx_grid_build(vbx_grid *g, const double *xyz, size_t n);
void vbx_grid_free(vbx_grid *g);

/* Cell range [lo[k], hi[k]] (inclusive) covering the box [blo, bhi]. */
void vbx_grid_range(const vbx_grid *g, const double blo[3], const double bhi[3], int lo[3],
                    int hi[3]);

static inline size_t vbx_grid_cell(const vbx_grid *g, int i, int j, int k)
{
    return ((size_t)k * (size_t)g->nc[1] + (size_t)j) * (size_t)g->nc[0] + (size_t)i;
}

#endif
