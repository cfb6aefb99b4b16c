/* The OpenCL backend of the sampling pipeline (gpu/sample_envelope.cl and
 * gpu/vertices_newton.cl behind the vb_sampler_backend interface). */
#ifndef VBG_SAMPLER_H
#define VBG_SAMPLER_H

#include "vb_sampler.h"
#include "vbg_runtime.h"

/* Builds both programs on the runtime's device and returns a backend that
 * borrows rt (rt must outlive it). VB_EDEVICE with the build log in the
 * context when a kernel does not build; VB_ENOMEM. Close with
 * vb_sampler_backend_close. */
int vbg_sampler_open(vb_ctx *ctx, vbg_runtime *rt, vb_sampler_backend **out);

#endif
