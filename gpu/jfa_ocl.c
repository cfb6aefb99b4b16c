/* The OpenCL JFA backend behind the vbj_backend table: the dense variants
 * (jfa.c), Facet-JFA (jfa_facet.c) and the exact diagram (jfa_exact.c) on
 * one engine, labels read back as the options want them. */
#include <stdlib.h>
#include <string.h>

#include "jfa_internal.h"
#include "vbg_jfa.h"

int vbj_cl_run(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, const vbj_options *o,
               unsigned want, vbj_result *out)
{
    int facet = o->variant == VBJ_FACET || o->variant == VBJ_FACET_FULL;
    cl_mem result = NULL;
    e->device_labels = NULL;
    int rc = VBJ_IS_EXACT(o->variant) ? vbj_cl_tiles(ctx, e, s, o->variant, out, &result)
             : facet                  ? vbj_cl_facet(ctx, e, s, o, out, &result)
                                      : vbj_cl_dense_run(ctx, e, s, o->variant, 0, out, &result);
    if (rc)
        return rc;
    if (want & VBJ_WANT_DEVICE)
        e->device_labels = result;
    if (want & (VBJ_WANT_LABELS | VBJ_WANT_NLABELS)) {
        double t0 = 1e3 * vb_now();
        out->labels = malloc(out->pixels * sizeof *out->labels);
        if (!out->labels)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "labels: out of memory");
        if (vbg_check(ctx,
                      clEnqueueReadBuffer(vbg_runtime_queue(e->rt), result, CL_TRUE, 0,
                                          out->pixels * 4, out->labels, 0, NULL, NULL),
                      "labels download"))
            return VB_EDEVICE;
        out->ms_transfer += 1e3 * vb_now() - t0;
    }
    if (want & VBJ_WANT_NLABELS) {
        out->nlabels = malloc(out->pixels);
        if (!out->nlabels)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "label counts: out of memory");
        if ((rc = vbj_cl_count_labels(ctx, e, s->dim, s->n, result, out->nlabels)))
            return rc;
    }
    if (!(want & VBJ_WANT_LABELS)) {
        free(out->labels);
        out->labels = NULL;
    }
    return VB_OK;
}

static int ocl_run(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, const vbj_options *o,
                   unsigned want, vbj_result *out)
{
    return vbj_cl_run(ctx, be->state, s, o, want & ~(unsigned)VBJ_WANT_DEVICE, out);
}

static int ocl_exact(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, uint32_t *labels)
{
    return vbj_cl_exact(ctx, be->state, s, labels);
}

static void ocl_close(vbj_backend *be)
{
    vbj_engine_close(be->state);
    free(be);
}

int vbg_jfa_open(vb_ctx *ctx, vbg_runtime *rt, vbj_backend **out)
{
    *out = NULL;
    vbj_backend *be = calloc(1, sizeof *be);
    if (!be)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "jfa engine: out of memory");
    vbj_engine *e = NULL;
    int rc = vbj_engine_open_runtime(ctx, rt, &e);
    if (rc != VB_OK) {
        free(be);
        return rc;
    }
    be->name = "opencl";
    snprintf(be->device, sizeof be->device, "%s", vbg_runtime_device_name(rt));
    be->state = e;
    be->run = ocl_run;
    be->exact = ocl_exact;
    be->close = ocl_close;
    *out = be;
    return VB_OK;
}
