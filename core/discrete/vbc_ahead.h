/* Frames in flight (issue 33): a reader thread reads the frames of a
 * trajectory, keeps the selected ones and runs their front half
 * (vbc_run_front: residues left out, grid, the pipe's labels, masks and
 * channel voxels) up to `depth` frames ahead, while the caller analyses
 * the frames before (vbc_flight.h; with VBC_FRONT_ANALYSE the reader
 * does), runs their back half (vbc_run_back) and writes them. Frames come out in frame order, each as vbc_run_frame would
 * have made it, so the tables are the same bytes as the sequential loop's
 * on any depth and any number of threads.
 *
 * With depth > 0 the reading itself runs on a second thread (the fetcher),
 * up to depth frames ahead of the front, so that reading and the device's
 * part of the frames overlap too.
 *
 * What the reader's thread says (warnings, info lines, its error) is held
 * with its frame (vbc_held.h) and the caller says it on its context when it
 * writes that frame: in the order and at the place the sequential loop
 * says it. A frame's error ends the frames; the ones before it come out
 * first. Depth 0 runs the same steps on the caller's thread, in
 * vbc_ahead_next (no reader thread: the frames in analysis, vbc_flight.h,
 * still overlap the reading). */
#ifndef VBC_AHEAD_H
#define VBC_AHEAD_H

#include "vb_frames.h"
#include "vbc_held.h"
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
    vbc_held *held;         /* what reading and the front said (the caller says and frees it) */
    double t_read, cpu_read; /* vb_now() and vb_cpu_now() when its reading began */
    double ms_read;         /* its reading (the frames skipped before it included) */
} vbc_ahead_frame;

/* The frames ahead setting: VORBALL_FRAMES_AHEAD when it is an integer 0
 * .. VBC_AHEAD_MAX (0: no reader thread, the sequential loop), else 2. */
int vbc_ahead_depth(void);

/* Starts the reader on the frames of src (open, none read yet) for run r
 * (its cfg's --frames selection f0, f1, fstep; r's pipe is the reader's
 * until vbc_ahead_close: the caller must not run it meanwhile), at most
 * depth (0 .. VBC_AHEAD_MAX; 0: no thread) frames ahead, each frame's
 * front run in mode `front` (vbc_run_front). Neither r nor src is owned.
 * VB_OK, VB_ENOMEM, VB_EINTERNAL (no thread could start). */
int vbc_ahead_open(vb_ctx *ctx, vbc_run *r, vb_frame_source *src, int depth, int front,
                   vbc_ahead **out);

/* The next selected frame in order into *f (*have = 1), or *have = 0 at
 * the end of the selection. Waits for the reader when it is behind. A
 * failure of the reader (reading, the grid, the pipe) returns its status
 * with *have = 0. Either way f->held holds the lines said since the frame
 * before, the error last (vbc_held_replay says them; the caller frees it). */
int vbc_ahead_next(vbc_ahead *a, vbc_ahead_frame *f, int *have);

/* Stops the reader, drops the frames not taken, adds its counters to
 * ctx's. NULL is allowed. */
void vbc_ahead_close(vb_ctx *ctx, vbc_ahead *a);

#endif
