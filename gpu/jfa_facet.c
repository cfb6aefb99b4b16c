/* Host side of Facet-JFA on OpenCL (kernels in gpu/facet_jfa.cl): JFA on the
 * coarse grid, then per doubling one step (the children of marked cells
 * inherit their labels) and the marking, over the active list only. List
 * lengths stay on the device (the kernels loop over them), so the host waits
 * once, at the end, not once per level. The coarse JFA and the small levels
 * run in one launch (facet_small), where a launch per phase costs more than
 * the phase; starting at m = n, the run is JFA on the grid and a count of its
 * boundary pixels. */
#include "jfa_internal.h"

/* Work-items per list kernel: enough to fill a large GPU; each loops over
 * the list with this stride, so the count can stay on the device. */
#define VBJ_LIST_ITEMS ((size_t)1 << 18)

static size_t list_items(uint64_t bound)
{
    return bound < VBJ_LIST_ITEMS ? (size_t)bound : VBJ_LIST_ITEMS;
}

static int launch_list(vb_ctx *ctx, vbj_engine *e, int which, const char *name, int nargs,
                       const vbj_arg *a, uint64_t bound)
{
    cl_kernel k;
    size_t g = list_items(bound);
    int rc;
    if ((rc = vbj_cl_kernel(ctx, e, which, &k)) || (rc = vbj_cl_set_args(ctx, k, name, nargs, a)))
        return rc;
    return vbj_cl_launch(ctx, e, k, 1, &g, name);
}

/* Most work-items of the one work-group of facet_small. */
#define VBJ_FUSE_ITEMS ((size_t)1024)

/* The start of the run in one launch (facet_small): the coarse JFA, its
 * marking and doublings 1 .. jlast. Its coarse steps count as the C
 * reference counts them. */
static int launch_small(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, int compact, cl_uint lm,
                        size_t npairs, cl_uint jlast, vbj_counts *counts)
{
    cl_uint np = (cl_uint)npairs, ln = vbj_log2u(s->n), dim = (cl_uint)s->dim;
    cl_uint ncnt = ln - lm + 2, cp = (cl_uint)compact;
    size_t cells = (size_t)1 << (dim * lm), wg = 0;
    cl_kernel k;
    int rc;
    if ((rc = vbj_clbuf_reserve(ctx, e, &e->grid[0], cells * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->grid[1], cells * 4)) ||
        (rc = vbj_cl_kernel(ctx, e, VBJ_K_FSMALL, &k)))
        return rc;
    vbj_arg a[] = {VBJ_ARG(e->pairs.mem),    VBJ_ARG(np),            VBJ_ARG(e->grid[0].mem),
                   VBJ_ARG(e->grid[1].mem),  VBJ_ARG(e->seeds.mem),  VBJ_ARG(e->counter.mem),
                   VBJ_ARG(ncnt),            VBJ_ARG(e->store[0].mem), VBJ_ARG(e->store[1].mem),
                   VBJ_ARG(e->list[0].mem),  VBJ_ARG(e->list[1].mem), VBJ_ARG(lm),
                   VBJ_ARG(ln),              VBJ_ARG(dim),           VBJ_ARG(cp),
                   VBJ_ARG(jlast)};
    if ((rc = vbj_cl_set_args(ctx, k, "facet_small", 16, a)))
        return rc;
    if (vbg_check(ctx,
                  clGetKernelWorkGroupInfo(k, vbg_runtime_device(e->rt), CL_KERNEL_WORK_GROUP_SIZE,
                                           sizeof wg, &wg, NULL),
                  "facet_small work-group size"))
        return VB_EDEVICE;
    if (wg > VBJ_FUSE_ITEMS)
        wg = VBJ_FUSE_ITEMS;
    if (vbg_check(ctx,
                  clEnqueueNDRangeKernel(vbg_runtime_queue(e->rt), k, 1, NULL, &wg, &wg, 0, NULL,
                                         vbj_cl_event(e)),
                  "facet_small"))
        return VB_EDEVICE;
    counts->threads += npairs + (uint64_t)lm * cells; /* lm coarse steps: m/2 .. 1 */
    counts->steps += lm;
    counts->step_pixels += (uint64_t)lm * cells;
    return VB_OK;
}

/* The start of the run a launch per phase: JFA on the coarse m^d grid
 * (steps 2-4 of Algorithm 1; level 0's dense array, *prev), the counters,
 * and step 7 for the coarse grid: nothing is marked before the first
 * doubling, so every coarse cell is refined (children into list 0). */
static int start(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t m, cl_uint levels,
                 size_t npairs, vbj_counts *counts, cl_mem *prev)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    cl_uint dim = (cl_uint)s->dim, lm = vbj_log2u(m);
    uint64_t cells_m = (uint64_t)1 << (dim * lm);
    uint32_t steps[40];
    int which = 0, rc;
    if ((rc = vbj_cl_dense(ctx, e, s, s->n / m, npairs, 0, steps,
                           vbj_schedule(VBJ_JFA, m, steps), counts, &which)))
        return rc;
    cl_uint zero = 0, first = (cl_uint)cells_m; /* fills copy their pattern at once */
    if (vbg_check(ctx,
                  clEnqueueFillBuffer(queue, e->counter.mem, &zero, sizeof zero, 0,
                                      (levels + 2) * 4, 0, NULL, NULL),
                  "facet counters") ||
        vbg_check(ctx,
                  clEnqueueFillBuffer(queue, e->counter.mem, &first, sizeof first, 0, 4, 0, NULL,
                                      NULL),
                  "facet counters"))
        return VB_EDEVICE;
    *prev = e->grid[which].mem;
    cl_uint dense = 1, j = 0, sh = 0, mk = 0, rf = 1;
    vbj_arg a[] = {VBJ_ARG(e->list[1].mem), VBJ_ARG(dense), VBJ_ARG(e->counter.mem),
                   VBJ_ARG(j),              VBJ_ARG(sh),    VBJ_ARG(mk),
                   VBJ_ARG(rf),             VBJ_ARG(*prev), VBJ_ARG(e->list[0].mem),
                   VBJ_ARG(lm),             VBJ_ARG(dim)};
    return launch_list(ctx, e, VBJ_K_MARKREFINE, "facet_mark_refine", 11, a, cells_m);
}

/* Steps 2-9 of Algorithm 1 on the device, then the counts. The labels of
 * the last level end in *out_mem (with marks). Levels of at most `fuse`
 * cells, with everything before them, run in one launch (launch_small). */
static int timed(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, int compact, uint32_t m,
                 uint32_t fuse, size_t npairs, vbj_result *out, cl_mem *out_mem)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    cl_uint n = s->n, dim = (cl_uint)s->dim, ln = vbj_log2u(n), lm = vbj_log2u(m);
    cl_uint levels = ln - lm, j0 = 0;
    uint64_t cells_m = (uint64_t)1 << (dim * lm);
    int rc, L = 0; /* L: list of the current cells */
    vbj_clbuf *bufs[2] = {&e->store[0], &e->store[1]};
    cl_mem prev;
    if (fuse != VBJ_FUSE_NONE && cells_m <= fuse) {
        while (j0 < levels && (uint64_t)1 << (dim * (lm + j0 + 1)) <= fuse)
            j0++;
        if ((rc = launch_small(ctx, e, s, compact, lm, npairs, j0, &out->counts)))
            return rc;
        L = (int)(j0 & 1);
        prev = j0 ? bufs[j0 & 1]->mem : e->grid[(lm & 1)].mem; /* lm coarse steps */
    } else if ((rc = start(ctx, e, s, m, levels, npairs, &out->counts, &prev)))
        return rc;

    /* Steps 8-9 per doubling: the children of marked cells inherit, one
     * l = 1 step on the children of the refined cells, then marking and (but
     * at the last level) refinement. The level's labels (B) alternate
     * between two buffers: the step reads the level above. */
    for (cl_uint j = j0 + 1; j <= levels; j++) {
        cl_uint lq = lm + j, lf = ln - lq, last = j == levels;
        cl_uint mk = compact || last, rf = !last, sh = dim, nd = 0;
        uint64_t cells_max = (uint64_t)1 << (dim * lq);
        cl_mem B = bufs[j & 1]->mem;
        vbj_arg sa[] = {VBJ_ARG(e->list[L].mem), VBJ_ARG(e->counter.mem), VBJ_ARG(j),
                        VBJ_ARG(prev),           VBJ_ARG(B),              VBJ_ARG(e->seeds.mem),
                        VBJ_ARG(lq),             VBJ_ARG(lf),             VBJ_ARG(dim)};
        if ((rc = launch_list(ctx, e, VBJ_K_FSTEP, "facet_step", 9, sa, cells_max)))
            return rc;
        vbj_arg ma[] = {VBJ_ARG(e->list[L].mem), VBJ_ARG(nd), VBJ_ARG(e->counter.mem),
                        VBJ_ARG(j),              VBJ_ARG(sh), VBJ_ARG(mk),
                        VBJ_ARG(rf),             VBJ_ARG(B),  VBJ_ARG(e->list[1 - L].mem),
                        VBJ_ARG(lq),             VBJ_ARG(dim)};
        if ((rc = launch_list(ctx, e, VBJ_K_MARKREFINE, "facet_mark_refine", 11, ma,
                              cells_max)))
            return rc;
        L = 1 - L;
        prev = B;
    }
    cl_uint cnt[40];
    if (vbg_check(ctx,
                  clEnqueueReadBuffer(queue, e->counter.mem, CL_TRUE, 0, (levels + 2) * 4, cnt, 0,
                                      NULL, NULL),
                  "facet counters read"))
        return VB_EDEVICE;
    /* The reference's counts: cnt[j] cells refined before doubling j, each
     * into 2^d children that take one step and (when marking) one mark. */
    for (cl_uint j = 1; j <= levels; j++) {
        uint64_t children = (uint64_t)cnt[j] << dim;
        int marked = compact || j == levels;
        out->counts.threads += cnt[j] + children + (marked ? children : 0);
        out->counts.step_pixels += children;
        out->counts.steps++;
    }
    out->counts.boundary = cnt[levels + 1];

    *out_mem = prev;
    return VB_OK;
}

int vbj_cl_facet(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, const vbj_options *opt,
                 vbj_result *out, cl_mem *result)
{
    cl_command_queue queue = vbg_runtime_queue(e->rt);
    double t0 = 1e3 * vb_now();
    uint32_t m = opt->m;
    int src = m ? VB_OK : vbj_start_resolution(ctx, s, &m);
    if (src != VB_OK)
        return src;
    cl_uint n = s->n, levels = vbj_log2u(n) - vbj_log2u(m);
    size_t pixels = out->pixels, npairs;
    int compact = opt->variant == VBJ_FACET;
    int rc;
    out->counts.m = m;
    if (levels == 0) /* m = n: JFA on the grid itself, then its boundary */
        return vbj_cl_dense_run(ctx, e, s, VBJ_JFA, 1, out, result);
    if ((rc = vbj_cl_upload_seeds(ctx, e, s)) ||
        (rc = vbj_cl_upload_pairs(ctx, e, s, n / m, &npairs, &out->counts.collisions)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->store[0], pixels * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->store[1], pixels * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->counter, (levels + 2) * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->list[0], pixels * 4)) ||
        (rc = vbj_clbuf_reserve(ctx, e, &e->list[1], pixels * 4)))
        return rc;
    double t1 = 1e3 * vb_now();
    vbj_cl_record(e);
    cl_mem last = NULL;
    uint32_t fuse = opt->fuse_cells      ? opt->fuse_cells
                    : s->dim == 3 ? VBJ_FUSE_CELLS_3D
                                  : VBJ_FUSE_CELLS_2D;
    rc = timed(ctx, e, s, compact, m, fuse, npairs, out, &last);
    if (!rc && vbg_check(ctx, clFinish(queue), "facet-jfa"))
        rc = VB_EDEVICE;
    double t2 = 1e3 * vb_now();
    out->ms_gpu = vbj_cl_recorded_ms(e);
    if (rc)
        return rc;

    /* The last level's labels without the marks. */
    cl_kernel k;
    cl_uint cells = (cl_uint)pixels;
    if ((rc = vbj_cl_kernel(ctx, e, VBJ_K_STRIP, &k)))
        return rc;
    vbj_arg fa[] = {VBJ_ARG(last), VBJ_ARG(cells)};
    if ((rc = vbj_cl_set_args(ctx, k, "facet_strip", 2, fa)) ||
        (rc = vbj_cl_launch(ctx, e, k, 1, &pixels, "facet_strip")))
        return rc;
    if (vbg_check(ctx, clFinish(queue), "facet strip"))
        return VB_EDEVICE;
    out->ms_fill = 1e3 * vb_now() - t2;
    out->ms_kernel = t2 - t1;
    out->ms_transfer = t1 - t0;
    *result = last;
    return VB_OK;
}
