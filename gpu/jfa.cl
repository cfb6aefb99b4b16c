/* Jump Flooding in gather form (paper Sec. 2.2 and 2.5): in the step of
 * length l every pixel reads the labels of its 3^d - 1 neighbours at distance
 * l and keeps the seed nearest to its centre (ties to the lower index).
 *
 * Each work-item handles VBJ_C pixels spaced l apart along the slowest axis
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

/* One step of length l on a q x q grid of cells of f fine pixels; c (1, 2 or
 * 4, dividing q / l) pixels per work-item along y. */
kernel void jfa_step_2d(global const vbj_label *src, global vbj_label *dst, global const int2 *seeds,
                        uint q, uint f, uint l, uint c)
{
    uint x = get_global_id(0), w = get_global_id(1);
    if (x >= q || w >= q / c)
        return;
    uint y0 = w % l + l * c * (w / l);
    int cx = vbj_cell_centre(x, f);
    ulong bd[VBJ_C];
    uint bl[VBJ_C];
    int cy[VBJ_C];
#pragma unroll
    for (int t = 0; t < VBJ_C; t++) {
        bd[t] = ULONG_MAX;
        bl[t] = VBJ_NONE;
        cy[t] = vbj_cell_centre(y0 + (uint)t * l, f);
    }
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
            int2 s = seeds[v];
            int ex = cx - s.x;
            ulong dxx = (ulong)((long)ex * ex);
#pragma unroll
            for (int t = 0; t < VBJ_C; t++) {
                if (t < j - 2 || t > j || t >= (int)c || v == bl[t])
                    continue;
                int ey = cy[t] - s.y;
                ulong d = dxx + (ulong)((long)ey * ey);
                if (vbj_better(d, v, bd[t], bl[t])) {
                    bd[t] = d;
                    bl[t] = v;
                }
            }
        }
    }
#pragma unroll
    for (int t = 0; t < VBJ_C; t++)
        if (t < (int)c)
            dst[(y0 + (uint)t * l) * q + x] = (vbj_label)bl[t];
}

/* The same on a q^3 grid, c pixels per work-item along z. */
kernel void jfa_step_3d(global const vbj_label *src, global vbj_label *dst, global const int4 *seeds,
                        uint q, uint f, uint l, uint c)
{
    uint x = get_global_id(0), y = get_global_id(1), w = get_global_id(2);
    if (x >= q || y >= q || w >= q / c)
        return;
    uint z0 = w % l + l * c * (w / l);
    int cx = vbj_cell_centre(x, f), cy = vbj_cell_centre(y, f);
    ulong bd[VBJ_C];
    uint bl[VBJ_C];
    int cz[VBJ_C];
#pragma unroll
    for (int t = 0; t < VBJ_C; t++) {
        bd[t] = ULONG_MAX;
        bl[t] = VBJ_NONE;
        cz[t] = vbj_cell_centre(z0 + (uint)t * l, f);
    }
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
                int4 s = seeds[v];
                int ex = cx - s.x, ey = cy - s.y;
                ulong dxy = (ulong)((long)ex * ex) + (ulong)((long)ey * ey);
#pragma unroll
                for (int t = 0; t < VBJ_C; t++) {
                    if (t < j - 2 || t > j || t >= (int)c || v == bl[t])
                        continue;
                    int ez = cz[t] - s.z;
                    ulong d = dxy + (ulong)((long)ez * ez);
                    if (vbj_better(d, v, bd[t], bl[t])) {
                        bd[t] = d;
                        bl[t] = v;
                    }
                }
            }
        }
    }
#pragma unroll
    for (int t = 0; t < VBJ_C; t++)
        if (t < (int)c)
            dst[((z0 + (uint)t * l) * q + y) * q + x] = (vbj_label)bl[t];
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
