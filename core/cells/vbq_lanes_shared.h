/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it after the tree walk of vbq_gather_shared.h and before
 * the cell of vbq_cell_shared.h; include that header, never this one): the
 * four-lane forms of a patch's label loops (vbq_cover_cell) of the host and
 * of a CPU device's work-item kernel.
 *
 * A crystal's face cell keeps its whole face layer (and deeper layers) as
 * labels in the patches at its outward normal, where they tie exactly at
 * infinity: lists of 400 to 650 labels evaluated at every level of the
 * chain down to the tie cluster's decision, and four times more in each
 * fetch (once per part). These loops were the largest share of such a
 * cell's time (stop 47, papers/degenerate-input/results/
 * twocore-stop47-fccx.md). Here they run in the lanes of GCC's and
 * Clang's vectors in the host's AVX2 build (cover_cell_avx2.c) and of
 * OpenCL's double4 in a CPU device's work-item kernel (VBQ_WALK_V4_CL with
 * the caches, VBQ_CACHES_CL; PoCL builds it for the host's CPU, AVX2 here):
 * each lane computes vbq_eval's operations in its order (no contraction),
 * so every enclosure is the same double as the scalar loop's, and the
 * maxima are the same doubles too (see vbq_lo_lanes). The plain host build
 * and the GPU kernels keep the scalar loops. */
#ifndef VBQ_LANES_SHARED_H
#define VBQ_LANES_SHARED_H

/* Only where the four lanes are one register (AVX: the host's AVX2 build
 * of the cover, cover_cell_avx2.c, and PoCL's kernels for an AVX CPU,
 * which define __AVX__ as the host's compilers do): in the plain build the
 * compiler splits each vector into SSE2 halves and lane accesses, and these
 * loops measured slower than the scalar ones there (fcc14_exact face
 * cells, one thread: 1.56 -> 2.15 ms a cell), so that build keeps the
 * kernels' loops. The upper ends go to ar->hi, which a kernel has with
 * VBQ_CACHES only. */
#if defined(VBQ_WALK_V4) && defined(VBQ_CACHES) && defined(__AVX__)
#define VBQ_LANES 1
/* A lane mask of four 64-bit integers, and its element type. */
#ifdef __OPENCL_C_VERSION__
#define VBQ_M4(a, b, c, d) ((long4)((a), (b), (c), (d)))
typedef long vbq_i64_lane;
#else
#define VBQ_M4(a, b, c, d) ((vbq_m4){(a), (b), (c), (d)})
typedef long long vbq_i64_lane;
#endif

/* vbq_eval of the four records r[0..3] over one box (m, h), lane l for
 * r[l]: the lower ends in *lo, the upper in *hi. */
VBQ_FN void vbq_eval_lanes(const VBS_GLOBAL vbq_nb *const r[4], const vbq_v4 pm[3],
                           const vbq_v4 pam[3], const vbq_v4 ph[3], vbq_v4 *lo, vbq_v4 *hi)
{
    vbq_v4 ax = VBQ_V4(r[0]->ax, r[1]->ax, r[2]->ax, r[3]->ax);
    vbq_v4 ay = VBQ_V4(r[0]->ay, r[1]->ay, r[2]->ay, r[3]->ay);
    vbq_v4 az = VBQ_V4(r[0]->az, r[1]->az, r[2]->az, r[3]->az);
    vbq_v4 b = VBQ_V4(r[0]->b, r[1]->b, r[2]->b, r[3]->b);
    vbq_v4 err = VBQ_V4(r[0]->err, r[1]->err, r[2]->err, r[3]->err);
    vbq_v4 F = ((ax * pm[0] + ay * pm[1]) + az * pm[2]) + b;
    vbq_v4 aax = VBQ_V4_ABS(ax), aay = VBQ_V4_ABS(ay), aaz = VBQ_V4_ABS(az);
    vbq_v4 G = ((aax * pam[0] + aay * pam[1]) + aaz * pam[2]) + VBQ_V4_ABS(b);
    vbq_v4 R = (((aax * ph[0] + aay * ph[1]) + aaz * ph[2]) + err) + VBQ_C * (G + VBQ_V4_ABS(F));
    R = R * (1.0 + VBQ_C) + VBQ_TINY;
    *lo = F - R;
    *hi = F + R;
}

/* The first pass over a patch's labels lab[off + k0 .. off + len) on the
 * box (m, h): returns LO = the largest of LO0 and the labels' lower ends,
 * and keeps label k's upper end in ar->hi[k] (where the arena has it), as
 * the scalar loop of vbq_cover_cell does (k0 = 0, LO0 its floor; k0 > 0
 * continues that loop where it stopped, LO0 its maximum so far: the same
 * result, see vbq_cover_cell's `again`). Labels k0, k0 + 4, ... share
 * a lane, which keeps its own running maximum (LO0 first, then `lo > max`,
 * the loop's own test); the lanes' maxima are joined the same way. The
 * result is the loop's double: LO0 >= 0 (vbq_floor), a maximum above it is
 * positive, and a positive double has one representation, so the order of
 * the comparisons only picks among equal doubles; NaN is never picked
 * (every comparison with it is false), as in the loop. */
VBQ_FN double vbq_lo_lanes(const vbq_arena *ar, vbs_u32 off, vbs_u32 k0, vbs_u32 len,
                           const double m[3], const double h[3], double LO0)
{
    vbq_v4 pm[3], pam[3], ph[3];
    for (int a = 0; a < 3; a++) {
        pm[a] = VBQ_V4_ALL(m[a]);
        pam[a] = VBQ_V4_ABS(pm[a]);
        ph[a] = VBQ_V4_ALL(h[a]);
    }
    vbq_v4 best = VBQ_V4_ALL(LO0);
    vbs_u32 k = k0;
    for (; k + 4u <= len; k += 4u) {
        const VBS_GLOBAL vbq_nb *r[4];
        for (int l = 0; l < 4; l++)
            r[l] = &ar->nb[ar->lab[off + k + (vbs_u32)l]];
        vbq_v4 lo, hi;
        vbq_eval_lanes(r, pm, pam, ph, &lo, &hi);
        best = VBQ_V4_PICK(lo > best, lo, best);
        if (ar->hi)
#ifdef __OPENCL_C_VERSION__
            vstore4(hi, 0, ar->hi + k);
#else
            __builtin_memcpy(ar->hi + k, &hi, sizeof hi);
#endif
    }
    double LO = best[0];
    for (int l = 1; l < 4; l++)
        LO = best[l] > LO ? best[l] : LO;
    for (; k < len; k++) {
        vbq_nb rec = ar->nb[ar->lab[off + k]];
        double lo, hi;
        vbq_eval(&rec, m, h, &lo, &hi);
        LO = lo > LO ? lo : LO;
        if (ar->hi)
            ar->hi[k] = hi;
    }
    return LO;
}

/* The fetch's pass over a patch's labels lab[off + k0 .. off + len) on its
 * four parts: lg[g] = the largest of lg0[g] and the labels' lower ends on
 * part g (vbq_sub_box), the four parts in the lanes, the labels in the
 * loop's order (each lane is the scalar loop of its part; k0 > 0 goes on
 * where an earlier pass over the same parts stopped, lg0 its result). */
VBQ_FN void vbq_sub_lo_lanes(const vbq_arena *ar, vbs_u32 off, vbs_u32 k0, vbs_u32 len,
                             const vbq_sub sub[4], const double lg0[4], double lg[4])
{
    vbq_v4 pm[3], pam[3], ph[3];
    for (int a = 0; a < 3; a++) {
        pm[a] = VBQ_V4(sub[0].m[a], sub[1].m[a], sub[2].m[a], sub[3].m[a]);
        pam[a] = VBQ_V4_ABS(pm[a]);
        ph[a] = VBQ_V4(sub[0].h[a], sub[1].h[a], sub[2].h[a], sub[3].h[a]);
    }
    vbq_v4 best = VBQ_V4(lg0[0], lg0[1], lg0[2], lg0[3]);
    for (vbs_u32 k = k0; k < len; k++) {
        const VBS_GLOBAL vbq_nb *rec = &ar->nb[ar->lab[off + k]];
        const VBS_GLOBAL vbq_nb *r[4] = {rec, rec, rec, rec};
        vbq_v4 lo, hi;
        vbq_eval_lanes(r, pm, pam, ph, &lo, &hi);
        best = VBQ_V4_PICK(lo > best, lo, best);
    }
    for (int g = 0; g < 4; g++)
        lg[g] = best[g];
}

/* The second pass over lab[off .. off + len) with the upper ends kept by
 * the first (ar->hi): the labels with hi >= LO copied, in order, to
 * lab[top ...]; returns how many, with *owned those of them above the
 * base i and *hm the largest upper end (from its value on entry, `hi >
 * hm`), as vbq_cover_cell's loop. */
VBQ_FN vbs_u32 vbq_keep_kept(const vbq_arena *ar, vbs_u32 off, vbs_u32 len, vbs_u32 top,
                             vbs_u32 i, double LO, double *hm, vbs_u32 *owned)
{
    vbs_u32 keep = 0u, own = 0u;
    double best = *hm;
    for (vbs_u32 k = 0u; k < len; k++) {
        double hi = ar->hi[k];
        best = hi > best ? hi : best;
        if (hi >= LO) {
            vbs_u32 li = ar->lab[off + k];
            ar->lab[top + keep++] = li;
            own += ar->nb[li].id > i ? 1u : 0u;
        }
    }
    *hm = best;
    *owned = own;
    return keep;
}

/* The distance pass of vbq_looks_flat over the owned labels (ids > i) of
 * lab[0 .. keep): for each, w = its point (ax, ay, az, b) - p0, c1 = w.v1,
 * c2 = w.v2 (summed left to right), e = w - c1 v1 - c2 v2 and d2 = |e|^2
 * (from 0.0, left to right); *far = the largest d2 (-1 when no label is
 * owned) and *at = the first position that has it, as the scalar loop's
 * `d2 > far` finds it. Labels a, a + 4, ... share a lane, which keeps its
 * own first largest; the lanes are joined by value, then by position. */
VBQ_FN void vbq_flat_far_lanes(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab,
                               vbs_u32 keep, vbs_u32 i, const double p0[4],
                               const double v1[4], const double v2[4], double *far,
                               vbs_u32 *at)
{
    vbq_v4 P[4], V1[4], V2[4];
    for (int k = 0; k < 4; k++) {
        P[k] = VBQ_V4_ALL(p0[k]);
        V1[k] = VBQ_V4_ALL(v1[k]);
        V2[k] = VBQ_V4_ALL(v2[k]);
    }
    vbq_v4 best = VBQ_V4_ALL(-1.0), none = best;
    vbq_m4 pos = VBQ_V4M_ALL((vbq_i64_lane)0), bestpos = VBQ_V4M_ALL((vbq_i64_lane)keep);
    for (vbs_u32 a = 0u; a < keep; a += 4u) {
        const VBS_GLOBAL vbq_nb *r[4];
        vbq_i64_lane own[4];
        for (vbs_u32 l = 0u; l < 4u; l++) {
            r[l] = &nb[lab[a + l < keep ? a + l : a]];
            own[l] = a + l < keep && r[l]->id > i ? -1 : 0;
        }
        vbq_m4 owned = VBQ_M4(own[0], own[1], own[2], own[3]);
        vbq_v4 w[4] = {VBQ_V4(r[0]->ax, r[1]->ax, r[2]->ax, r[3]->ax) - P[0],
                       VBQ_V4(r[0]->ay, r[1]->ay, r[2]->ay, r[3]->ay) - P[1],
                       VBQ_V4(r[0]->az, r[1]->az, r[2]->az, r[3]->az) - P[2],
                       VBQ_V4(r[0]->b, r[1]->b, r[2]->b, r[3]->b) - P[3]};
        vbq_v4 c1 = w[0] * V1[0] + w[1] * V1[1] + w[2] * V1[2] + w[3] * V1[3];
        vbq_v4 c2 = w[0] * V2[0] + w[1] * V2[1] + w[2] * V2[2] + w[3] * V2[3];
        vbq_v4 d2 = VBQ_V4_ALL(0.0);
        for (int k = 0; k < 4; k++) {
            vbq_v4 e = w[k] - c1 * V1[k] - c2 * V2[k];
            d2 += e * e;
        }
        d2 = VBQ_V4_PICK(owned, d2, none);
        vbq_m4 up = d2 > best;
        best = VBQ_V4_PICK(up, d2, best);
        pos = VBQ_V4M_ALL((vbq_i64_lane)a) + VBQ_M4(0, 1, 2, 3);
        bestpos = (pos & up) | (bestpos & ~up);
    }
    double f = -1.0;
    vbs_u32 fa = keep;
    for (int l = 0; l < 4; l++) {
        vbs_u32 pl = (vbs_u32)bestpos[l];
        if (best[l] > f || (best[l] == f && pl < fa)) {
            f = best[l];
            fa = pl;
        }
    }
    *far = f;
    *at = f > -1.0 ? fa : keep;
}
#endif

#endif
