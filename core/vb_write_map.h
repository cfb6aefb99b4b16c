/* The end of a regular output file written through a shared mapping, one
 * round of known length at a time, so that several threads copy their
 * blocks of text into it at once (vb_write_lines). The bytes are those
 * fwrite would have appended. */
#ifndef VB_WRITE_MAP_H
#define VB_WRITE_MAP_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

typedef struct vb_map_out {
    int fd;        /* -1: not mapped (stdio writes) */
    off_t off;     /* where the next round starts: the text's end */
    size_t page;
    void *base;    /* the round's mapping, from off's page */
    size_t maplen; /* its length */
    size_t len;    /* the round's bytes */
    int failed;    /* a failed round could not be cut back */
} vb_map_out;

/* Flushes f and sets *m up to write at f's end through mappings: 0, or -1
 * (nothing mapped; f writes on through stdio) when f is not a regular file
 * opened for reading and writing at its end without O_APPEND (vorball's
 * outputs under a temporary name are), or VORBALL_WRITE_MAP is not 1. */
int vb_map_begin(FILE *f, vb_map_out *m);

/* Reserves (fallocate) and maps the next len bytes at m->off; returns where
 * they go, or NULL when the file system cannot (full, no fallocate, no
 * mmap): then the file is as before the call, and the caller ends the
 * mapping with vb_map_end and writes the round through stdio. */
char *vb_map_round(vb_map_out *m, size_t len);

/* Unmaps the round the caller has filled; the next one starts after it. */
void vb_map_round_end(vb_map_out *m);

/* Ends writing through mappings: unmaps a round still mapped and moves f's
 * position to the text's end, for stdio to go on. 0, or -1 when the file
 * could not be put back, now or after an earlier failed round (the caller
 * reports an I/O error). */
int vb_map_end(FILE *f, vb_map_out *m);

#endif
