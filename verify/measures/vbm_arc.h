/* The integrals along one circle arc of a neighbour's region of directions
 * (arc_integral.c and the files of vbm_arcfun.h), which stokes_cell.c sums
 * into an atom's measures. */
#ifndef VBM_ARC_H
#define VBM_ARC_H

#include <stddef.h>
#include <stdint.h>

#include "vbm_cell.h"
#include "vbm_series1.h"
#include "vbx_ia.h"

enum { VBM_AREA, VBM_VOL, VBM_CON, VBM_NV }; /* the values integrated along an arc */

/* An arc of neighbour j's region (vbm_cap_arcs' arc with its circle). */
typedef struct vbm_arcrec {
    uint32_t j;
    int own;                   /* the arc lies on j's cap circle */
    vbx_ia c, s, A0, A1, A2;   /* the circle, and e_j in its frame */
    vbx_ia p[2], q[2];
    double tp, tq;
    vbx_ia v[VBM_NV];          /* the arc's integrals: area, volume, contact */
} vbm_arcrec;

/* The constants of neighbour j's integrands, the same on every arc of its
 * region (made once per region, not per arc: with contacts a log, a root
 * and series each; 1crn --contacts, 1 thread, ~7 % of the CPU when made
 * per arc). phi's series at y = 0 is not here: arc_near.c makes it
 * only on an arc with a piece near e_j (vbm_phic, vbm_arcfun.h). */
typedef struct vbm_owner {
    vbx_ia D, delta, N, K; /* |d_j|, and K = N^3 / (48 (D + delta)^2) */
    vbx_ia rN, hN, kL, lnd; /* sqrt N, 1 / (2 N), delta^2 / (2 N sqrt N), log (2 |delta|) */
    vbx_ia C, G1;           /* N^2 / (4 D), G(D + delta) */
    int contacts;           /* in->contacts and nb[j].con (else the face's other atom
                             * integrates it) */
} vbm_owner;

/* Neighbour j's constants into *o, D enclosing |d_j|. Returns 0 when an
 * interval cannot bound them (the arcs of j cannot be integrated then). */
int vbm_owner_make(const vbm_atom_in *in, size_t j, vbx_ia D, vbm_owner *o);

/* The integrals of the arc (solid angle's, volume's and, with
 * o->contacts, the contact's: F dphi along it) into a->v, each to the
 * width tg[VBM_AREA..VBM_CON]; o: its neighbour's constants
 * (vbm_owner_make). With `again`, a->v holds
 * the arc's enclosures from an earlier call: the area and volume are kept
 * when both meet their targets, the contact when it does (only the others
 * are integrated again). Adds the Taylor-model pieces used to *pieces.
 * Returns 0 when an interval cannot bound them. */
int vbm_arc_integrate(const vbm_owner *o, vbm_arcrec *a, const double *tg, int again,
                      size_t *pieces);

/* Whether some width of v[0..VBM_NV) exceeds its target in tg (a NaN
 * bound counts as infinitely wide). */
int vbm_arc_over(const vbx_ia *v, const double *tg);

#endif
