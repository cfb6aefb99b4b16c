/* The 2D pipeline stages of `vorball channels --png` (the paper's Fig. 5). */
#ifndef VB_CHANNELS_PNG_H
#define VB_CHANNELS_PNG_H

#include "vbc_channel_pipe.h"

/* Cuts the frame `s` with the plane through its centroid normal to axis
 * `normal` (0 x, 1 y, 2 z): every atom the plane crosses becomes a disk of its
 * cross-section radius. Runs the 2D pipeline (Voronoi boundaries are the
 * edges) on an n x n grid and writes eight panels, 4 x 2, to `path`: input
 * disks, disks grown by the probe, Voronoi regions, Voronoi edges, atomic
 * region, molecular region, interior, channels with their centrelines.
 * VB_EINPUT_EMPTY when the plane meets no atom; VB_EIO, VB_ENOMEM, VB_EDEVICE. */
int vbc_png_stages(vb_ctx *ctx, vbc_pipe *pipe, const vb_sphere_set *s, double probe, int n,
                   int normal, const vbc_options *opt, const char *path);

#endif
