/* The certifier's set-up beside the proposer, and certification part by
 * part beside the cover (vbv_certify.h): a queue of parts that one thread
 * certifies in turn. The vertices do not depend on how the quadruples were
 * cut into parts or in what order they came: the parts' sorted lists are
 * merged and a vertex certified in two parts written once. */
#include "vbv_certify.h"

#include <stdlib.h>
#include <string.h>

#include "vb_array.h"

int vbv_certify_quads(vb_ctx *ctx, const vb_certifier_ops *ops, void *cert,
                      const vb_quad_list *l, vb_vertex_list *certified, vb_vertex_list *rejected)
{
    const uint32_t(*q)[4] = (const uint32_t(*)[4])l->q;
    if (l->verdict && ops->certify_quads_judged)
        return ops->certify_quads_judged(ctx, cert, q, l->verdict, l->n, certified);
    return ops->certify_quads(ctx, cert, q, l->n, certified, rejected);
}

static void *open_certifier(void *arg)
{
    vbv_cert_open *co = arg;
    co->rc = co->tctx ? co->ops->open(co->tctx, co->set, co->threads, &co->cert) : VB_ENOMEM;
    return NULL;
}

void vbv_cert_open_start(vbv_cert_open *co, const vb_certifier_ops *ops, const vb_sphere_set *set,
                         unsigned threads, vb_ctx *owner)
{
    memset(co, 0, sizeof *co);
    co->ops = ops;
    co->set = set;
    co->threads = threads;
    if (vb_open_worker(&co->tctx, owner) != VB_OK)
        co->tctx = NULL;
    vb_jobs_start(&co->job, open_certifier, co, sizeof *co, 1);
}

static void open_wait(vbv_cert_open *co)
{
    if (!co->joined)
        vb_jobs_join(&co->job);
    co->joined = 1;
}

void *vbv_cert_open_join(vb_ctx *ctx, vbv_cert_open *co, int *rc)
{
    open_wait(co);
    *rc = co->rc;
    void *cert = co->cert;
    if (co->rc != VB_OK) {
        if (cert)
            co->ops->close(cert);
        cert = NULL;
        *rc = vb_error(ctx, co->rc, NULL, 0, "%s", co->tctx ? vb_errmsg(co->tctx) : "out of memory");
    }
    co->cert = NULL;
    vb_close(co->tctx);
    co->tctx = NULL;
    return cert;
}

void vbv_cert_open_discard(vbv_cert_open *co)
{
    open_wait(co);
    if (co->cert)
        co->ops->close(co->cert);
    co->cert = NULL;
    vb_close(co->tctx);
    co->tctx = NULL;
}

int vbv_cert_stream_init(vbv_cert_stream *cs, vbv_cert_open *co, vb_ctx *owner)
{
    memset(cs, 0, sizeof *cs);
    cs->co = co;
    cs->ops = co->ops;
    cs->threads = vb_threads(co->threads);
    if (pthread_mutex_init(&cs->mu, NULL))
        return VB_ENOMEM;
    if (pthread_cond_init(&cs->cv, NULL)) {
        pthread_mutex_destroy(&cs->mu);
        return VB_ENOMEM;
    }
    cs->owner = owner;
    cs->set = co->set;
    cs->started = -1; /* the lock and condition are made */
    return vb_open_worker(&cs->tctx, owner) == VB_OK ? VB_OK : VB_ENOMEM;
}

/* Merges the last k certified parts into one list. VB_OK or VB_ENOMEM. */
static int fold_parts(vbv_cert_stream *cs, size_t k)
{
    vb_vertex_list all;
    vb_vertex_list_init(&all);
    size_t dropped = 0, first = cs->nparts - k;
    int rc = vb_vertex_list_merge(&all, cs->parts + first, k, &dropped);
    if (rc != VB_OK) {
        vb_vertex_list_free(&all);
        return rc;
    }
    for (size_t p = first; p < cs->nparts; p++)
        vb_vertex_list_free(&cs->parts[p]);
    cs->parts[first] = all;
    cs->nparts = first + 1;
    cs->dropped += dropped;
    return VB_OK;
}

/* Keeps the certified lists few while the cover runs, so that little is
 * left to merge after it: the newest two are merged while the older is at
 * most twice the newer (sizes then halve down the list: about log2 of the
 * parts are held, and each vertex is copied about log2 times in all), and
 * never more than 64 are held (vb_vertex_list_merge's bound). */
static int fold_recent(vbv_cert_stream *cs)
{
    int rc = VB_OK;
    while (rc == VB_OK && cs->nparts >= 2 &&
           cs->parts[cs->nparts - 2].n <= 2 * cs->parts[cs->nparts - 1].n)
        rc = fold_parts(cs, 2);
    if (rc == VB_OK && cs->nparts == 64)
        rc = fold_parts(cs, 64);
    return rc;
}

/* One queued part: sorted, certified, its vertices kept. */
static int certify_one(vbv_cert_stream *cs, vb_quad_list *part)
{
    int rc = vb_quad_list_canonical(part, cs->threads);
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    if (rc == VB_OK)
        rc = vbv_certify_quads(cs->tctx, cs->ops, cs->cert, part, &v, NULL);
    /* the part's vertices to the work while the proposer goes on (its
     * seconds apart from the certification's: t_pw); none once the
     * proposer returned (pw_done: the work is then the caller's own) */
    pthread_mutex_lock(&cs->mu);
    int work = rc == VB_OK && cs->pw && v.n && !cs->pw_done;
    cs->in_pw = work;
    cs->pw_since = vb_now();
    pthread_mutex_unlock(&cs->mu);
    if (work) {
        if (!cs->pw_state && !cs->pw_opened)
            rc = cs->pw->open(cs->owner, cs->set, cs->ops, cs->cert, (unsigned)cs->threads,
                              &cs->pw_state);
        cs->pw_opened = 1;
        if (rc == VB_OK && cs->pw_state)
            rc = cs->pw->part(cs->tctx, cs->pw_state, &v);
        pthread_mutex_lock(&cs->mu);
        cs->in_pw = 0;
        cs->pw_last = vb_now() - cs->pw_since;
        cs->t_pw += cs->pw_last;
        pthread_mutex_unlock(&cs->mu);
    }
    /* The parts are the thread's alone until it is idle (stream_wait). */
    if (rc == VB_OK && VB_ARRAY_FIT(cs->parts, cs->cap, cs->nparts + 1, 8) != VB_OK)
        rc = VB_ENOMEM;
    if (rc == VB_OK) {
        cs->parts[cs->nparts++] = v;
        cs->certified_parts++;
        rc = fold_recent(cs);
    } else {
        vb_vertex_list_free(&v);
    }
    if (rc == VB_ENOMEM)
        vb_error(cs->tctx, VB_ENOMEM, NULL, 0, "out of memory (certifier)");
    return rc;
}

/* The stream's thread: the set-up joined, then the queued parts in turn
 * until the stream closes (after a failure it only drops them). */
static void *stream_thread(void *arg)
{
    vbv_cert_stream *cs = arg;
    int rc = VB_OK;
    if (cs->co) {
        cs->cert = vbv_cert_open_join(cs->tctx, cs->co, &rc);
        cs->co = NULL;
    }
    pthread_mutex_lock(&cs->mu);
    if (rc != VB_OK && cs->rc == VB_OK)
        cs->rc = rc;
    for (;;) {
        while (cs->qhead == cs->qn && !cs->closing)
            pthread_cond_wait(&cs->cv, &cs->mu);
        if (cs->qhead == cs->qn)
            break;
        vb_quad_list part = cs->queue[cs->qhead];
        cs->pw_last = 0;
        memset(&cs->queue[cs->qhead++], 0, sizeof part);
        int ok = cs->rc == VB_OK && !cs->drop;
        cs->busy = ok;
        cs->t_busy_since = vb_now();
        pthread_mutex_unlock(&cs->mu);
        rc = ok ? certify_one(cs, &part) : VB_OK;
        vb_quad_list_free(&part);
        pthread_mutex_lock(&cs->mu);
        if (ok)
            cs->t_work += vb_now() - cs->t_busy_since - cs->pw_last;
        if (rc != VB_OK && cs->rc == VB_OK)
            cs->rc = rc;
        cs->busy = 0;
        pthread_cond_broadcast(&cs->cv);
    }
    pthread_mutex_unlock(&cs->mu);
    return NULL;
}

int vbv_cert_stream_sink(void *user, vb_quad_list *part)
{
    vbv_cert_stream *cs = user;
    pthread_mutex_lock(&cs->mu);
    int rc = cs->rc;
    if (rc == VB_OK && cs->qhead == cs->qn)
        cs->qhead = cs->qn = 0; /* the queue is empty: its room is reused */
    if (rc == VB_OK && VB_ARRAY_FIT(cs->queue, cs->qcap, cs->qn + 1, 8) != VB_OK)
        rc = VB_ENOMEM;
    if (rc == VB_OK) {
        cs->queue[cs->qn++] = *part;
        memset(part, 0, sizeof *part);
        pthread_cond_broadcast(&cs->cv);
    }
    int start = rc == VB_OK && cs->started == -1;
    if (start)
        cs->started = 1;
    pthread_mutex_unlock(&cs->mu);
    /* A thread that cannot start certifies the queue when joined. */
    if (start && vb_jobs_start(&cs->job, stream_thread, cs, sizeof *cs, 1) != 1) {
        pthread_mutex_lock(&cs->mu);
        cs->started = 2;
        pthread_mutex_unlock(&cs->mu);
    }
    return rc;
}

/* Waits until the queue is empty and the thread idle; then, when `close`
 * (or when the thread never started), stops the thread and joins it.
 * Returns the stream's status. */
static int stream_wait(vbv_cert_stream *cs, int close)
{
    if (cs->started == 0)
        return cs->rc;
    pthread_mutex_lock(&cs->mu);
    while (cs->started == 1 && (cs->qhead < cs->qn || cs->busy))
        pthread_cond_wait(&cs->cv, &cs->mu);
    int join = cs->started == 2 || (close && cs->started == 1);
    if (join) {
        cs->closing = 1;
        pthread_cond_broadcast(&cs->cv);
    }
    int rc = cs->rc;
    pthread_mutex_unlock(&cs->mu);
    if (join) {
        vb_jobs_join(&cs->job);
        cs->started = -1;
        cs->closing = 0;
    }
    return rc;
}

static void drop_parts(vbv_cert_stream *cs)
{
    for (size_t k = 0; k < cs->nparts; k++)
        vb_vertex_list_free(&cs->parts[k]);
    cs->nparts = 0;
    cs->dropped = 0;
}

void vbv_cert_stream_reset(vbv_cert_stream *cs)
{
    stream_wait(cs, 0);
    drop_parts(cs);
    cs->certified_parts = 0; /* the thread is idle: the count is the next run's */
}

int vbv_cert_stream_finish(vb_ctx *ctx, vbv_cert_stream *cs, vb_vertex_list *out)
{
    if (cs->started > 0) {
        pthread_mutex_lock(&cs->mu);
        double now = vb_now();
        cs->pw_done = 1;
        cs->t_overlap = cs->t_work;
        cs->t_pw_overlap = cs->t_pw;
        if (cs->busy && cs->in_pw) { /* the part's certification done, its work in progress */
            cs->t_overlap += cs->pw_since - cs->t_busy_since;
            cs->t_pw_overlap += now - cs->pw_since;
        } else if (cs->busy) {
            cs->t_overlap += now - cs->t_busy_since;
        }
        pthread_mutex_unlock(&cs->mu);
    } else {
        cs->pw_done = 1; /* no thread: nothing reads it meanwhile */
    }
    int rc = stream_wait(cs, 1);
    if (cs->co) { /* no part came: the set-up is still to be joined */
        int orc;
        cs->cert = vbv_cert_open_join(cs->tctx, cs->co, &orc);
        cs->co = NULL;
        if (rc == VB_OK)
            rc = cs->rc = orc;
    }
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(cs->tctx));
    memset(vb_ctx_stats(cs->tctx), 0, sizeof(vb_stats));
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "%s", vb_errmsg(cs->tctx));
    /* A vertex of degree > 4 is reached from quadruples of every cell of
     * its members, which parts may split: certified in two parts, it is
     * the same entry twice, written once (and counted once). */
    size_t dropped = 0;
    if (cs->nparts == 1 && out->n == 0) { /* one list: handed over as it is */
        vb_vertex_list_free(out);
        *out = cs->parts[0];
        vb_vertex_list_init(&cs->parts[0]);
    } else {
        rc = vb_vertex_list_merge(out, cs->parts, cs->nparts, &dropped);
    }
    vb_ctx_stats(ctx)->certified -= dropped + cs->dropped;
    drop_parts(cs);
    return rc == VB_OK ? VB_OK : vb_error(ctx, rc, NULL, 0, "out of memory (certified vertices)");
}

void *vbv_cert_stream_take_work(vbv_cert_stream *cs)
{
    void *w = cs->pw_state;
    cs->pw_state = NULL;
    return w;
}

void *vbv_cert_stream_free(vbv_cert_stream *cs)
{
    if (cs->started > 0) { /* after a failure: what is queued is dropped */
        pthread_mutex_lock(&cs->mu);
        cs->drop = 1;
        pthread_mutex_unlock(&cs->mu);
    }
    stream_wait(cs, 1);
    if (cs->co)
        vbv_cert_open_discard(cs->co);
    if (cs->pw_state) /* before the certifier its tracers work on */
        cs->pw->close(cs->pw_state);
    drop_parts(cs);
    free(cs->parts);
    for (size_t k = cs->qhead; k < cs->qn; k++)
        vb_quad_list_free(&cs->queue[k]);
    free(cs->queue);
    if (cs->started == -1) {
        pthread_mutex_destroy(&cs->mu);
        pthread_cond_destroy(&cs->cv);
    }
    vb_close(cs->tctx);
    void *cert = cs->cert;
    memset(cs, 0, sizeof *cs);
    return cert;
}
