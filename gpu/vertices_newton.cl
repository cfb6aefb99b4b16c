/* Sec. 4-5 of the seed paper: one work-item per grid cell. Cells with three
 * or more colours run Newton-Raphson (with subdivision, the four-colour
 * triples and the wrong-sheet restart, all in vb_geom_shared.h) and append
 * their candidates through an atomic counter; the host sorts them by
 * (base, cell, rank), so the order of appends does not matter. */
#include "vb_geom_shared.h"

__kernel void vbs_vertices_kernel(__global const vbs_base *bases,
                                  __global const vbs_bisector *bis,
                                  __global const uint *tile_off,
                                  __global const uint *tile_idx,
                                  __global const uint *colours,
                                  __constant vbs_params *params,
                                  __global vbs_cand *out, __global uint *counters,
                                  uint cap, uint nbases)
{
    size_t gid = get_global_id(0);
    vbs_params p = *params;
    uint g = p.samples - 1u;
    size_t per_base = 6u * (size_t)g * g;
    if (gid >= per_base * nbases)
        return;
    uint b = (uint)(gid / per_base);
    uint cell = (uint)(gid % per_base);
    vbs_cand buf[VBS_MAX_CAND];
    vbs_emit em;
    em.out = buf;
    em.cap = VBS_MAX_CAND;
    em.n = 0u;
    em.overflow = 0u;
    em.cell = cell;
    __global const uint *col = colours + (size_t)b * 6u * p.samples * p.samples;
    vbs_cell_vertices(bases + b, bis, tile_off, tile_idx, &p, col, cell, &em);
    if (em.overflow)
        atomic_add(counters + 1, em.overflow);
    for (uint k = 0u; k < em.n; k++) {
        uint slot = atomic_inc(counters);
        if (slot < cap)
            out[slot] = buf[k];
    }
}
