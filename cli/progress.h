/* Progress on stderr, one line that updates in place: the library's
 * progress callback (vb_set_progress) drawn as "stage: done/total (pct%),
 * rate/s, ~Ns left" at most 4 times a second (rate and time left from a
 * smoothed rate), erased when the stage ends; and, between stages, a
 * status line for long commands: what is running and for how long, on
 * stderr, only when stderr is a terminal and only once the work has taken
 * a second (logs and pipes stay clean). A ticker thread redraws it twice a
 * second, so one long library call (the exact diagram of `jfa --check`, the
 * brute force of `reference`) shows that it is alive; commands with known
 * steps say "frame 3 of 51" through vb_cli_status_set. The vertex
 * pipeline's stages (cover, certify, arcs, sampling) come through the
 * library's callback. Nothing is drawn when stderr is not a terminal, with
 * --quiet, or on an MPI rank other than 0. */
#ifndef VB_CLI_PROGRESS_H
#define VB_CLI_PROGRESS_H

#include "vb.h"

/* --quiet (main.c): no progress and no status line, whatever the terminal
 * or VORBALL_PROGRESS say. */
void vb_cli_set_quiet(int on);

/* 1 when progress is drawn: not quiet, rank 0, and stderr a terminal
 * without VORBALL_NO_PROGRESS, or VORBALL_PROGRESS=1 (tests). */
int vb_cli_progress_wanted(void);

/* Installs the progress line as ctx's progress callback when it is
 * wanted (vb_cli_progress_wanted), and a log callback that erases the line
 * before a warning is printed; otherwise ctx is left alone. */
void vb_cli_progress_attach(vb_ctx *ctx);

/* Erases the progress line if one is drawn (a stage that failed before its
 * end); the next report starts afresh. */
void vb_cli_progress_clear(void);

/* Starts the status line with `label` (copied). Does nothing when stderr
 * is not a terminal or VORBALL_NO_PROGRESS is set; VORBALL_PROGRESS=1
 * draws it on any stderr (for tests). Safe to call once per command. */
void vb_cli_status_start(const char *label);

/* Changes the label (printf-style); the elapsed time keeps running. */
void vb_cli_status_set(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Stops the ticker and erases the line if it was drawn. */
void vb_cli_status_stop(void);

#endif
