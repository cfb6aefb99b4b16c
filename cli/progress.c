/* The status line of long commands (progress.h). */
#include "progress.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "vb_parallel.h"

static struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    pthread_t thread;
    int running, stop, shown;
    double start;
    char label[160];
} st = {.lock = PTHREAD_MUTEX_INITIALIZER, .wake = PTHREAD_COND_INITIALIZER};

/* Seconds before the line first appears, and between redraws. */
#define VB_STATUS_DELAY 1.0
#define VB_STATUS_PERIOD_NS 500000000L

static void draw_locked(void)
{
    double t = vb_now() - st.start;
    if (t < VB_STATUS_DELAY)
        return;
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

void vb_cli_status_start(const char *label)
{
    const char *force = getenv("VORBALL_PROGRESS");
    int on = (force && strcmp(force, "1") == 0) ||
             (isatty(fileno(stderr)) && !getenv("VORBALL_NO_PROGRESS"));
    if (!on || st.running)
        return;
    pthread_mutex_lock(&st.lock);
    snprintf(st.label, sizeof st.label, "%s", label);
    st.start = vb_now();
    st.stop = 0;
    st.shown = 0;
    st.running = pthread_create(&st.thread, NULL, ticker, NULL) == 0;
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
