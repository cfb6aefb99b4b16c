/* The exact discrete Voronoi diagram (the reference every JFA variant is
 * measured against): for each pixel the nearest seed, ties to the lowest
 * index, found by rings of seed buckets around the pixel's bucket until no
 * unvisited bucket can hold a seed as near: vbj_exact_nearest, the one copy
 * the C reference (core/discrete/jfa_ref.c) runs too. */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

kernel void jfa_exact(global const int *seeds, global const uint *start,
                      global const uint *items, global uint *out, uint n, uint dim, uint shift,
                      uint g)
{
    uint px = get_global_id(0), py = get_global_id(1), pz = get_global_id(2);
    if (px >= n || py >= n || pz >= (dim == 3 ? n : 1u))
        return;
    out[(pz * n + py) * n + px] =
        vbj_exact_nearest(seeds, dim == 3 ? 4u : 2u, start, items, dim, shift, g, px, py, pz);
}
