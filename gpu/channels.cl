/* Channel masks (Algorithm 2, steps 2-7, of the Facet-JFA paper) on a label
 * grid computed by gpu/jfa: the atomic mask by scattering atoms, the ray
 * bounds along the three axes, then one pass that classifies every voxel and
 * appends channel voxels to a compact list. The per-voxel arithmetic is
 * core/discrete/channel_math.h, shared with the C reference. */
#pragma OPENCL FP_CONTRACT OFF

#include "channel_math.h"

/* One work-group per atom: its items sweep the atom's bounding box and mark
 * the voxels whose centres lie in the grown ball. Many atoms write the same
 * byte, always the same value, so no atomics are needed. */
__kernel void vbc_atomic_mask(__global const float4 *atoms, __global uchar *flags, int nx, int ny,
                              int nz)
{
    float4 a = atoms[get_group_id(0)];
    int i0 = vbc_box_lo(a.x, a.w), i1 = vbc_box_hi(a.x, a.w, nx);
    int j0 = vbc_box_lo(a.y, a.w), j1 = vbc_box_hi(a.y, a.w, ny);
    int k0 = vbc_box_lo(a.z, a.w), k1 = vbc_box_hi(a.z, a.w, nz);
    int bx = i1 - i0, by = j1 - j0, bz = k1 - k0;
    if (bx <= 0 || by <= 0 || bz <= 0)
        return;
    int total = bx * by * bz;
    for (int t = (int)get_local_id(0); t < total; t += (int)get_local_size(0)) {
        int i = i0 + t % bx, j = j0 + (t / bx) % by, k = k0 + t / (bx * by);
        if (vbc_ball_contains(a.x, a.y, a.z, a.w, i, j, k))
            flags[i + nx * (j + ny * k)] = (uchar)VBC_F_ATOMIC;
    }
}

/* One work-item per ray of `axis` (see vbc_ray_scan for the (a,b) meaning). */
__kernel void vbc_ray_bounds(__global const uchar *flags, __global int *rb, int nx, int ny, int nz,
                             int axis)
{
    vbc_ray_scan(flags, nx, ny, nz, axis, (int)get_global_id(0), (int)get_global_id(1), rb);
}

/* One work-item per voxel: the flag byte in place (only the voxel's own
 * atomic bit is read from flags), and channel voxels appended to `list`
 * (index | mouth bit) through `count`; entries beyond `cap` are counted but
 * not stored, so the host can grow the list and rerun this pass. */
__kernel void vbc_classify_voxels(__global const int *labels, __global uchar *flags,
                                  __global const int *rb, int nx, int ny, int nz, int min_labels,
                                  __global uint *list, __global volatile uint *count, uint cap)
{
    int i = (int)get_global_id(0), j = (int)get_global_id(1), k = (int)get_global_id(2);
    if (i >= nx || j >= ny || k >= nz)
        return;
    unsigned f = vbc_classify(labels, flags, rb, nx, ny, nz, min_labels, i, j, k);
    int v = i + nx * (j + ny * k);
    flags[v] = (uchar)f;
    if (f & VBC_F_CHANNEL) {
        uint slot = atomic_inc(count);
        if (slot < cap)
            list[slot] = (uint)v | ((f & VBC_F_MOUTH) ? VBC_MOUTH_BIT : 0u);
    }
}

/* One work-item per listed channel voxel: the distance in Å from its centre
 * to the nearest atom surface (the clearance that steers the centrelines),
 * by brute force over the atoms staged through local memory. An atom's own
 * radius in voxels is its grown radius a.w minus the probe in voxels. */
__kernel void vbc_clearance(__global const uint *list, uint count, __global const float4 *atoms,
                            uint natoms, int nx, int ny, float probe_g, float h,
                            __global float *out, __local float4 *tile)
{
    uint gid = get_global_id(0), lid = get_local_id(0), ls = get_local_size(0);
    float px = 0.0f, py = 0.0f, pz = 0.0f;
    if (gid < count) {
        uint v = list[gid] & ~VBC_MOUTH_BIT;
        px = (float)(v % (uint)nx) + 0.5f;
        py = (float)((v / (uint)nx) % (uint)ny) + 0.5f;
        pz = (float)(v / ((uint)nx * (uint)ny)) + 0.5f;
    }
    float best = INFINITY;
    for (uint base = 0; base < natoms; base += ls) {
        if (base + lid < natoms)
            tile[lid] = atoms[base + lid];
        barrier(CLK_LOCAL_MEM_FENCE);
        uint m = min(ls, natoms - base);
        for (uint t = 0; t < m; t++) {
            float4 a = tile[t];
            float dx = px - a.x, dy = py - a.y, dz = pz - a.z;
            best = fmin(best, sqrt(dx * dx + dy * dy + dz * dz) - (a.w - probe_g));
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (gid < count)
        out[gid] = best * h;
}

/* Connected components of the listed channel voxels (26-connected), each
 * labelled by its smallest voxel index: the union-find's answer
 * (core/vb_uf.h, channel_components.c, the plain-C twin), which the host
 * checks on every edge it links. cc is a grid of labels, UINT_MAX off the
 * list. Hooking and pointer jumping: every label is a voxel of the same
 * component no larger than the voxel, labels only fall, so the order in
 * which work-items race does not change the fixed point, where a component
 * holds one label, its smallest voxel. */
__kernel void vbc_cc_seed(__global const uint *list, uint count, __global uint *cc)
{
    uint t = get_global_id(0);
    if (t < count) {
        uint v = list[t] & ~VBC_MOUTH_BIT;
        cc[v] = v;
    }
}

/* One work-item per listed voxel: the smallest label among its neighbours
 * hooks its own label's root; *changed set when any label fell. */
__kernel void vbc_cc_hook(__global const uint *list, uint count, __global volatile uint *cc,
                          int nx, int ny, int nz, __global volatile uint *changed)
{
    uint t = get_global_id(0);
    if (t >= count)
        return;
    uint v = list[t] & ~VBC_MOUTH_BIT;
    int i = (int)(v % (uint)nx), j = (int)((v / (uint)nx) % (uint)ny);
    int k = (int)(v / ((uint)nx * (uint)ny));
    uint mine = cc[v], best = mine;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int ii = i + dx, jj = j + dy, kk = k + dz;
                if (ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny || kk >= nz)
                    continue;
                best = min(best, cc[ii + nx * (jj + ny * kk)]);
            }
    if (best < mine) {
        atomic_min(&cc[mine], best);
        atomic_min(&cc[v], best);
        *changed = 1u;
    }
}

/* One work-item per listed voxel: its label replaced by its root's. */
__kernel void vbc_cc_jump(__global const uint *list, uint count, __global volatile uint *cc)
{
    uint t = get_global_id(0);
    if (t >= count)
        return;
    uint v = list[t] & ~VBC_MOUTH_BIT, l = cc[v];
    for (uint r = cc[l]; r != l; r = cc[l])
        l = r;
    cc[v] = l;
}

/* The label of each listed voxel, in list order. */
__kernel void vbc_cc_gather(__global const uint *list, uint count, __global const uint *cc,
                            __global uint *out)
{
    uint t = get_global_id(0);
    if (t < count)
        out[t] = cc[list[t] & ~VBC_MOUTH_BIT];
}
