/* The cell measures on the results page (core/page/vb_page.h): `cells
 * --html` and vorball's library callers add each frame's measures to a
 * page, which colours the atoms by a measure the reader picks (volume, SAS
 * area, and the sum of each atom's contact areas when contacts were
 * computed) and tables the frame's counts. */
#ifndef VB_MEASURES_PAGE_H
#define VB_MEASURES_PAGE_H

#include "vb_measures.h"
#include "vb_page.h"

/* The names of the page's measures, as the selector shows them. */
#define VB_MEASURES_PAGE_VOLUME "volume (Å³)"
#define VB_MEASURES_PAGE_SAS "SAS area (Å²)"
#define VB_MEASURES_PAGE_CONTACT "contact area (Å²)"

/* Adds a frame labelled `label` to page p with the coordinates of `set`
 * (vb_page_frame_set) and the measures m of that set: per atom the volume
 * and SAS area (the printed midpoints) and, with `contacts` (the run
 * computed them), the sum of the atom's contact areas; and the figures
 * atoms, empty cells, loose values, contacts (with `contacts`), the volume
 * and SAS sums. A frame the page has no room for is left out (W829, as
 * vb_page_frame). VB_OK, VB_EMISUSE (m not of set's count) or VB_ENOMEM, with the message
 * in ctx (the page's context). */
int vb_cell_measures_page_add(vb_ctx *ctx, vb_page *p, const char *label,
                              const vb_sphere_set *set, const vb_cell_measures *m, int contacts);

#endif
