/* The selected frames of a structure or trajectory, one by one (internal
 * to lib/: the frame loop of vb_cells_run_frames and
 * vb_periodic_run_frames). */
#ifndef VB_FRAMES_EACH_H
#define VB_FRAMES_EACH_H

#include "vb_frames.h"

/* Called with each selected frame (index from 0, model, the set, which the
 * callee may change but not keep); a status other than VB_OK stops. */
typedef int (*vb_frame_each_fn)(void *arg, long index, int model, vb_sphere_set *set);

/* Opens the frames of path (with traj_path: that trajectory over the
 * topology path; vb_frame_source_open), calls fn for every frame in range,
 * in order, and closes. *selected (may be NULL): the frames handed to fn.
 * VB_EINPUT_MODEL when none is selected; the readers' and fn's errors. */
int vb_frames_each(vb_ctx *ctx, const char *path, const char *traj_path,
                   const vb_read_options *ro, const vb_frame_range *range, vb_frame_each_fn fn,
                   void *arg, long *selected);

#endif
