/* Bivariate Taylor models in interval arithmetic: the remainder-proven
 * quadrature of the cell measures (verify/measures/).
 *
 * A vbm_ser holds the Taylor coefficients c_ij = (d/da)^i (d/db)^j f / (i! j!)
 * of a function f(a, b), i + j <= VBM_ORDER, each as an interval (vbx_ia.h:
 * every operation rounded outward). The arithmetic below (sum, product,
 * reciprocal, square root: the recurrences of truncated power series)
 * computes them as functions of the expansion point, so the same calls give
 *   - at a point (a_c, b_c): enclosures of f's coefficients there;
 *   - at a box (the variables' constant terms are the box's intervals):
 *     enclosures of the coefficients at every point of the box.
 * Taylor's theorem with Lagrange's remainder along the segment from the
 * centre (a_c, b_c) to (a_c + x, b_c + y) gives
 *   f = sum_{i+j<K} c_ij(centre) x^i y^j + sum_{i+j=K} c_ij(xi) x^i y^j,
 * xi on the segment, hence in the box; vbm_integrate integrates both parts
 * over the box with outward rounding, the second with c_ij(xi) in the box
 * enclosure. The error of the result is O(h^(K+2)) on a box of side h. */
#ifndef VBM_SERIES_H
#define VBM_SERIES_H

#include "vbx_ia.h"

/* K: the order of the remainder term (the polynomial part has degree K - 1). */
#define VBM_ORDER 6
#define VBM_NC ((VBM_ORDER + 1) * (VBM_ORDER + 2) / 2)

typedef struct vbm_ser {
    vbx_ia c[VBM_NC]; /* c[VBM_IDX(i, j)] */
} vbm_ser;

/* Coefficients stored by total degree, then by the power of b. */
#define VBM_IDX(i, j) (((i) + (j)) * ((i) + (j) + 1) / 2 + (j))

/* f = v (a constant). */
void vbm_const(vbm_ser *f, vbx_ia v);

/* f = the variable a (which = 0) or b (which = 1) expanded at `at`. */
void vbm_var(vbm_ser *f, vbx_ia at, int which);

/* r = f + g, r = f - g, r = v f + w (r may alias f or g). */
void vbm_add(vbm_ser *r, const vbm_ser *f, const vbm_ser *g);
void vbm_sub(vbm_ser *r, const vbm_ser *f, const vbm_ser *g);
void vbm_affine(vbm_ser *r, vbx_ia v, const vbm_ser *f, vbx_ia w);

/* r = f g (r must not alias f or g). */
void vbm_mul(vbm_ser *r, const vbm_ser *f, const vbm_ser *g);

/* r = f f (r must not alias f), with the constant term as a square (>= 0
 * even when f's constant term is an interval across 0). */
void vbm_square(vbm_ser *r, const vbm_ser *f);

/* r = 1 / f (r must not alias f). Returns 0, leaving r unspecified, when
 * f's constant term may be 0 (no enclosure then). */
int vbm_recip(vbm_ser *r, const vbm_ser *f);

/* r = sqrt(f) (r must not alias f). Returns 0 when f's constant term is
 * not proven > 0. */
int vbm_sqrt(vbm_ser *r, const vbm_ser *f);

/* An enclosure of the integral of f over [a_c - ha, a_c + ha] x
 * [b_c - hb, b_c + hb]: `centre` holds f's coefficients at (a_c, b_c),
 * `box` their enclosures over the box (see the top of this file). */
vbx_ia vbm_integrate(const vbm_ser *centre, const vbm_ser *box, double ha, double hb);

#endif
