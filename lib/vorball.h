/* vorball: the library's one public header. A program outside the tree
 * includes this file alone (`pkg-config --cflags vorball`) and links
 * libvorball; the headers it pulls in are the installed set, nothing more
 * (lib/CMakeLists.txt installs exactly them; tests/pipeline/install.sh
 * compiles a client against them).
 *
 * What a reader finds behind it, one flow per line:
 *   - the context, status codes and the diagnostics catalogue (vb.h,
 *     vb_diag.h): every call takes the context first and returns a status;
 *     vb_errmsg says what failed;
 *   - spheres from files, arrays and trajectory frames (vb_spheres.h,
 *     vb_frames.h);
 *   - the vertex flow with its default backends (vb_default.h:
 *     vb_vertices_run_default) and with its completion -- arc closure,
 *     faces and edges, the certificate -- in one call (vb_complete.h:
 *     vb_vertices_run_complete); vertex files read and written
 *     (vb_vertex_io.h) and shown on a results page (vb_vertex_page.h);
 *   - cell measures: per-atom volume and SAS area and contact areas as
 *     proven enclosures, of a set or of a trajectory's frames, in one call
 *     (vb_cells.h: vb_cells_run, vb_cells_run_frames; the result and its
 *     TSV and JSON writers: vb_measures.h);
 *   - verify: judging a vertex file or list exactly (vb_verify_file.h);
 *   - periodic boxes: the periodic diagram and its files (vb_periodic.h),
 *     a periodic vertex file judged (vb_periodic_verify.h), every frame of a
 *     trajectory in its own box (vb_periodic_frames.h);
 *   - channels over frames and the discrete Voronoi engines (vbc_frame.h,
 *     vbj_jfa.h through it), their options declared once and the run over
 *     frames (vbc_run.h, vbc_channels_config.h), on the device layer of
 *     vb_default_devices;
 *   - a `vorball jfa` run whole: seeds from their source, the timed
 *     variants checked against the exact diagram, the figures and the
 *     picture (vbj_runs.h). */
#ifndef VORBALL_H
#define VORBALL_H

#include "vb.h"
#include "vb_cells.h"
#include "vb_complete.h"
#include "vb_default.h"
#include "vb_diag.h"
#include "vb_frames.h"
#include "vb_periodic_frames.h"
#include "vb_periodic_verify.h"
#include "vb_select.h"
#include "vb_verify_file.h"
#include "vb_vertex_io.h"
#include "vb_vertex_page.h"
#include "vbc_frame.h"
#include "vbc_run.h"
#include "vbj_runs.h"

#endif
