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
#if defined(__OPENCL_C_VERSION__) && defined(VBQ_WALK_V4_CL)
#define VBS_FABS __builtin_fabs
#else
#define VBS_FABS fabs
#endif

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

/* The rest of the shared math, in parts of one job each. They are included
 * here only and never include this header back: the kernels' embedding
 * (gpu/embed_kernels.cmake) inlines every include it meets, guards or not. */
#include "vbs_cell_shared.h"

#endif
