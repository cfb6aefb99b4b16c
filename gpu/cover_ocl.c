/* Host side of the cover kernels (gpu/cover.cl: a work-item per cell, for
 * CPU devices; gpu/cover_wg.cl: a work-group per cell, for GPUs): the shared
 * input uploaded once per run, arena slices sized from the device's memory,
 * launches per batch of cells, read-back of the per-cell results and the
 * quadruples. A batch runs in tiers: many small slices first; on a GPU the
 * cells that passed the group kernel's step budget then run again as
 * root-patch tasks on the work-item kernel (the hand-off tier); the cells
 * that ran out of their slices again on a few large slices; what still does
 * not fit is left to the host. Every error path reports VB_EDEVICE; the
 * caller falls back to the host.
 *
 * Device memory within a budget: vbg_cover_state.h. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbg_buffer.h"
#include "vbg_cover.h"
#include "vbg_cover_state.h"
#include "vbg_cover_tasks.h"

static void release(cov_state *s, vbg_buf *b)
{
    vbg_buf_release(&s->meter, b);
}

/* Makes b hold at least `need` bytes (its contents are lost when it grows). */
static int ensure(vb_ctx *ctx, cov_state *s, vbg_buf *b, size_t need, cl_mem_flags flags)
{
    return vbg_buf_ensure(ctx, s->rt, &s->meter, b, need, flags);
}

/* Copies bytes of src into b (grown when too small). */
static int upload(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes)
{
    int rc = ensure(ctx, s, b, bytes, CL_MEM_READ_ONLY);
    if (rc != VB_OK || bytes == 0)
        return rc;
    return vbg_check(ctx,
                     clEnqueueWriteBuffer(vbg_runtime_queue(s->rt), b->mem, CL_TRUE, 0, bytes,
                                          src, 0, NULL, NULL),
                     "clEnqueueWriteBuffer");
}

/* Bytes of one slice of tier t (its share of the frame stack on the
 * work-item kernel; the group kernel's one stack is tier_fixed). */
static size_t tier_bytes(const cov_tier *t)
{
    return (size_t)t->nb_cap * sizeof(vbq_nb) + (size_t)t->lab_cap * 4 +
           (t->wg ? 0 : (size_t)t->st_cap * sizeof(vbq_frame)) + (size_t)t->q_cap * 16;
}

/* Bytes of tier t that do not grow with its slices. */
static size_t tier_fixed(const cov_tier *t)
{
    return t->wg ? (size_t)t->st_cap * sizeof(vbq_frame) : 0;
}

/* Bytes of one task of a launch on tier t: its cell, root and result, and
 * its room for quadruples. */
static size_t task_bytes(const cov_tier *t)
{
    return 2 * sizeof(uint32_t) + sizeof(vbq_cell_out) + (size_t)t->qper * 16;
}

static int tier_alloc(vb_ctx *ctx, cov_state *s, cov_tier *t)
{
    size_t w = t->slices;
    int rc = ensure(ctx, s, &t->nb, w * t->nb_cap * sizeof(vbq_nb), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &t->lab, w * t->lab_cap * sizeof(uint32_t), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &t->st, (t->wg ? 1 : w) * t->st_cap * sizeof(vbq_frame),
                    CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &t->q, w * 4 * t->q_cap * sizeof(uint32_t), CL_MEM_READ_WRITE);
    return rc;
}

static double mib(size_t bytes)
{
    return (double)bytes / (1024.0 * 1024.0);
}

/* Splits the budget left after the input (module comment): the first
 * tier's slices, the launch buffers' room, the rest for the large tiers.
 * E142 when it cannot hold one slice and one task. */
static int budget_split(vb_ctx *ctx, cov_state *s, size_t n, size_t input)
{
    cov_tier *t0 = &s->tier[COV_FIRST];
    size_t least = input + tier_fixed(t0) + tier_bytes(t0) + task_bytes(t0);
    if (s->budget < least)
        return vb_error(ctx, VB_ENOMEM_DEVICE, NULL, 0,
                        "the cover of %zu spheres needs at least %.1f MiB of device memory "
                        "(input %.1f MiB, one arena slice %.1f MiB, one task's launch %zu bytes); "
                        "its budget is %.1f MiB (VORBALL_DEVICE_MEMORY_MIB sets it; "
                        "--device ref needs none)",
                        n, mib(least), mib(input), mib(tier_fixed(t0) + tier_bytes(t0)),
                        task_bytes(t0), mib(s->budget));
    size_t avail = s->budget - input;
    /* A slice covers one cell at a time, so no tier gets more slices than
     * there are spheres (whole groups of 64 on the work-item kernel, which
     * keeps the launch a multiple of its group). On an H100 a 327-atom run
     * held 1,594 MiB with every slice allocated. */
    size_t cap = n == 0 ? 1 : t0->wg ? n : (n + 63) / 64 * 64;
    size_t share = avail / 4 * 3;
    size_t fit = share > tier_fixed(t0) ? (share - tier_fixed(t0)) / tier_bytes(t0) : 0;
    size_t w = t0->want < cap ? t0->want : cap;
    w = w < fit ? w : fit;
    if (!t0->wg && w >= 64)
        w = w / 64 * 64;
    t0->slices = w ? w : 1;
    size_t used = tier_fixed(t0) + t0->slices * tier_bytes(t0);
    s->launch_room = avail / 8 > task_bytes(t0) ? avail / 8 : task_bytes(t0);
    s->tier_room = avail - used > s->launch_room ? avail - used - s->launch_room : 0;
    return VB_OK;
}

/* Bytes the large tier, or the hand-off tier, may hold: the budget's rest,
 * halved when both may be made. */
static size_t tier_share(const cov_state *s)
{
    return s->tier_room / (s->tier[COV_HAND].k && s->tier[COV_BIG].want ? 2 : 1);
}

static void tier_release(cov_state *s, cov_tier *t)
{
    release(s, &t->nb);
    release(s, &t->lab);
    release(s, &t->st);
    release(s, &t->q);
}

/* Releases what an earlier run on this backend made larger than this run
 * (of n spheres, its budget split) may hold, and, for an input of another
 * size, the large tiers and launch buffers an earlier run made: the meter's
 * peak, started again here, is then this run's alone, while repeated runs
 * of one input (bench --repeat) keep their buffers. */
static void trim(cov_state *s, size_t n)
{
    cov_tier *t0 = &s->tier[COV_FIRST];
    int other = n != s->last_n;
    s->last_n = n;
    if (t0->nb.size > t0->slices * t0->nb_cap * sizeof(vbq_nb))
        tier_release(s, t0);
    for (int k = COV_BIG; k < COV_TIERS; k++) {
        cov_tier *t = &s->tier[k];
        if (other || tier_fixed(t) + t->slices * tier_bytes(t) > tier_share(s)) {
            tier_release(s, t);
            t->slices = 0;
        }
    }
    if (other || s->cells.size + s->roots.size + s->outs.size + s->qout.size > s->launch_room) {
        release(s, &s->cells);
        release(s, &s->roots);
        release(s, &s->outs);
        release(s, &s->qout);
        s->qout_cap = 0;
    }
    s->meter.peak = s->meter.live;
}

/* upload into a buffer of exactly `bytes` (16 for none): a larger one of
 * an earlier run is released first. */
static int upload_exact(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes)
{
    if (b->size > (bytes ? bytes : 16))
        release(s, b);
    return upload(ctx, s, b, src, bytes);
}

static int cov_begin(vb_ctx *ctx, vb_cover_backend *be, const vbq_env *env, size_t n)
{
    cov_state *s = be->state;
    s->env = *env;
    size_t nodes = 2 * (size_t)env->first;
    size_t input = 4 * n * sizeof(double) + 7 * nodes * sizeof(double) +
                   (size_t)env->m * sizeof(uint32_t) + 2 * sizeof(cl_uint);
    int rc = budget_split(ctx, s, n, input);
    if (rc == VB_OK)
        trim(s, n);
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->x, env->x, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->y, env->y, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->z, env->z, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->r, env->r, n * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->box, env->box, 6 * nodes * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->rmax, env->rmax, nodes * sizeof(double));
    if (rc == VB_OK)
        rc = upload_exact(ctx, s, &s->ids, env->ids, (size_t)env->m * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->counters, 2 * sizeof(cl_uint), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = tier_alloc(ctx, s, &s->tier[COV_FIRST]);
    be->device_bytes_peak = s->meter.peak;
    return rc;
}

static int set_arg(vb_ctx *ctx, cl_kernel k, cl_uint i, size_t size, const void *v)
{
    return vbg_check(ctx, clSetKernelArg(k, i, size, v), "clSetKernelArg");
}

/* Appends room for n more quadruples to host_q. */
static int host_q_room(vb_ctx *ctx, cov_state *s, size_t n)
{
    s->host_q = vb_array_grow(s->host_q, &s->host_q_cap, s->host_nq + n, 4 * sizeof *s->host_q,
                              4096);
    if (s->host_q_cap < s->host_nq + n)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (quadruples)");
    return VB_OK;
}

/* The kernel's run time of one launch of tier t (event profiling; the
 * queue is made with it) into the tier's clocks (vbg_cover_state.h); a
 * device that gives no times adds none. */
static void tier_clock(cov_state *s, const cov_tier *t, cl_event done, size_t ntasks)
{
    size_t i = (size_t)(t - s->tier);
    s->clocks->launches[i]++;
    s->clocks->tasks[i] += ntasks;
    s->clocks->kernel_s[i] += vbg_event_seconds(done);
}

/* One launch of tier t over the tasks (cells[k], roots[k]) for k <
 * ncells: out[k] and the quadruples appended to host_q (out[k].qoff made
 * relative to host_q). ncells * task_bytes(t) fits the launch room. */
static int launch_tier(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                       const uint32_t *roots, size_t ncells, vbq_cell_out *out)
{
    cl_command_queue q = vbg_runtime_queue(s->rt);
    /* About 10 quadruples per cell on proteins: room for t->qper per task,
     * more when an earlier launch needed it and the launch room holds it;
     * cells beyond it are marked and covered again (cov_run). */
    size_t want = (size_t)t->qper * ncells;
    if (want > s->qout_cap)
        s->qout_cap = want;
    size_t c4 = ncells * sizeof(uint32_t), c48 = ncells * sizeof(vbq_cell_out);
    size_t held = (s->cells.size > c4 ? s->cells.size : c4) +
                  (s->roots.size > c4 ? s->roots.size : c4) +
                  (s->outs.size > c48 ? s->outs.size : c48);
    size_t room = s->launch_room > held + 16 ? (s->launch_room - held) / 16 : 1;
    size_t qroom = s->qout_cap < room ? s->qout_cap : room;
    int rc = upload(ctx, s, &s->cells, cells, ncells * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = upload(ctx, s, &s->roots, roots, ncells * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->outs, ncells * sizeof(vbq_cell_out), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = ensure(ctx, s, &s->qout, 4 * qroom * sizeof(uint32_t), CL_MEM_READ_WRITE);
    cl_uint zero[2] = {0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueWriteBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof zero, zero, 0,
                                            NULL, NULL),
                       "clEnqueueWriteBuffer");
    const vbq_env *e = &s->env;
    cl_uint nc = (cl_uint)ncells, qcap = (cl_uint)qroom;
    cl_uint nbc = t->nb_cap, labc = t->lab_cap, stc = t->st_cap, qc = t->q_cap;
    cl_uint a = 0;
    cl_kernel k = t->k;
    if (rc == VB_OK)
        rc = set_arg(ctx, k, a++, sizeof(cl_mem), &s->x.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->y.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->z.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->r.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->box.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->rmax.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->ids.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->first) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->m) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->rmax_all) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->near) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->tmax) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->T) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->min_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->max_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->enum_max) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->cells.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->roots.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->nb.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->lab.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->st.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->q.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nbc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &labc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &stc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->outs.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->qout.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qcap) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->counters.mem) ||
             (t->wg && set_arg(ctx, k, a++, sizeof(cl_uint), &t->budget))
                 ? VB_EDEVICE
                 : VB_OK;
    size_t local, global;
    if (t->wg) {
        local = COV_WG;
        global = (t->slices < ncells ? t->slices : ncells) * COV_WG;
    } else {
        local = t->slices < 64 ? t->slices : 64;
        global = t->slices < ncells ? t->slices : ncells;
        global = (global + local - 1) / local * local;
        if (global > t->slices)
            global = t->slices; /* a multiple of local by construction */
    }
    cl_event done = NULL;
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueNDRangeKernel(q, k, 1, NULL, &global, &local, 0, NULL, &done),
                       "cover kernel");
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->outs.mem, CL_TRUE, 0,
                                           ncells * sizeof(vbq_cell_out), out, 0, NULL, NULL),
                       "cover kernel");
    if (done) {
        if (rc == VB_OK)
            tier_clock(s, t, done, ncells);
        clReleaseEvent(done);
    }
    cl_uint counters[2] = {0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof counters,
                                           counters, 0, NULL, NULL),
                       "read counters");
    size_t nq = counters[1] < qroom ? counters[1] : qroom;
    if (rc == VB_OK)
        rc = host_q_room(ctx, s, nq);
    if (rc == VB_OK && nq)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->qout.mem, CL_TRUE, 0, 4 * nq * sizeof(uint32_t),
                                           s->host_q + 4 * s->host_nq, 0, NULL, NULL),
                       "read quadruples");
    if (rc != VB_OK) {
        clFinish(q); /* nothing half-done may reach the caller */
        return rc;
    }
    for (size_t c = 0; c < ncells; c++)
        if (out[c].status == VBQ_OK)
            out[c].qoff += (uint32_t)s->host_nq;
    s->host_nq += nq;
    /* The next batch gets room for what this one needed. */
    if (counters[1] > qroom)
        s->qout_cap = counters[1] + counters[1] / 4;
    return VB_OK;
}

/* Tier t over the tasks (cells[k], roots[k]) for k < ncells, in as many
 * launches as the launch room needs (launch_tier). */
static int run_tier(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                    const uint32_t *roots, size_t ncells, vbq_cell_out *out)
{
    size_t chunk = s->launch_room / task_bytes(t);
    chunk = chunk ? chunk : 1;
    int rc = VB_OK;
    for (size_t k0 = 0; rc == VB_OK && k0 < ncells; k0 += chunk) {
        size_t nk = ncells - k0 < chunk ? ncells - k0 : chunk;
        rc = launch_tier(ctx, s, t, cells + k0, roots + k0, nk, out + k0);
    }
    return rc;
}

/* A cell that ran out of a small slice is tried again on large ones; a
 * tie cluster (VBQ_CLUSTER) goes to the host, which decides it exactly. */
static int retry_on_device(uint32_t status)
{
    return status != VBQ_OK && status != VBQ_CLUSTER && status != VBQ_BUDGET;
}

/* A cell past the group kernel's step budget. */
static int handed_off(uint32_t status)
{
    return status == VBQ_BUDGET;
}

/* The cells of out[0 .. ncells) that pick takes, once more on tier t as
 * root-patch tasks (vbg_cover_tasks.h): a costly cell then runs on many
 * slices at once instead of lengthening the batch. Each such out[c] gets
 * the joined result (its quadruples at the end of host_q), or the status of
 * a task that failed. *picked: the count of such cells. */
static int tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks);

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
        tier_release(s, t);
        t->slices = 0;
        rc = tier_grow(ctx, s, h, n3);
    }
    if (rc == VB_OK && h->slices)
        rc = run_tier(ctx, s, h, cells3, roots3, n3, outs3);
    if (rc == VB_OK && h->slices)
        for (size_t j = 0, k = 0; j < n2; j++)
            if (retry_on_device(s->outs2[j].status))
                s->outs2[j] = outs3[k++];
    tier_release(s, h);
    h->slices = 0;
    free(cells3);
    free(roots3);
    free(outs3);
    return rc;
}

static int run_tasks(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                     size_t ncells, vbq_cell_out *out, vbg_task_pick pick, size_t *picked)
{
    size_t per = vbg_tasks_per_cell(s->env.T), n2 = 0;
    *picked = 0;
    for (size_t c = 0; c < ncells; c++)
        if (pick(out[c].status))
            n2 += per;
    if (n2 == 0)
        return VB_OK;
    if (n2 > s->cap2) {
        int bad = vb_array_resize((void **)&s->outs2, n2, sizeof *s->outs2);
        bad |= vb_array_resize((void **)&s->cells2, n2, sizeof *s->cells2);
        bad |= vb_array_resize((void **)&s->roots2, n2, sizeof *s->roots2);
        if (bad)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
        s->cap2 = n2;
    }
    vbg_tasks_make(cells, out, ncells, pick, per, s->cells2, s->roots2);
    int rc = run_tier(ctx, s, t, s->cells2, s->roots2, n2, s->outs2);
    if (rc == VB_OK && t == &s->tier[COV_BIG])
        rc = retry_huge(ctx, s, t, n2);
    if (rc == VB_OK)
        rc = host_q_room(ctx, s, vbg_tasks_quads(s->outs2, n2));
    if (rc == VB_OK)
        *picked = vbg_tasks_join(s->outs2, out, ncells, pick, per, s->host_q, &s->host_nq);
    return rc;
}

/* Tier t (the large or the hand-off tier) with slices for `tasks` tasks,
 * made on first use: at most the device's occupancy and what its share of
 * the budget's rest holds (half of it when both tiers may be made), in
 * whole groups of 64 on the work-item kernel; the group kernel's large tier
 * one slice per COV_BIG_TASKS tasks. Returns VB_OK with no slices
 * when none fits: the cells then go to the host. */
static int tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks)
{
    size_t room = tier_share(s);
    size_t fit = room > tier_fixed(t) ? (room - tier_fixed(t)) / tier_bytes(t) : 0;
    size_t w = t->wg ? tasks : (tasks + 63) / 64 * 64;
    if (t->wg && t == &s->tier[COV_BIG])
        w = (tasks + COV_BIG_TASKS - 1) / COV_BIG_TASKS;
    w = w < t->want ? w : t->want;
    w = w < fit ? w : fit;
    if (!t->wg && w >= 64)
        w = w / 64 * 64;
    if (w <= t->slices)
        return VB_OK;
    t->slices = w;
    return tier_alloc(ctx, s, t);
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
    int rc = run_tier(ctx, s, &s->tier[COV_FIRST], cells, s->hroots, ncells, out);
    /* The cells past the group kernel's budget, on the work-item kernel;
     * those of them whose tasks ran out of arenas go on to the large
     * slices with the rest. */
    size_t per = vbg_tasks_per_cell(s->env.T), handed = 0, retried = 0;
    cov_tier *th = &s->tier[COV_HAND], *t1 = &s->tier[COV_BIG];
    size_t nh = rc == VB_OK && th->k ? count_picked(out, ncells, handed_off) : 0;
    if (nh)
        rc = tier_grow(ctx, s, th, nh * per);
    if (rc == VB_OK && nh && th->slices)
        rc = run_tasks(ctx, s, th, cells, ncells, out, handed_off, &handed);
    be->handed_cells += handed;
    size_t n1 = rc == VB_OK && t1->want ? count_picked(out, ncells, retry_on_device) : 0;
    if (n1)
        rc = tier_grow(ctx, s, t1, n1 * per);
    if (rc == VB_OK && n1 && t1->slices)
        rc = run_tasks(ctx, s, t1, cells, ncells, out, retry_on_device, &retried);
    if (s->meter.peak > be->device_bytes_peak)
        be->device_bytes_peak = s->meter.peak;
    if (rc == VB_OK)
        *quads = s->host_q;
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
                          &s->qout, &s->counters};
        for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
            release(s, all[k]);
        for (int t = 0; t < COV_TIERS; t++)
            tier_release(s, &s->tier[t]);
        if (s->k)
            clReleaseKernel(s->k);
        if (s->k_item)
            clReleaseKernel(s->k_item);
        free(s->host_q);
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
    be->state = s;
    be->close = cov_close;
    s->clocks = &be->clocks;
    s->rt = rt;
    /* GPUs run a group per cell; a CPU device (PoCL) a work-item per cell,
     * which its compiler turns into plain loops (its work-group compiler
     * does not handle the group kernel's barriers in loops).
     * VORBALL_COVER_KERNEL=item|group overrides. */
    const char *kn = getenv("VORBALL_COVER_KERNEL");
    s->wg = kn && strcmp(kn, "group") == 0 ? 1 : kn && strcmp(kn, "item") == 0 ? 0
                                                : vbg_runtime_is_gpu(rt);
    cov_tier *t0 = &s->tier[COV_FIRST], *t1 = &s->tier[COV_BIG], *th = &s->tier[COV_HAND];
    cov_tier *t3 = &s->tier[COV_HUGE];
    int cpu = !vbg_runtime_is_gpu(rt);
    t0->nb_cap = s->wg ? COV_WG_NB : cpu ? COV_CPU_NB : COV_NB;
    t0->lab_cap = s->wg ? COV_WG_LAB : cpu ? COV_CPU_LAB : COV_LAB;
    t0->st_cap = COV_ST;
    t0->q_cap = s->wg ? COV_WG_Q : COV_Q;
    t1->nb_cap = COV_BIG_NB;
    t1->lab_cap = COV_BIG_LAB;
    t1->st_cap = COV_ST;
    t1->q_cap = COV_BIG_Q;
    t3->nb_cap = COV_HUGE_NB;
    t3->lab_cap = COV_BIG_LAB;
    t3->st_cap = COV_ST;
    t3->q_cap = COV_BIG_Q;
    /* The hand-off tier's work-items get the group kernel's first-tier
     * arenas: a task of a cell past the budget then fits (fcc 10,976
     * jittered, simulated on the host: all 5,760 tasks of its 60 cells fit
     * them; with the work-item kernel's own arenas 66 of them ran out). */
    th->nb_cap = COV_WG_NB;
    th->lab_cap = COV_WG_LAB;
    th->st_cap = COV_ST;
    th->q_cap = COV_WG_Q;
    /* Output room per task: about 10 quadruples per cell on proteins; the
     * second tier's cells are the large ones. */
    t0->qper = th->qper = 24u;
    t1->qper = t3->qper = 256u;
    /* A CPU device's work-items test the four parts of a fetch side by
     * side (VBQ_WALK_V4_CL, core/cells/vbq_gather_shared.h: the same
     * answers). 2-core machine, PoCL on one thread, 4yvs first 14,070:
     * see papers/gpu-voronoi-cells-of-spheres/results/
     * cpu_vs_voronota_stop44.md. */
    int rc = s->wg ? kernel_get(ctx, rt, "cover_wg.cl", NULL, "vbq_cover_wg", &s->k)
                   : kernel_get(ctx, rt, "cover.cl", cpu ? "-DVBQ_WALK_V4_CL" : NULL,
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
    uint32_t budget = kb && *kb ? (uint32_t)strtoul(kb, NULL, 10) : COV_BUDGET;
    int to_host = !(kh && strcmp(kh, "item") == 0);
    if (rc == VB_OK && s->wg && budget && !to_host)
        rc = kernel_get(ctx, rt, "cover.cl", NULL, "vbq_cover_kernel", &s->k_item);
    t0->k = t1->k = t3->k = s->k;
    t0->wg = t1->wg = t3->wg = s->wg;
    t0->budget = s->wg ? budget : 0u;
    th->k = s->k_item;
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
    /* Slices wanted: as many as keep the device busy; each run makes as
     * many of them as its cells use and its budget holds (budget_split,
     * tier_grow). A CPU device gets no large tier (its cells are as cheap
     * on the host). */
    s->budget = vbg_runtime_memory_budget(rt);
    size_t want = s->wg ? (size_t)units * 16
                        : (vbg_runtime_is_gpu(rt) ? (size_t)units * 512 : (size_t)units * 64);
    /* Work-items come in groups of 64 (cov_run). */
    if (!s->wg && want >= 64)
        want = want / 64 * 64;
    /* VORBALL_COVER_SLICES overrides the count (measurements). */
    const char *ws = getenv("VORBALL_COVER_SLICES");
    if (ws && atol(ws) > 0)
        want = (size_t)atol(ws);
    t0->want = want;
    if (s->wg) {
        t1->want = (size_t)units * 4;
        /* Measured on an H100 (the 211,440-atom tiling): when the tier
         * reran whole cells (stop 43, run C) 4x the compute units gave 1.76 s
         * of cover and certification, 2x 1.84 s; rerunning only the tasks
         * that ran out (864 of them), 2x and 4x both take 0.25 s of huge-tier
         * kernel and 1.29 s of device cover, and 2x holds 4.0 GB of device
         * buffers at the peak against 6.0 GB (stop 44, run A). */
        t3->want = (size_t)units * 2;
        /* The hand-off tier: work-items as for the work-item kernel on a
         * GPU, in groups of 64. */
        th->want = (size_t)units * 512;
    }
    vbg_cover_knobs(s);
    be->name = "opencl";
    snprintf(be->device, sizeof be->device, "%s", vbg_runtime_device_name(rt));
    be->batch_cells = vbg_runtime_is_gpu(rt) ? 1u << 18 : 1u << 14;
    be->begin = cov_begin;
    be->run = cov_run;
    *out = be;
    return VB_OK;
}
