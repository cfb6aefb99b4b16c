/* The memo of a cell's tie-cluster answers (vbq_cluster.h). A near-tie that
 * the doubles cannot separate (a crystal jittered at 1e-12) keeps one list
 * of owned labels for many levels and in sibling patches, and each of them
 * asked the same exact question again: sc 1,000 at 1e-12 made 339,898
 * decisions for 1,003 cells, most of them in GMP.
 *
 * Why the key is complete. vbq_host_cluster's answer (decided, the rank and
 * the first independent labels) is computed by vbq_cluster_emin,
 * vbq_cluster_small and vbq_cluster_gmp from the sphere set's decimals, the
 * base i and the labels ids[0 .. n) in that order, and nothing else (no
 * arena, no patch, no double). The sphere set does not change while a cell
 * is covered, so (set, i, ids in order) is the whole key; the memo keeps one
 * cell's answers (set and i) and starts empty when another cell asks. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vbq_cluster.h"

typedef struct entry {
    uint64_t hash;
    size_t off;  /* its labels: ids[off .. off + n) */
    uint32_t n;
    vbq_cluster_ans a;
    size_t toff, nt; /* its hull triples: tri[3 toff .. 3 (toff + nt)) */
} entry;

struct vbq_cluster_memo {
    const void *set; /* whose cell the answers are (NULL: none yet) */
    uint32_t cell;
    vb_hash t;
    entry *e;
    size_t ne, ecap;
    uint32_t *ids;
    size_t nids, icap;
    uint32_t *tri;
    size_t ntri, tcap; /* in triples, and in uint32s */
};

/* What vb_hash's callbacks see: the memo and the key sought. */
typedef struct key {
    const vbq_cluster_memo *m;
    const uint32_t *ids;
    uint32_t n;
    uint64_t hash;
} key;

static int same(const void *kp, size_t item)
{
    const key *k = kp;
    const entry *x = &k->m->e[item];
    return x->hash == k->hash && x->n == k->n &&
           !memcmp(k->m->ids + x->off, k->ids, (size_t)k->n * sizeof *k->ids);
}

static uint64_t hash_of(const void *arg, size_t item)
{
    return ((const vbq_cluster_memo *)arg)->e[item].hash;
}

static uint64_t hash_ids(const uint32_t *ids, uint32_t n)
{
    uint64_t h = vb_hash_mix(0, n);
    for (uint32_t k = 0; k < n; k++)
        h = vb_hash_mix(h, ids[k]);
    return h;
}

vbq_cluster_memo *vbq_cluster_memo_new(void)
{
    return calloc(1, sizeof(vbq_cluster_memo));
}

void vbq_cluster_memo_free(vbq_cluster_memo *m)
{
    if (!m)
        return;
    vb_hash_free(&m->t);
    free(m->e);
    free(m->ids);
    free(m->tri);
    free(m);
}

/* Empties the memo for cell i of set (keeps its blocks). */
static void memo_for(vbq_cluster_memo *m, const void *set, uint32_t i)
{
    if (m->set == set && m->cell == i)
        return;
    vb_hash_clear(&m->t);
    m->ne = m->nids = m->ntri = 0;
    m->set = set;
    m->cell = i;
}

int vbq_cluster_memo_get(vbq_cluster_memo *m, const vb_sphere_set *s, uint32_t i,
                         const uint32_t *ids, uint32_t n, vbq_cluster_ans *a,
                         const uint32_t **tri, size_t *nt)
{
    memo_for(m, s, i);
    key k = {m, ids, n, hash_ids(ids, n)};
    size_t item = vb_hash_get(&m->t, k.hash, same, &k);
    if (item == SIZE_MAX)
        return 0;
    *a = m->e[item].a;
    *tri = m->tri + 3 * m->e[item].toff;
    *nt = m->e[item].nt;
    return 1;
}

void vbq_cluster_memo_put(vbq_cluster_memo *m, const vb_sphere_set *s, uint32_t i,
                          const uint32_t *ids, uint32_t n, const vbq_cluster_ans *a,
                          const uint32_t *tri, size_t nt)
{
    memo_for(m, s, i);
    key k = {m, ids, n, hash_ids(ids, n)};
    if (VB_ARRAY_FIT(m->e, m->ecap, m->ne + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(m->ids, m->icap, m->nids + n, 1024) != VB_OK ||
        VB_ARRAY_FIT(m->tri, m->tcap, 3 * (m->ntri + nt), 64) != VB_OK ||
        vb_hash_fit(&m->t, m->t.n + 1, hash_of, m) != VB_OK)
        return; /* not remembered: asked again, the same answer */
    size_t *slot = vb_hash_slot(&m->t, k.hash, same, &k);
    if (*slot)
        return;
    entry *x = &m->e[m->ne];
    x->hash = k.hash;
    x->off = m->nids;
    x->n = n;
    x->a = *a;
    memcpy(m->ids + m->nids, ids, (size_t)n * sizeof *ids);
    m->nids += n;
    x->toff = m->ntri;
    x->nt = nt;
    if (nt)
        memcpy(m->tri + 3 * m->ntri, tri, 3 * nt * sizeof *tri);
    m->ntri += nt;
    /* room was made above: the table stays at most half full */
    (void)vb_hash_put(&m->t, slot, m->ne++, hash_of, m);
}
