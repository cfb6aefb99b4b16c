/* Test helper: is an OpenCL CPU device (PoCL) there? The GPU-room tests run
 * their device paths only where it is. */
#ifndef VB_TEST_DEVICE_H
#define VB_TEST_DEVICE_H
#include <stdio.h>
#include <stdlib.h>

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

/* A GPU-room test's start: *src the source tree (VORBALL_SOURCE_DIR, set by
 * ctest), *ctx a context and *have_device whether a CPU OpenCL device opens
 * on it. Returns 0, or 1 (said on stderr where the tree is not set) when the
 * test cannot run. */
static inline int vb_test_device_open(const char **src, vb_ctx **ctx, int *have_device)
{
    *src = getenv("VORBALL_SOURCE_DIR");
    if (!*src) {
        fprintf(stderr, "VORBALL_SOURCE_DIR must be set\n");
        return 1;
    }
    vb_config cfg = {0, NULL};
    if (vb_open(ctx, &cfg) != VB_OK)
        return 1;
    *have_device = vb_test_have_cpu_device(*ctx);
    return 0;
}

#endif
