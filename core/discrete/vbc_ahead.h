/* Frames in flight (issue 33): a reader thread reads the frames of a
 * trajectory, keeps the selected ones and runs their front half
 * (vbc_run_front: residues left out, grid, the pipe's labels, masks and
 * channel voxels) up to `depth` frames ahead, while the caller runs the
 * back half (vbc_run_back: analysis, pore stage) of the frame before and
 * writes it. Frames come out in frame order, each as vbc_run_frame would
 * have made it, so the tables are the same bytes as the sequential loop's
 * on any depth and any number of threads.
 *
 * What the reader's thread says (warnings, info lines, its error) is held
 * with its frame and said on the caller's context when the caller takes
 * that frame: in the order and at the place the sequential loop says it.
 * A frame's error ends the frames; the ones before it come out first. */
#ifndef VBC_AHEAD_H
#define VBC_AHEAD_H

#include "vb_frames.h"
#include "vbc_run.h"

/* Most frames the reader runs ahead of the caller. */
#define VBC_AHEAD_MAX 8

typedef struct vbc_ahead vbc_ahead;

/* What vbc_ahead_next hands over: one selected frame. */
typedef struct vbc_ahead_frame {
    vbc_run_out o;          /* the front half done (vbc_run_back next) */
    vb_sphere_set *s0;      /* the frame as read (the caller frees it) */
    long index;             /* in the input, from 0 */
    long j;                 /* in the selection, from 0 */
} vbc_ahead_frame;

/* The frames ahead setting: VORBALL_FRAMES_AHEAD when it is an integer 0
 * .. VBC_AHEAD_MAX (0: no reader thread, the sequential loop), else 2. */
int vbc_ahead_depth(void);

/* Starts the reader on the frames of src (open, none read yet) for run r
 * (its cfg's --frames selection f0, f1, fstep; r's pipe is the reader's
 * until vbc_ahead_close: the caller must not run it meanwhile), at most
 * depth (1 .. VBC_AHEAD_MAX) frames ahead. Neither r nor src is owned.
 * VB_OK, VB_ENOMEM, VB_EINTERNAL (no thread could start). */
int vbc_ahead_open(vb_ctx *ctx, vbc_run *r, vb_frame_source *src, int depth, vbc_ahead **out);

/* The next selected frame in order into *f (*have = 1), or *have = 0 at
 * the end of the selection. Waits for the reader when it is behind. A
 * failure of the reader (reading, the grid, the pipe) returns its status
 * with its error on ctx and *have = 0. */
int vbc_ahead_next(vb_ctx *ctx, vbc_ahead *a, vbc_ahead_frame *f, int *have);

/* Stops the reader, drops the frames not taken, adds its counters to
 * ctx's. NULL is allowed. */
void vbc_ahead_close(vb_ctx *ctx, vbc_ahead *a);

#endif
