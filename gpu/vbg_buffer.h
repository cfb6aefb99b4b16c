/* Device buffers that count what they hold: every OpenCL buffer a stage
 * allocates goes through vbg_buf_ensure, which adds its size to the stage's
 * meter and keeps the meter's peak, so that `--stats` can report the device
 * memory a run held (device_bytes_peak) on any device, PoCL included. The
 * figure is the sum of the live buffers' sizes: it leaves out what the
 * OpenCL driver holds for itself (a CUDA context, about 0.5 GiB on an
 * H100). */
#ifndef VBG_BUFFER_H
#define VBG_BUFFER_H

#include "vbg_runtime.h"

/* Bytes a stage holds on its device now, and the most it held at once. */
typedef struct vbg_meter {
    size_t live, peak;
} vbg_meter;

/* A device buffer and its size in bytes (0 and NULL: none). */
typedef struct vbg_buf {
    cl_mem mem;
    size_t size;
} vbg_buf;

/* Makes b hold at least `need` bytes (16 when need is 0). A buffer that is
 * too small is released first (its contents are lost), then one of exactly
 * that size is created, so the meter never counts both. VB_OK, or
 * VB_EDEVICE (b then holds nothing) with the OpenCL error in ctx. */
int vbg_buf_ensure(vb_ctx *ctx, vbg_runtime *rt, vbg_meter *m, vbg_buf *b, size_t need,
                   cl_mem_flags flags);

/* Releases b (none is allowed) and takes its size off the meter. */
void vbg_buf_release(vbg_meter *m, vbg_buf *b);

#endif
