/* The channel pipeline of one frame on OpenCL: atoms up, discrete Voronoi
 * (gpu/jfa, Facet-JFA by default), masks and compaction (gpu/channels.cl),
 * the compact channel voxel list down. Buffers persist across frames. */
#ifndef VBC_CHANNEL_GPU_H
#define VBC_CHANNEL_GPU_H

#include "vbc_channel.h"
#include "vbg_runtime.h"
#include "vbj_jfa.h"

typedef struct vbc_gpu vbc_gpu;

/* What a frame run returns besides the voxel list. */
enum {
    VBC_WANT_FLAGS = 1, /* the flag volume (VBC_F_* per voxel) on the host */
    VBC_WANT_LABELS = 2 /* the Voronoi labels on the host */
};

typedef struct vbc_frame_out {
    uint32_t *voxels;   /* channel voxels, index | VBC_MOUTH_BIT, device order */
    size_t nvoxels;
    uint8_t *flags;     /* nx*ny*nz, when VBC_WANT_FLAGS (else NULL) */
    uint32_t *labels;   /* nx*ny*nz, when VBC_WANT_LABELS (else NULL) */
    float *clearance;   /* per listed voxel, Å (GPU devices only; NULL on CPU
                           devices, where the host's cell list is faster) */
    double ms_upload;   /* atoms to the device */
    double ms_jfa;      /* vbj_run wall time (seed upload, algorithm, fill) */
    double ms_masks;    /* atomic mask, rays, classification, list download */
    vbj_counts jfa;     /* the JFA run's work counts */
} vbc_frame_out;

/* Opens the pipeline on a runtime (borrowed; close it after this) with the
 * JFA variant to use. Builds the kernels. VB_EDEVICE / VB_ENOMEM. */
int vbc_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbj_variant variant, vbc_gpu **out);
void vbc_gpu_close(vbc_gpu *p);

/* Runs one frame: g must be a vbc_grid_fit grid (nx a power of two), atoms4
 * the vbc_atoms_pack output for `probe`. Fills *out (free with vbc_frame_out_free).
 * VB_EDEVICE / VB_ENOMEM / VB_EMISUSE (grid side not a power of two). */
int vbc_gpu_frame(vb_ctx *ctx, vbc_gpu *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                  double probe, unsigned want, vbc_frame_out *out);

void vbc_frame_out_free(vbc_frame_out *o);

/* The JFA seeds of a frame (every backend places them alike): atom a at
 * atoms4's centre minus half a voxel. Checks the grid as vbc_gpu_frame does.
 * Allocates *out (vbj_seeds_free). VB_EMISUSE / VB_EINPUT_EMPTY / VB_ENOMEM. */
int vbc_frame_seeds(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms,
                    vbj_seeds *out);

/* Where clearances are computed: 0 (default) on the device when it is a GPU,
 * 1 always on the device (tests of the kernel on PoCL), -1 never. */
void vbc_gpu_set_device_clearance(vbc_gpu *p, int mode);

#endif
