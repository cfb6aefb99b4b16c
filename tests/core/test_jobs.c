/* Jobs on threads (core/parallel.c, core/parallel_pool.c): the resident
 * pool runs every job once, reuses its threads from call to call, serves
 * nested calls and callers on several threads at once (those it cannot
 * take start threads of their own), takes job counts above its size, and
 * starts again after vb_parallel_shutdown; vb_jobs_first_error picks the error one
 * thread taking the items in order would meet, whichever job met it; a
 * worker context (vb_open_worker) speaks through its owner: warnings raised
 * on worker threads reach the owner's log callback, at the owner's
 * verbosity, while errors and counters stay the worker's. */
#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "vb_test.h"
#include "vb_diag.h"
#include "vb_parallel.h"

typedef struct job {
    int pad;
    int rc;
    size_t at;
} job;

static void first_error(void)
{
    job j[4] = {{0, VB_OK, SIZE_MAX}, {0, VB_OK, SIZE_MAX}, {0, VB_OK, SIZE_MAX},
                {0, VB_OK, SIZE_MAX}};
    size_t rc_off = offsetof(job, rc), at_off = offsetof(job, at);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), -1);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 0, rc_off, at_off), -1);
    /* The earliest item wins, not the lowest job. */
    j[1] = (job){0, VB_ENOMEM, 40};
    j[3] = (job){0, VB_EPREC, 7};
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), 3);
    /* Ties go to the lower job; a job past n is not looked at. */
    j[2] = (job){0, VB_EINTERNAL, 7};
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), 2);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 2, rc_off, at_off), 1);
    /* Unordered jobs: the lowest failing job. */
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, VB_JOBS_UNORDERED), 1);
    /* A bare array of statuses. */
    int rcs[3] = {VB_OK, VB_OK, VB_EDEVICE};
    CHECK_INT(vb_jobs_first_error(rcs, sizeof *rcs, 3, 0, VB_JOBS_UNORDERED), 2);
}

/* What the owner's log callback received. */
typedef struct heard {
    pthread_mutex_t mu;
    int n, warnings, infos;
    int numbers_ok, lines_ok, texts_ok;
} heard;

static void hear(void *arg, const vb_diag_record *r)
{
    heard *h = arg;
    pthread_mutex_lock(&h->mu);
    h->n++;
    if (r->kind == 'W') {
        h->warnings++;
        h->numbers_ok += r->number == VB_W_CONTAINED;
        h->lines_ok += r->file && strcmp(r->file, "worker.xyzr") == 0 && r->line >= 10 &&
                       r->line < 14;
        h->texts_ok += strncmp(r->message, "from worker ", 12) == 0;
    } else if (r->kind == 'I') {
        h->infos++;
    }
    pthread_mutex_unlock(&h->mu);
}

typedef struct wjob {
    vb_ctx *ctx;
    int index;
} wjob;

static void *warn_job(void *arg)
{
    wjob *j = arg;
    vb_warn(j->ctx, VB_W_CONTAINED, "worker.xyzr", 10 + j->index, "from worker %d", j->index);
    vb_info(j->ctx, "info from worker %d", j->index);
    vb_error(j->ctx, VB_EPREC, NULL, 0, "worker %d failed", j->index);
    return NULL;
}

static void worker_warnings(void)
{
    vb_ctx *owner, *w[4];
    CHECK_INT(vb_open(&owner, NULL), VB_OK);
    heard h = {PTHREAD_MUTEX_INITIALIZER, 0, 0, 0, 0, 0, 0};
    CHECK_INT(vb_set_log(owner, hear, &h), VB_OK);
    wjob jobs[4];
    for (int k = 0; k < 4; k++) {
        CHECK_INT(vb_open_worker(&w[k], owner), VB_OK);
        jobs[k] = (wjob){w[k], k};
    }
    vb_run_jobs(warn_job, jobs, sizeof *jobs, 4);
    /* Four warnings through the owner's callback, with their numbers,
     * places and texts; info lines wait for verbosity 2. */
    CHECK_INT(h.warnings, 4);
    CHECK_INT(h.numbers_ok, 4);
    CHECK_INT(h.lines_ok, 4);
    CHECK_INT(h.texts_ok, 4);
    CHECK_INT(h.infos, 0);
    /* Errors and counters stay the worker's. */
    CHECK_INT(vb_errcode(owner), VB_OK);
    CHECK_INT(vb_errcode(w[2]), VB_EPREC);
    CHECK_STR(vb_errmsg(w[2]), "worker 2 failed");
    CHECK_INT((long)vb_ctx_stats(w[1])->warnings, 1);
    CHECK_INT((long)vb_ctx_stats(owner)->warnings, 0);
    /* The owner's verbosity rules its workers: 2 lets info lines through,
     * 0 silences warnings (still counted). */
    vb_set_verbosity(owner, 2);
    vb_run_jobs(warn_job, jobs, sizeof *jobs, 4);
    CHECK_INT(h.warnings, 8);
    CHECK_INT(h.infos, 4);
    vb_set_verbosity(owner, 0);
    vb_run_jobs(warn_job, jobs, sizeof *jobs, 4);
    CHECK_INT(h.n, 12);
    CHECK_INT((long)vb_ctx_stats(w[3])->warnings, 3);
    for (int k = 0; k < 4; k++)
        vb_close(w[k]);
    /* A worker needs an open owner. */
    vb_ctx *bad = owner;
    CHECK_INT(vb_open_worker(&bad, NULL), VB_EMISUSE);
    CHECK(bad == NULL);
    vb_close(owner);
}

/* A parallel for writing each item's square and its thread's number. */
typedef struct squares {
    size_t *out;
    int *tid;
    int nt;
} squares;

static void square(void *ctx, size_t i, int tid)
{
    squares *s = ctx;
    s->out[i] = i * i;
    s->tid[i] = tid;
}

/* 1 when every item of n holds its square and ran on thread i mod nt. */
static int squares_ok(const squares *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (s->out[i] != i * i || s->tid[i] != (int)(i % (size_t)s->nt))
            return 0;
    return 1;
}

static int run_squares(size_t n, int nt)
{
    size_t out[1000];
    int tid[1000];
    squares s = {out, tid, nt < 1 ? 1 : nt > VB_MAX_THREADS ? VB_MAX_THREADS : nt};
    for (size_t i = 0; i < n; i++)
        out[i] = 7, tid[i] = -1;
    vb_parallel_for(square, &s, n, nt);
    return squares_ok(&s, n);
}

typedef struct who {
    pthread_t self;
    atomic_int *ran;
} who;

static void *note_thread(void *arg)
{
    who *w = arg;
    w->self = pthread_self();
    atomic_fetch_add(w->ran, 1);
    return NULL;
}

static void pool_reuse(void)
{
    /* Job t > 0 runs on the same parked thread call after call; job 0 on
     * the caller. */
    atomic_int ran = 0;
    who a[4], b[4];
    for (int t = 0; t < 4; t++)
        a[t] = b[t] = (who){0, &ran};
    vb_run_jobs(note_thread, a, sizeof *a, 4);
    vb_run_jobs(note_thread, b, sizeof *b, 4);
    CHECK_INT(atomic_load(&ran), 8);
    CHECK(pthread_equal(a[0].self, pthread_self()));
    int same = 0;
    for (int t = 1; t < 4; t++)
        same += pthread_equal(a[t].self, b[t].self) && !pthread_equal(a[t].self, pthread_self());
    CHECK_INT(same, 3);
    /* More jobs than the pool has threads: it grows; and the most it takes. */
    CHECK(run_squares(1000, 9));
    CHECK(run_squares(1000, VB_MAX_THREADS));
    CHECK(run_squares(1000, 1000));
    CHECK(run_squares(5, 16));
    CHECK(run_squares(0, 16));
    /* A shutdown joins the pool (twice is harmless); the next call starts
     * it again. */
    vb_parallel_shutdown();
    vb_parallel_shutdown();
    CHECK(run_squares(1000, 3));
    who c[4];
    for (int t = 0; t < 4; t++)
        c[t] = (who){0, &ran};
    vb_run_jobs(note_thread, c, sizeof *c, 4);
    CHECK_INT(atomic_load(&ran), 12);
}

/* Nested: each item of the outer for runs an inner for of its own. */
typedef struct nest {
    atomic_int ok;
} nest;

static void inner_for(void *ctx, size_t i, int tid)
{
    (void)tid;
    nest *n = ctx;
    atomic_fetch_add(&n->ok, run_squares(200 + i, 1 + (int)(i % 5)));
}

static void nested_calls(void)
{
    nest n = {0};
    vb_parallel_for(inner_for, &n, 24, 6);
    CHECK_INT(atomic_load(&n.ok), 24);
}

/* Callers on four threads at once, each running many parallel fors; every
 * tenth asks for VB_MAX_THREADS threads, more than the pool holds beside
 * the others' calls. */
static void *caller(void *arg)
{
    int *ok = arg;
    for (int r = 0; r < 200; r++)
        *ok += run_squares(300 + (size_t)r, r % 10 ? 2 + r % 7 : VB_MAX_THREADS);
    return NULL;
}

static void concurrent_callers(void)
{
    pthread_t th[4];
    int ok[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; k++)
        CHECK_INT(pthread_create(&th[k], NULL, caller, &ok[k]), 0);
    for (int k = 0; k < 4; k++)
        pthread_join(th[k], NULL);
    for (int k = 0; k < 4; k++)
        CHECK_INT(ok[k], 200);
}

int main(void)
{
    first_error();
    pool_reuse();
    nested_calls();
    concurrent_callers();
    worker_warnings();
    VB_TEST_END();
}
