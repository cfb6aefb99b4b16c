/* Clocks and threads for every room of the library: one monotonic clock, one
 * thread-count policy, one thread launcher, a parallel for and a parallel
 * sort built on it. No result of vorball depends on the number of threads:
 * every caller places results by item and merges them in item order. */
#ifndef VB_PARALLEL_H
#define VB_PARALLEL_H

#include <pthread.h>
#include <stddef.h>

#include "vb.h"

/* Most threads any stage runs. */
#define VB_MAX_THREADS 64

/* Monotonic wall clock in seconds (stage times, timings of the commands). */
double vb_now(void);

/* The thread-count policy: `requested` when positive, else the environment
 * variable VORBALL_THREADS when it is a positive integer, else the online
 * CPUs; at least 1, at most VB_MAX_THREADS. */
int vb_threads(unsigned requested);

/* The thread launcher: jobs running on threads of their own while the
 * caller goes on (the device opener, the culling of the next batch). */
typedef struct vb_jobs {
    void *(*fn)(void *);
    char *jobs;
    size_t job_size;
    int n;
    pthread_t th[VB_MAX_THREADS];
    int started[VB_MAX_THREADS];
} vb_jobs;

/* Starts fn on each of the n jobs (job_size bytes each, n at most
 * VB_MAX_THREADS), one thread each. Returns how many threads started; a job
 * whose thread could not start runs in vb_jobs_join. */
int vb_jobs_start(vb_jobs *g, void *(*fn)(void *), void *jobs, size_t job_size, int n);

/* Waits for the jobs of vb_jobs_start, first running on the caller's thread
 * those whose thread did not start. Returns when all have finished. */
void vb_jobs_join(vb_jobs *g);

/* Runs fn on each of the n jobs and returns when all have finished: the
 * caller runs the first; the others run on the resident pool's idle
 * parked threads (core/parallel_pool.c), those it cannot take (busy with
 * other calls, or the pool full) on threads of their own, else on the
 * caller after the first, in order. Safe to call from several threads at
 * once and from inside a job. */
void vb_run_jobs(void *(*fn)(void *), void *jobs, size_t job_size, int n);

/* Joins the resident pool's threads when all are idle (else does
 * nothing; from a pool thread, nothing); the next vb_run_jobs starts them again. vb_close of the last
 * open context and exit call it; a program that keeps no context open may
 * call it itself (leak checkers then see no thread left). */
void vb_parallel_shutdown(void);

/* Marks jobs whose failures carry no item for vb_jobs_first_error. */
#define VB_JOBS_UNORDERED ((size_t)-1)

/* The first error of n jobs that ran at once, as one thread taking their
 * items in order would have met it. Job t (at jobs + t * job_size) holds
 * its status, an int, at byte rc_off; unless at_off is VB_JOBS_UNORDERED it
 * holds at byte at_off the item (a size_t) where it failed. The failing job
 * with the earliest item wins, ties (and unordered jobs) to the lower job.
 * Returns that job's index, or -1 when every job ended VB_OK. */
int vb_jobs_first_error(const void *jobs, size_t job_size, int n, size_t rc_off, size_t at_off);

/* A parallel for: item i of n goes to thread i mod nthreads (tid is that
 * thread's number, for per-thread scratch); items must be independent.
 * nthreads is clamped to 1..VB_MAX_THREADS. */
typedef void (*vb_for_fn)(void *ctx, size_t i, int tid);
void vb_parallel_for(vb_for_fn fn, void *ctx, size_t n, int nthreads);

/* Sorts base[0..n) (elements of `size` bytes) on up to nthreads threads:
 * chunks by qsort, then merged. cmp must be a total order (ties broken by
 * an index), so the result is the one sorted array whatever nthreads is.
 * Returns VB_OK, or VB_ENOMEM with base unchanged. */
int vb_psort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *),
             int nthreads);

#endif
