/* The status line of long commands (progress.h). */
#include "progress.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "vb_parallel.h"
#include "vb_world.h"

static struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    pthread_t thread;
    int running, stop, shown;
    double start;
    char label[160];
    /* The library's progress (vb_progress_fn): the stage being drawn, its
     * counts, when it began, the smoothed rate and when it was last drawn. */
    int active;
    char stage[32];
    uint64_t done, total, rate_done;
    double stage_start, rate_t, rate, drawn_t;
} st = {.lock = PTHREAD_MUTEX_INITIALIZER, .wake = PTHREAD_COND_INITIALIZER};

static int quiet;

/* Seconds before the line first appears, and between redraws. */
#define VB_STATUS_DELAY 1.0
#define VB_STATUS_PERIOD_NS 500000000L

static int forced(void)
{
    const char *force = getenv("VORBALL_PROGRESS");
    return force && strcmp(force, "1") == 0;
}

static void draw_locked(void)
{
    if (st.active)
        return; /* the progress line has the terminal */
    double t = vb_now() - st.start;
    if (t < VB_STATUS_DELAY && !forced())
        return; /* VORBALL_PROGRESS=1 draws short runs too, from their start */
    fprintf(stderr, "\r\033[K%s  [%.0f s]", st.label, t);
    fflush(stderr);
    st.shown = 1;
}

static void *ticker(void *arg)
{
    (void)arg;
    pthread_mutex_lock(&st.lock);
    while (!st.stop) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        ts.tv_nsec += VB_STATUS_PERIOD_NS;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&st.wake, &st.lock, &ts);
        if (!st.stop)
            draw_locked();
    }
    pthread_mutex_unlock(&st.lock);
    return NULL;
}

void vb_cli_set_quiet(int on)
{
    quiet = on;
}

int vb_cli_progress_wanted(void)
{
    if (quiet || vb_world_rank() != 0)
        return 0;
    return forced() || (isatty(fileno(stderr)) && !getenv("VORBALL_NO_PROGRESS"));
}

void vb_cli_status_start(const char *label)
{
    if (!vb_cli_progress_wanted() || st.running)
        return;
    pthread_mutex_lock(&st.lock);
    snprintf(st.label, sizeof st.label, "%s", label);
    st.start = vb_now();
    st.stop = 0;
    st.shown = 0;
    st.running = pthread_create(&st.thread, NULL, ticker, NULL) == 0;
    if (st.running && forced())
        draw_locked();
    pthread_mutex_unlock(&st.lock);
}

void vb_cli_status_set(const char *fmt, ...)
{
    if (!st.running)
        return;
    pthread_mutex_lock(&st.lock);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st.label, sizeof st.label, fmt, ap);
    va_end(ap);
    if (st.shown)
        draw_locked();
    pthread_mutex_unlock(&st.lock);
}

void vb_cli_status_stop(void)
{
    vb_cli_progress_clear();
    if (!st.running)
        return;
    pthread_mutex_lock(&st.lock);
    st.stop = 1;
    pthread_cond_signal(&st.wake);
    pthread_mutex_unlock(&st.lock);
    pthread_join(st.thread, NULL);
    st.running = 0;
    if (st.shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
    }
    st.shown = 0;
}

/* ---- the library's progress --------------------------------------------- */

/* Seconds between two drawings of the progress line (at most 4 a second),
 * before a stage is first drawn (a quick stage is never drawn, unless
 * VORBALL_PROGRESS=1), and the weight of the newest rate in the smoothed
 * one (an exponential average over about the last 3 drawings). */
#define VB_PROGRESS_PERIOD 0.25
#define VB_PROGRESS_DELAY 0.5
#define VB_PROGRESS_ALPHA 0.3

static void progress_draw_locked(double now)
{
    char line[200];
    int k;
    if (st.total > 0) {
        double pct = 100.0 * (double)st.done / (double)st.total;
        k = snprintf(line, sizeof line, "%s: %llu/%llu (%.1f%%)", st.stage,
                     (unsigned long long)st.done, (unsigned long long)st.total, pct);
    } else {
        k = snprintf(line, sizeof line, "%s: %llu", st.stage, (unsigned long long)st.done);
    }
    if (k > 0 && (size_t)k < sizeof line && st.rate > 0.0) {
        int r = snprintf(line + k, sizeof line - (size_t)k, st.rate >= 100.0 ? ", %.0f/s" : ", %.2g/s",
                         st.rate);
        if (r > 0)
            k += r;
        if (st.total > st.done && (size_t)k < sizeof line)
            snprintf(line + k, sizeof line - (size_t)k, ", ~%.0fs left",
                     (double)(st.total - st.done) / st.rate);
    }
    fprintf(stderr, "\r\033[K%s", line);
    fflush(stderr);
    st.shown = 1;
    st.drawn_t = now;
}

static void erase_locked(void)
{
    if (st.shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
    }
    st.shown = 0;
}

/* The vb_progress_fn the CLI installs (the library serialises its calls;
 * the lock orders them with the status ticker). */
static void on_progress(void *user, const char *stage, uint64_t done, uint64_t total)
{
    (void)user;
    double now = vb_now();
    pthread_mutex_lock(&st.lock);
    if (!st.active || strncmp(st.stage, stage, sizeof st.stage - 1) != 0 || done < st.done) {
        snprintf(st.stage, sizeof st.stage, "%s", stage);
        st.active = 1;
        st.stage_start = st.rate_t = now;
        st.rate_done = done;
        st.rate = 0.0;
        st.drawn_t = 0.0;
    }
    st.done = done;
    st.total = total;
    if (now - st.rate_t >= VB_PROGRESS_PERIOD && done >= st.rate_done) {
        double r = (double)(done - st.rate_done) / (now - st.rate_t);
        st.rate = st.rate > 0.0 ? VB_PROGRESS_ALPHA * r + (1.0 - VB_PROGRESS_ALPHA) * st.rate : r;
        st.rate_t = now;
        st.rate_done = done;
    }
    int finished = total > 0 && done >= total;
    int due = now - st.drawn_t >= VB_PROGRESS_PERIOD &&
              (forced() || now - st.stage_start >= VB_PROGRESS_DELAY);
    if (finished) {
        if (st.shown)
            progress_draw_locked(now); /* its last count, then the line goes */
        erase_locked();
        st.active = 0;
    } else if (due) {
        progress_draw_locked(now);
    }
    pthread_mutex_unlock(&st.lock);
}

/* The vb_log_fn the CLI installs beside the progress: a warning or info
 * line erases the progress or status line first (it would otherwise be
 * printed after the line's text, and the next drawing would erase the
 * warning's start), then goes out as the library's own text. The line
 * comes back at its next drawing. */
static void on_log(void *user, const vb_diag_record *rec)
{
    (void)user;
    pthread_mutex_lock(&st.lock);
    erase_locked();
    vb_diag_record_write(stderr, rec);
    fflush(stderr);
    st.drawn_t = 0.0; /* redraw at the next report */
    pthread_mutex_unlock(&st.lock);
}

void vb_cli_progress_attach(vb_ctx *ctx)
{
    if (vb_cli_progress_wanted()) {
        vb_set_progress(ctx, on_progress, NULL);
        vb_set_log(ctx, on_log, NULL);
    }
}

void vb_cli_progress_clear(void)
{
    pthread_mutex_lock(&st.lock);
    if (st.active)
        erase_locked();
    st.active = 0;
    pthread_mutex_unlock(&st.lock);
}
