/* The exact tiled engine on OpenCL: one work-group per tile of S^d voxels,
 * one work-item per row of VBJ_XT_ROW voxels along x (64 work-items in 3D,
 * 32 in 2D). The decisions and their proofs are in
 * core/discrete/vbj_tiles.h; the plain-C twin, core/discrete/jfa_tiles.c,
 * runs the same search and tests, so labels and counts agree.
 *
 * Per tile: (1) the block of buckets around the tile's bucket out to its
 * first non-empty ring, then grown once to the radius its bound allows,
 * read by rows shared among the work-items, each pass closed by a
 * work-group reduction of U^2 and of the centre voxel's owner; (2) the
 * block the final bound needs: the seeds within the distance bound that the centre
 * owner does not dominate (the survivors), staged in local memory as
 * (x, y, z, index) relative to the tile's first voxel; (3) one survivor:
 * the tile is that seed's; else each work-item runs the float filter over
 * the survivors for its row (the y-z part once per survivor and row) and
 * redoes the undecided voxels with 64-bit integers. A tile with more than
 * VBJ_XT_CAP survivors stages them in chunks: each chunk rescans the block,
 * every work-item placing its k-th survivor at its prefix offset + k, so
 * the chunks partition the survivors whatever the scheduling. Loops that
 * hold barriers depend only on work-group-uniform values. */
#pragma OPENCL FP_CONTRACT OFF
#include "vbj_tiles.h"

typedef struct {
    global const int4 *recs;
    global const uint *start;
    vbj_xt_box box;
    int b0[3];
    int g, r0;
    uint dim, bs;
} tile_ctx;

/* The bound U^2 and the centre owner (cd its distance, cv its index, cj
 * its record) as the search goes, the same in every work-item between
 * passes. */
typedef struct {
    ulong u2, cd;
    uint cv, cj;
} bound_state;

/* Adds this work-item's share of the seeds of the block of radius R less
 * the block of radius Rin to st, then reduces st over the work-group
 * (ru .. rj: VBJ_XT_WG entries of local memory each). Every work-item calls
 * it with the same R and Rin (it holds barriers). */
__attribute__((always_inline)) static void bound_pass(const tile_ctx *t, int R, int Rin, int cx,
                                                      int cy, int cz, uint lid, uint W,
                                                      bound_state *st, uint *visited,
                                                      local ulong *ru, local ulong *rd,
                                                      local uint *rv, local uint *rj)
{
    for (uint u = lid, m = vbj_xt_units(R, Rin, t->dim); u < m; u += W) {
        int f, l;
        if (!vbj_xt_unit(t->b0[0], t->b0[1], t->b0[2], R, Rin, u, t->g, t->dim, &f, &l))
            continue;
        for (uint j = t->start[f]; j < t->start[l + 1]; j++) {
            int4 e = t->recs[j];
            ulong n2, f2;
            vbj_xt_bounds(t->box, e.x, e.y, e.z, t->dim, &n2, &f2);
            st->u2 = f2 < st->u2 ? f2 : st->u2;
            ulong d = vbj_dist2(cx, cy, cz, e.x, e.y, e.z);
            if (vbj_better(d, (uint)e.w, st->cd, st->cv)) {
                st->cd = d;
                st->cv = (uint)e.w;
                st->cj = j;
            }
            (*visited)++;
        }
    }
    ru[lid] = st->u2;
    rd[lid] = st->cd;
    rv[lid] = st->cv;
    rj[lid] = st->cj;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint h = W >> 1; h > 0; h >>= 1) {
        if (lid < h) {
            ru[lid] = ru[lid + h] < ru[lid] ? ru[lid + h] : ru[lid];
            if (vbj_better(rd[lid + h], rv[lid + h], rd[lid], rv[lid])) {
                rd[lid] = rd[lid + h];
                rv[lid] = rv[lid + h];
                rj[lid] = rj[lid + h];
            }
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    st->u2 = ru[0];
    st->cd = rd[0];
    st->cv = rv[0];
    st->cj = rj[0];
    barrier(CLK_LOCAL_MEM_FENCE);
}

/* Survivors of this work-item's share of the block of radius R (its rows,
 * in a fixed order; always inlined: PoCL 3 gave a called function its own
 * copy of a kernel's automatic local variable, lcount here). first_pass:
 * counts candidates and visits, sets *far, stores the survivor at an atomic
 * slot of *lcount when below VBJ_XT_CAP; otherwise stores its k-th survivor
 * at slot base + k when that falls in [lo, lo + VBJ_XT_CAP). Returns the
 * number of survivors met. */
__attribute__((always_inline)) static uint collect(const tile_ctx *t, int R, ulong u2, uint cv,
                                                   int4 c, uint lid, uint W, local int4 *list,
                                                   local uint *lcount, int first_pass, uint base,
                                                   uint lo, uint *visited, uint *cand, int *far)
{
    uint mine = 0;
    for (uint u = lid, m = vbj_xt_units(R, -1, t->dim); u < m; u += W) {
        int f, l;
        if (!vbj_xt_unit(t->b0[0], t->b0[1], t->b0[2], R, -1, u, t->g, t->dim, &f, &l))
            continue;
        for (uint j = t->start[f]; j < t->start[l + 1]; j++) {
            int4 e = t->recs[j];
            uint v = (uint)e.w;
            ulong n2, f2;
            vbj_xt_bounds(t->box, e.x, e.y, e.z, t->dim, &n2, &f2);
            if (first_pass)
                (*visited)++;
            if (n2 > u2)
                continue;
            if (first_pass)
                (*cand)++;
            if (v != cv && vbj_xt_dominated(t->box, c.x, c.y, c.z, cv, e.x, e.y, e.z, v, t->dim))
                continue;
            int4 r = (int4)(e.x - t->box.lo[0], e.y - t->box.lo[1], e.z - t->box.lo[2], e.w);
            if (first_pass) {
                *far |= !vbj_xt_float_ok(r.x, r.y, r.z);
                uint slot = atomic_inc(lcount);
                if (slot < VBJ_XT_CAP)
                    list[slot] = r;
            } else if (base + mine >= lo && base + mine < lo + VBJ_XT_CAP) {
                list[base + mine - lo] = r;
            }
            mine++;
        }
    }
    return mine;
}

/* Stages chunk ch of the `total` survivors in list and returns its length;
 * with one chunk the list staged by the first pass stays. Every work-item
 * of the tile calls it (it holds barriers when there are several chunks,
 * a work-group-uniform condition). */
__attribute__((always_inline)) static uint stage_chunk(const tile_ctx *t, int R, ulong u2, uint cv,
                                                       int4 c, uint lid, uint W, local int4 *list,
                                                       local uint *lcount, uint base, uint total,
                                                       uint ch, uint *visited, uint *cand, int *far)
{
    uint left = total - ch * VBJ_XT_CAP;
    if (total > VBJ_XT_CAP) {
        barrier(CLK_LOCAL_MEM_FENCE);
        collect(t, R, u2, cv, c, lid, W, list, lcount, 0, base, ch * VBJ_XT_CAP, visited, cand, far);
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    return left < VBJ_XT_CAP ? left : VBJ_XT_CAP;
}

/* The exact label of voxel offset (x, y, z) among n staged survivors. */
__attribute__((noinline)) static uint exact_among(local const int4 *list, uint n, int x, int y,
                                                  int z, ulong *bd, uint best)
{
    for (uint i = 0; i < n; i++) {
        int4 e = list[i];
        ulong d = vbj_dist2(x, y, z, e.x, e.y, e.z);
        if (vbj_better(d, (uint)e.w, *bd, best)) {
            *bd = d;
            best = (uint)e.w;
        }
    }
    return best;
}

/* list: VBJ_XT_CAP int4 of local memory (a kernel argument, so that
 * exact_among sees the same buffer). */
kernel void jfa_tiles(global const int4 *recs, global const uint *start,
                      global const uchar *ring0, global uint *labels,
                      global uint *counters, uint n, uint dim, uint ts, uint bs, uint g,
                      local int4 *list)
{
    local ulong ru[VBJ_XT_WG], rd[VBJ_XT_WG];
    local uint rv[VBJ_XT_WG], rj[VBJ_XT_WG], pre[VBJ_XT_WG + 1];
    local uint lcount, lflag, lsum[VBJ_XT_NC];

    uint lid = get_local_id(0), W = get_local_size(0), grp = get_group_id(0);
    uint S = 1u << ts, T = n >> ts, rowN = S < VBJ_XT_ROW ? S : VBJ_XT_ROW;
    uint tx = grp % T, ty = grp / T % T, tz = dim == 3 ? grp / (T * T) : 0u;
    tile_ctx t;
    t.recs = recs;
    t.start = start;
    t.box = vbj_xt_tile_box(tx, ty, tz, ts, dim);
    t.g = (int)g;
    t.dim = dim;
    t.bs = bs;
    t.b0[0] = (int)((tx << ts) >> bs);
    t.b0[1] = (int)((ty << ts) >> bs);
    t.b0[2] = dim == 3 ? (int)((tz << ts) >> bs) : 0;
    t.r0 = ring0[(t.b0[2] * t.g + t.b0[1]) * t.g + t.b0[0]];
    int cx = t.box.lo[0] + (int)(S / 2u) * VBJ_FIX_ONE, cy = t.box.lo[1] + (int)(S / 2u) * VBJ_FIX_ONE;
    int cz = dim == 3 ? t.box.lo[2] + (int)(S / 2u) * VBJ_FIX_ONE : 0;
    uint visited = 0, cand = 0;
    if (lid < VBJ_XT_NC)
        lsum[lid] = 0;
    if (lid == 0) {
        lcount = 0;
        lflag = 0;
    }

    /* (1) The block of radius r0 (more rings only past the saturation of
     * ring0), grown to R1: U^2 and the centre's owner (cv, its record cj). */
    bound_state st = {ULONG_MAX, ULONG_MAX, VBJ_NONE, 0u};
    int R = t.r0, Rin = -1;
    /* One call site for the pass and its barriers, in a loop whose exit
     * depends on reduced values only (PoCL copies the code after a
     * barrier under a branch). */
    for (;;) {
        bound_pass(&t, R, Rin, cx, cy, cz, lid, W, &st, &visited, ru, rd, rv, rj);
        int next = vbj_xt_next(t.box, t.b0[0], t.b0[1], t.b0[2], R, bs, t.g, dim, st.u2);
        if (next == R)
            break;
        Rin = R;
        R = next;
    }
    ulong u2 = st.u2;
    uint cv = st.cv, cj = st.cj;
    R = vbj_xt_radius(t.box, t.b0[0], t.b0[1], t.b0[2], t.r0, bs, t.g, dim, u2);
    int4 c = recs[cj];

    /* (2) Survivors (lcount and lflag were cleared before the rings' barriers). */
    int far = 0;
    uint mine = collect(&t, R, u2, cv, c, lid, W, list, &lcount, 1, 0, 0, &visited, &cand, &far);
    if (far)
        atomic_or(&lflag, 1u);
    pre[lid + 1] = mine;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint total = lcount;
    far = lflag != 0;
    uint nch = (total + VBJ_XT_CAP - 1) / VBJ_XT_CAP;
    if (nch > 1) {
        if (lid == 0) {
            pre[0] = 0;
            for (uint i = 1; i <= W; i++)
                pre[i] += pre[i - 1];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    uint base = pre[lid];
    barrier(CLK_LOCAL_MEM_FENCE); /* every far read before lflag is reused below */

    /* (3) The voxels of this work-item's row. */
    uint xr = S / rowN, x0 = lid % xr * rowN, y = lid / xr % S, z = dim == 3 ? lid / (xr * S) : 0u;
    uint lab[VBJ_XT_ROW];
    uint evals = 0, nexact = 0;
    if (total == 1) {
        for (uint j = 0; j < VBJ_XT_ROW; j++)
            lab[j] = cv;
    } else {
        float fx[VBJ_XT_ROW], d1[VBJ_XT_ROW], d2[VBJ_XT_ROW];
        float fy = (float)((int)y * VBJ_FIX_ONE), fz = (float)((int)z * VBJ_FIX_ONE);
        for (uint j = 0; j < VBJ_XT_ROW; j++) {
            fx[j] = (float)((int)(x0 + j) * VBJ_FIX_ONE);
            d1[j] = d2[j] = INFINITY;
            lab[j] = VBJ_NONE;
        }
        uint near = 0;
        if (!far) {
            for (uint ch = 0; ch < nch; ch++) {
                uint len = stage_chunk(&t, R, u2, cv, c, lid, W, list, &lcount, base, total, ch,
                                       &visited, &cand, &far);
                for (uint i = 0; i < len; i++) {
                    int4 e = list[i];
                    float ex = (float)e.x;
                    float yz = vbj_xt_yz(fy - (float)e.y, fz - (float)e.z);
#pragma unroll
                    for (uint j = 0; j < VBJ_XT_ROW; j++)
                        vbj_xt_offer(vbj_xt_dist(fx[j] - ex, yz), (uint)e.w, &d1[j], &d2[j],
                                     &lab[j]);
                }
            }
            for (uint j = 0; j < rowN; j++)
                near |= vbj_xt_decided(d1[j], d2[j]) ? 0u : 1u << j;
            evals = total * rowN;
        } else {
            near = (1u << rowN) - 1u;
        }
        nexact = popcount(near);
        /* Undecided voxels, exactly; every work-item takes part in the
         * chunk stages when some voxel of the tile needs them. */
        if (lid == 0)
            lflag = 0;
        barrier(CLK_LOCAL_MEM_FENCE);
        if (near)
            atomic_or(&lflag, 1u);
        barrier(CLK_LOCAL_MEM_FENCE);
        if (lflag) {
            ulong bd[VBJ_XT_ROW];
            for (uint j = 0; j < VBJ_XT_ROW; j++) {
                bd[j] = ULONG_MAX;
                if (near >> j & 1u)
                    lab[j] = VBJ_NONE;
            }
            for (uint ch = 0; ch < nch; ch++) {
                uint len = stage_chunk(&t, R, u2, cv, c, lid, W, list, &lcount, base, total, ch,
                                       &visited, &cand, &far);
                for (uint j = 0; j < rowN; j++)
                    if (near >> j & 1u)
                        lab[j] = exact_among(list, len, (int)(x0 + j) * VBJ_FIX_ONE,
                                             (int)y * VBJ_FIX_ONE, (int)z * VBJ_FIX_ONE, &bd[j],
                                             lab[j]);
            }
        }
    }
    global uint *row = labels + ((size_t)((tz << ts) + z) * n + (ty << ts) + y) * n + (tx << ts) + x0;
    if (rowN == VBJ_XT_ROW)
        vstore8((uint8)(lab[0], lab[1], lab[2], lab[3], lab[4], lab[5], lab[6], lab[7]), 0, row);
    else
        for (uint j = 0; j < rowN; j++)
            row[j] = lab[j];

    /* The run's counters (as the twin counts them). */
    uint mine_cnt[VBJ_XT_NC] = {0};
    mine_cnt[VBJ_XT_C_VISITED] = visited;
    mine_cnt[VBJ_XT_C_CAND] = cand;
    mine_cnt[VBJ_XT_C_EVALS] = evals;
    mine_cnt[VBJ_XT_C_EXACT] = nexact;
    for (uint i = 0; i < VBJ_XT_NC; i++)
        if (mine_cnt[i])
            atomic_add(&lsum[i], mine_cnt[i]);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (lid == 0) {
        lsum[VBJ_XT_C_UNIFORM] = total == 1;
        lsum[VBJ_XT_C_SURV] = total;
        lsum[VBJ_XT_C_CHUNKED] = total > VBJ_XT_CAP;
        for (uint i = 0; i < VBJ_XT_NC; i++)
            if (lsum[i])
                atomic_add(&counters[i * VBJ_XT_SLOTS + grp % VBJ_XT_SLOTS], lsum[i]);
    }
}
