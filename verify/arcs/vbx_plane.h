/* Linear algebra of a triple's plane for arc closure (arc_frame.c,
 * arc_local.c): dot and cross products and the generalised cross product
 * tau of the rows m_b, m_c with a third row, over interval enclosures and
 * exactly (integers, Z[sqrt(d)]). Inline: they run inside every frame
 * set-up and local test. */
#ifndef VBX_PLANE_H
#define VBX_PLANE_H

#include "vbx_arc.h"

/* Columns of the six 2x2 minors, and for each column i the three others. */
static const int vbx_minor_cols[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
static const int vbx_other_cols[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

static inline int vbx_minor_at(int p, int q)
{
    for (int k = 0; k < 6; k++)
        if (vbx_minor_cols[k][0] == p && vbx_minor_cols[k][1] == q)
            return k;
    return -1;
}

/* ---- in intervals ---------------------------------------------------------- */

/* Dot products, cross product: one error bound per expression
 * (vb_ia_dot, core/vb_ia_shared.h), not a step per operation. */
static inline vbx_ia vbx_ia_dot3(const vbx_ia *a, const vbx_ia *b)
{
    return vb_ia_dot(a, b, 3);
}

static inline vbx_ia vbx_ia_dot4(const vbx_ia *a, const vbx_ia *b)
{
    return vb_ia_dot(a, b, 4);
}

/* |m_0..2|^2 - m_3^2, one dot product. */
static inline vbx_ia vbx_ia_lorentz(const vbx_ia m[4])
{
    vbx_ia x[4] = {m[0], m[1], m[2], vbx_ia_neg(m[3])};
    return vb_ia_dot(x, m, 4);
}

/* a_i b_j - a_j b_i as the dot product of (a_i, -a_j) and (b_j, b_i)
 * (negation is exact). */
static inline vbx_ia vbx_ia_det2(vbx_ia ai, vbx_ia aj, vbx_ia bi, vbx_ia bj)
{
    vbx_ia x[2] = {ai, vbx_ia_neg(aj)}, y[2] = {bj, bi};
    return vb_ia_dot(x, y, 2);
}

static inline void vbx_ia_cross(const vbx_ia *a, const vbx_ia *b, vbx_ia *r)
{
    r[0] = vbx_ia_det2(a[1], a[2], b[1], b[2]);
    r[1] = vbx_ia_det2(a[2], a[0], b[2], b[0]);
    r[2] = vbx_ia_det2(a[0], a[1], b[0], b[1]);
}

static inline vbx_ia vbx_ia_scale(vbx_ia a, double s)
{
    return vbx_ia_mul(a, vbx_ia_point(s));
}

/* The generalised cross product tau of the rows m_b, m_c (through their
 * minors) and l: x . tau = det[x; m_b; m_c; l] for every x (Laplace along
 * the first row; the third row of each 3x3 minor is l). */
static inline void vbx_ia_tau(const vbx_ia minor[6], const vbx_ia l[4], vbx_ia tau[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = vbx_other_cols[i];
        vbx_ia x[3] = {l[c[0]], vbx_ia_neg(l[c[1]]), l[c[2]]};
        vbx_ia y[3] = {minor[vbx_minor_at(c[1], c[2])], minor[vbx_minor_at(c[0], c[2])],
                       minor[vbx_minor_at(c[0], c[1])]};
        vbx_ia t = vb_ia_dot(x, y, 3);
        tau[i] = (i & 1) ? vbx_ia_neg(t) : t;
    }
}

/* Row m_j = (c_j - c_a, R_j - R_a) over the enclosures, input units. */
static inline void vbx_ia_row(const vbx_arcw *w, uint32_t a, uint32_t j, vbx_ia m[4])
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)a], *bj = &w->c->d.box[4 * (size_t)j];
    for (int k = 0; k < 4; k++)
        m[k] = vbx_ia_sub(bj[k], ba[k]);
}

/* ---- exactly ---------------------------------------------------------------- */

/* tau from exact minors and l in Z[sqrt(d)]^4 (same formula as vbx_ia_tau). */
static inline void vbx_zs_tau(vbx_arcw *w, mpz_t minor[6], const vbx_zs l[4], vbx_zs tau[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = vbx_other_cols[i];
        mpz_set_ui(tau[i].a, 0);
        mpz_set_ui(tau[i].b, 0);
        vbx_zs_addmul_z(&tau[i], &l[c[0]], minor[vbx_minor_at(c[1], c[2])]);
        vbx_zs_submul_z(&tau[i], &l[c[1]], minor[vbx_minor_at(c[0], c[2])]);
        vbx_zs_addmul_z(&tau[i], &l[c[2]], minor[vbx_minor_at(c[0], c[1])]);
        if (i & 1) {
            mpz_neg(tau[i].a, tau[i].a);
            mpz_neg(tau[i].b, tau[i].b);
        }
    }
    (void)w;
}

/* tau for an integer third row x (the direction of {x . u = const} in the
 * plane): out[i] integers. */
static inline void vbx_z_tau(mpz_t minor[6], mpz_t *x, mpz_t out[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = vbx_other_cols[i];
        mpz_mul(out[i], x[c[0]], minor[vbx_minor_at(c[1], c[2])]);
        mpz_submul(out[i], x[c[1]], minor[vbx_minor_at(c[0], c[2])]);
        mpz_addmul(out[i], x[c[2]], minor[vbx_minor_at(c[0], c[1])]);
        if (i & 1)
            mpz_neg(out[i], out[i]);
    }
}

/* r = sum_k z[k] x[k] over k < n. */
static inline void vbx_zs_dot_z(vbx_zs *r, const vbx_zs *x, mpz_t *z, int n)
{
    mpz_set_ui(r->a, 0);
    mpz_set_ui(r->b, 0);
    for (int k = 0; k < n; k++)
        vbx_zs_addmul_z(r, &x[k], z[k]);
}

static inline void vbx_z_cross(mpz_t *a, mpz_t *b, mpz_t *r)
{
    mpz_mul(r[0], a[1], b[2]);
    mpz_submul(r[0], a[2], b[1]);
    mpz_mul(r[1], a[2], b[0]);
    mpz_submul(r[1], a[0], b[2]);
    mpz_mul(r[2], a[0], b[1]);
    mpz_submul(r[2], a[1], b[0]);
}

static inline void vbx_z_dot3(mpz_t r, mpz_t *a, mpz_t *b)
{
    mpz_mul(r, a[0], b[0]);
    mpz_addmul(r, a[1], b[1]);
    mpz_addmul(r, a[2], b[2]);
}

#endif
