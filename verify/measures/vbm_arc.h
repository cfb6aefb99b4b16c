/* The integrals along one circle arc of a neighbour's region of directions
 * (arc_integral.c), which stokes_cell.c sums into an atom's measures. */
#ifndef VBM_ARC_H
#define VBM_ARC_H

#include <stddef.h>
#include <stdint.h>

#include "vbm_cell.h"
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

/* The integrals of the arc (solid angle's, volume's and, with
 * in->contacts, the contact's: F dphi along it) into a->v, each to the
 * width tg[VBM_AREA..VBM_CON]; D encloses |d_j|. With `again`, a->v holds
 * the arc's enclosures from an earlier call: the area and volume are kept
 * when both meet their targets, the contact when it does (only the others
 * are integrated again). Adds the Taylor-model pieces used to *pieces.
 * Returns 0 when an interval cannot bound them. */
int vbm_arc_integrate(const vbm_atom_in *in, vbx_ia D, vbm_arcrec *a, const double *tg,
                      int again, size_t *pieces);

/* Whether some width of v[0..VBM_NV) exceeds its target in tg (a NaN
 * bound counts as infinitely wide). */
int vbm_arc_over(const vbx_ia *v, const double *tg);

#endif
