/* The resident worker pool behind vb_run_jobs (core/parallel_pool.c); a
 * header of the root room, not part of the public API. */
#ifndef VB_PARALLEL_POOL_H
#define VB_PARALLEL_POOL_H

#include <stddef.h>

/* Runs fn on each of the n jobs (job_size bytes each, 2 <= n <=
 * VB_MAX_THREADS) on the pool's parked threads, job 0 on the caller, and
 * returns 1 when all have finished (a job no worker could take runs on the
 * caller after job 0, in job order, as vb_jobs_join does). Returns 0, having
 * run nothing, when the pool is busy with another call or the caller is one
 * of its threads: the caller then starts threads of its own. */
int vb_pool_run(void *(*fn)(void *), void *jobs, size_t job_size, int n);

#endif
