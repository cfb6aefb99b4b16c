/* Host side of the exact discrete Voronoi diagram on OpenCL (kernel in
 * gpu/jfa_exact.cl): the seed buckets are built on the host (vbj_cells_build,
 * shared with the C reference) and searched per pixel on the device. */
#include "jfa_internal.h"

int vbj_cl_exact(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t *labels)
{
    vbj_cells c;
    int rc = vbj_cells_build(ctx, s, &c);
    if (rc)
        return rc;
    size_t nb = (size_t)c.g * c.g * (s->dim == 3 ? c.g : 1);
    size_t pixels = (size_t)s->n * s->n * (s->dim == 3 ? s->n : 1);
    cl_kernel k;
    cl_uint n = s->n, dim = (cl_uint)s->dim, shift = c.shift, g = c.g;
    if ((rc = vbj_cl_upload_seeds(ctx, e, s)) ||
        (rc = vbj_cl_upload(ctx, e, &e->cells_start, c.start, (nb + 1) * 4, "bucket upload")) ||
        (rc = vbj_cl_upload(ctx, e, &e->cells_items, c.items, s->k * 4, "bucket upload")) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->labels, pixels * 4)) ||
        (rc = vbj_cl_kernel(ctx, e, VBJ_K_EXACT, &k)))
        goto done;
    {
        vbj_arg a[] = {VBJ_ARG(e->seeds.mem), VBJ_ARG(e->cells_start.mem),
                       VBJ_ARG(e->cells_items.mem), VBJ_ARG(e->labels.mem), VBJ_ARG(n),
                       VBJ_ARG(dim), VBJ_ARG(shift), VBJ_ARG(g)};
        size_t gs[3] = {n, n, dim == 3 ? n : 1};
        if ((rc = vbj_cl_set_args(ctx, k, "jfa_exact", 8, a)) ||
            (rc = vbj_cl_launch(ctx, e, k, 3, gs, "jfa_exact")))
            goto done;
    }
    if (vbg_check(ctx,
                  clEnqueueReadBuffer(vbg_runtime_queue(e->rt), e->labels.mem, CL_TRUE, 0,
                                      pixels * 4, labels, 0, NULL, NULL),
                  "exact labels download"))
        rc = VB_EDEVICE;
done:
    vbj_cells_free(&c);
    return rc;
}
