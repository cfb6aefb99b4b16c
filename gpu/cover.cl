/* The direction cover on OpenCL: one work-item covers one cell at a time
 * with vbq_cover_cell (core/cells/vb_cover_shared.h, the same code the host
 * runs), taking cells from a shared counter so that cheap buried cells and
 * costly exposed ones balance. Each work-item owns a slice of the arenas. A
 * cell whose arena or the output ran out is marked and covered again on
 * the host; quadruples go to one output array in any order (the host
 * sorts them). */
#pragma OPENCL FP_CONTRACT OFF

#include "vb_cover_shared.h"

/* A cell whose quadruples did not fit the output array. */
#define VBQ_OVER_OUT 5u

__kernel void vbq_cover_kernel(__global const double *x, __global const double *y,
                               __global const double *z, __global const double *r,
                               __global const double *box, __global const double *rmax,
                               __global const uint *ids, const uint first, const uint m,
                               const double rmax_all, const double near, const double tmax,
                               const uint T,
                               const uint min_level, const uint max_level, const uint enum_max,
                               __global const uint *cells, __global const uint *roots,
                               const uint ncells,
                               __global vbq_nb *nb, __global uint *lab, __global vbq_frame *st,
                               __global uint *q, const uint nb_cap, const uint lab_cap,
                               const uint st_cap, const uint q_cap,
                               __global vbq_cell_out *outs, __global uint *qout,
                               const uint qout_cap, __global uint *counters
#ifdef VBQ_CACHES_CL
                               ,
                               __global double *hi, __global vbq_nb *memo, __global uint *memo_tag
#endif
#ifdef VBQ_HANDOFF
                               ,
                               __global uint *hand, const uint hand_cap
#endif
                               )
{
    size_t w = get_global_id(0);
    vbq_env e;
    vbq_env_make(&e, x, y, z, r, box, rmax, ids, first, m, rmax_all, near, tmax, T, min_level,
                 max_level, enum_max);
    vbq_arena ar;
    ar.nb = nb + w * (size_t)nb_cap;
    ar.lab = lab + w * (size_t)lab_cap;
    ar.st = st + w * (size_t)st_cap;
    ar.q = q + w * 4u * (size_t)q_cap;
    ar.nb_cap = nb_cap;
    ar.lab_cap = lab_cap;
    ar.st_cap = st_cap;
    ar.q_cap = q_cap;
#ifdef VBQ_CACHES_CL
    /* The caches of a CPU device (vbq_gather_shared.h, VBQ_CACHES): a
     * work-item's memo starts empty in every launch (a later run may bring
     * other spheres), cleared when it takes its first cell. */
    ar.hi = hi ? hi + w * (size_t)lab_cap : 0; /* NULL: a tier without caches */
    ar.memo = memo ? memo + w * (size_t)VBQ_MEMO : 0;
    ar.memo_tag = memo ? memo_tag + w * 2u * (size_t)VBQ_MEMO : 0;
    int fresh = memo != 0;
#endif
#ifdef VBQ_HANDOFF
    /* A CPU device's handed patches (vbq_hand_patch; NULL: hand cells):
     * counters[2] the words taken, counters[3] those written. */
    ar.hand = hand;
    ar.hand_used = counters + 2;
    ar.hand_cap = hand_cap;
#endif
    for (;;) {
        uint c = atomic_inc(&counters[0]);
        if (c >= ncells)
            break;
#ifdef VBQ_CACHES_CL
        if (fresh) {
            for (uint s = 0u; s < 2u * VBQ_MEMO; s++)
                ar.memo_tag[s] = 0u;
            fresh = 0;
        }
#endif
        vbq_cell_out o;
#ifdef VBQ_HANDOFF
        ar.hand_cell = c;
#endif
        vbq_cover_cell(&e, &ar, cells[c], roots[c], &o);
        if (o.status == VBQ_OK && o.nq > 0u) {
            uint base = atomic_add(&counters[1], o.nq);
            if (base + o.nq <= qout_cap) {
                for (uint k = 0u; k < 4u * o.nq; k++)
                    qout[4u * (size_t)base + k] = ar.q[k];
                o.qoff = base;
            } else {
                o.status = VBQ_OVER_OUT;
            }
        }
        outs[c] = o;
    }
}
