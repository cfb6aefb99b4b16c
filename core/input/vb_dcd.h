/* DCD trajectories (CHARMM / NAMD / X-PLOR binary): coordinates only, one
 * frame in memory at a time; atom identities come from a topology file (PDB).
 * Both byte orders, CHARMM unit-cell records, fixed atoms (NAMNF > 0) and the
 * 4D extra record are understood; 8-byte record markers are not. */
#ifndef VB_DCD_H
#define VB_DCD_H

#include "vb.h"

typedef struct vb_dcd vb_dcd;

/* Opens a DCD file and reads its header. VB_EIO when it cannot be opened,
 * VB_EINPUT_FORMAT when it is not a DCD, VB_EINPUT_MALFORMED for a damaged
 * header. Close with vb_dcd_close. */
int vb_dcd_open(vb_ctx *ctx, const char *path, vb_dcd **out);

/* Atoms per frame. */
size_t vb_dcd_atoms(const vb_dcd *d);

/* Frames announced by the header (NSET; writers that stream may leave 0). */
long vb_dcd_header_frames(const vb_dcd *d);

/* Time step in the header (AKMA units for CHARMM/NAMD). */
double vb_dcd_delta(const vb_dcd *d);

/* Reads the next frame into x, y, z (vb_dcd_atoms entries each) and, when the
 * file has unit cells and cell is not NULL, the 6 cell numbers as stored.
 * *got = 1 for a frame, 0 at the end. A truncated last frame ends the file
 * with warning W801. VB_EINPUT_MALFORMED on a damaged record. */
int vb_dcd_next(vb_ctx *ctx, vb_dcd *d, double *x, double *y, double *z, double cell[6], int *got);

void vb_dcd_close(vb_dcd *d);

/* A minimal CHARMM-style writer (native byte order, no unit cell, no fixed
 * atoms), for tests and conversions. */
typedef struct vb_dcd_writer vb_dcd_writer;

/* Creates `path` for natoms atoms per frame, with a one-line title. VB_EIO. */
int vb_dcd_writer_open(vb_ctx *ctx, const char *path, size_t natoms, double delta,
                       const char *title, vb_dcd_writer **out);

/* Appends a frame (stored as float32, as DCD does). VB_EIO. */
int vb_dcd_writer_frame(vb_ctx *ctx, vb_dcd_writer *w, const double *x, const double *y,
                        const double *z);

/* Patches the frame count into the header and closes. VB_EIO. NULL allowed. */
int vb_dcd_writer_close(vb_ctx *ctx, vb_dcd_writer *w);

#endif
