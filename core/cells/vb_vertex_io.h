/* Reading and writing vertex files.
 *
 * tsv (default): '#' header lines ("# vorball vertices", the provenance when
 *   given: "# tool: vorball V (commit C)", "# input: FILE, N spheres",
 *   "# options: ..." (vb_build.h), the caller's comment one '#' line per line
 *   of it, "# ids x y z t status"), then one line per vertex:
 *   ids<TAB>x<TAB>y<TAB>z<TAB>t<TAB>status   (ids sorted, comma-separated, 0-based;
 *   numbers printed with %.17g so the doubles round-trip bit-exactly; status
 *   candidate|certified|rejected, optional on reading)
 * json: {"tool":"..","input":"..","spheres":N,"options":"..", (the provenance,
 *   when given) "comment":"..","vertices":[{"ids":[...],"x":..,"y":..,"z":..,"t":..,
 *   "status":".."}, ...]}, one vertex per line; the reader skips unknown keys.
 * voronota: "q1 q2 q3 q4 x y z r" per line (Voronota's vertices/tangent spheres;
 *   a vertex of degree > 4 appears as several quadruple lines). Our writer
 *   gives a vertex with sorted members m0 < m1 < ... < m(k-1) the k - 3 lines
 *   {m0 m1 m2 mj}, j = 3..k-1: every member is named, and at least one line
 *   determines the point by itself (at a vertex the members' linear system has
 *   rank 3, and m0, m1, m2 are independent because three spheres tangent to
 *   one sphere cannot be in a pencil unless nested at one point), though other
 *   lines may not (e.g. four coplanar corners of a cube). The reader keeps one
 *   entry per line; grouping lines into vertices needs exact arithmetic and is
 *   done by `vorball verify`.
 * npz: a NumPy archive of arrays ids, start, xyz, t, status and comment
 *   (vertex_npz.c says what each holds; the comment holds the provenance
 *   lines, then the caller's comment), the same doubles bit for bit; for
 *   NumPy and other tools, not read back by vorball.
 * Non-finite numbers are refused by the reader (VB_EINPUT_NONFINITE). */
#ifndef VB_VERTEX_IO_H
#define VB_VERTEX_IO_H

#include <stdio.h>

#include "vb.h"
#include "vb_build.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum vb_vertex_format {
    VB_VFMT_TSV = 0,
    VB_VFMT_JSON,
    VB_VFMT_VORONOTA,
    VB_VFMT_NPZ
} vb_vertex_format;

/* Parses "tsv|json|voronota|npz". VB_OK or VB_EMISUSE. */
int vb_vertex_format_parse(vb_ctx *ctx, const char *name, vb_vertex_format *out);

/* Static name of a vertex status: "candidate", "certified", "rejected". */
const char *vb_vertex_status_name(int status);

/* Writes the list. `comment` (may be NULL) goes into the header of formats
 * that have one. Returns VB_OK or VB_EIO. */
int vb_vertex_write(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                    const char *comment);

/* As vb_vertex_write with the provenance (may be NULL) in the header:
 * tsv's '#' lines, json's keys, npz's comment; voronota has no header.
 * VB_OK, VB_EIO or VB_ENOMEM. */
int vb_vertex_write_prov(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                         const vb_provenance *prov, const char *comment);

/* Writes the list as a NumPy .npz archive (vertex_npz.c) with `comment`
 * (may be NULL) as its comment array. VB_OK, VB_EIO, VB_ENOMEM, or
 * VB_EMISUSE for an array over 4 GiB (ZIP64 is not written). */
int vb_vertex_write_npz(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, const char *comment);

/* Largest vertex file read: the input layer's limit for sphere files. */
#define VB_VERTEX_MAX_FILE_BYTES ((size_t)2 << 30)

/* Reads a vertex file (path or "-"), detecting tsv / json / voronota by
 * content. Appends to *out (status CANDIDATE unless the file says otherwise);
 * *lines (may be NULL) gets a malloc'd array (caller frees) of the 1-based
 * source line of each appended vertex, indexed from the first one appended.
 * An empty file, or one with only '#' lines, is a tsv file of no vertices.
 * Errors: VB_EINPUT_MALFORMED (also a line that names a sphere twice) /
 * VB_EINPUT_NONFINITE with file:line, VB_EINPUT_TOOLARGE (a file over
 * VB_VERTEX_MAX_FILE_BYTES), VB_EIO, VB_ENOMEM; on error *out keeps what it
 * had before the call. */
int vb_vertex_read_file(vb_ctx *ctx, const char *path, vb_vertex_list *out,
                        vb_vertex_format *detected, long **lines);

/* As vb_vertex_read_file from a memory buffer (need not be NUL-terminated);
 * `name` is used in messages. Entry point of tests and fuzzing. */
int vb_vertex_read_buffer(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                          vb_vertex_list *out, vb_vertex_format *detected, long **lines);

#ifdef __cplusplus
}
#endif
#endif
