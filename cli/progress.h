/* A status line for long commands: what is running and for how long, on
 * stderr, only when stderr is a terminal and only once the work has taken
 * a second (logs and pipes stay clean). A ticker thread redraws it twice a
 * second, so one long library call (the exact diagram of `jfa --check`, the
 * brute force of `reference`) shows that it is alive; commands with known
 * steps say "frame 3 of 51" through vb_cli_status_set. The vertex
 * pipeline's own bar (pipeline_options.h) draws its fraction done. */
#ifndef VB_CLI_PROGRESS_H
#define VB_CLI_PROGRESS_H

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
