/* The contact's integrand along an arc over one piece as a Taylor model
 * whose remainder comes from closed forms (contact_tm.c), for
 * arc_pieces.c's and arc_march.c's pieces. */
#ifndef VBM_CONTACT_TM_H
#define VBM_CONTACT_TM_H

#include "vbm_arc.h"
#include "vbm_series1.h"
#include "vbx_ia.h"

/* The arc's rational functions of t = tan(angle / 2) that the contact's
 * model reads (arc_fun.c's rational_of): q' / q^3 = rn / rd,
 * 1 - z = yn / sd (sd = E = 1 + t^2; S = N + 2 delta q follows from 1 - z
 * in the model) and the area's integrand (1 - z) dphi/dt = an / (sd po);
 * cd = po yn (the contact's divisor: con = F an / cd). */
typedef struct vbm_contact_rat {
    vbx_ia rn[5], rd[7], sd[3], yn[3], an[3], po[3], cd[5];
} vbm_contact_rat;

/* *G = G(q) = -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q) - delta^2 /
 * (2 N sqrt N) log |(sqrt S - sqrt N) / (sqrt S + sqrt N)|, S = N + 2 delta q
 * (o's N, delta and their constants), a primitive of sqrt(S) / q^3, at a
 * constant q (an interval): F = C (G1 - G(q)). Returns 0 unless q and S
 * are proven > 0. */
int vbm_contact_g(const vbm_owner *o, vbx_ia q, vbx_ia *G);

/* The contact's integrand con(xc + x) = F(z) / (1 - z) an / (sd po) (F = C (G1 -
 * G(q)), vbm_owner o's constants, F0 an enclosure of F at z(xc)) as
 * sum_{n<K} c_n x^n + x^K rho(x), K = VBM1_K: c->c[0..K-1] enclose the
 * Taylor coefficients at the point xc (c->c[K] = 0) and *rest encloses
 * rho over `x` (the piece less xc, holding 0), so that the piece's
 * integral is vbm1_integrate_m's with *rest as the box's order K. Returns
 * 0 when an interval cannot bound a denominator, q, S or 1 - z away from
 * 0 over the piece (the caller then splits it or, at its shortest, takes
 * the contact's series over it). */
int vbm_contact_tm(const vbm_contact_rat *p, const vbm_owner *o, vbx_ia F0, double xc, vbx_ia x,
                   vbm_s1 *c, vbx_ia *rest);

/* The factor to the next contact piece's length along an arc from the
 * last piece's ratio rho = width / its share of the target (a NaN or
 * infinite rho: the least, 1/4; 0: the most, 4): at most 0.75 for rho > 1
 * (a missed piece is always retried shorter), chosen so that the next
 * piece should meet its share with a margin. A step rule, not a bound:
 * every piece is proven by its own model. */
double vbm_contact_step(double rho);

/* vbm_contact_step with the margin `safety` (the in-use one: 0.25) in
 * place of the built-in one: the rule's factor is the largest 2^(j/4),
 * j in -8..8, with 2^(j K / 4) <= safety / rho, capped at 0.75 for rho > 1.
 * For tests and retuning. */
double vbm_contact_step_at(double rho, double safety);

/* The first contact piece's length along an arc as a part of the arc
 * (0 < part <= 1) from r, the area's remainder term over the whole arc
 * (|c_K| 2 h^(K+1) / (K + 1), c_K the area's order-K coefficient at the
 * middle, h the half-length) over the contact's target: the whole arc
 * where r is small, else at most half of it. Only where pieces end follows
 * from it. */
double vbm_contact_start(double r);

#endif
