/* Jump Flooding in gather form (paper Sec. 2.2 and 2.5): in the step of
 * length l every pixel reads the labels of its 3^d - 1 neighbours at distance
 * l and keeps the seed nearest to its centre (ties to the lower index).
 *
 * On an H100, 256^3 with 13,573 seeds, JFA+1 takes 3.23 ms (an H200: 3.22
 * ms), 0.43 ms for each step with l <= 8 (27 candidates per pixel: a label
 * read, a seed gather, a squared distance, a compare with the tie rule; the
 * float build capped at 48 registers on NVIDIA, see gpu/jfa.c). Moving the
 * arithmetic from doubles to floats gained about 10 % only, and code size
 * counts: with the exact fallback inlined at each of the unrolled offers the
 * kernel was 1.4x slower
 * (papers/facet-jfa-and-channels/results/jfa/README.md). So:
 *
 * - A work-item owns a block of pixels spaced l apart: VBJ_BX x VBJ_BY2 in
 *   2D, VBJ_BX x VBJ_BY x VBJ_BZ in 3D (build options: the host passes the
 *   shape it launches for, 2 x 4 and 2 x 2 x 2). Neighbours of the block's
 *   pixels coincide, so a 2 x 2 x 2 block reads 4^3 = 64 labels for 8 pixels
 *   instead of 216.
 * - Per label read, the seed's coordinate terms (x^2 + y^2 per column and
 *   row, z^2 per plane of the block) are computed once, and only when the
 *   label differs from the last one fetched; each pixel the read concerns
 *   then costs one add and the compare.
 * - Reads without a label are skipped, and so is a read whose label another
 *   read of the same row already offers to all of its pixels (late steps
 *   read the same label along x most of the time).
 * - Distances, three builds:
 *   VBJ_DISTF (the host's choice when n <= 256): a float filter; near ties
 *     are redone exactly. Seeds and centres are 16.16 integers of magnitude
 *     below 2^24, exact in float, so each difference e is an exact float
 *     integer (|e| <= 2^24) and only the squares and the two adds round:
 *     with u = 2^-24 the computed D~ = D (1 + t), |t| <= (1 + u)^3 - 1 <
 *     3.0001 u = eps (all terms are >= 0, so relative errors do not grow;
 *     D = 0 gives D~ = 0). Per pixel the kernel keeps h = fl(D~b (1 + 2^-19))
 *     for its best seed b (h = infinity before the first).
 *     A candidate c with D~c > h is farther: Dc >= D~c / (1 + eps) > D~b
 *     (1 + 2^-19)(1 - u) / (1 + eps) >= Db (1 + 2^-19)(1 - u)(1 - eps) /
 *     (1 + eps) > Db, since 2^-19 = 32 u exceeds u + 2 eps plus products.
 *     A candidate with D~c < fl(h (1 - 2^-17)) is nearer: D~c < D~b
 *     (1 + 2^-19)(1 - 2^-17)(1 + u)^2 < D~b (1 - 2^-18), so Dc <= D~c /
 *     (1 - eps) < Db (1 - 2^-18)(1 + eps) / (1 - eps) < Db (2^-18 = 64 u).
 *     c = b changes nothing. Anything else is a near tie (D~c within a
 *     relative ~2^-17 of D~b, incl. exact ties and D~b = D~c = 0): it only
 *     marks the pixel, whose step is then redone with exact 64-bit integer
 *     distances (vbj_exact_step3: its 27 candidates from the integer seed
 *     copy, vbj_dist2 and vbj_better as in the C reference). Pixels never
 *     marked took only decisions proven above.
 *   default: doubles holding the 16.16 integers, exact while dim n^2 2^32
 *     <= 2^53 (3D n <= 512, 2D n <= 1024).
 *   VBJ_DIST64: exact 64-bit integers, any n.
 * - Pixels of a block that lie past the grid (when q / l is below the block
 *   side) get a valid centre and are never written.
 * Every decision equals the exact one, and the minimum over (distance,
 * index) does not depend on the order of the candidates, so the kernels
 * agree with the C reference bit for bit.
 *
 * Built six times: -DVBJ_LABEL16 for 16-bit label grids (fewer than 65535
 * seeds; half the memory traffic), crossed with the three distance builds. */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

#ifdef VBJ_LABEL16
typedef ushort vbj_label;
#define VBJ_LNONE 0xffffu
#else
typedef uint vbj_label;
#define VBJ_LNONE VBJ_NONE
#endif

#if defined(VBJ_DISTF)
typedef float vbj_coord;
typedef float vbj_d;
typedef float2 vbj_seed2;
typedef float4 vbj_seed3;
#define VBJ_SQ(e) ((e) * (e))
#define VBJ_DINIT INFINITY
#define VBJ_CENTRE(p, f) ((float)vbj_cell_centre(p, f))
#define VBJ_UP (1.0f + 0x1p-19f)
#define VBJ_DOWN (1.0f - 0x1p-17f)
#elif defined(VBJ_DIST64)
typedef int vbj_coord;
typedef ulong vbj_d;
typedef int2 vbj_seed2;
typedef int4 vbj_seed3;
#define VBJ_SQ(e) ((ulong)((long)(e) * (e)))
#define VBJ_DINIT ULONG_MAX
#define VBJ_CENTRE(p, f) vbj_cell_centre(p, f)
#else
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double vbj_coord;
typedef double vbj_d;
typedef double2 vbj_seed2;
typedef double4 vbj_seed3;
#define VBJ_SQ(e) ((e) * (e))
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

/* "Not a label": forces the first offered read of a work-item to fetch its
 * seed. */
#define VBJ_NOCACHE 0xfffffffeu

/* Work-items along an axis with blocks of B pixels spaced l (q / l and B are
 * powers of two), and the first pixel of work-item w's block. */
#define VBJ_ITEMS(q, l, B) ((q) >> vbj_lg(l) >= (B) ? (q) / (B) : (l))
#define VBJ_FIRST(w, l, B) (((w) & ((l) - 1)) + (B) * (l) * ((w) >> vbj_lg(l)))

/* log2 of a power of two: shifts and masks instead of divisions by l. */
static inline uint vbj_lg(uint l) { return popcount(l - 1); }

/* Along an axis with blocks of B, read j (at first + (j - 1) l) concerns the
 * block's pixels lo..hi. Read j defers to read i of the same row that
 * concerns every pixel j does (and, concerning exactly the same pixels, comes
 * first); j is skipped when such an i holds the same label. Deferring is a
 * strict order, so a chain of skipped reads ends at one that is offered. */
#define VBJ_LO(j) ((j) >= 2 ? (j) - 2 : 0)
#define VBJ_HI(j, B) ((j) < (B) ? (j) : (B) - 1)
#define VBJ_COVERS(i, j, B) (VBJ_LO(i) <= VBJ_LO(j) && VBJ_HI(i, B) >= VBJ_HI(j, B))
#define VBJ_DEFERS(j, i, B)                                                       \
    ((i) != (j) && VBJ_COVERS(i, j, B) && (!VBJ_COVERS(j, i, B) || (i) < (j)))

/* Offers seed v at squared distance dist to the pixel whose state is
 * (key, lab): nearer, or as near with a lower index (Definition 2). A branch,
 * not selects: most offers change nothing. VBJ_DISTF: key is h of the filter
 * above; a near tie (neither test decides) sets the pixel's bit in `near`
 * and the pixel is redone exactly at the end (vbj_exact_step*), which keeps
 * the rare slow path out of the unrolled offers. */
#ifdef VBJ_DISTF
#define VBJ_OFFER(key, lab, dist, bit)                                            \
    {                                                                             \
        float d_ = (dist);                                                        \
        if (d_ <= (key) && v != (lab)) {                                          \
            if (d_ < (key) * VBJ_DOWN) {                                          \
                key = d_ * VBJ_UP;                                                \
                lab = v;                                                          \
            } else {                                                              \
                near |= (bit);                                                    \
            }                                                                     \
        }                                                                         \
    }
#else
#define VBJ_OFFER(key, lab, dist, bit)                                            \
    {                                                                             \
        vbj_d d_ = (dist);                                                        \
        if (d_ < (key) || (d_ == (key) && v < (lab))) {                           \
            key = d_;                                                             \
            lab = v;                                                              \
        }                                                                         \
    }
#endif

/* One pixel's step with exact integer distances, for pixels where the float
 * filter met a near tie: its label after the step of length l. */
__attribute__((noinline)) static uint vbj_exact_step2(global const vbj_label *src,
                                                      global const int2 *iseeds, uint q,
                                                      uint f, uint l, uint x, uint y)
{
    int cx = vbj_cell_centre(x, f), cy = vbj_cell_centre(y, f);
    uint best = VBJ_LNONE;
    ulong bd = ULONG_MAX;
    for (int j = 0; j < 9; j++) {
        uint xx = x + (uint)(j % 3) * l - l, yy = y + (uint)(j / 3) * l - l;
        uint v = xx < q && yy < q ? src[yy * q + xx] : VBJ_LNONE;
        if (v == VBJ_LNONE)
            continue;
        int2 s = iseeds[v];
        ulong d = vbj_dist2(cx, cy, 0, s.x, s.y, 0);
        if (vbj_better(d, v, bd, best)) {
            bd = d;
            best = v;
        }
    }
    return best;
}

__attribute__((noinline)) static uint vbj_exact_step3(global const vbj_label *src,
                                                      global const int4 *iseeds, uint q,
                                                      uint f, uint l, uint x, uint y, uint z)
{
    int cx = vbj_cell_centre(x, f), cy = vbj_cell_centre(y, f), cz = vbj_cell_centre(z, f);
    uint best = VBJ_LNONE;
    ulong bd = ULONG_MAX;
    for (int j = 0; j < 27; j++) {
        uint xx = x + (uint)(j % 3) * l - l, yy = y + (uint)(j / 3 % 3) * l - l;
        uint zz = z + (uint)(j / 9) * l - l;
        uint v = xx < q && yy < q && zz < q ? src[(zz * q + yy) * q + xx] : VBJ_LNONE;
        if (v == VBJ_LNONE)
            continue;
        int4 s = iseeds[v];
        ulong d = vbj_dist2(cx, cy, cz, s.x, s.y, s.z);
        if (vbj_better(d, v, bd, best)) {
            bd = d;
            best = v;
        }
    }
    return best;
}

/* Reads the labels of one row of the neighbourhood (x = x0 + (j - 1) l,
 * j < VBJ_BX + 2) into vr; outside the grid (or !ok) reads as VBJ_LNONE. */
static inline void vbj_row(global const vbj_label *src, uint *vr, int ok, uint row, uint x0,
                           uint l, uint q)
{
#pragma unroll
    for (int j = 0; j < VBJ_BX + 2; j++) {
        uint xx = x0 + (uint)j * l - l;
        vr[j] = ok && xx < q ? (uint)src[row + xx] : VBJ_LNONE;
    }
}

/* Nonzero when read j of row vr is offered: a label, and no other read of
 * the row offers it to all of j's pixels. */
static inline int vbj_wanted(const uint *vr, int j)
{
    int keep = vr[j] != VBJ_LNONE;
#pragma unroll
    for (int i = 0; i < VBJ_BX + 2; i++)
        if (VBJ_DEFERS(j, i, VBJ_BX))
            keep &= vr[i] != vr[j];
    return keep;
}

/* The step kernels, jfa_step_2d and jfa_step_3d: one body (jfa_step.h)
 * built for each dimension. */
#define VBJ_D 2
#include "jfa_step.h"
#undef VBJ_D
#define VBJ_D 3
#include "jfa_step.h"
#undef VBJ_D

/* "No such line" in jfa_boundary (past the grid), unlike VBJ_NONE ("not one
 * label"). */
#define VBJ_BND_ABSENT 0xfffffffeu

/* The label shared by the cross-section of a pixel's neighbourhood at
 * position w of the last axis (3D: x +- 1, y +- 1 at z = w; 2D: x +- 1 at
 * y = w; inside the grid), or VBJ_NONE when they differ. */
static uint vbj_section_label(global const vbj_label *lab, uint n, uint dim, uint x, uint y,
                              uint w)
{
    uint first = VBJ_NONE;
    int same = 1, ry = dim == 3 ? 1 : 0;
    for (int dy = -ry; dy <= ry; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            uint xx = x + (uint)dx, yy = y + (uint)dy;
            if (xx >= n || yy >= n)
                continue;
            uint v = lab[(dim == 3 ? (w * n + yy) * n : w * n) + xx];
            same &= first == VBJ_NONE || v == first;
            first = v;
        }
    return same ? first : VBJ_NONE;
}

/* Adds to *count the pixels of the n^d label grid (dim 2 or 3) with a
 * neighbour (3^d - 1, l = 1) of another label: the boundary pixels, which
 * Facet-JFA leaves unmarked. A work-item takes VBJ_BND_B pixels along the
 * last axis: a pixel is interior when the cross-sections before, at and
 * after it each share one label, the same (or lie past the grid), so a
 * cross-section is read once for up to three pixels. Global size n x n x
 * ceil(n / VBJ_BND_B) (3D), n x ceil(n / VBJ_BND_B) (2D); one atomic per
 * work-group. */
kernel void jfa_boundary(global const vbj_label *lab, global uint *count, uint n, uint dim)
{
    local uint group_count;
    uint x = get_global_id(0), y = dim == 3 ? get_global_id(1) : 0;
    uint w0 = (dim == 3 ? get_global_id(2) : get_global_id(1)) * VBJ_BND_B;
    int first = get_local_id(0) == 0 && get_local_id(1) == 0 && get_local_id(2) == 0;
    if (first)
        group_count = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (x < n && y < n && w0 < n) {
        uint u[VBJ_BND_B + 2], edge = 0;
#pragma unroll
        for (int t = 0; t < VBJ_BND_B + 2; t++) {
            uint w = w0 + (uint)t - 1u;
            u[t] = w < n ? vbj_section_label(lab, n, dim, x, y, w) : VBJ_BND_ABSENT;
        }
#pragma unroll
        for (int i = 1; i <= VBJ_BND_B; i++)
            if (u[i] != VBJ_BND_ABSENT)
                edge += u[i] == VBJ_NONE || (u[i - 1] != u[i] && u[i - 1] != VBJ_BND_ABSENT) ||
                        (u[i + 1] != u[i] && u[i + 1] != VBJ_BND_ABSENT);
        if (edge)
            atomic_add(&group_count, edge);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (first && group_count)
        atomic_add(count, group_count);
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
