/* The results page: one self-contained HTML file that opens offline in a
 * browser and shows what a command computed — the molecule (with the NGL
 * viewer embedded), channel centrelines coloured by radius, pore profiles,
 * atoms coloured by per-atom measures (a selector picks one), point sets
 * (Voronoi vertices), a frame slider for trajectories and a table of the
 * figures of each frame.
 *
 * The page is for looking: coordinates and values are written as rounded
 * decimals (3 decimals for coordinates, 6 significant digits for values);
 * the command's tables remain the record. A page is built in memory, then
 * written whole through vb_output_open (no partial file on failure).
 *
 * The viewer (NGL, MIT licence) is embedded when vorball was built with it
 * (VORBALL_NGL_JS, fetched by .ci/viewer); vb_page_viewer_available says so. */
#ifndef VB_PAGE_H
#define VB_PAGE_H

#include <stddef.h>

#include "vb.h"
#include "vb_spheres.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_page vb_page;

/* Nonzero when this build embeds the viewer; 0 when it was built without
 * (then vb_page_write fails with VB_EMISUSE and a message saying how to get
 * it). */
int vb_page_viewer_available(void);

/* VB_OK when a page can be written to `path` by this build; VB_EMISUSE
 * with vb_page_write's message (how to get the viewer) in ctx when it was
 * built without it. Commands ask before their work, not after it. */
int vb_page_check(vb_ctx *ctx, const char *path);

/* Starts a page titled `title` (e.g. "vorball channels 1grm.pdb") about the
 * sphere set s: its atoms (names, residues, chains and elements where the
 * input has them; spheres of XYZR input are shown as atoms named after
 * their 0-based id) are the molecule; s's coordinates are frame 0 until
 * vb_page_frame says otherwise. The page keeps a copy of what it needs, not
 * s. Returns NULL with VB_ENOMEM in ctx. */
vb_page *vb_page_new(vb_ctx *ctx, const char *title, const vb_sphere_set *s);

/* The number of atoms on the page (the count of the set it was made
 * from). */
size_t vb_page_atoms(const vb_page *p);

/* Frees the page; NULL is allowed. */
void vb_page_free(vb_page *p);

/* Adds a frame labelled `label` (e.g. "frame 3") whose atom coordinates are
 * xyz (3 doubles per atom, the set's count); xyz NULL means the set's own
 * coordinates. Frames appear in the order added; the slider shows them when
 * there are two or more. *index receives the frame's index, or -1 when the
 * page is full (VB_PAGE_MAX_NUMBERS coordinates in all: the frame is left
 * out, warned once as W829; the command's tables still hold it). Returns
 * VB_OK or VB_ENOMEM. */
#define VB_PAGE_MAX_NUMBERS 30000000u
int vb_page_frame(vb_page *p, const char *label, const double *xyz, int *index);

/* vb_page_frame with the coordinates of the sphere set s (a frame of the
 * page's trajectory); a set of another count (not one of the page's
 * frames) keeps the page's atoms where they are. Same returns. */
int vb_page_frame_set(vb_page *p, const char *label, const vb_sphere_set *s, int *index);

/* Adds a path to frame `frame` (an index from vb_page_frame): n points (3
 * doubles each, Å) with the free radius at each point; drawn as a tube of
 * spheres coloured from narrow (red) to wide (blue), named `name` in the
 * legend. VB_OK, VB_EMISUSE (frame out of range) or VB_ENOMEM. A frame index
 * of -1 (a full page) is allowed and does nothing, as in the calls below. */
int vb_page_path(vb_page *p, int frame, const char *name, size_t n, const double *xyz,
                 const double *radius);

/* Adds a profile plot to frame `frame`: n points (s[k], r[k]) (axial
 * coordinate and radius, Å), named `name`. VB_OK, VB_EMISUSE or VB_ENOMEM. */
int vb_page_profile(vb_page *p, int frame, const char *name, size_t n, const double *s,
                    const double *r);

/* Adds one row (key, value as text) to the figures table of frame `frame`.
 * VB_OK, VB_EMISUSE or VB_ENOMEM. */
int vb_page_fact(vb_page *p, int frame, const char *key, const char *value);

/* vb_page_fact with a count as its value, written as the tables write
 * counts (decimal digits). Same returns. */
int vb_page_fact_count(vb_page *p, int frame, const char *key, size_t count);

/* Adds a per-atom measure named `name` (e.g. "volume (Å³)") to frame
 * `frame`: v holds one value per atom; atoms without a value (NaN) are
 * grey. A frame may carry several measures: the page colours the atoms by
 * the one its selector names (the first added, at first). VB_OK,
 * VB_EMISUSE or VB_ENOMEM. */
int vb_page_atom_values(vb_page *p, int frame, const char *name, const double *v);

/* Adds a set of n points (3 doubles each, Å) named `name` to frame `frame`,
 * each with a radius (e.g. the radius of the sphere a Voronoi vertex is the
 * centre of; NaN: none), drawn as small markers with the radius in their
 * tooltip. VB_OK, VB_EMISUSE or VB_ENOMEM. */
int vb_page_points(vb_page *p, int frame, const char *name, size_t n, const double *xyz,
                   const double *radius);

/* Writes the page to `path` (whole or not at all). VB_OK, VB_EMISUSE
 * (built without the viewer, or a page with no frame and no atoms), VB_EIO
 * or VB_ENOMEM, with the message in ctx. */
int vb_page_write(vb_page *p, const char *path);

#ifdef __cplusplus
}
#endif
#endif
