/* Growable CSR list of vertices and its canonical order. */
#include "vb_array.h"
#include "vb_vertex.h"

#include <stdlib.h>
#include <string.h>

void vb_vertex_list_init(vb_vertex_list *v)
{
    memset(v, 0, sizeof *v);
}

void vb_vertex_list_free(vb_vertex_list *v)
{
    free(v->start);
    free(v->ids);
    free(v->x);
    free(v->y);
    free(v->z);
    free(v->t);
    free(v->dist);
    free(v->status);
    vb_vertex_list_init(v);
}

static int reserve_vertices(vb_vertex_list *v, size_t need)
{
    if (need <= v->cap && v->start)
        return VB_OK;
    size_t cap = vb_array_capacity(v->cap, need ? need : 1, 64);
    if (vb_array_resize((void **)&v->start, cap + 1, sizeof *v->start) ||
        vb_array_resize((void **)&v->x, cap, sizeof *v->x) ||
        vb_array_resize((void **)&v->y, cap, sizeof *v->y) ||
        vb_array_resize((void **)&v->z, cap, sizeof *v->z) ||
        vb_array_resize((void **)&v->t, cap, sizeof *v->t) ||
        vb_array_resize((void **)&v->dist, cap, sizeof *v->dist) ||
        vb_array_resize((void **)&v->status, cap, sizeof *v->status))
        return VB_ENOMEM;
    if (v->cap == 0)
        v->start[0] = 0;
    v->cap = cap;
    return VB_OK;
}

static int reserve_ids(vb_vertex_list *v, size_t need)
{
    return VB_ARRAY_FIT(v->ids, v->ids_cap, need, 256);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

int vb_vertex_list_push(vb_vertex_list *v, const uint32_t *ids, size_t nids, double x,
                        double y, double z, double t, double dist, int status)
{
    if (reserve_vertices(v, v->n + 1) || reserve_ids(v, v->nids + nids))
        return VB_ENOMEM;
    uint32_t *dst = v->ids + v->nids;
    memcpy(dst, ids, nids * sizeof *ids);
    /* Most callers pass sorted ids (certified vertices): no qsort then. */
    size_t sorted = 1;
    while (sorted < nids && dst[sorted - 1] <= dst[sorted])
        sorted++;
    if (sorted < nids)
        qsort(dst, nids, sizeof *dst, cmp_u32);
    size_t k = v->n;
    v->x[k] = x;
    v->y[k] = y;
    v->z[k] = z;
    v->t[k] = t;
    v->dist[k] = dist;
    v->status[k] = (uint8_t)status;
    v->nids += nids;
    v->n++;
    v->start[v->n] = v->nids;
    return VB_OK;
}

static int cmp_double(double a, double b)
{
    return (a > b) - (a < b);
}

/* C11 qsort has no user pointer; each key carries the list so the comparator
 * needs no global state. */
typedef struct {
    const vb_vertex_list *v;
    size_t k;
} sort_key;

/* The canonical order of entry a of list u and entry b of list v. */
static int cmp_entries(const vb_vertex_list *u, size_t a, const vb_vertex_list *v, size_t b)
{
    size_t na = u->start[a + 1] - u->start[a];
    size_t nb = v->start[b + 1] - v->start[b];
    const uint32_t *ia = u->ids + u->start[a], *ib = v->ids + v->start[b];
    size_t m = na < nb ? na : nb;
    for (size_t i = 0; i < m; i++)
        if (ia[i] != ib[i])
            return ia[i] < ib[i] ? -1 : 1;
    if (na != nb)
        return na < nb ? -1 : 1;
    int c;
    if ((c = cmp_double(u->x[a], v->x[b])) || (c = cmp_double(u->y[a], v->y[b])) ||
        (c = cmp_double(u->z[a], v->z[b])) || (c = cmp_double(u->t[a], v->t[b])))
        return c;
    return 0;
}

static int cmp_key(const void *pa, const void *pb)
{
    const sort_key *a = pa, *b = pb;
    int c = cmp_entries(a->v, a->k, b->v, b->k);
    return c ? c : (a->k > b->k) - (a->k < b->k);
}

static int push_entry(vb_vertex_list *out, const vb_vertex_list *v, size_t k)
{
    return vb_vertex_list_push(out, v->ids + v->start[k], v->start[k + 1] - v->start[k], v->x[k],
                               v->y[k], v->z[k], v->t[k], v->dist[k], v->status[k]);
}

int vb_vertex_list_sort(vb_vertex_list *v)
{
    return vb_vertex_list_sort_perm(v, NULL);
}

int vb_vertex_list_sort_perm(vb_vertex_list *v, size_t *where)
{
    if (where && v->n == 1)
        where[0] = 0;
    if (v->n < 2)
        return VB_OK;
    sort_key *keys = malloc(v->n * sizeof *keys);
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    if (!keys)
        return VB_ENOMEM;
    for (size_t k = 0; k < v->n; k++)
        keys[k] = (sort_key){v, k};
    qsort(keys, v->n, sizeof *keys, cmp_key);
    int rc = VB_OK;
    for (size_t i = 0; i < v->n && rc == VB_OK; i++) {
        size_t k = keys[i].k;
        if (where)
            where[k] = i;
        rc = push_entry(&out, v, k);
    }
    free(keys);
    if (rc != VB_OK) {
        vb_vertex_list_free(&out);
        return rc;
    }
    vb_vertex_list_free(v);
    *v = out;
    return VB_OK;
}

int vb_vertex_list_append(vb_vertex_list *dst, const vb_vertex_list *src)
{
    if (reserve_vertices(dst, dst->n + src->n) || reserve_ids(dst, dst->nids + src->nids))
        return VB_ENOMEM;
    if (!src->n)
        return VB_OK;
    /* A list's vertices hold their ids sorted (vb_vertex_list_push): the
     * arrays are copied as they are, the offsets moved. */
    size_t n = dst->n, s0 = src->start[0], nids = src->start[src->n] - s0;
    memcpy(dst->ids + dst->nids, src->ids + s0, nids * sizeof *dst->ids);
    for (size_t k = 0; k < src->n; k++)
        dst->start[n + k + 1] = dst->nids + (src->start[k + 1] - s0);
    memcpy(dst->x + n, src->x, src->n * sizeof *dst->x);
    memcpy(dst->y + n, src->y, src->n * sizeof *dst->y);
    memcpy(dst->z + n, src->z, src->n * sizeof *dst->z);
    memcpy(dst->t + n, src->t, src->n * sizeof *dst->t);
    memcpy(dst->dist + n, src->dist, src->n * sizeof *dst->dist);
    memcpy(dst->status + n, src->status, src->n * sizeof *dst->status);
    dst->n += src->n;
    dst->nids += nids;
    return VB_OK;
}

/* Same members, same rounded point and t: the same canonical vertex. */
static int same_vertex(const vb_vertex_list *v, size_t a, size_t b)
{
    size_t n = v->start[a + 1] - v->start[a];
    return n == v->start[b + 1] - v->start[b] &&
           memcmp(v->ids + v->start[a], v->ids + v->start[b], n * sizeof *v->ids) == 0 &&
           v->x[a] == v->x[b] && v->y[a] == v->y[b] && v->z[a] == v->z[b] && v->t[a] == v->t[b];
}

int vb_vertex_list_canonical(vb_vertex_list *v, size_t *dropped)
{
    if (vb_vertex_list_sort(v))
        return VB_ENOMEM;
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    size_t drop = 0;
    for (size_t k = 0; k < v->n; k++) {
        if (k > 0 && same_vertex(v, k, k - 1)) {
            drop++;
            continue;
        }
        if (vb_vertex_list_push(&out, v->ids + v->start[k], v->start[k + 1] - v->start[k], v->x[k],
                                v->y[k], v->z[k], v->t[k], v->dist[k], v->status[k])) {
            vb_vertex_list_free(&out);
            return VB_ENOMEM;
        }
    }
    vb_vertex_list_free(v);
    *v = out;
    if (dropped)
        *dropped = drop;
    return VB_OK;
}


int vb_vertex_list_merge(vb_vertex_list *out, const vb_vertex_list *parts, size_t nparts,
                         size_t *dropped)
{
    size_t pos[64] = {0}, n0 = out->n, drop = 0;
    if (dropped)
        *dropped = 0;
    if (nparts > 64)
        return VB_EMISUSE;
    for (;;) {
        size_t best = nparts;
        for (size_t p = 0; p < nparts; p++)
            if (pos[p] < parts[p].n &&
                (best == nparts || cmp_entries(&parts[p], pos[p], &parts[best], pos[best]) < 0))
                best = p;
        if (best == nparts)
            break;
        size_t k = pos[best]++;
        if (out->n > n0 && cmp_entries(out, out->n - 1, &parts[best], k) == 0) {
            drop++;
            continue;
        }
        if (push_entry(out, &parts[best], k) != VB_OK)
            return VB_ENOMEM;
    }
    if (dropped)
        *dropped = drop;
    return VB_OK;
}
