/* Work on several threads: running a set of jobs, and the sort of the
 * matching stage's large arrays. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vbs_internal.h"

/* Below this many elements the threads cost more than they save. */
#define VBS_PSORT_MIN 8192

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

void vbs_run_jobs(void *(*fn)(void *), void *jobs, size_t job_size, int n)
{
    pthread_t th[VBS_MAX_THREADS];
    int started[VBS_MAX_THREADS] = {0};
    char *job = jobs;
    if (n > VBS_MAX_THREADS)
        n = VBS_MAX_THREADS;
    for (int t = 1; t < n; t++)
        started[t] = pthread_create(&th[t], NULL, fn, job + (size_t)t * job_size) == 0;
    if (n > 0)
        fn(job);
    for (int t = 1; t < n; t++) {
        if (started[t])
            pthread_join(th[t], NULL);
        else
            fn(job + (size_t)t * job_size);
    }
}

int vbs_psort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *),
              int nthreads)
{
    int nt = nthreads < 1 ? 1 : nthreads > VBS_MAX_THREADS ? VBS_MAX_THREADS : nthreads;
    if (n < 2)
        return VB_OK;
    if (nt == 1 || n < VBS_PSORT_MIN) {
        qsort(base, n, size, cmp);
        return VB_OK;
    }
    char *tmp = malloc(n * size);
    if (!tmp)
        return VB_ENOMEM;
    /* Run boundaries: nt chunks of nearly equal length. */
    size_t bound[VBS_MAX_THREADS + 1];
    for (int t = 0; t <= nt; t++)
        bound[t] = n * (size_t)t / (size_t)nt;
    psort_job jobs[VBS_MAX_THREADS];
    for (int t = 0; t < nt; t++)
        jobs[t] = (psort_job){base, NULL, bound[t], 0, bound[t + 1], size, cmp};
    vbs_run_jobs(sort_chunk, jobs, sizeof *jobs, nt);
    char *src = base, *dst = tmp;
    for (int runs = nt; runs > 1; runs = (runs + 1) / 2) {
        int nj = 0;
        for (int r = 0; r < runs; r += 2) {
            size_t hi = r + 2 <= runs ? bound[r + 2] : bound[r + 1];
            jobs[nj++] = (psort_job){src, dst, bound[r], bound[r + 1], hi, size, cmp};
        }
        vbs_run_jobs(merge_runs, jobs, sizeof *jobs, nj);
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
