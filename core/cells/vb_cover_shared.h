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
 * vertex of the cell in P. The patches of the cover tile the sphere of
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
VBS_FN int vbq_nb_make(double cix, double ciy, double ciz, double ri, double cjx, double cjy,
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
VBS_FN void vbq_patch_box(vbs_u32 f, double u0, double u1, double v0, double v1, double m[3],
                          double h[3])
{
    double uc = u0 > 0.0 ? u0 : (u1 < 0.0 ? u1 : 0.0);
    double vc = v0 > 0.0 ? v0 : (v1 < 0.0 ? v1 : 0.0);
    double us[3] = {u0, u1, uc}, vs[3] = {v0, v1, vc};
    double lo[3] = {2.0, 2.0, 2.0}, hi[3] = {-2.0, -2.0, -2.0};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double d[3];
            vbs_face_dir(f, us[a], vs[b], d);
            for (int k = 0; k < 3; k++) {
                lo[k] = d[k] < lo[k] ? d[k] : lo[k];
                hi[k] = d[k] > hi[k] ? d[k] : hi[k];
            }
        }
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

/* ---- the cover of one cell ---------------------------------------------- */

/* Tuning (speed only; every value keeps the cover complete). */
#define VBQ_LEAF 8u            /* spheres per leaf of the tree */
#define VBQ_FETCH_LEVEL 2u     /* unclosed patches from this level fetch rings */

#define VBQ_STALL 4u           /* levels without an exclusion before enumerating */
#define VBQ_STALL_ENUM 14u     /* ... when at most this many owned labels */
#define VBQ_DOM_MAX 12u        /* patches with at most this many labels test pairs */
#define VBQ_STACK 64u          /* tree traversal stack (depth <= 33) */

/* Statuses of vbq_cover_cell: 0, or which arena ran out (the host reruns the
 * cell with larger arenas). */
#define VBQ_OK 0u
#define VBQ_OVER_NB 1u
#define VBQ_OVER_LAB 2u
#define VBQ_OVER_ST 3u
#define VBQ_OVER_Q 4u
/* 5 is the kernels' VBQ_OVER_OUT. A patch that looks like a tie cluster
 * (vbq_tie_cluster): the cell is covered again on the host, which decides
 * such patches exactly (vbq_host_cluster). */
#define VBQ_CLUSTER 6u

/* A closed patch to enumerate or subdivide with more owned labels than this
 * that look flat is a tie cluster, decided exactly before any of its
 * C(owned, 3) quadruples is written or its children are made (speed only:
 * both ways are complete). */
#define VBQ_CLUSTER_OWNED 5u

/* A patch waiting in the depth-first stack. */
typedef struct vbq_frame {
    vbs_u32 f, level;
    vbs_u64 iu, iv;    /* 64 bits: near-ties need levels past 31 */
    vbs_u32 off, len;  /* labels in lab[off .. off + len): indices into nb */
    vbs_u32 stall;     /* consecutive levels that excluded no label */
    vbs_u32 pad;
    double rq;         /* every sphere centred within rq of c_i is in the list or was
                          excluded by an ancestor (INFINITY: every sphere) */
} vbq_frame;
VBS_ASSERT_LAYOUT(sizeof(vbq_frame) == 48, "vbq_frame layout shared with OpenCL");

/* What one cell's cover did (counters for --stats; nq quadruples written). */
typedef struct vbq_cell_out {
    vbs_u32 status, nq, nnb, far;
    vbs_u32 patches, evals_k, leaves, deep, maxlev;
    vbs_u32 lab_hw, st_hw;  /* high-water marks of the label and frame stacks */
    vbs_u32 qoff;           /* where a backend stored the quadruples */
} vbq_cell_out;
VBS_ASSERT_LAYOUT(sizeof(vbq_cell_out) == 48, "vbq_cell_out layout shared with OpenCL");

/* The input of every cell: the spheres, and a tree over the centres of the
 * spheres that no other sphere contains: their ids along a Morton curve,
 * in leaves of VBQ_LEAF, a complete binary tree over the leaves (heap
 * order: node 1 the root, leaves from `first`), each node with the box of
 * its centres (lo xyz, hi xyz) and the largest radius below it. */
typedef struct vbq_env {
    const VBS_GLOBAL double *x, *y, *z, *r;
    const VBS_GLOBAL double *box;
    const VBS_GLOBAL double *rmax;
    const VBS_GLOBAL vbs_u32 *ids;
    vbs_u32 first, m;
    double rmax_all;   /* largest radius of the tree's spheres */
    double near;       /* first guess of a near list's radius, beyond 2 rmax_all */
    vbs_u32 T, min_level, max_level, enum_max;
#ifndef __OPENCL_C_VERSION__
    const void *host;  /* the host's exact input for vbq_host_cluster (NULL: none) */
#endif
} vbq_env;

/* Scratch of one cell, fixed capacities. */
typedef struct vbq_arena {
    VBS_GLOBAL vbq_nb *nb;
    VBS_GLOBAL vbs_u32 *lab;
    VBS_GLOBAL vbq_frame *st;
    VBS_GLOBAL vbs_u32 *q;      /* 4 per quadruple */
    vbs_u32 nb_cap, lab_cap, st_cap, q_cap;
} vbq_arena;

/* Squared distance from c to node nd's box (0 inside), and to its farthest
 * corner. */
VBS_FN double vbq_box_dist2(const vbq_env *e, vbs_u32 nd, const double c[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double l = e->box[6u * nd + (vbs_u32)a], h = e->box[6u * nd + 3u + (vbs_u32)a];
        double dn = c[a] < l ? l - c[a] : (c[a] > h ? c[a] - h : 0.0);
        d2 += dn * dn;
    }
    return d2;
}

VBS_FN double vbq_box_far2(const vbq_env *e, vbs_u32 nd, const double c[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double l = VBS_FABS(e->box[6u * nd + (vbs_u32)a] - c[a]);
        double h = VBS_FABS(e->box[6u * nd + 3u + (vbs_u32)a] - c[a]);
        double f = l > h ? l : h;
        d2 += f * f;
    }
    return d2;
}

/* A query of the tree for the spheres centred in (rq0, rq1] from c_i
 * (rq0 < 0: from 0) that can be labels in the patch (m, h) with lower
 * envelope LO (LO < 0: every sphere of the ring, the near list). Where
 * f_j >= LO at u: u.d + delta >= LO N >= 0, so the sphere reaches the
 * half-space u.(x - c_i) >= R_i - R_j; and for LO > 0 the bisector along u
 * is at most s = 1/(2 LO) from c_i, so the tangent sphere there, centre
 * c_i + s u and radius s - R_i, must reach sphere j: |c_i + s u - c_j| <=
 * s - R_i + R_j. A node is pruned when one of these fails for every u of
 * the patch box and every centre of its box (R_j <= its R_max), or when its
 * box lies within rq0 or beyond rq1; the bounds carry a relative margin of
 * 1e-9, far above the rounding errors of these few operations. */
typedef struct vbq_query {
    double c[3], ri;
    double m[3], h[3];
    double LO, rq0, rq1;
    double sdist, in2, out2;
    int filter;
} vbq_query;

VBS_FN void vbq_query_make(const vbq_env *e, vbs_u32 i, const double m[3], const double h[3],
                           double LO, double rq0, double rq1, vbq_query *q)
{
    q->c[0] = e->x[i];
    q->c[1] = e->y[i];
    q->c[2] = e->z[i];
    q->ri = e->r[i];
    for (int a = 0; a < 3; a++) {
        q->m[a] = m[a];
        q->h[a] = h[a];
    }
    q->LO = LO;
    q->rq0 = rq0;
    q->rq1 = rq1;
    q->sdist = LO > 0.0 ? 0.5 / LO : (double)INFINITY;
    q->filter = LO >= 0.0;
    q->in2 = rq0 > 0.0 ? rq0 * rq0 * (1.0 - 1e-9) : -1.0;
    q->out2 = rq1 * rq1 * (1.0 + 1e-9);
}

/* Can node nd hold a sphere that passes the query? */
VBS_FN int vbq_node_pass(const vbq_env *e, const vbq_query *q, vbs_u32 nd)
{
    const VBS_GLOBAL double *bx = e->box + 6u * nd;
    double slack = e->rmax[nd] - q->ri;
    double best = 0.0, mag = 0.0, dmax2 = 0.0, dmin2 = 0.0, bb2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double b0 = bx[a] - q->c[a], b1 = bx[3 + a] - q->c[a];
        double u0 = q->m[a] - q->h[a], u1 = q->m[a] + q->h[a];
        double p0 = u0 * b0, p1 = u0 * b1, p2 = u1 * b0, p3 = u1 * b1;
        double mx = p0 > p1 ? p0 : p1;
        mx = p2 > mx ? p2 : mx;
        mx = p3 > mx ? p3 : mx;
        best += mx;
        mag += VBS_FABS(b0) + VBS_FABS(b1);
        double f = VBS_FABS(b0) > VBS_FABS(b1) ? VBS_FABS(b0) : VBS_FABS(b1);
        dmax2 += f * f;
        double dn = b0 > 0.0 ? b0 : (b1 < 0.0 ? -b1 : 0.0);
        dmin2 += dn * dn;
        if (q->sdist < (double)INFINITY) {
            double t0 = q->sdist * u0, t1 = q->sdist * u1;
            double gp = b0 > t1 ? b0 - t1 : (t0 > b1 ? t0 - b1 : 0.0);
            bb2 += gp * gp;
        }
    }
    if (dmax2 < q->in2 || dmin2 > q->out2)
        return 0;
    if (q->filter && best + slack < -1e-9 * (mag + VBS_FABS(slack) + 1e-300))
        return 0;
    if (q->sdist < (double)INFINITY) {
        double reach = (q->sdist + slack) * (1.0 + 1e-9) + 1e-9 * (mag + q->sdist);
        if (reach < 0.0 || bb2 > reach * reach)
            return 0;
    }
    return 1;
}

/* Does sphere j (not the base) pass the query? Fills its record when so.
 * Spheres within rq0 are in the list or were excluded; those beyond rq1
 * belong to a later ring. A sphere of a ring is kept when its enclosure
 * reaches LO. */
VBS_FN int vbq_sphere_pass(const vbq_env *e, const vbq_query *q, vbs_u32 j,
                           vbq_nb *rec)
{
    double dx = e->x[j] - q->c[0], dy = e->y[j] - q->c[1], dz = e->z[j] - q->c[2];
    double d2 = dx * dx + dy * dy + dz * dz;
    if ((q->rq0 > 0.0 && !(d2 > q->rq0 * q->rq0)) || d2 > q->rq1 * q->rq1)
        return 0;
    vbq_nb_make(q->c[0], q->c[1], q->c[2], q->ri, e->x[j], e->y[j], e->z[j], e->r[j], j, rec);
    if (q->filter) {
        double lo, hi;
        vbq_eval(rec, q->m, q->h, &lo, &hi);
        if (!(hi >= q->LO))
            return 0;
    }
    return 1;
}

/* ---- ring fetches resolved by sub-patch --------------------------------
 * A fetching patch is split VBQ_SUB x VBQ_SUB; each part g gets its own box
 * and lower envelope LO_g from the list. A sphere can be a label somewhere
 * in the patch only if it can be one somewhere in some part, i.e. only if
 * it passes the query of some part: a far sharper test than the patch's
 * single LO where the cell's reach varies across the patch (exposed cells
 * facing a cavity). The address space of the parts' array is VBQ_SQ
 * (private by default; the group kernel keeps them in local memory). */
#ifndef VBQ_SUB
#define VBQ_SUB 2u
#endif
#define VBQ_NSUB (VBQ_SUB * VBQ_SUB)
#ifndef VBQ_SQ
#define VBQ_SQ
#endif

typedef struct vbq_sub {
    double m[3], h[3];
    double LO, sdist;
} vbq_sub;

/* Part g (row-major) of the square [u0,u1] x [v0,v1] on face f. */
VBS_FN void vbq_sub_box(vbs_u32 f, double u0, double u1, double v0, double v1, vbs_u32 g,
                        double m[3], double h[3])
{
    double du = (u1 - u0) / (double)VBQ_SUB, dv = (v1 - v0) / (double)VBQ_SUB;
    vbs_u32 a = g % VBQ_SUB, b = g / VBQ_SUB;
    /* The parts' edges are the patch's dyadic grid refined VBQ_SUB times:
     * exact doubles, and the outer ones equal the patch's edges. */
    double a0 = a == 0u ? u0 : u0 + du * (double)a, a1 = a + 1u == VBQ_SUB ? u1 : u0 + du * (double)(a + 1u);
    double b0 = b == 0u ? v0 : v0 + dv * (double)b, b1 = b + 1u == VBQ_SUB ? v1 : v0 + dv * (double)(b + 1u);
    vbq_patch_box(f, a0, a1, b0, b1, m, h);
}

/* Can node nd hold a sphere that is centred in (rq0, rq1] and reaches
 * LO_g in some part g? (vbq_node_pass for each part.) */
VBS_FN int vbq_node_pass_sub(const vbq_env *e, const double c[3], double ri, double rq0,
                             double rq1, const VBQ_SQ vbq_sub *sub, vbs_u32 nd)
{
    const VBS_GLOBAL double *bx = e->box + 6u * nd;
    double slack = e->rmax[nd] - ri;
    double b0[3], b1[3], mag = 0.0, dmax2 = 0.0, dmin2 = 0.0;
    for (int a = 0; a < 3; a++) {
        b0[a] = bx[a] - c[a];
        b1[a] = bx[3 + a] - c[a];
        mag += VBS_FABS(b0[a]) + VBS_FABS(b1[a]);
        double f = VBS_FABS(b0[a]) > VBS_FABS(b1[a]) ? VBS_FABS(b0[a]) : VBS_FABS(b1[a]);
        dmax2 += f * f;
        double dn = b0[a] > 0.0 ? b0[a] : (b1[a] < 0.0 ? -b1[a] : 0.0);
        dmin2 += dn * dn;
    }
    double in2 = rq0 > 0.0 ? rq0 * rq0 * (1.0 - 1e-9) : -1.0, out2 = rq1 * rq1 * (1.0 + 1e-9);
    if (dmax2 < in2 || dmin2 > out2)
        return 0;
    for (vbs_u32 g = 0u; g < VBQ_NSUB; g++) {
        double best = 0.0, bb2 = 0.0;
        double sd = sub[g].sdist;
        for (int a = 0; a < 3; a++) {
            double u0 = sub[g].m[a] - sub[g].h[a], u1 = sub[g].m[a] + sub[g].h[a];
            double p0 = u0 * b0[a], p1 = u0 * b1[a], p2 = u1 * b0[a], p3 = u1 * b1[a];
            double mx = p0 > p1 ? p0 : p1;
            mx = p2 > mx ? p2 : mx;
            mx = p3 > mx ? p3 : mx;
            best += mx;
            if (sd < (double)INFINITY) {
                double t0 = sd * u0, t1 = sd * u1;
                double gp = b0[a] > t1 ? b0[a] - t1 : (t0 > b1[a] ? t0 - b1[a] : 0.0);
                bb2 += gp * gp;
            }
        }
        if (best + slack < -1e-9 * (mag + VBS_FABS(slack) + 1e-300))
            continue;
        if (sd < (double)INFINITY) {
            double reach = (sd + slack) * (1.0 + 1e-9) + 1e-9 * (mag + sd);
            if (reach < 0.0 || bb2 > reach * reach)
                continue;
        }
        return 1;
    }
    return 0;
}

/* Does sphere j (centred in (rq0, rq1] from c) reach LO_g in some part g?
 * Fills its record when so. */
VBS_FN int vbq_sphere_pass_sub(const vbq_env *e, const double c[3], double ri, double rq0,
                               double rq1, const VBQ_SQ vbq_sub *sub, vbs_u32 j, vbq_nb *rec)
{
    double dx = e->x[j] - c[0], dy = e->y[j] - c[1], dz = e->z[j] - c[2];
    double d2 = dx * dx + dy * dy + dz * dz;
    if ((rq0 > 0.0 && !(d2 > rq0 * rq0)) || d2 > rq1 * rq1)
        return 0;
    vbq_nb_make(c[0], c[1], c[2], ri, e->x[j], e->y[j], e->z[j], e->r[j], j, rec);
    for (vbs_u32 g = 0u; g < VBQ_NSUB; g++) {
        double m[3] = {sub[g].m[0], sub[g].m[1], sub[g].m[2]};
        double h[3] = {sub[g].h[0], sub[g].h[1], sub[g].h[2]};
        double lo, hi;
        vbq_eval(rec, m, h, &lo, &hi);
        if (hi >= sub[g].LO)
            return 1;
    }
    return 0;
}

#ifndef VBQ_GROUP_ONLY
/* The ring fetch on one work-item, resolved by parts: spheres centred in
 * (rq0, rq1] that reach some part's LO_g, appended to nb and to the list at
 * lab[off + *len ...]. Returns 0 when an arena is full. */
VBS_FN int vbq_gather_sub(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                          const VBQ_SQ vbq_sub *sub, double rq0, double rq1, vbs_u32 off,
                          vbs_u32 *len)
{
    const double c[3] = {e->x[i], e->y[i], e->z[i]};
    double ri = e->r[i];
    vbs_u32 stack[VBQ_STACK], ns = 0;
    if (e->m)
        stack[ns++] = 1u;
    while (ns) {
        vbs_u32 nd = stack[--ns];
        if (!vbq_node_pass_sub(e, c, ri, rq0, rq1, sub, nd))
            continue;
        if (nd < e->first) {
            stack[ns++] = 2u * nd + 1u;
            stack[ns++] = 2u * nd;
            continue;
        }
        vbs_u32 q0 = (nd - e->first) * VBQ_LEAF;
        for (vbs_u32 k = q0; k < e->m && k < q0 + VBQ_LEAF; k++) {
            vbs_u32 j = e->ids[k];
            vbq_nb rec;
            if (j == i || !vbq_sphere_pass_sub(e, c, ri, rq0, rq1, sub, j, &rec))
                continue;
            o->far++;
            if (o->nnb >= ar->nb_cap) {
                o->status = VBQ_OVER_NB;
                return 0;
            }
            ar->nb[o->nnb++] = rec;
            if (off + *len >= ar->lab_cap) {
                o->status = VBQ_OVER_LAB;
                return 0;
            }
            ar->lab[off + (*len)++] = o->nnb - 1u;
        }
    }
    return 1;
}
#endif

/* The query on one work-item: passing spheres appended to nb and to the
 * list at lab[off + *len ...]. Returns 0 when an arena is full. */
VBS_FN int vbq_gather(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                      const double m[3], const double h[3], double LO, double rq0, double rq1,
                      vbs_u32 off, vbs_u32 *len)
{
    vbq_query q;
    vbq_query_make(e, i, m, h, LO, rq0, rq1, &q);
    vbs_u32 stack[VBQ_STACK], ns = 0;
    if (e->m)
        stack[ns++] = 1u;
    while (ns) {
        vbs_u32 nd = stack[--ns];
        if (!vbq_node_pass(e, &q, nd))
            continue;
        if (nd < e->first) {
            stack[ns++] = 2u * nd + 1u;
            stack[ns++] = 2u * nd;
            continue;
        }
        vbs_u32 q0 = (nd - e->first) * VBQ_LEAF;
        for (vbs_u32 k = q0; k < e->m && k < q0 + VBQ_LEAF; k++) {
            vbs_u32 j = e->ids[k];
            vbq_nb rec;
            if (j == i || !vbq_sphere_pass(e, &q, j, &rec))
                continue;
            if (q.filter)
                o->far++;
            if (o->nnb >= ar->nb_cap) {
                o->status = VBQ_OVER_NB;
                return 0;
            }
            ar->nb[o->nnb++] = rec;
            if (off + *len >= ar->lab_cap) {
                o->status = VBQ_OVER_LAB;
                return 0;
            }
            ar->lab[off + (*len)++] = o->nnb - 1u;
        }
    }
    return 1;
}

/* ---- the decisions of a patch (the same for every backend) ------------- */

/* Closed: no sphere outside the list can reach LO. Each such sphere is
 * centred beyond rq, so e_j > ecert = rq - (R_max - R_i) and f_j <= 1/e_j
 * < 1/ecert <= LO. slack_i = R_max - R_i. */
VBS_FN int vbq_closed(double rq, double LO, double slack_i)
{
    double ecert = rq - slack_i;
    return rq == (double)INFINITY || (LO > 0.0 && ecert > 0.0 && 1.0 / ecert < LO * (1.0 - 1e-9));
}

/* The outer radius of the next ring a patch fetches: out to the reach LO
 * asks for, at most twice the present radius (LO grows with what is
 * found); infinite once it passes the farthest centre. */
VBS_FN double vbq_ring_radius(double rq, double LO, double slack_i, double far)
{
    double want = LO > 0.0 ? (1.0 / LO) * (1.0 + 1e-8) + slack_i + 1e-9 * rq : (double)INFINITY;
    double rq1 = want < 2.0 * rq ? want : 2.0 * rq;
    return rq1 >= far ? (double)INFINITY : rq1;
}

/* What a closed patch with `keep` surviving labels (of `len`), `owned` of
 * them above the base, does: 0 nothing (fewer than three owned labels: no
 * vertex with smallest member i in P), 1 subdivide, 2 enumerate, 3
 * enumerate at the deepest level. Labels that tie exactly along a curve
 * (equal spheres on a circle, lattices) survive every subdivision there:
 * once VBQ_STALL levels in a row excluded nothing, more levels would only
 * multiply the patches, so the patch enumerates (a larger patch only adds
 * quadruples whose roots the certifier refutes). */
VBS_FN int vbq_decide(const vbq_env *e, const vbq_frame *fr, vbs_u32 keep, vbs_u32 owned)
{
    if (owned < 3u)
        return 0;
    int stalled = keep == fr->len && fr->stall + 1u >= VBQ_STALL;
    int deep = fr->level + 1u >= e->max_level || (stalled && owned <= VBQ_STALL_ENUM);
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
    fr.pad = 0u;
    fr.rq = rq >= far ? (double)INFINITY : rq;
    return fr;
}

/* The four children of a subdivided patch, sharing its surviving list. */
VBS_FN void vbq_child(const vbq_frame *fr, vbs_u32 k, vbs_u32 off, vbs_u32 keep, vbq_frame *ch)
{
    ch->f = fr->f;
    ch->level = fr->level + 1u;
    ch->iu = 2u * fr->iu + (vbs_u64)(k & 1u);
    ch->iv = 2u * fr->iv + (vbs_u64)(k >> 1);
    ch->off = off;
    ch->len = keep;
    ch->stall = keep == fr->len ? fr->stall + 1u : 0u;
    ch->pad = 0u;
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

/* Do the owned labels (ids > i) of lab[0 .. keep) look like an exact tie
 * cluster: are their points (a, b) in R^4 on one affine plane as far as the
 * doubles tell (within 8 times the records' error bounds and 1e-12 of the
 * points' size)? Only a trigger: the host decides exactly (vbq_host_cluster)
 * and enumerates whatever is not a cluster; near-ties beyond the doubles'
 * noise do not look flat and are left to the subdivision. Three passes: the
 * point farthest from the first, the one farthest from their line, then
 * every distance to the plane of the three. */
VBS_FN int vbq_looks_flat(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab, vbs_u32 keep,
                          vbs_u32 i)
{
    double p0[4] = {0.0, 0.0, 0.0, 0.0}, v1[4] = {0.0, 0.0, 0.0, 0.0}, v2[4] = {0.0, 0.0, 0.0, 0.0};
    double scale = 0.0, emax = 0.0, best = -1.0;
    int have = 0;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.id <= i)
            continue;
        if (!(r.err < (double)INFINITY))
            return 0;
        double q[4] = {r.ax, r.ay, r.az, r.b};
        emax = r.err > emax ? r.err : emax;
        for (int k = 0; k < 4; k++)
            scale = VBS_FABS(q[k]) > scale ? VBS_FABS(q[k]) : scale;
        if (!have) {
            for (int k = 0; k < 4; k++)
                p0[k] = q[k];
            have = 1;
            continue;
        }
        double d2 = 0.0;
        for (int k = 0; k < 4; k++)
            d2 += (q[k] - p0[k]) * (q[k] - p0[k]);
        if (d2 > best) {
            best = d2;
            for (int k = 0; k < 4; k++)
                v1[k] = q[k] - p0[k];
        }
    }
    double tol = 8.0 * emax + 1e-12 * scale;
    if (!(best > tol * tol))
        return 1;
    double n1 = VBS_SQRT(best);
    for (int k = 0; k < 4; k++)
        v1[k] /= n1;
    for (int pass = 0; pass < 2; pass++) {
        double far = -1.0, w2[4] = {0.0, 0.0, 0.0, 0.0};
        for (vbs_u32 a = 0u; a < keep; a++) {
            vbq_nb r = nb[lab[a]];
            if (r.id <= i)
                continue;
            double w[4] = {r.ax - p0[0], r.ay - p0[1], r.az - p0[2], r.b - p0[3]};
            double c1 = w[0] * v1[0] + w[1] * v1[1] + w[2] * v1[2] + w[3] * v1[3];
            double c2 = w[0] * v2[0] + w[1] * v2[1] + w[2] * v2[2] + w[3] * v2[3];
            double e[4], d2 = 0.0;
            for (int k = 0; k < 4; k++) {
                e[k] = w[k] - c1 * v1[k] - c2 * v2[k];
                d2 += e[k] * e[k];
            }
            if (d2 > far) {
                far = d2;
                for (int k = 0; k < 4; k++)
                    w2[k] = e[k];
            }
        }
        if (!(far > tol * tol))
            return 1;
        if (pass == 1)
            return 0;
        double n2 = VBS_SQRT(far);
        for (int k = 0; k < 4; k++)
            v2[k] = w2[k] / n2;
    }
    return 0;
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

/* The root patches of a task: all of them (VBQ_ALL_ROOTS), or root r
 * alone (task (r << 3)), or child c (0..3) of root r alone (task (r << 3) |
 * (c + 1)): the root's own evaluation is the same in every task, and only
 * its subdivision keeps one child, so the union of the tasks makes the
 * whole cell's decisions. */
#define VBQ_ALL_ROOTS 0xffffffffu
#define VBQ_TASK(r, c) (((r) << 3) | (c))

VBS_FN int vbq_task_root(vbs_u32 task, vbs_u32 k)
{
    return task == VBQ_ALL_ROOTS || (task >> 3) == k;
}

/* Does a task keep child k of a subdivided patch at `level`? */
VBS_FN int vbq_task_child(vbs_u32 task, vbs_u32 level, vbs_u32 k)
{
    return task == VBQ_ALL_ROOTS || level > 0u || (task & 7u) == 0u || (task & 7u) == k + 1u;
}

#ifndef VBQ_GROUP_ONLY

#ifndef __OPENCL_C_VERSION__
/* The exact decision of a tie cluster on the host (core/cells/
 * cover_cluster.c): the owned labels ids[0 .. n) of a leaf of cell i.
 * Returns 1 when it proved which quadruples the leaf needs and added them
 * (vbq_add_quad), 0 when the leaf must be enumerated, -1 when an arena ran
 * out (o->status set). */
int vbq_host_cluster(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                     const vbs_u32 *ids, vbs_u32 n);

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
    const double m0[3] = {0.0, 0.0, 0.0}, h0[3] = {1.0, 1.0, 1.0};
    /* Near list: every sphere centred within rq of c_i; so every sphere
     * with e_j <= rq - (R_max - R_i) is in it. */
    double rq = e->near + 2.0 * e->rmax_all;
    vbs_u32 len0 = 0u;
    if (!vbq_gather(e, ar, o, i, m0, h0, -1.0, -1.0, rq, 0u, &len0))
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
    /* The roots share lab[0 .. len0); lists of deeper frames are stacked
     * above top. A frame's list lies below the lists of every frame pushed
     * after it, so popping a frame frees everything above its list. */
    vbs_u32 top = len0;
    double slack_i = e->rmax_all - e->r[i];
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
         * "infinity", the floor of the envelope). */
        double LO = 0.0;
        for (vbs_u32 k = 0u; k < fr.len; k++) {
            vbq_nb rec = ar->nb[ar->lab[fr.off + k]];
            double lo, hi;
            vbq_eval(&rec, m, h, &lo, &hi);
            LO = lo > LO ? lo : LO;
        }
        evals += (double)fr.len;
        int closed = vbq_closed(fr.rq, LO, slack_i);
        /* A fetch takes every sphere that can reach LO anywhere in the
         * patch; the children share what it found. Fetching from deeper
         * levels makes each fetch smaller but repeats it in every child
         * (measured: level 2 is the cheaper on proteins and the capsid). */
        if (!closed && fr.level >= VBQ_FETCH_LEVEL) {
            double rq1 = vbq_ring_radius(fr.rq, LO, slack_i, far);
            if (top + fr.len > ar->lab_cap) {
                o->status = VBQ_OVER_LAB;
                return;
            }
            for (vbs_u32 k = 0u; k < fr.len; k++)
                ar->lab[top + k] = ar->lab[fr.off + k];
            vbq_sub sub[VBQ_NSUB];
            for (vbs_u32 g = 0u; g < VBQ_NSUB; g++) {
                vbq_sub_box(fr.f, u0, u1, v0, v1, g, sub[g].m, sub[g].h);
                double lg = 0.0;
                for (vbs_u32 k = 0u; k < fr.len; k++) {
                    vbq_nb rec = ar->nb[ar->lab[fr.off + k]];
                    double lo, hi;
                    vbq_eval(&rec, sub[g].m, sub[g].h, &lo, &hi);
                    lg = lo > lg ? lo : lg;
                }
                sub[g].LO = lg;
                sub[g].sdist = lg > 0.0 ? 0.5 / lg : (double)INFINITY;
            }
            evals += (double)(VBQ_NSUB * fr.len);
            vbs_u32 nlen = fr.len;
            if (!vbq_gather_sub(e, ar, o, i, sub, fr.rq, rq1, top, &nlen))
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
        for (vbs_u32 k = 0u; k < fr.len; k++) {
            vbs_u32 li = ar->lab[fr.off + k];
            vbq_nb rec = ar->nb[li];
            double lo, hi;
            vbq_eval(&rec, m, h, &lo, &hi);
            if (hi >= LO) {
                ar->lab[top + keep++] = li;
                if (rec.id > i)
                    owned++;
            }
        }
        evals += (double)fr.len;
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
        int act = closed ? vbq_decide(e, &fr, keep, owned) : 1;
        if (act == 0)
            continue;
        if (vbq_tie_cluster(ar->nb, ar->lab + top, keep, owned, i, act, closed)) {
#ifdef __OPENCL_C_VERSION__
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
#endif
        }
        if (act >= 2) {
            o->leaves++;
            if (act == 3)
                o->deep++;
            if (fr.level > o->maxlev)
                o->maxlev = fr.level;
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
                        if (jd < i)
                            continue;
                        if (!vbq_add_quad(ar, o, i, ja, jb, jd))
                            return;
                    }
                }
            }
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
            vbq_child(&fr, k, off, keep, &ch);
            ar->st[nst++] = ch;
        }
    }
    o->evals_k = (vbs_u32)(evals / 1000.0);
}
#endif /* VBQ_GROUP_ONLY */

#endif
