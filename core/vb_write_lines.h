/* Writing many text lines fast and in order: blocks of lines formatted on
 * the host threads into memory, a round of blocks at a time, then written
 * in order, so the bytes are those one thread writes. */
#ifndef VB_WRITE_LINES_H
#define VB_WRITE_LINES_H

#include <stddef.h>
#include <stdio.h>

/* Writes the text of item k (any number of lines) to f. */
typedef void (*vb_line_fn)(FILE *f, const void *arg, size_t k);

/* Writes fn(f, arg, k) for k = 0 .. n-1 to f, in that order; blocks of
 * items are formatted on vb_threads(0) threads into memory streams (fn is
 * called from several threads at once: it may only read arg). With one
 * thread or few items, fn writes to f directly. Returns VB_OK, or
 * VB_ENOMEM (a block's memory stream failed; what came before it is
 * written). */
int vb_write_lines(FILE *f, size_t n, vb_line_fn fn, const void *arg);

#endif
