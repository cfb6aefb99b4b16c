/* The JFA backends table: the checks every run shares, the plain-C
 * reference behind the table, and the backend a device kind opens. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vbj_prep.h"

void vbj_result_free(vbj_result *r)
{
    if (!r)
        return;
    free(r->labels);
    free(r->nlabels);
    memset(r, 0, sizeof *r);
}

static int check_options(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *o)
{
    if ((unsigned)o->variant >= VBJ_NVARIANTS)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown JFA variant %d", (int)o->variant);
    if (o->m && (o->m > s->n || (o->m & (o->m - 1))))
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "start resolution m = %u must be a power of two <= n = %u", o->m, s->n);
    if (s->dim != 2 && s->dim != 3)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "grid dimension must be 2 or 3");
    return VB_OK;
}

/* A device backend that failed with VB_EDEVICE becomes the reference in
 * place (W751) when it falls back itself: returns 1 when the caller should
 * run again. The OpenCL state is closed; be keeps its address. */
static int fall_back(vb_ctx *ctx, vbj_backend *be, int rc, const char *what)
{
    vbj_backend *ref = NULL;
    if (VB_CATEGORY(rc) != VB_EDEVICE || !be->fallback_warning)
        return 0;
    char reason[256];
    snprintf(reason, sizeof reason, "%s", vb_errmsg(ctx));
    vb_clear_error(ctx);
    if (vbj_ref_open(ctx, &ref) != VB_OK)
        return 0;
    char rest[96];
    snprintf(rest, sizeof rest, "%s and the rest of jfa run on the reference backend", what);
    vb_device_failed_warn(ctx, be->fallback_warning, be->device, reason, rest);
    vbj_backend dead = *be;
    *be = *ref;
    *ref = dead;
    vbj_backend_close(ref); /* the OpenCL backend, now at ref's address */
    return 1;
}

static void result_reset(vbj_result *out, const vbj_seeds *s)
{
    vbj_result_free(out);
    out->dim = s->dim;
    out->n = s->n;
    out->pixels = (size_t)s->n * s->n * (s->dim == 3 ? s->n : 1);
}

int vbj_run(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, const vbj_options *opt,
            vbj_result *out)
{
    vbj_options def = {VBJ_JFA1, 0, 0, 0};
    const vbj_options *o = opt ? opt : &def;
    memset(out, 0, sizeof *out);
    result_reset(out, s);
    int rc = check_options(ctx, s, o);
    if (rc)
        return rc;
    unsigned want = o->want ? o->want : VBJ_WANT_LABELS;
    rc = be->run(ctx, be, s, o, want, out);
    if (rc != VB_OK && fall_back(ctx, be, rc, vbj_variant_name(o->variant))) {
        result_reset(out, s);
        rc = be->run(ctx, be, s, o, want, out);
    }
    if (rc)
        vbj_result_free(out);
    return rc;
}

int vbj_exact(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, uint32_t *labels)
{
    int rc = be->exact(ctx, be, s, labels);
    if (rc != VB_OK && fall_back(ctx, be, rc, "the exact diagram"))
        rc = be->exact(ctx, be, s, labels);
    return rc;
}

void vbj_backend_close(vbj_backend *be)
{
    if (be)
        be->close(be);
}

static int ref_run(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, const vbj_options *o,
                   unsigned want, vbj_result *out)
{
    (void)be;
    int rc = vbj_ref_run(ctx, s, o, out);
    if (rc)
        return rc;
    if (want & VBJ_WANT_NLABELS) {
        out->nlabels = malloc(out->pixels);
        if (!out->nlabels)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "label counts: out of memory");
        vbj_count_labels(s->dim, s->n, out->labels, out->nlabels);
    }
    if (!(want & VBJ_WANT_LABELS)) {
        free(out->labels);
        out->labels = NULL;
    }
    return VB_OK;
}

static int ref_exact(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, uint32_t *labels)
{
    (void)be;
    return vbj_ref_exact(ctx, s, labels);
}

static void ref_close(vbj_backend *be)
{
    free(be);
}

int vbj_ref_open(vb_ctx *ctx, vbj_backend **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "jfa engine: out of memory");
    (*out)->name = "ref";
    snprintf((*out)->device, sizeof (*out)->device, "reference (C)");
    (*out)->run = ref_run;
    (*out)->exact = ref_exact;
    (*out)->close = ref_close;
    return VB_OK;
}

static int open_engine(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void *user,
                       void **engine)
{
    (void)user;
    vbj_backend *be = NULL;
    int rc = dev ? layer->jfa_open(ctx, dev, &be) : vbj_ref_open(ctx, &be);
    *engine = be;
    return rc;
}

int vbj_backend_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device_kind kind,
                     vb_device **dev, vbj_backend **out)
{
    vb_engine_request req = {kind, open_engine, NULL, VB_W_JFA_DEVICE_FALLBACK, "jfa"};
    void *e = NULL;
    int rc = vb_device_open_engine(ctx, layer, &req, dev, &e);
    *out = e;
    if (rc == VB_OK && *dev)
        (*out)->fallback_warning = VB_W_JFA_DEVICE_FAILED;
    return rc;
}
