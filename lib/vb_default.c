/* The default backends of the library (vb_default.h). */
#include "vb_default.h"

#include "vb_diag.h"
#include "vb_verify.h"
#include "vbg_runtime.h"

const vb_vertices_backends *vb_default_backends(void)
{
    static const vb_vertices_backends be = {&vbg_device_layer, &vb_exact_certifier};
    return &be;
}

const vb_device_layer *vb_default_devices(void)
{
    return &vbg_device_layer;
}

int vb_vertices_run_default(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertices_config *cfg,
                            vb_vertices_result *res)
{
    return vb_vertices_run(ctx, set, cfg, vb_default_backends(), res);
}

int vb_devices_write(vb_ctx *ctx, FILE *f)
{
    int rc = vbg_list_devices(ctx, f);
    if (rc != VB_OK)
        return rc;
    vbg_runtime *rt;
    if (vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt) == VB_OK) {
        fprintf(f, "#auto\t%s\n", vbg_runtime_device_name(rt));
        vbg_runtime_close(rt);
    } else {
        fprintf(f, "#auto\treference backend (%s)\n", vb_errmsg(ctx));
        vb_clear_error(ctx);
    }
    return VB_OK;
}

void vb_devices_write_auto(vb_ctx *ctx, FILE *f)
{
    vbg_runtime *rt = NULL;
    if (vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt) == VB_OK) {
        char v[800];
        vbg_runtime_versions(rt, v, sizeof v);
        fprintf(f, "device (--device auto): %s %s (%s)\n", vbg_runtime_is_gpu(rt) ? "GPU" : "CPU",
                vbg_runtime_device_name(rt), v);
        vbg_runtime_close(rt);
    } else {
        fprintf(f, "device (--device auto): reference backend, no OpenCL device (%s)\n",
                vb_errmsg(ctx));
        vb_clear_error(ctx);
    }
}
