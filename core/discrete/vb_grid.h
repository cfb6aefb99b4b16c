/* Discrete grids for JFA / Facet-JFA: the one copy of the distance math,
 * compiled both as C11 (reference backend, checks) and as OpenCL C (kernels).
 *
 * Seeds live in grid coordinates where pixel p has its centre at p, stored as
 * 16.16 fixed point (VBJ_FIX_ONE = one pixel). A cell of f pixels per axis at
 * coarse position P has its centre at P*f + (f-1)/2, also exact in 16.16.
 * Squared distances are then exact 64-bit integers (|d| < 2^30 for n <= 2^14,
 * so three squares stay below 2^62): "nearest seed, ties to the lowest index"
 * (the paper's Definition 2) is decided without rounding, identically on every
 * device, and the exact reference is exact for the seeds as stored. */
#ifndef VB_GRID_H
#define VB_GRID_H

#include "vb_cl_compat.h"
#include "vbj_limits.h"

typedef vb_i32 vbj_i32;
typedef vb_u32 vbj_u32;
typedef vb_i64 vbj_i64;
typedef vb_u64 vbj_u64;
#define VBJ_FN VB_SHARED_FN
#define VBJ_GLOBAL VB_GLOBAL
#define VBJ_I64_MAX VB_I64_MAX
#define VBJ_U64_MAX VB_U64_MAX

/* Pixels per work-item of the boundary count (gpu/jfa.cl's jfa_boundary), along
 * the last axis; the host sizes that launch by it. */
#define VBJ_BND_B 8

/* Fixed-point centre of the cell at coarse position p when a cell spans f
 * fine pixels (f a power of two; f = 1 is the pixel itself). */
VBJ_FN vbj_i32 vbj_cell_centre(vbj_u32 p, vbj_u32 f)
{
    return (vbj_i32)(p * f) * VBJ_FIX_ONE + (vbj_i32)(f - 1u) * VBJ_FIX_HALF;
}

/* Exact squared distance between two fixed-point points (units 2^-32 px^2).
 * Coordinates lie in [-2^15, 2^30), so each difference fits in 32 bits and
 * each square is one widening 32x32 -> 64 multiply. */
VBJ_FN vbj_u64 vbj_dist2(vbj_i32 ax, vbj_i32 ay, vbj_i32 az, vbj_i32 bx, vbj_i32 by,
                         vbj_i32 bz)
{
    vbj_i32 dx = ax - bx, dy = ay - by, dz = az - bz;
    return (vbj_u64)((vbj_i64)dx * dx) + (vbj_u64)((vbj_i64)dy * dy) +
           (vbj_u64)((vbj_i64)dz * dz);
}

/* True when candidate (d, l) beats the current (bd, bl): nearer, or as near
 * with a lower seed index (Definition 2's tie rule). */
VBJ_FN int vbj_better(vbj_u64 d, vbj_u32 l, vbj_u64 bd, vbj_u32 bl)
{
    return d < bd || (d == bd && l < bl);
}

/* Fine pixel nearest to a fixed-point coordinate (halves round up); callers
 * guarantee -0.5 <= c < n - 0.5 so the result lies in [0, n). */
VBJ_FN vbj_u32 vbj_pixel_of(vbj_i32 c)
{
    return (vbj_u32)((c + VBJ_FIX_HALF) >> VBJ_FIX_BITS);
}

/* The exact nearest seed to pixel (px, py, pz) (pz = 0 in 2D), ties to the
 * lowest index: the exact discrete diagram every JFA variant is measured
 * against, one copy for the C reference and the OpenCL kernel. Seeds are
 * 16.16 coordinates, `stride` ints per seed (x, y[, z]); they sit in buckets
 * of 2^shift pixels per axis, g per axis, bucket b holding
 * items[start[b] .. start[b+1]) in ascending index. Rings of buckets around
 * the pixel's bucket are searched until no unvisited bucket can hold a seed
 * as near as the best. */
VBJ_FN vbj_u32 vbj_exact_nearest(VBJ_GLOBAL const vbj_i32 *seeds, vbj_u32 stride,
                                 VBJ_GLOBAL const vbj_u32 *start, VBJ_GLOBAL const vbj_u32 *items,
                                 vbj_u32 dim, vbj_u32 shift, vbj_u32 g, vbj_u32 px, vbj_u32 py,
                                 vbj_u32 pz)
{
    int G = (int)g;
    vbj_i64 bs = (vbj_i64)1 << shift;
    vbj_i64 p[3] = {(vbj_i64)px * VBJ_FIX_ONE, (vbj_i64)py * VBJ_FIX_ONE,
                    (vbj_i64)pz * VBJ_FIX_ONE};
    int b[3] = {(int)(px >> shift), (int)(py >> shift), dim == 3 ? (int)(pz >> shift) : 0};
    vbj_u32 best = VBJ_NONE;
    vbj_u64 bd = VBJ_U64_MAX;
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
                    vbj_u32 bk = ((vbj_u32)iz * g + (vbj_u32)iy) * g + (vbj_u32)ix;
                    for (vbj_u32 j = start[bk]; j < start[bk + 1]; j++) {
                        vbj_u32 v = items[j];
                        VBJ_GLOBAL const vbj_i32 *s = seeds + (vbj_u64)v * stride;
                        vbj_u64 d = vbj_dist2((vbj_i32)p[0], (vbj_i32)p[1], (vbj_i32)p[2], s[0],
                                              s[1], dim == 3 ? s[2] : 0);
                        if (vbj_better(d, v, bd, best)) {
                            bd = d;
                            best = v;
                        }
                    }
                }
            }
        }
        /* Seeds outside the visited block lie beyond one of its faces. */
        vbj_i64 D = VBJ_I64_MAX;
        for (int a = 0; a < (int)dim; a++) {
            if (b[a] - r - 1 >= 0) {
                vbj_i64 lo = (vbj_i64)(b[a] - r) * bs * VBJ_FIX_ONE - VBJ_FIX_HALF;
                D = p[a] - lo < D ? p[a] - lo : D;
            }
            if (b[a] + r + 1 < G) {
                vbj_i64 hi = (vbj_i64)(b[a] + r + 1) * bs * VBJ_FIX_ONE - VBJ_FIX_HALF;
                D = hi - p[a] < D ? hi - p[a] : D;
            }
        }
        if (D == VBJ_I64_MAX || (best != VBJ_NONE && bd < (vbj_u64)D * (vbj_u64)D))
            return best;
    }
}

#endif
