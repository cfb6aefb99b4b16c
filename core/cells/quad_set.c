/* The set of sorted quadruples already handled by the tangent phase and
 * the neighbourhood completion (vbs_match.h): partitioned into tables of
 * the library's hash (vb_hash.h), so bulk inserts run one table per thread
 * and still give the set and flags of inserting one by one. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbs_match.h"

static uint64_t qhash(const uint32_t q[4])
{
    uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < 4; k++)
        h = (h ^ q[k]) * 1099511628211ull;
    return h;
}

/* Table of a quadruple with hash h (the multiply leaves the top bits the
 * best mixed), and the hash its table places it by. */
static unsigned qpart(uint64_t h)
{
    return (unsigned)(h >> 58);
}

static uint64_t qslot_hash(uint64_t h)
{
    return h ^ (h >> 29);
}

/* A quadruple sought in table t (vb_hash's key). */
typedef struct qkey {
    const vbs_qtab *t;
    const uint32_t *q;
} qkey;

static int qsame(const void *key, size_t item)
{
    const qkey *k = key;
    return memcmp(k->t->keys[item], k->q, 4 * sizeof *k->q) == 0;
}

static uint64_t qhash_of(const void *arg, size_t item)
{
    const vbs_qtab *t = arg;
    return qslot_hash(qhash(t->keys[item]));
}

int vbs_qset_has(const vbs_qset *s, const uint32_t q[4])
{
    uint64_t hv = qhash(q);
    const vbs_qtab *t = &s->part[qpart(hv)];
    qkey k = {t, q};
    return vb_hash_get(&t->h, qslot_hash(hv), qsame, &k) != SIZE_MAX;
}

/* Inserts q, whose hash is hv, into its table t; returns 1 if new, 0 if
 * present, -1 on allocation failure. Touches no other table. */
static int qtab_add(vbs_qtab *t, uint64_t hv, const uint32_t q[4])
{
    if ((!t->h.cap && vb_hash_fit(&t->h, 1, qhash_of, t) != VB_OK) ||
        VB_ARRAY_FIT(t->keys, t->cap, t->n + 1, 256) != VB_OK)
        return -1;
    qkey k = {t, q};
    size_t *slot = vb_hash_slot(&t->h, qslot_hash(hv), qsame, &k);
    if (*slot)
        return 0;
    memcpy(t->keys[t->n], q, 4 * sizeof *q);
    t->n++;
    return vb_hash_put(&t->h, slot, t->n - 1, qhash_of, t) == VB_OK ? 1 : -1;
}

int vbs_qset_add(vbs_qset *s, const uint32_t q[4])
{
    uint64_t hv = qhash(q);
    return qtab_add(&s->part[qpart(hv)], hv, q);
}

void vbs_qset_free(vbs_qset *s)
{
    for (int p = 0; p < VBS_QPARTS; p++) {
        free(s->part[p].keys);
        vb_hash_free(&s->part[p].h);
    }
    memset(s, 0, sizeof *s);
}


/* Bulk insertion: the items of each table of the set in index order. */
typedef struct qbulk {
    vbs_qset *s;
    const uint32_t (*q)[4];
    const uint64_t *hash;
    const size_t *start;     /* VBS_QPARTS + 1 */
    const uint32_t *items;
    uint8_t *fresh;
    int err;
} qbulk;

static void qbulk_table(void *arg, size_t p, int tid)
{
    qbulk *b = arg;
    (void)tid;
    for (size_t j = b->start[p]; j < b->start[p + 1]; j++) {
        uint32_t k = b->items[j];
        int f = qtab_add(&b->s->part[p], b->hash[k], b->q[k]);
        if (f < 0) {
            b->err = VB_ENOMEM;
            return;
        }
        if (b->fresh)
            b->fresh[k] = (uint8_t)f;
    }
}

int vbs_qset_add_bulk(vbs_qset *s, const uint32_t (*q)[4], size_t n, const uint8_t *skip,
                         uint8_t *fresh, int nthreads)
{
    uint64_t *hash = malloc((n + 1) * sizeof *hash);
    uint32_t *items = malloc((n + 1) * sizeof *items);
    size_t start[VBS_QPARTS + 1] = {0}, fill[VBS_QPARTS];
    if (!hash || !items) {
        free(hash);
        free(items);
        return VB_ENOMEM;
    }
    for (size_t k = 0; k < n; k++) {
        if (fresh)
            fresh[k] = 0;
        if (skip && skip[k])
            continue;
        hash[k] = qhash(q[k]);
        start[qpart(hash[k]) + 1]++;
    }
    for (int p = 0; p < VBS_QPARTS; p++)
        start[p + 1] += start[p];
    memcpy(fill, start, sizeof fill);
    for (size_t k = 0; k < n; k++)
        if (!(skip && skip[k]))
            items[fill[qpart(hash[k])]++] = (uint32_t)k;
    qbulk b = {s, q, hash, start, items, fresh, VB_OK};
    vb_parallel_for(qbulk_table, &b, VBS_QPARTS, nthreads);
    free(hash);
    free(items);
    return b.err;
}
