/* The channel graph's batch sweeps on the device (core/discrete/vbc_paths.h;
 * the plain-C twin is core/discrete/channel_paths.c): Jacobi rounds of
 * relaxation over the listed channel voxels, one work-item per voxel
 * pulling from those of its 26 neighbours (found through a grid map of
 * positions) that fell in the round before, until a round lowers none; then the predecessor rule. Each round reads
 * one distance buffer and writes the other, so no work-item reads what
 * another writes in the same round, and the fixed point, which is unique,
 * is the twin's and Dijkstra's bit for bit (the step arithmetic is
 * channel_paths_math.h, contraction off). */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

#include "channel_paths_math.h"

#define VBC_NONE 0xffffffffu

/* map[v[t]] = t (set) or VBC_NONE (clear) for every position t. */
__kernel void vbc_paths_map(__global const uint *v, uint n, __global uint *map, uint set)
{
    uint t = get_global_id(0);
    if (t < n)
        map[v[t]] = set ? t : VBC_NONE;
}

/* Both distance buffers: infinity, then 0 at the sources; the stamps
 * (the round that last lowered each distance) none, then 0 at the sources. */
__kernel void vbc_paths_init(uint n, __global double *d0, __global double *d1, __global uint *s0,
                             __global uint *s1)
{
    uint t = get_global_id(0);
    if (t < n) {
        d0[t] = d1[t] = INFINITY;
        s0[t] = s1[t] = VBC_NONE;
    }
}

__kernel void vbc_paths_seed(__global const uint *src, uint nsrc, __global double *d0,
                             __global double *d1, __global uint *s0, __global uint *s1)
{
    uint i = get_global_id(0);
    if (i < nsrc) {
        d0[src[i]] = d1[src[i]] = 0.0;
        s0[src[i]] = s1[src[i]] = 0u;
    }
}

/* Round r (from 1): dout[t] = min(din[t], din[u] + step(u, t)) over the
 * neighbours u lowered in round r - 1 (sprev[u] == r - 1): the others gave
 * their value to t already, in the round after they last fell, and a
 * distance only falls. snext[t] = r when t fell, else sprev[t]. */
__kernel void vbc_paths_round(__global const uint *v, uint n, __global const uint *map,
                              __global const double *clear, int nx, int ny, int nz, int weighted,
                              __global const double *din, __global double *dout,
                              __global const uint *sprev, __global uint *snext, uint r,
                              __global volatile uint *changed)
{
    uint t = get_global_id(0);
    if (t >= n)
        return;
    uint vt = v[t];
    int i = (int)(vt % (uint)nx), j = (int)((vt / (uint)nx) % (uint)ny);
    int k = (int)(vt / ((uint)nx * (uint)ny));
    double old = din[t], best = old, ct = clear[t];
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int ii = i + dx, jj = j + dy, kk = k + dz;
                if ((dx | dy | dz) == 0 || ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny ||
                    kk >= nz)
                    continue;
                uint u = map[ii + nx * (jj + ny * kk)];
                if (u == VBC_NONE || sprev[u] != r - 1u)
                    continue;
                double nd = din[u] + vbc_path_step(abs(dx) + abs(dy) + abs(dz), clear[u], ct, weighted);
                if (nd < best)
                    best = nd;
            }
    dout[t] = best;
    snext[t] = best < old ? r : sprev[t];
    if (best < old)
        *changed = 1u;
}

/* The predecessor of every position from the fixed point d (vbc_paths.h). */
__kernel void vbc_paths_pred(__global const uint *v, uint n, __global const uint *map,
                             __global const double *clear, int nx, int ny, int nz, int weighted,
                             __global const double *d, __global uint *pred)
{
    uint t = get_global_id(0);
    if (t >= n)
        return;
    uint vt = v[t], best = VBC_NONE;
    int i = (int)(vt % (uint)nx), j = (int)((vt / (uint)nx) % (uint)ny);
    int k = (int)(vt / ((uint)nx * (uint)ny));
    double dq = d[t], bd = INFINITY, ct = clear[t];
    if (dq > 0.0 && dq < INFINITY)
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int ii = i + dx, jj = j + dy, kk = k + dz;
                    if ((dx | dy | dz) == 0 || ii < 0 || jj < 0 || kk < 0 || ii >= nx ||
                        jj >= ny || kk >= nz)
                        continue;
                    uint u = map[ii + nx * (jj + ny * kk)];
                    if (u == VBC_NONE)
                        continue;
                    double du = d[u];
                    if (du + vbc_path_step(abs(dx) + abs(dy) + abs(dz), clear[u], ct, weighted) == dq &&
                        vbc_path_pred_before(du, u, bd, best)) {
                        bd = du;
                        best = u;
                    }
                }
    pred[t] = best;
}
