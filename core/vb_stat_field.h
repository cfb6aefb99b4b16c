/* The --stats counters as one table: each counter is declared once, with
 * its printed name, into a vb_stat_fields (the library's stats of a run),
 * printed by one loop (vb_stat_fields_write) and read by the bindings as
 * typed values (python/src/vertices.c), never re-parsed from text. */
#ifndef VB_STAT_FIELD_H
#define VB_STAT_FIELD_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { VB_STAT_UINT = 0, VB_STAT_REAL = 1, VB_STAT_TEXT = 2 } vb_stat_kind;

typedef struct vb_stat_field {
    const char *name;  /* the printed name (static storage) */
    vb_stat_kind kind;
    const char *fmt;   /* VB_STAT_REAL: the printf conversion of its line ("%.3f") */
    uint64_t u;        /* VB_STAT_UINT */
    double x;          /* VB_STAT_REAL */
    const char *s;     /* VB_STAT_TEXT (owned by the result the table describes) */
} vb_stat_field;

/* Room for every counter of a vertex run and its arc closure: 127 at stop
 * 53 (the early tracing's included), so 192 leaves room to grow (a full
 * table would drop its last counters; test_stat_field checks the room). */
enum { VB_STAT_FIELDS_MAX = 192 };

typedef struct vb_stat_fields {
    vb_stat_field f[VB_STAT_FIELDS_MAX];
    size_t n;
} vb_stat_fields;

/* Appends one counter (name and fmt static strings; s lives as long as the
 * table is read). A full table keeps its first VB_STAT_FIELDS_MAX entries
 * (the library's tables are below it: tests/verify/test_stat_field.c checks). */
void vb_stat_uint(vb_stat_fields *fs, const char *name, uint64_t v);
void vb_stat_real(vb_stat_fields *fs, const char *name, const char *fmt, double v);
void vb_stat_text(vb_stat_fields *fs, const char *name, const char *s);

/* Writes fields [from, fs->n) to f, one "name<TAB>value" line each: an
 * integer in decimal, a real with its fmt, a text as it is. */
void vb_stat_fields_write(FILE *f, const vb_stat_fields *fs, size_t from);

/* Writes fields [from, fs->n) whose name begins with prefix (NULL or "":
 * all) to f as the members of a JSON object, {"name": value, ...}: an
 * integer in decimal, a real with its fmt (a value that is not finite as
 * null), a text as a JSON string. */
void vb_stat_fields_write_json(FILE *f, const vb_stat_fields *fs, size_t from,
                               const char *prefix);

#ifdef __cplusplus
}
#endif
#endif
