/* The OpenCL backend of the direction cover (gpu/cover.cl behind the
 * vb_cover_backend interface of core/cells/vb_cover.h). */
#ifndef VBG_COVER_H
#define VBG_COVER_H

#include "vb_cover.h"
#include "vbg_runtime.h"

/* Builds the cover program on the runtime's device and returns a backend
 * that borrows rt (rt must outlive it). VB_EDEVICE with the build log in the
 * context when the kernel does not build; VB_ENOMEM. Close with
 * vb_cover_backend_close. */
int vbg_cover_open(vb_ctx *ctx, vbg_runtime *rt, vb_cover_backend **out);

#endif
