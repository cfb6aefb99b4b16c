/* Certified vertices on the results page (core/page/vb_page.h): `vertices
 * --html` shows the spheres and their certified Voronoi vertices in a
 * browser, for small inputs (a page draws every vertex as a marker). */
#ifndef VB_VERTEX_PAGE_H
#define VB_VERTEX_PAGE_H

#include "vb.h"
#include "vb_spheres.h"
#include "vb_vertex.h"

/* The most spheres a vertices page takes: about 7 vertices per sphere,
 * each a marker the browser draws. */
#define VB_VERTEX_PAGE_MAX_SPHERES 2000u

/* VB_OK when a vertices page of `set` can be made; VB_EINPUT_PAGE_SIZE
 * (E133, with the set's source and count in ctx's message) over
 * VB_VERTEX_PAGE_MAX_SPHERES spheres. Callers ask before the work. */
int vb_vertex_page_check(vb_ctx *ctx, const vb_sphere_set *set);

/* Writes the page `path` titled `title`: the spheres of `set` (radius as
 * read) and the vertices of v as markers (their tangent-sphere radius t in
 * the tooltip), with the figures spheres, vertices (v's count: the lines of
 * the vertex table) and, when given, the certificate line. Whole or not at
 * all (vb_page_write). VB_OK, VB_EINPUT_PAGE_SIZE (as the check),
 * VB_EMISUSE (built without the viewer), VB_EIO or VB_ENOMEM, with the
 * message in ctx. */
int vb_vertex_page_write(vb_ctx *ctx, const char *path, const char *title,
                         const vb_sphere_set *set, const vb_vertex_list *v,
                         const char *certificate);

#endif
