/* The channel pipeline of one frame on OpenCL: atoms up, discrete Voronoi
 * (gpu/jfa, Facet-JFA by default), masks and compaction (gpu/channels.cl),
 * the compact channel voxel list down. Buffers persist across frames. */
#ifndef VBC_CHANNEL_GPU_H
#define VBC_CHANNEL_GPU_H

#include "vbc_channel_pipe.h"
#include "vbg_runtime.h"

typedef struct vbc_gpu vbc_gpu;

/* Opens the pipeline on a runtime (borrowed; close it after this) with the
 * JFA variant to use. Builds the kernels. VB_EDEVICE / VB_ENOMEM. */
int vbc_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbj_variant variant, vbc_gpu **out);
void vbc_gpu_close(vbc_gpu *p);

/* Runs one frame: g must be a vbc_grid_fit grid (nx a power of two), atoms4
 * the vbc_atoms_pack output for `probe`. Fills *out (free with vbc_frame_out_free).
 * VB_EDEVICE / VB_ENOMEM / VB_EMISUSE (grid side not a power of two). */
int vbc_gpu_frame(vb_ctx *ctx, vbc_gpu *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                  double probe, unsigned want, vbc_frame_out *out);

/* Where clearances are computed: 0 (default) on the device when it is a GPU,
 * 1 always on the device (tests of the kernel on PoCL), -1 never.
 * VORBALL_DEVICE_CLEARANCE=0 or 1 in the environment overrides it. */
void vbc_gpu_set_device_clearance(vbc_gpu *p, int mode);

/* Where the components of the channel voxels are labelled (out->comp):
 * 0 (default) on the device when it is a GPU, else by the host's
 * union-find; 1 always on the device (tests of the kernels on PoCL); -1
 * never. VORBALL_DEVICE_GRAPH=0 or 1 in the environment overrides it. */
void vbc_gpu_set_device_graph(vbc_gpu *p, int mode);

/* Makes *buf (NULL: none yet) hold at least `need` elements of `size`
 * bytes on rt's context, *cap its elements, growing by half again to
 * amortise trajectories whose sizes creep up (the contents are lost when
 * it grows). CL_SUCCESS or the OpenCL error (*buf NULL, *cap 0). */
cl_int vbc_gpu_buffer_fit(vbg_runtime *rt, cl_mem *buf, size_t *cap, size_t need, size_t size);

/* The channel analysis's batch sweeps (core/discrete/vbc_paths.h) on a
 * runtime (borrowed): gpu/channel_paths.cl. vbc_paths_gpu_engine gives
 * its engine table (NULL for NULL); one lock serves frames from several
 * threads. VB_EDEVICE / VB_ENOMEM. */
typedef struct vbc_paths_gpu vbc_paths_gpu;
int vbc_paths_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbc_paths_gpu **out);
const struct vbc_paths_engine *vbc_paths_gpu_engine(const vbc_paths_gpu *P);
void vbc_paths_gpu_close(vbc_paths_gpu *P);

/* The pore verdict's rasters (core/discrete/vbc_walls.h) on a runtime
 * (borrowed): gpu/channel_walls.cl, on a command queue of their own.
 * vbc_walls_gpu_engine gives its engine table (NULL for NULL); one lock
 * serves frames from several threads. VB_EDEVICE / VB_ENOMEM. */
typedef struct vbc_walls_gpu vbc_walls_gpu;
int vbc_walls_gpu_open(vb_ctx *ctx, vbg_runtime *rt, vbc_walls_gpu **out);
const struct vbc_walls_engine *vbc_walls_gpu_engine(const vbc_walls_gpu *W);
void vbc_walls_gpu_close(vbc_walls_gpu *W);

/* The engine table of vbc_channel_pipe.h on a runtime (borrowed: close it
 * after the engine): what the device layer's channels_open gives. */
int vbg_channels_open(vb_ctx *ctx, vbg_runtime *rt, vbj_variant variant, vbc_engine **out);

#endif
