/* The pore verdict's raster filter (vbc_walls.h), written once for the
 * plain-C twin (core/discrete/channel_walls.c) and the OpenCL kernel
 * (gpu/channel_walls.cl). Both evaluate the same float expressions in the
 * same order with contraction off (float +, -, * are correctly rounded in
 * OpenCL C as in C; no division, no sqrt), so they give the same bits.
 *
 * A pixel of a plane's raster is blocked when some atom surface lies
 * within VBC_WALL_PROBE of it: |q - c| - r <= probe, as the host's
 * vbc_cells_any_within evaluates it in double. Here, in float, with
 * R2 = (r + probe)^2 and t = |q - c|^2 - R2:
 *   t < -bound  the host's test says blocked (VBC_WALLS_BLOCKED);
 *   t > bound   for every atom: it says free (VBC_WALLS_FREE);
 *   else        VBC_WALLS_UNSURE: the host asks vbc_cells_any_within.
 * bound is the proven error of t (vbc_walls_bound, channel_walls.c, with
 * its derivation), so the float pass decides no uncertain sign. */
#ifndef VBC_CHANNEL_WALLS_MATH_H
#define VBC_CHANNEL_WALLS_MATH_H

#include "vb_cl_compat.h"

#ifndef __OPENCL_C_VERSION__
#include <math.h>
#endif

enum { VBC_WALLS_FREE = 0, VBC_WALLS_BLOCKED = 1, VBC_WALLS_UNSURE = 2 };

/* The pixel (i, j) of a plane (centre P relative to the cells' corner,
 * axes a and b, pixel edge `pixel`): P + (x a + y b), x = i pixel,
 * y = j pixel, in this order. */
VB_SHARED_FN void vbc_walls_point(const float P[3], const float a[3], const float b[3], float pixel,
                                  int i, int j, float q[3])
{
    float x = pixel * (float)i, y = pixel * (float)j;
    for (int d = 0; d < 3; d++)
        q[d] = P[d] + (x * a[d] + y * b[d]);
}

/* The state of the point q (relative to the cells' corner) against the
 * atoms in cell order (x, y, z, R2 per atom, four floats), cells of edge
 * 1 / inv_cell, dims dim[3], the atoms of cell c at start[c] ..
 * start[c + 1]. Atoms are looked for within `reach` of q (cells clamped
 * as the host's cell list clamps them); one with |q - c|^2 > far2 (far2 >
 * every R2 by far more than bound) blocks nothing. */
VB_SHARED_FN int vbc_walls_state(VB_GLOBAL const float *atoms, VB_GLOBAL const vb_u64 *start,
                                 const int dim[3], float inv_cell, float reach, float far2,
                                 float bound, const float q[3])
{
    int lo[3], hi[3];
    for (int d = 0; d < 3; d++) {
        float l = floor((q[d] - reach) * inv_cell), h = floor((q[d] + reach) * inv_cell);
        lo[d] = l < 0.0f ? 0 : l >= (float)dim[d] ? dim[d] - 1 : (int)l;
        hi[d] = h < 0.0f ? 0 : h >= (float)dim[d] ? dim[d] - 1 : (int)h;
    }
    int state = VBC_WALLS_FREE;
    for (int cz = lo[2]; cz <= hi[2]; cz++)
        for (int cy = lo[1]; cy <= hi[1]; cy++) {
            vb_u64 row = (vb_u64)dim[0] * ((vb_u64)cy + (vb_u64)dim[1] * (vb_u64)cz);
            /* The cells lo[0] .. hi[0] of a row are consecutive: one run of atoms. */
            vb_u64 k0 = start[row + (vb_u64)lo[0]], k1 = start[row + (vb_u64)hi[0] + 1];
            for (vb_u64 k = k0; k < k1; k++) {
                VB_GLOBAL const float *A = atoms + 4 * k;
                float dx = q[0] - A[0], dy = q[1] - A[1], dz = q[2] - A[2];
                float d2 = dx * dx + dy * dy;
                d2 = d2 + dz * dz;
                if (d2 > far2)
                    continue;
                float t = d2 - A[3];
                if (t < -bound)
                    return VBC_WALLS_BLOCKED;
                if (t <= bound)
                    state = VBC_WALLS_UNSURE;
            }
        }
    return state;
}

/* One word of a plane's raster: the pixels 32 w .. 32 w + 31 of the
 * (2 n + 1)^2 square, row-major (pixel v = (i + n) (2 n + 1) + (j + n),
 * vbc_plane_walled's order), blocked and unsure bits. */
VB_SHARED_FN void vbc_walls_word(VB_GLOBAL const float *atoms, VB_GLOBAL const vb_u64 *start,
                                 const int dim[3], float inv_cell, float reach, float far2,
                                 float bound, const float P[3], const float a[3], const float b[3],
                                 float pixel, int n, vb_u32 w, vb_u32 *blocked, vb_u32 *unsure)
{
    vb_u32 side = (vb_u32)(2 * n + 1), npix = side * side, bl = 0u, un = 0u;
    for (vb_u32 bit = 0; bit < 32u; bit++) {
        vb_u32 v = 32u * w + bit;
        if (v >= npix)
            break;
        float q[3];
        vbc_walls_point(P, a, b, pixel, (int)(v / side) - n, (int)(v % side) - n, q);
        int s = vbc_walls_state(atoms, start, dim, inv_cell, reach, far2, bound, q);
        if (s == VBC_WALLS_BLOCKED)
            bl |= 1u << bit;
        else if (s == VBC_WALLS_UNSURE)
            un |= 1u << bit;
    }
    *blocked = bl;
    *unsure = un;
}

#endif
