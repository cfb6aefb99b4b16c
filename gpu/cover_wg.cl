/* The direction cover on OpenCL with one work-group per cell (GPUs); the
 * work-item kernel beside it (cover.cl) serves CPU devices. */
#pragma OPENCL FP_CONTRACT OFF

/* The parts of a fetching patch live in the group's local memory; the
 * work-item versions of the shared code (for private parts) are left out. */
#ifndef VBQ_SQ
#define VBQ_SQ __local
#endif
#define VBQ_GROUP_ONLY
/* Combination dominance's champions: one set per group in local memory,
 * made by lane 0, read by every lane (not 488 private bytes per lane). */
#ifndef VBQ_CH
#define VBQ_CH __local
#endif
#include "vb_cover_shared.h"

/* A cell whose quadruples did not fit the output array. */
#define VBQ_OVER_OUT 5u

/* ---- the cover with one work-group per cell (GPUs) ----------------------
 * The same decisions as vbq_cover_cell, made once per patch by the group:
 * the lanes evaluate a patch's labels side by side (reading the list and
 * the records together), reduce LO, compact the survivors, and walk the
 * tree breadth-first for the near list and the ring fetches. Lists and
 * records live in the group's arena slice (global memory); the frame stack,
 * the node stack and the scalars in local memory. Labels land in the lists
 * in any order, which changes no decision (every one depends on the set). */

/* Lanes of a group: 32 on GPUs (one warp); any power of two gives the same
 * result (the emulation in tests/gpu runs 4). */
#ifndef WG
#define WG 32u
#endif
/* The group's shared variables; tests/gpu/cover_wg_emu.c runs this file as C
 * on 32 threads, with them static. */
#ifndef WG_SHARED
#define WG_SHARED __local
#endif
#define WG_ST 192u /* frames: 3 per level to VB_COVER_MAX_LEVEL 48, and the roots */
#define WG_NODES 1024u

/* Shared scalars of a group (indices into sh[]). */
#define S_CELL 0
#define S_NST 1
#define S_NS 2
#define S_NNB 3
#define S_LEN 4
#define S_OWNED 5
#define S_STATUS 6
#define S_TOP 7
#define S_FAR 8
#define S_N 9

/* The tree walk (vbq_walk_node, vbq_walk_sphere) on the group, breadth
 * first: the lanes take the nodes at the top of the shared stack side by
 * side. Passing spheres are appended to nb (shared count sh[S_NNB]) and to
 * lab[off + sh[S_LEN] ...]; those of a ring fetched through parts count as
 * far. Every lane calls it; on return sh[S_STATUS] says whether an arena or
 * the node stack ran out. */
static inline __attribute__((always_inline)) void
wg_walk(const vbq_env *e, const vbq_walk *w, __global vbq_nb *nb, uint nb_cap,
        __global uint *lab, uint lab_cap, uint off, __local uint *sh, __local uint *nodes)
{
    uint lane = get_local_id(0);
    if (lane == 0u) {
        sh[S_NS] = e->m ? 1u : 0u;
        nodes[0] = 1u;
    }
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    for (;;) {
        uint n = sh[S_NS];
        if (n == 0u || sh[S_STATUS] != VBQ_OK)
            break;
        uint take = n < WG ? n : WG;
        uint nd = lane < take ? nodes[n - 1u - lane] : 0u;
        barrier(CLK_LOCAL_MEM_FENCE);
        if (lane == 0u)
            sh[S_NS] = n - take;
        barrier(CLK_LOCAL_MEM_FENCE);
        if (nd != 0u && vbq_walk_node(e, w, nd)) {
            if (nd < e->first) {
                uint k = atomic_add(&sh[S_NS], 2u);
                if (k + 2u <= WG_NODES) {
                    nodes[k] = 2u * nd;
                    nodes[k + 1u] = 2u * nd + 1u;
                } else {
                    sh[S_STATUS] = VBQ_OVER_ST;
                }
            } else {
                uint k0, k1;
                vbq_walk_leaf(e, nd, &k0, &k1);
                for (uint k = k0; k < k1; k++) {
                    vbq_nb rec;
                    if (!vbq_walk_sphere(e, w, k, &rec))
                        continue;
                    if (w->nsub)
                        atomic_inc(&sh[S_FAR]);
                    uint idx = atomic_inc(&sh[S_NNB]);
                    uint pos = atomic_inc(&sh[S_LEN]);
                    if (idx >= nb_cap)
                        sh[S_STATUS] = VBQ_OVER_NB;
                    else if (off + pos >= lab_cap)
                        sh[S_STATUS] = VBQ_OVER_LAB;
                    else {
                        nb[idx] = rec;
                        lab[off + pos] = idx;
                    }
                }
            }
        }
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    }
    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
}

/* Largest of the lanes' values v (every lane gets it). */
static inline __attribute__((always_inline)) double wg_max(double v, __local double *red)
{
    uint lane = get_local_id(0);
    red[lane] = v;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint s = WG / 2u; s > 0u; s >>= 1) {
        if (lane < s && red[lane + s] > red[lane])
            red[lane] = red[lane + s];
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    double r = red[0];
    barrier(CLK_LOCAL_MEM_FENCE);
    return r;
}

/* Lane 0's compaction after a dominance pass: the labels lab[0..keep) the
 * pass did not drop (with use_dom, dom[a] == 0; else the label's top bit
 * clear) moved to the front in order, their count and owned count (ids
 * above i) into sh[S_LEN] and sh[S_OWNED]. */
static inline __attribute__((always_inline)) void
wg_keep_undropped(__global uint *lab, uint keep, int use_dom, __local const uint *dom,
                  __global const vbq_nb *nb, uint i, __local uint *sh)
{
    uint w = 0u, ow = 0u;
    for (uint a = 0u; a < keep; a++) {
        uint li = lab[a];
        if (use_dom ? dom[a] != 0u : (li & 0x80000000u) != 0u)
            continue;
        lab[w++] = li;
        if (nb[li].id > i)
            ow++;
    }
    sh[S_LEN] = w;
    sh[S_OWNED] = ow;
}

/* Lane 0 hands the undecided patch fr (vbq_hand_patch): 1 when written,
 * 0 when the cell goes whole to the host (VBQ_CLUSTER). */
static inline __attribute__((always_inline)) int wg_hand(const vbq_arena *ar, vbq_cell_out *o,
                                                         const vbq_frame *fr)
{
#ifdef VBQ_HANDOFF
    return vbq_hand_patch(ar, o, fr);
#else
    (void)ar;
    (void)o;
    (void)fr;
    return 0;
#endif
}

__kernel __attribute__((reqd_work_group_size(WG, 1, 1)))
void vbq_cover_wg(__global const double *x, __global const double *y, __global const double *z,
                  __global const double *r, __global const double *box,
                  __global const double *rmax, __global const uint *ids, const uint first,
                  const uint m, const double rmax_all, const double near, const double tmax,
                  const uint T,
                  const uint min_level, const uint max_level, const uint enum_max,
                  __global const uint *cells, __global const uint *roots, const uint ncells,
                  __global vbq_nb *nbs,
                  __global uint *labs, __global vbq_frame *unused_st, __global uint *qs,
                  const uint nb_cap, const uint lab_cap, const uint st_cap, const uint q_cap,
                  __global vbq_cell_out *outs, __global uint *qout, const uint qout_cap,
                  __global uint *counters, const uint budget
#ifdef VBQ_HANDOFF
                  ,
                  __global uint *hand, const uint hand_cap
#endif
                  )
{
    WG_SHARED vbq_frame stk[WG_ST];
    WG_SHARED uint nodes[WG_NODES];
    WG_SHARED double red[WG];
    WG_SHARED uint sh[S_N];
    WG_SHARED uint dom[VBQ_DOM_MAX];
    WG_SHARED vbq_frame cur;
    WG_SHARED vbq_champ chs;
    WG_SHARED vbq_sub subs[VBQ_NSUB];
    uint lane = get_local_id(0);
    size_t g = get_group_id(0);
    vbq_env e;
    vbq_env_make(&e, x, y, z, r, box, rmax, ids, first, m, rmax_all, near, tmax, T, min_level,
                 max_level, enum_max);
    __global vbq_nb *nb = nbs + g * (size_t)nb_cap;
    __global uint *lab = labs + g * (size_t)lab_cap;
    __global uint *qa = qs + g * 4u * (size_t)q_cap;
    vbq_arena ar;
    ar.nb = nb;
    ar.lab = lab;
    ar.st = unused_st;
    ar.q = qa;
    ar.nb_cap = nb_cap;
    ar.lab_cap = lab_cap;
    ar.st_cap = st_cap;
    ar.q_cap = q_cap;
#ifdef VBQ_HANDOFF
    /* The handed patches (vbq_hand_patch, lane 0; NULL: hand cells), as
     * the work-item kernel's: counters[2] the words taken, counters[3]
     * those written. */
    ar.hand = hand;
    ar.hand_used = counters + 2;
    ar.hand_cap = hand_cap;
#endif
    for (;;) {
        if (lane == 0u)
            sh[S_CELL] = atomic_inc(&counters[0]);
        barrier(CLK_LOCAL_MEM_FENCE);
        uint c = sh[S_CELL];
        barrier(CLK_LOCAL_MEM_FENCE);
        if (c >= ncells)
            break;
        uint i = cells[c];
#ifdef VBQ_HANDOFF
        ar.hand_cell = c;
#endif
        vbq_cell_out o;   /* lane 0's counters */
        o.status = VBQ_OK;
        o.nq = o.nnb = o.far = 0u;
        o.patches = o.evals_k = o.leaves = o.deep = o.maxlev = 0u;
        o.lab_hw = o.st_hw = o.qoff = 0u;
        double evals = 0.0;
        if (lane == 0u) {
            sh[S_NNB] = 0u;
            sh[S_LEN] = 0u;
            sh[S_STATUS] = VBQ_OK;
            sh[S_FAR] = 0u;
        }
        barrier(CLK_LOCAL_MEM_FENCE);
        const double ci[3] = {x[i], y[i], z[i]};
        double rq = near + 2.0 * rmax_all;
        vbq_walk wk;
        vbq_walk_make(&e, i, -1.0, rq, 0, 0u, &wk);
        wg_walk(&e, &wk, nb, nb_cap, lab, lab_cap, 0u, sh, nodes);
        uint len0 = sh[S_LEN];
        double far = sqrt(vbq_box_far2(&e, 1u, ci)) * (1.0 + 1e-9);
        double slack_i = rmax_all - r[i], floor_i = vbq_floor(&e, i);
        uint nroot = 6u * T * T;
        if (nroot > WG_ST && lane == 0u)
            sh[S_STATUS] = VBQ_OVER_ST;
        if (lane == 0u && sh[S_STATUS] == VBQ_OK) {
            uint rt = roots[c], n0 = 0u;
            for (uint k = 0u; k < nroot; k++)
                if (vbq_task_root(rt, k))
                    stk[n0++] = vbq_root(T, k, len0, rq, far);
            sh[S_NST] = n0;
            sh[S_TOP] = len0;
        }
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
        /* Steps (patches popped) of this cell: the same count in every lane,
         * so that all of them leave together when it passes the budget. */
        uint steps = 0u, max_steps = budget & ~VBQ_BUDGET_HAND;
        for (;;) {
            /* Every lane reads the condition before lane 0 pops. */
            int go = sh[S_STATUS] == VBQ_OK && sh[S_NST] > 0u;
            barrier(CLK_LOCAL_MEM_FENCE);
            if (!go)
                break;
            /* A long chain of levels walked one patch at a time idles the
             * chip: past the budget (0: none) the cell hands the patches left
             * on its stack to the host and keeps what it did (the budget's
             * VBQ_BUDGET_HAND bit, lane 0: unpopped frames, each with its
             * list below the stack's top, counted when the host pops them),
             * else it is left, none of it kept, to the host or the
             * work-item kernel (VBQ_BUDGET, cover_ocl.c). */
            if (max_steps != 0u && ++steps > max_steps) {
                if (lane == 0u) {
                    uint left = (budget & VBQ_BUDGET_HAND) ? sh[S_NST] : 0u, k = 0u;
                    for (; k < left; k++) {
                        vbq_frame f = stk[k]; /* a private copy: OpenCL 1.2 has no generic pointers */
                        o.patches++;          /* vbq_hand_patch uncounts a popped patch */
                        if (!wg_hand(&ar, &o, &f))
                            break;
                    }
                    sh[S_STATUS] = left != 0u && k == left ? VBQ_OK : VBQ_BUDGET;
                    sh[S_NST] = 0u;
                }
                barrier(CLK_LOCAL_MEM_FENCE);
                break;
            }
            if (lane == 0u) {
                uint nst = sh[S_NST], top = sh[S_TOP];
                o.st_hw = nst > o.st_hw ? nst : o.st_hw;
                o.lab_hw = top > o.lab_hw ? top : o.lab_hw;
                cur = stk[nst - 1u];
                sh[S_NST] = nst - 1u;
                if (cur.off + cur.len < top)
                    sh[S_TOP] = cur.off + cur.len > len0 ? cur.off + cur.len : len0;
                o.patches++;
            }
            barrier(CLK_LOCAL_MEM_FENCE);
            vbq_frame fr = cur;
            uint top = sh[S_TOP];
            double u0, u1, v0, v1, mm[3], hh[3];
            vbq_patch_square(T, fr.level, fr.iu, fr.iv, &u0, &u1, &v0, &v1);
            vbq_patch_box(fr.f, u0, u1, v0, v1, mm, hh);
            double lmax = floor_i;
            for (uint k = lane; k < fr.len; k += WG) {
                vbq_nb rec = nb[lab[fr.off + k]];
                double lo, hi;
                vbq_eval(&rec, mm, hh, &lo, &hi);
                lmax = lo > lmax ? lo : lmax;
            }
            double LO = wg_max(lmax, red);
            evals += (double)fr.len;
            int closed = vbq_closed(fr.rq, LO, slack_i);
            if (!closed && fr.level >= VBQ_FETCH_LEVEL + vbq_near_tie(LO, far)) {
                double rq1 = vbq_ring_radius(fr.rq, LO, slack_i, far);
                if (top + fr.len > lab_cap) {
                    if (lane == 0u)
                        sh[S_STATUS] = VBQ_OVER_LAB;
                    barrier(CLK_LOCAL_MEM_FENCE);
                    break;
                }
                for (uint k = lane; k < fr.len; k += WG)
                    lab[top + k] = lab[fr.off + k];
                if (lane == 0u)
                    sh[S_LEN] = fr.len;
                barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                /* The parts' lower envelopes: each lane's maxima, then one
                 * reduction per part. */
                double lg[VBQ_NSUB];
                for (uint g = 0u; g < VBQ_NSUB; g++)
                    lg[g] = floor_i;
                for (uint g = lane; g < VBQ_NSUB; g += WG) {
                    double sm[3], sh3[3];
                    vbq_sub_box(fr.f, u0, u1, v0, v1, g, sm, sh3);
                    for (int a = 0; a < 3; a++) {
                        subs[g].m[a] = sm[a];
                        subs[g].h[a] = sh3[a];
                    }
                }
                barrier(CLK_LOCAL_MEM_FENCE);
                for (uint k = lane; k < fr.len; k += WG) {
                    vbq_nb rec = nb[lab[fr.off + k]];
                    for (uint g = 0u; g < VBQ_NSUB; g++) {
                        double sm[3] = {subs[g].m[0], subs[g].m[1], subs[g].m[2]};
                        double sh3[3] = {subs[g].h[0], subs[g].h[1], subs[g].h[2]};
                        double lo, hi;
                        vbq_eval(&rec, sm, sh3, &lo, &hi);
                        lg[g] = lo > lg[g] ? lo : lg[g];
                    }
                }
                for (uint g = 0u; g < VBQ_NSUB; g++) {
                    double v = wg_max(lg[g], red);
                    if (lane == 0u)
                        vbq_sub_set_lo(&subs[g], v);
                }
                barrier(CLK_LOCAL_MEM_FENCE);
                evals += (double)(VBQ_NSUB * fr.len);
                vbq_walk_make(&e, i, fr.rq, rq1, subs, VBQ_NSUB, &wk);
                wg_walk(&e, &wk, nb, nb_cap, lab, lab_cap, top, sh, nodes);
                if (lane == 0u && sh[S_STATUS] == VBQ_OK) {
                    uint nlen = sh[S_LEN];
                    fr.off = top;
                    fr.len = nlen;
                    fr.rq = rq1;
                    sh[S_TOP] = top + nlen;
                    uint nst = sh[S_NST];
                    if (nst >= WG_ST)
                        sh[S_STATUS] = VBQ_OVER_ST;
                    else {
                        stk[nst] = fr;
                        sh[S_NST] = nst + 1u;
                    }
                    o.patches--;
                }
                barrier(CLK_LOCAL_MEM_FENCE);
                continue;
            }
            if (top + fr.len > lab_cap) {
                if (lane == 0u)
                    sh[S_STATUS] = VBQ_OVER_LAB;
                barrier(CLK_LOCAL_MEM_FENCE);
                break;
            }
            if (lane == 0u) {
                sh[S_LEN] = 0u;
                sh[S_OWNED] = 0u;
            }
            barrier(CLK_LOCAL_MEM_FENCE);
            double hm = -(double)INFINITY; /* this lane's largest hi (vbq_combo_may_go) */
            for (uint k = lane; k < fr.len; k += WG) {
                uint li = lab[fr.off + k];
                vbq_nb rec = nb[li];
                double lo, hi;
                vbq_eval(&rec, mm, hh, &lo, &hi);
                hm = hi > hm ? hi : hm;
                if (hi >= LO) {
                    uint pos = atomic_inc(&sh[S_LEN]);
                    lab[top + pos] = li;
                    if (rec.id > i)
                        atomic_inc(&sh[S_OWNED]);
                }
            }
            barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
            evals += (double)fr.len;
            uint keep = sh[S_LEN], owned = sh[S_OWNED];
            /* Combination dominance (vbq_combo_shared.h): lane 0 makes the
             * champions in local memory, every lane tests its labels and
             * marks the beaten ones (top bit: labels index nb, far below
             * 2^31), lane 0 compacts. */
            uint tried = vbq_combo_due(&fr, closed, keep, owned);
            uint list_tried = tried || ((fr.combo & VBQ_FR_COMBO) && keep == fr.len);
            uint round = tried ? 0u : VBQ_CHAMP_ROUNDS;
            /* tried is the same on every lane (fr, keep, owned are shared) */
            if (tried && !vbq_combo_may_go(LO, wg_max(hm, red)))
                round = VBQ_CHAMP_ROUNDS;
            /* every lane has left the last round's champions (barriers
             * since); only lane 0 writes them */
            if (lane == 0u) {
                chs.round = 0u;
                chs.n = 0u;
            }
            while (keep > VBQ_DOM_MAX && owned >= 3u && round < VBQ_CHAMP_ROUNDS) {
                if (lane == 0u) {
                    vbq_champ_make(nb, lab + top, keep, mm, hh, &chs);
                    chs.round++;
                }
                round++;
                /* the champions are made and lane 0 has read the list
                 * before any lane marks it */
                barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                if (!vbq_combo_go(&chs, LO))
                    break;
                for (uint a = lane; a < keep; a += WG) {
                    vbq_nb nj = nb[lab[top + a]];
                    if (vbq_combo_beaten(&chs, &nj, mm, hh, LO))
                        lab[top + a] |= 0x80000000u;
                }
                barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                evals += 2.0 * (double)keep;
                if (lane == 0u)
                    wg_keep_undropped(lab + top, keep, 0, dom, nb, i, sh);
                barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                /* a round that beat nothing ends them (as on the host) */
                int beat = sh[S_LEN] < keep;
                keep = sh[S_LEN];
                owned = sh[S_OWNED];
                if (!beat)
                    break;
            }
            if (closed && owned >= 3u && keep <= VBQ_DOM_MAX) {
                for (uint a = lane; a < keep; a += WG) {
                    vbq_nb nj = nb[lab[top + a]];
                    uint d = 0u;
                    for (uint b = 0u; b < keep && !d; b++) {
                        if (b == a)
                            continue;
                        vbq_nb nk = nb[lab[top + b]];
                        double dl, dh;
                        vbq_eval_diff(&nk, &nj, mm, hh, &dl, &dh);
                        d = dl > 0.0;
                    }
                    dom[a] = d;
                }
                barrier(CLK_LOCAL_MEM_FENCE);
                evals += (double)(keep * (keep - 1u));
                if (lane == 0u)
                    wg_keep_undropped(lab + top, keep, 1, dom, nb, i, sh);
                barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                keep = sh[S_LEN];
                owned = sh[S_OWNED];
            }
            int act = closed ? vbq_decide(&e, &fr, nb, lab + top, i, keep, owned) : 1;
            /* a tie cluster: the host decides it (vbq_cover_cell), the
             * patch alone where lane 0 hands it (fr is the frame popped,
             * its list lab[fr.off .. + fr.len) untouched since), else the
             * whole cell. Every lane leaves the patch (act 0); the status
             * lane 0 sets is read after the step's last barrier. */
            if (act != 0 && vbq_tie_cluster(nb, lab + top, keep, owned, i, act, closed)) {
                if (lane == 0u && !wg_hand(&ar, &o, &fr))
                    sh[S_STATUS] = VBQ_CLUSTER;
                act = 0;
            }
            /* a stalled near-tie chain: decided in doubles by lane 0, or by
             * the host where a sign needs its exact fallback */
            /* (as the work-item kernel, vbq_cover_cell) */
            if (vbq_envelope_due(&e, &fr, nb, lab + top, keep, owned, act, closed) &&
                (owned > VBQ_CLUSTER_OWNED || vbq_envelope_sure(&e, &ar, i, &fr, top, keep))) {
                if (lane == 0u && owned > VBQ_ENV_FILTER_OWNED) {
                    if (!wg_hand(&ar, &o, &fr))
                        sh[S_STATUS] = VBQ_CLUSTER;
                } else if (lane == 0u) {
                    int he = vbq_envelope_filter(&e, &ar, &o, i, &fr, top, keep);
                    /* what the filter added is the host's too (exact signs) */
                    if (he == 2 && !wg_hand(&ar, &o, &fr))
                        sh[S_STATUS] = VBQ_CLUSTER;
                    else if (he < 0)
                        sh[S_STATUS] = o.status;
                    else
                        o.leaves++;
                }
                act = 0;
            }
            if (lane == 0u && act >= 2 && !vbq_leaf_quads(&ar, &o, i, top, keep, act, fr.level))
                sh[S_STATUS] = o.status;
            if (lane == 0u && act == 1) {
                uint nst = sh[S_NST];
                if (nst + 4u > WG_ST) {
                    sh[S_STATUS] = VBQ_OVER_ST;
                } else {
                    uint rt = roots[c], nc = 0u;
                    for (uint k = 0u; k < 4u; k++) {
                        if (!vbq_task_child(rt, fr.level, k))
                            continue;
                        vbq_frame cf;
                        vbq_child(&fr, k, top, keep, list_tried, &cf);
                        stk[nst + nc++] = cf;
                    }
                    sh[S_NST] = nst + nc;
                    sh[S_TOP] = top + keep;
                }
            }
            barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
        }
        if (lane == 0u) {
            o.status = sh[S_STATUS];
            o.nnb = sh[S_NNB];
            o.far = sh[S_FAR];
            o.evals_k = (uint)(evals / 1000.0);
            if (o.status == VBQ_OK && o.nq > 0u) {
                uint base = atomic_add(&counters[1], o.nq);
                if (base + o.nq <= qout_cap) {
                    for (uint k = 0u; k < 4u * o.nq; k++)
                        qout[4u * (size_t)base + k] = qa[k];
                    o.qoff = base;
                } else {
                    o.status = VBQ_OVER_OUT;
                }
            }
            outs[c] = o;
        }
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
    }
}
