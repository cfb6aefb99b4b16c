/* The integrands of the cell measures per da db on a cube face, as Taylor
 * models (integrands.c), and the integration of patches cut by one curve
 * (cut_patches.c). See cell_patches.c for the formulas. */
#ifndef VBM_PIECE_H
#define VBM_PIECE_H

#include "vbm_cell.h"
#include "vbm_series.h"

/* a is exactly [0, 0] (a difference of equal radii). */
static inline int vbm_ia_is_zero(vbx_ia a)
{
    return a.lo == 0.0 && a.hi == 0.0;
}

/* The axes of a face: the direction is sigma e_w + a e_p + b e_q. */
typedef struct vbm_axes {
    int w, p, q;
    double sigma;
} vbm_axes;

/* Series of the three integrands where `owner` (-1: the ball's sphere, else
 * a neighbour index) owns the directions (a, b) (given as series): vol, sas
 * and con (contact area, owner's face). Returns 0 when a denominator or a
 * root's argument is not proven away from 0. */
int vbm_piece(const vbm_atom_in *in, int owner, const vbm_axes *ax, const vbm_ser *a,
              const vbm_ser *b, vbm_ser *vol, vbm_ser *sas, vbm_ser *con);

/* The solid angle of the patch [a0, a1] x [b0, b1] of a cube face, in
 * closed form (signed corner terms atan(a b / sqrt(1 + a^2 + b^2)),
 * vbm_ia_atan). */
vbx_ia vbm_solid_angle(double a0, double a1, double b0, double b1);

/* Enclosures of atan x and log x (x.lo > 0) in double intervals with
 * a-priori remainder bounds (integrands.c: series after an exact range
 * reduction, at x's middle where x is narrow, widened by the mean value
 * theorem); MPFR's outward-rounded values of x's ends where x is not
 * finite. */
vbx_ia vbm_ia_atan(vbx_ia x);
vbx_ia vbm_ia_log(vbx_ia x);

/* Frees the calling thread's MPFR constant cache: atan keeps pi (log, log
 * 2) there, and a worker thread that ends with it leaves it behind
 * (LeakSanitizer in CI). Called once per atom, not per call: rebuilding pi
 * at every atan was most of an arc's closed form. */
void vbm_ia_release(void);

/* A curve F = l0 + la a + lb b - kappa s = 0 across a patch; F > 0 is where
 * owner `pos` owns, F < 0 where `neg` does (-1: the ball). */
typedef struct vbm_curve {
    vbx_ia l0, la, lb, kappa;
    int pos, neg;
} vbm_curve;

/* The sign of F over the box A x B (s: an enclosure of sqrt(1 + a^2 + b^2)
 * there): 1 where F > 0 is proven on all of it (`pos` owns it), -1 where
 * F < 0 is (`neg` owns it), 0 when unproven (cell_patches.c; the pairwise
 * test and the cut routes share it). */
int vbm_curve_sign(const vbm_curve *cv, vbx_ia A, vbx_ia B, vbx_ia s);

/* Taylor-model integrals over the box [a0, a1] x [b0, b1] of face `ax`
 * owned by `owner` alone (-1: the ball): volume, SAS and contact area
 * (the latter [0, 0] unless owner >= 0 and in->contacts). Returns 0 when
 * vbm_piece cannot bound an integrand there. */
int vbm_box_integrate(const vbm_atom_in *in, int owner, const vbm_axes *ax, double a0, double a1,
                      double b0, double b1, vbx_ia *vol, vbx_ia *sas, vbx_ia *con);

/* Integrates the patch [a0, a1] x [b0, b1] of face `ax` split by the curve
 * into its two single-owner parts, as the region between an edge and the
 * curve b = b*(a) (or a = a*(b)) mapped onto a box: enclosures of the
 * volume, SAS and contact areas of `pos` and `neg` (0 where they own
 * nothing). A curve that leaves through the side it is a graph over (it
 * clips a corner, or crosses the patch twice) is cut there (cut_clipped):
 * the strips between its exits are integrated as above or, where F has one
 * sign, whole, and thin slivers around the exits get min..max bounds.
 * Returns 0 when no route proves the split (then the caller refines). */
int vbm_cut_integrate(const vbm_atom_in *in, const vbm_axes *ax, const vbm_curve *cv, double a0,
                      double a1, double b0, double b1, vbx_ia *vol, vbx_ia *sas, vbx_ia *con_pos,
                      vbx_ia *con_neg);

#endif
