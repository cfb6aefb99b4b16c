/* The device layer as the library's drivers see it: which device a command
 * asks for, the table through which gpu/ opens OpenCL devices and the
 * engines of each stage on them, and the one fallback rule.
 *
 * --device auto|gpu|cpu|ref means the same for every command: auto takes a
 * GPU with double precision if one is present, else a CPU device (PoCL);
 * gpu and cpu take that kind only; ref runs the plain-C twin of the engine,
 * which every engine has. When the device, or the engine on it, cannot be
 * opened (VB_EDEVICE: no OpenCL, no such device, a kernel that does not
 * build), the command warns once with its number and runs the twin; any
 * other failure (VB_ENOMEM, a bug) stops it. A device that fails in the
 * middle of a run is dropped the same way (vb_device_failed_warn) and the
 * work is redone on the twin, which gives the same output.
 *
 * core/ never calls OpenCL: gpu/ fills a vb_device_layer (vbg_device_layer)
 * and callers hand it to the drivers; NULL is a library without devices. */
#ifndef VB_DEVICE_H
#define VB_DEVICE_H

#include "vb.h"

typedef enum vb_device_kind {
    VB_DEVICE_AUTO = 0, /* a GPU if one is present, else a CPU device (PoCL) */
    VB_DEVICE_GPU,
    VB_DEVICE_CPU,
    VB_DEVICE_REF       /* no OpenCL: the plain-C twin */
} vb_device_kind;

/* Parses "auto|gpu|cpu|ref". Returns VB_OK or VB_EMISUSE (message in ctx;
 * ctx may be NULL). */
int vb_device_kind_parse(vb_ctx *ctx, const char *s, vb_device_kind *out);

/* An opened device (gpu/: the OpenCL context, queue and program cache). */
typedef struct vb_device vb_device;

struct vb_sampler_backend;
struct vb_cover_backend;
struct vbj_backend;
struct vbc_engine;

/* What gpu/ adds to the library. Every function returns VB_OK, VB_ENOMEM
 * or VB_EDEVICE (message in ctx); engines borrow the device, which must
 * outlive them. */
typedef struct vb_device_layer {
    /* Opens a device of `kind` (never VB_DEVICE_REF); VB_EDEVICE when there
     * is none. */
    int (*open)(vb_ctx *ctx, vb_device_kind kind, vb_device **out);
    void (*close)(vb_device *dev);
    /* "NVIDIA H100 80GB HBM3 (NVIDIA CUDA)" style name, owned by dev. */
    const char *(*name)(const vb_device *dev);
    int (*is_gpu)(const vb_device *dev);
    /* The engines of the stages on an opened device (they build their
     * programs): the sampling backend of the vertex pipeline, the
     * direction cover's backend, the JFA engine, the channel frame engine
     * for a JFA variant. */
    int (*sampler_open)(vb_ctx *ctx, vb_device *dev, struct vb_sampler_backend **out);
    int (*cover_open)(vb_ctx *ctx, vb_device *dev, struct vb_cover_backend **out);
    int (*jfa_open)(vb_ctx *ctx, vb_device *dev, struct vbj_backend **out);
    int (*channels_open)(vb_ctx *ctx, vb_device *dev, int jfa_variant, struct vbc_engine **out);
    /* Whether the host shows a GPU (a driver's device node; nothing opened,
     * no OpenCL call): the hint of --device auto's crossover. */
    int (*gpu_present)(void);
} vb_device_layer;

/* Opens the engine of one stage: on the opened device dev, or its plain-C
 * twin when dev is NULL. Returns VB_OK with *engine, VB_ENOMEM, VB_EDEVICE. */
typedef int (*vb_engine_open_fn)(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev,
                                 void *user, void **engine);

/* An engine a command asks for. */
typedef struct vb_engine_request {
    vb_device_kind kind;
    vb_engine_open_fn open;
    void *user;          /* handed to open */
    int fallback_warning; /* the command's warning number (vb_diag.h) when it falls back */
    const char *who;     /* the command, named in the warning ("vertices", "jfa", "channels") */
} vb_engine_request;

/* The OpenCL side of a request (kind not REF): the device and the engine
 * on it. VB_OK with *dev and *engine set; VB_EDEVICE (reason in ctx) when
 * the layer is NULL, there is no such device, or the engine does not build
 * there (the device is closed again); other codes are failures. */
int vb_device_try(vb_ctx *ctx, const vb_device_layer *layer, const vb_engine_request *req,
                  vb_device **dev, void **engine);

/* The one fallback rule: for kind ref the twin; else vb_device_try, and on
 * VB_EDEVICE vb_device_fallback_warn and the twin. *dev is NULL on the
 * twin. Returns VB_OK, or the failure of the engine's twin, or a
 * non-device failure of vb_device_try. */
int vb_device_open_engine(vb_ctx *ctx, const vb_device_layer *layer,
                          const vb_engine_request *req, vb_device **dev, void **engine);

/* The warning of a fallback at opening, with the reason the device could
 * not be used: "W<n>: no usable OpenCL device (<reason>): <who> runs on the
 * reference backend". */
void vb_device_fallback_warn(vb_ctx *ctx, const vb_engine_request *req, const char *reason);

/* The warning of a device that failed during a run (`number`, the
 * command's): "W<n>: OpenCL device <device> failed (<reason>): <rest>",
 * rest saying what now runs on the reference backend. */
void vb_device_failed_warn(vb_ctx *ctx, int number, const char *device, const char *reason,
                           const char *rest);

#endif
