/* The vertices of each triple of a vertex list, sorted (vbx_closure.h):
 * where the forward arc of a triple is first searched up to. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"

#include "vbx_closure.h"

static int tent_cmp(const void *pa, const void *pb)
{
    const vbx_tent *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

/* The entries of bucket i ([off[i], off[i + 1]): one first sphere) sorted:
 * insertion sort for the few of a protein's sphere, qsort beyond. */
typedef struct tbuckets {
    vbx_tent *e;
    const size_t *off;
} tbuckets;

static void sort_bucket(void *arg, size_t i, int tid)
{
    (void)tid;
    const tbuckets *b = arg;
    vbx_tent *e = b->e + b->off[i];
    size_t n = b->off[i + 1] - b->off[i];
    if (n > 32) {
        qsort(e, n, sizeof *e, tent_cmp);
        return;
    }
    for (size_t a = 1; a < n; a++) {
        vbx_tent x = e[a];
        size_t c = a;
        while (c > 0 && tent_cmp(&e[c - 1], &x) > 0) {
            e[c] = e[c - 1];
            c--;
        }
        e[c] = x;
    }
}

/* Sorts the n entries by tent_cmp: a counting pass by first sphere (in
 * entry order), then each sphere's bucket on its own, on nt threads.
 * tent_cmp is a total order, so the array is the one sorted array. VB_OK,
 * VB_ENOMEM (entries unchanged). */
static int sort_entries(vbx_tmap *m, unsigned nt)
{
    size_t n = m->n, top = 0;
    for (size_t i = 0; i < n; i++)
        if (m->e[i].t[0] >= top)
            top = (size_t)m->e[i].t[0] + 1;
    size_t *off = calloc(top + 1, sizeof *off);
    vbx_tent *out = malloc((n ? n : 1) * sizeof *out);
    if (!off || !out) {
        free(off);
        free(out);
        return VB_ENOMEM;
    }
    for (size_t i = 0; i < n; i++)
        off[m->e[i].t[0] + 1]++;
    for (size_t b = 0; b < top; b++)
        off[b + 1] += off[b];
    for (size_t i = 0; i < n; i++)
        out[off[m->e[i].t[0]]++] = m->e[i];
    for (size_t b = top; b > 0; b--)
        off[b] = off[b - 1];
    off[0] = 0;
    tbuckets tb = {out, off};
    vb_parallel_for(sort_bucket, &tb, top, (int)nt);
    free(m->off);
    m->off = off;
    m->noff = top;
    free(m->e);
    m->e = out;
    m->cap = n ? n : 1;
    return VB_OK;
}

int vbx_tmap_update(vbx_tmap *m, const vb_vertex_list *all, unsigned nt)
{
    for (size_t k = m->done; k < all->n; k++) {
        size_t s = all->start[k], nm = all->start[k + 1] - s;
        const uint32_t *id = all->ids + s;
        for (size_t a = 0; a < nm; a++)
            for (size_t b = a + 1; b < nm; b++)
                for (size_t c = b + 1; c < nm; c++) {
                    if (VB_ARRAY_FIT(m->e, m->cap, m->n + 1, 4096) != VB_OK) {
                        m->n = 0;
                        return VB_ENOMEM;
                    }
                    vbx_tent *e = &m->e[m->n++];
                    e->t[0] = id[a];
                    e->t[1] = id[b];
                    e->t[2] = id[c];
                    e->k = (uint32_t)k;
                }
    }
    m->done = all->n;
    if (sort_entries(m, nt) != VB_OK) {
        m->n = 0;
        return VB_ENOMEM;
    }
    return VB_OK;
}

size_t vbx_tmap_find(const vbx_tmap *m, const vb_vertex_list *all, const uint32_t t[3],
                     const uint32_t *ids, size_t nm, const double p[4])
{
    size_t lo, hi;
    vbx_tmap_range(m, t, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
        size_t k = m->e[i].k, s = all->start[k];
        if (all->start[k + 1] - s == nm && memcmp(all->ids + s, ids, nm * sizeof *ids) == 0 &&
            all->x[k] == p[0] && all->y[k] == p[1] && all->z[k] == p[2] && all->t[k] == p[3])
            return k;
    }
    return SIZE_MAX;
}

void vbx_tmap_range(const vbx_tmap *m, const uint32_t t[3], size_t *lo, size_t *hi)
{
    vbx_tent key = {{t[0], t[1], t[2]}, 0};
    size_t a = 0, b = m->n;
    if (m->off) {
        a = t[0] < m->noff ? m->off[t[0]] : m->n;
        b = t[0] < m->noff ? m->off[t[0] + 1] : m->n;
    }
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        if (tent_cmp(&m->e[mid], &key) < 0)
            a = mid + 1;
        else
            b = mid;
    }
    *lo = a;
    while (a < m->n && m->e[a].t[0] == t[0] && m->e[a].t[1] == t[1] && m->e[a].t[2] == t[2])
        a++;
    *hi = a;
}
