/* Clocks and threads (vb_parallel.h): the monotonic clock, the thread-count
 * policy, the launcher, the parallel for and the parallel sort. */
#include "vb_parallel.h"
#include "parallel_pool.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Below this many elements the threads cost more than they save. */
#define VB_PSORT_MIN 8192

typedef struct psort_job {
    char *src, *dst;
    size_t lo, mid, hi;      /* a chunk [lo, hi), or runs [lo, mid) and [mid, hi) */
    size_t size;
    int (*cmp)(const void *, const void *);
} psort_job;

static void *sort_chunk(void *arg)
{
    psort_job *j = arg;
    qsort(j->src + j->lo * j->size, j->hi - j->lo, j->size, j->cmp);
    return NULL;
}

/* Merges the sorted runs src[lo, mid) and src[mid, hi) into dst[lo, hi);
 * on equal elements the left run goes first. */
static void *merge_runs(void *arg)
{
    psort_job *j = arg;
    size_t a = j->lo, b = j->mid, o = j->lo, sz = j->size;
    while (a < j->mid && b < j->hi) {
        const char *pa = j->src + a * sz, *pb = j->src + b * sz;
        if (j->cmp(pb, pa) < 0) {
            memcpy(j->dst + o++ * sz, pb, sz);
            b++;
        } else {
            memcpy(j->dst + o++ * sz, pa, sz);
            a++;
        }
    }
    memcpy(j->dst + o * sz, j->src + a * sz, (j->mid - a) * sz);
    o += j->mid - a;
    memcpy(j->dst + o * sz, j->src + b * sz, (j->hi - b) * sz);
    return NULL;
}

double vb_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int vb_threads(unsigned requested)
{
    long n = (long)requested;
    const char *env = getenv("VORBALL_THREADS");
    if (n <= 0 && env && *env) {
        char *end;
        long v = strtol(env, &end, 10);
        if (*end == '\0' && v > 0)
            n = v;
    }
    if (n <= 0)
        n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > VB_MAX_THREADS ? VB_MAX_THREADS : (int)n;
}

/* Starts jobs first..n-1 of g on threads, but those skip marks (the pool's;
 * skip may be NULL). */
static int start_from(vb_jobs *g, int first, const int *skip)
{
    int started = 0;
    for (int t = 0; t < g->n; t++) {
        g->started[t] = t >= first && !(skip && skip[t]) &&
                        pthread_create(&g->th[t], NULL, g->fn, g->jobs + (size_t)t * g->job_size) == 0;
        started += g->started[t];
    }
    return started;
}

static void setup(vb_jobs *g, void *(*fn)(void *), void *jobs, size_t job_size, int n)
{
    g->fn = fn;
    g->jobs = jobs;
    g->job_size = job_size;
    g->n = n < 0 ? 0 : n > VB_MAX_THREADS ? VB_MAX_THREADS : n;
}

int vb_jobs_start(vb_jobs *g, void *(*fn)(void *), void *jobs, size_t job_size, int n)
{
    setup(g, fn, jobs, job_size, n);
    return start_from(g, 0, NULL);
}

/* Waits for g's jobs but those skip marks (may be NULL), in order, running
 * on the caller's thread those whose thread did not start. */
static void join_except(vb_jobs *g, const int *skip)
{
    for (int t = 0; t < g->n; t++) {
        if (skip && skip[t])
            continue;
        if (g->started[t])
            pthread_join(g->th[t], NULL);
        else
            g->fn(g->jobs + (size_t)t * g->job_size);
        g->started[t] = 0;
    }
    g->n = 0;
}

void vb_jobs_join(vb_jobs *g)
{
    join_except(g, NULL);
}

void vb_run_jobs(void *(*fn)(void *), void *jobs, size_t job_size, int n)
{
    vb_jobs g;
    setup(&g, fn, jobs, job_size, n);
    vb_pool_call pc;
    int pooled[VB_MAX_THREADS];
    vb_pool_post(&pc, fn, jobs, job_size, g.n, pooled);
    /* Jobs the pool could not take: threads of their own, else the caller;
     * the caller's job first, then those that did not start, in order. */
    start_from(&g, 1, pooled);
    join_except(&g, pooled);
    vb_pool_wait(&pc);
}

int vb_jobs_first_error(const void *jobs, size_t job_size, int n, size_t rc_off, size_t at_off)
{
    const char *base = jobs;
    int bad = -1;
    size_t bad_at = 0;
    for (int t = 0; t < n; t++) {
        const char *j = base + (size_t)t * job_size;
        int rc;
        memcpy(&rc, j + rc_off, sizeof rc);
        if (rc == VB_OK)
            continue;
        size_t at = 0;
        if (at_off != VB_JOBS_UNORDERED)
            memcpy(&at, j + at_off, sizeof at);
        if (bad < 0 || at < bad_at) {
            bad = t;
            bad_at = at;
        }
    }
    return bad;
}

typedef struct for_job {
    vb_for_fn fn;
    void *ctx;
    size_t n;
    int tid, nt;
} for_job;

static void *for_worker(void *arg)
{
    for_job *j = arg;
    for (size_t i = (size_t)j->tid; i < j->n; i += (size_t)j->nt)
        j->fn(j->ctx, i, j->tid);
    return NULL;
}

void vb_parallel_for(vb_for_fn fn, void *ctx, size_t n, int nthreads)
{
    int nt = nthreads < 1 ? 1 : nthreads > VB_MAX_THREADS ? VB_MAX_THREADS : nthreads;
    for_job jobs[VB_MAX_THREADS];
    for (int t = 0; t < nt; t++)
        jobs[t] = (for_job){fn, ctx, n, t, nt};
    vb_run_jobs(for_worker, jobs, sizeof *jobs, nt);
}

int vb_psort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *),
              int nthreads)
{
    int nt = nthreads < 1 ? 1 : nthreads > VB_MAX_THREADS ? VB_MAX_THREADS : nthreads;
    if (n < 2)
        return VB_OK;
    if (nt == 1 || n < VB_PSORT_MIN) {
        qsort(base, n, size, cmp);
        return VB_OK;
    }
    char *tmp = malloc(n * size);
    if (!tmp)
        return VB_ENOMEM;
    /* Run boundaries: nt chunks of nearly equal length. */
    size_t bound[VB_MAX_THREADS + 1];
    for (int t = 0; t <= nt; t++)
        bound[t] = n * (size_t)t / (size_t)nt;
    psort_job jobs[VB_MAX_THREADS];
    for (int t = 0; t < nt; t++)
        jobs[t] = (psort_job){base, NULL, bound[t], 0, bound[t + 1], size, cmp};
    vb_run_jobs(sort_chunk, jobs, sizeof *jobs, nt);
    char *src = base, *dst = tmp;
    for (int runs = nt; runs > 1; runs = (runs + 1) / 2) {
        int nj = 0;
        for (int r = 0; r < runs; r += 2) {
            size_t hi = r + 2 <= runs ? bound[r + 2] : bound[r + 1];
            jobs[nj++] = (psort_job){src, dst, bound[r], bound[r + 1], hi, size, cmp};
        }
        vb_run_jobs(merge_runs, jobs, sizeof *jobs, nj);
        /* The surviving boundaries: every other one. */
        int k = 0;
        for (int r = 0; r <= runs; r += 2)
            bound[k++] = bound[r];
        if (runs % 2)
            bound[k++] = bound[runs];
        char *sw = src;
        src = dst;
        dst = sw;
    }
    if (src != base)
        memcpy(base, src, n * size);
    free(tmp);
    return VB_OK;
}
