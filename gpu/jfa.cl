/* Jump Flooding in gather form (paper Sec. 2.2 and 2.5): in the step of
 * length l every pixel reads the labels of its 3^d - 1 neighbours at distance
 * l and keeps the seed nearest to its centre (ties to the lower index).
 *
 * The step is bound by the distance work, not memory: on an H200, 256^3 with
 * 13,573 seeds, JFA+1 takes 3.9 ms, of which the label reads alone (the same
 * kernel with the distance work optimised away) take 0.75 ms; 27 candidate
 * seeds per pixel in 3D, each a squared distance and a compare with the tie
 * rule. So:
 *
 * - A work-item owns a block of pixels spaced l apart (3D: 2 along y x 4
 *   along z; 2D: 4 along y). Neighbours of the block's pixels coincide, so
 *   the block reads (2+2)(4+2)3 = 72 labels for 8 pixels instead of 216.
 * - Per label read, the seed's coordinate terms (x^2, y^2 per row, z^2 per
 *   plane of the block) are computed once, and only when the label differs
 *   from the previous read's (neighbours mostly repeat a label); each pixel
 *   the read concerns then costs one add and the compare.
 * - Distances are doubles where doubles are exact: seeds and centres are
 *   16.16 fixed-point integers held in doubles, so differences are exact, and
 *   for |difference| < n 2^16 the sum of squares stays below dim n^2 2^32
 *   <= 2^53 (3D n <= 512, 2D n <= 1024): every value is an exact integer and
 *   the result equals the 64-bit integer reference bit for bit. The host picks
 *   the double program then (fp64 is on every device the runtime opens; one
 *   double compare replaces the two-word compares of 64-bit integers), and
 *   the build with -DVBJ_DIST64 (exact 64-bit integers) on larger grids.
 * - No branches around the reads: a neighbour outside the grid or without a
 *   label reads as VBJ_LNONE, whose distance is VBJ_DFAR, beyond every real
 *   one; pixels of a block that lie past the grid (when q / l < 4) get a
 *   valid centre and are never written.
 * The minimum over (distance, index) does not depend on the order of the
 * candidates, so the kernels agree with the C reference bit for bit.
 *
 * Built four times: -DVBJ_LABEL16 for 16-bit label grids (fewer than 65535
 * seeds; half the memory traffic), crossed with -DVBJ_DIST64. */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

#ifdef VBJ_LABEL16
typedef ushort vbj_label;
#define VBJ_LNONE 0xffffu
#else
typedef uint vbj_label;
#define VBJ_LNONE VBJ_NONE
#endif

#ifdef VBJ_DIST64
typedef int vbj_coord;
typedef ulong vbj_d;
typedef int2 vbj_seed2;
typedef int4 vbj_seed3;
#define VBJ_SQ(e) ((ulong)((long)(e) * (e)))
/* |difference| < 2^30 + 2^15, so three squares stay below 2^62 and
 * VBJ_DFAR plus two of them below 2^64. */
#define VBJ_DFAR ((ulong)1 << 63)
#define VBJ_DINIT ULONG_MAX
#define VBJ_CENTRE(p, f) vbj_cell_centre(p, f)
#else
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double vbj_coord;
typedef double vbj_d;
typedef double2 vbj_seed2;
typedef double4 vbj_seed3;
#define VBJ_SQ(e) ((e) * (e))
#define VBJ_DFAR 0x1p200
#define VBJ_DINIT INFINITY
#define VBJ_CENTRE(p, f) ((double)vbj_cell_centre(p, f))
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

/* "Not a label": forces the first read of a work-item to fetch its seed. */
#define VBJ_NOCACHE 0xfffffffeu

/* Offers the seed just read (label v) to pixel t of the block: nearer, or as
 * near with a lower index (Definition 2). dist is its squared distance.
 * A branch, not selects: most offers change nothing, and on an H200 the
 * select form (min / compare / select every offer) was 1.4x slower. */
#define VBJ_OFFER(t, dist)                                                        \
    {                                                                             \
        vbj_d d_ = (dist);                                                        \
        if (d_ < bd##t || (d_ == bd##t && v < bl##t)) {                           \
            bd##t = d_;                                                           \
            bl##t = v;                                                            \
        }                                                                         \
    }

/* 2D: pixels y0 + t l (t < 4) of column x read rows y0 + (j - 1) l, j < 6;
 * row j concerns the pixels t with j - 2 <= t <= j (constants: the compiler
 * drops the others). */
#define VBJ_IF2(t, J)                                                             \
    if ((t) + 2 >= (J) && (t) <= (J))                                             \
        VBJ_OFFER(t, ds##t)

#define VBJ_READ2(J, xx, okx)                                                     \
    {                                                                             \
        uint v = okr_ && (okx) ? (uint)src[row_ + (xx)] : VBJ_LNONE;              \
        if (v != cv) {                                                            \
            cv = v;                                                               \
            vbj_seed2 s_ = seeds[v == VBJ_LNONE ? 0u : v];                        \
            vbj_d x_ = v == VBJ_LNONE ? VBJ_DFAR : VBJ_SQ(cx - s_.x);             \
            ds0 = x_ + VBJ_SQ(cy0 - s_.y);                                        \
            ds1 = x_ + VBJ_SQ(cy1 - s_.y);                                        \
            ds2 = x_ + VBJ_SQ(cy2 - s_.y);                                        \
            ds3 = x_ + VBJ_SQ(cy3 - s_.y);                                        \
        }                                                                         \
        VBJ_IF2(0, J) VBJ_IF2(1, J) VBJ_IF2(2, J) VBJ_IF2(3, J)                   \
    }

#define VBJ_ROW2(J)                                                               \
    {                                                                             \
        uint yy_ = y0 + (uint)((J) - 1) * l;                                      \
        int okr_ = yy_ < q;                                                       \
        uint row_ = yy_ * q;                                                      \
        VBJ_READ2(J, xm, xm < q)                                                  \
        VBJ_READ2(J, x, 1)                                                        \
        VBJ_READ2(J, xp, xp < q)                                                  \
    }

/* One step of length l on a q x q grid of cells of f fine pixels. Work-item
 * (x, w) owns pixels y0 + t l, t < 4 (those past the grid when q / l = 2 are
 * skipped): global size q x (q / l >= 4 ? q / 4 : l). */
kernel void jfa_step_2d(global const vbj_label *src, global vbj_label *dst,
                        global const vbj_seed2 *seeds, uint q, uint f, uint l)
{
    uint x = get_global_id(0), w = get_global_id(1);
    if (x >= q || w >= (q / l >= 4u ? q / 4u : l))
        return;
    uint y0 = w % l + 4u * l * (w / l), xm = x - l, xp = x + l;
    vbj_coord cx = VBJ_CENTRE(x, f), cy0 = VBJ_CENTRE(y0, f), cy1 = VBJ_CENTRE(y0 + l, f);
    vbj_coord cy2 = y0 + 2u * l < q ? VBJ_CENTRE(y0 + 2u * l, f) : cy0;
    vbj_coord cy3 = y0 + 3u * l < q ? VBJ_CENTRE(y0 + 3u * l, f) : cy0;
    vbj_d bd0 = VBJ_DINIT, bd1 = VBJ_DINIT, bd2 = VBJ_DINIT, bd3 = VBJ_DINIT;
    uint bl0 = VBJ_LNONE, bl1 = VBJ_LNONE, bl2 = VBJ_LNONE, bl3 = VBJ_LNONE;
    vbj_d ds0 = 0, ds1 = 0, ds2 = 0, ds3 = 0;
    uint cv = VBJ_NOCACHE;
    VBJ_ROW2(0) VBJ_ROW2(1) VBJ_ROW2(2) VBJ_ROW2(3) VBJ_ROW2(4) VBJ_ROW2(5)
    uint r = y0 * q + x, stride = l * q;
    dst[r] = (vbj_label)bl0;
    dst[r + stride] = (vbj_label)bl1;
    if (y0 + 2u * l < q) {
        dst[r + 2u * stride] = (vbj_label)bl2;
        dst[r + 3u * stride] = (vbj_label)bl3;
    }
}

/* 3D: pixels (y0 + a l, z0 + b l), a < 2, b < 4, named t = ab, read rows
 * y0 + (JY - 1) l, JY < 4, of planes z0 + (JZ - 1) l, JZ < 6; the read
 * concerns a in JY-2..JY and b in JZ-2..JZ. */
#define VBJ_IF3(a, b, JY, JZ)                                                     \
    if ((a) + 2 >= (JY) && (a) <= (JY) && (b) + 2 >= (JZ) && (b) <= (JZ))         \
        VBJ_OFFER(a##b, xy##a + zs##b)

#define VBJ_READ3(JY, JZ, xx, okx)                                                \
    {                                                                             \
        uint v = okr_ && (okx) ? (uint)src[row_ + (xx)] : VBJ_LNONE;              \
        if (v != cv) {                                                            \
            cv = v;                                                               \
            vbj_seed3 s_ = seeds[v == VBJ_LNONE ? 0u : v];                        \
            vbj_d x_ = v == VBJ_LNONE ? VBJ_DFAR : VBJ_SQ(cx - s_.x);             \
            xy0 = x_ + VBJ_SQ(cy0 - s_.y);                                        \
            xy1 = x_ + VBJ_SQ(cy1 - s_.y);                                        \
            zs0 = VBJ_SQ(cz0 - s_.z);                                             \
            zs1 = VBJ_SQ(cz1 - s_.z);                                             \
            zs2 = VBJ_SQ(cz2 - s_.z);                                             \
            zs3 = VBJ_SQ(cz3 - s_.z);                                             \
        }                                                                         \
        VBJ_IF3(0, 0, JY, JZ) VBJ_IF3(0, 1, JY, JZ) VBJ_IF3(0, 2, JY, JZ)         \
        VBJ_IF3(0, 3, JY, JZ) VBJ_IF3(1, 0, JY, JZ) VBJ_IF3(1, 1, JY, JZ)         \
        VBJ_IF3(1, 2, JY, JZ) VBJ_IF3(1, 3, JY, JZ)                               \
    }

#define VBJ_ROW3(JY, JZ)                                                          \
    {                                                                             \
        uint yy_ = y0 + (uint)((JY) - 1) * l, zz_ = z0 + (uint)((JZ) - 1) * l;    \
        int okr_ = yy_ < q && zz_ < q;                                            \
        uint row_ = (zz_ * q + yy_) * q;                                          \
        VBJ_READ3(JY, JZ, xm, xm < q)                                             \
        VBJ_READ3(JY, JZ, x, 1)                                                   \
        VBJ_READ3(JY, JZ, xp, xp < q)                                             \
    }
#define VBJ_PLANE3(JZ) VBJ_ROW3(0, JZ) VBJ_ROW3(1, JZ) VBJ_ROW3(2, JZ) VBJ_ROW3(3, JZ)

/* The same on a q^3 grid: work-item (x, wy, wz) owns the 2 x 4 block above;
 * global size q x q / 2 x (q / l >= 4 ? q / 4 : l). */
kernel void jfa_step_3d(global const vbj_label *src, global vbj_label *dst,
                        global const vbj_seed3 *seeds, uint q, uint f, uint l)
{
    uint x = get_global_id(0), wy = get_global_id(1), wz = get_global_id(2);
    if (x >= q || wy >= q / 2u || wz >= (q / l >= 4u ? q / 4u : l))
        return;
    uint y0 = wy % l + 2u * l * (wy / l), z0 = wz % l + 4u * l * (wz / l);
    uint xm = x - l, xp = x + l;
    vbj_coord cx = VBJ_CENTRE(x, f), cy0 = VBJ_CENTRE(y0, f), cy1 = VBJ_CENTRE(y0 + l, f);
    vbj_coord cz0 = VBJ_CENTRE(z0, f), cz1 = VBJ_CENTRE(z0 + l, f);
    vbj_coord cz2 = z0 + 2u * l < q ? VBJ_CENTRE(z0 + 2u * l, f) : cz0;
    vbj_coord cz3 = z0 + 3u * l < q ? VBJ_CENTRE(z0 + 3u * l, f) : cz0;
    vbj_d bd00 = VBJ_DINIT, bd01 = VBJ_DINIT, bd02 = VBJ_DINIT, bd03 = VBJ_DINIT;
    vbj_d bd10 = VBJ_DINIT, bd11 = VBJ_DINIT, bd12 = VBJ_DINIT, bd13 = VBJ_DINIT;
    uint bl00 = VBJ_LNONE, bl01 = VBJ_LNONE, bl02 = VBJ_LNONE, bl03 = VBJ_LNONE;
    uint bl10 = VBJ_LNONE, bl11 = VBJ_LNONE, bl12 = VBJ_LNONE, bl13 = VBJ_LNONE;
    vbj_d xy0 = 0, xy1 = 0, zs0 = 0, zs1 = 0, zs2 = 0, zs3 = 0;
    uint cv = VBJ_NOCACHE;
    VBJ_PLANE3(0) VBJ_PLANE3(1) VBJ_PLANE3(2) VBJ_PLANE3(3) VBJ_PLANE3(4) VBJ_PLANE3(5)
    uint r = (z0 * q + y0) * q + x, sy = l * q, sz = l * q * q;
    dst[r] = (vbj_label)bl00;
    dst[r + sy] = (vbj_label)bl10;
    dst[r + sz] = (vbj_label)bl01;
    dst[r + sz + sy] = (vbj_label)bl11;
    if (z0 + 2u * l < q) {
        dst[r + 2u * sz] = (vbj_label)bl02;
        dst[r + 2u * sz + sy] = (vbj_label)bl12;
        dst[r + 3u * sz] = (vbj_label)bl03;
        dst[r + 3u * sz + sy] = (vbj_label)bl13;
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
