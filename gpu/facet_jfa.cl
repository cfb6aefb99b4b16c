/* Facet-JFA (paper Sec. 2.3, Algorithm 1) with compaction: after JFA on the
 * coarse m^d grid, each doubling runs one l = 1 step on the children of the
 * unmarked cells only and marks the children whose neighbours all share
 * their label. Work-items of the step and the marking are launched only for
 * the cells of the active list, never for the whole grid (the optimisation
 * the paper leaves open).
 *
 * Storage: one dense array per level, (2^lq)^d labels at level-linear index
 * x | y << lq | z << 2 lq (the coarse JFA's own grid for level 0). Before
 * the step of a doubling every cell holds its parent's label, so the step
 * reads the level above; the children of marked cells inherit label and
 * mark (as in the C reference), the listed cells get the step's result.
 * Every read is one load from a dense array, where sparse storage (only the
 * listed cells written) would walk up from unwritten cells to their marked
 * ancestors, one dependent load per level. Labels of marked cells carry
 * VBJ_MARK.
 *
 * Lists hold level-linear cell indices. Their lengths stay on the device:
 * the cells of doubling j are the children of the cnt[j] parents refined
 * before it, and the marking of doubling j counts the parents of the next
 * one in cnt[j + 1] (at the last level: the boundary pixels). The kernels
 * loop over the lists with a fixed number of work-items, so no level waits
 * for the host. Seeds are a flat int array of stride 2 (2D) or 4 (3D), 16.16
 * fixed point. */
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

static inline uint encode(uint x, uint y, uint z, uint lq)
{
    return x | (y << lq) | (z << (2u * lq));
}

/* Offers label v (none: the value that means "no seed") to a cell centred
 * at (px, py, pz) whose nearest so far is (*bd, *best): the nearer seed wins,
 * ties to the lower index. */
static inline void offer(global const int *seeds, uint dim, int px, int py, int pz, uint v,
                         uint none, ulong *bd, uint *best)
{
    if (v == none || v == *best)
        return;
    global const int *s = seeds + (size_t)v * (dim == 3 ? 4u : 2u);
    ulong d = vbj_dist2(px, py, pz, s[0], s[1], dim == 3 ? s[2] : 0);
    if (vbj_better(d, v, *bd, *best)) {
        *bd = d;
        *best = v;
    }
}

/* Doubling j to level 2^lq (cells of 2^lf pixels), from prev, the labels of
 * the level above: every cell whose parent is marked inherits the parent's
 * label and mark into B; each of the cnt[j] << dim listed cells (the
 * children of the unmarked parents) takes one JFA step with l = 1: the
 * nearest seed among its own and its neighbours' labels before the step,
 * written to B. Before the step every cell holds its parent's label, so
 * those 3^d cells offer the labels of the 2^d parents around the cell's
 * corner (parents p - 1 and p along x for an even x, p and p + 1 for an odd
 * one; the same set, read 2^d times instead of 3^d). The two parts write
 * disjoint cells and read only prev, so they share one launch. */
static void step_level(global const uint *list, global const uint *cnt, uint j,
                       global const uint *prev, global uint *B, global const int *seeds,
                       uint lq, uint lf, uint dim, uint first, uint stride_items)
{
    uint cells = 1u << (dim * lq);
    for (uint i = first; i < cells; i += stride_items) {
        cell3 c = decode(i, lq, dim);
        uint p = prev[encode(c.x >> 1, c.y >> 1, c.z >> 1, lq - 1u)];
        if (p & VBJ_MARK)
            B[i] = p;
    }
    uint count = cnt[j] << dim;
    uint qp = 1u << (lq - 1u), f = 1u << lf;
    uint nz = dim == 3 ? 2u : 1u;
    for (uint i = first; i < count; i += stride_items) {
        uint idx = list[i];
        cell3 c = decode(idx, lq, dim);
        int px = vbj_cell_centre(c.x, f), py = vbj_cell_centre(c.y, f);
        int pz = dim == 3 ? vbj_cell_centre(c.z, f) : 0;
        /* First parent of the 2^d: p - 1 for an even coordinate (past qp
         * as unsigned at 0), p for an odd one. */
        uint x0 = (c.x >> 1) - 1u + (c.x & 1u), y0 = (c.y >> 1) - 1u + (c.y & 1u);
        uint z0 = dim == 3 ? (c.z >> 1) - 1u + (c.z & 1u) : 0u;
        uint best = VBJ_NONE;
        ulong bd = ULONG_MAX;
        for (uint dz = 0; dz < nz; dz++)
            for (uint dy = 0; dy < 2; dy++)
                for (uint dx = 0; dx < 2; dx++) {
                    uint x = x0 + dx, y = y0 + dy, z = z0 + dz;
                    if (x >= qp || y >= qp || (dim == 3 && z >= qp))
                        continue; /* outside */
                    offer(seeds, dim, px, py, pz,
                          prev[encode(x, y, z, lq - 1u)] & VBJ_LABEL_MASK,
                          VBJ_NONE & VBJ_LABEL_MASK, &bd, &best);
                }
        B[idx] = best;
    }
}

/* The work-items of a list kernel share its loops: work-item i of N takes
 * entries i, i + N, ... (N: the global size, so a fixed launch covers any
 * list length). */
kernel void facet_step(global const uint *list, global const uint *cnt, uint j,
                       global const uint *prev, global uint *B, global const int *seeds,
                       uint lq, uint lf, uint dim)
{
    step_level(list, cnt, j, prev, B, seeds, lq, lf, dim, get_global_id(0), get_global_size(0));
}

/* For the cnt[j] << shift listed cells (dense: cell i) of level 2^lq, whose
 * labels are in B: with do_mark, marks the cells whose neighbours all carry
 * their label; with do_refine, lists the 2^dim children of every other cell
 * in next and counts it in cnt[j + 1]; without do_refine (the last level)
 * lists the cell itself, so next ends as the boundary pixels. Marking only
 * sets VBJ_MARK, so concurrent readers that compare labels see the same
 * label. */
static void mark_refine_level(global const uint *list, uint dense, global uint *cnt, uint j,
                              uint shift, uint do_mark, uint do_refine, global uint *B,
                              global uint *next, uint lq, uint dim, uint first,
                              uint stride_items)
{
    uint count = cnt[j] << shift;
    uint q = 1u << lq, nc = 1u << dim;
    int rz = dim == 3 ? 1 : 0;
    for (uint i = first; i < count; i += stride_items) {
        uint idx = dense ? i : list[i];
        cell3 c = decode(idx, lq, dim);
        uint me = B[idx] & VBJ_LABEL_MASK;
        int same = do_mark != 0;
        for (int dz = -rz; dz <= rz && same; dz++)
            for (int dy = -1; dy <= 1 && same; dy++)
                for (int dx = -1; dx <= 1 && same; dx++) {
                    uint x = c.x + (uint)dx, y = c.y + (uint)dy, z = c.z + (uint)dz;
                    if (x >= q || y >= q || (dim == 3 && z >= q))
                        continue;
                    same = (B[encode(x, y, z, lq)] & VBJ_LABEL_MASK) == me;
                }
        if (same) {
            B[idx] = me | VBJ_MARK;
        } else if (do_refine) {
            uint slot = atomic_inc(&cnt[j + 1]);
            for (uint k = 0; k < nc; k++)
                next[slot * nc + k] = encode(2u * c.x + (k & 1u), 2u * c.y + ((k >> 1) & 1u),
                                             dim == 3 ? 2u * c.z + (k >> 2) : 0u, lq + 1u);
        } else {
            next[atomic_inc(&cnt[j + 1])] = idx;
        }
    }
}

kernel void facet_mark_refine(global const uint *list, uint dense, global uint *cnt, uint j,
                              uint shift, uint do_mark, uint do_refine, global uint *B,
                              global uint *next, uint lq, uint dim)
{
    mark_refine_level(list, dense, cnt, j, shift, do_mark, do_refine, B, next, lq, dim,
                      get_global_id(0), get_global_size(0));
}

/* One dense JFA step of length l on the q^d grid of cells of f pixels, src
 * to dst, exactly as the C reference: each cell takes the nearest seed
 * (ties to the lower index) among its own and its 3^d - 1 neighbours'
 * labels. Cells first, first + stride_items, ... */
static void coarse_step(global const uint *src, global uint *dst, global const int *seeds,
                        uint q, uint lq, uint f, uint l, uint dim, uint first,
                        uint stride_items)
{
    uint cells = 1u << (dim * lq);
    int rz = dim == 3 ? 1 : 0;
    for (uint i = first; i < cells; i += stride_items) {
        cell3 c = decode(i, lq, dim);
        int px = vbj_cell_centre(c.x, f), py = vbj_cell_centre(c.y, f);
        int pz = dim == 3 ? vbj_cell_centre(c.z, f) : 0;
        uint best = VBJ_NONE;
        ulong bd = ULONG_MAX;
        for (int dz = -rz; dz <= rz; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    uint x = c.x + (uint)dx * l, y = c.y + (uint)dy * l, z = c.z + (uint)dz * l;
                    if (x >= q || y >= q || (dim == 3 && z >= q))
                        continue; /* outside */
                    offer(seeds, dim, px, py, pz, src[encode(x, y, z, lq)], VBJ_NONE, &bd,
                          &best);
                }
        dst[i] = best;
    }
}

/* The start of Facet-JFA in one work-group, for small levels, where a launch
 * per phase would cost more than the phase: the counters (cnt[0] = m^d, the
 * rest 0), the seeds placed on the coarse m^d grid (g0), JFA on it (lengths
 * m/2 .. 1, g0 and g1 in turn), its marking/refinement as level 0 (list0),
 * then doublings 1 .. jlast exactly as facet_step and facet_mark_refine
 * (level j's labels in store[j & 1], its list in list[j & 1]), with a
 * barrier between phases. compact and levels as the host's loop: a doubling
 * marks when compact or at the last level, and refines but at the last. */
kernel void facet_small(global const uint *pairs, uint npairs, global uint *g0, global uint *g1,
                        global const int *seeds, global uint *cnt, uint ncnt,
                        global uint *store0, global uint *store1, global uint *list0,
                        global uint *list1, uint lm, uint ln, uint dim, uint compact,
                        uint jlast)
{
    uint me = get_local_id(0), items = get_local_size(0);
    uint m = 1u << lm, cells = 1u << (dim * lm), levels = ln - lm;
    for (uint i = me; i < ncnt; i += items)
        cnt[i] = i == 0 ? cells : 0u;
    for (uint i = me; i < cells; i += items)
        g0[i] = VBJ_NONE;
    barrier(CLK_GLOBAL_MEM_FENCE);
    for (uint i = me; i < npairs; i += items)
        g0[pairs[2 * i]] = pairs[2 * i + 1];
    global uint *src = g0, *dst = g1;
    for (uint l = m >> 1; l >= 1; l >>= 1) {
        barrier(CLK_GLOBAL_MEM_FENCE);
        coarse_step(src, dst, seeds, m, lm, 1u << (ln - lm), l, dim, me, items);
        global uint *t = src;
        src = dst;
        dst = t;
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
    mark_refine_level(list1, 1, cnt, 0, 0, 0, 1, src, list0, lm, dim, me, items);
    global const uint *prev = src;
    for (uint j = 1; j <= jlast; j++) {
        uint lq = lm + j, last = j == levels;
        global uint *B = j & 1 ? store1 : store0;
        global uint *from = j & 1 ? list0 : list1, *to = j & 1 ? list1 : list0;
        barrier(CLK_GLOBAL_MEM_FENCE);
        step_level(from, cnt, j, prev, B, seeds, lq, ln - lq, dim, me, items);
        barrier(CLK_GLOBAL_MEM_FENCE);
        mark_refine_level(from, 0, cnt, j, dim, compact || last, !last, B, to, lq, dim, me,
                          items);
        prev = B;
    }
}

/* The label grid of the last level without the marks, in place. */
kernel void facet_strip(global uint *B, uint cells)
{
    uint i = get_global_id(0);
    if (i < cells)
        B[i] &= VBJ_LABEL_MASK;
}
