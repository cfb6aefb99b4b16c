/* The cover's lists of quadruples (vb_cover.h): their order, a cell's run
 * made unique, appending, and the canonical form of a whole list. */
#include "vb_array.h"
#include "vb_cover.h"

#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"

/* The length of q's strictly increasing prefix (n: q is canonical). */
static size_t sorted_run(const uint32_t (*q)[4], size_t n)
{
    size_t k = 1;
    while (k < n && vb_quad_cmp(q[k - 1], q[k]) < 0)
        k++;
    return n ? k : 0;
}

/* Drops the repeats of sorted q; returns how many are left. */
static size_t drop_repeats(uint32_t (*q)[4], size_t n)
{
    size_t k = n ? 1 : 0;
    for (size_t a = 1; a < n; a++)
        if (vb_quad_cmp(q[a], q[k - 1]) != 0)
            memcpy(q[k++], q[a], sizeof *q);
    return k;
}

size_t vb_quad_cell_unique(uint32_t (*q)[4], size_t n)
{
    if (sorted_run((const uint32_t(*)[4])q, n) == n)
        return n;
    qsort(q, n, sizeof *q, vb_quad_cmp);
    return drop_repeats(q, n);
}

int vb_quad_list_append(vb_quad_list *l, const uint32_t *q, size_t n)
{
    if (n == 0)
        return VB_OK;
    if (VB_ARRAY_FIT(l->q, l->cap, l->n + n, 4096) != VB_OK)
        return VB_ENOMEM;
    memcpy(l->q + l->n, q, n * sizeof *l->q);
    l->n += n;
    return VB_OK;
}

int vb_quad_cmp(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    for (int k = 0; k < 4; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

void vb_quad_list_free(vb_quad_list *l)
{
    free(l->q);
    free(l->verdict);
    memset(l, 0, sizeof *l);
}

int vb_quad_list_canonical(vb_quad_list *l, int nt)
{
    if (sorted_run((const uint32_t(*)[4])l->q, l->n) == l->n)
        return VB_OK; /* a part the cover sorted already */
    int rc = vb_psort(l->q, l->n, sizeof *l->q, vb_quad_cmp, nt);
    if (rc == VB_OK)
        l->n = drop_repeats(l->q, l->n);
    return rc;
}

