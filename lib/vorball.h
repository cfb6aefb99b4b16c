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
 *   - channels and cavities, one frame or every frame of a source, behind
 *     one handle (vb_channels.h): the options declared once (the table the
 *     command parses and Python reads), the engine on the device layer of
 *     vb_default_devices, results through accessors, the command's
 *     writers;
 *   - a `vorball jfa` run whole behind one handle (vb_jfa.h): the options
 *     declared once (the table the command parses and Python reads), seeds
 *     from their source, the timed variants checked against the exact
 *     diagram, the figures through accessors and writers, the picture; the
 *     discrete Voronoi engine (core/discrete's vbj_*) is not installed. */
#ifndef VORBALL_H
#define VORBALL_H

#include "vb.h"
#include "vb_cells.h"
#include "vb_channels.h"
#include "vb_complete.h"
#include "vb_default.h"
#include "vb_diag.h"
#include "vb_frames.h"
#include "vb_periodic_frames.h"
#include "vb_periodic_verify.h"
#include "vb_select.h"
#include "vb_verify_file.h"
#include "vb_vertex_io.h"
#include "vb_jfa.h"
#include "vb_vertex_page.h"

#endif
