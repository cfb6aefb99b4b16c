/* Periodic boxes from edge vectors, from lengths and angles (the GRO and
 * PDB box lines, trajectory frames) and from `--box`: the box is a property
 * of the sphere set (vb_sphere_set.box), read here with the spheres; the
 * periodic diagram on it is core/periodic (vb_periodic.h). */
#ifndef VB_BOX_H
#define VB_BOX_H

#include "vb_spheres.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The box with edge vectors ev (rows a, b, c). Returns VB_OK, or
 * VB_EINPUT_BOX naming file:line when the vectors are linearly dependent
 * (decided exactly on the decimals) or a coordinate has more digits than
 * an image needs room for. file may be NULL. Allocates nothing. */
int vb_box_from_vectors(vb_ctx *ctx, const vb_decimal ev[9], const char *file, long line,
                        vb_box *out);

/* For readers: 1 and *out set when ev is a box (as vb_box_from_vectors
 * would accept), else 0 and no message (a file's zero or flat box is no
 * box: --periodic then asks for --box). */
int vb_box_try(const vb_decimal ev[9], vb_box *out);

/* The box of edge lengths len (a, b, c) and angles deg (alpha between b
 * and c, beta between a and c, gamma between a and b, in degrees), in the
 * convention of GROMACS and PDB: a along x, b in the xy plane. With three
 * right angles the vectors are the exact lengths; otherwise the vectors'
 * components are irrational in general: each is computed in double and
 * rounded to 6 decimals (1e-6 of the input unit), and that decimal box is
 * the exact box from there on. VB_OK or VB_EINPUT_BOX (an angle outside
 * (0, 180), a length <= 0, angles that make no cell); ctx NULL: no
 * message (a reader's try). */
int vb_box_from_cell(vb_ctx *ctx, const vb_decimal len[3], const vb_decimal deg[3],
                     const char *file, long line, vb_box *out);

/* The box of `--box`: n = 3 numbers (a b c, a rectangular box), 6 (a b c
 * alpha beta gamma) or 9 (the vectors a, b, c, as rows). VB_OK,
 * VB_EINPUT_BOX (wrong count, malformed number, no cell). */
int vb_box_parse_args(vb_ctx *ctx, const char *const *tok, int n, vb_box *out);

/* Fractional coordinates of p (doubles, for bounds with margins only):
 * p = f[0] a + f[1] b + f[2] c. inv is vb_box_inverse's. */
void vb_box_inverse(const vb_box *box, double inv[9]);

#ifdef __cplusplus
}
#endif
#endif
