/* The exact discrete Voronoi diagram (the reference every JFA variant is
 * measured against): for each pixel the nearest seed, ties to the lowest
 * index, found by rings of seed buckets around the pixel's bucket until no
 * unvisited bucket can hold a seed as near. Same search and integer math as
 * the C reference (gpu/jfa_ref.c, exact_pixel). */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

kernel void jfa_exact(global const int *seeds, global const uint *start,
                      global const uint *items, global uint *out, uint n, uint dim, uint shift,
                      uint g)
{
    uint px = get_global_id(0), py = get_global_id(1), pz = get_global_id(2);
    if (px >= n || py >= n || pz >= (dim == 3 ? n : 1u))
        return;
    uint stride = dim == 3 ? 4u : 2u;
    int G = (int)g;
    long bs = 1L << shift;
    long p[3] = {(long)px * VBJ_FIX_ONE, (long)py * VBJ_FIX_ONE, (long)pz * VBJ_FIX_ONE};
    int b[3] = {(int)(px >> shift), (int)(py >> shift), dim == 3 ? (int)(pz >> shift) : 0};
    uint best = VBJ_NONE;
    ulong bd = ULONG_MAX;
    for (int r = 0;; r++) {
        int rz = dim == 3 ? r : 0;
        for (int dz = -rz; dz <= rz; dz++) {
            int iz = b[2] + dz;
            if (iz < 0 || iz >= (dim == 3 ? G : 1))
                continue;
            int zedge = dim == 3 && (dz == -r || dz == r);
            for (int dy = -r; dy <= r; dy++) {
                int iy = b[1] + dy;
                if (iy < 0 || iy >= G)
                    continue;
                int step = (zedge || dy == -r || dy == r || r == 0) ? 1 : 2 * r;
                for (int dx = -r; dx <= r; dx += step) {
                    int ix = b[0] + dx;
                    if (ix < 0 || ix >= G)
                        continue;
                    uint bk = ((uint)iz * g + (uint)iy) * g + (uint)ix;
                    for (uint j = start[bk]; j < start[bk + 1]; j++) {
                        uint v = items[j];
                        global const int *s = seeds + (size_t)v * stride;
                        ulong d = vbj_dist2((int)p[0], (int)p[1], (int)p[2], s[0], s[1],
                                            dim == 3 ? s[2] : 0);
                        if (vbj_better(d, v, bd, best)) {
                            bd = d;
                            best = v;
                        }
                    }
                }
            }
        }
        long D = LONG_MAX;
        for (int a = 0; a < (int)dim; a++) {
            if (b[a] - r - 1 >= 0) {
                long lo = (long)(b[a] - r) * bs * VBJ_FIX_ONE - VBJ_FIX_HALF;
                D = min(D, p[a] - lo);
            }
            if (b[a] + r + 1 < G) {
                long hi = (long)(b[a] + r + 1) * bs * VBJ_FIX_ONE - VBJ_FIX_HALF;
                D = min(D, hi - p[a]);
            }
        }
        if (D == LONG_MAX || (best != VBJ_NONE && bd < (ulong)D * (ulong)D))
            break;
    }
    out[(pz * n + py) * n + px] = best;
}
