/* The one fallback rule of the device layer (vb_device.h). */
#include "vb_device.h"

#include <string.h>

int vb_device_kind_parse(vb_ctx *ctx, const char *s, vb_device_kind *out)
{
    static const struct {
        const char *name;
        vb_device_kind kind;
    } kinds[] = {{"auto", VB_DEVICE_AUTO}, {"gpu", VB_DEVICE_GPU},
                 {"cpu", VB_DEVICE_CPU}, {"ref", VB_DEVICE_REF}};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        if (strcmp(s, kinds[i].name) == 0) {
            *out = kinds[i].kind;
            return VB_OK;
        }
    return vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown device '%s' (auto, gpu, cpu or ref)", s);
}

int vb_device_try(vb_ctx *ctx, const vb_device_layer *layer, const vb_engine_request *req,
                  vb_device **dev, void **engine)
{
    *dev = NULL;
    *engine = NULL;
    if (req->kind == VB_DEVICE_REF)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "the reference backend has no device");
    if (!layer)
        return vb_error(ctx, VB_EDEVICE, NULL, 0, "built without OpenCL");
    int rc = layer->open(ctx, req->kind, dev);
    if (rc == VB_OK)
        rc = req->open(ctx, layer, *dev, req->user, engine);
    if (rc != VB_OK && *dev) {
        layer->close(*dev);
        *dev = NULL;
    }
    return rc;
}

void vb_device_fallback_warn(vb_ctx *ctx, const vb_engine_request *req, const char *reason)
{
    vb_warn(ctx, req->fallback_warning, NULL, 0,
            "no usable OpenCL device (%s): %s runs on the reference backend", reason, req->who);
}

int vb_device_open_engine(vb_ctx *ctx, const vb_device_layer *layer,
                          const vb_engine_request *req, vb_device **dev, void **engine)
{
    *dev = NULL;
    *engine = NULL;
    if (req->kind != VB_DEVICE_REF) {
        int rc = vb_device_try(ctx, layer, req, dev, engine);
        if (VB_CATEGORY(rc) != VB_EDEVICE)
            return rc;
        vb_device_fallback_warn(ctx, req, vb_errmsg(ctx));
        vb_clear_error(ctx);
    }
    return req->open(ctx, layer, NULL, req->user, engine);
}

void vb_device_failed_warn(vb_ctx *ctx, int number, const char *device, const char *reason,
                           const char *rest)
{
    vb_warn(ctx, number, NULL, 0, "OpenCL device %s failed (%s): %s", device, reason, rest);
}
