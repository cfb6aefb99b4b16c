/* The OpenCL runtime shared by every GPU stage: device choice, program build
 * (kernels embedded at build time, or loaded from VORBALL_KERNEL_DIR for
 * development), error mapping. A failed build always reports the build log. */
#ifndef VBG_RUNTIME_H
#define VBG_RUNTIME_H

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
/* The device layer of the library on OpenCL: these runtimes and the
 * OpenCL engines of every stage (gpu/device_layer.c). */
extern const vb_device_layer vbg_device_layer;

#endif
#include <CL/cl.h>
#include <stdio.h>

#include "vb.h"
#include "vb_device.h"

/* The runtime is the device of the device layer (core/vb_device.h). */
typedef struct vb_device vbg_runtime;

/* Opens an OpenCL context and in-order queue (profiling enabled) on a device of
 * the requested kind with double-precision support: the first, or number
 * VORBALL_DEVICE_INDEX (modulo their count) of those devices, counted over
 * the platforms in order (one GPU per MPI rank on a host). VB_EDEVICE when
 * none is available (the caller decides about falling back to the
 * reference backend and warns: vb_device.h), VB_EMISUSE for a
 * VORBALL_DEVICE_INDEX that is not a number. kind must not be
 * VB_DEVICE_REF. */
int vbg_runtime_open(vb_ctx *ctx, vb_device_kind kind, vbg_runtime **out);

void vbg_runtime_close(vbg_runtime *rt);

/* Bytes of device memory one pipeline stage may hold at once on rt's device
 * (the device layer's budget: a bounded share of the device, and on a CPU
 * device of the host memory free now; VORBALL_DEVICE_MEMORY_MIB overrides
 * it). Stages split their work to fit it; the output does not depend on it. */
size_t vbg_runtime_memory_budget(const vbg_runtime *rt);

cl_context vbg_runtime_context(const vbg_runtime *rt);
cl_command_queue vbg_runtime_queue(const vbg_runtime *rt);
cl_device_id vbg_runtime_device(const vbg_runtime *rt);
/* "NVIDIA H100 80GB HBM3 (NVIDIA CUDA)" style name, owned by the runtime. */
const char *vbg_runtime_device_name(const vbg_runtime *rt);
int vbg_runtime_is_gpu(const vbg_runtime *rt);

/* Seconds a finished command ran on the device, from its profiling event
 * (the runtime's queues have profiling on); 0 when the device gives no
 * times. */
double vbg_event_seconds(cl_event e);
/* 1 when the host shows a GPU driver's device node (/dev/nvidiaN, AMD's
 * /dev/kfd), else 0: a hint for --device auto's crossover, which changes
 * speed, never bytes. Listing the OpenCL platforms instead took 0.2 s on the
 * H100 machine (PoCL's start-up there), ten times a 327-atom run on host
 * threads. */
int vbg_runtime_gpu_present(void);
/* The versions behind the runtime, for provenance: "platform <version>;
 * device <OpenCL version>, driver <version>" (e.g. "OpenCL 3.0 PoCL 3.1 ...;
 * device OpenCL 3.0 PoCL HSTR: ..., driver 3.1"), into buf (always
 * NUL-terminated). */
void vbg_runtime_versions(const vbg_runtime *rt, char *buf, size_t len);

/* Builds (once per runtime; cached) the program from kernel file `name`
 * (e.g. "jfa.cl"). Its `#include "x.h"` lines were resolved at build time.
 * Options are appended to the standard ones ("-cl-std=CL1.2", never any fast
 * math flag). On failure returns VB_EDEVICE with the build log in the message. */
int vbg_program_get(vb_ctx *ctx, vbg_runtime *rt, const char *name, const char *options,
                    cl_program *out);

/* Maps an OpenCL error to VB_EDEVICE with "what: CL_ERROR_NAME" in the
 * context; returns VB_OK when err == CL_SUCCESS. */
int vbg_check(vb_ctx *ctx, cl_int err, const char *what);

/* Writes a table of platforms and devices (name, type, version, fp64, memory). */
int vbg_list_devices(vb_ctx *ctx, FILE *out);

/* The folder of vorball's caches into dir: $XDG_CACHE_HOME/vorball, else
 * $HOME/.cache/vorball (created with its parent when make_dir). Returns 1,
 * or 0 when there is none (no such variable, a path over cap, or it could
 * not be created). */
int vbg_cache_dir(char *dir, size_t cap, int make_dir);

/* Checks PoCL's kernel cache (gpu/pocl_cache.c) once per process, before
 * the first OpenCL call: without POCL_CACHE_DIR, points it at
 * <vbg_cache_dir>/pocl; removes each cached program with a damaged bitcode
 * or kernel file, with warning W750. Never fails: the cache only saves
 * time. Allocates nothing that outlives the call. */
void vbg_pocl_cache_check(vb_ctx *ctx);

/* Returns the embedded source of kernel file `name`, or NULL if unknown. */
const char *vbg_kernel_source(const char *name);

/* The device layer of the library on OpenCL: these runtimes and the
 * OpenCL engines of every stage (gpu/device_layer.c). */
extern const vb_device_layer vbg_device_layer;

#endif
