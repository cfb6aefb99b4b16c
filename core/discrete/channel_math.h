/* The arithmetic of the channel masks, written once for the C reference
 * (core/discrete/channel_masks_ref.c) and the OpenCL kernels (gpu/channels.cl).
 *
 * Everything is in grid units: voxel (i,j,k) has its centre at
 * (i + 0.5, j + 0.5, k + 0.5); an atom is a float4 (x, y, z, R) with R the
 * atomic radius plus the solvent radius, already divided by the voxel edge.
 * Both sides evaluate the same float expressions in the same order with
 * contraction off, so the masks agree bit for bit. */
#ifndef VBC_CHANNEL_MATH_H
#define VBC_CHANNEL_MATH_H

#include "vb_cl_compat.h"
#include "vbc_flags.h"

#define VBC_INLINE VB_SHARED_FN
#define VBC_GLOBAL VB_GLOBAL
typedef vb_u8 vbc_u8;


/* True when the centre of voxel (i,j,k) lies in the closed ball a. */
VBC_INLINE int vbc_ball_contains(float ax, float ay, float az, float ar, int i, int j, int k)
{
    float dx = ((float)i + 0.5f) - ax;
    float dy = ((float)j + 0.5f) - ay;
    float dz = ((float)k + 0.5f) - az;
    float d2 = dx * dx + dy * dy;
    d2 = d2 + dz * dz;
    return d2 <= ar * ar;
}

/* First voxel index along one axis whose centre may lie in a ball centred at
 * c with radius r (conservative by one voxel; the ball test decides). */
VBC_INLINE int vbc_box_lo(float c, float r)
{
    float v = c - r - 1.5f;
    return v < 0.0f ? 0 : (int)v;
}

/* One past the last voxel index that may lie in the ball, clipped to n. */
VBC_INLINE int vbc_box_hi(float c, float r, int n)
{
    float v = c + r + 1.5f;
    if (v < 0.0f)
        return 0;
    return (v > (float)n) ? n : (int)v;
}

/* Number of distinct values among l[0..m-1] (m small). */
VBC_INLINE int vbc_distinct(const int *l, int m)
{
    int count = 0;
    for (int a = 0; a < m; a++) {
        int seen = 0;
        for (int b = 0; b < a; b++)
            seen |= (l[b] == l[a]);
        count += !seen;
    }
    return count;
}

/* Ray bounds: for every axis ray the first and last voxel of the atomic mask
 * it meets (first = n, last = -1 when it meets none). Layout of the int array
 * `rb`: x rays (j,k) at 2*(j + ny*k), then y rays (i,k) at vbc_rb_y + 2*(i + nx*k),
 * then z rays (i,j) at vbc_rb_z + 2*(i + nx*j). Total vbc_rb_size ints. */
VBC_INLINE int vbc_rb_y(int nx, int ny, int nz)
{
    (void)nx;
    return 2 * ny * nz;
}

VBC_INLINE int vbc_rb_z(int nx, int ny, int nz)
{
    return 2 * ny * nz + 2 * nx * nz;
}

VBC_INLINE int vbc_rb_size(int nx, int ny, int nz)
{
    return 2 * ny * nz + 2 * nx * nz + 2 * nx * ny;
}

/* Scans ray (a,b) of `axis` (0 x: a=j b=k; 1 y: a=i b=k; 2 z: a=i b=j) through
 * the atomic mask and stores its first and last hit in rb. */
VBC_INLINE void vbc_ray_scan(VBC_GLOBAL const vbc_u8 *am, int nx, int ny, int nz, int axis, int a,
                             int b, VBC_GLOBAL int *rb)
{
    int n, stride, base, slot;
    if (axis == 0) {
        n = nx; stride = 1; base = nx * (a + ny * b); slot = 2 * (a + ny * b);
    } else if (axis == 1) {
        n = ny; stride = nx; base = a + nx * ny * b; slot = vbc_rb_y(nx, ny, nz) + 2 * (a + nx * b);
    } else {
        n = nz; stride = nx * ny; base = a + nx * b; slot = vbc_rb_z(nx, ny, nz) + 2 * (a + nx * b);
    }
    int first = n, last = -1;
    for (int t = 0; t < n; t++) {
        if (am[base + t * stride] & VBC_F_ATOMIC) {
            if (first == n)
                first = t;
            last = t;
        }
    }
    rb[slot] = first;
    rb[slot + 1] = last;
}

/* Molecular mask at (i,j,k): inside the hit interval of at least one of the
 * three axis rays through it (the union, as in Algorithm 2 step 5). Voxels
 * outside the grid are outside. */
VBC_INLINE int vbc_molecular(VBC_GLOBAL const int *rb, int nx, int ny, int nz, int i, int j, int k)
{
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz)
        return 0;
    int s = 2 * (j + ny * k);
    if (rb[s] <= i && i <= rb[s + 1])
        return 1;
    s = vbc_rb_y(nx, ny, nz) + 2 * (i + nx * k);
    if (rb[s] <= j && j <= rb[s + 1])
        return 1;
    s = vbc_rb_z(nx, ny, nz) + 2 * (i + nx * j);
    return rb[s] <= k && k <= rb[s + 1];
}

/* The flag byte of voxel (i,j,k) from the atomic mask, the ray bounds and the
 * Voronoi labels. A voxel is a Voronoi edge when its own label and those of its
 * face neighbours inside the grid hold at least `min_labels` distinct values
 * (3 in 3D: three regions meet; 2 in 2D, where the diagram is all edges). */
VBC_INLINE unsigned vbc_classify(VBC_GLOBAL const int *labels, VBC_GLOBAL const vbc_u8 *am,
                                 VBC_GLOBAL const int *rb, int nx, int ny, int nz, int min_labels,
                                 int i, int j, int k)
{
    int v = i + nx * (j + ny * k);
    unsigned f = am[v] & VBC_F_ATOMIC;
    if (vbc_molecular(rb, nx, ny, nz, i, j, k))
        f |= VBC_F_MOLECULAR;
    int l[7];
    int m = 0;
    l[m++] = labels[v];
    if (i > 0) l[m++] = labels[v - 1];
    if (i + 1 < nx) l[m++] = labels[v + 1];
    if (j > 0) l[m++] = labels[v - nx];
    if (j + 1 < ny) l[m++] = labels[v + nx];
    if (k > 0) l[m++] = labels[v - nx * ny];
    if (k + 1 < nz) l[m++] = labels[v + nx * ny];
    if (vbc_distinct(l, m) >= min_labels)
        f |= VBC_F_EDGE;
    if ((f & (VBC_F_ATOMIC | VBC_F_MOLECULAR)) == VBC_F_MOLECULAR)
        f |= VBC_F_INTERIOR;
    if ((f & (VBC_F_EDGE | VBC_F_INTERIOR)) == (VBC_F_EDGE | VBC_F_INTERIOR)) {
        f |= VBC_F_CHANNEL;
        if (!vbc_molecular(rb, nx, ny, nz, i - 1, j, k) || !vbc_molecular(rb, nx, ny, nz, i + 1, j, k) ||
            !vbc_molecular(rb, nx, ny, nz, i, j - 1, k) || !vbc_molecular(rb, nx, ny, nz, i, j + 1, k) ||
            !vbc_molecular(rb, nx, ny, nz, i, j, k - 1) || !vbc_molecular(rb, nx, ny, nz, i, j, k + 1))
            f |= VBC_F_MOUTH;
    }
    return f;
}

#endif
