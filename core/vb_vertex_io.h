/* Reading and writing vertex files.
 *
 * tsv (default): '#' header lines, then one line per vertex:
 *   ids<TAB>x<TAB>y<TAB>z<TAB>t<TAB>status   (ids sorted, comma-separated, 0-based;
 *   numbers printed with %.17g so the doubles round-trip bit-exactly)
 * json: {"vertices":[{"ids":[...],"x":..,"y":..,"z":..,"t":..,"status":".."}, ...]}
 * voronota: "q1 q2 q3 q4 x y z r" per line (Voronota's vertices/tangent spheres;
 *   a vertex of degree > 4 appears as several quadruple lines). */
#ifndef VB_VERTEX_IO_H
#define VB_VERTEX_IO_H

#include <stdio.h>

#include "vb.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum vb_vertex_format {
    VB_VFMT_TSV = 0,
    VB_VFMT_JSON,
    VB_VFMT_VORONOTA
} vb_vertex_format;

/* Parses "tsv|json|voronota". VB_OK or VB_EMISUSE. */
int vb_vertex_format_parse(vb_ctx *ctx, const char *name, vb_vertex_format *out);

/* Writes the list. `comment` (may be NULL) goes into the header of formats
 * that have one. Returns VB_OK or VB_EIO. */
int vb_vertex_write(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                    const char *comment);

/* Reads a vertex file (path or "-"), detecting tsv / json / voronota by
 * content. Appends to *out (status CANDIDATE unless the file says otherwise);
 * *lines (may be NULL) gets a malloc'd array of the source line of each vertex.
 * Errors: VB_EINPUT_MALFORMED with file:line, VB_EIO. */
int vb_vertex_read_file(vb_ctx *ctx, const char *path, vb_vertex_list *out,
                        vb_vertex_format *detected, long **lines);

#ifdef __cplusplus
}
#endif
#endif
