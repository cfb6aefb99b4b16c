/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it last; include that header, never this one): the
 * decisions of a patch, the same for every backend (closed, ring radius,
 * enumerate or subdivide, tie clusters), and the depth-first cover of one
 * cell. */
#ifndef VBQ_CELL_SHARED_H
#define VBQ_CELL_SHARED_H

/* ---- the decisions of a patch (the same for every backend) ------------- */

/* Closed: no sphere outside the list can reach LO. Each such sphere is
 * centred beyond rq, so e_j > ecert = rq - (R_max - R_i) and f_j <= 1/e_j
 * < 1/ecert <= LO. slack_i = R_max - R_i. */
VBS_FN int vbq_closed(double rq, double LO, double slack_i)
{
    double ecert = rq - slack_i;
    return rq == (double)INFINITY || (LO > 0.0 && ecert > 0.0 && 1.0 / ecert < LO * (1.0 - 1e-9));
}

/* The floor of cell i's envelope: 0 ("infinity") when every vertex is
 * sought; with a bound tmax of the tangent radius, a vertex of the cell at
 * distance s = t + R_i <= tmax + R_i along u has f = 1 / (2 s) >= 1 / (2
 * (tmax + R_i)), so the three labels that meet there have hi >= this
 * floor, and a patch whose labels all stay below it holds no vertex sought
 * (the periodic pipeline drops the others: t above the bound is no
 * periodic vertex). Rounded down by a relative 1e-9, far above the few
 * roundings of R_i's double and this quotient. */
VBS_FN double vbq_floor(const vbq_env *e, vbs_u32 i)
{
    return e->tmax < (double)INFINITY ? 0.5 / (e->tmax + e->r[i]) * (1.0 - 1e-9) : 0.0;
}

/* What a closed patch with `keep` surviving labels (of `len`), `owned` of
 * them above the base, does: 0 nothing (fewer than three owned labels: no
 * vertex with smallest member i in P), 1 subdivide, 2 enumerate, 3
 * enumerate at the deepest level. Labels that tie exactly along a curve
 * (equal spheres on a circle, lattices) survive every subdivision there:
 * once VBQ_STALL levels in a row excluded nothing, more levels would only
 * multiply the patches, so the patch enumerates (a larger patch only adds
 * quadruples whose roots the certifier refutes). */
VBS_FN int vbq_decide(const vbq_env *e, const vbq_frame *fr, const VBS_GLOBAL vbq_nb *nb,
                      const VBS_GLOBAL vbs_u32 *lab, vbs_u32 i, vbs_u32 keep, vbs_u32 owned)
{
    if (owned < 3u)
        return 0;
    int stalled = keep == fr->len && fr->stall + 1u >= VBQ_STALL;
    /* Past VBQ_CLUSTER_OWNED owned labels only labels tied along a curve
     * stall (vbq_near_line): near-ties at a point separate deeper. */
    stalled = stalled && owned <= VBQ_STALL_ENUM &&
              (owned <= VBQ_CLUSTER_OWNED || vbq_near_line(nb, lab, keep, i));
    int deep = fr->level + 1u >= e->max_level || stalled;
    if (deep)
        return 3;
    if (fr->level >= e->min_level && owned <= e->enum_max)
        return 2;
    return 1;
}

/* Root patch k of 6 T^2 (face-major), over the near list lab[0 .. len0)
 * of radius rq (every sphere, once rq passes the farthest centre). */
VBS_FN vbq_frame vbq_root(vbs_u32 T, vbs_u32 k, vbs_u32 len0, double rq, double far)
{
    vbq_frame fr;
    fr.f = k / (T * T);
    fr.level = 0u;
    fr.iu = k % T;
    fr.iv = (k / T) % T;
    fr.off = 0u;
    fr.len = len0;
    fr.stall = 0u;
    fr.combo = 0u;
    fr.rq = rq >= far ? (double)INFINITY : rq;
    return fr;
}

/* The four children of a subdivided patch, sharing its surviving list
 * (combo: VBQ_FR_COMBO when the patch tried combinations on it,
 * vbq_combo_due; VBQ_FR_NOTFLAT when it found it no tie cluster). */
VBS_FN void vbq_child(const vbq_frame *fr, vbs_u32 k, vbs_u32 off, vbs_u32 keep, vbs_u32 combo,
                      vbq_frame *ch)
{
    ch->f = fr->f;
    ch->level = fr->level + 1u;
    ch->iu = 2u * fr->iu + (vbs_u64)(k & 1u);
    ch->iv = 2u * fr->iv + (vbs_u64)(k >> 1);
    ch->off = off;
    ch->len = keep;
    ch->stall = keep == fr->len ? fr->stall + 1u : 0u;
    ch->combo = combo;
    ch->rq = fr->rq;
}

/* Inserts quadruple (i, a, b, c) (i smallest) into the sorted unique list
 * q[0 .. nq). Returns 0 when q is full. */
VBS_FN int vbq_add_quad(const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i, vbs_u32 a, vbs_u32 b,
                        vbs_u32 c)
{
    vbs_u32 v[4] = {i, a, b, c};
    for (int x = 2; x < 4; x++)
        for (int y = x; y > 1 && v[y - 1] > v[y]; y--) {
            vbs_u32 t = v[y];
            v[y] = v[y - 1];
            v[y - 1] = t;
        }
    /* Binary search for the first entry >= v (entries share v[0] = i). */
    vbs_u32 lo = 0u, hi = o->nq;
    while (lo < hi) {
        vbs_u32 mid = (lo + hi) / 2u;
        const VBS_GLOBAL vbs_u32 *w = ar->q + 4u * mid;
        int less = w[1] != v[1] ? w[1] < v[1] : (w[2] != v[2] ? w[2] < v[2] : w[3] < v[3]);
        if (less)
            lo = mid + 1u;
        else
            hi = mid;
    }
    if (lo < o->nq) {
        const VBS_GLOBAL vbs_u32 *w = ar->q + 4u * lo;
        if (w[1] == v[1] && w[2] == v[2] && w[3] == v[3])
            return 1;
    }
    if (o->nq >= ar->q_cap) {
        o->status = VBQ_OVER_Q;
        return 0;
    }
    for (vbs_u32 k = o->nq; k > lo; k--)
        for (int x = 0; x < 4; x++)
            ar->q[4u * k + (vbs_u32)x] = ar->q[4u * (k - 1u) + (vbs_u32)x];
    for (int x = 0; x < 4; x++)
        ar->q[4u * lo + (vbs_u32)x] = v[x];
    o->nq++;
    return 1;
}

/* A leaf patch (vbq_decide's act 2, or 3 for a deep one) at `level` with
 * the surviving labels lab[top .. top + keep): counted, and every
 * quadruple of i with three owned labels (ids > i) inserted. Returns 0
 * when q is full. */
VBS_FN int vbq_leaf_quads(const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i, vbs_u32 top,
                          vbs_u32 keep, int act, vbs_u32 level)
{
    o->leaves++;
    if (act == 3)
        o->deep++;
    if (level > o->maxlev)
        o->maxlev = level;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbs_u32 ja = ar->nb[ar->lab[top + a]].id;
        if (ja < i)
            continue;
        for (vbs_u32 b = a + 1u; b < keep; b++) {
            vbs_u32 jb = ar->nb[ar->lab[top + b]].id;
            if (jb < i)
                continue;
            for (vbs_u32 d = b + 1u; d < keep; d++) {
                vbs_u32 jd = ar->nb[ar->lab[top + d]].id;
                if (jd >= i && !vbq_add_quad(ar, o, i, ja, jb, jd))
                    return 0;
            }
        }
    }
    return 1;
}

/* Is a closed patch a tie cluster to decide exactly (vbq_host_cluster)
 * before it is enumerated (act 3) or subdivided (act 1): more than
 * VBQ_CLUSTER_OWNED owned labels that look flat (vbq_looks_flat). */
VBS_FN int vbq_tie_cluster(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab,
                           vbs_u32 keep, vbs_u32 owned, vbs_u32 i, int act, int closed)
{
    if (owned <= VBQ_CLUSTER_OWNED || !closed || (act != 1 && act != 3))
        return 0;
    return vbq_looks_flat(nb, lab, keep, i);
}

/* The envelope decision of a due patch (vbq_envelope_due) with the double
 * filter alone (vbq_env_triple): adds the quadruples of every owned triple
 * of lab[top .. top + keep) that is a vertex of the envelope on the patch
 * and returns 1, or returns 2 at the first sign it cannot decide (the
 * host's exact fallback decides; a kernel hands the cell to the host), -1
 * when q is full. Every sign it takes is the exact one, so it adds what
 * vbq_host_envelope adds. */
VBS_FN int vbq_envelope_filter(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                               const vbq_frame *fr, vbs_u32 top, vbs_u32 keep)
{
    double qs[5][3];
    vbq_env_sides(e->T, fr, qs);
    const VBS_GLOBAL vbs_u32 *lab = ar->lab + top;
    vbs_u32 last = 0u;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbs_u32 ja = ar->nb[lab[a]].id;
        if (ja <= i)
            continue;
        for (vbs_u32 b = a + 1u; b < keep; b++) {
            vbs_u32 jb = ar->nb[lab[b]].id;
            if (jb <= i)
                continue;
            for (vbs_u32 d = b + 1u; d < keep; d++) {
                vbs_u32 jd = ar->nb[lab[d]].id;
                if (jd <= i)
                    continue;
                int r = vbq_env_triple(ar->nb, lab, keep, a, b, d, qs, &last);
                if (r == 2)
                    return 2;
                if (r == 1 && !vbq_add_quad(ar, o, i, ja, jb, jd))
                    return -1;
            }
        }
    }
    return 1;
}

/* The root patches of a task: all of them (VBQ_ALL_ROOTS), or root r
 * alone (task (r << 6)), or child c (0..3) of root r alone (task (r << 6)
 * | (c + 1)), or grandchild g (0..3) of that child alone (task (r << 6) |
 * ((g + 1) << 3) | (c + 1), VBQ_TASK2): a patch above the one kept is
 * evaluated the same in every task, and only its subdivision keeps one
 * child, so the union of the tasks makes the whole cell's decisions. A
 * level's selector 0 keeps every child of that level (VBQ_RESUME's are 0). */
#define VBQ_ALL_ROOTS 0xffffffffu
#define VBQ_TASK(r, c) (((r) << 6) | (c))
#define VBQ_TASK2(r, c, g) (((r) << 6) | ((g) << 3) | (c))

VBS_FN int vbq_task_root(vbs_u32 task, vbs_u32 k)
{
    return task == VBQ_ALL_ROOTS || (task >> 6) == k;
}

/* Does a task keep child k of a subdivided patch at `level`? */
VBS_FN int vbq_task_child(vbs_u32 task, vbs_u32 level, vbs_u32 k)
{
    if (task == VBQ_ALL_ROOTS || level > 1u)
        return 1;
    vbs_u32 sel = level == 0u ? (task & 7u) : ((task >> 3) & 7u);
    return sel == 0u || sel == k + 1u;
}

#ifndef VBQ_GROUP_ONLY

/* The upper end of label k's enclosure over the patch (m, h): kept by the
 * patch's first pass where the arena has room for it (VBQ_HI_KEEP: the
 * host, and CPU devices' work-item kernel, VBQ_CACHES), evaluated again on
 * a GPU (no scratch per label there). The same double either way. */
#ifndef VBQ_CACHES
#define VBQ_HI_KEEP(ar, k, hi) ((void)(hi))
#else
#define VBQ_HI_KEEP(ar, k, hi)   \
    do {                         \
        if ((ar)->hi)            \
            (ar)->hi[k] = (hi);  \
    } while (0)
#endif

VBS_FN double vbq_hi_again(const vbq_arena *ar, vbs_u32 k, const vbq_nb *rec, const double m[3],
                           const double h[3])
{
#ifdef VBQ_CACHES
    if (ar->hi)
        return ar->hi[k];
#endif
    double lo, hi;
    vbq_eval(rec, m, h, &lo, &hi);
    (void)k;
    (void)ar;
    return hi;
}

#ifndef __OPENCL_C_VERSION__
/* The exact decision of a tie cluster on the host (core/cells/
 * cover_cluster.c): the owned labels ids[0 .. n) of a leaf of cell i,
 * sorted in place first, so that the quadruples it picks depend on the set
 * alone (a GPU's group kernel lists a patch's labels in another order than
 * the host, and hands it such a patch, vbq_hand_patch). Returns 1 when it
 * proved which quadruples the leaf needs and added them (vbq_add_quad), 0
 * when the leaf must be enumerated, -1 when an arena ran out (o->status
 * set). */
int vbq_host_cluster(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                     vbs_u32 *ids, vbs_u32 n);

/* The exact decision of a stalled near-tie chain on the host (core/cells/
 * cover_envelope.c) where vbq_envelope_due says so (owned of the keep
 * surviving labels lab[top .. top + keep) above i, closed, act 1): adds the
 * quadruples of cell i's vertices in the directions of patch fr and returns
 * 1; returns 0 when it is not due or cannot decide (no exact input, radii
 * that differ as decimals: the patch is subdivided as before), -1 when an
 * arena ran out (o->status set). Out of line and on a copy of the frame:
 * with the loop's own frame's address taken, the loop kept it in memory and
 * EXTREMESET's Polysized set took 5 % more CPU, the decision never acting. */
int vbq_host_envelope(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                      const vbq_frame *fr, vbs_u32 top, vbs_u32 keep, vbs_u32 owned, int act,
                      int closed);

/* The two ways of vbq_envelope_decide, which find the same quadruples:
 * every owned triple tested (cubic in the owned labels), or the convex
 * hull of the labels' points (core/cells/cover_env_hull.c); AUTO takes the
 * hull above VBQ_ENV_HULL_OWNED owned labels. Measured (sc 2,744 jittered
 * 1e-12, see papers/degenerate-input/results/twocore-stop46-sc.md). */
#define VBQ_ENV_AUTO 0
#define VBQ_ENV_TRIPLES 1
#define VBQ_ENV_HULL 2
#define VBQ_ENV_HULL_OWNED 8u
#define VBQ_ENV_TRIPLES_MAX 128u /* the triples' pair table: one bit per label in two words */

/* vbq_host_envelope by a given way (VBQ_ENV_*) that also counts the exact
 * signs it took in *exact_calls (NULL: not counted; the tests compare
 * them). Returns as vbq_host_envelope; the triples' way returns 0 for more
 * than VBQ_ENV_TRIPLES_MAX owned labels. */
int vbq_envelope_decide(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                        const vbq_frame *fr, vbs_u32 top, vbs_u32 keep, int way,
                        vbs_u32 *exact_calls);

/* vbq_host_cluster over the owned labels of the surviving list
 * lab[top .. top + keep) (their ids copied above it). */
static inline int vbq_cluster_leaf(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o,
                                   vbs_u32 i, vbs_u32 top, vbs_u32 keep)
{
    if (!e->host)
        return 0;
    vbs_u32 no = 0u, base = top + keep;
    if (base + keep > ar->lab_cap) {
        o->status = VBQ_OVER_LAB;
        return -1;
    }
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbs_u32 ja = ar->nb[ar->lab[top + a]].id;
        if (ja > i)
            ar->lab[base + no++] = ja;
    }
    return vbq_host_cluster(e, ar, o, i, ar->lab + base, no);
}
#endif

#endif /* VBQ_GROUP_ONLY: the group kernel hands patches too (lane 0) */

#ifdef VBQ_HANDOFF
/* Hands patch fr of the cell (its list lab[fr->off .. + fr->len) as it was
 * popped) to the host: its entry (VBQ_HAND_WORDS) appended to ar->hand.
 * Returns 1 when written (the caller goes on as if the patch were done; the
 * host covers it alone, and counts it), 0 when the launch takes none or
 * has no room left (the caller hands the whole cell, VBQ_CLUSTER: the
 * driver runs such a cell again with more room, gpu/cover_ocl.c). The
 * work-item kernel calls it, and lane 0 of the group kernel (cover_wg.cl)
 * with the frame it popped. */
VBS_FN int vbq_hand_patch(const vbq_arena *ar, vbq_cell_out *o, const vbq_frame *fr)
{
    if (!ar->hand)
        return 0;
    vbs_u32 n = VBQ_HAND_WORDS(fr->len);
    vbs_u32 at = atomic_add(ar->hand_used, n);
    if (n > ar->hand_cap || at > ar->hand_cap - n)
        return 0;
    vbq_frame h = *fr;
    h.off = ar->hand_cell;
    *(VBS_GLOBAL vbq_frame *)(ar->hand + at) = h;
    for (vbs_u32 k = 0u; k < n - VBQ_HAND_HEAD; k++)
        ar->hand[at + VBQ_HAND_HEAD + k] = k < fr->len ? ar->nb[ar->lab[fr->off + k]].id : 0u;
    atomic_add(ar->hand_used + 1, n);
    o->patches--;
    return 1;
}
#endif

#ifndef VBQ_GROUP_ONLY

#ifndef __OPENCL_C_VERSION__
/* The patches a device handed for cell i (ar->resume, ar->resume_n words
 * of vbq_hand_patch's entries) pushed on the stack st[*nst ..) with their
 * lists at lab[*len0 ..) and their records made again (the walk's
 * vbq_nb_make, so the same doubles); *len0 moves past them. 1, or 0 when
 * an arena ran out (o->status set). core/cells/cover_resume.c. */
int vbq_resume_push(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                    vbs_u32 *nst, vbs_u32 *len0);
#endif

/* Covers the cell of sphere i (the root patch `root` of it, or every one
 * with VBQ_ALL_ROOTS): writes the quadruples {i < j < k < l} whose roots
 * hold every vertex of the cell with smallest member i in those directions
 * to ar->q (sorted, unique; o->nq of them) and the counters to *o.
 * o->status is VBQ_OK, or the arena that ran out (the output is then
 * incomplete and must not be used). See the top of this file for why the
 * quadruples are complete. */
VBS_FN void vbq_cover_cell(const vbq_env *e, const vbq_arena *ar, vbs_u32 i, vbs_u32 root,
                           vbq_cell_out *o)
{
    o->status = VBQ_OK;
    o->nq = o->nnb = o->far = 0u;
    o->patches = o->evals_k = o->leaves = o->deep = o->maxlev = 0u;
    o->lab_hw = o->st_hw = o->qoff = 0u;
    double evals = 0.0;
    const double c[3] = {e->x[i], e->y[i], e->z[i]};
    /* Near list: every sphere centred within rq of c_i; so every sphere
     * with e_j <= rq - (R_max - R_i) is in it. */
    double rq = e->near + 2.0 * e->rmax_all;
    vbs_u32 len0 = 0u;
    vbq_walk wk;
    vbq_walk_make(e, i, -1.0, rq, 0, 0u, &wk);
    if (!vbq_walk_gather(e, ar, o, &wk, 0u, &len0))
        return;
    /* Beyond this distance from c_i there is no centre. */
    double far = VBS_SQRT(vbq_box_far2(e, 1u, c)) * (1.0 + 1e-9);
    vbs_u32 T = e->T, nst = 0u;
    if (6u * T * T > ar->st_cap) {
        o->status = VBQ_OVER_ST;
        return;
    }
    for (vbs_u32 k = 0u; k < 6u * T * T; k++)
        if (vbq_task_root(root, k))
            ar->st[nst++] = vbq_root(T, k, len0, rq, far);
#ifndef __OPENCL_C_VERSION__
    if (root == VBQ_RESUME && !vbq_resume_push(e, ar, o, i, &nst, &len0))
        return;
#endif
    /* The roots share lab[0 .. len0); lists of deeper frames are stacked
     * above top. A frame's list lies below the lists of every frame pushed
     * after it, so popping a frame frees everything above its list. */
    vbs_u32 top = len0;
    double slack_i = e->rmax_all - e->r[i], floor_i = vbq_floor(e, i);
#ifdef VBQ_LANES
    /* A fetching patch is popped again at once with its list lengthened
     * (the same labels first, in order, then the ring's): with the lanes
     * (the host's AVX2 build, a CPU device's kernel) the first `again`
     * labels' lower ends (their maximum again_LO), upper ends
     * (ar->hi, written by nothing in between) and lower ends on the parts
     * (again_lg: the same parts) are the doubles of the pass before, so
     * only the ring's labels are evaluated (speed only). */
    vbs_u32 again = 0u;
    double again_LO = 0.0, again_lg[4] = {0.0, 0.0, 0.0, 0.0};
#endif
    while (nst > 0u) {
        o->st_hw = nst > o->st_hw ? nst : o->st_hw;
        o->lab_hw = top > o->lab_hw ? top : o->lab_hw;
        vbq_frame fr = ar->st[--nst];
        if (fr.off + fr.len < top)
            top = fr.off + fr.len > len0 ? fr.off + fr.len : len0;
        double u0, u1, v0, v1, m[3], h[3];
        vbq_patch_square(T, fr.level, fr.iu, fr.iv, &u0, &u1, &v0, &v1);
        vbq_patch_box(fr.f, u0, u1, v0, v1, m, h);
        o->patches++;
        /* LO: the envelope is at least max(0, lo_k) everywhere in P (0 is
         * "infinity", the floor of the envelope; vbq_floor with a bound). */
#ifdef VBQ_LANES
        vbs_u32 known = again;
        again = 0u;
        double LO = vbq_lo_lanes(ar, fr.off, known, fr.len, m, h, known ? again_LO : floor_i);
#else
        double LO = floor_i;
        for (vbs_u32 k = 0u; k < fr.len; k++) {
            vbq_nb rec = ar->nb[ar->lab[fr.off + k]];
            double lo, hi;
            vbq_eval(&rec, m, h, &lo, &hi);
            LO = lo > LO ? lo : LO;
            VBQ_HI_KEEP(ar, k, hi);
        }
#endif
        evals += (double)fr.len;
        int closed = vbq_closed(fr.rq, LO, slack_i);
        /* A fetch takes every sphere that can reach LO anywhere in the
         * patch; the children share what it found. Fetching from deeper
         * levels makes each fetch smaller but repeats it in every child
         * (measured: level 2 is the cheaper on proteins and the capsid). */
        if (!closed && fr.level >= VBQ_FETCH_LEVEL + vbq_near_tie(LO, far)) {
            double rq1 = vbq_ring_radius(fr.rq, LO, slack_i, far);
            if (top + fr.len > ar->lab_cap) {
                o->status = VBQ_OVER_LAB;
                return;
            }
            for (vbs_u32 k = 0u; k < fr.len; k++)
                ar->lab[top + k] = ar->lab[fr.off + k];
            vbq_sub sub[VBQ_NSUB];
#if defined(VBQ_LANES) && VBQ_NSUB == 4
            double lg0[4] = {floor_i, floor_i, floor_i, floor_i};
            for (vbs_u32 g = 0u; g < VBQ_NSUB; g++) {
                vbq_sub_box(fr.f, u0, u1, v0, v1, g, sub[g].m, sub[g].h);
                lg0[g] = known ? again_lg[g] : floor_i;
            }
            vbq_sub_lo_lanes(ar, fr.off, known, fr.len, sub, lg0, again_lg);
            for (vbs_u32 g = 0u; g < VBQ_NSUB; g++)
                vbq_sub_set_lo(&sub[g], again_lg[g]);
            again = fr.len;
            again_LO = LO;
#else
            for (vbs_u32 g = 0u; g < VBQ_NSUB; g++) {
                vbq_sub_box(fr.f, u0, u1, v0, v1, g, sub[g].m, sub[g].h);
                double lg = floor_i;
                for (vbs_u32 k = 0u; k < fr.len; k++) {
                    vbq_nb rec = ar->nb[ar->lab[fr.off + k]];
                    double lo, hi;
                    vbq_eval(&rec, sub[g].m, sub[g].h, &lo, &hi);
                    lg = lo > lg ? lo : lg;
                }
                vbq_sub_set_lo(&sub[g], lg);
            }
#endif
            evals += (double)(VBQ_NSUB * fr.len);
            vbs_u32 nlen = fr.len;
            vbq_walk_make(e, i, fr.rq, rq1, sub, VBQ_NSUB, &wk);
            if (!vbq_walk_gather(e, ar, o, &wk, top, &nlen))
                return;
            fr.off = top;
            fr.len = nlen;
            fr.rq = rq1;
            top += nlen;
            ar->st[nst++] = fr; /* evaluated again with the new labels */
            o->patches--;
            continue;
        }
        /* The surviving labels, copied above top. */
        if (top + fr.len > ar->lab_cap) {
            o->status = VBQ_OVER_LAB;
            return;
        }
        vbs_u32 keep = 0u, owned = 0u;
        double hm = -(double)INFINITY; /* every label's hi at most (vbq_combo_may_go) */
#ifdef VBQ_LANES
        /* The upper ends are kept: a record is read for its id only
         * where its label survives (most of a long list's do not). */
        if (ar->hi)
            keep = vbq_keep_kept(ar, fr.off, fr.len, top, i, LO, &hm, &owned);
        else
#endif
        for (vbs_u32 k = 0u; k < fr.len; k++) {
            vbs_u32 li = ar->lab[fr.off + k];
            vbq_nb rec = ar->nb[li];
            double hi = vbq_hi_again(ar, k, &rec, m, h);
            hm = hi > hm ? hi : hm;
            if (hi >= LO) {
                ar->lab[top + keep++] = li;
                if (rec.id > i)
                    owned++;
            }
        }
        evals += (double)fr.len;
        /* Combination dominance (vbq_combo_shared.h): many labels that
         * nearly tie at a point of P. */
        vbq_champ ch;
        ch.round = 0u;
        ch.n = 0u;
        vbs_u32 ch_tried = vbq_combo_due(&fr, closed, keep, owned);
        vbs_u32 list_tried = ch_tried || ((fr.combo & VBQ_FR_COMBO) && keep == fr.len);
        if (!ch_tried || !vbq_combo_may_go(LO, hm))
            ch.round = VBQ_CHAMP_ROUNDS;
        while (keep > VBQ_DOM_MAX && owned >= 3u && ch.round < VBQ_CHAMP_ROUNDS) {
            vbq_champ_make(ar->nb, ar->lab + top, keep, m, h, &ch);
            ch.round++;
            if (!vbq_combo_go(&ch, LO))
                break;
            vbs_u32 w = 0u;
            owned = 0u;
            for (vbs_u32 a = 0u; a < keep; a++) {
                vbq_nb nj = ar->nb[ar->lab[top + a]];
                if (!vbq_combo_beaten(&ch, &nj, m, h, LO)) {
                    ar->lab[top + w++] = ar->lab[top + a];
                    if (nj.id > i)
                        owned++;
                }
            }
            evals += 2.0 * (double)keep;
            /* a round that beat nothing ends them (exact ties: none can) */
            int beat = w < keep;
            keep = w;
            if (!beat)
                break;
        }
        /* Pairwise dominance: where f_k - f_j > 0 all over P, j is nowhere
         * the largest in P. Few labels only (it is quadratic). */
        if (closed && owned >= 3u && keep <= VBQ_DOM_MAX) {
            vbs_u32 w = 0u;
            owned = 0u;
            for (vbs_u32 a = 0u; a < keep; a++) {
                vbq_nb nj = ar->nb[ar->lab[top + a]];
                int dom = 0;
                for (vbs_u32 b = 0u; b < keep && !dom; b++) {
                    if (b == a)
                        continue;
                    vbq_nb nk = ar->nb[ar->lab[top + b]];
                    double dl, dh;
                    vbq_eval_diff(&nk, &nj, m, h, &dl, &dh);
                    dom = dl > 0.0;
                }
                evals += (double)(keep - 1u);
                if (!dom) {
                    ar->lab[top + w++] = ar->lab[top + a];
                    if (nj.id > i)
                        owned++;
                }
            }
            keep = w;
        }
        int act = closed ? vbq_decide(e, &fr, ar->nb, ar->lab + top, i, keep, owned) : 1;
        if (act == 0)
            continue;
        /* A stalled chain (a near-tie at a point: a jittered face's layer at
         * its normal) keeps one list for many levels; whether it looks flat
         * depends on the list alone (in order), so a child that excluded
         * nothing reuses its parent's answer (speed only: the same
         * decision). */
        vbs_u32 same = keep == fr.len && (fr.combo & VBQ_FR_NOTFLAT);
        int cluster = !same && vbq_tie_cluster(ar->nb, ar->lab + top, keep, owned, i, act, closed);
        int refuted = 0; /* the host's exact rank said: no tie cluster */
        vbs_u32 notflat = !cluster && (same || (owned > VBQ_CLUSTER_OWNED && closed)) ? VBQ_FR_NOTFLAT : 0u;
        if (cluster) {
#ifdef __OPENCL_C_VERSION__
#ifdef VBQ_HANDOFF
            if (vbq_hand_patch(ar, o, &fr))
                continue;
#endif
            o->status = VBQ_CLUSTER;
            return;
#else
            int hc = vbq_cluster_leaf(e, ar, o, i, top, keep);
            if (hc < 0)
                return;
            if (hc > 0) {
                o->leaves++;
                continue;
            }
            /* exactly no tie cluster: a near-tie the doubles call flat (a
             * crystal jittered at their resolution); on as one, and its
             * children with the same list need not ask again. Its list
             * stalls below (sc16_j12: a level-1 child with it decided), so
             * it is decided now, as a stalled chain's (cover_envelope.c). */
            cluster = 0;
            notflat = VBQ_FR_NOTFLAT;
            refuted = 1;
#endif
        }
        /* A stalled near-tie chain (vbq_envelope_due; its first tests
         * here, the rest out of this loop): its envelope decided exactly at
         * once (a kernel decides in doubles, or hands the cell to the host). */
        if (!cluster && (refuted || (((act == 1 && keep == fr.len) || act == VBQ_ENV_DEEP_ACT) &&
                                     owned > VBQ_CLUSTER_OWNED) ||
                         (owned >= 3u && VBQ_ENV_DEEP(act, &fr)))) {
#ifdef __OPENCL_C_VERSION__
            if (vbq_envelope_due(e, &fr, ar->nb, ar->lab + top, keep, owned, act, closed) &&
                (owned > VBQ_CLUSTER_OWNED || vbq_envelope_sure(e, ar, i, &fr, top, keep))) {
                /* past the cubic filter's limit: the host's hull decides */
                if (owned > VBQ_ENV_FILTER_OWNED) {
#ifdef VBQ_HANDOFF
                    if (vbq_hand_patch(ar, o, &fr))
                        continue;
#endif
                    o->status = VBQ_CLUSTER;
                    return;
                }
                int he = vbq_envelope_filter(e, ar, o, i, &fr, top, keep);
#ifdef VBQ_HANDOFF
                /* what the filter added is the host's too (exact signs) */
                if (he == 2 && vbq_hand_patch(ar, o, &fr))
                    continue;
#endif
                if (he == 2)
                    o->status = VBQ_CLUSTER;
                if (he != 1)
                    return;
                o->leaves++;
                continue;
            }
#else
            vbq_frame fc = fr; /* a copy: fr's address never escapes the loop */
            fc.len = refuted ? keep : fc.len; /* refuted: due as if stalled */
            int he = vbq_host_envelope(e, ar, o, i, &fc, top, keep, owned, act, closed);
            if (he < 0)
                return;
            if (he > 0) {
                o->leaves++;
                continue;
            }
#endif
        }
        if (act >= 2) {
            if (!vbq_leaf_quads(ar, o, i, top, keep, act, fr.level))
                return;
            continue;
        }
        /* Subdivide: the four children share the surviving list. */
        if (nst + 4u > ar->st_cap) {
            o->status = VBQ_OVER_ST;
            return;
        }
        vbs_u32 off = top;
        top += keep;
        for (vbs_u32 k = 0u; k < 4u; k++) {
            if (!vbq_task_child(root, fr.level, k))
                continue;
            vbq_frame ch;
            vbq_child(&fr, k, off, keep, (list_tried ? VBQ_FR_COMBO : 0u) | notflat, &ch);
            ar->st[nst++] = ch;
        }
    }
    o->evals_k = (vbs_u32)(evals / 1000.0);
}
#endif /* VBQ_GROUP_ONLY */

#endif
