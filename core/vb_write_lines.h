/* Writing many text lines fast and in order: blocks of lines formatted on
 * the host threads into plain memory (no stdio per number), a round of
 * blocks at a time, then written in order (into a mapped file by the
 * threads, else through stdio) while the next round is formatted, so the
 * bytes are those one thread writes. */
#ifndef VB_WRITE_LINES_H
#define VB_WRITE_LINES_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* A growable text in memory. Zero-initialise; free p. After a failed
 * growth nomem is set and further text is dropped. */
typedef struct vb_text {
    char *p;
    size_t n, cap;
    int nomem;
} vb_text;

/* Grows t so that `need` more bytes fit; returns 0, or -1 (t->nomem set). */
int vb_text_grow(vb_text *t, size_t need);

/* Where `need` more bytes go (t->p + t->n; the caller adds what it wrote
 * to t->n), or NULL when memory is short. */
static inline char *vb_text_room(vb_text *t, size_t need)
{
    if (t->cap - t->n < need && vb_text_grow(t, need) != 0)
        return NULL;
    return t->p + t->n;
}

/* Appends the n bytes of s. */
void vb_text_put(vb_text *t, const char *s, size_t n);

/* Appends sep (unless it is 0) and v as "%u". */
void vb_text_u32(vb_text *t, char sep, uint32_t v);

/* Appends sep (unless it is 0) and x as "%.17g" (vb_format_g17). */
void vb_text_g17(vb_text *t, char sep, double x);

/* Appends the text of item k (any number of lines) to t. */
typedef void (*vb_line_fn)(vb_text *t, const void *arg, size_t k);

/* Writes fn(t, arg, k) for k = 0 .. n-1 to f, in that order; blocks of
 * items are formatted on vb_threads(0) threads (fn is called from several
 * threads at once: it may only read arg), and each round of blocks is
 * written while the next one is formatted: by every thread into a mapping
 * where f is a regular file at its end (vb_write_map.h; f's position is
 * then moved past the text), else through stdio. Returns VB_OK, VB_ENOMEM
 * (a block's text could not grow; what came before it is written) or
 * VB_EIO (a mapped file that could not be put back after a failed round).
 * The caller checks ferror(f). */
int vb_write_lines(FILE *f, size_t n, vb_line_fn fn, const void *arg);

#endif
