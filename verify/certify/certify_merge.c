/* The merge of vb_certify_quads: certified roots in quadruple order ->
 * vertices, each once, in vb_vertex_list_sort's order. */
#include <stdlib.h>

#include "vbx_qties.h"

static int cmp_double(double a, double b)
{
    return (a > b) - (a < b);
}

/* The order of vb_vertex_list_sort: ids lexicographically (a prefix first),
 * then x, y, z, t. */
static int cmp_vref(const vbx_vref *a, const vbx_vref *b)
{
    size_t m = a->nm < b->nm ? a->nm : b->nm;
    for (size_t i = 0; i < m; i++)
        if (a->m[i] != b->m[i])
            return a->m[i] < b->m[i] ? -1 : 1;
    if (a->nm != b->nm)
        return a->nm < b->nm ? -1 : 1;
    for (int k = 0; k < 4; k++) {
        int c = cmp_double(a->xyzt[k], b->xyzt[k]);
        if (c)
            return c;
    }
    return 0;
}

static int cmp_vref_q(const void *pa, const void *pb)
{
    return cmp_vref(pa, pb);
}

static int push_ref(vb_vertex_list *out, const vbx_vref *v)
{
    return vb_vertex_list_push(out, v->m, v->nm, v->xyzt[0], v->xyzt[1], v->xyzt[2], v->xyzt[3],
                               0.0, VB_VERTEX_CERTIFIED);
}

/* Vertex k of a list as a reference (its t and x, y, z are not adjacent:
 * copied into buf). */
static vbx_vref ref_list(const vb_vertex_list *v, size_t k, double buf[4])
{
    buf[0] = v->x[k];
    buf[1] = v->y[k];
    buf[2] = v->z[k];
    buf[3] = v->t[k];
    vbx_vref r = {v->ids + v->start[k], v->start[k + 1] - v->start[k], buf, 0};
    return r;
}

int vbx_quads_merge(vb_ctx *ctx, vb_certifier *c, const vbx_vref *refs, size_t n,
                    vb_vertex_list *out, vb_cert_quad_stats *qs)
{
    vbx_vref *four = malloc((n ? n : 1) * sizeof *four);
    vbx_vref *more = malloc((n ? n : 1) * sizeof *more);
    size_t nfour = 0, nmore = 0;
    size_t *where = NULL, nwhere = 0; /* key -> 1 when written in this call, else SIZE_MAX */
    int rc = four && more ? VB_OK : VB_ENOMEM;
    for (size_t i = 0; i < n && rc == VB_OK; i++) {
        vbx_vref v = refs[i];
        if (v.nm == 4) {
            /* Quadruples are sorted, so these come in order but for the
             * two roots of one quadruple. */
            if (nfour && v.m == four[nfour - 1].m && cmp_vref(&v, &four[nfour - 1]) < 0) {
                four[nfour] = four[nfour - 1];
                four[nfour - 1] = v;
            } else {
                four[nfour] = v;
            }
            nfour++;
            continue;
        }
        size_t key;
        rc = vbx_cert_key_of(ctx, c, v.m, v.nm, v.sigma, &key);
        if (rc != VB_OK)
            break;
        rc = vbx_where_fit(&where, &nwhere, key);
        if (rc != VB_OK)
            break;
        if (where[key] != SIZE_MAX) {
            qs->duplicates++;
            continue;
        }
        where[key] = 1;
        more[nmore++] = v;
    }
    free(where);
    if (rc == VB_OK)
        qsort(more, nmore, sizeof *more, cmp_vref_q);
    size_t old = out->n, a = 0, b = 0;
    while (rc == VB_OK && (a < nfour || b < nmore)) {
        if (b == nmore || (a < nfour && cmp_vref(&four[a], &more[b]) <= 0))
            rc = push_ref(out, &four[a++]);
        else
            rc = push_ref(out, &more[b++]);
    }
    free(four);
    free(more);
    if (rc == VB_OK) {
        qs->vertices += out->n - old;
        vb_ctx_stats(ctx)->certified += out->n - old;
    }
    /* Appended after earlier vertices: sort only when they interleave. */
    if (rc == VB_OK && old > 0 && out->n > old) {
        double b1[4], b2[4];
        vbx_vref last = ref_list(out, old - 1, b1), first = ref_list(out, old, b2);
        if (cmp_vref(&last, &first) > 0)
            rc = vb_vertex_list_sort(out);
    }
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    return rc;
}
