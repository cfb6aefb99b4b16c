/* The frames of a molecule for the discrete pipelines (channels): the
 * models of a multi-model PDB / PQR / mmCIF / GRO / XYZR file, or the
 * frames of a DCD, XTC or TRR trajectory over a topology file that lists
 * its atoms (PDB, GRO, mmCIF, PQR, or a PSF).
 *
 * Every frame is checked as the sphere input of every command is: frames
 * read from text by vb_spheres_validate (radius < 0, duplicates, absurd
 * magnitudes: the same numbered errors as `vorball vertices`); trajectory
 * frames, which carry no decimals, coordinate by coordinate (E102 for a NaN or
 * infinite value, E107 beyond 1e9, naming the frame), with their radii from
 * the validated topology. */
#ifndef VB_FRAMES_H
#define VB_FRAMES_H

#include "vb_spheres.h"

typedef struct vb_frame_source vb_frame_source;

/* Opens the frames of `path` ("-" = stdin), or with dcd_path the frames of
 * that trajectory (DCD, XTC or TRR, told by its magic number; compressed
 * too) with `path` its topology (a file: every atom of the trajectory,
 * water and hydrogens too; ro->keep_water and ro->drop_hydrogens then
 * select the atoms of the frames). VB_EINPUT_TOPOLOGY when the atom counts
 * differ, VB_EINPUT_FORMAT when the trajectory is none of the three,
 * VB_EINPUT_EMPTY when no atom is left, the readers' errors, VB_ENOMEM.
 * Close with vb_frame_source_close. */
int vb_frame_source_open(vb_ctx *ctx, const char *path, const char *dcd_path,
                         const vb_read_options *ro, vb_frame_source **out);

/* The next frame, checked (caller frees; *out NULL at the end, with VB_OK)
 * and its model number (the MODEL serial, or 1 + the frame index of a
 * DCD). A trajectory frame's box (XTC/TRR box vectors, DCD unit cell) is
 * the set's box (vb_frame_box_xdr, vb_frame_box_dcd), NULL when the frame
 * has none; a text frame's is its reader's. */
int vb_frame_source_next(vb_ctx *ctx, vb_frame_source *src, vb_sphere_set **out, int *model);

/* NULL is allowed. */
void vb_frame_source_close(vb_frame_source *src);

/* The box of an XTC/TRR frame (frame_box.c): nm (9 numbers, rows a, b, c,
 * floats widened unless is_double) to exact decimals in Angstrom, each the
 * shortest decimal that reads back to the stored number. 1 and *out set,
 * or 0 (no box: zero, flat, out of range). */
int vb_frame_box_xdr(const double nm[9], int is_double, vb_box *out);

/* The box of a DCD unit cell (A, gamma, B, beta, alpha, C as stored;
 * angles in degrees, or their cosines when all three lie in [-1, 1]):
 * 1 and *out set, or 0 (no box). */
int vb_frame_box_dcd(const double cell[6], vb_box *out);

/* Which frames: index >= first, index < end (end < 0: to the last), every
 * step-th from first (step >= 1), frames counted from 0 (`--frames`). */
typedef struct vb_frame_range {
    long first, end, step;
} vb_frame_range;

/* Parses "A:B:S" (parts optional: "A:", ":B", "A:B", "A:B:S"; a single
 * number "A" is that frame alone; parts up to 1e9) into *out. 0, or -1 for
 * text that is not such a range with B > A and S >= 1. */
int vb_frame_range_parse(const char *text, vb_frame_range *out);

/* 1 when frame `index` is in the range, else 0. */
int vb_frame_range_has(const vb_frame_range *r, long index);

#endif
