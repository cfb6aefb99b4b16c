/* The exact certifier behind the certifier table of the vertex pipeline
 * (core/cells/vb_vertices.h): what verify/ gives the library's driver. */
#include <stdint.h>

#include "vb_verify.h"
#include "vb_vertices.h"

static int ops_open(vb_ctx *ctx, const vb_sphere_set *set, unsigned threads, void **out)
{
    vb_certifier *c = NULL;
    int rc = vb_certifier_open(ctx, set, &c);
    if (rc == VB_OK)
        vb_certifier_set_threads(c, threads);
    *out = c;
    return rc;
}

/* No distance limit: the exact solution nearest the candidate is what gets
 * certified, and far-away vertices (hull cells, nearly coplanar centres)
 * have candidates whose absolute error exceeds any tolerance. */
static int ops_list(vb_ctx *ctx, void *cert, const vb_vertex_list *cand, vb_vertex_list *ok,
                    vb_vertex_list *bad)
{
    return vb_certify_list(ctx, cert, cand, 0.0, ok, bad);
}

static int ops_intruder(vb_ctx *ctx, void *cert, const uint32_t ids[4], const double p[4],
                        uint32_t *intruder)
{
    vb_cert_result cr;
    int rc = vb_certify_candidate(ctx, cert, ids, 4, p, 0.0, &cr);
    *intruder = rc == VB_OK && cr.verdict == VB_CERT_INTRUDER ? cr.intruder : UINT32_MAX;
    return rc;
}

/* Every exact root of the proposer's quadruples (vb_certify_quads): the
 * roots that are not vertices are counted in the context's stats (rejected
 * quadruples), not listed. */
static int ops_quads(vb_ctx *ctx, void *cert, const uint32_t (*quads)[4], size_t n,
                     vb_vertex_list *certified, vb_vertex_list *rejected)
{
    (void)rejected;
    return vb_certify_quads(ctx, cert, quads, n, certified, NULL);
}

static int ops_quads_judged(vb_ctx *ctx, void *cert, const uint32_t (*quads)[4],
                            const uint8_t *verdict, size_t n, vb_vertex_list *certified)
{
    return vb_certify_quads_judged(ctx, cert, quads, verdict, n, certified, NULL);
}

static void ops_close(void *cert)
{
    vb_certifier_close(cert);
}

const vb_certifier_ops vb_exact_certifier = {"exact",   ops_open,  ops_list,        ops_intruder,
                                             ops_close, ops_quads, ops_quads_judged};
