/* Diagnostics held for later (frames in flight, issue 33): the warnings,
 * info lines and the error a frame's work said on a thread, kept with the
 * frame and said on the caller's context when the caller takes the frame,
 * so that they come in frame order whatever ran at once. */
#ifndef VBC_HELD_H
#define VBC_HELD_H

#include "vb.h"

typedef struct vbc_held vbc_held;

/* An empty list; NULL when out of memory. */
vbc_held *vbc_held_new(void);

/* A vb_log_fn adding the record to the list `held` (a vbc_held *); it
 * locks, so the worker threads of one stage may call it at once. */
void vbc_held_log(void *held, const vb_diag_record *rec);

/* Adds ctx's last error record (an 'E' line) to h. */
void vbc_held_error(vbc_held *h, vb_ctx *ctx);

/* Moves every record of `from` to the end of h (from is left empty). */
void vbc_held_move(vbc_held *h, vbc_held *from);

/* A context whose lines h holds: every line kept (verbosity 2: the caller's
 * verbosity decides when they are said). VB_OK or VB_ENOMEM. */
int vbc_held_open(vb_ctx **out, vbc_held *h);

/* Says h's warnings and info lines on ctx in order, and with rc not VB_OK
 * its error (the status returned); a record lost for memory makes VB_ENOMEM.
 * Empties h. NULL h returns rc. */
int vbc_held_replay(vb_ctx *ctx, vbc_held *h, int rc);

/* Frees h (NULL allowed). */
void vbc_held_free(vbc_held *h);

#endif
