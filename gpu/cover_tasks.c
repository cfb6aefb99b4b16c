/* Root-patch tasks of the direction cover (vbg_cover_tasks.h). */
#include "vbg_cover_tasks.h"

#include <stdlib.h>
#include <string.h>

size_t vbg_tasks_per_cell(uint32_t T, unsigned split)
{
    return (6u * (size_t)T * T) << (2u * (split == 1u ? 1u : 2u));
}

size_t vbg_tasks_make(const uint32_t *cells, const vbq_cell_out *out, size_t ncells,
                      vbg_task_pick pick, size_t per, unsigned split, uint32_t *cells2,
                      uint32_t *roots2)
{
    size_t j = 0;
    for (size_t c = 0; c < ncells; c++)
        if (pick(out[c].status))
            for (size_t r = 0; r < per; r++, j++) {
                cells2[j] = cells[c];
                roots2[j] = split == 1u ? VBQ_TASK((uint32_t)(r / 4), (uint32_t)(r % 4) + 1u)
                                        : VBQ_TASK2((uint32_t)(r / 16), (uint32_t)(r / 4 % 4) + 1u,
                                                    (uint32_t)(r % 4) + 1u);
            }
    return j;
}

size_t vbg_tasks_quads(const vbq_cell_out *t, size_t ntasks)
{
    size_t n = 0;
    for (size_t j = 0; j < ntasks; j++)
        if (t[j].status == VBQ_OK)
            n += t[j].nq;
    return n;
}

size_t vbg_tasks_join(const vbq_cell_out *t, vbq_cell_out *out, size_t ncells, vbg_task_pick pick,
                      size_t per, uint32_t *q, size_t *nq)
{
    size_t picked = 0;
    for (size_t c = 0; c < ncells; c++) {
        if (!pick(out[c].status))
            continue;
        const vbq_cell_out *tc = t + per * picked++;
        vbq_cell_out sum = tc[0];
        size_t n = 0;
        for (size_t r = 0; r < per; r++) {
            if (tc[r].status != VBQ_OK)
                sum.status = tc[r].status;
            n += tc[r].nq;
        }
        if (sum.status != VBQ_OK) {
            out[c].status = sum.status;
            continue;
        }
        sum.qoff = (uint32_t)*nq;
        sum.nq = (uint32_t)n;
        for (size_t r = 1; r < per; r++) {
            sum.nnb += tc[r].nnb;
            sum.far += tc[r].far;
            sum.patches += tc[r].patches;
            sum.evals_k += tc[r].evals_k;
            sum.leaves += tc[r].leaves;
            sum.deep += tc[r].deep;
            sum.maxlev = tc[r].maxlev > sum.maxlev ? tc[r].maxlev : sum.maxlev;
        }
        /* the sources lie below *nq, the copies from it on: no overlap */
        for (size_t r = 0; r < per; r++) {
            memcpy(q + 4 * *nq, q + 4 * (size_t)tc[r].qoff, 4 * (size_t)tc[r].nq * sizeof *q);
            *nq += tc[r].nq;
        }
        out[c] = sum;
    }
    return picked;
}

/* A picked cell's first-launch patches and index, for qsort. */
typedef struct task_key {
    uint32_t patches, c;
} task_key;

static int costlier_first(const void *a, const void *b)
{
    const task_key *x = a, *y = b;
    if (x->patches != y->patches)
        return x->patches > y->patches ? -1 : 1;
    return x->c < y->c ? -1 : x->c > y->c;
}

int vbg_tasks_ordered(int order, size_t np)
{
    return order == 2 || (order == 1 && np <= VBG_ORDER_CELLS);
}

size_t vbg_tasks_order(const vbq_cell_out *out, size_t ncells, vbg_task_pick pick,
                       uint32_t *order)
{
    size_t n = 0;
    for (size_t c = 0; c < ncells; c++)
        n += pick(out[c].status) != 0;
    task_key *k = malloc((n ? n : 1) * sizeof *k);
    if (!k)
        return SIZE_MAX;
    n = 0;
    for (size_t c = 0; c < ncells; c++)
        if (pick(out[c].status)) {
            k[n].patches = out[c].patches;
            k[n++].c = (uint32_t)c;
        }
    qsort(k, n, sizeof *k, costlier_first);
    for (size_t j = 0; j < n; j++)
        order[j] = k[j].c;
    free(k);
    return n;
}
