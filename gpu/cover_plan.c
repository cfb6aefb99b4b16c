/* The cover backend's device memory plan (vbg_cover_state.h): how many
 * arena slices each tier gets, the pool they share, the launch buffers'
 * room and the peak these add up to. Sizes only, no OpenCL call, so that
 * a unit test can size a made-up device (tests/gpu/test_cover_plan.c);
 * gpu/cover_mem.c makes the buffers these functions size. */
#include <string.h>

#include "vbg_cover_state.h"

/* Bytes of one slice of tier t (its share of the frame stack on the
 * work-item kernel; the group kernel's one stack does not grow with its
 * slices). */
static size_t slice_bytes(const cov_tier *t)
{
    return (size_t)t->nb_cap * sizeof(vbq_nb) + (size_t)t->lab_cap * 4 +
           (t->wg ? 0 : (size_t)t->st_cap * sizeof(vbq_frame)) + (size_t)t->q_cap * 16 +
           (t->caches ? (size_t)t->lab_cap * 8 + VBQ_MEMO * (sizeof(vbq_nb) + 8) : 0);
}

void vbg_cov_tier_arrays(const cov_tier *t, size_t w, size_t bytes[COV_ARRAYS])
{
    bytes[0] = w * t->nb_cap * sizeof(vbq_nb);
    bytes[1] = w * t->lab_cap * sizeof(uint32_t);
    bytes[2] = (t->wg ? 1 : w) * t->st_cap * sizeof(vbq_frame);
    bytes[3] = w * 4 * t->q_cap * sizeof(uint32_t);
    bytes[4] = t->caches ? w * t->lab_cap * sizeof(double) : 0;
    bytes[5] = t->caches ? w * VBQ_MEMO * sizeof(vbq_nb) : 0;
    bytes[6] = t->caches ? w * 2 * VBQ_MEMO * sizeof(uint32_t) : 0;
    for (int k = 0; k < 4; k++)
        bytes[k] = bytes[k] ? bytes[k] : 16;
}

size_t vbg_cov_pool_need(const cov_state *s, const cov_tier *t, size_t w)
{
    size_t a[COV_ARRAYS], sum = 0;
    vbg_cov_tier_arrays(t, w, a);
    for (int k = 0; k < COV_ARRAYS; k++)
        sum += s->arr[k].size > a[k] ? s->arr[k].size : a[k];
    return sum;
}

/* The most slices of tier t, at most `most`, whose arrays fit `room`
 * bytes with the pool's arrays as s holds them (each array grown to the
 * larger of the two). */
static size_t slices_fit(const cov_state *s, const cov_tier *t, size_t room, size_t most)
{
    size_t lo = 0, hi = most;
    while (lo < hi) {
        size_t mid = lo + (hi - lo + 1) / 2;
        if (vbg_cov_pool_need(s, t, mid) <= room)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

size_t vbg_cov_input_bytes(size_t n, size_t first, size_t m)
{
    size_t nodes = 2 * first;
    return 4 * n * sizeof(double) + 7 * nodes * sizeof(double) + m * sizeof(uint32_t) +
           4 * sizeof(cl_uint);
}

size_t vbg_cov_task_bytes(const cov_tier *t)
{
    return 2 * sizeof(uint32_t) + sizeof(vbq_cell_out) + (size_t)t->qper * 16;
}

/* The capacities of a solo tier's slices (vbg_cover_state.h, COV_CPU_NB):
 * those wanted, halved while `want` slices exceed `share` bytes, each no
 * lower than the work-item kernel's own (nor than it was wanted). */
static void solo_caps(cov_tier *t, size_t share)
{
    t->nb_cap = t->nb_want;
    t->lab_cap = t->lab_want;
    while (t->want * slice_bytes(t) > share) {
        uint32_t nb = t->nb_cap / 2 >= COV_NB ? t->nb_cap / 2 : t->nb_cap;
        uint32_t lab = t->lab_cap / 2 >= COV_LAB ? t->lab_cap / 2 : t->lab_cap;
        if (nb == t->nb_cap && lab == t->lab_cap)
            break;
        t->nb_cap = nb;
        t->lab_cap = lab;
    }
}

size_t vbg_cov_split(cov_state *s, size_t n, size_t input)
{
    cov_tier *t0 = &s->tier[COV_FIRST];
    if (t0->solo)
        solo_caps(t0, s->budget > input ? (s->budget - input) / 4 * 3 : 0);
    cov_state none; /* the first tier's share, as if no array were held */
    memset(none.arr, 0, sizeof none.arr);
    size_t least = input + vbg_cov_pool_need(&none, t0, 1) + vbg_cov_task_bytes(t0);
    if (s->budget < least)
        return least;
    size_t avail = s->budget - input;
    /* A slice covers one cell at a time, so no tier gets more slices than
     * there are spheres (whole groups of 64 on the work-item kernel, which
     * keeps the launch a multiple of its group), and the group kernel's no
     * more than one per cells_per_slice spheres (vbg_cover_state.h). On an
     * H100 a 327-atom run held 1,594 MiB with every slice allocated. */
    size_t cps = s->cells_per_slice ? s->cells_per_slice : 1;
    size_t cap = n == 0 ? 1 : t0->wg ? (n + cps - 1) / cps : (n + 63) / 64 * 64;
    size_t w = t0->want < cap ? t0->want : cap;
    w = slices_fit(&none, t0, avail / 4 * 3, w);
    if (!t0->wg && !t0->solo && w >= 64)
        w = w / 64 * 64;
    t0->slices = w ? w : 1;
    size_t first = vbg_cov_pool_need(&none, t0, t0->slices);
    s->launch_room = avail / 8 > vbg_cov_task_bytes(t0) ? avail / 8 : vbg_cov_task_bytes(t0);
    /* The pool: what the budget leaves after the input and the launch
     * room, but no more than the first tier's slices or pool_per_sphere
     * bytes a sphere, whichever is more (and COV_POOL_FLOOR). */
    size_t room = avail > s->launch_room ? avail - s->launch_room : 0;
    if (s->pool_per_sphere) {
        size_t prop = n * s->pool_per_sphere;
        prop = prop > COV_POOL_FLOOR ? prop : COV_POOL_FLOOR;
        prop = prop > first ? prop : first;
        room = room < prop ? room : prop;
    }
    s->pool_room = room > first ? room : first;
    return 0;
}

size_t vbg_cov_task_share(const cov_state *s)
{
    return s->task_split == 1u ? 1u : 4u;
}

void vbg_cov_big_qper(cov_state *s, uint32_t qper)
{
    uint32_t q = qper / (uint32_t)vbg_cov_task_share(s);
    s->tier[COV_BIG].qper = s->tier[COV_HUGE].qper = q ? q : 1u;
}

size_t vbg_cov_tier_slices(const cov_state *s, const cov_tier *t, size_t tasks)
{
    size_t w = t->wg ? tasks : (tasks + 63) / 64 * 64;
    if (t->wg && t == &s->tier[COV_BIG]) {
        size_t per = (size_t)COV_BIG_TASKS * vbg_cov_task_share(s);
        w = (tasks + per - 1) / per;
    }
    w = w < t->want ? w : t->want;
    w = slices_fit(s, t, s->pool_room, w);
    if (!t->wg && w >= 64)
        w = w / 64 * 64;
    return w;
}

size_t vbg_cov_launch_held(const cov_state *s, size_t ncells)
{
    size_t c4 = ncells * sizeof(uint32_t), c48 = ncells * sizeof(vbq_cell_out);
    return (s->cells.size > c4 ? s->cells.size : c4) + (s->roots.size > c4 ? s->roots.size : c4) +
           (s->outs.size > c48 ? s->outs.size : c48) + s->hand.size;
}

void vbg_cov_launch_sizes(cov_state *s, const cov_tier *t, size_t ncells, size_t *qroom,
                          size_t *hwords)
{
    /* About 10 quadruples per cell on proteins: room for t->qper per task,
     * more when an earlier launch needed it and the launch room holds it;
     * cells beyond it are marked and covered again (cov_run). */
    size_t want = (size_t)t->qper * ncells;
    if (want > s->qout_cap)
        s->qout_cap = want;
    size_t held = vbg_cov_launch_held(s, ncells);
    size_t room = s->launch_room > held + 16 ? (s->launch_room - held) / 16 : 1;
    *qroom = s->qout_cap < room ? s->qout_cap : room;
    /* The handed patches (vbq_hand_patch): the first tier only, room for
     * hand_cell_words a cell, but no less than COV_HAND_FLOOR words in all
     * (nor than COV_HAND_WORDS a cell), at most COV_HAND_CAP words in all,
     * or what an earlier launch asked, within what the launch room leaves
     * after the quadruples and the other buffers (the hand buffer held
     * counted). */
    int hand = s->k_hand && t == &s->tier[COV_FIRST];
    size_t per = (size_t)s->hand_cell_words * ncells;
    size_t floor_w = (size_t)COV_HAND_WORDS * ncells;
    floor_w = floor_w < s->hand_floor_words ? floor_w : s->hand_floor_words;
    /* The floor is for crystals' and small sets' ties: an input whose
     * sample fitted the arenas (few large cells: proteins) gets its
     * hand_cell_words a cell alone (COV_FITTED_SAMPLE). */
    floor_w = s->fitted == COV_FITTED_SAMPLE ? 0 : floor_w;
    per = per > floor_w ? per : floor_w;
    per = per < s->hand_cap_words ? per : s->hand_cap_words;
    size_t hw = hand ? (s->hand_want > per ? s->hand_want : per) : 0;
    size_t used = held - s->hand.size + 16 * *qroom;
    size_t left = s->launch_room > used ? s->launch_room - used : 0;
    hw = hw < left / 4 ? hw : left / 4;
    *hwords = hw > UINT32_MAX / 2 ? UINT32_MAX / 2 : hw;
}

/* The launch buffers grown (as vbg_buf_ensure does) for the launches of
 * tier t over `tasks` tasks, in the chunks vbg_cov_run_tier runs. */
static void plan_launches(cov_state *s, const cov_tier *t, size_t tasks)
{
    size_t chunk = s->launch_room / vbg_cov_task_bytes(t);
    chunk = chunk ? chunk : 1;
    for (size_t k0 = 0; k0 < tasks; k0 += chunk) {
        size_t nk = tasks - k0 < chunk ? tasks - k0 : chunk, q, h;
        vbg_cov_launch_sizes(s, t, nk, &q, &h);
        size_t need[5] = {nk * 4, nk * 4, nk * sizeof(vbq_cell_out), 16 * q, 4 * h};
        vbg_buf *b[5] = {&s->cells, &s->roots, &s->outs, &s->qout, &s->hand};
        for (int i = 0; i < 5; i++) {
            size_t nd = need[i] ? need[i] : 16;
            if (i < 4 || h)
                b[i]->size = b[i]->size > nd ? b[i]->size : nd;
        }
    }
}

/* The pool's arrays grown (as vbg_cov_tier_bind does) for w slices of t. */
static void plan_grow(cov_state *s, const cov_tier *t, size_t w)
{
    size_t a[COV_ARRAYS];
    vbg_cov_tier_arrays(t, w, a);
    for (int k = 0; k < COV_ARRAYS; k++)
        s->arr[k].size = s->arr[k].size > a[k] ? s->arr[k].size : a[k];
}

size_t vbg_cov_peak_plan(cov_state *s, size_t n, size_t input, size_t batch, size_t big_tasks,
                         size_t huge_tasks)
{
    if (vbg_cov_split(s, n, input))
        return 0;
    s->qout_cap = 0;
    s->hand_want = 0;
    memset(s->arr, 0, sizeof s->arr);
    cov_tier *t0 = &s->tier[COV_FIRST], *t1 = &s->tier[COV_BIG], *t3 = &s->tier[COV_HUGE];
    plan_grow(s, t0, t0->slices);
    plan_launches(s, t0, batch);
    size_t w1 = big_tasks && t1->want ? vbg_cov_tier_slices(s, t1, big_tasks) : 0;
    if (w1) {
        plan_grow(s, t1, w1);
        plan_launches(s, t1, big_tasks);
    }
    size_t w3 = w1 && huge_tasks && t3->want ? vbg_cov_tier_slices(s, t3, huge_tasks) : 0;
    if (w3) {
        plan_grow(s, t3, w3);
        plan_launches(s, t3, huge_tasks);
    }
    size_t pool = 0;
    for (int k = 0; k < COV_ARRAYS; k++)
        pool += s->arr[k].size;
    return input + pool + s->cells.size + s->roots.size + s->outs.size + s->qout.size +
           s->hand.size;
}

int vbg_cov_fit_wanted(const cov_state *s, size_t n)
{
    const cov_tier *t0 = &s->tier[COV_FIRST];
    if (!s->fit || !t0->wg || n < COV_FIT_SPHERES)
        return 0;
    size_t cps = s->cells_per_slice ? s->cells_per_slice : 1;
    size_t w = (n + cps - 1) / cps;
    w = w < t0->want ? w : t0->want;
    cov_tier d = *t0;
    d.nb_cap = t0->nb_want;
    d.lab_cap = t0->lab_want;
    d.q_cap = COV_WG_Q;
    return w * slice_bytes(&d) >= COV_FIT_MIN;
}

void vbg_cov_fit(cov_state *s, size_t n, size_t covered, size_t over)
{
    cov_tier *t0 = &s->tier[COV_FIRST];
    s->fitted = covered > 0 && over * COV_FIT_SHARE < covered ? COV_FITTED_SAMPLE
                : n < COV_FIT_SMALL                            ? COV_FITTED_SMALL
                                                               : COV_FITTED_NONE;
    t0->nb_cap = s->fitted ? COV_FIT_NB : t0->nb_want;
    t0->lab_cap = s->fitted == COV_FITTED_SAMPLE ? COV_FIT_LAB
                  : s->fitted                    ? COV_FIT_SMALL_LAB
                                                 : t0->lab_want;
    t0->q_cap = s->fitted ? COV_FIT_Q : COV_WG_Q;
}

void vbg_cov_caps(cov_state *s, int cpu, int caches, int hand, size_t units)
{
    cov_tier *t0 = &s->tier[COV_FIRST], *t1 = &s->tier[COV_BIG], *th = &s->tier[COV_HAND];
    cov_tier *t3 = &s->tier[COV_HUGE];
    t0->nb_cap = s->wg ? COV_WG_NB : cpu ? COV_CPU_NB : COV_NB;
    t0->lab_cap = s->wg ? COV_WG_LAB : cpu ? COV_CPU_LAB : COV_LAB;
    t0->st_cap = COV_ST;
    t0->q_cap = s->wg ? COV_WG_Q : COV_Q;
    t1->nb_cap = COV_BIG_NB;
    t1->lab_cap = COV_BIG_LAB;
    t1->st_cap = COV_ST;
    t1->q_cap = COV_BIG_Q;
    t3->nb_cap = COV_HUGE_NB;
    t3->lab_cap = COV_HUGE_LAB;
    t3->st_cap = COV_ST;
    t3->q_cap = COV_BIG_Q;
    /* The hand-off tier's work-items get the group kernel's first-tier
     * arenas as they were until stop 54 (8,192 records, 32,768 labels, 512
     * quadruples): a task of a cell past the budget then fits (fcc 10,976
     * jittered, simulated on the host: all 5,760 tasks of its 60 cells fit
     * them; with the work-item kernel's own arenas 66 of them ran out). */
    th->nb_cap = COV_WG_NB;
    th->lab_cap = COV_HANDOFF_LAB;
    th->st_cap = COV_ST;
    th->q_cap = COV_HANDOFF_Q;
    /* Output room per task: about 10 quadruples per cell on proteins; the
     * second tier's cells are the large ones. */
    t0->qper = th->qper = 24u;
    s->task_split = COV_TASK_SPLIT;
    s->task_order = 1;
    vbg_cov_big_qper(s, COV_BIG_QPER);
    t0->wg = t1->wg = t3->wg = s->wg;
    /* The caches on the first tier only: a CPU device's large tiers (test
     * knobs alone make them) keep their slices' size. */
    s->k_caches = t0->caches = caches;
    /* A CPU device's work-item kernel hands a patch it does not decide to
     * the host (VBQ_HANDOFF, core/cells/vbq_gather_shared.h): the host then
     * covers that patch, not the whole cell again; so does the group
     * kernel (hand). A GPU's first launch has up to 2^18 cells (the
     * 211,440-atom tiling in one), mostly protein cells that hand none: a
     * quarter of a CPU device's room a cell, grown as a launch asks. */
    s->k_hand = (cpu && !s->wg) || hand;
    s->hand_cell_words = s->wg ? COV_HAND_WORDS / 8 : COV_HAND_WORDS;
    s->hand_cap_words = COV_HAND_CAP;
    s->hand_floor_words = COV_HAND_FLOOR;
    s->cells_per_slice = s->wg ? COV_CELLS_PER_SLICE : 1;
    s->pool_per_sphere = COV_POOL_PER_SPHERE;
    /* Slices wanted: as many as keep the device busy; each run makes as
     * many of them as its cells use and its budget holds (vbg_cov_split,
     * vbg_cov_tier_slices). A CPU device gets no large tier (its cells are
     * as cheap on the host). */
    size_t want = s->wg ? units * 16 : !cpu ? units * 512 : units;
    /* Work-items come in groups of 64 (cov_run), on a CPU device alone
     * (vbg_cover_state.h, COV_CPU_NB). */
    t0->solo = cpu && !s->wg;
    if (!s->wg && !t0->solo && want >= 64)
        want = want / 64 * 64;
    t0->want = want;
    if (s->wg) {
        t1->want = units * 4;
        /* Measured on an H100 (the 211,440-atom tiling): when the tier
         * reran whole cells (stop 43, run C) 4x the compute units gave 1.76 s
         * of cover and certification, 2x 1.84 s; rerunning only the tasks
         * that ran out (864 of them), 2x and 4x both take 0.25 s of huge-tier
         * kernel and 1.29 s of device cover, and 2x holds 4.0 GB of device
         * buffers at the peak against 6.0 GB (stop 44, run A). */
        t3->want = units * 2;
        /* The hand-off tier: work-items as for the work-item kernel on a
         * GPU, in groups of 64. */
        th->want = units * 512;
    }
    t0->nb_want = t0->nb_cap;
    t0->lab_want = t0->lab_cap;
    /* The group kernel's first tier follows the input (COV_FIT_SAMPLE). */
    s->fit = s->wg;
    s->fitted = 0;
}
