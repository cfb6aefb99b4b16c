/* GROMACS trajectories: XTC (compressed coordinates) and TRR (full
 * precision), both sequences of XDR frames (big-endian 4-byte words).
 * Coordinates only, one frame in memory at a time; atom identities come from
 * a topology file. Written from the formats' specifications (GROMACS'
 * xtcio/trnio and the public-domain xdrfile library describe them); gzip or
 * bzip2 compressed files are read too (vbi_open_input).
 *
 * XTC: per frame magic 1995 (2023: GROMACS' variant with a 64-bit byte
 * count), atom count, step, time, box, then the coordinates: raw floats for
 * 9 atoms or fewer, else integers at the frame's precision packed by the
 * xtc3d integer compression (coordinates_xtc.c). TRR: per frame magic 1993,
 * version string "GMX_trn_file", the sizes of box, virial, pressure, x, v
 * and f, atom count, step, time and lambda, then those arrays in float or
 * double (told by the sizes). */
#ifndef VB_XDR_H
#define VB_XDR_H

#include <stdint.h>
#include <stdio.h>

#include "vb.h"

typedef struct vb_xdr_traj vb_xdr_traj;

/* One frame's header. */
typedef struct vb_xdr_frame {
    int64_t step;
    double time;     /* ps */
    double box[9];   /* nm, row-major as stored (zero when the frame has none) */
    double precision; /* XTC: coordinates are multiples of 1/precision nm (0 for raw floats) */
    int is_double;   /* TRR written in double precision */
} vb_xdr_frame;

/* Opens an XTC or TRR file (told by its magic number; compressed ones
 * too) and reads the first frame's header for its atom count. VB_EIO when it
 * cannot be opened, VB_EINPUT_FORMAT when it is neither, VB_EINPUT_TRAJECTORY
 * for a damaged first header. Close with vb_xdr_close. */
int vb_xdr_open(vb_ctx *ctx, const char *path, vb_xdr_traj **out);

/* As vb_xdr_open over an open stream (the fuzz target's fmemopen); the
 * reader closes f. `name` is used in messages. */
int vb_xdr_open_stream(vb_ctx *ctx, const char *name, FILE *f, vb_xdr_traj **out);

/* Atoms per frame, and VBI_TRAJ_XTC or VBI_TRAJ_TRR. */
size_t vb_xdr_atoms(const vb_xdr_traj *t);
int vb_xdr_kind(const vb_xdr_traj *t);

/* Reads the next frame's coordinates, in nm as stored (floats widened to
 * double exactly), into xyz (3 * vb_xdr_atoms doubles: x0 y0 z0 x1 ...)
 * and its header into *fr (may be NULL). *got = 1 for a frame, 0 at the
 * end. TRR frames without coordinates are skipped (counted in warning
 * W718 at the end). VB_EINPUT_TRAJECTORY (naming the frame and byte
 * offset) for damaged or truncated frames, VB_EINPUT_TOPOLOGY when a frame's
 * atom count changes, VB_ENOMEM. */
int vb_xdr_next(vb_ctx *ctx, vb_xdr_traj *t, double *xyz, vb_xdr_frame *fr, int *got);

/* NULL is allowed. */
void vb_xdr_close(vb_xdr_traj *t);

/* The xtc3d decoder: natoms coordinates from `len` bytes of packed data
 * (minint, maxint, smallidx as in the frame), as integers into ints
 * (3 * natoms). Returns 0, or -1 when the data do not decode to natoms
 * atoms (damaged). For tests and the XTC reader. */
int vb_xtc_unpack(const unsigned char *data, size_t len, size_t natoms, const int32_t minint[3],
                  const int32_t maxint[3], int32_t smallidx, int32_t *ints);

#endif
