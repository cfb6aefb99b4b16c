/* Facet-JFA (paper Sec. 2.3, Algorithm 1) with compaction: after JFA on the
 * coarse m^d grid, each doubling refines only the unmarked cells, runs one
 * l = 1 step on their children and marks the children whose neighbours all
 * share their label. Work-items are launched only for the cells of the active
 * list, never for the whole grid (the optimisation the paper leaves open).
 *
 * Storage: two n^d arrays in fine pixels. A cell of 2^lf pixels at level
 * coordinates (x, y, z) keeps its label at its origin pixel (x, y, z) << lf.
 * Refinement writes the children of unmarked cells only, so the children of a
 * marked cell are never written: reading such a cell finds VBJ_NONE and walks
 * up to the nearest written ancestor, the marked one, whose label it inherits
 * (read_cell). Labels of marked cells carry VBJ_MARK. The step reads one array
 * and writes its results into the other (the step must see the labels from
 * before the step); marking and refinement then write both, so at every level
 * boundary the two agree and swap roles. Two kernels per doubling: step, and
 * mark + refine.
 *
 * Lists hold level-linear cell indices (x | y << lq | z << 2 lq). Their lengths
 * stay on the device: the cells of doubling j are the children of the cnt[j]
 * parents refined before it, and the marking of doubling j counts the
 * parents of the next one in cnt[j + 1] (at the last level: the boundary
 * pixels). The kernels loop over the lists with a fixed number of
 * work-items, so no level waits for the host. Seeds are a flat int array of
 * stride 2 (2D) or 4 (3D), 16.16 fixed point. */
#pragma OPENCL FP_CONTRACT OFF
#include "vb_grid.h"

typedef struct {
    uint x, y, z;
} cell3;

static inline cell3 decode(uint idx, uint lq, uint dim)
{
    uint mask = (1u << lq) - 1u;
    cell3 c = {idx & mask, (idx >> lq) & mask, dim == 3 ? idx >> (2u * lq) : 0u};
    return c;
}

static inline uint origin(uint x, uint y, uint z, uint lf, uint n)
{
    return ((z << lf) * n + (y << lf)) * n + (x << lf);
}

/* Label stored for a cell, or inherited from its nearest written ancestor
 * (lfmax: cell size of the coarse JFA level, where every cell is written). */
static inline uint read_cell(global const uint *B, uint n, uint x, uint y, uint z, uint lf,
                             uint lfmax)
{
    uint v = B[origin(x, y, z, lf, n)];
    while (v == VBJ_NONE && lf < lfmax) {
        x >>= 1;
        y >>= 1;
        z >>= 1;
        lf++;
        v = B[origin(x, y, z, lf, n)];
    }
    return v;
}

/* Copies the dense coarse JFA result (m = 2^lq per side) into both arrays. */
kernel void facet_expand(global const uint *coarse, global uint *B0, global uint *B1, uint lq,
                         uint lf, uint n, uint dim)
{
    uint cells = 1u << (dim * lq);
    for (uint i = get_global_id(0); i < cells; i += get_global_size(0)) {
        cell3 c = decode(i, lq, dim);
        uint o = origin(c.x, c.y, c.z, lf, n);
        B0[o] = B1[o] = coarse[i];
    }
}

/* One JFA step with l = 1 on the cnt[j] << dim listed cells (level 2^lq,
 * cells of 2^lf pixels): the nearest seed among the cell's label and its
 * neighbours' in Bold, written to the cell's origin in Bnew. */
kernel void facet_step(global const uint *list, global const uint *cnt, uint j,
                       global const uint *Bold, global uint *Bnew, global const int *seeds,
                       uint lq, uint lf, uint lfmax, uint n, uint dim)
{
    uint count = cnt[j] << dim;
    uint q = 1u << lq, f = 1u << lf, stride = dim == 3 ? 4u : 2u;
    int rz = dim == 3 ? 1 : 0;
    for (uint i = get_global_id(0); i < count; i += get_global_size(0)) {
        cell3 c = decode(list[i], lq, dim);
        int px = vbj_cell_centre(c.x, f), py = vbj_cell_centre(c.y, f);
        int pz = dim == 3 ? vbj_cell_centre(c.z, f) : 0;
        uint best = VBJ_NONE;
        ulong bd = ULONG_MAX;
        for (int dz = -rz; dz <= rz; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int x = (int)c.x + dx, y = (int)c.y + dy, z = (int)c.z + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= (int)q || y >= (int)q ||
                        z >= (dim == 3 ? (int)q : 1))
                        continue;
                    uint v = read_cell(Bold, n, (uint)x, (uint)y, (uint)z, lf, lfmax) &
                             VBJ_LABEL_MASK;
                    if (v == (VBJ_NONE & VBJ_LABEL_MASK) || v == best)
                        continue;
                    global const int *s = seeds + (size_t)v * stride;
                    ulong d = vbj_dist2(px, py, pz, s[0], s[1], dim == 3 ? s[2] : 0);
                    if (vbj_better(d, v, bd, best)) {
                        bd = d;
                        best = v;
                    }
                }
        Bnew[origin(c.x, c.y, c.z, lf, n)] = best;
    }
}

/* For the cnt[j] << shift listed cells (dense: cell i) of level 2^lq, whose
 * labels are in Bnew: with do_mark, marks (in both arrays) the cells whose
 * neighbours all carry their label; with do_refine, splits every other cell
 * into its 2^dim children (labels in both arrays, indices appended to next)
 * and counts it in cnt[j + 1]; without do_refine (the last level) appends the
 * cell itself, so next ends as the boundary pixels. Marking only sets
 * VBJ_MARK, so concurrent readers that compare labels see the same label. */
kernel void facet_mark_refine(global const uint *list, uint dense, global uint *cnt, uint j,
                              uint shift, uint do_mark, uint do_refine, global uint *Bnew,
                              global uint *Bold, global uint *next, uint lq, uint lf,
                              uint lfmax, uint n, uint dim)
{
    uint count = cnt[j] << shift;
    uint q = 1u << lq, nc = 1u << dim, lq2 = lq + 1u;
    int rz = dim == 3 ? 1 : 0;
    for (uint i = get_global_id(0); i < count; i += get_global_size(0)) {
        uint idx = dense ? i : list[i];
        cell3 c = decode(idx, lq, dim);
        uint o = origin(c.x, c.y, c.z, lf, n);
        uint me = Bnew[o] & VBJ_LABEL_MASK;
        int same = do_mark != 0;
        for (int dz = -rz; dz <= rz && same; dz++)
            for (int dy = -1; dy <= 1 && same; dy++)
                for (int dx = -1; dx <= 1 && same; dx++) {
                    int x = (int)c.x + dx, y = (int)c.y + dy, z = (int)c.z + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= (int)q || y >= (int)q ||
                        z >= (dim == 3 ? (int)q : 1))
                        continue;
                    same = (read_cell(Bnew, n, (uint)x, (uint)y, (uint)z, lf, lfmax) &
                            VBJ_LABEL_MASK) == me;
                }
        if (same) {
            Bnew[o] = Bold[o] = me | VBJ_MARK;
        } else if (do_refine) {
            uint slot = atomic_inc(&cnt[j + 1]);
            for (uint k = 0; k < nc; k++) {
                uint x = 2u * c.x + (k & 1u), y = 2u * c.y + ((k >> 1) & 1u),
                     z = dim == 3 ? 2u * c.z + (k >> 2) : 0u;
                uint oc = origin(x, y, z, lf - 1u, n);
                Bnew[oc] = Bold[oc] = me;
                next[slot * nc + k] = x | (y << lq2) | (z << (2u * lq2));
            }
        } else {
            next[atomic_inc(&cnt[j + 1])] = idx;
        }
    }
}

/* The full label grid: every pixel's own label or its marked ancestor's. */
kernel void facet_fill(global const uint *B, global uint *out, uint n, uint lfmax, uint dim)
{
    uint x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
    if (x >= n || y >= n || z >= (dim == 3 ? n : 1u))
        return;
    out[(z * n + y) * n + x] = read_cell(B, n, x, y, z, 0u, lfmax) & VBJ_LABEL_MASK;
}
