/* The device layer of the library on OpenCL (core/vb_device.h): runtimes as
 * devices, and on them the OpenCL engine of every stage. */
#include "vbc_channel_gpu.h"
#include "vbg_cover.h"
#include "vbg_jfa.h"
#include "vbg_judge.h"
#include "vbg_runtime.h"
#include "vbg_sampler.h"

static int open_device(vb_ctx *ctx, vb_device_kind kind, vb_device **out)
{
    return vbg_runtime_open(ctx, kind, out);
}

static int open_channels(vb_ctx *ctx, vb_device *dev, int variant, vbc_engine **out)
{
    return vbg_channels_open(ctx, dev, (vbj_variant)variant, out);
}

/* The cover, and beside it the certification filter (vbg_judge_attach). */
static int open_cover(vb_ctx *ctx, vb_device *dev, vb_cover_backend **out)
{
    int rc = vbg_cover_open(ctx, dev, out);
    if (rc == VB_OK)
        vbg_judge_attach(ctx, dev, *out);
    return rc;
}

const vb_device_layer vbg_device_layer = {
    open_device,
    vbg_runtime_close,
    vbg_runtime_device_name,
    vbg_runtime_is_gpu,
    vbg_sampler_open,
    open_cover,
    vbg_jfa_open,
    open_channels,
    vbg_runtime_gpu_present,
};
