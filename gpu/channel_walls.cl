/* The pore verdict's rasters on the device (core/discrete/vbc_walls.h; the
 * plain-C twin is core/discrete/channel_walls.c): one work-item per word
 * of 32 pixels of one plane, every plane of the pore in one launch, each
 * pixel blocked, free or unsure by channel_walls_math.h's float filter
 * (contraction off: the twin's bits). The host's flood reads them and
 * asks its cell list for the unsure pixels only. */
#pragma OPENCL FP_CONTRACT OFF

#include "channel_walls_math.h"

/* word0: nplanes + 1 first words (the last: the total); planes: 4 floats a
 * plane (its centre less the cells' corner); halves: each plane's half
 * side. The plane of word w is found by bisection of word0. */
__kernel void vbc_walls_raster(__global const float *atoms, __global const ulong *start, int dx,
                               int dy, int dz, float inv_cell, float reach, float far2,
                               float bound, float pixel, float4 a4, float4 b4,
                               __global const float *planes, __global const int *halves,
                               __global const ulong *word0, uint nplanes,
                               __global uint *blocked, __global uint *unsure)
{
    ulong w = get_global_id(0);
    if (w >= word0[nplanes])
        return;
    uint lo = 0, hi = nplanes; /* word0[lo] <= w < word0[hi] */
    while (hi - lo > 1) {
        uint mid = (lo + hi) / 2;
        if (word0[mid] <= w)
            lo = mid;
        else
            hi = mid;
    }
    int dim[3] = {dx, dy, dz};
    float P[3] = {planes[4 * lo], planes[4 * lo + 1], planes[4 * lo + 2]};
    float a[3] = {a4.x, a4.y, a4.z}, b[3] = {b4.x, b4.y, b4.z};
    uint bl, un;
    vbc_walls_word(atoms, start, dim, inv_cell, reach, far2, bound, P, a, b, pixel, halves[lo],
                   (uint)(w - word0[lo]), &bl, &un);
    blocked[w] = bl;
    unsure[w] = un;
}
