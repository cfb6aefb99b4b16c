/* The plain-C reference of the mask stage (Algorithm 2, steps 2-7), built from
 * the same per-voxel functions as gpu/channels.cl. */
#include <stdlib.h>
#include <string.h>

#include "vbc_channel.h"

void vbc_masks_ref(const vbc_grid *g, const float *atoms4, size_t natoms, const int32_t *labels,
                   int min_labels, int *rb, uint8_t *flags)
{
    int nx = g->nx, ny = g->ny, nz = g->nz;
    memset(flags, 0, vbc_grid_voxels(g));
    for (size_t a = 0; a < natoms; a++) {
        const float *p = atoms4 + 4 * a;
        int i1 = vbc_box_hi(p[0], p[3], nx), j1 = vbc_box_hi(p[1], p[3], ny);
        int k1 = vbc_box_hi(p[2], p[3], nz);
        for (int k = vbc_box_lo(p[2], p[3]); k < k1; k++)
            for (int j = vbc_box_lo(p[1], p[3]); j < j1; j++)
                for (int i = vbc_box_lo(p[0], p[3]); i < i1; i++)
                    if (vbc_ball_contains(p[0], p[1], p[2], p[3], i, j, k))
                        flags[i + (size_t)nx * (j + (size_t)ny * k)] = VBC_F_ATOMIC;
    }
    for (int b = 0; b < nz; b++)
        for (int a = 0; a < ny; a++)
            vbc_ray_scan(flags, nx, ny, nz, 0, a, b, rb);
    for (int b = 0; b < nz; b++)
        for (int a = 0; a < nx; a++)
            vbc_ray_scan(flags, nx, ny, nz, 1, a, b, rb);
    for (int b = 0; b < ny; b++)
        for (int a = 0; a < nx; a++)
            vbc_ray_scan(flags, nx, ny, nz, 2, a, b, rb);
    /* The classification reads only the atomic bit of neighbours' flags, which
     * the pass below never changes, so updating in place is safe. */
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                flags[i + (size_t)nx * (j + (size_t)ny * k)] =
                    (uint8_t)vbc_classify(labels, flags, rb, nx, ny, nz, min_labels, i, j, k);
}

int vbc_flags_compact(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, uint32_t **out,
                      size_t *count)
{
    size_t nv = vbc_grid_voxels(g), m = 0;
    *out = NULL;
    *count = 0;
    for (size_t v = 0; v < nv; v++)
        m += (flags[v] & VBC_F_CHANNEL) != 0;
    if (m == 0)
        return VB_OK;
    uint32_t *list = malloc(m * sizeof *list);
    if (!list)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel voxel list (%zu)", m);
    m = 0;
    for (size_t v = 0; v < nv; v++)
        if (flags[v] & VBC_F_CHANNEL)
            list[m++] = (uint32_t)v | ((flags[v] & VBC_F_MOUTH) ? VBC_MOUTH_BIT : 0u);
    *out = list;
    *count = m;
    return VB_OK;
}
