/* The certifier's set-up beside the proposer, and certification part by
 * part beside the cover (vbv_certify.h). The vertices do not depend on how
 * the quadruples were cut into parts: the parts' sorted lists are merged
 * and a vertex certified in two parts written once. */
#include "vbv_certify.h"

#include <stdlib.h>
#include <string.h>

#include "vb_array.h"

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
    return vb_open_worker(&cs->tctx, owner) == VB_OK ? VB_OK : VB_ENOMEM;
}

static void *certify_part(void *arg)
{
    vbv_cert_stream *cs = arg;
    double t0 = vb_now();
    if (cs->co) {
        cs->cert = vbv_cert_open_join(cs->tctx, cs->co, &cs->rc);
        cs->co = NULL;
    }
    if (cs->rc == VB_OK)
        cs->rc = cs->ops->certify_quads(cs->tctx, cs->cert, (const uint32_t(*)[4])cs->cur.q,
                                        cs->cur.n, &cs->parts[cs->nparts - 1], NULL);
    cs->t_work += vb_now() - t0;
    return NULL;
}

static int stream_wait(vbv_cert_stream *cs)
{
    if (cs->busy)
        vb_jobs_join(&cs->job);
    cs->busy = 0;
    vb_quad_list_free(&cs->cur);
    return cs->rc;
}

int vbv_cert_stream_sink(void *user, vb_quad_list *part)
{
    vbv_cert_stream *cs = user;
    int rc = stream_wait(cs);
    if (rc != VB_OK)
        return rc;
    if (VB_ARRAY_FIT(cs->parts, cs->cap, cs->nparts + 1, 8) != VB_OK)
        return cs->rc = vb_error(cs->tctx, VB_ENOMEM, NULL, 0, "out of memory (certifier)");
    vb_vertex_list_init(&cs->parts[cs->nparts++]);
    cs->cur = *part;
    memset(part, 0, sizeof *part);
    vb_jobs_start(&cs->job, certify_part, cs, sizeof *cs, 1);
    cs->busy = 1;
    return VB_OK;
}

static void drop_parts(vbv_cert_stream *cs)
{
    for (size_t k = 0; k < cs->nparts; k++)
        vb_vertex_list_free(&cs->parts[k]);
    cs->nparts = 0;
}

void vbv_cert_stream_reset(vbv_cert_stream *cs)
{
    stream_wait(cs);
    drop_parts(cs);
}

int vbv_cert_stream_finish(vb_ctx *ctx, vbv_cert_stream *cs, vb_vertex_list *out)
{
    int rc = stream_wait(cs);
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
    rc = vb_vertex_list_merge(out, cs->parts, cs->nparts, &dropped);
    vb_ctx_stats(ctx)->certified -= dropped;
    drop_parts(cs);
    return rc == VB_OK ? VB_OK : vb_error(ctx, rc, NULL, 0, "out of memory (certified vertices)");
}

void *vbv_cert_stream_free(vbv_cert_stream *cs)
{
    stream_wait(cs);
    if (cs->co)
        vbv_cert_open_discard(cs->co);
    drop_parts(cs);
    free(cs->parts);
    vb_close(cs->tctx);
    void *cert = cs->cert;
    memset(cs, 0, sizeof *cs);
    return cert;
}
