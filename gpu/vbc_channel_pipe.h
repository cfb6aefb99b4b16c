/* The channel frame pipeline behind one interface, whatever runs it: OpenCL
 * (gpu/channel_gpu.c) or the plain-C reference (the JFA reference backend,
 * vbc_masks_ref, vbc_flags_compact; clearances left to the host analysis).
 * Both give the same channel voxel set, so the same tables and centrelines.
 *
 * The project's rule "a device that fails falls back to the CPU with a
 * warning" lives here, in one place:
 *   W804  no usable OpenCL device: the reference backend runs every frame
 *   W805  --device gpu and no GPU: the CPU OpenCL device (PoCL) instead
 *   W806  OpenCL failed during a frame: that frame and the rest on the reference */
#ifndef VBC_CHANNEL_PIPE_H
#define VBC_CHANNEL_PIPE_H

#include "vbc_channel_gpu.h"

typedef struct vbc_pipe vbc_pipe;

/* Opens the pipeline for device `kind` with JFA `variant`. VBG_DEVICE_REF
 * opens the reference; any other kind opens OpenCL and, when that fails with
 * VB_EDEVICE, falls back (GPU -> CPU device -> reference) with W805 / W804.
 * *out owns its runtime. VB_ENOMEM, or VB_EDEVICE only if even the reference
 * cannot open. */
int vbc_pipe_open(vb_ctx *ctx, vbg_device_kind kind, vbj_variant variant, vbc_pipe **out);
void vbc_pipe_close(vbc_pipe *p);

/* Runs one frame as vbc_gpu_frame does (same arguments and contract). When
 * the OpenCL backend fails with VB_EDEVICE, warns W806, releases OpenCL and
 * reruns the frame on the reference, which then serves every later frame.
 * out->clearance is NULL on the reference. */
int vbc_pipe_frame(vb_ctx *ctx, vbc_pipe *p, const vbc_grid *g, const float *atoms4, size_t natoms,
                   double probe, unsigned want, vbc_frame_out *out);

/* The device running the frames now: the OpenCL name or "reference (C)". */
const char *vbc_pipe_device_name(const vbc_pipe *p);
/* Nonzero while frames run on the reference backend. */
int vbc_pipe_is_ref(const vbc_pipe *p);

/* Fault injection (tests, as SQLite's *fault.test): the OpenCL backend fails
 * with VB_EDEVICE on its frame number `frame` (counted from 0 over this
 * pipe's OpenCL frames); -1 (the default) never. */
void vbc_pipe_inject_device_fault(vbc_pipe *p, long frame);

#endif
