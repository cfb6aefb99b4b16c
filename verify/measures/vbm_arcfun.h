/* The integrands along one arc of a neighbour's region of directions, and
 * the pieces that integrate them (the formulas at the top of stokes_cell.c).
 * Module-internal: arc_integral.c (an arc's ends and its own-circle closed
 * form) drives arc_pieces.c (the area's and volume's halved pieces and one
 * piece's Taylor-model values) and arc_march.c (the contact's stepped
 * pieces); arc_fun.c makes the integrands' series in t, arc_near.c the
 * contact's where the arc passes near e_j, arc_owner.c a neighbour's
 * constants.
 *
 * On an arc not on j's own cap circle the integral runs over t =
 * tan(angle / 2) about the arc's middle (|t| < 0.7), the integrand a
 * rational function of t (the area's and volume's quotients of
 * polynomials, the contact's a root and logs of such quotients: their
 * Taylor coefficients by linear recurrences, vbm1_rational), enclosed by
 * univariate Taylor models (vbm_series1.h) on pieces halved until each
 * meets its share of the tolerance. */
#ifndef VBM_ARCFUN_H
#define VBM_ARCFUN_H

#include <math.h>

#include "vbm_arc.h"
#include "vbm_contact_tm.h"
#include "vbm_series1.h"

/* short names of the values, for the arc files (only they include this) */
enum { AREA = VBM_AREA, VOL = VBM_VOL, CON = VBM_CON, NV = VBM_NV };

#define VBM_ARC_MAX_DEPTH 20 /* halvings of an arc's parameter range */

/* 1 - z below which over a piece the contact goes by contact_near (1crn
 * --contacts, 1 thread: 0.02, 0.05, 0.1 gave 2.61, 2.33, 2.38 s of CPU;
 * without it 3.34 s) */
#define VBM_NEAR_Y 0.05

/* E = 1 + t^2's coefficients: z = Pz / E and the other quotients of the
 * arc's integrands (arc_fun.c). */
extern const vbx_ia vbm_arc_E[3];

/* The width of a, a NaN bound counting as infinitely wide. */
static inline double vbm_ia_width(vbx_ia a)
{
    double d = a.hi - a.lo;
    return d == d ? d : INFINITY;
}

/* phi's Taylor coefficients at y = 0 (contact_near's h), made on the
 * arc's first piece near e_j (state 0: not yet, 1: made, -1: the series
 * failed). Made for every owner before (c1k --contacts: 6,283 owners,
 * 104 M instructions, for 2,052 pieces near e_j; bounding 1 - z on the
 * arc's circle instead still left 6,550 arcs). */
typedef struct vbm_phic {
    vbm_s1 phi0;
    int state;
} vbm_phic;

/* The integrands along a circle arc in t: F dphi/dt for the area, the
 * volume and (o.contacts) the contact area. */
typedef struct vbm_arcfun {
    vbm_owner o;
    vbx_ia cA0, s, sA0s, mcs, A1, A2; /* c A0, s, s^2 A0, -c s, e_j in the rotated frame */
    /* the area's and the volume's integrands as quotients of polynomials
     * in t (vbm_arcfun_make) */
    vbx_ia an[3], ad[5], vn[5], vd[7];
    vbx_ia Pz[3], Pq[3];          /* z = Pz / E, q = Pq / E */
    /* the contact's (contact_of): the area's integrand over 1 - z an / cd
     * (its algebraic part Rn / Rd only where contact_of needs it: alg_of) */
    vbx_ia Emz[3], cd[5]; /* ... 1 - z = Emz / E, cd = Po Emz */
    vbm_contact_rat cr; /* the contact's model (contact_tm.c): q' / q^3, S, an / cd */
    vbm_phic *pc;       /* phi's coefficients at y = 0: contact_near */
    int want; /* the values integrated now: bits 1 << VBM_AREA, VBM_VOL, VBM_CON */
} vbm_arcfun;

/* The sums of an arc's pieces: the values, and how many pieces. */
typedef struct vbm_sums {
    vbx_ia v[VBM_NV];
    size_t pieces;
} vbm_sums;

/* --- arc_owner.c: a neighbour's constants as functions of z --- */

/* phi(y) = f(1 - y) with f(z) = N^2 sqrt(N + 2 delta q) / (4 q^3),
 * q = D z + delta: the contact's integrand per solid angle (F = int_z^1 f)
 * as a function of y = 1 - z; its series at `at` (a point, or an interval
 * of y holding 0, where q(0) = D + delta > 0, so that q proven non-zero is
 * proven > 0) into *phi. Returns 0 when q or S = N + 2 delta q is not
 * proven so. */
int vbm_owner_phi(const vbm_owner *o, vbx_ia at, vbm_s1 *phi);

/* F_vol(z) / (1 - z) = K (D (1 + z) + 2 delta) / (D z + delta)^2 at z. */
vbx_ia vbm_owner_fvol_over(const vbm_owner *o, vbx_ia z);

/* F_con(z) = C (G(D + delta) - G(D z + delta)) at a constant z into *F.
 * Returns 0 when an interval cannot bound G there. */
int vbm_owner_fcon(const vbm_owner *o, vbx_ia z, vbx_ia *F);

/* --- arc_fun.c: the integrands' series in t --- */

/* *f for the arc a of owner o (a not on o's own circle), the frame
 * rotated to the arc's middle (cm, sm its cos and sin: vbm_unit_at): the
 * polynomials of the area's, the volume's and (o->contacts) the contact's
 * integrands; pc: the arc's phi cache (state 0), kept by the caller for as
 * long as f. f->want is left 0. */
void vbm_arcfun_make(vbm_arcfun *f, const vbm_owner *o, const vbm_arcrec *a, vbx_ia cm,
                     vbx_ia sm, vbm_phic *pc);

/* The series of the integrands `want` (bits 1 << VBM_AREA, VBM_VOL,
 * VBM_CON) at `at` into v[0..VBM_NV), coefficients up to kmax (the others
 * 0, and the values not wanted 0); with `last`, of the contact the order
 * kmax alone; with `keep` (at a point, kmax VBM1_K) the area's and the
 * volume's moved polynomials in keep[0] and keep[1], for their remainders
 * (vbm1_rational_rest). Returns 1, 2 when the contact's series cannot be
 * bounded near e_j (v[VBM_CON] is then a constant: its bound where `at`
 * ranges), 0 when nothing can. */
int vbm_arcfun_series(const vbm_arcfun *f, int want, vbx_ia at, vbm_s1 *v, int kmax, int last,
                      vbm1_rat *keep);

/* The contact's integrand over t in `at`, no series: F(z) / (1 - z) =
 * f(xi), xi in [z, 1] (F = int_z^1 f), f = N^2 sqrt(S) / (4 q^3) over
 * [z.lo, 1], times the area's integrand, into *b. Returns 0 when an
 * interval cannot bound it. */
int vbm_arcfun_contact_bound(const vbm_arcfun *f, vbx_ia at, vbx_ia *b);

/* --- arc_near.c: the contact where the arc passes near e_j --- */

/* The contact's integrand's series where 1 - z in [0, yhi] over the piece
 * (yhi < VBM_NEAR_Y), by phi's series in y = 1 - z (contact_near in
 * arc_near.c, its derivation there): *con at `at` to the order kmax; *rem
 * (NULL: not wanted) the remainder's bound over `at`, and then of *con the
 * order kmax alone. Makes f->pc's series on first use. Returns 0 when a
 * series cannot be bounded. */
int vbm_arcfun_near(const vbm_arcfun *f, vbx_ia at, int kmax, double yhi, vbm_s1 *con,
                    vbx_ia *rem);

/* --- arc_pieces.c: pieces --- */

/* The integrals over the piece [x0, x1] of the values f->want into
 * v[0..VBM_NV) (those not wanted: any enclosure); `pre` (NULL: none) the
 * integrand's series at the middle already, rpre what vbm_arcfun_series
 * returned for it, prek its kept polynomials; tg the widths asked.
 * Returns 0 when an interval cannot bound them or, with `halves` (the
 * piece may still be split), when the contact's model cannot be made. */
int vbm_arc_piece_values(const vbm_arcfun *f, double x0, double x1, const double *tg, int halves,
                         const vbm_s1 *pre, int rpre, const vbm1_rat *prek, vbx_ia *v);

/* Adds the values f->want of v to *out (the others are not: a zero
 * series' integral is not exactly 0) and counts the piece. */
void vbm_arc_add_piece(const vbm_arcfun *f, const vbx_ia *v, vbm_sums *out);

/* The area and the volume (f->want) over [x0, x1] to the widths tg, first
 * halved as often as the middle's series says they will need, each piece
 * then halved where it falls short; added to *out. *est_area: the area's
 * remainder term at the middle over the whole range (-1 where the series
 * cannot be made), for vbm_arc_march. Returns 0 when an interval cannot
 * bound a piece at its shortest. */
int vbm_arc_planned(const vbm_arcfun *f, double x0, double x1, const double *tg, vbm_sums *out,
                    double *est_area);

/* --- arc_march.c --- */

/* The contact alone (f->want 1 << VBM_CON) over [x0, x1] to the width
 * tg[VBM_CON], stepped along the arc, added to *out (est_area:
 * vbm_arc_planned's, the first piece's length). Returns 0 when an
 * interval cannot bound a piece at its shortest. */
int vbm_arc_march(const vbm_arcfun *f, double x0, double x1, const double *tg, double est_area,
                  vbm_sums *out);

#endif
