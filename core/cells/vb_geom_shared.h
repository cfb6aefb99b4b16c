/* The one copy of the sampling geometry of the seed paper (Sec. 3-5), compiled
 * as C11 by the reference backend (core/cells/sampler_ref.c) and the host stages
 * (culling, targeted search), and as OpenCL C by gpu/sample_envelope.cl and
 * gpu/vertices_newton.cl. Names carry the prefix vbs_ (sampler shared).
 *
 * Frame (Sec. 3.1): every base sphere i is translated to the origin and scaled
 * to radius 1 (a point site, R_i = 0, keeps scale 1: vbs_frame_scale). A
 * neighbour j becomes e = (c_j - c_i)/s, delta = (R_j - R_i)/s.
 * Rays leave the centre (Sec. 3.3) in direction d; the point at distance s is
 * s*d. Equidistance |s d - e| - R_j' = s - 1 squares to
 *     s^2 - 2 s d.e + |e|^2 = s^2 + 2 s delta + delta^2,
 * which is LINEAR in s because rays start at the centre (a focus of the
 * hyperboloid): s = (|e|^2 - delta^2) / (2 (d.e + delta)). The unsquared side
 * s + delta equals |e + delta d|^2 / (2 (d.e + delta)) >= 0 exactly when the
 * denominator is positive, so "denominator > 0" is the test for the correct
 * sheet of Fig. 3, and each ray meets the correct sheet at most once.
 *
 * Nothing here decides a sign that ends up in the output: the functions make
 * candidates; verify/ certifies them exactly. Floating-point expressions are
 * written out in a fixed order and contraction is off on both sides, so the
 * C and OpenCL builds evaluate the same IEEE operations. */
#ifndef VB_GEOM_SHARED_H
#define VB_GEOM_SHARED_H

#include "vb_cl_compat.h"

#ifdef __OPENCL_C_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF
#define VBS_ASSERT_LAYOUT(cond, msg)
#else
#include <math.h>
#define VBS_ASSERT_LAYOUT(cond, msg) _Static_assert(cond, msg)
#endif
typedef vb_u32 vbs_u32;
typedef vb_u64 vbs_u64;
#define VBS_GLOBAL VB_GLOBAL
#define VBS_FN VB_SHARED_FN
#define VBS_SQRT sqrt
#define VBS_FABS fabs

/* Colour of a ray that meets no bisector before the clip distance (Sec. 3.3:
 * the "bisector with infinity"). */
#define VBS_INF_COLOUR 0xffffffffu
/* Candidates one grid cell may emit (four triples, a few subdivided children). */
#define VBS_MAX_CAND 12
/* Sub-cells pending in the depth-first subdivision (3 per level + 1). */
#define VBS_STACK 40
/* Deepest subdivision the parameters may ask for (VBS_STACK covers it). */
#define VBS_MAX_DEPTH_LIMIT 12

/* A neighbour j of base i in i's normalised frame (the paper's "Calculate
 * Bisectors" kernel output). num = |e|^2 - delta^2 > 0 for spheres that are
 * not nested; nested pairs are never stored. */
typedef struct vbs_bisector {
    double ex, ey, ez;
    double delta;
    double num;
    vbs_u32 id;
    vbs_u32 pad;
} vbs_bisector;
VBS_ASSERT_LAYOUT(sizeof(vbs_bisector) == 48, "vbs_bisector layout shared with OpenCL");

/* One base sphere of a batch. Its bisectors are bis[bis_start ..
 * bis_start + bis_count); tile k of its 6*T*T direction tiles lists the
 * bisectors that can matter there in tile_idx[tile_off[tile_start + k] ..
 * tile_off[tile_start + k + 1]). */
typedef struct vbs_base {
    double cx, cy, cz, r;
    double scale;         /* frame scale s: R_i, or 1 for a point site */
    double clip;          /* clip distance in the normalised frame */
    vbs_u32 id;           /* sphere index */
    vbs_u32 bis_start, bis_count;
    vbs_u32 tile_start;
} vbs_base;
VBS_ASSERT_LAYOUT(sizeof(vbs_base) == 64, "vbs_base layout shared with OpenCL");

/* Parameters of one run. tol is in world units (the paper's epsilon). */
typedef struct vbs_params {
    double tol;
    double sing;          /* |det J| / (|J1||J2||J3|) below this: singular */
    vbs_u32 samples;      /* S: S x S rays per cube face, grid cells (S-1)^2 */
    vbs_u32 tiles;        /* T: T x T culling tiles per cube face */
    vbs_u32 max_depth;    /* subdivision depth (Sec. 5.1) */
    vbs_u32 max_iter;     /* Newton iterations before "oscillates" */
} vbs_params;
VBS_ASSERT_LAYOUT(sizeof(vbs_params) == 32, "vbs_params layout shared with OpenCL");

/* A candidate vertex from one base's cell: ids[0] = base, ids[1..3] = the
 * three colours; world point and tangent radius; cell = index of the grid
 * cell that produced it (for a deterministic order), seq = its rank among
 * that cell's candidates; flags = VBS_CF_*. */
typedef struct vbs_cand {
    double x, y, z, t;
    vbs_u32 ids[4];
    vbs_u32 cell;
    vbs_u32 seq;
    vbs_u32 flags;
    vbs_u32 pad;
} vbs_cand;
VBS_ASSERT_LAYOUT(sizeof(vbs_cand) == 64, "vbs_cand layout shared with OpenCL");

#define VBS_CF_SUBDIVIDED 1u  /* found in a sub-cell (Sec. 5.1) */
#define VBS_CF_FOURCOLOUR 2u  /* from a four-colour cell (Sec. 5.2) */
#define VBS_CF_RESTARTED 4u   /* needed the wrong-sheet restart (Sec. 5.3) */
#define VBS_CF_TARGETED 8u    /* found by the targeted search (Sec. 5.5) */

/* ---- Sec. 3.1: rays through the six faces of the bounding cube ---------- */

/* Face f in 0..5: axis f/2, sign + for even f. (u, v) in [-1, 1]^2 map to the
 * cube point with that axis at +-1 and the next two axes (cyclically) u, v. */
VBS_FN void vbs_face_dir(vbs_u32 f, double u, double v, double d[3])
{
    vbs_u32 a = f / 2u;
    double sgn = (f & 1u) ? -1.0 : 1.0;
    double inv = 1.0 / VBS_SQRT(u * u + v * v + 1.0);
    d[a] = sgn * inv;
    d[(a + 1u) % 3u] = u * inv;
    d[(a + 2u) % 3u] = v * inv;
}

/* Grid coordinate k in 0..S-1 of a face: -1 + 2k/(S-1), so the cube's edges
 * are sampled and the grid cells of the six faces cover every direction. */
VBS_FN double vbs_sample_coord(vbs_u32 k, vbs_u32 S)
{
    return (2.0 * (double)k) / (double)(S - 1u) - 1.0;
}

/* Inverse of vbs_face_dir for any non-zero direction: the face of the axis
 * with the largest |component| (lowest axis on ties). */
VBS_FN vbs_u32 vbs_dir_face(const double d[3], double *u, double *v)
{
    vbs_u32 a = 0u;
    if (VBS_FABS(d[1]) > VBS_FABS(d[a]))
        a = 1u;
    if (VBS_FABS(d[2]) > VBS_FABS(d[a]))
        a = 2u;
    double m = VBS_FABS(d[a]);
    *u = d[(a + 1u) % 3u] / m;
    *v = d[(a + 2u) % 3u] / m;
    return 2u * a + (d[a] < 0.0 ? 1u : 0u);
}

/* Culling tile (0..T-1) of a face coordinate in [-1, 1]. */
VBS_FN vbs_u32 vbs_tile_of(double u, vbs_u32 T)
{
    double w = (u + 1.0) * 0.5 * (double)T;
    if (!(w > 0.0))
        return 0u;
    vbs_u32 k = (vbs_u32)w;
    return k >= T ? T - 1u : k;
}

/* ---- Sec. 3.2: bisectors in the normalised frame ------------------------ */

/* Scale of a base's normalised frame: its radius, or 1 for a point site. */
VBS_FN double vbs_frame_scale(double r)
{
    return r > 0.0 ? r : 1.0;
}

/* Fills the bisector of base (ci, Ri) and sphere id j (cj, Rj) in the frame
 * of scale sc (vbs_frame_scale(Ri)). Returns 0 when the spheres are nested
 * (|e| <= |delta|): then one cell never reaches the other sphere, and the
 * pair has no bisector to store. */
VBS_FN int vbs_bisector_make(double cix, double ciy, double ciz, double ri, double sc,
                             double cjx, double cjy, double cjz, double rj, vbs_u32 j,
                             vbs_bisector *b)
{
    b->ex = (cjx - cix) / sc;
    b->ey = (cjy - ciy) / sc;
    b->ez = (cjz - ciz) / sc;
    b->delta = (rj - ri) / sc;
    b->num = (b->ex * b->ex + b->ey * b->ey + b->ez * b->ez) - b->delta * b->delta;
    b->id = j;
    b->pad = 0u;
    return b->num > 0.0;
}

/* ---- Sec. 3.3: ray / bisector and the lower envelope -------------------- */

/* Distance from the centre along unit ray d to the correct sheet of the
 * bisector, or a negative value when the ray misses it. */
VBS_FN double vbs_ray_hit(double ex, double ey, double ez, double delta, double num,
                          const double d[3])
{
    double g = (d[0] * ex + d[1] * ey + d[2] * ez) + delta;
    if (!(g > 0.0))
        return -1.0;
    return num / (g + g);
}

/* Lower envelope over a list of bisectors: *s gets the smallest hit and the
 * result is its sphere id (ties: the lowest id, so every backend agrees), or
 * VBS_INF_COLOUR when nothing is hit within `clip`. */
VBS_FN vbs_u32 vbs_envelope(const VBS_GLOBAL vbs_bisector *bis,
                            const VBS_GLOBAL vbs_u32 *list, vbs_u32 n, double clip,
                            const double d[3], double *s)
{
    double best = clip;
    vbs_u32 colour = VBS_INF_COLOUR;
    for (vbs_u32 k = 0u; k < n; k++) {
        const VBS_GLOBAL vbs_bisector *b = bis + list[k];
        double h = vbs_ray_hit(b->ex, b->ey, b->ez, b->delta, b->num, d);
        if (h >= 0.0 && (h < best || (h == best && b->id < colour))) {
            best = h;
            colour = b->id;
        }
    }
    *s = best;
    return colour;
}

/* Envelope of the ray (face f, u, v) of batch base `bb` using its tile list. */
VBS_FN vbs_u32 vbs_envelope_at(const VBS_GLOBAL vbs_base *base,
                               const VBS_GLOBAL vbs_bisector *bis,
                               const VBS_GLOBAL vbs_u32 *tile_off,
                               const VBS_GLOBAL vbs_u32 *tile_idx, vbs_u32 T, vbs_u32 f,
                               double u, double v, double d[3], double *s)
{
    vbs_face_dir(f, u, v, d);
    /* A sub-cell may reach past its face (targeted search near a cube edge):
     * the culling tile is the one of the face the ray really crosses. */
    if (VBS_FABS(u) > 1.0 || VBS_FABS(v) > 1.0)
        f = vbs_dir_face(d, &u, &v);
    vbs_u32 tile = base->tile_start + f * T * T + vbs_tile_of(v, T) * T + vbs_tile_of(u, T);
    vbs_u32 lo = tile_off[tile], hi = tile_off[tile + 1u];
    return vbs_envelope(bis, tile_idx + lo, hi - lo, base->clip, d, s);
}

/* ---- Sec. 5: Newton-Raphson on three bisectors -------------------------- */

/* Bisector function of Eq. 3 in the normalised frame, and its gradient:
 * with L = |e|^2 - delta^2 - 2 P.e, the two sheets are L = +-2 delta |P| and
 * f = L^2 - 4 delta^2 |P|^2; for equal radii the plane L = 0 (Eq. 4). */
VBS_FN double vbs_bisector_eval(const vbs_bisector *b, const double P[3], double grad[3])
{
    double pe = P[0] * b->ex + P[1] * b->ey + P[2] * b->ez;
    double L = b->num - 2.0 * pe;
    if (b->delta == 0.0) {
        grad[0] = -2.0 * b->ex;
        grad[1] = -2.0 * b->ey;
        grad[2] = -2.0 * b->ez;
        return L;
    }
    double dd = 4.0 * b->delta * b->delta;
    double pp = P[0] * P[0] + P[1] * P[1] + P[2] * P[2];
    grad[0] = -4.0 * L * b->ex - 2.0 * dd * P[0];
    grad[1] = -4.0 * L * b->ey - 2.0 * dd * P[1];
    grad[2] = -4.0 * L * b->ez - 2.0 * dd * P[2];
    return L * L - dd * pp;
}

/* Signed equidistance defect |P - e| - |P| - delta: zero on the correct sheet. */
VBS_FN double vbs_defect(const vbs_bisector *b, const double P[3])
{
    double qx = P[0] - b->ex, qy = P[1] - b->ey, qz = P[2] - b->ez;
    double np = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
    return VBS_SQRT(qx * qx + qy * qy + qz * qz) - np - b->delta;
}

#define VBS_NEWTON_OK 0
#define VBS_NEWTON_SINGULAR 1
#define VBS_NEWTON_DIVERGED 2

/* Eq. 9 from P (updated in place) until the step is below 1e-13 of |P|+1;
 * VBS_NEWTON_SINGULAR when the normalised Jacobian determinant falls under
 * `sing` (Fig. 6/7), VBS_NEWTON_DIVERGED after max_iter steps (Fig. 8). */
VBS_FN int vbs_newton(const vbs_bisector *b0, const vbs_bisector *b1,
                      const vbs_bisector *b2, double sing, vbs_u32 max_iter, double P[3])
{
    for (vbs_u32 it = 0u; it < max_iter; it++) {
        double J0[3], J1[3], J2[3];
        double F0 = vbs_bisector_eval(b0, P, J0);
        double F1 = vbs_bisector_eval(b1, P, J1);
        double F2 = vbs_bisector_eval(b2, P, J2);
        /* Cofactors of J (rows J0, J1, J2). */
        double c00 = J1[1] * J2[2] - J1[2] * J2[1];
        double c01 = J1[2] * J2[0] - J1[0] * J2[2];
        double c02 = J1[0] * J2[1] - J1[1] * J2[0];
        double det = J0[0] * c00 + J0[1] * c01 + J0[2] * c02;
        double n0 = VBS_SQRT(J0[0] * J0[0] + J0[1] * J0[1] + J0[2] * J0[2]);
        double n1 = VBS_SQRT(J1[0] * J1[0] + J1[1] * J1[1] + J1[2] * J1[2]);
        double n2 = VBS_SQRT(J2[0] * J2[0] + J2[1] * J2[1] + J2[2] * J2[2]);
        if (!(VBS_FABS(det) > sing * (n0 * n1 * n2)))
            return VBS_NEWTON_SINGULAR;
        double c10 = J0[2] * J2[1] - J0[1] * J2[2];
        double c11 = J0[0] * J2[2] - J0[2] * J2[0];
        double c12 = J0[1] * J2[0] - J0[0] * J2[1];
        double c20 = J0[1] * J1[2] - J0[2] * J1[1];
        double c21 = J0[2] * J1[0] - J0[0] * J1[2];
        double c22 = J0[0] * J1[1] - J0[1] * J1[0];
        /* J^-1 = adj(J)/det, adj = transposed cofactors. */
        double dx = (c00 * F0 + c10 * F1 + c20 * F2) / det;
        double dy = (c01 * F0 + c11 * F1 + c21 * F2) / det;
        double dz = (c02 * F0 + c12 * F1 + c22 * F2) / det;
        P[0] -= dx;
        P[1] -= dy;
        P[2] -= dz;
        double step = VBS_SQRT(dx * dx + dy * dy + dz * dz);
        double scale = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]) + 1.0;
        if (step <= 1e-13 * scale)
            return VBS_NEWTON_OK;
    }
    return VBS_NEWTON_DIVERGED;
}

/* ---- Sec. 4-5: one grid cell, with subdivision and restarts ------------- */

typedef struct vbs_quad {
    double u0, v0, h;     /* lower corner and side in face coordinates */
    vbs_u32 col[4];       /* colours at (u0,v0), (u0+h,v0), (u0,v0+h), (u0+h,v0+h) */
    vbs_u32 depth;
} vbs_quad;

/* Where a grid cell's candidates go: a private array of `cap` entries. */
typedef struct vbs_emit {
    vbs_cand *out;
    vbs_u32 cap, n;
    vbs_u32 overflow;     /* candidates that did not fit */
    vbs_u32 cell;
} vbs_emit;

/* Copies the bisector of sphere `id` out of the base's list (private copy for
 * Newton). Returns 0 if the id is not a neighbour of the base. */
VBS_FN int vbs_find_bisector(const VBS_GLOBAL vbs_base *base,
                             const VBS_GLOBAL vbs_bisector *bis, vbs_u32 id,
                             vbs_bisector *out)
{
    /* Bisectors of a base are stored sorted by id: binary search. */
    vbs_u32 lo = base->bis_start, hi = base->bis_start + base->bis_count;
    while (lo < hi) {
        vbs_u32 mid = lo + (hi - lo) / 2u;
        if (bis[mid].id < id)
            lo = mid + 1u;
        else
            hi = mid;
    }
    if (lo >= base->bis_start + base->bis_count || bis[lo].id != id)
        return 0;
    *out = bis[lo];
    return 1;
}

/* Tries to find the vertex of the triple from the ray d (unit): start at the
 * triple's own lower envelope along d (Sec. 5), and when the converged point
 * is not equidistant (a wrong sheet, Sec. 5.3) restart from each of the three
 * ray/bisector hits. Accepts only points whose direction lies within angle
 * `cosmax` of d. Returns 1 with P set, 0 on failure; *flags gets
 * VBS_CF_RESTARTED when a restart was needed. */
VBS_FN int vbs_solve_triple(const vbs_bisector tri[3], const double d[3], double eq_tol,
                            double cosmax, double sing, vbs_u32 max_iter, double P[3],
                            vbs_u32 *flags)
{
    double hits[3];
    double s0 = -1.0;
    for (int k = 0; k < 3; k++) {
        hits[k] = vbs_ray_hit(tri[k].ex, tri[k].ey, tri[k].ez, tri[k].delta, tri[k].num, d);
        if (hits[k] >= 0.0 && (s0 < 0.0 || hits[k] < s0))
            s0 = hits[k];
    }
    if (s0 < 0.0)
        return 0;
    /* Attempt 0: the envelope point; attempts 1..3: each bisector's hit. */
    for (int attempt = 0; attempt < 4; attempt++) {
        double s = attempt == 0 ? s0 : hits[attempt - 1];
        if (s < 0.0 || (attempt > 0 && s == s0))
            continue;
        P[0] = s * d[0];
        P[1] = s * d[1];
        P[2] = s * d[2];
        if (vbs_newton(&tri[0], &tri[1], &tri[2], sing, max_iter, P) != VBS_NEWTON_OK)
            return 0; /* singular or oscillating: the caller subdivides */
        double np = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
        if (!(np > 0.0))
            return 0;
        int equi = 1;
        for (int k = 0; k < 3; k++)
            if (!(VBS_FABS(vbs_defect(&tri[k], P)) <= eq_tol))
                equi = 0;
        if (!equi) {
            *flags |= VBS_CF_RESTARTED;
            continue;
        }
        double c = (P[0] * d[0] + P[1] * d[1] + P[2] * d[2]) / np;
        return c >= cosmax;
    }
    return 0;
}

VBS_FN void vbs_emit_point(const VBS_GLOBAL vbs_base *base, vbs_u32 a, vbs_u32 b, vbs_u32 c,
                           const double P[3], vbs_u32 flags, vbs_emit *em)
{
    if (em->n >= em->cap) {
        em->overflow++;
        return;
    }
    vbs_cand *o = em->out + em->n;
    double np = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
    o->x = base->cx + base->scale * P[0];
    o->y = base->cy + base->scale * P[1];
    o->z = base->cz + base->scale * P[2];
    o->t = base->scale * np - base->r;
    o->ids[0] = base->id;
    o->ids[1] = a;
    o->ids[2] = b;
    o->ids[3] = c;
    o->cell = em->cell;
    o->seq = em->n;
    o->flags = flags;
    o->pad = 0u;
    em->n++;
}

/* Unit average of corner rays `mask` (bit k = corner k) of quad q on face f;
 * *cosr gets the cosine of the largest angle from it to those corners. */
VBS_FN void vbs_quad_ray(vbs_u32 f, const vbs_quad *q, vbs_u32 mask, double d[3], double *cosr)
{
    double cd[4][3];
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (vbs_u32 k = 0u; k < 4u; k++) {
        double u = q->u0 + ((k & 1u) ? q->h : 0.0);
        double v = q->v0 + ((k & 2u) ? q->h : 0.0);
        vbs_face_dir(f, u, v, cd[k]);
        if (mask & (1u << k)) {
            sx += cd[k][0];
            sy += cd[k][1];
            sz += cd[k][2];
        }
    }
    double n = VBS_SQRT(sx * sx + sy * sy + sz * sz);
    d[0] = sx / n;
    d[1] = sy / n;
    d[2] = sz / n;
    double cmin = 1.0;
    for (vbs_u32 k = 0u; k < 4u; k++) {
        double c = cd[k][0] * d[0] + cd[k][1] * d[1] + cd[k][2] * d[2];
        if (c < cmin)
            cmin = c;
    }
    *cosr = cmin;
}

/* Processes one grid cell of base `base` on face f (Sec. 4-5): three finite
 * colours -> Newton from the averaged ray; four -> every triple from the
 * average of its three corners, and subdivision when they disagree (5.2);
 * singular Jacobian, oscillation or a failed restart -> subdivision into four
 * children with five new rays (5.1), down to p->max_depth. Rays of colour
 * VBS_INF_COLOUR mark a vertex at infinity and take part in no triple. */
VBS_FN void vbs_process_cell(const VBS_GLOBAL vbs_base *base,
                             const VBS_GLOBAL vbs_bisector *bis,
                             const VBS_GLOBAL vbs_u32 *tile_off,
                             const VBS_GLOBAL vbs_u32 *tile_idx, const vbs_params *p,
                             vbs_u32 f, const vbs_quad *root, vbs_u32 extra_flags,
                             vbs_emit *em)
{
    vbs_quad stack[VBS_STACK];
    vbs_u32 top = 0u;
    stack[top++] = *root;
    double eq_tol = p->tol / base->scale;
    while (top > 0u) {
        vbs_quad q = stack[--top];
        /* Distinct finite colours and the corners that carry each. */
        vbs_u32 cols[4], masks[4], nc = 0u;
        for (vbs_u32 k = 0u; k < 4u; k++) {
            vbs_u32 c = q.col[k];
            if (c == VBS_INF_COLOUR)
                continue;
            vbs_u32 m = 0u;
            while (m < nc && cols[m] != c)
                m++;
            if (m == nc) {
                cols[nc] = c;
                masks[nc] = 0u;
                nc++;
            }
            masks[m] |= 1u << k;
        }
        if (nc < 3u)
            continue;
        vbs_u32 flags = extra_flags | (q.depth > root->depth ? VBS_CF_SUBDIVIDED : 0u);
        int failed = 0;
        if (nc == 3u) {
            vbs_bisector tri[3];
            double d[3], cosr, P[3];
            vbs_u32 fl = flags;
            vbs_quad_ray(f, &q, 15u, d, &cosr);
            /* Accept points within twice the cell's angular radius. */
            double cosmax = 2.0 * cosr * cosr - 1.0;
            if (vbs_find_bisector(base, bis, cols[0], &tri[0]) &&
                vbs_find_bisector(base, bis, cols[1], &tri[1]) &&
                vbs_find_bisector(base, bis, cols[2], &tri[2]) &&
                vbs_solve_triple(tri, d, eq_tol, cosmax, p->sing, p->max_iter, P, &fl))
                vbs_emit_point(base, cols[0], cols[1], cols[2], P, fl, em);
            else
                failed = 1;
        } else {
            /* Four colours: one triple per omitted colour, started from the
             * average of the three corners that carry the kept colours. */
            double pts[4][3];
            vbs_u32 ok[4], fls[4];
            vbs_u32 nok = 0u;
            double d4[3], cos4;
            vbs_quad_ray(f, &q, 15u, d4, &cos4);
            double cosmax = 2.0 * cos4 * cos4 - 1.0;
            for (vbs_u32 skip = 0u; skip < 4u; skip++) {
                vbs_bisector tri[3];
                vbs_u32 m = 0u, mask = 0u;
                ok[skip] = 0u;
                fls[skip] = flags | VBS_CF_FOURCOLOUR;
                int have = 1;
                for (vbs_u32 k = 0u; k < 4u; k++) {
                    if (k == skip)
                        continue;
                    have &= vbs_find_bisector(base, bis, cols[k], &tri[m]);
                    mask |= masks[k];
                    m++;
                }
                double d[3], cosr;
                vbs_quad_ray(f, &q, mask, d, &cosr);
                if (have && vbs_solve_triple(tri, d, eq_tol, cosmax, p->sing, p->max_iter,
                                             pts[skip], &fls[skip])) {
                    ok[skip] = 1u;
                    nok++;
                }
            }
            /* Agreement: every converged triple at one point (within tol). */
            int agree = nok == 4u;
            for (vbs_u32 a = 0u; a < 4u && agree; a++)
                for (vbs_u32 b = a + 1u; b < 4u; b++) {
                    double dx = pts[a][0] - pts[b][0], dy = pts[a][1] - pts[b][1],
                           dz = pts[a][2] - pts[b][2];
                    if (!(VBS_SQRT(dx * dx + dy * dy + dz * dz) <= eq_tol))
                        agree = 0;
                }
            if (agree || q.depth >= p->max_depth) {
                for (vbs_u32 skip = 0u; skip < 4u; skip++) {
                    if (!ok[skip])
                        continue;
                    vbs_u32 t3[3], m = 0u;
                    for (vbs_u32 k = 0u; k < 4u; k++)
                        if (k != skip)
                            t3[m++] = cols[k];
                    vbs_emit_point(base, t3[0], t3[1], t3[2], pts[skip], fls[skip], em);
                }
            } else {
                failed = 1;
            }
        }
        if (!failed || q.depth >= p->max_depth || top + 4u > VBS_STACK)
            continue;
        /* Sec. 5.1: five new rays (edge midpoints and centre), four children. */
        double hh = 0.5 * q.h, d[3], s;
        vbs_u32 T = p->tiles;
        vbs_u32 cb = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0, d, &s);
        vbs_u32 cl = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0, q.v0 + hh, d, &s);
        vbs_u32 cm = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0 + hh, d, &s);
        vbs_u32 cr = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + q.h, q.v0 + hh, d, &s);
        vbs_u32 ct = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0 + q.h, d, &s);
        vbs_quad c;
        c.h = hh;
        c.depth = q.depth + 1u;
        /* Pushed in reverse so the lower-left child is processed first. */
        c.u0 = q.u0 + hh; c.v0 = q.v0 + hh;
        c.col[0] = cm; c.col[1] = cr; c.col[2] = ct; c.col[3] = q.col[3];
        stack[top++] = c;
        c.u0 = q.u0; c.v0 = q.v0 + hh;
        c.col[0] = cl; c.col[1] = cm; c.col[2] = q.col[2]; c.col[3] = ct;
        stack[top++] = c;
        c.u0 = q.u0 + hh; c.v0 = q.v0;
        c.col[0] = cb; c.col[1] = q.col[1]; c.col[2] = cm; c.col[3] = cr;
        stack[top++] = c;
        c.u0 = q.u0; c.v0 = q.v0;
        c.col[0] = q.col[0]; c.col[1] = cb; c.col[2] = cl; c.col[3] = cm;
        stack[top++] = c;
    }
}

/* Grid cell (f, iu, iv) of a batch base, corners read from the colour array
 * of that base (6*S*S entries, face-major, then v, then u). */
VBS_FN void vbs_grid_quad(const VBS_GLOBAL vbs_u32 *colours, vbs_u32 S, vbs_u32 f,
                          vbs_u32 iu, vbs_u32 iv, vbs_quad *q)
{
    const VBS_GLOBAL vbs_u32 *c = colours + f * S * S;
    q->u0 = vbs_sample_coord(iu, S);
    q->v0 = vbs_sample_coord(iv, S);
    q->h = vbs_sample_coord(iu + 1u, S) - q->u0;
    q->col[0] = c[iv * S + iu];
    q->col[1] = c[iv * S + iu + 1u];
    q->col[2] = c[(iv + 1u) * S + iu];
    q->col[3] = c[(iv + 1u) * S + iu + 1u];
    q->depth = 0u;
}

/* ---- Tangent spheres of four spheres, in double (candidates only) ------ */

/* Points p and radii t with |p - c_k| = t + r_k for the four spheres s[k]
 * (x, y, z, r each), relative to sphere 0: with q = p - c_0, e_k = c_k - c_0,
 * the differences give three linear equations 2 e_k.q + 2 (r_k - r_0) t =
 * |e_k|^2 - r_k^2 + r_0^2. The best-conditioned 3x3 minor of [e_k | dr_k]
 * gives three unknowns as u + w s in the fourth, and |q|^2 = (t + r_0)^2
 * becomes a quadratic in s. Writes up to two roots (x, y, z, t) to out and
 * returns their number; 0 when the minor is singular (the exact certifier
 * handles such sets) or no real root has t + r_k >= 0 for all k. */
VBS_FN int vbs_tangent_roots(const double s[4][4], double out[2][4])
{
    double M[3][4], b[3];
    for (int k = 0; k < 3; k++) {
        double ex = s[k + 1][0] - s[0][0], ey = s[k + 1][1] - s[0][1], ez = s[k + 1][2] - s[0][2];
        M[k][0] = ex;
        M[k][1] = ey;
        M[k][2] = ez;
        M[k][3] = s[k + 1][3] - s[0][3];
        b[k] = 0.5 * ((ex * ex + ey * ey + ez * ez) - s[k + 1][3] * s[k + 1][3] + s[0][3] * s[0][3]);
    }
    /* Free column: the one whose removal leaves the largest |det|. */
    int free_col = -1;
    double best = 0.0, bdet = 0.0;
    int cols[3];
    for (int f = 0; f < 4; f++) {
        int c[3], m = 0;
        for (int j = 0; j < 4; j++)
            if (j != f)
                c[m++] = j;
        double det = M[0][c[0]] * (M[1][c[1]] * M[2][c[2]] - M[1][c[2]] * M[2][c[1]]) -
                     M[0][c[1]] * (M[1][c[0]] * M[2][c[2]] - M[1][c[2]] * M[2][c[0]]) +
                     M[0][c[2]] * (M[1][c[0]] * M[2][c[1]] - M[1][c[1]] * M[2][c[0]]);
        if (VBS_FABS(det) > best) {
            best = VBS_FABS(det);
            bdet = det;
            free_col = f;
            cols[0] = c[0];
            cols[1] = c[1];
            cols[2] = c[2];
        }
    }
    double scale = 0.0;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < 4; j++)
            scale += M[k][j] * M[k][j];
    if (free_col < 0 || !(best > 1e-12 * scale * VBS_SQRT(scale)))
        return 0;
    /* Solve A x = r for r = b (u) and r = -M[:,free] (w) by Cramer. */
    double u[4] = {0.0, 0.0, 0.0, 0.0}, w[4] = {0.0, 0.0, 0.0, 0.0};
    for (int pass = 0; pass < 2; pass++) {
        double r[3];
        for (int k = 0; k < 3; k++)
            r[k] = pass == 0 ? b[k] : -M[k][free_col];
        for (int j = 0; j < 3; j++) {
            double A[3][3];
            for (int k = 0; k < 3; k++)
                for (int m = 0; m < 3; m++)
                    A[k][m] = m == j ? r[k] : M[k][cols[m]];
            double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
            if (pass == 0)
                u[cols[j]] = det / bdet;
            else
                w[cols[j]] = det / bdet;
        }
    }
    w[free_col] = 1.0;
    double r0 = s[0][3];
    double qa = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - w[3] * w[3];
    double qb = 2.0 * ((u[0] * w[0] + u[1] * w[1] + u[2] * w[2] - u[3] * w[3]) - r0 * w[3]);
    double qc = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - u[3] * u[3]) - 2.0 * r0 * u[3] - r0 * r0;
    double roots[2];
    int nr = 0;
    double mag = VBS_FABS(qa) + VBS_FABS(qb) + VBS_FABS(qc);
    if (VBS_FABS(qa) <= 1e-14 * mag) {
        if (VBS_FABS(qb) > 0.0)
            roots[nr++] = -qc / qb;
    } else {
        double disc = qb * qb - 4.0 * qa * qc;
        if (disc < 0.0 && disc > -1e-12 * qb * qb)
            disc = 0.0;
        if (disc >= 0.0) {
            double sq = VBS_SQRT(disc);
            /* Numerically stable pair of roots. */
            double qq = -0.5 * (qb + (qb >= 0.0 ? sq : -sq));
            roots[nr++] = qq / qa;
            if (qq != 0.0 && disc > 0.0)
                roots[nr++] = qc / qq;
        }
    }
    int n = 0;
    for (int k = 0; k < nr; k++) {
        double X[4];
        for (int j = 0; j < 4; j++)
            X[j] = u[j] + w[j] * roots[k];
        int ok = 1;
        double tol = 1e-9 * (VBS_SQRT(scale) + VBS_FABS(X[3]) + r0);
        for (int m = 0; m < 4 && ok; m++) {
            double px = X[0] + s[0][0] - s[m][0], py = X[1] + s[0][1] - s[m][1],
                   pz = X[2] + s[0][2] - s[m][2];
            double dist = VBS_SQRT(px * px + py * py + pz * pz);
            if (!(VBS_FABS(dist - (X[3] + s[m][3])) <= tol))
                ok = 0;
        }
        if (!ok)
            continue;
        out[n][0] = X[0] + s[0][0];
        out[n][1] = X[1] + s[0][1];
        out[n][2] = X[2] + s[0][2];
        out[n][3] = X[3];
        n++;
    }
    return n;
}

/* Colour of grid ray (f, iu, iv) of a base: the envelope stage per ray. */
VBS_FN vbs_u32 vbs_ray_colour(const VBS_GLOBAL vbs_base *base,
                              const VBS_GLOBAL vbs_bisector *bis,
                              const VBS_GLOBAL vbs_u32 *tile_off,
                              const VBS_GLOBAL vbs_u32 *tile_idx, vbs_u32 T, vbs_u32 S,
                              vbs_u32 f, vbs_u32 iu, vbs_u32 iv)
{
    double d[3], s;
    return vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, vbs_sample_coord(iu, S),
                           vbs_sample_coord(iv, S), d, &s);
}

/* The vertex stage for grid cell `cell` (f * (S-1)^2 + iv * (S-1) + iu) of a
 * base whose 6*S*S colours are `colours`; candidates go to em. */
VBS_FN void vbs_cell_vertices(const VBS_GLOBAL vbs_base *base,
                              const VBS_GLOBAL vbs_bisector *bis,
                              const VBS_GLOBAL vbs_u32 *tile_off,
                              const VBS_GLOBAL vbs_u32 *tile_idx, const vbs_params *p,
                              const VBS_GLOBAL vbs_u32 *colours, vbs_u32 cell, vbs_emit *em)
{
    vbs_u32 S = p->samples, g = S - 1u;
    vbs_u32 f = cell / (g * g), r = cell % (g * g);
    vbs_u32 iv = r / g, iu = r % g;
    vbs_quad q;
    vbs_grid_quad(colours, S, f, iu, iv, &q);
    /* Most cells see one or two colours: leave before any setup. */
    if (q.col[0] == q.col[1] && q.col[2] == q.col[3])
        return;
    if (q.col[0] == q.col[2] && q.col[1] == q.col[3])
        return;
    em->cell = cell;
    vbs_process_cell(base, bis, tile_off, tile_idx, p, f, &q, 0u, em);
}

#endif
