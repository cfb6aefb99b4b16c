/* The cover backend's device buffers (gpu/cover_ocl.c is its host side):
 * the shared input uploaded once per run, the budget split between the
 * tiers' arena slices and the launches, and the tiers made, grown and
 * released within it (vbg_cover_state.h). */
#include "vbg_buffer.h"
#include "vbg_cover_state.h"

void vbg_cov_release(cov_state *s, vbg_buf *b)
{
    vbg_buf_release(&s->meter, b);
}

/* Makes b hold at least `need` bytes (its contents are lost when it grows). */
int vbg_cov_ensure(vb_ctx *ctx, cov_state *s, vbg_buf *b, size_t need, cl_mem_flags flags)
{
    return vbg_buf_ensure(ctx, s->rt, &s->meter, b, need, flags);
}

/* Copies bytes of src into b (grown when too small). */
int vbg_cov_upload(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes)
{
    int rc = vbg_cov_ensure(ctx, s, b, bytes, CL_MEM_READ_ONLY);
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
           (t->wg ? 0 : (size_t)t->st_cap * sizeof(vbq_frame)) + (size_t)t->q_cap * 16 +
           (t->caches ? (size_t)t->lab_cap * 8 + VBQ_MEMO * (sizeof(vbq_nb) + 8) : 0);
}

/* Bytes of tier t that do not grow with its slices. */
static size_t tier_fixed(const cov_tier *t)
{
    return t->wg ? (size_t)t->st_cap * sizeof(vbq_frame) : 0;
}

/* Bytes of one task of a launch on tier t: its cell, root and result, and
 * its room for quadruples. */
size_t vbg_cov_task_bytes(const cov_tier *t)
{
    return 2 * sizeof(uint32_t) + sizeof(vbq_cell_out) + (size_t)t->qper * 16;
}

static int tier_alloc(vb_ctx *ctx, cov_state *s, cov_tier *t)
{
    size_t w = t->slices;
    int rc = vbg_cov_ensure(ctx, s, &t->nb, w * t->nb_cap * sizeof(vbq_nb), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = vbg_cov_ensure(ctx, s, &t->lab, w * t->lab_cap * sizeof(uint32_t),
                            CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = vbg_cov_ensure(ctx, s, &t->st, (t->wg ? 1 : w) * t->st_cap * sizeof(vbq_frame),
                            CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = vbg_cov_ensure(ctx, s, &t->q, w * 4 * t->q_cap * sizeof(uint32_t),
                            CL_MEM_READ_WRITE);
    if (rc == VB_OK && t->caches)
        rc = vbg_cov_ensure(ctx, s, &t->hi, w * t->lab_cap * sizeof(double), CL_MEM_READ_WRITE);
    if (rc == VB_OK && t->caches)
        rc = vbg_cov_ensure(ctx, s, &t->memo, w * VBQ_MEMO * sizeof(vbq_nb), CL_MEM_READ_WRITE);
    if (rc == VB_OK && t->caches)
        rc = vbg_cov_ensure(ctx, s, &t->memo_tag, w * 2 * VBQ_MEMO * sizeof(uint32_t),
                            CL_MEM_READ_WRITE);
    return rc;
}

static double mib(size_t bytes)
{
    return (double)bytes / (1024.0 * 1024.0);
}

/* The capacities of a solo tier's slices (vbg_cover_state.h, COV_CPU_NB):
 * those wanted, halved while `want` slices exceed `share` bytes, each no
 * lower than the work-item kernel's own (nor than it was wanted). */
static void solo_caps(cov_tier *t, size_t share)
{
    t->nb_cap = t->nb_want;
    t->lab_cap = t->lab_want;
    while (t->want * tier_bytes(t) > share) {
        uint32_t nb = t->nb_cap / 2 >= COV_NB ? t->nb_cap / 2 : t->nb_cap;
        uint32_t lab = t->lab_cap / 2 >= COV_LAB ? t->lab_cap / 2 : t->lab_cap;
        if (nb == t->nb_cap && lab == t->lab_cap)
            break;
        t->nb_cap = nb;
        t->lab_cap = lab;
    }
}

/* Splits the budget left after the input (module comment): the first
 * tier's slices, the launch buffers' room, the rest for the large tiers.
 * E142 when it cannot hold one slice and one task. */
static int budget_split(vb_ctx *ctx, cov_state *s, size_t n, size_t input)
{
    cov_tier *t0 = &s->tier[COV_FIRST];
    if (t0->solo)
        solo_caps(t0, s->budget > input ? (s->budget - input) / 4 * 3 : 0);
    size_t least = input + tier_fixed(t0) + tier_bytes(t0) + vbg_cov_task_bytes(t0);
    if (s->budget < least)
        return vb_error(ctx, VB_ENOMEM_DEVICE, NULL, 0,
                        "the cover of %zu spheres needs at least %.1f MiB of device memory "
                        "(input %.1f MiB, one arena slice %.1f MiB, one task's launch %zu bytes); "
                        "its budget is %.1f MiB (VORBALL_DEVICE_MEMORY_MIB sets it; "
                        "--device ref needs none)",
                        n, mib(least), mib(input), mib(tier_fixed(t0) + tier_bytes(t0)),
                        vbg_cov_task_bytes(t0), mib(s->budget));
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
    if (!t0->wg && !t0->solo && w >= 64)
        w = w / 64 * 64;
    t0->slices = w ? w : 1;
    size_t used = tier_fixed(t0) + t0->slices * tier_bytes(t0);
    s->launch_room = avail / 8 > vbg_cov_task_bytes(t0) ? avail / 8 : vbg_cov_task_bytes(t0);
    s->tier_room = avail - used > s->launch_room ? avail - used - s->launch_room : 0;
    return VB_OK;
}

/* Bytes the large tier, or the hand-off tier, may hold: the budget's rest,
 * halved when both may be made. */
static size_t tier_share(const cov_state *s)
{
    return s->tier_room / (s->tier[COV_HAND].k && s->tier[COV_BIG].want ? 2 : 1);
}

void vbg_cov_tier_release(cov_state *s, cov_tier *t)
{
    vbg_cov_release(s, &t->nb);
    vbg_cov_release(s, &t->lab);
    vbg_cov_release(s, &t->st);
    vbg_cov_release(s, &t->q);
    vbg_cov_release(s, &t->hi);
    vbg_cov_release(s, &t->memo);
    vbg_cov_release(s, &t->memo_tag);
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
        vbg_cov_tier_release(s, t0);
    for (int k = COV_BIG; k < COV_TIERS; k++) {
        cov_tier *t = &s->tier[k];
        if (other || tier_fixed(t) + t->slices * tier_bytes(t) > tier_share(s)) {
            vbg_cov_tier_release(s, t);
            t->slices = 0;
        }
    }
    if (other || s->cells.size + s->roots.size + s->outs.size + s->qout.size + s->hand.size >
                     s->launch_room) {
        vbg_cov_release(s, &s->cells);
        vbg_cov_release(s, &s->roots);
        vbg_cov_release(s, &s->outs);
        vbg_cov_release(s, &s->qout);
        vbg_cov_release(s, &s->hand);
        s->qout_cap = 0;
        s->hand_want = 0;
    }
    s->meter.peak = s->meter.live;
}

/* upload into a buffer of exactly `bytes` (16 for none): a larger one of
 * an earlier run is released first. */
static int upload_exact(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes)
{
    if (b->size > (bytes ? bytes : 16))
        vbg_cov_release(s, b);
    return vbg_cov_upload(ctx, s, b, src, bytes);
}

int vbg_cov_begin(vb_ctx *ctx, vb_cover_backend *be, const vbq_env *env, size_t n)
{
    cov_state *s = be->state;
    s->env = *env;
    size_t nodes = 2 * (size_t)env->first;
    size_t input = 4 * n * sizeof(double) + 7 * nodes * sizeof(double) +
                   (size_t)env->m * sizeof(uint32_t) + 4 * sizeof(cl_uint);
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
        rc = vbg_cov_ensure(ctx, s, &s->counters, 4 * sizeof(cl_uint), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = tier_alloc(ctx, s, &s->tier[COV_FIRST]);
    be->device_bytes_peak = s->meter.peak;
    return rc;
}


/* Tier t (the large or the hand-off tier) with slices for `tasks` tasks,
 * made on first use: at most the device's occupancy and what its share of
 * the budget's rest holds (half of it when both tiers may be made), in
 * whole groups of 64 on the work-item kernel; the group kernel's large tier
 * one slice per COV_BIG_TASKS tasks. Returns VB_OK with no slices
 * when none fits: the cells then go to the host. */
int vbg_cov_tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks)
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
