/* Jump Flooding in gather form (paper Sec. 2.2 and 2.5): in the step of
 * length l every pixel reads the labels of its 3^d - 1 neighbours at distance
 * l and keeps the seed nearest to its centre (ties to the lower index).
 *
 * Each work-item handles VBJ_C = 4 pixels spaced l apart along the slowest axis
 * (y in 2D, z in 3D): pixel t reads planes t-1, t, t+1 (in units of l), so
 * VBJ_C pixels share VBJ_C + 2 planes of loads instead of 3 * VBJ_C. The
 * result does not depend on this grouping: the minimum over (distance, index)
 * is the same in any order, so the kernels agree with the C reference bit for
 * bit. Labels are seed indices; seeds are 16.16 fixed point (vb_grid.h).
 *
 * Built twice: with -DVBJ_LABEL16 the grids hold 16-bit labels (fewer than
 * 65535 seeds), which halves the memory traffic that bounds every step. */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

#define VBJ_C 4

#ifdef VBJ_LABEL16
typedef ushort vbj_label;
#define VBJ_LNONE 0xffffu
#else
typedef uint vbj_label;
#define VBJ_LNONE VBJ_NONE
#endif

/* Writes each placed seed into its start cell (pairs: cell, seed). */
kernel void jfa_place(global vbj_label *grid, global const uint *pairs, uint count)
{
    uint i = get_global_id(0);
    if (i < count)
        grid[pairs[2 * i]] = (vbj_label)pairs[2 * i + 1];
}

/* The 32-bit label grid of a run (VBJ_LNONE becomes VBJ_NONE). */
kernel void jfa_widen(global const vbj_label *src, global uint *dst, uint count)
{
    uint i = get_global_id(0);
    if (i < count) {
        uint v = src[i];
        dst[i] = v == VBJ_LNONE ? VBJ_NONE : v;
    }
}

/* Offers seed v (coordinate along the coarsened axis sa, partial squared
 * distance `base` over the other axes) to pixel t of the work-item, whose
 * state is the scalars bd##t / bl##t / ca##t: scalars rather than arrays, so
 * that no compiler keeps them in (slow) private memory. r##t says whether
 * plane j is one of pixel t's three planes and v is not its label already. */
#define VBJ_OFFER(t)                                                              \
    if (r##t) {                                                                   \
        int e_ = ca##t - sa;                                                      \
        ulong d_ = base + (ulong)((long)e_ * e_);                                 \
        if (vbj_better(d_, v, bd##t, bl##t)) {                                    \
            bd##t = d_;                                                           \
            bl##t = v;                                                            \
        }                                                                         \
    }
#define VBJ_RELEVANT(t) ((t) < (int)c && (t) >= j - 2 && (t) <= j && v != bl##t)

/* One step of length l on a q x q grid of cells of f fine pixels; c (1, 2 or
 * 4, dividing q / l) pixels per work-item along y. */
kernel void jfa_step_2d(global const vbj_label *src, global vbj_label *dst,
                        global const int2 *seeds, uint q, uint f, uint l, uint c)
{
    uint x = get_global_id(0), w = get_global_id(1);
    if (x >= q || w >= q / c)
        return;
    uint y0 = w % l + l * c * (w / l);
    int cx = vbj_cell_centre(x, f);
    ulong bd0 = ULONG_MAX, bd1 = ULONG_MAX, bd2 = ULONG_MAX, bd3 = ULONG_MAX;
    uint bl0 = VBJ_NONE, bl1 = VBJ_NONE, bl2 = VBJ_NONE, bl3 = VBJ_NONE;
    /* Pixels past c do not exist (their centres could overflow). */
    int ca0 = vbj_cell_centre(y0, f), ca1 = c > 1 ? vbj_cell_centre(y0 + l, f) : 0,
        ca2 = c > 2 ? vbj_cell_centre(y0 + 2u * l, f) : 0,
        ca3 = c > 2 ? vbj_cell_centre(y0 + 3u * l, f) : 0;
    /* The last seed fetched: neighbours mostly repeat a label. */
    uint cv = VBJ_NONE;
    int2 cs = (int2)(0, 0);
    /* Unrolled, the plane index j is a constant in VBJ_RELEVANT. */
#pragma unroll
    for (int j = 0; j < VBJ_C + 2; j++) {
        int yy = (int)y0 + (j - 1) * (int)l;
        if (j > (int)c + 1 || yy < 0 || yy >= (int)q)
            continue;
        for (int dx = -1; dx <= 1; dx++) {
            int xx = (int)x + dx * (int)l;
            if (xx < 0 || xx >= (int)q)
                continue;
            uint v = src[(uint)yy * q + (uint)xx];
            if (v == VBJ_LNONE)
                continue;
            int r0 = VBJ_RELEVANT(0), r1 = VBJ_RELEVANT(1), r2 = VBJ_RELEVANT(2),
                r3 = VBJ_RELEVANT(3);
            if (!(r0 | r1 | r2 | r3))
                continue;
            if (v != cv) {
                cs = seeds[v];
                cv = v;
            }
            int ex = cx - cs.x, sa = cs.y;
            ulong base = (ulong)((long)ex * ex);
            VBJ_OFFER(0)
            VBJ_OFFER(1)
            VBJ_OFFER(2)
            VBJ_OFFER(3)
        }
    }
    uint r = y0 * q + x, stride = l * q;
    dst[r] = (vbj_label)bl0;
    if (c > 1)
        dst[r + stride] = (vbj_label)bl1;
    if (c > 2) {
        dst[r + 2u * stride] = (vbj_label)bl2;
        dst[r + 3u * stride] = (vbj_label)bl3;
    }
}

/* The same on a q^3 grid, c pixels per work-item along z. */
kernel void jfa_step_3d(global const vbj_label *src, global vbj_label *dst,
                        global const int4 *seeds, uint q, uint f, uint l, uint c)
{
    uint x = get_global_id(0), y = get_global_id(1), w = get_global_id(2);
    if (x >= q || y >= q || w >= q / c)
        return;
    uint z0 = w % l + l * c * (w / l);
    int cx = vbj_cell_centre(x, f), cy = vbj_cell_centre(y, f);
    ulong bd0 = ULONG_MAX, bd1 = ULONG_MAX, bd2 = ULONG_MAX, bd3 = ULONG_MAX;
    uint bl0 = VBJ_NONE, bl1 = VBJ_NONE, bl2 = VBJ_NONE, bl3 = VBJ_NONE;
    /* Pixels past c do not exist (their centres could overflow). */
    int ca0 = vbj_cell_centre(z0, f), ca1 = c > 1 ? vbj_cell_centre(z0 + l, f) : 0,
        ca2 = c > 2 ? vbj_cell_centre(z0 + 2u * l, f) : 0,
        ca3 = c > 2 ? vbj_cell_centre(z0 + 3u * l, f) : 0;
    uint cv = VBJ_NONE;
    int4 cs = (int4)(0, 0, 0, 0);
    /* Unrolled, the plane index j is a constant in VBJ_RELEVANT. */
#pragma unroll
    for (int j = 0; j < VBJ_C + 2; j++) {
        int zz = (int)z0 + (j - 1) * (int)l;
        if (j > (int)c + 1 || zz < 0 || zz >= (int)q)
            continue;
        for (int dy = -1; dy <= 1; dy++) {
            int yy = (int)y + dy * (int)l;
            if (yy < 0 || yy >= (int)q)
                continue;
            for (int dx = -1; dx <= 1; dx++) {
                int xx = (int)x + dx * (int)l;
                if (xx < 0 || xx >= (int)q)
                    continue;
                uint v = src[((uint)zz * q + (uint)yy) * q + (uint)xx];
                if (v == VBJ_LNONE)
                    continue;
                int r0 = VBJ_RELEVANT(0), r1 = VBJ_RELEVANT(1), r2 = VBJ_RELEVANT(2),
                    r3 = VBJ_RELEVANT(3);
                if (!(r0 | r1 | r2 | r3))
                    continue;
                if (v != cv) {
                    cs = seeds[v];
                    cv = v;
                }
                int ex = cx - cs.x, ey = cy - cs.y, sa = cs.z;
                ulong base = (ulong)((long)ex * ex) + (ulong)((long)ey * ey);
                VBJ_OFFER(0)
                VBJ_OFFER(1)
                VBJ_OFFER(2)
                VBJ_OFFER(3)
            }
        }
    }
    uint r = (z0 * q + y) * q + x, stride = l * q * q;
    dst[r] = (vbj_label)bl0;
    if (c > 1)
        dst[r + stride] = (vbj_label)bl1;
    if (c > 2) {
        dst[r + 2u * stride] = (vbj_label)bl2;
        dst[r + 3u * stride] = (vbj_label)bl3;
    }
}

/* Number of distinct labels among each pixel and its 3^d - 1 neighbours
 * (dim 2 or 3): 1 interior, 2 facet, >= 3 edge, >= 4 vertex. */
kernel void jfa_count_labels(global const uint *lab, global uchar *out, uint n, uint dim)
{
    uint x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
    uint nz = dim == 3 ? n : 1;
    if (x >= n || y >= n || z >= nz)
        return;
    uint seen[27];
    int ns = 0;
    int rz = dim == 3 ? 1 : 0;
    for (int dz = -rz; dz <= rz; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int xx = (int)x + dx, yy = (int)y + dy, zz = (int)z + dz;
                if (xx < 0 || yy < 0 || zz < 0 || xx >= (int)n || yy >= (int)n || zz >= (int)nz)
                    continue;
                uint v = lab[((uint)zz * n + (uint)yy) * n + (uint)xx];
                int dup = 0;
                for (int t = 0; t < ns; t++)
                    dup |= seen[t] == v;
                if (!dup)
                    seen[ns++] = v;
            }
    out[(z * n + y) * n + x] = (uchar)ns;
}
