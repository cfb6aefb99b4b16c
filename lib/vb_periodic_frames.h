/* The periodic diagram of every selected frame of a trajectory, each in
 * its own box (issue 34): the frames of an XTC, TRR or DCD over its
 * topology, or the models of a multi-model file, with the box each frame
 * carries (vb_frame_source_next) or one box for all. */
#ifndef VB_PERIODIC_FRAMES_H
#define VB_PERIODIC_FRAMES_H

#include "vb.h"
#include "vb_cells.h"
#include "vb_frames.h"
#include "vb_periodic.h"

/* Called for every selected frame with its periodic result and the box
 * it was computed in, which the callee may read but not keep; a status
 * other than VB_OK stops the run with it. */
typedef int (*vb_periodic_frame_fn)(void *arg, long frame, int model, const vb_sphere_set *set,
                                    const vb_box *box, const vb_periodic_result *res);

/* The periodic vertices (vb_periodic_vertices_run, the default backends,
 * cfg as for one set) of the selected frames of `path` (with traj_path,
 * of that trajectory over the topology `path`), read with ro, in frame
 * order, each handed to fn. box: one box for every frame, or NULL for each
 * frame's own (VB_EINPUT_BOX naming the frame when one has none). A
 * binary frame gets decimals of its doubles first (vb_cells_frame_decimals).
 * *selected (may be NULL) gets the frames run. VB_EINPUT_MODEL when no frame
 * is selected; the readers' and vb_periodic_vertices_run's errors. */
int vb_periodic_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                           const vb_read_options *ro, const vb_frame_range *range,
                           const vb_box *box, const vb_vertices_config *cfg,
                           vb_periodic_frame_fn fn, void *arg, long *selected);

/* The periodic cell measures (vb_cells_run_periodic, opt) of the selected
 * frames, as vb_periodic_run_frames selects them and gives each its box
 * (box, or each frame's own) and its decimals, each handed to fn
 * (vb_cells.h) in frame order. *selected (may be NULL) gets the frames
 * measured. VB_EINPUT_BOX naming the frame when it has no box and box is
 * NULL, VB_EINPUT_MODEL when no frame is selected; the readers',
 * vb_cells_run_periodic's and fn's statuses otherwise. */
int vb_cells_run_frames_periodic(vb_ctx *ctx, const char *path, const char *traj_path,
                                 const vb_read_options *ro, const vb_frame_range *range,
                                 const vb_box *box, const vb_measure_options *opt,
                                 vb_cells_frame_fn fn, void *arg, long *selected);

#endif
