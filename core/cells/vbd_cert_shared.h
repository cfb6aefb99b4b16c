/* The certification filter of a proposed quadruple, shared by the OpenCL
 * kernel (gpu/cert_filter.cl) and its plain-C twin (core/cells/cert_filter.c):
 * one copy of the arithmetic, compiled as C11 and as OpenCL C. Names carry
 * the prefix vbd_ (device certification).
 *
 * What it decides. A quadruple q (sorted ids, base a = q[0], rows q[1..3])
 * is solved as the exact certifier solves it (verify/certify/tangent_solver.c,
 * verify/exact/quad_filter.c): in scaled integers (input times 10^E),
 * u = (p - c_a, t + R_a) lies on the line u = (U + mu v) / (2 D) and
 * mu = (-B + sigma sqrt(delta)) / A, root 0 being sigma = +1. Each root gets
 * a verdict:
 *   VBD_VERTEX  every sign proven: t + R_i > 0 for the four members, and
 *               every other sphere strictly outside the tangent ball
 *               (|p - c_j| > t + R_j), so the root is a vertex of degree 4
 *               with members q (the exact stage would say so too);
 *   VBD_NOT     one sign proven the wrong way: no real root (delta < 0), a
 *               member with t + R_i < 0, or a sphere strictly inside the
 *               tangent ball (|p - c_j| < t + R_j with t + R_j > 0);
 *   VBD_OPEN    anything else (the host's filter and exact stage decide).
 * A root is only ever judged when D != 0 and A != 0 are proven, where the
 * exact solver takes the same unknowns (the free s, k = 3) and root order,
 * so "root r" names the same exact point on both sides.
 *
 * Error bound (the proof the verdicts rest on). Every quantity is an
 * interval [lo, hi] of doubles that contains the exact value; each
 * operation is evaluated in round-to-nearest and its bounds are then moved
 * one double outward (vb_pred, vb_succ). IEEE 754 binary64 returns, for
 * an exact result x of +, -, *, / or sqrt on doubles, the double r nearest
 * to x; the gap between r and its neighbour on x's side is at least twice
 * |x - r|, so pred(r) <= x <= succ(r) (also for subnormal results and at
 * overflow, where pred(+inf) = DBL_MAX); see core/vb_ia_shared.h, whose
 * argument this is. OpenCL C (1.2, section 7.4) requires exactly this
 * correct rounding of double +, -, *, / and sqrt, and conversion of a long
 * to double rounds to nearest; the kernel is built without fast-math or
 * mad and with FP_CONTRACT OFF (an FMA would round once and stay enclosed
 * anyway). An integer below 2^53 converts exactly; a larger one is
 * enclosed by [pred, succ] of its conversion. The corner rule gives the
 * product of two intervals; a division's denominator must exclude 0; a
 * sign is taken only from lo > 0 or hi < 0, so infinite or NaN bounds
 * answer "open". Hence each verdict's signs are those of the exact values.
 *
 * Which spheres are tested. A sphere j can touch or enter the tangent ball
 * only if |c_j - p| <= t + R_j <= s + rmax - R_a (s = t + R_a, rmax the
 * largest radius), so its centre lies in the box p +- that radius. The
 * spheres are kept in a uniform grid keyed by vbd_cell of their centres'
 * nearest doubles; vbd_cell (a subtraction, a product by a positive
 * constant, floor, clamping) is monotone, and rounding to nearest is
 * monotone, so an exact centre in [lo, hi] (bounds doubles) has its key
 * between vbd_cell(lo) and vbd_cell(hi): the cells scanned hold every
 * sphere that could matter. A query box of more than VBD_MAX_CELLS cells
 * (a huge tangent ball at the hull) leaves the root open rather than scan.
 *
 * The result of a quadruple does not depend on the order the spheres are
 * visited (VBD_NOT iff some sphere or member sign proves it), so the kernel
 * and the twin give the same byte. */
#ifndef VBD_CERT_SHARED_H
#define VBD_CERT_SHARED_H

#include "vb_ia_shared.h"

/* Per-root verdicts, two bits each: root 0 in bits 0-1, root 1 in 2-3. */
#define VBD_OPEN 0u
#define VBD_VERTEX 1u
#define VBD_NOT 2u
#define VBD_ROOT(v, r) (((v) >> (2 * (r))) & 3u)

/* Cells one root may scan before it is left open. */
#define VBD_MAX_CELLS 4096

/* The grid of the spheres' scaled centres (cert_filter.c builds it). */
typedef struct vbd_grid {
    double ox, oy, oz; /* corner (scaled units) */
    double inv;        /* 1 / cell side */
    vb_u32 nx, ny, nz;
    vb_i64 rmax;       /* largest scaled radius */
} vbd_grid;

/* The grid key of a coordinate along an axis of n cells (monotone in x). */
VB_SHARED_FN vb_u32 vbd_cell(double x, double o, double inv, vb_u32 n)
{
    double f = floor((x - o) * inv);
    if (!(f >= 0.0))
        return 0u;
    if (f >= (double)(n - 1u))
        return n - 1u;
    return (vb_u32)f;
}

/* The i-th index of [lo, hi] counted from m outward (m, m - 1, m + 1,
 * m - 2, ...; m clamped into the range), or -1 for an i that falls
 * outside: i = 0 .. 2 (hi - lo) visits every index once. */
VB_SHARED_FN vb_i64 vbd_around(vb_u32 lo, vb_u32 hi, vb_u32 m, vb_u32 i)
{
    vb_i64 c = (vb_i64)(m < lo ? lo : m > hi ? hi : m);
    vb_i64 d = (vb_i64)((i + 1u) / 2u);
    vb_i64 x = (i & 1u) ? c - d : c + d;
    return x < (vb_i64)lo || x > (vb_i64)hi ? -1 : x;
}

/* 3x3 determinant of columns c0, c1, c2 of e, expanded along row 0 with the
 * minors M of rows 1 and 2 (M[a * 5 + b], a < b). */
VB_SHARED_FN vb_ia vbd_det3(const vb_ia *e, const vb_ia *M, int c0, int c1, int c2)
{
    vb_ia t = vb_ia_sub(vb_ia_mul(e[c0], M[c1 * 5 + c2]), vb_ia_mul(e[c1], M[c0 * 5 + c2]));
    return vb_ia_add(t, vb_ia_mul(e[c2], M[c0 * 5 + c1]));
}

/* det3 in 64-bit integers of row r0 and the minors Mi (the caller proves
 * that no product or sum overflows). */
VB_SHARED_FN vb_i64 vbd_det3i(const vb_i64 *r0, const vb_i64 *Mi, int c0, int c1, int c2)
{
    return r0[c0] * Mi[c1 * 5 + c2] - r0[c1] * Mi[c0 * 5 + c2] + r0[c2] * Mi[c0 * 5 + c1];
}

/* The line and the quadratic of a quadruple. */
typedef struct vbd_line {
    vb_ia v[3], U[3], D, A, B, C, sq;
    vb_i64 r[4]; /* R_i - R_a (r[0] = 0) */
} vbd_line;

/* vbd_line_make up to D and v: rows m[i] = z(q[i+1]) - z(q[0]) (|z| <
 * 2^62: exact in 64 bits), L->r, L->D, L->v, and the first row e[0..4] and
 * minors M that vbd_line_end takes. 1 when D != 0 is proven, else 0. */
VB_SHARED_FN int vbd_line_begin(VB_GLOBAL const vb_i64 *z, vb_u32 a, vb_u32 b, vb_u32 c,
                                vb_u32 d, vbd_line *L, vb_ia *e, vb_ia *M)
{
    vb_i64 m[3][4];
    vb_u32 ids[3];
    ids[0] = b;
    ids[1] = c;
    ids[2] = d;
    int small = 1, tiny = 1;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 4; k++) {
            m[i][k] = z[4 * (vb_u64)ids[i] + k] - z[4 * (vb_u64)a + k];
            if (m[i][k] >= ((vb_i64)1 << 30) || m[i][k] <= -((vb_i64)1 << 30))
                small = 0;
            if (m[i][k] >= ((vb_i64)1 << 20) || m[i][k] <= -((vb_i64)1 << 20))
                tiny = 0;
        }
    L->r[0] = 0;
    for (int i = 0; i < 3; i++)
        L->r[i + 1] = m[i][3];
    /* Rows e[i * 5 + k]: the four entries and W = |d|^2 - r^2. Below 2^30
     * W (< 2^62) and the 2x2 minors of the entries (< 2^61) are exact in 64
     * bits. */
    for (int i = 0; !tiny && i < 3; i++) {
        for (int k = 0; k < 4; k++)
            e[i * 5 + k] = vb_ia_int(m[i][k]);
        if (small) {
            e[i * 5 + 4] = vb_ia_int(m[i][0] * m[i][0] + m[i][1] * m[i][1] +
                                      m[i][2] * m[i][2] - m[i][3] * m[i][3]);
        } else {
            vb_ia w = vb_ia_add(vb_ia_sqr(e[i * 5]), vb_ia_sqr(e[i * 5 + 1]));
            w = vb_ia_add(w, vb_ia_sqr(e[i * 5 + 2]));
            e[i * 5 + 4] = vb_ia_sub(w, vb_ia_sqr(e[i * 5 + 3]));
        }
    }
    for (int p = 0; !tiny && p < 5; p++)
        for (int c = p + 1; c < 5; c++) {
            if (small && c < 4)
                M[p * 5 + c] = vb_ia_int(m[1][p] * m[2][c] - m[1][c] * m[2][p]);
            else
                M[p * 5 + c] = vb_ia_sub(vb_ia_mul(e[5 + p], e[10 + c]), vb_ia_mul(e[5 + c], e[10 + p]));
        }
    if (tiny) {
        /* Entries below 2^20: the minors of the entries (< 2^41), D and v
         * (three terms below 2^61), W (< 2^42) and the minors with W (two
         * terms below 2^62) are exact in 64 bits; only U's last products
         * are intervals. */
        vb_i64 Mi[25], Wv[3];
        for (int i = 0; i < 3; i++)
            Wv[i] = m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2] - m[i][3] * m[i][3];
        for (int p = 0; p < 4; p++) {
            for (int c = p + 1; c < 4; c++) {
                Mi[p * 5 + c] = m[1][p] * m[2][c] - m[1][c] * m[2][p];
                M[p * 5 + c] = vb_ia_int(Mi[p * 5 + c]);
            }
            M[p * 5 + 4] = vb_ia_int(m[1][p] * Wv[2] - Wv[1] * m[2][p]);
        }
        L->D = vb_ia_int(vbd_det3i(m[0], Mi, 0, 1, 2));
        if (!vb_ia_sign(L->D))
            return 0;
        L->v[0] = vb_ia_int(vbd_det3i(m[0], Mi, 1, 2, 3));
        L->v[1] = vb_ia_int(-vbd_det3i(m[0], Mi, 0, 2, 3));
        L->v[2] = vb_ia_int(vbd_det3i(m[0], Mi, 0, 1, 3));
        for (int k = 0; k < 4; k++)
            e[k] = vb_ia_int(m[0][k]);
        e[4] = vb_ia_int(Wv[0]);
    } else {
        L->D = vbd_det3(e, M, 0, 1, 2);
        if (!vb_ia_sign(L->D))
            return 0;
        L->v[0] = vbd_det3(e, M, 1, 2, 3);
        L->v[1] = vb_ia_neg(vbd_det3(e, M, 0, 2, 3));
        L->v[2] = vbd_det3(e, M, 0, 1, 3);
    }
    return 1;
}

/* vbd_line_end's last step, delta = B^2 - A C given (A != 0 proven):
 * L->sq and 1 for two proven distinct roots, -1 for none, 0 when open. */
VB_SHARED_FN int vbd_line_roots(vbd_line *L, vb_ia delta)
{
    int sd = vb_ia_sign(delta);
    if (sd < 0)
        return -1;
    if (sd == 0)
        return 0;
    L->sq = vb_ia_sqrt(delta);
    return 1;
}

/* vbd_line_make from vbd_line_begin's e and M on: U, A, B, C and the root
 * of delta, with vbd_line_make's result. */
VB_SHARED_FN int vbd_line_end(const vb_ia *e, const vb_ia *M, vbd_line *L)
{
    L->U[0] = vbd_det3(e, M, 1, 2, 4);
    L->U[1] = vb_ia_neg(vbd_det3(e, M, 0, 2, 4));
    L->U[2] = vbd_det3(e, M, 0, 1, 4);
    /* Lorentz forms with v_3 = -D and U_3 = 0. */
    vb_ia A = vb_ia_add(vb_ia_add(vb_ia_sqr(L->v[0]), vb_ia_sqr(L->v[1])), vb_ia_sqr(L->v[2]));
    L->A = vb_ia_sub(A, vb_ia_sqr(L->D));
    L->B = vb_ia_add(vb_ia_add(vb_ia_mul(L->U[0], L->v[0]), vb_ia_mul(L->U[1], L->v[1])),
                   vb_ia_mul(L->U[2], L->v[2]));
    L->C = vb_ia_add(vb_ia_add(vb_ia_sqr(L->U[0]), vb_ia_sqr(L->U[1])), vb_ia_sqr(L->U[2]));
    if (!vb_ia_sign(L->A))
        return 0;
    return vbd_line_roots(L, vb_ia_sub(vb_ia_sqr(L->B), vb_ia_mul(L->A, L->C)));
}

/* The line and quadratic of the quadruple a < b < c < d. 1 with two proven
 * distinct roots, -1 when delta < 0 is proven (no root), 0 when open (D, A
 * or delta not proven non-zero). */
VB_SHARED_FN int vbd_line_make(VB_GLOBAL const vb_i64 *z, vb_u32 a, vb_u32 b, vb_u32 c,
                               vb_u32 d, vbd_line *L)
{
    vb_ia e[15], M[25];
    if (!vbd_line_begin(z, a, b, c, d, L, e, M))
        return 0;
    return vbd_line_end(e, M, L);
}

/* The emptiness test of one sphere in plain doubles, one error bound for
 * the whole expression (the intervals' outward steps cost more than the
 * rest of the scan). With the box P (exact p_k in [P_k.lo, P_k.hi]) and
 * [S.lo, S.hi] (exact s), and d_k, r the sphere's row (exact doubles:
 * every |z_j - z_a| < 2^53, else VBD_FAST_NONE):
 *   outside when fl(S.hi + r) < 0, or when
 *     q = fl(l_0^2 + l_1^2 + l_2^2) > fl(fl(w~^2) (1 + 2^-46) + 2^-1000),
 *     l_k = max(fl(P_k.lo - d_k), fl(d_k - P_k.hi), 0), w~ = fl(S.hi + r) >= 0;
 *   inside when w' = fl(S.lo + r) > 0 and
 *     q' = fl(m_0^2 + m_1^2 + m_2^2) < fl(fl(w'^2) (1 - 2^-46) - 2^-1000),
 *     m_k = max(fl(P_k.hi - d_k), fl(d_k - P_k.lo)).
 * Proof (u = 2^-53). A difference or sum of two doubles is x (1 + e),
 * |e| <= u, also below 2^-1022 (where it is exact), and keeps its sign;
 * a product or a sum of non-negative terms that lands below 2^-1022 is off
 * by at most 2^-1075 absolutely. Outside: |e_k| >= L_k = max(P_k.lo - d_k,
 * d_k - P_k.hi, 0) >= l_k / (1 + u), so |p - c_j|^2 >= sum L_k^2 >=
 * (q - 2^-1072) / (1 + u)^5, and t + R_j <= W = S.hi + r <= w~ / (1 - u),
 * W^2 <= (fl(w~^2) + 2^-1075) / (1 - u)^3; the right side computed is at
 * least fl(w~^2) (1 + 2^-46)(1 - u)^2 + 2^-1001 >= fl(w~^2) (1 + 2^-47) +
 * 2^-1001, which exceeds (fl(w~^2) + 2^-1075)(1 + u)^5 / (1 - u)^3 +
 * 2^-1072 since (1 + u)^5 / (1 - u)^3 < 1 + 2^-49; so q above it proves
 * |p - c_j| > t + R_j. Inside, in the mirror image: |e_k| <= m_k / (1 - u),
 * |p - c_j|^2 <= (q' + 2^-1072) / (1 - u)^5, t + R_j >= S.lo + r >=
 * w' / (1 + u) > 0, and the right side computed is at most fl(w'^2)
 * (1 - 2^-47) - 2^-1001, below (fl(w'^2) - 2^-1075)(1 - u)^5 / (1 + u)^3 -
 * 2^-1072; so q' below it proves |p - c_j| < t + R_j with t + R_j > 0.
 * Overflow to inf only makes a comparison fail (or holds the exact claim:
 * q = inf means sum l_k^2 > DBL_MAX while fl(w~^2) (1 + 2^-46) is finite),
 * and NaN fails every comparison. */
#define VBD_FAST_NONE 0
#define VBD_FAST_OUT 1
#define VBD_FAST_IN 2
#define VBD_FAST_OPEN 3

/* vbd_scan_fast's test on the sphere's row as exact doubles d_k = z_j,k -
 * z_a,k and r = R_j - R_a (the host twin keeps them as doubles where every
 * |z| < 2^52, cert_filter.c): VBD_FAST_OUT, _IN or _OPEN. */
VB_SHARED_FN int vbd_fast_test(const vb_ia *p, vb_ia s, double d0, double d1, double d2, double r)
{
    double wh = s.hi + r;
    if (wh < 0.0)
        return VBD_FAST_OUT;
    double l0 = vb_fmax(vb_fmax(p[0].lo - d0, d0 - p[0].hi), 0.0);
    double l1 = vb_fmax(vb_fmax(p[1].lo - d1, d1 - p[1].hi), 0.0);
    double l2 = vb_fmax(vb_fmax(p[2].lo - d2, d2 - p[2].hi), 0.0);
    double q = 0.0 + l0 * l0;
    q = q + l1 * l1;
    q = q + l2 * l2;
    if (q > wh * wh * (1.0 + 0x1p-46) + 0x1p-1000)
        return VBD_FAST_OUT;
    double wl = s.lo + r;
    if (!(wl > 0.0))
        return VBD_FAST_OPEN;
    double m0 = vb_fmax(p[0].hi - d0, d0 - p[0].lo);
    double m1 = vb_fmax(p[1].hi - d1, d1 - p[1].lo);
    double m2 = vb_fmax(p[2].hi - d2, d2 - p[2].lo);
    double q2 = 0.0 + m0 * m0;
    q2 = q2 + m1 * m1;
    q2 = q2 + m2 * m2;
    return q2 < wl * wl * (1.0 - 0x1p-46) - 0x1p-1000 ? VBD_FAST_IN : VBD_FAST_OPEN;
}

VB_SHARED_FN int vbd_scan_fast(const vb_ia *p, vb_ia s, VB_GLOBAL const vb_i64 *zj,
                               VB_GLOBAL const vb_i64 *za)
{
    const vb_i64 lim = (vb_i64)1 << 53;
    vb_i64 dk[4];
    for (int k = 0; k < 4; k++) {
        dk[k] = zj[k] - za[k];
        if (dk[k] >= lim || dk[k] <= -lim)
            return VBD_FAST_NONE;
    }
    return vbd_fast_test(p, s, (double)dk[0], (double)dk[1], (double)dk[2], (double)dk[3]);
}

/* A root's tangent ball and the grid cells its scan visits (vbd_root_box). */
typedef struct vbd_box {
    vb_ia p[3], s;         /* p - c_a and s = t + R_a */
    int open;              /* a member's sign not proven */
    vb_u32 c0[3], c1[3];   /* cells c0[k] .. c1[k] along axis k */
    vb_u32 mz, my;         /* the centre's slab and row (scanned first) */
} vbd_box;

/* VBD_SCAN: vbd_root_box leaves the verdict to the scan of its cells. */
#define VBD_SCAN 3u

/* Root r (0: sigma = +1) of a line with two roots up to its scan: the
 * verdict when it is known without one (VBD_OPEN, _VERTEX or _NOT), else
 * VBD_SCAN with *b filled. */
VB_SHARED_FN vb_u32 vbd_root_box(VB_GLOBAL const vb_i64 *z, const vbd_grid *g, vb_u32 q0,
                                 const vbd_line *L, int r, vbd_box *b)
{
    /* mu = -Pn / Qd: (B - sigma sq) / A, or, where B has the sign sigma and
     * that difference would cancel, C / (B + sigma sq) (the roots'
     * product is C / A). s = t + R_a = -mu / 2. */
    vb_ia sq = r ? vb_ia_neg(L->sq) : L->sq, Pn, Qd;
    int sigma = r ? -1 : 1;
    if (vb_ia_sign(L->B) == sigma) {
        Pn = L->C;
        Qd = vb_ia_add(L->B, sq);
    } else {
        Pn = vb_ia_sub(L->B, sq);
        Qd = L->A;
    }
    if (!vb_ia_sign(Qd))
        return VBD_OPEN;
    vb_ia mu = vb_ia_neg(vb_ia_div(Pn, Qd));
    vb_ia s = vb_ia_div(Pn, vb_ia_add(Qd, Qd));
    vb_ia D2 = vb_ia_add(L->D, L->D);
    for (int k = 0; k < 3; k++)
        b->p[k] = vb_ia_div(vb_ia_add(L->U[k], vb_ia_mul(mu, L->v[k])), D2);
    b->s = s;
    int open = 0;
    for (int i = 0; i < 4; i++) {
        vb_ia w = vb_ia_add(s, vb_ia_int(L->r[i]));
        if (w.hi < 0.0)
            return VBD_NOT;
        if (!(w.lo > 0.0))
            open = 1;
    }
    b->open = open;
    /* The box of centres that may touch the tangent ball. */
    VB_GLOBAL const vb_i64 *za = z + 4 * (vb_u64)q0;
    double rad = vb_ia_add(s, vb_ia_int(g->rmax - za[3])).hi;
    if (!(rad < VB_IA_INF) || rad != rad)
        return VBD_OPEN;
    if (rad < 0.0)
        return open ? VBD_OPEN : VBD_VERTEX; /* t + R_j < 0 for every j */
    double o[3];
    o[0] = g->ox;
    o[1] = g->oy;
    o[2] = g->oz;
    vb_u32 nn[3];
    nn[0] = g->nx;
    nn[1] = g->ny;
    nn[2] = g->nz;
    vb_u64 cells = 1;
    for (int k = 0; k < 3; k++) {
        vb_ia ck = vb_ia_add(vb_ia_int(za[k]), b->p[k]);
        double lo = vb_pred(ck.lo - rad), hi = vb_succ(ck.hi + rad);
        if (!(lo > -VB_IA_INF && hi < VB_IA_INF))
            return VBD_OPEN;
        b->c0[k] = vbd_cell(lo, o[k], g->inv, nn[k]);
        b->c1[k] = vbd_cell(hi, o[k], g->inv, nn[k]);
        cells *= (vb_u64)(b->c1[k] - b->c0[k] + 1u);
    }
    if (cells > VBD_MAX_CELLS)
        return VBD_OPEN;
    /* Slabs and rows from the centre's outward (an intruder, which ends the
     * scan, is usually near): the same cells, in another order. */
    b->mz = vbd_cell(vb_ia_add(vb_ia_int(za[2]), b->p[2]).lo, o[2], g->inv, nn[2]);
    b->my = vbd_cell(vb_ia_add(vb_ia_int(za[1]), b->p[1]).lo, o[1], g->inv, nn[1]);
    return VBD_SCAN;
}

/* The verdict of root r (0: sigma = +1) of a line with two roots. */
VB_SHARED_FN vb_u32 vbd_root(VB_GLOBAL const vb_i64 *z, VB_GLOBAL const vb_u32 *cell_start,
                             VB_GLOBAL const vb_u32 *cell_ids, VB_GLOBAL const vb_i64 *cell_z,
                             const vbd_grid *g, vb_u32 q0,
                             vb_u32 q1, vb_u32 q2, vb_u32 q3, const vbd_line *L, int r)
{
    vbd_box b;
    vb_u32 v = vbd_root_box(z, g, q0, L, r, &b);
    if (v != VBD_SCAN)
        return v;
    VB_GLOBAL const vb_i64 *za = z + 4 * (vb_u64)q0;
    const vb_ia *p = b.p;
    vb_ia s = b.s;
    int open = b.open;
    for (vb_u32 iz = 0; iz < 2u * (b.c1[2] - b.c0[2]) + 1u; iz++) {
        vb_i64 cz = vbd_around(b.c0[2], b.c1[2], b.mz, iz);
        if (cz < 0)
            continue;
        for (vb_u32 iy = 0; iy < 2u * (b.c1[1] - b.c0[1]) + 1u; iy++) {
            vb_i64 cy = vbd_around(b.c0[1], b.c1[1], b.my, iy);
            if (cy < 0)
                continue;
            vb_u64 row = ((vb_u64)cz * g->ny + (vb_u64)cy) * g->nx;
            vb_u32 j0 = cell_start[row + b.c0[0]], j1 = cell_start[row + b.c1[0] + 1u];
            for (vb_u32 t = j0; t < j1; t++) {
                vb_u32 j = cell_ids[t];
                if (j == q0 || j == q1 || j == q2 || j == q3)
                    continue;
                VB_GLOBAL const vb_i64 *zj = cell_z + 4 * (vb_u64)t;
                int fast = vbd_scan_fast(p, s, zj, za);
                if (fast == VBD_FAST_OUT)
                    continue;
                if (fast == VBD_FAST_IN)
                    return VBD_NOT;
                if (fast == VBD_FAST_OPEN) {
                    open = 1;
                    continue;
                }
                vb_ia w = vb_ia_add(s, vb_ia_int(zj[3] - za[3]));
                if (w.hi < 0.0)
                    continue; /* t + R_j < 0: outside */
                vb_ia e[3];
                double lo2 = 0.0;
                for (int k = 0; k < 3; k++) {
                    e[k] = vb_ia_sub(p[k], vb_ia_int(zj[k] - za[k]));
                    lo2 = vb_pred(lo2 + vb_ia_sqr(e[k]).lo);
                }
                /* outside: |p - c_j| > t + R_j */
                if (lo2 > vb_succ(w.hi * w.hi))
                    continue;
                /* inside: |p - c_j| < t + R_j with t + R_j > 0 */
                vb_ia d2 = vb_ia_add(vb_ia_add(vb_ia_sqr(e[0]), vb_ia_sqr(e[1])), vb_ia_sqr(e[2]));
                if (w.lo > 0.0 && d2.hi < vb_pred(w.lo * w.lo))
                    return VBD_NOT;
                open = 1;
            }
        }
    }
    return open ? VBD_OPEN : VBD_VERTEX;
}

/* The verdicts of quadruple q0 < q1 < q2 < q3 (VBD_ROOT(v, r) for root r):
 * z the spheres' scaled values by id, the grid's cells cell_start, their
 * spheres' ids cell_ids and values cell_z in cell order. */
VB_SHARED_FN vb_u32 vbd_judge(VB_GLOBAL const vb_i64 *z, VB_GLOBAL const vb_u32 *cell_start,
                              VB_GLOBAL const vb_u32 *cell_ids, VB_GLOBAL const vb_i64 *cell_z,
                              const vbd_grid *g, vb_u32 q0, vb_u32 q1, vb_u32 q2, vb_u32 q3)
{
    vbd_line L;
    int k = vbd_line_make(z, q0, q1, q2, q3, &L);
    if (k < 0)
        return VBD_NOT | (VBD_NOT << 2);
    if (k == 0)
        return VBD_OPEN;
    return vbd_root(z, cell_start, cell_ids, cell_z, g, q0, q1, q2, q3, &L, 0) |
           (vbd_root(z, cell_start, cell_ids, cell_z, g, q0, q1, q2, q3, &L, 1) << 2);
}

#endif
