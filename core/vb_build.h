/* What this build of vorball is: version, source commit, build type,
 * compiler, options, and the numeric libraries it links (provenance for
 * `vorball --version`, output headers and bug reports). */
#ifndef VB_BUILD_H
#define VB_BUILD_H

#include <stddef.h>
#include <stdio.h>

#include "vb.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the library, e.g. "0.1.0" (CMake's project version). */
const char *vb_build_version(void);

/* The source commit the library was built from: `git describe --always
 * --dirty` taken at build time ("unknown" outside a git checkout). */
const char *vb_build_commit(void);

/* One line: build type, compiler and the options that change what the
 * library does or checks, e.g. "Release, GNU 12.2.0, -ffp-contract=off,
 * sanitizers off, CGAL cross-check on, MPI off, results-page viewer
 * embedded". */
const char *vb_build_options(void);

/* The GMP version the library runs with (gmp_version). */
const char *vb_build_gmp_version(void);

/* Where an output file came from (issue 35), for the header of the files
 * that have one: the tool, the input and the options that shaped it. */
typedef struct vb_provenance {
    const char *input;   /* the input as named ("-": stdin) */
    size_t spheres;      /* spheres read from it */
    const char *options; /* the command line that shapes the output, e.g.
                          * "vertices --arcs in.xyzr" (may be NULL or "") */
} vb_provenance;

/* The three header lines, without '#', each ended by '\n':
 *   tool: vorball 0.1.0 (commit 1a2b3c4)
 *   input: FILE, N spheres
 *   options: ...
 * into buf (truncated to size - 1 and NUL-terminated). Returns the length
 * the full text needs, as snprintf does. */
size_t vb_provenance_text(const vb_provenance *p, char *buf, size_t size);

/* The same as JSON members, each followed by ',':
 *   "tool":"vorball 0.1.0 (commit ..)","input":"FILE","spheres":N,"options":"..",
 * for a writer to put before its own keys. */
void vb_provenance_write_json(FILE *f, const vb_provenance *p);

/* The head of a JSON output object: "{", the members of
 * vb_provenance_write_json (NULL p: none), then "comment":"..." and ','
 * (NULL comment: none), for a writer to put its own keys after. */
void vb_provenance_write_json_head(FILE *f, const vb_provenance *p, const char *comment);

/* Writes text as comment lines: each of its lines after prefix, ended by
 * '\n' (NULL or "" text: nothing). */
void vb_comment_lines(FILE *f, const char *prefix, const char *text);

/* The header comments of a text output: the provenance lines of p
 * (vb_provenance_text; NULL p: none), then the comment's lines (NULL:
 * none), each after prefix ("# " for TSV and CSV headers). Returns VB_OK,
 * or VB_ENOMEM with nothing written. */
int vb_provenance_write_comments(FILE *f, const char *prefix, const vb_provenance *p,
                                 const char *comment);

#ifdef __cplusplus
}
#endif
#endif
