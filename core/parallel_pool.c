/* The resident worker pool (parallel_pool.h, vb_parallel_shutdown): threads
 * created on first use, each parked on a condition variable of its own and
 * woken for one job a call, so a parallel for costs a wake-up, not a thread
 * start. One call holds the pool at a time; a call made while it is held
 * (another thread's, or a nested one from a pool thread or from the job the
 * caller runs) is refused and starts threads of its own, as every call did
 * before the pool. The threads are joined by vb_parallel_shutdown: when the
 * last context closes (vb_close), at exit, or when the program asks. */
#include "parallel_pool.h"

#include <pthread.h>
#include <stdlib.h>

#include "vb_parallel.h"

typedef struct worker {
    pthread_t th;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    void *(*fn)(void *);
    void *job;              /* the job to run; NULL while parked */
    int stop;               /* set by vb_parallel_shutdown */
} worker;

static worker ws[VB_MAX_THREADS - 1];
static pthread_mutex_t pool_mu = PTHREAD_MUTEX_INITIALIZER;
static int nworkers;        /* threads running, ws[0..nworkers) (pool_mu) */
static int busy;            /* a call (or a shutdown) holds the pool (pool_mu) */
static pthread_mutex_t done_mu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t done_cv = PTHREAD_COND_INITIALIZER;
static int pending;         /* jobs of the call not yet finished (done_mu) */
static pthread_once_t hooks_once = PTHREAD_ONCE_INIT;
static _Thread_local int in_pool; /* this thread is one of the pool's */

static void *work(void *arg)
{
    worker *w = arg;
    in_pool = 1;
    for (;;) {
        pthread_mutex_lock(&w->mu);
        while (!w->job && !w->stop)
            pthread_cond_wait(&w->cv, &w->mu);
        void *job = w->job;
        void *(*fn)(void *) = w->fn;
        w->job = NULL;
        pthread_mutex_unlock(&w->mu);
        if (!job)
            return NULL;
        fn(job);
        pthread_mutex_lock(&done_mu);
        if (--pending == 0)
            pthread_cond_signal(&done_cv);
        pthread_mutex_unlock(&done_mu);
    }
}

/* A forked child has the caller's thread only: it forgets the parent's
 * workers (their memory is the child's to leak, never to join). */
static void forget_after_fork(void)
{
    pool_mu = (pthread_mutex_t)PTHREAD_MUTEX_INITIALIZER;
    done_mu = (pthread_mutex_t)PTHREAD_MUTEX_INITIALIZER;
    done_cv = (pthread_cond_t)PTHREAD_COND_INITIALIZER;
    nworkers = busy = pending = 0;
}

static void install_hooks(void)
{
    atexit(vb_parallel_shutdown);
    pthread_atfork(NULL, NULL, forget_after_fork);
}

/* Starts workers until `want` run or one fails to start; pool_mu held. */
static void grow(int want)
{
    pthread_once(&hooks_once, install_hooks);
    while (nworkers < want) {
        worker *w = &ws[nworkers];
        *w = (worker){.fn = NULL};
        if (pthread_mutex_init(&w->mu, NULL) != 0)
            return;
        if (pthread_cond_init(&w->cv, NULL) != 0) {
            pthread_mutex_destroy(&w->mu);
            return;
        }
        if (pthread_create(&w->th, NULL, work, w) != 0) {
            pthread_cond_destroy(&w->cv);
            pthread_mutex_destroy(&w->mu);
            return;
        }
        nworkers++;
    }
}

/* Takes the pool for one call or a shutdown: 0 when it is held already or
 * the caller is a pool thread. */
static int take(void)
{
    if (in_pool)
        return 0;
    pthread_mutex_lock(&pool_mu);
    int got = !busy;
    busy = 1;
    pthread_mutex_unlock(&pool_mu);
    return got;
}

static void release(void)
{
    pthread_mutex_lock(&pool_mu);
    busy = 0;
    pthread_mutex_unlock(&pool_mu);
}

int vb_pool_run(void *(*fn)(void *), void *jobs, size_t job_size, int n)
{
    if (n > VB_MAX_THREADS)
        n = VB_MAX_THREADS;
    if (n < 2 || !take())
        return 0;
    pthread_mutex_lock(&pool_mu);
    grow(n - 1);
    int m = nworkers < n - 1 ? nworkers : n - 1;
    pthread_mutex_unlock(&pool_mu);
    char *base = jobs;
    pthread_mutex_lock(&done_mu);
    pending = m;
    pthread_mutex_unlock(&done_mu);
    for (int k = 0; k < m; k++) {
        worker *w = &ws[k];
        pthread_mutex_lock(&w->mu);
        w->fn = fn;
        w->job = base + (size_t)(k + 1) * job_size;
        pthread_cond_signal(&w->cv);
        pthread_mutex_unlock(&w->mu);
    }
    /* The caller's job, then those no worker took, in job order. */
    fn(base);
    for (int t = m + 1; t < n; t++)
        fn(base + (size_t)t * job_size);
    pthread_mutex_lock(&done_mu);
    while (pending > 0)
        pthread_cond_wait(&done_cv, &done_mu);
    pthread_mutex_unlock(&done_mu);
    release();
    return 1;
}

void vb_parallel_shutdown(void)
{
    if (!take())
        return;
    pthread_mutex_lock(&pool_mu);
    int n = nworkers;
    pthread_mutex_unlock(&pool_mu);
    for (int k = 0; k < n; k++) {
        pthread_mutex_lock(&ws[k].mu);
        ws[k].stop = 1;
        pthread_cond_signal(&ws[k].cv);
        pthread_mutex_unlock(&ws[k].mu);
    }
    for (int k = 0; k < n; k++) {
        pthread_join(ws[k].th, NULL);
        pthread_cond_destroy(&ws[k].cv);
        pthread_mutex_destroy(&ws[k].mu);
    }
    pthread_mutex_lock(&pool_mu);
    nworkers = 0;
    pthread_mutex_unlock(&pool_mu);
    release();
}
