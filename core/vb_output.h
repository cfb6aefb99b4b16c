/* Output files that appear whole or not at all: each is written under a
 * temporary name in its own folder and renamed over its path when it is
 * complete, so a command that fails (or is interrupted) leaves neither a
 * partial file nor a damaged previous one. */
#ifndef VB_OUTPUT_H
#define VB_OUTPUT_H

#include <stdio.h>

#include "vb.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Opens `path` for writing (binary and text alike) as a temporary file
 * ".NAME.vorball-XXXXXX" beside it; a symbolic link is followed, so the
 * rename replaces its target and the link stays. A path that exists and is
 * not a regular file (/dev/null, a FIFO, a terminal) is written directly.
 * Returns the stream, or NULL with VB_EIO (or VB_ENOMEM) in the context.
 * Finish with vb_output_commit or vb_output_discard. On SIGINT, SIGTERM and
 * SIGHUP the temporary files still open are removed. */
FILE *vb_output_open(vb_ctx *ctx, const char *path);

/* Closes f and renames it over its path. Returns VB_OK, or VB_EIO (message
 * naming the path) when a write, the close or the rename failed: then the
 * temporary file is removed and the path left as it was. f must come from
 * vb_output_open. */
int vb_output_commit(vb_ctx *ctx, FILE *f);

/* Closes f and removes its temporary file (the path is left as it was).
 * NULL is allowed. */
void vb_output_discard(FILE *f);

/* Discards every output still open or waiting for a deferred commit (the
 * safety net of a program that is about to exit after a failure). */
void vb_output_discard_all(void);

/* With deferral on, vb_output_commit checks and closes a file but leaves it
 * under its temporary name; vb_output_commit_deferred then renames them all
 * (after the first rename that fails, it removes the rest and returns
 * VB_EIO). The CLI defers, so that a command's outputs appear together when
 * it succeeds and none does when it fails. Off by default. */
void vb_output_defer(int on);
int vb_output_commit_deferred(vb_ctx *ctx);

/* The path f writes (through a link: its target), when f came from
 * vb_output_open and is still open; NULL otherwise. Owned by the output
 * table: valid until f is committed or discarded. */
const char *vb_output_name(FILE *f);

/* Nonzero when f came from vb_output_open and is still open. */
int vb_output_is_open(FILE *f);

#ifdef __cplusplus
}
#endif
#endif
