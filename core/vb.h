/* vorball public API: context, status codes, diagnostics, statistics.
 *
 * Every public call takes the context first, returns an int status (VB_OK or a
 * VB_E* code) and writes results through OUT parameters. On failure the context
 * keeps a message (vb_errmsg) and, for input errors, the file:line it refers to.
 * Library code never exits, aborts or asserts on user input: only cli/ stops. */
#ifndef VB_H
#define VB_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Primary status codes (categories). The low byte is the category; extended
 * codes carry a detail in the upper bits, as SQLite's extended result codes do:
 * VB_CATEGORY(code) recovers the category. */
enum vb_status {
    VB_OK = 0,
    VB_EINPUT = 1,      /* user input is malformed or outside what we accept */
    VB_EDEGENERATE = 2, /* input is legal but geometry is degenerate for the operation */
    VB_EPREC = 3,       /* a precision limit was reached (exact fallback impossible) */
    VB_ENOMEM = 4,      /* allocation failed */
    VB_EDEVICE = 5,     /* OpenCL device or runtime failure */
    VB_EINTERNAL = 6,   /* a bug: an invariant of vorball did not hold */
    VB_EMISUSE = 7,     /* API or CLI misuse (bad argument, bad option) */
    VB_EIO = 8,         /* file cannot be opened, read or written */
    VB_EMISMATCH = 9    /* a check ran and found a difference (verify, crosscheck) */
};

/* Extended input codes: VB_EINPUT | (detail << 8). Each has its own stable
 * diagnostic number (E1xx) and its own CLI exit code (see cli/cli_common.h). */
enum vb_input_error {
    VB_EINPUT_MALFORMED  = VB_EINPUT | (1 << 8), /* E101 line cannot be parsed */
    VB_EINPUT_NONFINITE  = VB_EINPUT | (2 << 8), /* E102 NaN or Inf */
    VB_EINPUT_RADIUS     = VB_EINPUT | (3 << 8), /* E103 radius <= 0 */
    VB_EINPUT_DUPLICATE  = VB_EINPUT | (4 << 8), /* E104 two spheres identical */
    VB_EINPUT_EMPTY      = VB_EINPUT | (5 << 8), /* E105 no spheres at all */
    VB_EINPUT_TOOFEW     = VB_EINPUT | (6 << 8), /* E106 fewer than 4 spheres */
    VB_EINPUT_MAGNITUDE  = VB_EINPUT | (7 << 8), /* E107 absurd magnitude or precision */
    VB_EINPUT_ELEMENT    = VB_EINPUT | (8 << 8), /* E108 unknown element (strict mode) */
    VB_EINPUT_FORMAT     = VB_EINPUT | (9 << 8), /* E109 format not recognised / wrong --format */
    VB_EINPUT_TOOLARGE   = VB_EINPUT | (10 << 8),/* E110 file or sphere count over limit */
    VB_EINPUT_MODEL      = VB_EINPUT | (11 << 8),/* E111 requested model/frame absent */
    VB_EINPUT_INFERRED   = VB_EINPUT | (12 << 8),/* E112 element not written (strict mode) */
    VB_EINPUT_COMPRESSED = VB_EINPUT | (13 << 8),/* E113 damaged gzip/bzip2 data */
    VB_EINPUT_NOSPHERES  = VB_EINPUT | (14 << 8),/* E114 trajectory/topology alone: no spheres */
    VB_EINPUT_TRAJECTORY = VB_EINPUT | (15 << 8),/* E115 damaged binary trajectory */
    VB_EINPUT_TOPOLOGY   = VB_EINPUT | (16 << 8),/* E116 trajectory and topology disagree */
    VB_EINPUT_ASSEMBLY   = VB_EINPUT | (17 << 8),/* E117 assembly absent or malformed */
    VB_EINPUT_SELECT     = VB_EINPUT | (18 << 8),/* E118 --select: bad expression or no atom */
    VB_EINPUT_BOX        = VB_EINPUT | (20 << 8),/* E120 periodic box absent, malformed or flat */
    VB_EINPUT_FRAMES_MEMORY = VB_EINPUT | (27 << 8),/* E127 frames in flight over their memory budget */
    /* E130-E139: limits of an operation on an input it could otherwise read. */
    VB_EINPUT_REFERENCE_SIZE = VB_EINPUT | (30 << 8), /* E130 too many spheres for `reference` */
    VB_EINPUT_SCALE      = VB_EINPUT | (31 << 8),/* E131 radii too small for the sampler's doubles */
    VB_EINPUT_TOL        = VB_EINPUT | (32 << 8),/* E132 --tol finer than the sampler's doubles */
    VB_EINPUT_PAGE_SIZE  = VB_EINPUT | (33 << 8),/* E133 too many spheres for a vertices page */
    VB_EINPUT_BOX_SMALL  = VB_EINPUT | (35 << 8) /* E135 periodic box too small for its atoms */
};

/* Extended codes of resource limits (E140-E149): category | (detail << 8),
 * numbered 100 + detail as the input codes are. */
enum vb_limit_error {
    VB_ENOMEM_ESTIMATE = VB_ENOMEM | (40 << 8), /* E140 the estimated need exceeds the room */
    VB_ENOMEM_DEVICE = VB_ENOMEM | (42 << 8)    /* E142 the device budget cannot hold the input */
};

#define VB_CATEGORY(code) ((code) & 0xff)
#define VB_DETAIL(code) ((code) >> 8)

/* Returns a static English name for a status code, extended or primary. */
const char *vb_errstr(int code);

/* One diagnostic as it leaves the library: what a log callback receives
 * (SQLite's SQLITE_CONFIG_LOG), so that a host prints, raises, warns or
 * forwards it without parsing text back. */
typedef struct vb_diag_record {
    char kind;                /* 'W' a warning, 'I' an informational line, 'E' an error */
    int number;               /* the catalogue number (vb_diag.h); 0 for 'I' */
    const char *file;         /* the file (or source) it names, or NULL */
    long line;                /* its line, 0 for none */
    const char *message;      /* the text: no prefix, no location, no newline */
} vb_diag_record;

/* A log callback: called once per warning or info line that the verbosity
 * lets through, on the thread that emitted it (several threads of one run
 * may call it at once, worker threads included (vb_open_worker): a
 * callback that collects must lock). The record
 * and its strings are valid during the call only. */
typedef void (*vb_log_fn)(void *arg, const vb_diag_record *rec);

/* Writes the record to f as the library's text does without a log
 * callback: "vorball: W<n>: file:line: message\n" (file and line when
 * given; "vorball: message\n" for an 'I' line), so that a callback that
 * only needs to act before the text (the CLI erases its progress line)
 * prints the same bytes. */
void vb_diag_record_write(FILE *f, const vb_diag_record *rec);

/* Configuration handed to vb_open. Zero-initialise, then set what you need. */
typedef struct vb_config {
    int verbosity;            /* 0 quiet, 1 warnings (default when 0-init: warnings on), 2 info */
    FILE *diag;               /* where warnings go; NULL means stderr */
} vb_config;

/* Counters of the filtered predicates and the pipeline (--stats). */
typedef struct vb_stats {
    uint64_t filter_calls;     /* sign evaluations attempted in double */
    uint64_t filter_failures;  /* of those, undecided by the error bound */
    uint64_t exact_evals;      /* evaluations done with GMP */
    uint64_t candidates;       /* candidate vertices handed to the certifier */
    uint64_t certified;        /* canonical vertices certified */
    uint64_t rejected;         /* candidates the certifier refused */
    uint64_t warnings;         /* warnings emitted */
    /* Roots of proposed quadruples by the certification filter's verdict
     * (core/cells/vbd_cert_shared.h, on the device or its host twin):
     * proven vertices, proven not vertices, and left open (sent to the
     * host's filter and exact stage). */
    uint64_t judged_vertex, judged_not, judged_open;
} vb_stats;

typedef struct vb_ctx vb_ctx;

/* Creates a context. cfg may be NULL (defaults). On VB_ENOMEM *out is NULL.
 * Free with vb_close. */
int vb_open(vb_ctx **out, const vb_config *cfg);

/* Frees the context; NULL (and a closed context) is allowed. */
void vb_close(vb_ctx *ctx);

/* The misuse guard: VB_OK for an open context, VB_EMISUSE for NULL or one
 * already closed (detected while its memory is not reused). Every call of
 * this header checks it first: vb_warn, vb_info and vb_clear_error then do
 * nothing, vb_error returns its code, vb_errcode VB_EMISUSE, vb_errmsg a
 * static text and vb_ctx_stats NULL. */
int vb_ctx_check(const vb_ctx *ctx);

/* Last error message (never NULL; "" when none). Valid until the next call
 * that sets an error. */
const char *vb_errmsg(const vb_ctx *ctx);

/* Last error code recorded by vb_error (VB_OK when none). */
int vb_errcode(const vb_ctx *ctx);

/* Records an error: code, optional file and line (line 0 = none) and a
 * printf-style message. Returns code, so callers can `return vb_error(...)`. */
int vb_error(vb_ctx *ctx, int code, const char *file, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* Emits warning number `num` (a VB_W_* name of vb_diag.h) to the diagnostic
 * stream when verbosity allows, and counts it. file may be NULL, line 0 for
 * none. Returns VB_OK, or VB_EMISUSE (nothing done) for a NULL or closed
 * context. */
int vb_warn(vb_ctx *ctx, int num, const char *file, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* Emits an informational line (verbosity >= 2). */
void vb_info(vb_ctx *ctx, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Sets the context's verbosity (as vb_config's) and returns the previous
 * one; -1 (nothing done) for a NULL or closed context. Lets a caller
 * silence warnings that another process prints already (MPI ranks that
 * all read the same input). */
int vb_set_verbosity(vb_ctx *ctx, int verbosity);

/* Installs the context's log callback: from now on every warning and info
 * line the verbosity lets through goes to fn(arg, record) instead of the
 * text "vorball: W<n>: file:line: message" on the diagnostic stream; NULL
 * restores the text. VB_OK, or VB_EMISUSE (nothing done) for a NULL or
 * closed context. */
int vb_set_log(vb_ctx *ctx, vb_log_fn fn, void *arg);

/* A progress callback: `stage` names the loop ("cover", "certify",
 * "arcs", "reference", "frames", "cells", "sampling"; a static string),
 * `done` of `total` units are finished (total 0: not known). Called at a
 * bounded rate (when done crosses a new 1/1000 of total, and once with
 * done == total), serialised (never two calls at once, though possibly
 * from a worker thread), with done increasing within one run of a stage.
 * It only observes: results are the same with or without it. */
typedef void (*vb_progress_fn)(void *user, const char *stage, uint64_t done, uint64_t total);

/* Installs the context's progress callback (NULL removes it). VB_OK, or
 * VB_EMISUSE (nothing done) for a NULL or closed context. */
int vb_set_progress(vb_ctx *ctx, vb_progress_fn fn, void *user);

/* Makes `worker` (a context a library loop opened for a thread) report
 * through `owner`: its progress through owner's callback and rate limit,
 * its warnings and info lines through owner's log callback (or owner's
 * diagnostic stream) at owner's verbosity, so that nothing a thread says
 * is lost on a worker context. Its errors and counters stay its own (the
 * loop hands them on when it joins the thread). owner must outlive
 * worker's use; NULL for either, or worker == owner, does nothing. */
void vb_progress_forward(vb_ctx *worker, vb_ctx *owner);

/* Opens a worker context for a library loop's thread: a fresh context
 * (own error state and counters) that reports through owner as
 * vb_progress_forward says. owner must outlive it. Returns VB_OK, or
 * VB_ENOMEM with *out NULL, or VB_EMISUSE with *out NULL when owner is
 * NULL or closed. Free with vb_close. */
int vb_open_worker(vb_ctx **out, vb_ctx *owner);

/* Library loops report here: `done` of `total` units of `stage` finished.
 * Cheap when no callback is installed or no new 1/1000 is crossed (one
 * atomic load); thread-safe. Reports that go backwards within a stage
 * are dropped, except done == 0 which starts a new run of it. */
void vb_progress(vb_ctx *ctx, const char *stage, uint64_t done, uint64_t total);

/* Mutable access to the context's counters; never NULL for an open ctx. */
vb_stats *vb_ctx_stats(vb_ctx *ctx);

/* Adds every counter of `from` to `to` (a worker's context into the
 * caller's); NULL for either does nothing. */
void vb_stats_add(vb_stats *to, const vb_stats *from);

/* The last error as a record (kind 'E', its E-number, the file and line
 * vb_error was given, the message without them); VB_OK, or VB_EMISUSE for
 * a NULL or closed context. Valid until the next call that sets an error. */
int vb_error_record(const vb_ctx *ctx, vb_diag_record *out);

/* Resets the error state to VB_OK. */
void vb_clear_error(vb_ctx *ctx);

/* The diagnostic number belonging to an error code (e.g. 101 for
 * VB_EINPUT_MALFORMED, 1 for a plain VB_EINPUT) used in "E101" prefixes. */
int vb_diag_number(int code);

#ifdef __cplusplus
}
#endif
#endif
