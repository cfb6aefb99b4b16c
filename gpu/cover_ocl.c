/* Host side of the cover kernels (gpu/cover.cl: a work-item per cell, for
 * CPU devices; gpu/cover_wg.cl: a work-group per cell, for GPUs): the
 * backend made and closed, and a batch of cells run in tiers: many small
 * slices first; on a GPU the cells that passed the group kernel's step
 * budget then run again as root-patch tasks on the work-item kernel (the
 * hand-off tier); the cells that ran out of their slices again on a few
 * large slices; what still does not fit is left to the host. Every error
 * path reports VB_EDEVICE; the caller falls back to the host. The input's
 * upload and the arena slices: gpu/cover_mem.c; one launch and its
 * read-back: gpu/cover_launch.c.
 *
 * Device memory within a budget: vbg_cover_state.h. */
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_array.h"
#include "vbg_buffer.h"
#include "vbg_cover.h"
#include "vbg_cover_state.h"
#include "vbg_cover_tasks.h"

/* A cell that ran out of a small slice is tried again on large ones; a
 * tie cluster (VBQ_CLUSTER) goes to the host, which decides it exactly. */
static int retry_on_device(uint32_t status)
{
    return status != VBQ_OK && status != VBQ_CLUSTER && status != VBQ_BUDGET;
}

/* Room for n2 tasks in s->outs2, cells2, roots2. VB_OK or VB_ENOMEM. */
static int room2(vb_ctx *ctx, cov_state *s, size_t n2)
{
    if (n2 <= s->cap2)
        return VB_OK;
    int bad = vb_array_resize((void **)&s->outs2, n2, sizeof *s->outs2);
    bad |= vb_array_resize((void **)&s->cells2, n2, sizeof *s->cells2);
    bad |= vb_array_resize((void **)&s->roots2, n2, sizeof *s->roots2);
    if (bad)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    s->cap2 = n2;
    return VB_OK;
}

/* A cell past the group kernel's step budget. */
static int handed_off(uint32_t status)
{
    return status == VBQ_BUDGET;
}

/* The tasks of outs2[0 .. n2) that ran out of tier t's arenas, again on the
 * huge tier (vbg_cover_state.h): made in t's place (released first) and
 * released after, so the two are never held at once and the next batch
 * starts without them. Each such outs2[j] gets its task's new result (its
 * quadruples appended to host_q); the other tasks keep theirs. */
static int retry_huge(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t n2)
{
    cov_tier *h = &s->tier[COV_HUGE];
    size_t n3 = 0;
    for (size_t j = 0; j < n2; j++)
        n3 += retry_on_device(s->outs2[j].status);
    if (n3 == 0 || h->want == 0)
        return VB_OK;
    uint32_t *cells3 = malloc(n3 * sizeof *cells3), *roots3 = malloc(n3 * sizeof *roots3);
    vbq_cell_out *outs3 = malloc(n3 * sizeof *outs3);
    int rc = cells3 && roots3 && outs3 ? VB_OK
                                       : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    for (size_t j = 0, k = 0; rc == VB_OK && j < n2; j++)
        if (retry_on_device(s->outs2[j].status)) {
            cells3[k] = s->cells2[j];
            roots3[k++] = s->roots2[j];
        }
    if (rc == VB_OK) {
        vbg_cov_tier_release(s, t);
        t->slices = 0;
        rc = vbg_cov_tier_grow(ctx, s, h, n3);
    }
    if (rc == VB_OK && h->slices)
        rc = vbg_cov_run_tier(ctx, s, h, cells3, roots3, n3, outs3);
    if (rc == VB_OK && h->slices)
        for (size_t j = 0, k = 0; j < n2; j++)
            if (retry_on_device(s->outs2[j].status))
                s->outs2[j] = outs3[k++];
    vbg_cov_tier_release(s, h);
    h->slices = 0;
    free(cells3);
    free(roots3);
    free(outs3);
    return rc;
}

/* The cells of out[0 .. ncells) that pick takes, once more on tier t as
 * root-patch tasks (vbg_cover_tasks.h): a costly cell then runs on many
 * slices at once instead of lengthening the batch. The cells' tasks in
 * the order vbg_tasks_order gives (costliest first where
 * vbg_tasks_ordered says, else index order; s->task_order). Each such out[c] gets the
 * joined result (its quadruples at the end of host_q), or the status of a
 * task that failed. *picked: the count of such cells. */
static int run_tasks(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                     size_t ncells, vbq_cell_out *out, vbg_task_pick pick, size_t *picked)
{
    size_t per = vbg_tasks_per_cell(s->env.T, s->task_split), np = 0;
    *picked = 0;
    for (size_t c = 0; c < ncells; c++)
        np += pick(out[c].status) != 0;
    if (np == 0)
        return VB_OK;
    uint32_t *ord = malloc(np * sizeof *ord), *pc = malloc(np * sizeof *pc);
    vbq_cell_out *po = malloc(np * sizeof *po);
    int rc = ord && pc && po ? VB_OK : VB_ENOMEM;
    if (rc == VB_OK && vbg_tasks_ordered(s->task_order, np))
        rc = vbg_tasks_order(out, ncells, pick, ord) == np ? VB_OK : VB_ENOMEM;
    else if (rc == VB_OK)
        for (size_t c = 0, j = 0; c < ncells; c++)
            if (pick(out[c].status))
                ord[j++] = (uint32_t)c;
    rc = rc == VB_OK ? room2(ctx, s, np * per)
                     : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    for (size_t j = 0; rc == VB_OK && j < np; j++) {
        pc[j] = cells[ord[j]];
        po[j] = out[ord[j]];
    }
    size_t n2 = np * per;
    if (rc == VB_OK) {
        vbg_tasks_make(pc, po, np, pick, per, s->task_split, s->cells2, s->roots2);
        rc = vbg_cov_run_tier(ctx, s, t, s->cells2, s->roots2, n2, s->outs2);
    }
    if (rc == VB_OK && t == &s->tier[COV_BIG])
        rc = retry_huge(ctx, s, t, n2);
    if (rc == VB_OK)
        rc = vbg_cov_host_q_room(ctx, s, vbg_tasks_quads(s->outs2, n2));
    if (rc == VB_OK) {
        *picked = vbg_tasks_join(s->outs2, po, np, pick, per, s->host_q, &s->host_nq);
        for (size_t j = 0; j < np; j++)
            out[ord[j]] = po[j];
    }
    free(ord);
    free(pc);
    free(po);
    return rc;
}

/* The first tier's kernel (a CPU device's work-item kernel, a GPU's group
 * kernel) hands every patch it does not decide to the host
 * (vbq_hand_patch); a cell it hands whole (VBQ_CLUSTER) found no room for
 * one. Those cells of out[0 .. ncells) again on the first tier, while a
 * launch asked for more room than it had (launch_tier grows it, within the
 * launch room) and the last one left fewer such cells, a few times; what
 * is still left goes to the host whole. A cell past the group kernel's
 * budget whose stack found no room (VBQ_BUDGET with VBQ_BUDGET_HAND) is not
 * run again: that would walk its budget's steps again, which the host
 * threads beat (README, Devices); it goes to them whole, as before stop
 * 49. */
static int rerun_hand_short(vb_ctx *ctx, cov_state *s, const uint32_t *cells, size_t ncells,
                            vbq_cell_out *out)
{
    int rc = VB_OK;
    size_t last = SIZE_MAX;
    for (int again = 0; rc == VB_OK && again < 4 && s->hand_short; again++) {
        size_t n2 = 0;
        for (size_t c = 0; c < ncells; c++)
            n2 += out[c].status == VBQ_CLUSTER;
        if (n2 == 0 || n2 >= last)
            break;
        last = n2;
        if (room2(ctx, s, n2) != VB_OK)
            return VB_ENOMEM;
        for (size_t c = 0, k = 0; c < ncells; c++)
            if (out[c].status == VBQ_CLUSTER) {
                s->cells2[k] = cells[c];
                s->roots2[k++] = VBQ_ALL_ROOTS;
            }
        s->hand_short = 0;
        s->rerun = 1;
        rc = vbg_cov_run_tier(ctx, s, &s->tier[COV_FIRST], s->cells2, s->roots2, n2, s->outs2);
        s->rerun = 0;
        for (size_t c = 0, k = 0; rc == VB_OK && c < ncells; c++)
            if (out[c].status == VBQ_CLUSTER)
                out[c] = s->outs2[k++];
    }
    return rc;
}

/* Cells of out[0 .. ncells) that pick takes. */
static size_t count_picked(const vbq_cell_out *out, size_t ncells, vbg_task_pick pick)
{
    size_t n = 0;
    for (size_t c = 0; c < ncells; c++)
        n += pick(out[c].status) != 0;
    return n;
}

static int cov_run(vb_ctx *ctx, vb_cover_backend *be, const uint32_t *cells, size_t ncells,
                   vbq_cell_out *out, const uint32_t **quads)
{
    cov_state *s = be->state;
    *quads = NULL;
    s->host_nq = 0;
    s->host_hand_n = 0;
    s->hand_short = 0;
    be->hand = NULL;
    be->hand_words = 0;
    if (ncells == 0)
        return VB_OK;
    if (ncells > UINT32_MAX)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "cover batch too large");
    if (ncells > s->hroots_cap) {
        uint32_t *hr = realloc(s->hroots, ncells * sizeof *hr);
        if (!hr)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
        s->hroots = hr;
        s->hroots_cap = ncells;
    }
    for (size_t c = 0; c < ncells; c++)
        s->hroots[c] = VBQ_ALL_ROOTS;
    int rc = vbg_cov_run_tier(ctx, s, &s->tier[COV_FIRST], cells, s->hroots, ncells, out);
    if (rc == VB_OK && s->k_hand)
        rc = rerun_hand_short(ctx, s, cells, ncells, out);
    /* The cells finished so far, to the caller while the tiers below run. */
    if (rc == VB_OK && be->early)
        rc = be->early(be->early_user, out, ncells, s->host_q, s->host_hand, s->host_hand_n);
    /* The cells past the group kernel's budget, on the work-item kernel;
     * those of them whose tasks ran out of arenas go on to the large
     * slices with the rest. */
    size_t per = vbg_tasks_per_cell(s->env.T, s->task_split), handed = 0, retried = 0;
    cov_tier *th = &s->tier[COV_HAND], *t1 = &s->tier[COV_BIG];
    size_t nh = rc == VB_OK && th->k ? count_picked(out, ncells, handed_off) : 0;
    if (nh)
        rc = vbg_cov_tier_grow(ctx, s, th, nh * per);
    if (rc == VB_OK && nh && th->slices)
        rc = run_tasks(ctx, s, th, cells, ncells, out, handed_off, &handed);
    be->handed_cells += handed;
    size_t n1 = rc == VB_OK && t1->want ? count_picked(out, ncells, retry_on_device) : 0;
    /* A fitted first tier's few cells past it go to the host threads
     * rather than a large launch of their own (COV_FIT_HOST). */
    if (s->fitted && n1 <= COV_FIT_HOST)
        n1 = 0;
    if (n1)
        rc = vbg_cov_tier_grow(ctx, s, t1, n1 * per);
    if (rc == VB_OK && n1 && t1->slices)
        rc = run_tasks(ctx, s, t1, cells, ncells, out, retry_on_device, &retried);
    if (s->meter.peak > be->device_bytes_peak)
        be->device_bytes_peak = s->meter.peak;
    if (rc == VB_OK) {
        *quads = s->host_q;
        be->hand = s->host_hand;
        be->hand_words = s->host_hand_n;
    }
    return rc;
}

static void cov_close(vb_cover_backend *be)
{
    if (!be)
        return;
    cov_state *s = be->state;
    if (s) {
        vbg_buf *all[] = {&s->x,    &s->y,     &s->z,     &s->r,    &s->box,
                          &s->rmax, &s->ids,   &s->cells, &s->roots, &s->outs,
                          &s->qout, &s->counters, &s->hand};
        for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
            vbg_cov_release(s, all[k]);
        for (int t = 0; t < COV_TIERS; t++)
            vbg_cov_tier_release(s, &s->tier[t]);
        for (int k = 0; k < COV_ARRAYS; k++)
            vbg_cov_release(s, &s->arr[k]);
        if (s->k)
            clReleaseKernel(s->k);
        if (s->k_item)
            clReleaseKernel(s->k_item);
        free(s->host_q);
        free(s->host_hand);
        free(s->outs2);
        free(s->cells2);
        free(s->roots2);
        free(s->hroots);
        free(s);
    }
    free(be);
}

/* A kernel of the program built from `file` with the build options opts
 * (NULL: none). */
static int kernel_get(vb_ctx *ctx, vbg_runtime *rt, const char *file, const char *opts,
                      const char *name, cl_kernel *k)
{
    cl_program prog;
    /* VORBALL_COVER_CL_OPTS: build options appended to the cover kernels'
     * (measurements: -DVBQ_HOST_FORM gives a GPU the host's forms) */
    const char *xo = getenv("VORBALL_COVER_CL_OPTS");
    char buf[512];
    if (xo && *xo) {
        snprintf(buf, sizeof buf, "%s %s", opts ? opts : "", xo);
        opts = buf;
    }
    int rc = vbg_program_get(ctx, rt, file, opts, &prog);
    cl_int err = CL_SUCCESS;
    if (rc == VB_OK) {
        *k = clCreateKernel(prog, name, &err);
        rc = vbg_check(ctx, err, name);
    }
    return rc;
}

int vbg_cover_open(vb_ctx *ctx, vbg_runtime *rt, vb_cover_backend **out)
{
    *out = NULL;
    vb_cover_backend *be = calloc(1, sizeof *be);
    cov_state *s = calloc(1, sizeof *s);
    if (!be || !s) {
        free(be);
        free(s);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    atomic_init(&be->running, 0);
    be->state = s;
    be->close = cov_close;
    s->clocks = &be->clocks;
    s->rt = rt;
    /* GPUs run a group per cell; a CPU device (PoCL) a work-item per cell,
     * which its compiler turns into plain loops (its work-group compiler
     * does not handle the group kernel's barriers in loops).
     * VORBALL_COVER_KERNEL=item|group overrides. */
    const char *kn = getenv("VORBALL_COVER_KERNEL");
    int group = kn && strcmp(kn, "group") == 0;
    if (group && !vbg_runtime_is_gpu(rt)) {
        /* PoCL 3.1 crashed running it (corpus jittered_fcc, stop 46). */
        vb_warn(ctx, VB_W_COVER_GROUP_CPU, NULL, 0,
                "VORBALL_COVER_KERNEL=group is ignored on %s, a CPU device: its compiler does "
                "not take the group kernel's barriers in loops; the work-item kernel runs",
                vbg_runtime_device_name(rt));
        group = 0;
    }
    s->wg = group ? 1 : kn && strcmp(kn, "item") == 0 ? 0 : vbg_runtime_is_gpu(rt);
    int cpu = !vbg_runtime_is_gpu(rt);
    /* A CPU device's work-items test the four parts of a fetch side by
     * side (VBQ_WALK_V4_CL, core/cells/vbq_gather_shared.h: the same
     * answers) and keep the host's two caches (VBQ_CACHES_CL: each slice
     * gets lab_cap doubles and the record memo, 240 KiB more;
     * VORBALL_COVER_CACHES=0 leaves them out, for measurements). 2-core
     * machine, PoCL on one thread, 4yvs first 14,070: see
     * papers/gpu-voronoi-cells-of-spheres/results/cpu_vs_voronota_stop44.md
     * and _stop45.md. */
    const char *kc = getenv("VORBALL_COVER_CACHES");
    int caches = cpu && !s->wg && !(kc && strcmp(kc, "0") == 0);
    /* The group kernel hands a patch it does not decide to the host too
     * (built with -DVBQ_HANDOFF; lane 0 calls vbq_hand_patch), the host
     * resuming it alone (core/cells/cover_resume.c) where it covered the
     * whole cell again before stop 48 (on an H100, fcc 10,976 exact: 2,160
     * of its 10,976 cells; sc 16^3 jittered 1e-12: 4,070 of 4,096).
     * VORBALL_COVER_GPU_HAND=0 builds it without (measurements). */
    const char *kg = getenv("VORBALL_COVER_GPU_HAND");
    int gpu_hand = s->wg && !(kg && strcmp(kg, "0") == 0);
    int rc = s->wg ? kernel_get(ctx, rt, "cover_wg.cl", gpu_hand ? "-DVBQ_HANDOFF" : NULL,
                                "vbq_cover_wg", &s->k)
                   : kernel_get(ctx, rt, "cover.cl",
                                caches ? "-DVBQ_WALK_V4_CL -DVBQ_CACHES_CL"
                                       : cpu ? "-DVBQ_WALK_V4_CL" : NULL,
                                "vbq_cover_kernel", &s->k);
    /* The group kernel's budget (VORBALL_COVER_BUDGET: steps, 0 for none):
     * the cells past it go to the host threads, as cells that ran out of
     * arenas do, beside the device's next batch; with
     * VORBALL_COVER_HANDOFF=item to a second launch of the work-item kernel
     * on the device instead. Measured on an H100 with 16 host threads
     * (bench, best of 3): fcc 10,976 jittered by 1e-9, cover 0.38 s to the
     * host against 3.96 s to the work-item kernel (4.72 s with no budget);
     * the capsid and its 2x2x2 tiling 0.267 / 1.250 s against 0.297 /
     * 1.344 s (papers/degenerate-input/results/h100_stop41.txt). */
    const char *kb = getenv("VORBALL_COVER_BUDGET"), *kh = getenv("VORBALL_COVER_HANDOFF");
    uint32_t budget = (kb && *kb ? (uint32_t)strtoul(kb, NULL, 10) : COV_BUDGET) & ~VBQ_BUDGET_HAND;
    int to_host = !(kh && strcmp(kh, "item") == 0);
    if (rc == VB_OK && s->wg && budget && !to_host)
        rc = kernel_get(ctx, rt, "cover.cl", NULL, "vbq_cover_kernel", &s->k_item);
    /* A GPU's host threads are idle, so they resume the handed patches
     * (vb_cover.h); VORBALL_COVER_RESUME_SPREAD=1|0 overrides (tests). */
    const char *kr = getenv("VORBALL_COVER_RESUME_SPREAD");
    be->resume_spread = kr && *kr ? strcmp(kr, "0") != 0 : s->wg;
    /* Past the budget a cell hands the patches left on its stack, where
     * the group kernel hands patches and its budget cells go to the host
     * threads: they resume those patches instead of covering the cell again
     * (stop 48 on an H100: fcc 10,976 exact 28 cells, jittered 1e-9 62,
     * covered whole); VORBALL_COVER_BUDGET_HAND=0 leaves them whole
     * (measurements). */
    const char *kbh = getenv("VORBALL_COVER_BUDGET_HAND");
    int budget_hand = gpu_hand && to_host && !(kbh && strcmp(kbh, "0") == 0);
    cl_uint units = 1;
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clGetDeviceInfo(vbg_runtime_device(rt), CL_DEVICE_MAX_COMPUTE_UNITS,
                                       sizeof units, &units, NULL),
                       "clGetDeviceInfo");
    if (rc != VB_OK) {
        cov_close(be);
        return rc;
    }
    s->budget = vbg_runtime_memory_budget(rt);
    vbg_cov_caps(s, cpu, caches, gpu_hand, units);
    cov_tier *t0 = &s->tier[COV_FIRST];
    t0->k = s->tier[COV_BIG].k = s->tier[COV_HUGE].k = s->k;
    s->tier[COV_HAND].k = s->k_item;
    t0->budget = s->wg && budget ? budget | (budget_hand ? VBQ_BUDGET_HAND : 0u) : 0u;
    /* VORBALL_COVER_SLICES overrides the first tier's count (measurements). */
    const char *ws = getenv("VORBALL_COVER_SLICES");
    if (ws && atol(ws) > 0)
        t0->want = (size_t)atol(ws);
    vbg_cover_knobs(s);
    t0->nb_want = t0->nb_cap;
    t0->lab_want = t0->lab_cap;
    be->name = "opencl";
    snprintf(be->device, sizeof be->device, "%s", vbg_runtime_device_name(rt));
    be->batch_cells = vbg_runtime_is_gpu(rt) ? 1u << 18 : 1u << 14;
    be->begin = vbg_cov_begin;
    be->run = cov_run;
    *out = be;
    return VB_OK;
}
