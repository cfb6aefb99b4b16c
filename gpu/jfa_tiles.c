/* Host side of the exact tiled engine on OpenCL (kernel gpu/jfa_tiles.cl,
 * decisions core/discrete/vbj_tiles.h): the seed grid is built on the host
 * (vbj_tiles_prep_build, shared with the C twin) and uploaded, one launch
 * decides every tile, and exact-boundary counts the boundary pixels of the
 * result (jfa_boundary). Kernels are fetched (built) before the clock. */
#include "jfa_internal.h"
#include "vbj_tiles.h"

int vbj_cl_tiles(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, vbj_variant v, vbj_result *out,
                 cl_mem *result)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    double t0 = 1e3 * vb_now();
    vbj_tiles_prep p;
    int rc = vbj_tiles_prep_build(ctx, s, &p);
    if (rc)
        return rc;
    out->ms_prep = 1e3 * vb_now() - t0;
    int boundary = v == VBJ_EXACT_BOUNDARY;
    cl_kernel k, kb = NULL;
    size_t ncnt = (size_t)VBJ_XT_NC * VBJ_XT_SLOTS;
    if ((rc = vbj_cl_upload(ctx, e, &e->cells_start, p.start, (p.nbuckets + 1) * 4, "seed grid upload")) ||
        (rc = vbj_cl_upload(ctx, e, &e->cells_items, p.recs, s->k * 16, "seed grid upload")) ||
        (rc = vbj_cl_upload(ctx, e, &e->cells_ring0, p.ring0, p.nbuckets, "seed grid upload")) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->labels, out->pixels * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->tcounters, ncnt * 4)) ||
        (rc = vbj_cl_kernel(ctx, e, VBJ_K_TILES, &k)) ||
        (boundary && (rc = vbj_cl_kernel(ctx, e, vbj_cl_jfa_kernel_index(s, 0, VBJ_K_BOUNDARY), &kb))))
        goto done;
    cl_uint n = s->n, dim = (cl_uint)s->dim, ts = p.ts, bs = p.bs, g = p.g;
    uint32_t S = 1u << p.ts, T = s->n >> p.ts, row = S < VBJ_XT_ROW ? S : VBJ_XT_ROW;
    size_t tiles = (size_t)T * T * (s->dim == 3 ? T : 1);
    size_t wg = (size_t)S * S * (s->dim == 3 ? S : 1) / row, gs = tiles * wg;
    {
        vbj_arg a[] = {VBJ_ARG(e->cells_items.mem), VBJ_ARG(e->cells_start.mem),
                       VBJ_ARG(e->cells_ring0.mem), VBJ_ARG(e->labels.mem),
                       VBJ_ARG(e->tcounters.mem),   VBJ_ARG(n),
                       VBJ_ARG(dim),                VBJ_ARG(ts),
                       VBJ_ARG(bs),                 VBJ_ARG(g)};
        if ((rc = vbj_cl_set_args(ctx, k, "jfa_tiles", 10, a)) ||
            (rc = vbg_check(ctx, clSetKernelArg(k, 10, VBJ_XT_CAP * 16, NULL), "jfa_tiles local")
                      ? VB_EDEVICE
                      : VB_OK))
            goto done;
    }
    double t1 = 1e3 * vb_now();
    vbj_cl_record(e);
    cl_uint zero = 0;
    if (vbg_check(ctx,
                  clEnqueueFillBuffer(queue, e->tcounters.mem, &zero, sizeof zero, 0, ncnt * 4, 0,
                                      NULL, vbj_cl_event(e)),
                  "exact counters") ||
        vbg_check(ctx,
                  clEnqueueNDRangeKernel(queue, k, 1, NULL, &gs, &wg, 0, NULL, vbj_cl_event(e)),
                  "jfa_tiles"))
        rc = VB_EDEVICE;
    if (!rc && boundary)
        rc = vbj_cl_count_boundary(ctx, e, s, 0, e->labels.mem, &out->counts);
    if (!rc && vbg_check(ctx, clFinish(queue), "jfa_tiles"))
        rc = VB_EDEVICE;
    double t2 = 1e3 * vb_now();
    out->ms_gpu = vbj_cl_recorded_ms(e);
    if (rc)
        goto done;
    /* The counters, after the clock (the C twin counts the same). */
    cl_uint *slots = malloc(ncnt * sizeof *slots);
    if (!slots) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "exact counters: out of memory");
        goto done;
    }
    if (vbg_check(ctx,
                  clEnqueueReadBuffer(queue, e->tcounters.mem, CL_TRUE, 0, ncnt * 4, slots, 0,
                                      NULL, NULL),
                  "exact counters read"))
        rc = VB_EDEVICE;
    uint64_t cnt[VBJ_XT_NC] = {0};
    for (size_t i = 0; i < ncnt; i++)
        cnt[i / VBJ_XT_SLOTS] += slots[i];
    free(slots);
    if (rc)
        goto done;
    vbj_tiles_counts(s, &p, cnt, &out->counts);
    out->ms_kernel = t2 - t1;
    out->ms_transfer = t1 - t0;
    *result = e->labels.mem;
done:
    vbj_tiles_prep_free(&p);
    return rc;
}
