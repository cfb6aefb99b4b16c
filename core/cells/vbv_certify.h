/* The vertex pipeline's certification stages (core/cells/cert_stream.c),
 * internal to the driver (vertices.c): the certifier's set-up on a thread
 * of its own while the proposer works, and the certification of a complete
 * proposer's quadruples part by part, overlapping the proposal of the
 * next part. */
#ifndef VBV_CERTIFY_H
#define VBV_CERTIFY_H

#include "vb_cover.h"
#include "vb_parallel.h"
#include "vb_vertices.h"

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
 * vbv_cert_stream_sink (a vb_cover_sink) is certified (ops->certify_quads)
 * on a thread of its own while the proposer goes on; one part at a time is
 * in flight, so memory holds two parts of quadruples at most. */
typedef struct vbv_cert_stream {
    vbv_cert_open *co;       /* the set-up, joined by the first part */
    const vb_certifier_ops *ops;
    void *cert;
    vb_ctx *tctx;            /* the certifying thread's messages and counters */
    vb_quad_list cur;        /* the part in flight */
    vb_vertex_list *parts;   /* certified vertices, one sorted list per part */
    size_t nparts, cap;
    vb_jobs job;
    int busy, rc;
    double t_work;           /* seconds the certifying thread worked */
} vbv_cert_stream;

/* A stream over the set-up co (which it joins and whose certifier it
 * keeps), its thread's context reporting through owner (vb_open_worker).
 * VB_OK or VB_ENOMEM. */
int vbv_cert_stream_init(vbv_cert_stream *cs, vbv_cert_open *co, vb_ctx *owner);

/* vb_cover_sink: waits for the part in flight, then starts this one (its
 * array taken). Returns the stream's first error (message kept for
 * vbv_cert_stream_finish). */
int vbv_cert_stream_sink(void *user, vb_quad_list *part);

/* Waits for the part in flight and drops every certified part (the
 * certifier stays): the proposal starts over (a device failed). */
void vbv_cert_stream_reset(vbv_cert_stream *cs);

/* Waits for the last part, adds the thread's counters to ctx, and appends
 * the parts' vertices to out in canonical order (a merge). On an error its
 * message is relayed to ctx. VB_OK or the error. */
int vbv_cert_stream_finish(vb_ctx *ctx, vbv_cert_stream *cs, vb_vertex_list *out);

/* Frees the stream and hands back its certifier (NULL if the set-up
 * failed) for the caller to close. */
void *vbv_cert_stream_free(vbv_cert_stream *cs);

#endif
