/* The resident worker pool (parallel_pool.h, vb_parallel_shutdown): threads
 * created on first use, each parked on a condition variable of its own and
 * woken for one job at a time, so a parallel for costs wake-ups, not thread
 * starts. Calls from several threads at once, and nested calls from inside
 * a job, each take the threads idle at that moment; the pool grows to at
 * most VB_MAX_THREADS - 1 threads, and the jobs it cannot take go back to
 * the caller (vb_run_jobs starts threads of their own for them, as every
 * call did before the pool). The threads are joined by
 * vb_parallel_shutdown: when the last context closes (vb_close), at exit,
 * or when the program asks. */
#include "parallel_pool.h"

#include <pthread.h>
#include <stdlib.h>

#include "vb_parallel.h"

#define POOL_MAX (VB_MAX_THREADS - 1)

typedef struct worker {
    pthread_t th;
    pthread_mutex_t mu;     /* guards fn, job, call, stop */
    pthread_cond_t cv;
    void *(*fn)(void *);
    void *job;              /* the job to run; NULL while parked */
    vb_pool_call *call;     /* the call it belongs to */
    int stop;               /* set by vb_parallel_shutdown */
    int idle;               /* free to take a job (pool_mu) */
} worker;

static worker ws[POOL_MAX];
static pthread_mutex_t pool_mu = PTHREAD_MUTEX_INITIALIZER;
static int nworkers;        /* threads running: ws[0..nworkers) (pool_mu) */
/* The calls' pending counts; done_cv wakes their callers. */
static pthread_mutex_t done_mu = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t done_cv = PTHREAD_COND_INITIALIZER;
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
        vb_pool_call *c = w->call;
        w->job = NULL;
        pthread_mutex_unlock(&w->mu);
        if (!job)
            return NULL;
        fn(job);
        /* Idle before the caller hears: its next call finds this thread. */
        pthread_mutex_lock(&pool_mu);
        w->idle = 1;
        pthread_mutex_unlock(&pool_mu);
        pthread_mutex_lock(&done_mu);
        if (--c->pending == 0)
            pthread_cond_broadcast(&done_cv);
        pthread_mutex_unlock(&done_mu);
    }
}

/* A forked child has the forking thread only: it forgets the parent's
 * workers (their memory is the child's to leak, never to join). */
static void forget_after_fork(void)
{
    pool_mu = (pthread_mutex_t)PTHREAD_MUTEX_INITIALIZER;
    done_mu = (pthread_mutex_t)PTHREAD_MUTEX_INITIALIZER;
    done_cv = (pthread_cond_t)PTHREAD_COND_INITIALIZER;
    nworkers = 0;
}

static void install_hooks(void)
{
    atexit(vb_parallel_shutdown);
    pthread_atfork(NULL, NULL, forget_after_fork);
}

/* Starts one more worker, busy (the caller's to give a job); pool_mu held.
 * Returns it, or NULL when the pool is full or the thread did not start. */
static worker *grow(void)
{
    if (nworkers >= POOL_MAX)
        return NULL;
    pthread_once(&hooks_once, install_hooks);
    worker *w = &ws[nworkers];
    *w = (worker){.idle = 0};
    if (pthread_mutex_init(&w->mu, NULL) != 0)
        return NULL;
    if (pthread_cond_init(&w->cv, NULL) != 0) {
        pthread_mutex_destroy(&w->mu);
        return NULL;
    }
    if (pthread_create(&w->th, NULL, work, w) != 0) {
        pthread_cond_destroy(&w->cv);
        pthread_mutex_destroy(&w->mu);
        return NULL;
    }
    nworkers++;
    return w;
}

int vb_pool_post(vb_pool_call *c, void *(*fn)(void *), void *jobs, size_t job_size, int n,
                 int pooled[])
{
    worker *mine[POOL_MAX];
    int m = 0;
    n = n > VB_MAX_THREADS ? VB_MAX_THREADS : n;
    for (int t = 0; t < n; t++)
        pooled[t] = 0;
    pthread_mutex_lock(&pool_mu);
    for (int k = 0; k < nworkers && m < n - 1; k++)
        if (ws[k].idle) {
            ws[k].idle = 0;
            mine[m++] = &ws[k];
        }
    while (m < n - 1) {
        worker *w = grow();
        if (!w)
            break;
        mine[m++] = w;
    }
    pthread_mutex_unlock(&pool_mu);
    c->pending = m;  /* no worker of c runs yet: done_mu not needed */
    char *base = jobs;
    for (int k = 0; k < m; k++) {
        worker *w = mine[k];
        pthread_mutex_lock(&w->mu);
        w->fn = fn;
        w->call = c;
        w->job = base + (size_t)(k + 1) * job_size;
        pthread_cond_signal(&w->cv);
        pthread_mutex_unlock(&w->mu);
        pooled[k + 1] = 1;
    }
    return m;
}

void vb_pool_wait(vb_pool_call *c)
{
    pthread_mutex_lock(&done_mu);
    while (c->pending > 0)
        pthread_cond_wait(&done_cv, &done_mu);
    pthread_mutex_unlock(&done_mu);
}

void vb_parallel_shutdown(void)
{
    if (in_pool)
        return;
    pthread_mutex_lock(&pool_mu);
    for (int k = 0; k < nworkers; k++)
        if (!ws[k].idle) {
            pthread_mutex_unlock(&pool_mu);
            return;
        }
    /* Every thread idle, and none can be taken while pool_mu is held. */
    for (int k = 0; k < nworkers; k++) {
        pthread_mutex_lock(&ws[k].mu);
        ws[k].stop = 1;
        pthread_cond_signal(&ws[k].cv);
        pthread_mutex_unlock(&ws[k].mu);
    }
    for (int k = 0; k < nworkers; k++) {
        pthread_join(ws[k].th, NULL);
        pthread_cond_destroy(&ws[k].cv);
        pthread_mutex_destroy(&ws[k].mu);
    }
    nworkers = 0;
    pthread_mutex_unlock(&pool_mu);
}
