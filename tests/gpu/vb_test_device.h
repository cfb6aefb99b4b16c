/* Test helper: is an OpenCL CPU device (PoCL) there? The GPU-room tests run
 * their device paths only where it is. */
#ifndef VB_TEST_DEVICE_H
#define VB_TEST_DEVICE_H
#include "vb_diag.h"
#include "vbg_runtime.h"

/* 1 when a CPU OpenCL device opens on ctx (it is closed again and the
 * context's error cleared), else 0. */
static inline int vb_test_have_cpu_device(vb_ctx *ctx)
{
    vbg_runtime *rt = NULL;
    int have = vbg_runtime_open(ctx, VB_DEVICE_CPU, &rt) == VB_OK;
    vbg_runtime_close(rt);
    vb_clear_error(ctx);
    return have;
}

#endif
