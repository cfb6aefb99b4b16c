/* The resident worker pool behind vb_run_jobs (core/parallel_pool.c); a
 * header of the root room, not part of the public API. */
#ifndef VB_PARALLEL_POOL_H
#define VB_PARALLEL_POOL_H

#include <stddef.h>

/* One vb_run_jobs call's jobs on the pool: how many have not finished. */
typedef struct vb_pool_call {
    int pending;
} vb_pool_call;

/* Hands jobs 1..n-1 of `jobs` (job_size bytes each, n at most
 * VB_MAX_THREADS) to idle pool threads, starting threads while the pool
 * holds fewer than VB_MAX_THREADS - 1, and sets pooled[t] to 1 for each job
 * t handed over, 0 for the others (job 0 always: the caller's). Safe from
 * several threads at once and from inside a job: a job no idle thread can
 * take is left to the caller. Returns how many were handed over. */
int vb_pool_post(vb_pool_call *c, void *(*fn)(void *), void *jobs, size_t job_size, int n,
                 int pooled[]);

/* Returns when every job vb_pool_post handed over for c has finished. */
void vb_pool_wait(vb_pool_call *c);

#endif
