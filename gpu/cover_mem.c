/* The cover backend's device buffers (gpu/cover_ocl.c is its host side):
 * the shared input uploaded once per run, and the pool of arena arrays
 * the tiers pass to their kernels, one tier after the other, sized by the
 * plan (gpu/cover_plan.c, vbg_cover_state.h). */
#include "vb_parallel.h"
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

/* The tier's arrays, in the order the pool holds them (vbg_cov_tier_layout). */
static vbg_buf *tier_buf(cov_tier *t, int k)
{
    vbg_buf *all[COV_ARRAYS] = {&t->nb, &t->lab, &t->st, &t->q, &t->hi, &t->memo, &t->memo_tag};
    return all[k];
}

/* Drops tier t's hold on the pool's arrays (they are s->arr's). */
static void tier_unbind(cov_tier *t)
{
    for (int k = 0; k < COV_ARRAYS; k++) {
        vbg_buf *b = tier_buf(t, k);
        b->mem = NULL;
        b->size = 0;
    }
    t->pool_gen = 0;
}

/* Releases the pool's arrays (no tier holds them after). */
static void pool_release(cov_state *s)
{
    for (int k = 0; k < COV_TIERS; k++)
        tier_unbind(&s->tier[k]);
    for (int k = 0; k < COV_ARRAYS; k++)
        vbg_cov_release(s, &s->arr[k]);
    s->pool_gen++;
}

int vbg_cov_tier_bind(vb_ctx *ctx, cov_state *s, cov_tier *t)
{
    if (t->pool_gen && t->pool_gen == s->pool_gen && t->bound_slices == t->slices &&
        t->bound_nb == t->nb_cap && t->bound_lab == t->lab_cap)
        return VB_OK;
    tier_unbind(t);
    size_t a[COV_ARRAYS];
    vbg_cov_tier_arrays(t, t->slices, a);
    int rc = VB_OK;
    for (int k = 0; rc == VB_OK && k < COV_ARRAYS; k++)
        if (a[k] > s->arr[k].size) {
            /* An array grows (its contents lost): every tier lets go of it. */
            for (int j = 0; j < COV_TIERS; j++)
                tier_unbind(&s->tier[j]);
            s->pool_gen++;
            vbg_cov_release(s, &s->arr[k]);
            rc = vbg_cov_ensure(ctx, s, &s->arr[k], a[k], CL_MEM_READ_WRITE);
        }
    if (rc != VB_OK)
        return rc;
    for (int k = 0; k < COV_ARRAYS; k++) {
        vbg_buf *b = tier_buf(t, k);
        b->mem = a[k] ? s->arr[k].mem : NULL;
        b->size = a[k];
    }
    t->pool_gen = s->pool_gen ? s->pool_gen : (s->pool_gen = 1);
    t->bound_slices = t->slices;
    t->bound_nb = t->nb_cap;
    t->bound_lab = t->lab_cap;
    return VB_OK;
}

static double mib(size_t bytes)
{
    return (double)bytes / (1024.0 * 1024.0);
}

void vbg_cov_tier_release(cov_state *s, cov_tier *t)
{
    (void)s;
    tier_unbind(t);
}

/* Releases what an earlier run on this backend made larger than this run
 * (of n spheres, its budget split) may hold, and, for an input of another
 * size, the pool, the large tiers and the launch buffers an earlier run
 * made: the meter's peak, started again here, is then this run's alone,
 * while repeated runs of one input (bench --repeat) keep their buffers. */
static void trim(cov_state *s, size_t n)
{
    int other = n != s->last_n;
    s->last_n = n;
    for (int k = COV_BIG; k < COV_TIERS; k++)
        if (other) {
            vbg_cov_tier_release(s, &s->tier[k]);
            s->tier[k].slices = 0;
        }
    size_t pool = 0;
    for (int k = 0; k < COV_ARRAYS; k++)
        pool += s->arr[k].size;
    if (other || pool > s->pool_room)
        pool_release(s);
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
    size_t input = vbg_cov_input_bytes(n, env->first, env->m);
    /* The first tier's arenas for this input, from a sample of its cells
     * covered on the host threads (idle before the first launch); an input
     * that takes no sample gets the defaults again, whatever an earlier
     * run on this backend got, or the fitted arenas below COV_FIT_SMALL
     * spheres (vbg_cov_fit). */
    size_t covered = 0, over = 0;
    if (vbg_cov_fit_wanted(s, n) &&
        vb_cover_sample_over(env, COV_FIT_SAMPLE, COV_FIT_NB / 2, COV_FIT_LAB / 2, vb_threads(be->host_threads),
                             &covered, &over) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover sample)");
    if (s->fit)
        vbg_cov_fit(s, n, covered, over);
    size_t least = vbg_cov_split(s, n, input);
    if (least) {
        const cov_tier *t0 = &s->tier[COV_FIRST];
        return vb_error(ctx, VB_ENOMEM_DEVICE, NULL, 0,
                        "the cover of %zu spheres needs at least %.1f MiB of device memory "
                        "(input %.1f MiB, one arena slice %.1f MiB, one task's launch %zu bytes); "
                        "its budget is %.1f MiB (VORBALL_DEVICE_MEMORY_MIB sets it; "
                        "--device ref needs none)",
                        n, mib(least), mib(input), mib(least - input - vbg_cov_task_bytes(t0)),
                        vbg_cov_task_bytes(t0), mib(s->budget));
    }
    trim(s, n);
    int rc = upload_exact(ctx, s, &s->x, env->x, n * sizeof(double));
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
        rc = vbg_cov_tier_bind(ctx, s, &s->tier[COV_FIRST]);
    be->device_bytes_peak = s->meter.peak;
    return rc;
}

/* Tier t (the large, huge or hand-off tier) with slices for `tasks` tasks,
 * made on first use in the pool (vbg_cov_tier_slices says how many).
 * Returns VB_OK with no slices when none fits: the cells then go to the
 * host. */
int vbg_cov_tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks)
{
    size_t w = vbg_cov_tier_slices(s, t, tasks);
    if (w <= t->slices)
        return VB_OK;
    t->slices = w;
    return vbg_cov_tier_bind(ctx, s, t);
}
