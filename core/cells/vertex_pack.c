/* Vertex lists as bytes for another process of the same build (vb_vertex.h):
 * the MPI ranks of `vorball vertices` send their certified parts to rank 0
 * this way. The layout is the list's own arrays, in the host's byte order:
 *
 *   "vbvlist1"  n (u64)  nids (u64)  start[n + 1] (u64)  ids[nids] (u32)
 *   x[n] y[n] z[n] t[n] dist[n] (double)  status[n] (u8)
 *
 * so a buffer's size follows from n and nids, and unpack checks it and the
 * offsets before it trusts anything. */
#include "vb_vertex.h"

#include <stdlib.h>
#include <string.h>

static const char magic[8] = {'v', 'b', 'v', 'l', 'i', 's', 't', '1'};

/* Bytes of a list of n vertices and nids ids; 0 when that overflows. */
static size_t packed_size(uint64_t n, uint64_t nids)
{
    const uint64_t big = (uint64_t)SIZE_MAX / 64;
    if (n >= big || nids >= big)
        return 0;
    return sizeof magic + 16 + 8 * (size_t)(n + 1) + 4 * (size_t)nids + 41 * (size_t)n;
}

static unsigned char *put(unsigned char *p, const void *src, size_t bytes)
{
    if (bytes)
        memcpy(p, src, bytes);
    return p + bytes;
}

int vb_vertex_list_pack(const vb_vertex_list *v, unsigned char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    uint64_t n = v->n, nids = v->nids;
    size_t size = packed_size(n, nids);
    unsigned char *b = size ? malloc(size) : NULL;
    if (!b)
        return VB_ENOMEM;
    unsigned char *p = put(b, magic, sizeof magic);
    p = put(p, &n, 8);
    p = put(p, &nids, 8);
    for (size_t k = 0; k <= v->n; k++) {
        uint64_t s = v->n ? v->start[k] : 0;
        p = put(p, &s, 8);
    }
    p = put(p, v->ids, 4 * v->nids);
    const double *cols[5] = {v->x, v->y, v->z, v->t, v->dist};
    for (int c = 0; c < 5; c++)
        p = put(p, cols[c], 8 * v->n);
    put(p, v->status, v->n);
    *buf = b;
    *len = size;
    return VB_OK;
}

static const unsigned char *get(const unsigned char *p, void *dst, size_t bytes)
{
    if (bytes)
        memcpy(dst, p, bytes);
    return p + bytes;
}

int vb_vertex_list_unpack(vb_ctx *ctx, const unsigned char *buf, size_t len, vb_vertex_list *v)
{
    uint64_t n = 0, nids = 0;
    if (len < sizeof magic + 16 || memcmp(buf, magic, sizeof magic) != 0)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "not a packed vertex list (%zu bytes)", len);
    const unsigned char *p = get(buf + sizeof magic, &n, 8);
    p = get(p, &nids, 8);
    if (packed_size(n, nids) != len)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0,
                        "packed vertex list of %zu bytes for %llu vertices, %llu ids", len,
                        (unsigned long long)n, (unsigned long long)nids);
    const unsigned char *start = p, *ids = start + 8 * (size_t)(n + 1);
    const unsigned char *cols = ids + 4 * (size_t)nids, *status = cols + 40 * (size_t)n;
    uint64_t prev = 0;
    for (size_t k = 0; k <= n; k++) {
        uint64_t s;
        get(start + 8 * k, &s, 8);
        /* Offsets rise from 0 to nids, at least 4 ids a vertex, as the
         * pipeline's vertices have; status is a vb_vertex_status. */
        if ((k == 0 && s != 0) || (k > 0 && s < prev + 4) || s > nids || (k == n && s != nids) ||
            (k < n && status[k] > VB_VERTEX_REJECTED))
            return vb_error(ctx, VB_EINTERNAL, NULL, 0, "packed vertex list: bad vertex %zu", k);
        prev = s;
    }
    uint32_t mid[64];
    for (size_t k = 0; k < n; k++) {
        uint64_t s0, s1;
        get(start + 8 * k, &s0, 8);
        get(start + 8 * (k + 1), &s1, 8);
        size_t m = (size_t)(s1 - s0);
        uint32_t *tmp = m <= 64 ? mid : malloc(m * sizeof *tmp);
        if (!tmp)
            return VB_ENOMEM;
        get(ids + 4 * (size_t)s0, tmp, 4 * m);
        double c[5];
        for (int j = 0; j < 5; j++)
            get(cols + 8 * ((size_t)j * (size_t)n + k), &c[j], 8);
        int rc = vb_vertex_list_push(v, tmp, m, c[0], c[1], c[2], c[3], c[4], status[k]);
        if (tmp != mid)
            free(tmp);
        if (rc != VB_OK)
            return rc;
    }
    return VB_OK;
}
