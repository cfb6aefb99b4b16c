/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it before vbq_cell_shared.h; include that header, never
 * this one): combination dominance, the exclusion that decides a near-flat
 * label cluster without deep subdivision.
 *
 * Why it is needed. On a crystal's flat face jittered by 1e-9, the face
 * sphere's whole face layer nearly ties with infinity along the outward
 * normal: every f_j is ~1e-10 there and grows with slope |a_j| away from
 * it, so the test hi_j >= LO keeps all of them until the patch is ~1e-10
 * wide (level 30 and more), one chain of patches per such point, each
 * evaluating the whole layer. Pairwise dominance cannot help: no single
 * label lies above another over a patch that holds the near-tie point.
 *
 * The argument. Let E(u) = max(0, max_k f_k(u)) be the envelope; E >= LO
 * all over the patch P (LO = max(0, lo_k), lo_k enclosing f_k from below).
 * Take labels k, l and doubles lk, ll, mu >= 0 with lk + ll + mu <= 1. As
 * E >= max(f_k, f_l, LO) >= 0, a weighted sum with weights of total at
 * most 1 lies below it: lk f_k + ll f_l + mu LO <= E. So if
 *     lk f_k(u) + ll f_l(u) + mu LO - f_j(u) > 0   for every u in P,
 * then f_j < E all over P, j is nowhere the largest (ties included), and
 * dropping it keeps every vertex of the cell in P, as hi_j < LO does. The
 * weights are only a certificate: any choice is sound, and the enclosure
 * (vbq_eval_diff of a record that holds the weighted sum, its error bound
 * widened by the roundings of building it) decides. The weights are chosen
 * so that the gradient of the sum cancels j's across the patch: the two
 * "champions" (the VBQ_CHAMP labels with the largest hi) whose gradients,
 * projected off the patch centre m, span j's with non-negative weights of
 * least total; mu takes what is left of 1. A far label of a jittered face
 * is then beaten once the weighted jitter of the near ones (plus mu LO)
 * exceeds its own, which on a random face is most of them. Up to
 * VBQ_CHAMP_ROUNDS rounds take the next VBQ_CHAMP labels by hi as champions
 * (farther labels beaten by mid-distance pairs); a round that beats nothing
 * ends them (exact ties, where no combination wins strictly).
 *
 * The result depends on the set of surviving labels only (champions are
 * ordered by hi, then id), never on their order, so the work-group kernel,
 * which lists them in any order, makes the same decisions. */
#ifndef VBQ_COMBO_SHARED_H
#define VBQ_COMBO_SHARED_H

/* Champions of a patch (tuning: speed only, every value is sound). */
#define VBQ_CHAMP 6u
#define VBQ_CHAMP_ROUNDS 4u
#define VBQ_COMBO_CLAMP 1e-6
#define VBQ_CURVE_REL 1e-3
#define VBQ_COMBO_FLAT 1e-3
/* Patches with more surviving labels than VBQ_DOM_MAX try combinations. */

/* The address space of the champions the group kernel keeps in local memory
 * (one set per group, made by lane 0); private elsewhere. */
#ifndef VBQ_CH
#define VBQ_CH
#endif
typedef struct vbq_champ {
    vbq_nb rec[VBQ_CHAMP];
    double hi[VBQ_CHAMP];
    double w[VBQ_CHAMP][3]; /* a_c x m: det(x, a_c, m) = x . w_c */
    /* Per pair k < l of champions, in the order of vbq_combo_beaten's
     * loops: D = det(a_k, a_l, m) = a_k . w_l and 1e-290 |D|, made once
     * per round instead of once per label tested (the same doubles). */
#if defined(VBQ_WALK_V4)
    /* ... on the host and CPU devices in the 16 lanes of vbq_pair_k/l (the
     * loops' order for six champions, then a lane of none): 0 where there
     * is no such pair, which the loop skips (D == 0) as it skips these. */
    vbq_v4 vd[4], vf[4];
#elif !defined(VBQ_GPU_FORM)
    double pd[VBQ_CHAMP * (VBQ_CHAMP - 1u) / 2u];
    double pf[VBQ_CHAMP * (VBQ_CHAMP - 1u) / 2u];
#endif
    vbs_u32 n;
    vbs_u32 round; /* 0 before the first vbq_champ_make; the caller counts */
} vbq_champ;

/* D = det(a_k, a_l, m) = a_k . w_l of champions k and l. */
VBS_FN double vbq_champ_det(const VBQ_CH vbq_champ *c, vbs_u32 k, vbs_u32 l)
{
    const VBQ_CH vbq_nb *rk = &c->rec[k];
    return (rk->ax * c->w[l][0] + rk->ay * c->w[l][1]) + rk->az * c->w[l][2];
}

#if defined(VBQ_WALK_V4)
/* Lane t (0..15) of the pairs k < l of six champions in the loops' order
 * ((0,1) .. (0,5), (1,2) .. (4,5)); lane 15 is none (l = 6). */
VBS_FN vbs_u32 vbq_pair_k(vbs_u32 t)
{
    return t < 5u ? 0u : t < 9u ? 1u : t < 12u ? 2u : t < 14u ? 3u : t < 15u ? 4u : 5u;
}

VBS_FN vbs_u32 vbq_pair_l(vbs_u32 t)
{
    const vbs_u32 first[6] = {0u, 5u, 9u, 12u, 14u, 15u};
    vbs_u32 k = vbq_pair_k(t);
    return t < 15u ? k + 1u + (t - first[k]) : 6u;
}
#endif

/* The champions of the labels lab[0 .. keep) over the patch (m, h): the
 * VBQ_CHAMP with the largest upper ends hi (vbq_eval), ties to the smaller
 * id; labels with an infinite error bound are never champions. */
VBS_FN void vbq_champ_make(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab,
                           vbs_u32 keep, const double m[3], const double h[3], VBQ_CH vbq_champ *c)
{
    /* Round 0 or the band after the previous round's last champion. */
    int after = c->round > 0u && c->n > 0u;
    double ahi = after ? c->hi[c->n - 1u] : 0.0;
    vbs_u32 aid = after ? c->rec[c->n - 1u].id : 0u;
    if (c->round > 0u && !after)
        return;
    c->n = 0u;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (!(r.err < (double)INFINITY))
            continue;
        double lo, hi;
        vbq_eval(&r, m, h, &lo, &hi);
        if (after && (hi > ahi || (hi == ahi && r.id <= aid)))
            continue;
        vbs_u32 p = c->n;
        while (p > 0u && (c->hi[p - 1u] < hi || (c->hi[p - 1u] == hi && c->rec[p - 1u].id > r.id)))
            p--;
        if (p >= VBQ_CHAMP)
            continue;
        vbs_u32 last = c->n < VBQ_CHAMP ? c->n : VBQ_CHAMP - 1u;
        for (vbs_u32 q = last; q > p; q--) {
            c->rec[q] = c->rec[q - 1u];
            c->hi[q] = c->hi[q - 1u];
        }
        c->rec[p] = r;
        c->hi[p] = hi;
        if (c->n < VBQ_CHAMP)
            c->n++;
    }
    for (vbs_u32 q = 0u; q < c->n; q++) {
        const VBQ_CH vbq_nb *r = &c->rec[q];
        c->w[q][0] = r->ay * m[2] - r->az * m[1];
        c->w[q][1] = r->az * m[0] - r->ax * m[2];
        c->w[q][2] = r->ax * m[1] - r->ay * m[0];
    }
#if defined(VBQ_WALK_V4)
    double d[16], f[16];
    for (vbs_u32 t = 0u; t < 16u; t++) {
        vbs_u32 k = vbq_pair_k(t), l = vbq_pair_l(t);
        d[t] = l < c->n ? vbq_champ_det(c, k, l) : 0.0;
        f[t] = 1e-290 * VBS_FABS(d[t]);
    }
    for (vbs_u32 g = 0u; g < 4u; g++) {
        c->vd[g] = VBQ_V4(d[4u * g], d[4u * g + 1u], d[4u * g + 2u], d[4u * g + 3u]);
        c->vf[g] = VBQ_V4(f[4u * g], f[4u * g + 1u], f[4u * g + 2u], f[4u * g + 3u]);
    }
#elif !defined(VBQ_GPU_FORM)
    vbs_u32 np = 0u;
    for (vbs_u32 k = 0u; k < c->n; k++)
        for (vbs_u32 l = k + 1u; l < c->n; l++) {
            double D = vbq_champ_det(c, k, l);
            c->pd[np] = D;
            c->pf[np++] = 1e-290 * VBS_FABS(D);
        }
#endif
}

#if defined(VBQ_WALK_V4)
#ifdef __OPENCL_C_VERSION__
#define VBQ_V4_STORE(v, a) vstore4((v), 0, (a))
#else
#define VBQ_V4_STORE(v, a)                \
    do {                                  \
        for (int l_ = 0; l_ < 4; l_++)    \
            (a)[l_] = (v)[l_];            \
    } while (0)
#endif
/* vbq_combo_beaten's pair loop on the host and CPU devices: the 15 pairs in
 * the lanes of four vectors, each lane the loop's operations for its pair
 * in the same order (no contraction), a lane that the loop skips or that
 * fails its weights set to 2 (never below best); the least sum then taken
 * in the loop's order, the first of equal ones, as the loop's strict < does.
 * The same pair and weights, without the loop's unpredictable branches. */
VBS_FN void vbq_combo_pairs4(const VBQ_CH vbq_champ *c, const double p[VBQ_CHAMP], double *best,
                             double *bk, double *bl, vbs_u32 *kk, vbs_u32 *kl)
{
    double s[16], lkv[16], llv[16];
    vbq_v4 pk[4] = {VBQ_V4(p[0], p[0], p[0], p[0]), VBQ_V4(p[0], p[1], p[1], p[1]),
                    VBQ_V4(p[1], p[2], p[2], p[2]), VBQ_V4(p[3], p[3], p[4], 0.0)};
    vbq_v4 pl[4] = {VBQ_V4(p[1], p[2], p[3], p[4]), VBQ_V4(p[5], p[2], p[3], p[4]),
                    VBQ_V4(p[5], p[3], p[4], p[5]), VBQ_V4(p[4], p[5], p[5], 0.0)};
    vbq_v4 zero = VBQ_V4_ALL(0.0), two = VBQ_V4_ALL(2.0);
    for (vbs_u32 g = 0u; g < 4u; g++) {
        vbq_v4 D = c->vd[g], fl = c->vf[g];
        vbq_m4 pos = D > zero;
        vbq_v4 sl = VBQ_V4_PICK(pos, pl[g], -pl[g]), sk = VBQ_V4_PICK(pos, -pk[g], pk[g]);
        vbq_v4 al = VBQ_V4_ABS(pl[g]), ak = VBQ_V4_ABS(pk[g]);
        vbq_m4 rej = ((sl < zero) & (al > 1e-5 * ak) & (al > fl)) |
                     ((sk < zero) & (ak > 1e-5 * al) & (ak > fl)) | (D == zero);
        vbq_v4 lk = pl[g] / D, ll = -pk[g] / D;
        vbq_v4 tol = VBQ_COMBO_CLAMP * (VBQ_V4_ABS(lk) + VBQ_V4_ABS(ll));
        lk = VBQ_V4_PICK((lk < zero) & (lk >= -tol), zero, lk);
        ll = VBQ_V4_PICK((ll < zero) & (ll >= -tol), zero, ll);
        vbq_v4 sum = lk + ll;
        vbq_m4 ok = ~rej & (lk >= zero) & (ll >= zero) & (sum < two);
        sum = VBQ_V4_PICK(ok, sum, two);
        VBQ_V4_STORE(sum, s + 4u * g);
        VBQ_V4_STORE(lk, lkv + 4u * g);
        VBQ_V4_STORE(ll, llv + 4u * g);
    }
    for (vbs_u32 t = 0u; t < 15u; t++)
        if (s[t] < *best) {
            *best = s[t];
            *bk = lkv[t];
            *bl = llv[t];
            *kk = vbq_pair_k(t);
            *kl = vbq_pair_l(t);
        }
}
#endif

/* Is label nj beaten all over the patch (m, h) by a weighted sum of two
 * champions and LO (the argument at the top of this file)? 1 only when the
 * enclosure proves it. */
VBS_FN int vbq_combo_beaten(const VBQ_CH vbq_champ *c, const vbq_nb *nj, const double m[3],
                            const double h[3], double LO)
{
    if (!(nj->err < (double)INFINITY))
        return 0;
#if defined(VBQ_WALK_V4)
    double p[VBQ_CHAMP] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; /* the lanes read all six */
#else
    double p[VBQ_CHAMP];
#endif
    for (vbs_u32 q = 0u; q < c->n; q++) {
        if (c->rec[q].id == nj->id)
            return 0;
        p[q] = (nj->ax * c->w[q][0] + nj->ay * c->w[q][1]) + nj->az * c->w[q][2];
    }
    /* a_j = lk a_k + ll a_l off m: lk = det(a_j, a_l, m) / det(a_k, a_l, m),
     * ll = det(a_k, a_j, m) / det(a_k, a_l, m). */
    double best = 2.0, bk = 0.0, bl = 0.0;
    vbs_u32 kk = 0u, kl = 0u;
#if defined(VBQ_WALK_V4)
    vbq_combo_pairs4(c, p, &best, &bk, &bl, &kk, &kl);
#else
    vbs_u32 np = 0u; /* np: the pair's index in pd, pf */
    for (vbs_u32 k = 0u; k < c->n; k++)
        for (vbs_u32 l = k + 1u; l < c->n; l++) {
#ifndef VBQ_GPU_FORM
            double D = c->pd[np], fl = c->pf[np++];
#else
            double D = vbq_champ_det(c, k, l), fl = 1e-290 * VBS_FABS(D);
#endif
            if (D == 0.0)
                continue;
            /* A weight whose sign is negative and whose size is above
             * 1e-5 of the other's is below minus the clamp's tolerance
             * (at most 1e-6 (1 + 1e5) of it, plus a few roundings) once
             * divided, and the pair fails: skipped before the divisions
             * (speed only; a quotient above 1e-290 is normal, so keeps the
             * sign). Most pairs fail so. */
            double sl = D > 0.0 ? p[l] : -p[l], sk = D > 0.0 ? -p[k] : p[k];
            double al = VBS_FABS(p[l]), ak = VBS_FABS(p[k]);
            if ((sl < 0.0 && al > 1e-5 * ak && al > fl) || (sk < 0.0 && ak > 1e-5 * al && ak > fl))
                continue;
            double lk = p[l] / D, ll = -p[k] / D;
            /* j on the ray of one champion (a lattice row) solves with a
             * weight that is zero up to the jitter: clamp it. */
            double tol = VBQ_COMBO_CLAMP * (VBS_FABS(lk) + VBS_FABS(ll));
            lk = lk < 0.0 && lk >= -tol ? 0.0 : lk;
            ll = ll < 0.0 && ll >= -tol ? 0.0 : ll;
            if (lk >= 0.0 && ll >= 0.0 && lk + ll < best) {
                best = lk + ll;
                bk = lk;
                bl = ll;
                kk = k;
                kl = l;
            }
        }
#endif
    /* lk + ll <= s (1 + u) <= s + 1.2e-16 for s = fl(lk + ll) <= 1; mu is
     * below 1 - s by more than that (two roundings of at most 1.2e-16). */
    if (!(best <= 1.0 - 4e-16))
        return 0;
    double mu = (1.0 - best) - 4e-16;
    mu = mu > 0.0 ? mu : 0.0;
    const VBQ_CH vbq_nb *rk = &c->rec[kk], *rl = &c->rec[kl];
    vbq_nb s;
    s.ax = bk * rk->ax + bl * rl->ax;
    s.ay = bk * rk->ay + bl * rl->ay;
    s.az = bk * rk->az + bl * rl->az;
    s.b = (bk * rk->b + bl * rl->b) + mu * LO;
    s.id = nj->id;
    s.pad = 0u;
    /* Each coefficient is two or three products and their sums: within 4u
     * of the sum of its terms' magnitudes; the weighted exact records
     * differ from the doubles by bk err_k + bl err_l. 1 + 1e-14 covers the
     * roundings of this bound's own non-negative terms. */
    double mag = (bk * (((VBS_FABS(rk->ax) + VBS_FABS(rk->ay)) + VBS_FABS(rk->az)) + VBS_FABS(rk->b)) +
                  bl * (((VBS_FABS(rl->ax) + VBS_FABS(rl->ay)) + VBS_FABS(rl->az)) + VBS_FABS(rl->b))) +
                 mu * LO;
    s.err = ((bk * rk->err + bl * rl->err) + 4.0 * VBQ_U * mag) * (1.0 + 1e-14) + VBQ_TINY;
    double dl, dh;
    vbq_eval_diff(&s, nj, m, h, &dl, &dh);
    return dl > 0.0;
}

/* Does a patch try combinations: closed, at least three owned labels and
 * more than VBQ_DOM_MAX labels, unless its parent tried them on the same
 * list (the first pass excluded nothing since): the same champions over a
 * smaller patch would mostly fail again (speed only). */
VBS_FN vbs_u32 vbq_combo_due(const vbq_frame *fr, int closed, vbs_u32 keep, vbs_u32 owned)
{
    return closed && owned >= 3u && keep > VBQ_DOM_MAX &&
                   !((fr->combo & VBQ_FR_COMBO) && keep == fr->len) ? 1u : 0u;
}

/* May the champions' first round go at all, tested before they are made?
 * hm is at least every label's upper end hi over the patch, so at least
 * the best champion's hi[0] (the same vbq_eval over the same box; rounding
 * is monotone, so fl(VBQ_COMBO_FLAT hi[0]) <= fl(VBQ_COMBO_FLAT hm)): where
 * LO >= VBQ_COMBO_FLAT hm, vbq_combo_go fails whatever the champions, and
 * skipping vbq_champ_make gives the same labels. In general position LO
 * is far from tiny and this skips the champions' pass over the list (the
 * group kernel made them on every lane). Nor do they go where LO is 0: no
 * label is proven above infinity's 0 anywhere in the patch, which is an
 * exact crystal's flat face at its normal (every face-layer label is 0
 * there exactly, a tie cluster that vbq_host_cluster decides), not a
 * jittered face's near-tie (LO ~ 1e-10 there). Measured (fcc 10,976, one
 * thread, tie44): all 30,112 patches of the exact crystal that tried
 * combinations had LO = 0, and their 39,840 rounds tested 13.7 M labels
 * to save 1.9 % of the patches: 4.69 -> 3.89 CPU s without them, the
 * jittered crystal 4.98 -> 5.03, the random twin 2.15 -> 2.13, the same
 * vertices. Speed only. */
VBS_FN int vbq_combo_may_go(double LO, double hm)
{
    return LO > 0.0 && LO < VBQ_COMBO_FLAT * hm;
}

/* Are the champions worth a round: two at least, and LO below
 * VBQ_COMBO_FLAT of the best champion's upper end (the labels nearly tie
 * at a point of the patch, where LO stays tiny; elsewhere hi_j < LO has
 * already dropped what combinations would). Speed only. */
VBS_FN int vbq_combo_go(const VBQ_CH vbq_champ *c, double LO)
{
    return c->n >= 2u && LO < VBQ_COMBO_FLAT * c->hi[0];
}

/* Do the owned labels (ids > i) of lab[0 .. keep) tie along a curve as far
 * as the doubles tell: are their points p_j = (a_j, b_j) in R^4 within
 * VBQ_CURVE_REL of their spread from one line (affine rank <= 1)? Labels
 * that tie along a curve never separate, and subdividing them multiplies
 * the patches along it; labels whose points span a plane or more tie at
 * isolated points at most (a near-flat face cluster: its points lie near
 * the plane of the face), where subdividing goes down one chain of patches
 * and separates them unless they tie exactly. Only a speed decision (both
 * ways are complete). Independent of the order of the labels: the line
 * runs from the smallest id to the point farthest from it (ties to the
 * smaller id). */
VBS_FN int vbq_near_line(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab,
                         vbs_u32 keep, vbs_u32 i)
{
    vbs_u32 id0 = 0xffffffffu;
    double p0[4] = {0.0, 0.0, 0.0, 0.0};
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        /* a nested neighbour (infinite error) never separates */
        if (r.id > i && !(r.err < (double)INFINITY))
            return 1;
        if (r.id > i && r.id < id0) {
            id0 = r.id;
            p0[0] = r.ax;
            p0[1] = r.ay;
            p0[2] = r.az;
            p0[3] = r.b;
        }
    }
    double best = -1.0, v[4] = {0.0, 0.0, 0.0, 0.0};
    vbs_u32 bid = 0xffffffffu;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.id <= i)
            continue;
        double w[4] = {r.ax - p0[0], r.ay - p0[1], r.az - p0[2], r.b - p0[3]};
        double d2 = ((w[0] * w[0] + w[1] * w[1]) + w[2] * w[2]) + w[3] * w[3];
        if (d2 > best || (d2 == best && r.id < bid)) {
            best = d2;
            bid = r.id;
            for (int k = 0; k < 4; k++)
                v[k] = w[k];
        }
    }
    if (!(best > 0.0))
        return 1;
    double far = 0.0;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.id <= i)
            continue;
        double w[4] = {r.ax - p0[0], r.ay - p0[1], r.az - p0[2], r.b - p0[3]};
        double c = (((w[0] * v[0] + w[1] * v[1]) + w[2] * v[2]) + w[3] * v[3]) / best, d2 = 0.0;
        for (int k = 0; k < 4; k++)
            d2 += (w[k] - c * v[k]) * (w[k] - c * v[k]);
        far = d2 > far ? d2 : far;
    }
    return !(far > VBQ_CURVE_REL * VBQ_CURVE_REL * best);
}

#endif
