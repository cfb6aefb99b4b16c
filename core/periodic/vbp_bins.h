/* Spatial bins of a periodic box (internal to core/periodic/): the box cut
 * into nb[0] x nb[1] x nb[2] bins along its fractional coordinates, the
 * atoms sorted into them (wrapped into the box), and per bin a proven
 * upper bound of the largest empty sphere centred in it (bins.c states
 * the argument); and the per-bin reach built on them (reach.c). */
#ifndef VBP_BINS_H
#define VBP_BINS_H

#include <stddef.h>
#include <stdint.h>

#include "vb_periodic.h"

typedef struct vbp_bins {
    int nb[3];          /* bins per edge (1 .. 512) */
    double inv[9];      /* vb_box_inverse */
    double h[3];        /* the box's heights across edges a, b, c */
    double *F;          /* per bin (index (b0 nb1 + b1) nb2 + b2): >= f over the bin grown
                         * by `grow`, plus 2 slack (see bins.c) */
    double rho;         /* the largest F: >= f everywhere */
    double grow;        /* how far (distance) past its bin each F holds */
} vbp_bins;

/* Bins of about one atom each for the validated atoms in box, and their
 * bounds F (bins.c). grow: the distance past each bin that its bound must
 * cover (the doubles' error of a point's bin, plus a caller's slack);
 * slack: added twice more to every F (a verifier's tolerance). VB_OK or
 * VB_ENOMEM (no message). */
int vbp_bins_build(const vb_sphere_set *atoms, const vb_box *box, double grow, double slack,
                   double margin, vbp_bins *out);

/* The bin of fractional coordinates f (wrapped into the box). */
size_t vbp_bins_index(const vbp_bins *bn, const double f[3]);

void vbp_bins_free(vbp_bins *bn);

/* The per-bin reach (reach.c): over the unwrapped bins lo[k] .. lo[k] +
 * n[k] - 1 (bin b covers fractional [b / nb, (b + 1) / nb)), need[W] = 1
 * when a sphere centred in W may touch a periodic vertex. */
typedef struct vbp_reach {
    long lo[3], n[3];
    uint8_t *need;
} vbp_reach;

/* Builds the reach for the atoms (exact decimals, validated) whose
 * images are kept within fractional [klo, khi]: VB_OK, VB_ENOMEM, or 1
 * when the bins over that range would be too many (no reach: keep the
 * full layer). rmax: the largest radius. */
int vbp_reach_build(const vbp_bins *bn, const vb_box *box, const vb_sphere_set *atoms,
                    const double klo[3], const double khi[3], double rmax, double margin,
                    vbp_reach *out);

/* Whether a sphere centred at unwrapped fractional coordinates f may be
 * needed (need[] of its bin; 0 outside the range). */
int vbp_reach_keeps(const vbp_reach *r, const vbp_bins *bn, const double f[3]);

void vbp_reach_free(vbp_reach *r);

#endif
