/* The cell measures in one call: per-atom volume and SAS area and the
 * contact areas of the additively weighted cells inside the probe-expanded
 * balls, as proven enclosures (the method and the result's struct:
 * vb_measures.h), of a sphere set or of every selected frame of a
 * trajectory. `vorball cells` and vorball.cells() are these calls. */
#ifndef VB_CELLS_H
#define VB_CELLS_H

#include "vb.h"
#include "vb_frames.h"
#include "vb_measures.h"
#include "vb_periodic.h"

/* The measures of `set` (as read or built; validated here on a shallow
 * copy when its contained marks are not set: VB_EINPUT_* as
 * vb_spheres_validate, with min_count 1). A set without exact decimals
 * (a binary trajectory's frame) gets decimals of its doubles first
 * (vb_cells_frame_decimals). On VB_OK *out owns the arrays
 * (vb_cell_measures_free); otherwise *out is zeroed and the status says
 * why: the validation's, vb_cell_measures_compute's (VB_EMISUSE for a
 * negative probe or a tolerance outside (0, 1)), VB_ENOMEM. */
int vb_cells_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_measure_options *opt,
                 vb_cell_measures *out);

/* The measures of the atoms of `set` repeated by `box` (issue 34): each
 * atom once, its cell cut by every atom and image whose expanded ball can
 * meet its own (all within 2 (Rmax + probe), core/periodic/images.c); out
 * as vb_cells_run's with out->n = set->n, out->periodic 1 and each
 * periodic contact once, with the shift of its second atom (vb_contact).
 * Without a probe limit the volumes of a box the expanded balls cover sum
 * to the box's volume. Returns vb_cells_run's statuses and those of
 * vb_periodic_images_build (VB_EINPUT_BOX_SMALL: 2 (Rmax + probe) beyond
 * 4 box heights; VB_EINPUT_DUPLICATE: two atoms equal modulo the box). */
int vb_cells_run_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_box *box,
                          const vb_measure_options *opt, vb_cell_measures *out);

/* Gives a set read without decimals (set->ex NULL: a DCD, XTC or TRR
 * frame) the decimals of its doubles (the shortest of 15, 16 or 17
 * significant digits whose nearest double is the coordinate or radius
 * itself). A set with decimals is
 * left alone. VB_OK or VB_ENOMEM (the set unchanged). */
int vb_cells_frame_decimals(vb_ctx *ctx, vb_sphere_set *set);

/* Called for every selected frame with its measures, which the callee may
 * read but not keep; a status other than VB_OK stops the run with it. */
typedef int (*vb_cells_frame_fn)(void *arg, long frame, int model, const vb_sphere_set *set,
                                 const vb_cell_measures *m);

/* The measures of the selected frames of `path` (its models; with
 * traj_path, the frames of that DCD/XTC/TRR trajectory over the topology
 * `path`), read with `ro` (vb_frame_source_open: ro->model picks one
 * model), in frame order, each handed to fn. *selected (may be NULL) gets
 * the frames measured. VB_EINPUT_MODEL when no frame is selected; the
 * readers', vb_cells_run's and fn's statuses otherwise. */
int vb_cells_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                        const vb_read_options *ro, const vb_frame_range *range,
                        const vb_measure_options *opt, vb_cells_frame_fn fn, void *arg,
                        long *selected);

/* The results page of one structure's measures (`vorball cells --html`
 * without frames): titled `title`, the molecule with its atoms coloured
 * by volume, SAS or (with contacts) contact area, as one frame labelled
 * "frame 0", written to path. VB_OK; VB_EMISUSE when this build has no
 * viewer (the message says how to get it); the page's size and I/O
 * errors. Nothing is left at path on failure. */
int vb_cells_page_write(vb_ctx *ctx, const char *path, const char *title,
                        const vb_sphere_set *set, const vb_cell_measures *m, int contacts);

#endif
