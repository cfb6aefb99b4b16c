/* Matching across cells (Sec. 5.4): candidates that lie within tol of each
 * other (point and tangent radius) are one vertex; its members are the union
 * of their ids, so a degenerate vertex seen as different quadruples from
 * different cells is one vertex, and it is complete when every member
 * produced a candidate from its own cell. Union-find over the candidates
 * sorted by x. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

typedef struct xkey {
    double x;
    uint32_t k;
} xkey;

static int cmp_x(const void *pa, const void *pb)
{
    const xkey *a = pa, *b = pb;
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

void vbs_clusters_free(vbs_clusters *m)
{
    vb_uf_free(&m->uf);
    free(m->order);
    free(m->cl_of);
    free(m->cl_start);
    free(m->cl_items);
    m->order = m->cl_of = m->cl_start = m->cl_items = NULL;
    m->ncl = 0;
}

int vbs_clusters_build(vbs_clusters *m, const vb_cand_vec *cv, int nthreads)
{
    size_t n = cv->n;
    vbs_clusters_free(m);
    m->order = malloc((n + 1) * sizeof *m->order);
    m->cl_of = malloc((n + 1) * sizeof *m->cl_of);
    m->cl_start = calloc(n + 2, sizeof *m->cl_start);
    m->cl_items = malloc((n + 1) * sizeof *m->cl_items);
    if (vb_uf_fit(&m->uf, n) != VB_OK || !m->order || !m->cl_of || !m->cl_start || !m->cl_items)
        return VB_ENOMEM;
    xkey *keys = malloc((n + 1) * sizeof *keys);
    if (!keys)
        return VB_ENOMEM;
    for (size_t k = 0; k < n; k++)
        keys[k] = (xkey){cv->v[k].x, (uint32_t)k};
    if (vb_psort(keys, n, sizeof *keys, cmp_x, nthreads) != VB_OK) {
        free(keys);
        return VB_ENOMEM;
    }
    for (size_t k = 0; k < n; k++)
        m->order[k] = keys[k].k;
    free(keys);
    double tol = m->tol;
    for (size_t a = 0; a < n; a++) {
        const vbs_cand *ca = cv->v + m->order[a];
        for (size_t b = a + 1; b < n; b++) {
            const vbs_cand *cb = cv->v + m->order[b];
            if (cb->x - ca->x > tol)
                break;
            double dy = cb->y - ca->y, dz = cb->z - ca->z, dt = cb->t - ca->t;
            if (fabs(dy) > tol || fabs(dz) > tol || fabs(dt) > tol)
                continue;
            vb_uf_join(&m->uf, m->order[a], m->order[b]);
        }
    }
    /* Number clusters by first candidate (roots are the smallest index). */
    size_t ncl = 0;
    for (size_t k = 0; k < n; k++) {
        uint32_t r = vb_uf_root(&m->uf, (uint32_t)k);
        m->cl_of[k] = r == k ? (uint32_t)ncl++ : m->cl_of[r];
    }
    for (size_t k = 0; k < n; k++)
        m->cl_start[m->cl_of[k] + 1]++;
    for (size_t c = 0; c < ncl; c++)
        m->cl_start[c + 1] += m->cl_start[c];
    uint32_t *fill = m->order; /* reuse */
    memcpy(fill, m->cl_start, ncl * sizeof *fill);
    for (size_t k = 0; k < n; k++)
        m->cl_items[fill[m->cl_of[k]]++] = (uint32_t)k;
    m->ncl = ncl;
    return VB_OK;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Sorts v and drops repeats; returns the new length. The lists are short
 * (4 ids per candidate of one cluster), so small ones are sorted by
 * insertion rather than through qsort's calls. */
static size_t uniq(uint32_t *v, size_t n)
{
    if (n <= 32) {
        for (size_t a = 1; a < n; a++) {
            uint32_t x = v[a];
            size_t b = a;
            while (b > 0 && v[b - 1] > x) {
                v[b] = v[b - 1];
                b--;
            }
            v[b] = x;
        }
    } else {
        qsort(v, n, sizeof *v, cmp_u32);
    }
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (m == 0 || v[m - 1] != v[k])
            v[m++] = v[k];
    return m;
}

size_t vbs_cluster_sets(const vbs_clusters *m, const vb_cand_vec *cv, size_t c, uint32_t *mem,
                           size_t *nmem, uint32_t *found)
{
    size_t nm = 0, nf = 0;
    for (uint32_t q = m->cl_start[c]; q < m->cl_start[c + 1]; q++) {
        const vbs_cand *k = cv->v + m->cl_items[q];
        for (int a = 0; a < 4; a++)
            mem[nm++] = k->ids[a];
        found[nf++] = k->ids[0];
    }
    *nmem = uniq(mem, nm);
    return uniq(found, nf);
}
