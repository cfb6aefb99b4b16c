/* The filtered tangent solve of one quadruple (see vbx_quad.h). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "vbx_dd.h"
#include "vbx_quad.h"

/* x (|x| < 2^117) as a double-double: x = a 2^64 + b 2^32 + c with
 * |a| < 2^53 and 0 <= b, c < 2^32, each exact in a double, and the scalings
 * exact; two_sum(a 2^64, b 2^32) is exact, and adding c to its low part
 * rounds once (error <= u |low + c|, in the radius). */
static vbx_dd dd_of(vbx_i128 x)
{
    if (x < ((vbx_i128)1 << 53) && x > -((vbx_i128)1 << 53))
        return vbx_dd_exact((double)(int64_t)x);
    double a = (double)(int64_t)(x >> 64);
    uint64_t lo = (uint64_t)x;
    double b = (double)(uint32_t)(lo >> 32), c = (double)(uint32_t)lo;
    double h, l;
    vbx_two_sum(a * 0x1p64, b * 0x1p32, &h, &l);
    double l2 = l + c;
    vbx_dd z;
    vbx_two_sum(h, l2, &z.h, &z.l);
    z.r = fabs(l2) * VBX_DD_U * VBX_DD_UP;
    return z;
}

/* |x| < 2^62 is exact as a double-double: x - fl(x) is an integer below
 * 2^10. */
static vbx_dd dd_of64(int64_t x)
{
    double h = (double)x;
    vbx_dd z = {h, (double)(x - (int64_t)h), 0.0};
    return z;
}

/* The line from rows too large for 128 bits (|entry| < 2^62), in
 * double-double: every entry is exact as a pair (dd_of64), and each sum and
 * product adds its error bound to the radius (vbx_dd.h), so v, U and D
 * enclose the exact minors (those of the 128-bit path). Magnitudes stay
 * below 2^62 (entries), 2^126 (W), 2^189 (minors with W) and 2^253 (v, U,
 * D): far inside vbx_dd.h's range. VBX_QL_LINE; where D is not proven
 * non-zero, VBX_QL_FLAT or VBX_QL_EXACT by the exact rank test. */
static int line_dd(const int64_t m[3][4], vbx_qline *L)
{
    L->exact = 0;
    vbx_dd e[3][5];
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 4; k++)
            e[i][k] = dd_of64(m[i][k]);
        vbx_dd w = vbx_dd_add(vbx_dd_mul(e[i][0], e[i][0]), vbx_dd_mul(e[i][1], e[i][1]));
        w = vbx_dd_add(w, vbx_dd_mul(e[i][2], e[i][2]));
        e[i][4] = vbx_dd_sub(w, vbx_dd_mul(e[i][3], e[i][3]));
    }
    vbx_dd M[5][5];
    for (int a = 0; a < 5; a++)
        for (int b = a + 1; b < 5; b++)
            M[a][b] = vbx_dd_sub(vbx_dd_mul(e[1][a], e[2][b]), vbx_dd_mul(e[1][b], e[2][a]));
#define VBX_DET3_DD(c0, c1, c2)                                                         \
    vbx_dd_add(vbx_dd_sub(vbx_dd_mul(e[0][c0], M[c1][c2]), vbx_dd_mul(e[0][c1], M[c0][c2])), \
               vbx_dd_mul(e[0][c2], M[c0][c1]))
    L->D = VBX_DET3_DD(0, 1, 2);
    if (!vbx_dd_sign(L->D))
        return vbx_qf_rank_low(m) ? VBX_QL_FLAT : VBX_QL_EXACT;
    L->v[0] = VBX_DET3_DD(1, 2, 3);
    L->v[1] = vbx_dd_neg(VBX_DET3_DD(0, 2, 3));
    L->v[2] = VBX_DET3_DD(0, 1, 3);
    L->v[3] = vbx_dd_neg(L->D);
    L->U[0] = VBX_DET3_DD(1, 2, 4);
    L->U[1] = vbx_dd_neg(VBX_DET3_DD(0, 2, 4));
    L->U[2] = VBX_DET3_DD(0, 1, 4);
#undef VBX_DET3_DD
    return VBX_QL_LINE;
}

/* Row entries (scaled coordinates and radii relative to the base) below
 * 2^28 keep every integer of the line within 128 bits:
 *   |d_k|, |r| < 2^28, so |W| = |d|^2 - r^2 < 3 * 2^56 + 2^56 = 2^58;
 *   2x2 minors of rows 1, 2: < 2 * 2^56 = 2^57 on the columns d, r, and
 *   < 2 * 2^28 * 2^58 = 2^87 with the column W;
 *   v (3x3 minors on d, r): < 3 * 2^28 * 2^57 < 2^87;
 *   U (3x3 minors with W): each term is an entry times a minor, < 2^28 * 2^87
 *   or < 2^58 * 2^57, so |U| < 3 * 2^115 < 2^117; 2D < 2^88.
 * Every product below is formed in 128 bits and fits, and every value is
 * below 2^117 as dd_of needs. */
#define VBX_QF_ROW_LIMIT ((int64_t)1 << 28)

int vbx_qf_line(const vbx_qdata *z, const uint32_t q[4], vbx_qline *L)
{
    if (!z->ok)
        return VBX_QL_EXACT;
    const int64_t *cb = &z->z[4 * (size_t)q[0]];
    int64_t m[3][5];
    int wide = 0;
    for (int i = 0; i < 3; i++) {
        const int64_t *cj = &z->z[4 * (size_t)q[i + 1]];
        /* |z| < 2^61 (open_qdata), so the differences fit in 62 bits. */
        for (int k = 0; k < 4; k++) {
            m[i][k] = cj[k] - cb[k];
            if (m[i][k] >= VBX_QF_ROW_LIMIT || m[i][k] <= -VBX_QF_ROW_LIMIT)
                wide = 1;
        }
    }
    memcpy(L->q, q, sizeof L->q);
    L->r[0] = 0;
    for (int i = 0; i < 3; i++)
        L->r[i + 1] = m[i][3];
    if (wide) {
        int64_t m4[3][4];
        for (int i = 0; i < 3; i++)
            memcpy(m4[i], m[i], sizeof m4[i]);
        return line_dd((const int64_t(*)[4])m4, L);
    }
    for (int i = 0; i < 3; i++)
        m[i][4] = m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2] - m[i][3] * m[i][3];
    /* Minors of rows 1 and 2, M[a][b] for columns a < b. */
    vbx_i128 M[5][5];
    for (int a = 0; a < 5; a++)
        for (int b = a + 1; b < 5; b++)
            M[a][b] = (vbx_i128)m[1][a] * m[2][b] - (vbx_i128)m[1][b] * m[2][a];
    /* det3 of columns c0 < c1 < c2, expanded along row 0. */
#define VBX_DET3(c0, c1, c2)                                                            \
    ((vbx_i128)m[0][c0] * M[c1][c2] - (vbx_i128)m[0][c1] * M[c0][c2] +                  \
     (vbx_i128)m[0][c2] * M[c0][c1])
    /* v_k = (-1)^k D_k (the minor without column k); k = 3 is required.
     * All four zero: the exact solver's VBX_SINGULAR (rank < 3 on the
     * columns d, r; tangent_solver.c finds no free unknown). */
    vbx_i128 *vi = L->vi, *Ui = L->Ui;
    vi[0] = VBX_DET3(1, 2, 3);
    vi[1] = -VBX_DET3(0, 2, 3);
    vi[2] = VBX_DET3(0, 1, 3);
    vi[3] = -VBX_DET3(0, 1, 2);
    if (vi[3] == 0)
        return vi[0] == 0 && vi[1] == 0 && vi[2] == 0 ? VBX_QL_FLAT : VBX_QL_EXACT;
    /* Cramer with s = 0: column j of the minor (0, 1, 2) replaced by W in
     * place; moving W to the last column takes 2 - j transpositions (the
     * same signs in line_dd). */
    Ui[0] = VBX_DET3(1, 2, 4);
    Ui[1] = -VBX_DET3(0, 2, 4);
    Ui[2] = VBX_DET3(0, 1, 4);
#undef VBX_DET3
    for (int k = 0; k < 4; k++)
        L->v[k] = dd_of(vi[k]);
    L->D = dd_of(-vi[3]);
    for (int k = 0; k < 3; k++)
        L->U[k] = dd_of(Ui[k]);
    L->exact = 1;
    return VBX_QL_LINE;
}

int vbx_qf_tangent_sign(const vbx_qline *L, vbx_ia s, int i)
{
    /* |r_i| < 2^53 is exact in double, and a sum rounded to nearest keeps
     * its sign (or is 0): fl(lo + r) > 0 proves lo + r > 0. Larger radius
     * differences (wide rows) are left to the exact path. */
    if (L->r[i] >= ((int64_t)1 << 53) || L->r[i] <= -((int64_t)1 << 53))
        return 0;
    double r = (double)L->r[i];
    if (s.lo + r > 0.0)
        return 1;
    if (s.hi + r < 0.0)
        return -1;
    return 0;
}


/* ---- the correctly rounded coordinates ----------------------------------- */

/* The double nearest to N / Den, if the enclosures decide it: x~ is a
 * guess, and it is the answer when the exact quotient lies strictly
 * between the midpoints x~ - gd and x~ + gu to its neighbours, which two
 * signs decide: N - (x~ + gu) Den and N - (x~ - gd) Den against the sign
 * of Den (gu, gd: half the gaps to succ and pred, powers of two, exact).
 * The first guess (quotient of the rounded pairs) may be a few units off;
 * a wrong guess is corrected once by the residual N - x~ Den, then moved
 * by single steps. Values at 0 or out of the normal range are left to the
 * exact path (whose zero is +0). */
static int dd_round(vbx_dd N, vbx_dd Den, double *out)
{
    int sd = vbx_dd_sign(Den);
    if (!sd || !vbx_dd_sane(N) || !vbx_dd_sane(Den))
        return 0;
    double den = Den.h + Den.l, x = (N.h + N.l) / den;
    for (int tries = 0; tries < 4; tries++) {
        if (!(fabs(x) >= 0x1p-900 && fabs(x) <= 0x1p900))
            return 0;
        double up = vbx_succ(x), dn = vbx_pred(x);
        vbx_dd E = vbx_dd_sub(N, vbx_dd_mul(Den, vbx_dd_exact(x)));
        int su = vbx_dd_sign(vbx_dd_sub(E, vbx_dd_scale2(Den, (up - x) * 0.5))) * sd;
        int sl = vbx_dd_sign(vbx_dd_add(E, vbx_dd_scale2(Den, (x - dn) * 0.5))) * sd;
        if (su < 0 && sl > 0) {
            *out = x;
            return 1;
        }
        if (!(su > 0 || sl < 0))
            return 0;
        if (tries == 0)
            x += (E.h + E.l) / den;
        else
            x = su > 0 ? up : dn;
    }
    return 0;
}

/* [h + l - r, h + l + r] in doubles: h + l lies in [pred(h), succ(h)]
 * (h = fl(h + l) for a normalised pair, vbx_ia.h), and one more step
 * outward covers the rounding of -r and +r. */
static vbx_ia ia_of_dd(vbx_dd a)
{
    vbx_ia r = {vbx_pred(vbx_pred(a.h) - a.r), vbx_succ(vbx_succ(a.h) + a.r)};
    return r;
}

int vbx_qf_prep(const vbx_qline *L, vbx_qprep *P)
{
    vbx_dd *v = P->v, *U = P->U;
    P->delta_exact = 0;
    memcpy(v, L->v, sizeof P->v);
    memcpy(U, L->U, sizeof P->U);
    P->D = L->D;
    /* Lorentz forms; U_3 = 0 leaves three terms in B and C. */
    vbx_dd A = vbx_dd_add(vbx_dd_add(vbx_dd_mul(v[0], v[0]), vbx_dd_mul(v[1], v[1])),
                          vbx_dd_mul(v[2], v[2]));
    P->A = vbx_dd_sub(A, vbx_dd_mul(v[3], v[3]));
    P->B = vbx_dd_add(vbx_dd_add(vbx_dd_mul(U[0], v[0]), vbx_dd_mul(U[1], v[1])),
                      vbx_dd_mul(U[2], v[2]));
    P->C = vbx_dd_add(vbx_dd_add(vbx_dd_mul(U[0], U[0]), vbx_dd_mul(U[1], U[1])),
                      vbx_dd_mul(U[2], U[2]));
    vbx_dd delta = vbx_dd_sub(vbx_dd_mul(P->B, P->B), vbx_dd_mul(P->A, P->C));
    /* A = 0 is the exact solver's linear case. */
    if (!vbx_dd_sign(P->A) || !vbx_dd_sane(delta) || !vbx_dd_sane(P->A) || !vbx_dd_sane(P->C))
        return VBX_QF_EXACT;
    int sd = vbx_dd_sign(delta);
    P->sb = vbx_dd_sign(P->B);
    if (sd == 0 && L->exact) {
        /* Mostly an exact 0 (a double root: cospherical input), which no
         * enclosure proves. Then mu = -B / A: vbx_qf_root's root 0 with
         * sq = 0 gives it (as -B / A, or as -C / B where B's sign is
         * proven, equal since B^2 = A C). */
        sd = vbx_qf_delta_sign(L);
        P->delta_exact = 1;
        if (sd == 0) {
            P->sq = vbx_dd_exact(0.0);
            return VBX_QF_ONE;
        }
        if (sd > 0)
            return VBX_QF_EXACT; /* two roots too close for sqrt's enclosure */
    }
    if (sd < 0)
        return VBX_QF_NONE;
    if (sd == 0)
        return VBX_QF_EXACT;
    P->sq = vbx_dd_sqrt(delta);
    return VBX_QF_TWO;
}

void vbx_qf_root(const vbx_qprep *P, int root, vbx_qroot *R)
{
    /* mu = (-B + sigma sqrt(delta)) / A = -G / A with G = B - sigma sq,
     * or, where B has the sign sigma (G would cancel), the other factor of
     * mu+ mu- = C / A: mu = -C / G' with G' = B + sigma sq. So
     * mu = -Pn / Qd with (Pn, Qd) = (G, A) or (C, G'); Qd != 0 (A != 0, and
     * G' has the sign of B, proven). s = -mu / 2 = Pn / (2 Qd). */
    int sigma = root ? -1 : 1;
    vbx_dd sq = sigma > 0 ? P->sq : vbx_dd_neg(P->sq);
    if (P->sb == sigma) {
        R->Pn = P->C;
        R->Qd = vbx_dd_add(P->B, sq);
    } else {
        R->Pn = vbx_dd_sub(P->B, sq);
        R->Qd = P->A;
    }
    R->s = vbx_ia_div(ia_of_dd(R->Pn), ia_of_dd(vbx_dd_scale2(R->Qd, 2.0)));
    R->have_x = 0;
}

int vbx_qf_point(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R)
{
    /* With q = (U + mu v) / (2D):
     *   x scale = (2D Qd X_a + U Qd - Pn v) / (2D Qd),
     *   t scale = s - R_a = (Pn - 2 Qd R_a) / (2 Qd). */
    const int64_t *cb = &z->z[4 * (size_t)L->q[0]];
    vbx_dd Qx = vbx_dd_scale2(vbx_dd_mul(P->D, R->Qd), 2.0), sc = vbx_dd_exact(z->scale);
    R->Den[0] = vbx_dd_mul(Qx, sc);
    for (int k = 0; k < 3; k++) {
        vbx_dd N = vbx_dd_add(vbx_dd_mul(Qx, dd_of64(cb[k])), vbx_dd_mul(P->U[k], R->Qd));
        R->N[k] = vbx_dd_sub(N, vbx_dd_mul(R->Pn, P->v[k]));
    }
    vbx_dd Q2 = vbx_dd_scale2(R->Qd, 2.0);
    R->N[3] = vbx_dd_sub(R->Pn, vbx_dd_mul(Q2, dd_of64(cb[3])));
    R->Den[1] = vbx_dd_mul(Q2, sc);
    if (!vbx_dd_sane(R->Den[0]) || !vbx_dd_sane(R->Den[1]))
        return 0;
    vbx_ia d0 = ia_of_dd(R->Den[0]), d1 = ia_of_dd(R->Den[1]);
    for (int k = 0; k < 4; k++) {
        if (!vbx_dd_sane(R->N[k]))
            return 0;
        R->p[k] = vbx_ia_div(ia_of_dd(R->N[k]), k < 3 ? d0 : d1);
    }
    return 1;
}

int vbx_qf_power_sign(const vbx_qdata *z, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R,
                      uint32_t j)
{
    /* On the base's cone |q|^2 = s^2, the power is W_j - 2 m_j . u
     * (tangent_solver.c, vbx_sign_power) with the row m_j = (c_j - c_a,
     * R_j - R_a) and W_j = |d_j|^2 - r_j^2; with u = X / (2 DQ) it is
     * (W_j DQ - m_j . X) / DQ. The row is exact (|z| < 2^61, so its
     * entries are below 2^62: dd_of64); every product and sum adds its
     * bound to the radius. */
    if (!R->have_x) {
        for (int k = 0; k < 3; k++)
            R->X[k] = vbx_dd_sub(vbx_dd_mul(P->U[k], R->Qd), vbx_dd_mul(R->Pn, P->v[k]));
        R->X[3] = vbx_dd_neg(vbx_dd_mul(R->Pn, P->v[3])); /* U_3 = 0 */
        R->DQ = vbx_dd_mul(P->D, R->Qd);
        R->have_x = 1;
    }
    int sq = vbx_dd_sign(R->DQ);
    if (!sq || !vbx_dd_sane(R->DQ))
        return 0;
    const int64_t *cb = &z->z[4 * (size_t)L->q[0]], *cj = &z->z[4 * (size_t)j];
    vbx_dd m[4];
    for (int k = 0; k < 4; k++)
        m[k] = dd_of64(cj[k] - cb[k]);
    vbx_dd W = vbx_dd_add(vbx_dd_mul(m[0], m[0]), vbx_dd_mul(m[1], m[1]));
    W = vbx_dd_sub(vbx_dd_add(W, vbx_dd_mul(m[2], m[2])), vbx_dd_mul(m[3], m[3]));
    vbx_dd E = vbx_dd_mul(W, R->DQ);
    for (int k = 0; k < 4; k++) {
        if (!vbx_dd_sane(R->X[k]))
            return 0;
        E = vbx_dd_sub(E, vbx_dd_mul(m[k], R->X[k]));
    }
    if (!vbx_dd_sane(E))
        return 0;
    return vbx_dd_sign(E) * sq;
}

int vbx_qf_round(const vbx_qroot *R, double out[4])
{
    for (int k = 0; k < 4; k++)
        if (!dd_round(R->N[k], R->Den[k < 3 ? 0 : 1], &out[k]))
            return 0;
    return 1;
}

#ifndef VBX_DD_USE_FMA
const vbx_qf_ops vbx_qf_ops_plain = {vbx_qf_line, vbx_qf_prep, vbx_qf_root,
                                     vbx_qf_point, vbx_qf_round, vbx_qf_power_sign};

const vbx_qf_ops *vbx_qf_ops_best(void)
{
#if defined(VBX_QF_HAVE_FMA) && defined(__GNUC__) && defined(__x86_64__)
    if (__builtin_cpu_supports("fma"))
        return &vbx_qf_ops_fma;
#endif
    return &vbx_qf_ops_plain;
}
#else
const vbx_qf_ops vbx_qf_ops_fma = {vbx_qf_line, vbx_qf_prep, vbx_qf_root,
                                   vbx_qf_point, vbx_qf_round, vbx_qf_power_sign};
#endif
