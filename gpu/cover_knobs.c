/* The cover backend's knobs for tests and measurements (vbg_cover_state.h):
 * environment variables that change its arenas' capacities and slices. The
 * output never depends on them; what runs where does. */
#include <stdlib.h>

#include "vbg_cover_state.h"

/* A positive (or, with zero_ok, non-negative) count from the environment
 * variable `name`, else -1. */
static long knob(const char *name, int zero_ok)
{
    const char *v = getenv(name);
    long n = v ? atol(v) : -1;
    return v && (n > 0 || (zero_ok && n == 0)) ? n : -1;
}

void vbg_cover_knobs(cov_state *s)
{
    cov_tier *t0 = &s->tier[COV_FIRST], *t1 = &s->tier[COV_BIG], *t3 = &s->tier[COV_HUGE];
    long v;
    /* VORBALL_COVER_NB and VORBALL_COVER_LAB: the first tier's records and
     * labels (so that cells overflow; or smaller slices for measurements of
     * memory against speed). */
    if ((v = knob("VORBALL_COVER_NB", 0)) > 0)
        t0->nb_cap = (uint32_t)v;
    if ((v = knob("VORBALL_COVER_LAB", 0)) > 0)
        t0->lab_cap = (uint32_t)v;
    /* The first tier's arenas follow the input (vbg_cov_fit) unless a knob
     * sets them or VORBALL_COVER_FIT=0 (measurements: the defaults always). */
    if (knob("VORBALL_COVER_NB", 0) > 0 || knob("VORBALL_COVER_LAB", 0) > 0)
        s->fit = 0;
    if (knob("VORBALL_COVER_FIT", 1) == 0)
        s->fit = 0;
    /* VORBALL_COVER_TIER2 and VORBALL_COVER_TIER3: the large and huge tiers'
     * slices, also on CPU devices (to test the split into root-patch tasks
     * and the huge tier's retry; 0: none). */
    if ((v = knob("VORBALL_COVER_TIER2", 1)) >= 0)
        t1->want = (size_t)v;
    if ((v = knob("VORBALL_COVER_TIER3", 1)) >= 0)
        t3->want = (size_t)v;
    /* VORBALL_COVER_BIG_NB and VORBALL_COVER_HUGE_NB: the large and huge
     * tiers' records per slice. */
    if ((v = knob("VORBALL_COVER_BIG_NB", 0)) > 0)
        t1->nb_cap = (uint32_t)v;
    if ((v = knob("VORBALL_COVER_HUGE_NB", 0)) > 0)
        t3->nb_cap = (uint32_t)v;
    /* VORBALL_COVER_HAND_WORDS: words of handed patches a cell gets in the
     * first launch (so that cells find no room and the first tier runs
     * again for them: rerun_hand_short, counted in the reruns' clocks). */
    if ((v = knob("VORBALL_COVER_HAND_WORDS", 0)) > 0) {
        s->hand_cell_words = (uint32_t)v;
        s->hand_floor_words = 0; /* the cells' room is the knob's alone */
    }
    /* Device memory against speed (vbg_cover_state.h, measurements):
     * VORBALL_COVER_CELLS_PER_SLICE, the group kernel's first tier's
     * spheres a slice; VORBALL_COVER_POOL_PER_SPHERE, the pool's bytes a
     * sphere (0: the budget alone bounds it); VORBALL_COVER_HAND_CAP, the
     * handed-patch words a launch reserves at most; VORBALL_COVER_BIG_QPER,
     * the large and huge tiers' output room a task. */
    if ((v = knob("VORBALL_COVER_CELLS_PER_SLICE", 0)) > 0)
        s->cells_per_slice = (size_t)v;
    if ((v = knob("VORBALL_COVER_POOL_PER_SPHERE", 1)) >= 0)
        s->pool_per_sphere = (size_t)v;
    if ((v = knob("VORBALL_COVER_HAND_CAP", 0)) > 0)
        s->hand_cap_words = (size_t)v;
    /* VORBALL_COVER_TASK_SPLIT: 1 or 2, the levels below the roots a
     * cell's tasks split at (COV_TASK_SPLIT; the output room follows). */
    if ((v = knob("VORBALL_COVER_TASK_SPLIT", 0)) == 1 || v == 2) {
        s->task_split = (unsigned)v;
        vbg_cov_big_qper(s, COV_BIG_QPER);
    }
    /* VORBALL_COVER_TASK_ORDER=0: a tier's tasks in cell order; =2
     * costliest first at any size (vbg_tasks_ordered; measurements). */
    if ((v = knob("VORBALL_COVER_TASK_ORDER", 1)) == 0 || v == 2)
        s->task_order = (int)v;
    if ((v = knob("VORBALL_COVER_BIG_QPER", 0)) > 0)
        t1->qper = t3->qper = (uint32_t)v;
}
