/* The GPU kernel of the direction cover (gpu/cover_wg.cl), run as C on
 * threads that stand for the lanes of one work-group: barriers are a
 * pthread barrier, the group's shared variables static, atomics GCC's. So
 * the group kernel's logic (its barriers and shared state included) is
 * tested on machines without a GPU, where PoCL cannot run it. Four lanes
 * instead of 32: the kernel's loops stride by the group size, so every
 * power of two makes the same decisions, and four threads keep the test
 * quick on two cores. Built with VBQ_HANDOFF, as the driver builds it for a
 * GPU (gpu/cover_ocl.c): with no hand buffer it hands whole cells, as
 * VORBALL_COVER_GPU_HAND=0 does. */
/* The kernel's hand-off (vbq_hand_patch, with GCC's atomics) before the
 * shared header is first read (cover_wg_emu.h includes it). */
#define VBQ_HANDOFF 1
#define atomic_add(p, v) __atomic_fetch_add((p), (v), __ATOMIC_SEQ_CST)
#include "cover_wg_emu.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static pthread_barrier_t emu_barrier;
static __thread unsigned emu_lane;

#define __kernel
#define __global
#define __local
#define WG_SHARED static
#define WG 4u
#define __attribute__(x)
#define inline
#define get_local_id(d) emu_lane
#define get_group_id(d) 0
#define barrier(f) pthread_barrier_wait(&emu_barrier)
#define CLK_LOCAL_MEM_FENCE 1
#define CLK_GLOBAL_MEM_FENCE 2
#define atomic_inc(p) __atomic_fetch_add((p), 1u, __ATOMIC_SEQ_CST)
typedef unsigned int uint;
#include VB_COVER_WG_CL
#undef inline
#undef __attribute__

typedef struct lane_arg {
    unsigned lane;
    const vbq_env *e;
    const uint32_t *cells, *roots;
    uint32_t ncells, budget;
    vbq_nb *nb;
    uint32_t *lab, *q, *qout, *counters, qout_cap;
    vbq_frame *st;
    vbq_cell_out *outs;
    uint32_t *hand, hand_cap;
} lane_arg;

static void *lane_main(void *p)
{
    lane_arg *a = p;
    emu_lane = a->lane;
    const vbq_env *e = a->e;
    vbq_cover_wg(e->x, e->y, e->z, e->r, e->box, e->rmax, e->ids, e->first, e->m, e->rmax_all,
                 e->near, e->tmax, e->T, e->min_level, e->max_level, e->enum_max, a->cells, a->roots,
                 a->ncells, a->nb, a->lab, a->st, a->q, EMU_NB, EMU_LAB, 1, EMU_Q, a->outs,
                 a->qout, a->qout_cap, a->counters, a->budget, a->hand, a->hand_cap);
    return NULL;
}

int vb_cover_wg_emulate(const vbq_env *e, const uint32_t *cells, const uint32_t *roots,
                        uint32_t ncells, uint32_t budget, vbq_cell_out *outs, uint32_t *qout,
                        uint32_t qout_cap, uint32_t *nquads, uint32_t *hand, uint32_t hand_cap,
                        uint32_t hand_words[2])
{
    vbq_nb *nb = malloc((size_t)EMU_NB * sizeof *nb);
    uint32_t *lab = malloc((size_t)EMU_LAB * sizeof *lab);
    uint32_t *q = malloc(4 * (size_t)EMU_Q * sizeof *q);
    vbq_frame st[1];
    uint32_t counters[4] = {0, 0, 0, 0};
    int rc = nb && lab && q && pthread_barrier_init(&emu_barrier, NULL, WG) == 0 ? 0 : -1;
    pthread_t th[WG];
    lane_arg a[WG];
    int started = 0;
    for (unsigned l = 0; rc == 0 && l < WG; l++) {
        a[l] = (lane_arg){l,   e,    cells,    roots,    ncells, budget, nb,      lab,
                          q,   qout, counters, qout_cap, st,     outs,   hand, hand_cap};
        if (pthread_create(&th[l], NULL, lane_main, &a[l]) != 0) {
            rc = -1; /* a barrier of WG cannot complete: abandon (test fails) */
            break;
        }
        started++;
    }
    for (int l = 0; l < started && rc == 0; l++)
        pthread_join(th[l], NULL);
    if (rc == 0)
        pthread_barrier_destroy(&emu_barrier);
    free(nb);
    free(lab);
    free(q);
    *nquads = counters[1];
    hand_words[0] = counters[2];
    hand_words[1] = counters[3];
    return rc;
}
