/* The vertex pipeline's certification stages (core/cells/cert_stream.c),
 * internal to the driver (vertices.c): the certifier's set-up on a thread
 * of its own while the proposer works, and the certification of a complete
 * proposer's quadruples part by part, overlapping the proposal of the
 * next part. */
#ifndef VBV_CERTIFY_H
#define VBV_CERTIFY_H

#include <pthread.h>

#include "vb_cover.h"
#include "vb_parallel.h"
#include "vb_vertices.h"

/* The repair rounds after certifying a sampling proposer's candidates:
 * each of res->rejected whose tangent sphere a sphere cuts (ops->intruder)
 * gives the quadruples with that intruder swapped in
 * (vb_sampler_swap_candidates), those not certified before are certified
 * with cert, and the new vertices merged into res->certified (canonical);
 * up to 4 rounds, res->repaired_candidates counting them. VB_OK, VB_ENOMEM
 * (message in ctx) or the certifier's error. */
int vbv_vertices_repair(vb_ctx *ctx, const vb_sphere_set *set, const vb_certifier_ops *ops,
                        void *cert, vb_vertices_result *res);

/* ops->certify_quads of list l, or ops->certify_quads_judged when l
 * carries the certification filter's verdicts and ops has it (the same
 * vertices either way). Its returns. */
int vbv_certify_quads(vb_ctx *ctx, const vb_certifier_ops *ops, void *cert,
                      const vb_quad_list *l, vb_vertex_list *certified, vb_vertex_list *rejected);

/* The set-up: ops->open on its own thread, with its own context. */
typedef struct vbv_cert_open {
    const vb_certifier_ops *ops;
    const vb_sphere_set *set;
    unsigned threads;
    vb_ctx *tctx;
    void *cert;
    int rc;
    vb_jobs job;
    int joined;
} vbv_cert_open;

/* Starts the set-up of ops's certifier for set (threads: its threads) on
 * a thread whose context reports through owner (vb_open_worker). */
void vbv_cert_open_start(vbv_cert_open *co, const vb_certifier_ops *ops, const vb_sphere_set *set,
                         unsigned threads, vb_ctx *owner);

/* Waits for the set-up: the certifier (the caller closes it), or NULL with
 * *rc the error, its message relayed to ctx. */
void *vbv_cert_open_join(vb_ctx *ctx, vbv_cert_open *co, int *rc);

/* Waits for the set-up and drops it with its messages (after a failed
 * proposal, whose error stands). */
void vbv_cert_open_discard(vbv_cert_open *co);

/* Certification of quadruples part by part: each part handed to
 * vbv_cert_stream_sink (a vb_cover_sink) is queued and returns at once; one
 * thread of the stream certifies the queued parts in turn
 * (ops->certify_quads, with the certifier's threads) while the proposer
 * goes on. Which part is certified when changes no vertex: the parts'
 * sorted lists are merged at the end (vb_vertex_list_merge). Memory holds
 * the queued parts' quadruples. */
typedef struct vbv_cert_stream {
    vbv_cert_open *co;       /* the set-up, joined by the stream's thread */
    const vb_certifier_ops *ops;
    void *cert;
    vb_ctx *tctx;            /* the certifying thread's messages and counters */
    int threads;             /* for sorting a part (vb_quad_list_canonical) */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    vb_quad_list *queue;     /* parts waiting, [qhead, qn) */
    size_t qhead, qn, qcap;
    vb_vertex_list *parts;   /* certified vertices, sorted lists (parts merged as they come) */
    size_t nparts, cap;
    size_t dropped;          /* repeats dropped when parts were merged early */
    vb_jobs job;
    int started;             /* 0: no lock yet, -1: no thread, 1: running, 2: runs when joined */
    int closing, busy, rc;
    int drop;                /* 1: the queued parts are dropped, not certified */
    size_t certified_parts;  /* parts certified */
    double t_work;           /* seconds the certifying thread worked */
    double t_busy_since;     /* when the part in work started */
    double t_overlap;        /* of t_work, seconds before vbv_cert_stream_finish */
    vb_ctx *owner;           /* the run's context */
    const vb_sphere_set *set; /* the certifier's */
    const vb_part_work *pw;  /* NULL, or work on each certified part (its thread) */
    void *pw_state;          /* ... opened at the first part */
    int in_pw;               /* the thread is in the part work (since pw_since) */
    int pw_done;             /* 1: the proposer returned, no part work starts */
    int pw_opened;           /* pw->open was called (pw_state may be NULL) */
    double pw_since, pw_last; /* ... and how long the last part's work took */
    double t_pw;             /* seconds of part work, all parts */
    double t_pw_overlap;     /* of t_pw, seconds before vbv_cert_stream_finish */
} vbv_cert_stream;

/* A stream over the set-up co (which it joins and whose certifier it
 * keeps), its thread's context reporting through owner (vb_open_worker).
 * VB_OK or VB_ENOMEM. */
int vbv_cert_stream_init(vbv_cert_stream *cs, vbv_cert_open *co, vb_ctx *owner);

/* vb_cover_sink: queues the part (its array taken) and returns; the
 * stream's thread starts with the first part. Returns the stream's first
 * error (message kept for vbv_cert_stream_finish), or VB_ENOMEM. */
int vbv_cert_stream_sink(void *user, vb_quad_list *part);

/* Waits until every queued part is certified and drops them all (the
 * certifier stays): the proposal starts over (a device failed). */
void vbv_cert_stream_reset(vbv_cert_stream *cs);

/* Notes the certifying thread's work so far as overlap (t_overlap; the
 * part work's, t_pw_overlap), starts no more part work, waits
 * for the queued parts, adds the thread's counters to ctx, and appends the
 * parts' vertices to out in canonical order (a merge). On an error its
 * message is relayed to ctx. VB_OK or the error. */
int vbv_cert_stream_finish(vb_ctx *ctx, vbv_cert_stream *cs, vb_vertex_list *out);

/* The part work's state (NULL: none), taken from the stream, which no
 * longer closes it; call after vbv_cert_stream_finish. */
void *vbv_cert_stream_take_work(vbv_cert_stream *cs);

/* Frees the stream (parts still queued are dropped, not certified) and
 * hands back its certifier (NULL if the set-up failed) for the caller to
 * close. */
void *vbv_cert_stream_free(vbv_cert_stream *cs);

#endif
