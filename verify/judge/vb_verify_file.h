/* Judging a vertex file (ours or Voronota's) exactly against the spheres,
 * as `vorball verify` reports it. The certifier decides every line; this
 * module groups its verdicts into the report classes:
 *   certified          the line's ids are tangent to one empty sphere at its point
 *   not a vertex       a sphere cuts the tangent sphere, no tangent sphere exists,
 *                      or the ids do not determine a point
 *   wrong coordinates  the exact vertex is farther than tol from the line's
 *                      x y z (or its t differs by more than tol)
 *   missing members    the line's ids are a strict subset of the vertex's spheres
 *   duplicate          an earlier line names the same exact vertex
 * Voronota lists a vertex of degree > 4 as several quadruple lines: its lines
 * are grouped by exact vertex and membership is judged on the group's union.
 * With `complete`, the exact reference lists the vertices no line names. */
#ifndef VB_VERIFY_FILE_H
#define VB_VERIFY_FILE_H

#include <stdio.h>

#include "vb_arc.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"

#ifdef __cplusplus
extern "C" {
#endif

enum vb_verify_problem {
    VB_VERIFY_NOT_VERTEX = 1 << 0,
    VB_VERIFY_WRONG_COORDS = 1 << 1,
    VB_VERIFY_MISSING = 1 << 2,
    VB_VERIFY_DUPLICATE = 1 << 3
};

/* The judgement of one line of the vertex file. */
typedef struct vb_verify_line {
    int problems;       /* enum vb_verify_problem bits; 0 = certified */
    int verdict;        /* certifier verdict behind VB_VERIFY_NOT_VERTEX */
    uint32_t intruder;
    double dist, dt;    /* distance to the exact point, |t - exact t| */
    double ex[4];       /* exact vertex (x y z t) rounded, when known */
    int has_key;        /* the exact vertex is identified */
    size_t key;
    uint32_t *members;  /* all spheres of the exact vertex (owned) */
    size_t nmembers;
    long dup_of;        /* DUPLICATE: source line of the first line of the vertex */
    int group_missing;  /* Voronota: members was cut down to those no line of the group names */
} vb_verify_line;

typedef struct vb_verify_counts {
    size_t lines, certified, not_vertex, wrong, missing, duplicate, missed, groups;
} vb_verify_counts;

typedef struct vb_verify_report {
    vb_vertex_list vertices;  /* the file's vertex lines */
    long *lines;              /* their source lines */
    vb_vertex_format format;  /* as detected */
    vb_verify_line *judged;   /* one per vertex line */
    vb_vertex_list missed;    /* with complete: reference vertices no line names */
    vb_verify_counts counts;
    double tol;
    int complete;
    /* The certifier that judged the lines, of the set cert_set, kept open
     * so that vb_verify_arcs traces with it instead of building another
     * (closed by vb_verify_report_free), its keys forgotten
     * (vb_certifier_forget_keys). NULL when judging never opened one. */
    vb_certifier *cert;
    const vb_sphere_set *cert_set;
} vb_verify_report;

/* Reads the vertex file `path` ("-" = stdin) and judges every line against
 * the validated set with distance tolerance tol > 0; with complete, also
 * runs the exact reference (brute force: small inputs) for missed
 * vertices. Fills *out (free with vb_verify_report_free, also on error;
 * out->cert stays open until then).
 * Returns VB_OK when the judging ran (whatever it found: see
 * vb_verify_report_ok), VB_EINPUT_EMPTY for a file without vertex lines
 * (nothing to verify is not a success), the reader's errors (file:line),
 * VB_ENOMEM, VB_EPREC, VB_EINTERNAL. */
int vb_verify_file(vb_ctx *ctx, const vb_sphere_set *set, const char *path, double tol,
                   int complete, vb_verify_report *out);

/* As vb_verify_file for vertices in memory (a binding's arrays): the n
 * vertices of v are judged as the lines 1 .. n of a vertex file called
 * `name` in `format` (VB_VFMT_VORONOTA groups quadruple lines by exact
 * vertex, as for a file). v is copied; ids need not be sorted. Fills *out
 * (free with vb_verify_report_free, also on error). VB_EINPUT_EMPTY for
 * n = 0, VB_ENOMEM, VB_EPREC, VB_EINTERNAL. */
int vb_verify_list(vb_ctx *ctx, const vb_sphere_set *set, const char *name,
                   const vb_vertex_list *v, vb_vertex_format format, double tol, int complete,
                   vb_verify_report *out);

/* 1 when every line is certified and nothing was missed. */
int vb_verify_report_ok(const vb_verify_report *r);

void vb_verify_report_free(vb_verify_report *r);

/* The report as text: one line per problem ("FILE:LINE: class: ...") and a
 * summary line; `name` is the vertex file as the user named it. VB_OK or
 * VB_ENOMEM. */
int vb_verify_write_text(vb_ctx *ctx, FILE *f, const char *name, const vb_sphere_set *set,
                         const vb_verify_report *r);

/* The report as JSON, with the counts per class and one object per problem. */
int vb_verify_write_json(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                         const vb_sphere_set *set, const vb_verify_report *r);

/* The same with one more member, "key": the JSON value that more(f, arg)
 * writes, before "ok"; "ok" is also false when more_ok is 0 (more NULL:
 * vb_verify_write_json). VB_OK or VB_ENOMEM. */
int vb_verify_write_json_more(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                              const vb_sphere_set *set, const vb_verify_report *r,
                              const char *key, void (*more)(FILE *, const void *),
                              const void *arg, int more_ok);

/* Arc closure of a judged vertex file: the exact vertices of its certified
 * lines (one per exact vertex, so a Voronota group counts once) through
 * vb_arc_close, tracing with judged->cert when it is the certifier of this
 * very set (its exact input and spatial index depend on the set alone; the
 * judge's verdicts stay in the report), else with one of its own. Same
 * returns as vb_arc_close. */
int vb_verify_arcs(vb_ctx *ctx, const vb_sphere_set *set, const vb_verify_report *judged,
                   unsigned threads, vb_arc_report *out);

/* The verify report as JSON (vb_verify_write_json) with a member "arcs":
 * {"vertices", "half_arcs", "closed", "infinite", "loops", "undecided",
 * "added", "components", "complete", "missing": [{"ids", "x", "y", "z",
 * "t"}, ...]}; "ok" is false also when the closure is not complete.
 * VB_OK, VB_ENOMEM or VB_EIO. */
int vb_verify_write_json_arcs(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                              const vb_sphere_set *set, const vb_verify_report *judged,
                              const vb_arc_report *r);

#ifdef __cplusplus
}
#endif
#endif
