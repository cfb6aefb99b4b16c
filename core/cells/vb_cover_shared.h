/* The direction cover of a Voronoi cell of spheres: the math shared by the
 * plain-C proposer (core/cells/cover.c) and the OpenCL one (gpu/cover.cl).
 * Compiles as C11 and as OpenCL C. Names carry the prefix vbq_.
 *
 * Why a cover proves completeness. Put sphere i at the origin; a neighbour j
 * is d = c_j - c_i, delta = R_j - R_i, N = |d|^2 - delta^2 (N > 0 exactly
 * when neither sphere contains the other). The ray from c_i in unit
 * direction u meets the correct sheet of the bisector of i and j at distance
 *     s_j(u) = N / (2 (u.d + delta))     when u.d + delta > 0,
 * and never otherwise (vb_geom_shared.h derives it). So along u the nearest
 * bisector is the one with the largest
 *     f_j(u) = a_j . u + b_j,   a_j = d / N,   b_j = delta / N,
 * if that largest value is positive, and none (the ray runs to infinity)
 * otherwise. Writing f_inf = 0 for "infinity", the cell's boundary seen from
 * c_i is the upper envelope of the affine functions {f_j} and f_inf on the
 * unit sphere, and a vertex of the cell with neighbours j, k, l is a
 * direction where f_j = f_k = f_l >= every other f, with the common value
 * > 0 (a common value 0 would be a vertex at infinity).
 *
 * The cover splits the six faces of the cube [-1,1]^3 into squares (patches;
 * the directions u/|u| of a square's points). For a patch P it encloses every
 * f_j over P in [lo_j, hi_j] (rigorously: see vbq_patch_box, vbq_nb_make and
 * vbq_eval); j can be the largest anywhere in P only if hi_j >= LO(P) =
 * max(0, max_k lo_k). Every vertex of the cell in a direction of P therefore
 * has its three neighbours among the labels that survive that test, and the
 * quadruples of i with three surviving labels, solved exactly, hold every
 * vertex of the cell in P. With a bound tmax of the tangent radius of the
 * vertices sought (periodic boxes), the floor 0 becomes 1 / (2 (tmax +
 * R_i)) (vbq_floor): a vertex with t <= tmax lies at s <= tmax + R_i, so
 * its labels reach that floor, and the cover is complete for those
 * vertices. The patches of the cover tile the sphere of
 * directions, so the union over the patches holds every vertex of the cell.
 * The decisions made here only ever drop a label whose exclusion is proven
 * by the enclosures; nothing that is uncertain is decided.
 *
 * Floating point: every enclosure below is computed in round-to-nearest
 * with its error bound written beside it; contraction into FMA is off on
 * both sides (an FMA would only shrink the error). u = 2^-53. */
#ifndef VB_COVER_SHARED_H
#define VB_COVER_SHARED_H

#include "vb_geom_shared.h"

/* VBQ_FN: a shared function of the cover's hot loops (the records, the
 * patches' boxes, the walk's parts, the label lanes) that a CPU device's
 * work-item kernel (VBQ_WALK_V4_CL) inlines at every call, as the host's
 * compiler does on its own. PoCL's front end drops `inline` (-Dinline=)
 * and its inliner runs before the optimiser, so it left vbq_nb_make,
 * vbq_patch_box and vbq_walk_parts as calls (stop 47's perf). Speed only:
 * the same operations in the same order. GPU kernels and the host get
 * VBS_FN (the GPU text is unchanged). */
#if defined(__OPENCL_C_VERSION__) && defined(VBQ_WALK_V4_CL)
#define VBQ_FN static inline __attribute__((always_inline))
#else
#define VBQ_FN VBS_FN
#endif

/* A neighbour of the base sphere in the cover: f(u) = a . u + b, known to
 * within err for every unit u (|u|_inf <= 1): |a~ - a|_1 + |b~ - b| <= err
 * for the exact a, b of the input decimals. id is the sphere index. */
typedef struct vbq_nb {
    double ax, ay, az, b;
    double err;
    vbs_u32 id, pad;
} vbq_nb;
VBS_ASSERT_LAYOUT(sizeof(vbq_nb) == 48, "vbq_nb layout shared with OpenCL");

/* c in the enclosures: 2e-15 > 18 u. */
#define VBQ_C 2e-15
/* A floor for sums of non-negative terms that may underflow. */
#define VBQ_TINY 1e-300

/* ---- the neighbours ------------------------------------------------------ */

/* u = 2^-53 and a bound slightly above it for |X - x| of an input decimal X
 * and its nearest double x (|X - x| <= u |x| / (1 - u)). */
#define VBQ_U 1.1102230246251565e-16
#define VBQ_U_IN 1.1102230246251568e-16

/* Fills nb for base (ci, Ri) and sphere j (cj, Rj), doubles nearest to the
 * input decimals. Error bound of a~ = fl(d~ / N~), b~ = fl(delta~ / N~)
 * against the exact a = D / M, b = Delta / M of the decimals:
 *   each difference d~ = fl(x_j - x_i) is within e = 2.02 u (|x_i| + |x_j|)
 *   of the exact D (input error 1.01 u per operand, one rounding);
 *   N~ = fl(sum d~^2 - delta~^2) is within
 *     E = sum_k e_k (2 |d~_k| + e_k) + 4.01 u (sum_k d~_k^2)
 *   of the exact M (squares of perturbed values, then four squares and
 *   three additions: gamma_4 of the sum of the magnitudes);
 *   when N~ > 2E, |D/M - d~/N~| <= (e + |d~| E / N~) / (N~ - E), and the
 *   final division adds u |a~|.
 * err sums the four bounds and is multiplied by 1 + 1e-14, which covers the
 * (at most 20) roundings of its own non-negative terms; VBQ_TINY covers
 * underflow. Returns 0 when N~ <= 2E (nested or nearly nested spheres: err
 * is infinite and the caller keeps j in every patch), 1 otherwise. */
VBQ_FN int vbq_nb_make(double cix, double ciy, double ciz, double ri, double cjx, double cjy,
                       double cjz, double rj, vbs_u32 j, vbq_nb *nb)
{
    double ci[4] = {cix, ciy, ciz, ri}, cj[4] = {cjx, cjy, cjz, rj};
    double d[4], e[4], E = 0.0, mag = 0.0;
    for (int k = 0; k < 4; k++) {
        d[k] = cj[k] - ci[k];
        e[k] = 2.02 * VBQ_U_IN * (VBS_FABS(ci[k]) + VBS_FABS(cj[k])) + VBQ_TINY;
        E += e[k] * (2.0 * VBS_FABS(d[k]) + e[k]);
        mag += d[k] * d[k];
    }
    double N = ((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]) - d[3] * d[3];
    E = (E + 4.01 * VBQ_U * mag) * (1.0 + 1e-14) + VBQ_TINY;
    nb->id = j;
    nb->pad = 0u;
    if (!(N > 2.0 * E)) {
        nb->ax = nb->ay = nb->az = nb->b = 0.0;
        nb->err = (double)INFINITY;
        return 0;
    }
    double inv = 1.0 / (N - E), q[4], err = 0.0;
    for (int k = 0; k < 4; k++) {
        q[k] = d[k] / N;
        err += (e[k] + VBS_FABS(d[k]) * (E / N)) * inv + VBQ_U * VBS_FABS(q[k]);
    }
    nb->ax = q[0];
    nb->ay = q[1];
    nb->az = q[2];
    nb->b = q[3];
    nb->err = err * (1.0 + 1e-14) + VBQ_TINY;
    return 1;
}

/* VBQ_GPU_FORM: a GPU's kernels (OpenCL without the CPU devices'
 * VBQ_WALK_V4_CL) keep two forms timed on an H100 at stop 44 where a later
 * host change made them slower there (stop 45, run A: the capsid's cover
 * kernels +10-20 %): the champions' pair determinants made per label
 * tested and the flatness trigger's plane only. Speed only: every form
 * reaches the same vertices. Since stop 49 they take the host's envelope
 * decision at deep leaves (with its owned limits) and the ring's near-tie
 * jump: on an H100 (bench best of 3, gpu = ref rows) fcc 10,976 jittered
 * 1e-9 0.299 -> 0.167 s with seed 1 (its 127,817 quadruples -> 76,537,
 * the large tier's kernel 0.134 -> 0.021 s) and 0.183 -> 0.153 s with seed
 * 10,976, against their random twin's 0.087-0.094; the capsid 0.262 ->
 * 0.271, its cells the host covered whole 184 -> 5 (the flatness space pass
 * alone cost it 0.302). VBQ_HOST_FORM (VORBALL_COVER_CL_OPTS) gives a GPU
 * every host form, for measurements. */
#if defined(__OPENCL_C_VERSION__) && !defined(VBQ_WALK_V4_CL) && !defined(VBQ_HOST_FORM)
#define VBQ_GPU_FORM 1
#define VBQ_FLAT_SPACE 0         /* vbq_looks_flat: the plane only */
#else
#define VBQ_FLAT_SPACE 1
#endif
#define VBQ_ENV_DEEP_ACT 3       /* the deep leaves' act */
/* vbq_envelope_due: a deep leaf, or a patch past this level, is decided
 * with 3 or more owned labels. A jittered face's near-tie chain keeps one
 * list of ~140 labels from level 5 on and was decided at level 20 (stop
 * 46): 6 ends it 14 levels sooner with the same list and the same rows
 * (sc 2,744 jittered 1e-12, ref, one thread, load ~6: 0.91 -> 0.80 CPU s;
 * 4,096: 1.39 -> 1.17; EXTREMESET Congruent 0.30 -> 0.17; twins, fcc 1,372
 * exact, j9, random and Polysized unchanged; 3 cost fcc 1,372 exact 0.25
 * -> 0.32, 4 0.27) */
#define VBQ_ENV_DEEP_LEVEL 6u
#define VBQ_ENV_DEEP(act, fr) ((act) == 3 || ((act) == 1 && (fr)->level >= VBQ_ENV_DEEP_LEVEL))

/* ---- the patches --------------------------------------------------------- */

/* Enclosing box of the directions of the square [u0,u1] x [v0,v1] on cube
 * face f (vbs_face_dir): every unit direction w of the square has
 * |w_k - m[k]| <= h[k]. Exact extremes: the face-axis component
 * +-1/sqrt(1+u^2+v^2) is extreme where u^2 + v^2 is (the square's point
 * nearest the origin, or a corner); the component u/sqrt(1+u^2+v^2) grows
 * with u and shrinks with |v|, so its extremes lie at u in {u0, u1} with v
 * in {v0, v1, clamp(0)}; likewise for v. The nine points (corners, the
 * clamped zeros on each edge, the clamped centre) hold all of them.
 * vbs_face_dir computes each component with at most 6 roundings, so within
 * 6u relative: the box is widened by 8u |x| + VBQ_TINY on each side. */
VBQ_FN void vbq_patch_box(vbs_u32 f, double u0, double u1, double v0, double v1, double m[3],
                          double h[3])
{
    double uc = u0 > 0.0 ? u0 : (u1 < 0.0 ? u1 : 0.0);
    double vc = v0 > 0.0 ? v0 : (v1 < 0.0 ? v1 : 0.0);
    double us[3] = {u0, u1, uc}, vs[3] = {v0, v1, vc};
    double lo[3] = {2.0, 2.0, 2.0}, hi[3] = {-2.0, -2.0, -2.0};
    /* A clamped zero equal to an end (every square but one that straddles
     * an axis: all of them below the roots, whose edges are dyadic) repeats
     * its points, whose directions are the same doubles: they are skipped
     * (speed only, the same box). */
    int na = uc == u0 || uc == u1 ? 2 : 3, nb = vc == v0 || vc == v1 ? 2 : 3;
#ifndef VBQ_GPU_FORM
    /* The host and CPU devices keep the extremes in the face's own order
     * (the face axis, then u, then v: vbs_face_dir's doubles, computed by
     * its operations) and place them on the axes once: written to d[] at
     * an index picked by the face and read back as a vector, every point
     * stalled PoCL's code on a store it could not forward (stop 45). The
     * same doubles, so the same box. */
    double sgn = (f & 1u) ? -1.0 : 1.0, L[3] = {2.0, 2.0, 2.0}, H[3] = {-2.0, -2.0, -2.0};
    for (int a = 0; a < na; a++)
        for (int b = 0; b < nb; b++) {
            double u = us[a], v = vs[b];
            double inv = 1.0 / VBS_SQRT(u * u + v * v + 1.0);
            double t[3] = {sgn * inv, u * inv, v * inv};
            for (int k = 0; k < 3; k++) {
                L[k] = t[k] < L[k] ? t[k] : L[k];
                H[k] = t[k] > H[k] ? t[k] : H[k];
            }
        }
    vbs_u32 ax = f / 2u;
    for (vbs_u32 k = 0u; k < 3u; k++) {
        vbs_u32 s = (k + 3u - ax) % 3u; /* axis k holds the face's component s */
        lo[k] = s == 0u ? L[0] : (s == 1u ? L[1] : L[2]);
        hi[k] = s == 0u ? H[0] : (s == 1u ? H[1] : H[2]);
    }
#else
    for (int a = 0; a < na; a++)
        for (int b = 0; b < nb; b++) {
            double d[3];
            vbs_face_dir(f, us[a], vs[b], d);
            for (int k = 0; k < 3; k++) {
                lo[k] = d[k] < lo[k] ? d[k] : lo[k];
                hi[k] = d[k] > hi[k] ? d[k] : hi[k];
            }
        }
#endif
    for (int k = 0; k < 3; k++) {
        double l = lo[k] - (8.0 * VBQ_U * VBS_FABS(lo[k]) + VBQ_TINY);
        double g = hi[k] + (8.0 * VBQ_U * VBS_FABS(hi[k]) + VBQ_TINY);
        m[k] = 0.5 * l + 0.5 * g;
        /* max(g - m, m - l) rounds once: 1 + 2u covers it. */
        double e1 = g - m[k], e2 = m[k] - l;
        h[k] = (e1 > e2 ? e1 : e2) * (1.0 + 2.0 * VBQ_U) + VBQ_TINY;
    }
}

/* Encloses f(u) = a . u + b over every unit u with |u_k - m_k| <= h_k:
 * f(u) = F + a.(u - m) + (exact - computed). With F the computed a~.m + b~,
 * |F - (a~.m + b~)| <= 4.01u G (G = |a~|.|m| + |b~|, a sum of four
 * products), |a~.(u - m)| <= |a~|.h, and the exact a, b differ from a~, b~
 * by err in total (|u|_inf <= 1). The sum R of these is computed with at
 * most 8 roundings of non-negative terms (relative 8.01u), and lo = F - R,
 * hi = F + R round once more (u (|F| + R)): R gets VBQ_C (G + |F|) and a
 * factor (1 + VBQ_C), which covers all of it. */
VBS_FN void vbq_eval(const vbq_nb *nb, const double m[3], const double h[3], double *lo,
                     double *hi)
{
    double F = ((nb->ax * m[0] + nb->ay * m[1]) + nb->az * m[2]) + nb->b;
    double aax = VBS_FABS(nb->ax), aay = VBS_FABS(nb->ay), aaz = VBS_FABS(nb->az);
    double G = ((aax * VBS_FABS(m[0]) + aay * VBS_FABS(m[1])) + aaz * VBS_FABS(m[2])) +
               VBS_FABS(nb->b);
    double R = (((aax * h[0] + aay * h[1]) + aaz * h[2]) + nb->err) +
               VBQ_C * (G + VBS_FABS(F));
    R = R * (1.0 + VBQ_C) + VBQ_TINY;
    *lo = F - R;
    *hi = F + R;
}

/* Encloses f_k(u) - f_j(u) = (a_k - a_j).u + (b_k - b_j) over the same u
 * as vbq_eval, with the bound of vbq_eval applied to the difference
 * (coefficients differenced once more: G covers both operands, err adds). A
 * difference is far tighter than two separate enclosures, since most of
 * a~.m cancels. */
VBS_FN void vbq_eval_diff(const vbq_nb *k, const vbq_nb *j, const double m[3], const double h[3],
                          double *lo, double *hi)
{
    double dx = k->ax - j->ax, dy = k->ay - j->ay, dz = k->az - j->az, db = k->b - j->b;
    double F = ((dx * m[0] + dy * m[1]) + dz * m[2]) + db;
    double adx = VBS_FABS(dx), ady = VBS_FABS(dy), adz = VBS_FABS(dz);
    /* The differences of the coefficients round once each: u times the sum
     * of both operands' magnitudes, weighted by |m| <= 1 + h. */
    double G = ((VBS_FABS(k->ax) + VBS_FABS(j->ax)) + (VBS_FABS(k->ay) + VBS_FABS(j->ay))) +
               ((VBS_FABS(k->az) + VBS_FABS(j->az)) + (VBS_FABS(k->b) + VBS_FABS(j->b)));
    double R = (((adx * h[0] + ady * h[1]) + adz * h[2]) + (k->err + j->err)) +
               VBQ_C * (2.0 * G + VBS_FABS(F));
    R = R * (1.0 + VBQ_C) + VBQ_TINY;
    *lo = F - R;
    *hi = F + R;
}

/* The square of a patch: level l (< 53 - log2 T), integer position
 * (iu, iv) of 2^l T squares per face side. Dyadic, so u0..v1 are exact
 * doubles (the positions are below 2^53). */
VBS_FN void vbq_patch_square(vbs_u32 T, vbs_u32 level, vbs_u64 iu, vbs_u64 iv, double *u0,
                             double *u1, double *v0, double *v1)
{
    double side = 2.0 / ((double)T * (double)((vbs_u64)1 << level));
    *u0 = -1.0 + side * (double)iu;
    *u1 = -1.0 + side * (double)(iu + 1u);
    *v0 = -1.0 + side * (double)iv;
    *v1 = -1.0 + side * (double)(iv + 1u);
}

/* The rest of the shared math, in parts of one job each. They are included
 * here only and never include this header back: the kernels' embedding
 * (gpu/embed_kernels.cmake) inlines every include it meets, guards or not. */
#include "vbq_ring_shared.h"
#include "vbq_gather_shared.h"
#include "vbq_lanes_shared.h"
#include "vbq_combo_shared.h"
#include "vbq_envelope_shared.h"
#include "vbq_flat_shared.h"
#include "vbq_cell_shared.h"

#endif
