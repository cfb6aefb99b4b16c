/* Frames in analysis at once (issue 33): a window of up to `width`
 * frames whose front half is done (vbc_ahead.h: read, grid, the pipe) and
 * whose analysis (vbc_run_analyse: components, centrelines, and the pore
 * stage once its request is the frame's: fixed, or the frames before it
 * out of the window, vbc_run_gate; with the analysis beside the pore
 * stage, vbc_frame_beside, both wait for that) runs on a thread of its own
 * each, while the caller's thread takes the next frames in and writes the
 * oldest. The
 * frames leave the window in the order they came, each with what its
 * reading, front and analysis said (held, vbc_held.h), so the outputs and
 * the warnings are the same bytes as the sequential loop's for any width,
 * depth and number of threads.
 *
 * Memory: every frame in the window, in the reader's ring and in the
 * reader's hands holds its spheres, packed atoms and the pipe's outputs
 * (flag volume: a byte per voxel; labels: 4; 4 to 12 bytes per channel
 * voxel) and its analysis' scratch. vbc_flight_fit bounds them by a budget
 * (VORBALL_FRAMES_MEMORY) measured on the first frame. */
#ifndef VBC_FLIGHT_H
#define VBC_FLIGHT_H

#include "vbc_ahead.h"

/* Most frames in analysis at once. */
#define VBC_FLIGHT_MAX 16

typedef struct vbc_flight vbc_flight;

/* The width asked for: VORBALL_FRAMES_IN_FLIGHT when it is an integer 1 ..
 * VBC_FLIGHT_MAX (*given = 1), else (*given = 0) from the thread count
 * (vb_threads): half the threads, 1 .. 8. */
int vbc_flight_width(int *given);

/* The budget for the frames held at once in bytes: VORBALL_FRAMES_MEMORY
 * (MiB, a positive integer; *given = 1), else a quarter of the physical
 * memory (*given = 0). */
size_t vbc_flight_budget(int *given);

/* The bytes a frame in flight holds, bounded from the fronted frame o (its
 * spheres s0 as read, its buffers, its analysis' scratch) with half again
 * for later frames. */
size_t vbc_flight_frame_bytes(const vbc_run_out *o, const vb_sphere_set *s0);

/* The width that fits `budget` bytes with frames of `per` bytes when
 * `ahead` more are held by the reader (its ring, its fetcher's ring of
 * frames as read, counted as whole frames, and its hands: 2 depth + 1):
 * min(width, budget / per - ahead). A given width that does not fit, or no
 * width of 1 that fits, is E127 (VB_EINPUT_FRAMES_MEMORY), saying the bytes
 * per frame and the budget; *out is the width. */
int vbc_flight_fit(vb_ctx *ctx, int width, int width_given, size_t budget, size_t per,
                   int ahead, int *out);

/* A window of `width` (1 .. VBC_FLIGHT_MAX) frames of run r. VB_OK or
 * VB_ENOMEM. */
int vbc_flight_open(vb_ctx *ctx, vbc_run *r, int width, vbc_flight **out);

/* Frames in the window, and its width (vbc_flight_shrink may lower it). */
int vbc_flight_count(const vbc_flight *w);
int vbc_flight_room(const vbc_flight *w);
void vbc_flight_shrink(vbc_flight *w, int width);

/* Takes the fronted frame *f (its held lines included) into the window and
 * starts its analysis on a thread (run at once on this one when no thread
 * starts). The window must have room. *f is emptied. VB_OK or VB_ENOMEM
 * (then *f is dropped, its lines said on ctx). */
int vbc_flight_push(vb_ctx *ctx, vbc_flight *w, vbc_ahead_frame *f);

/* The oldest frame out of the window: opens its gate (the caller has run
 * the back half, vbc_run_back, of every frame popped before it), waits for
 * its analysis, says its held
 * lines on ctx (reading and front first), and fills *f for vbc_run_back
 * (f->held NULL). Returns its status; after a failure, its error said on
 * ctx, *f holds nothing. The window must not be empty. */
int vbc_flight_pop(vb_ctx *ctx, vbc_flight *w, vbc_ahead_frame *f);

/* Opens the gates of the frames left (their pore stages not run), waits
 * for them and drops them, their lines unsaid; adds the
 * analyses' counters to ctx's. NULL is allowed. */
void vbc_flight_close(vb_ctx *ctx, vbc_flight *w);

#endif
