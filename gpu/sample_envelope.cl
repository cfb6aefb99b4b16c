/* Sec. 3.3 of the seed paper: one work-item per ray. The ray's colour is the
 * id of the first bisector it meets (lower envelope over the tile's culled
 * bisector list), or VBS_INF_COLOUR. All the math is vb_geom_shared.h, the
 * same code the reference backend runs. */
#include "vb_geom_shared.h"

__kernel void vbs_envelope_kernel(__global const vbs_base *bases,
                                  __global const vbs_bisector *bis,
                                  __global const uint *tile_off,
                                  __global const uint *tile_idx,
                                  __global uint *colours, uint S, uint T, uint nbases)
{
    size_t gid = get_global_id(0);
    size_t per_base = 6u * (size_t)S * S;
    if (gid >= per_base * nbases)
        return;
    uint b = (uint)(gid / per_base);
    uint r = (uint)(gid % per_base);
    uint f = r / (S * S), q = r % (S * S);
    colours[gid] = vbs_ray_colour(bases + b, bis, tile_off, tile_idx, T, S, f, q % S, q / S);
}
