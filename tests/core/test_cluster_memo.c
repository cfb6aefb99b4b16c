/* The memo of tie-cluster answers (core/cells/cluster_memo.c): a question
 * asked again (the same set, base and labels in the same order) gets the
 * answer computed the first time, and every other question, however close
 * (the labels in another order, one label fewer, another base, another
 * set), is computed afresh: each answer the memo gives is checked against
 * the rank test itself. */
#include <stdint.h>

#include "vb_test.h"
#include "vb_test_spheres.h"
#include "vbq_cluster.h"

static uint64_t rng = 0x2545f4914f6cdd1dull;

static uint32_t next(uint32_t n)
{
    vb_test_xorshift(&rng);
    return (uint32_t)(rng % n);
}

/* The rank test without a memo. */
static vbq_cluster_ans direct(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n)
{
    int32_t emin = vbq_cluster_emin(s, i, ids, n);
    vbq_cluster_ans a;
    if (!vbq_cluster_small(s, i, ids, n, emin, &a))
        vbq_cluster_gmp(s, i, ids, n, emin, &a);
    return a;
}

static int same_ans(const vbq_cluster_ans *a, const vbq_cluster_ans *b)
{
    if (a->decided != b->decided || a->nbasis != b->nbasis)
        return 0;
    for (int r = 0; r < a->nbasis && a->decided; r++)
        if (a->id[r] != b->id[r])
            return 0;
    return 1;
}

static int hits;

/* Asks the memo as vbq_host_cluster does; checks the answer. */
static void ask(vbq_cluster_memo *m, const vb_sphere_set *s, uint32_t i, const uint32_t *ids,
                uint32_t n)
{
    vbq_cluster_ans want = direct(s, i, ids, n), got;
    const uint32_t *tri;
    size_t nt;
    if (vbq_cluster_memo_get(m, s, i, ids, n, &got, &tri, &nt))
        hits++;
    else {
        got = want;
        vbq_cluster_memo_put(m, s, i, ids, n, &got, NULL, 0);
    }
    CHECK(same_ans(&got, &want));
}

/* Spheres 0 .. np-1 at the integer points of |p| = 11 (scaled by unit
 * thousandths, shifted), equal radii: every base's cluster is decided with
 * rank 3, and the basis is the first three independent labels in order;
 * with `jitter` one decimal of each centre moves by a thousandth, so the
 * same lists have rank 4. */
static vb_sphere_set *sphere_points(uint32_t *np, int jitter)
{
    vb_sphere_set *s = vb_test_spheres_alloc(200, 1);
    uint32_t m = 0;
    int64_t unit = 1000 + next(9000);
    for (int x = -11; x <= 11; x++)
        for (int y = -11; y <= 11; y++)
            for (int z = -11; z <= 11; z++)
                if (x * x + y * y + z * z == 121 && m < 200) {
                    s->ex[m] = (vb_decimal){x * unit + 10250 + (jitter ? next(3) : 0), -3};
                    s->ey[m] = (vb_decimal){y * unit - 3700, -3};
                    s->ez[m] = (vb_decimal){z * unit + 125, -3};
                    s->er[m] = (vb_decimal){1500, -3};
                    m++;
                }
    *np = m;
    return s;
}

int main(void)
{
    uint32_t ids[200], rev[200];
    for (int trial = 0; trial < 40; trial++) {
        uint32_t np, np2;
        vb_sphere_set *s = sphere_points(&np, 0), *t = sphere_points(&np2, 1);
        vbq_cluster_memo *m = vbq_cluster_memo_new();
        CHECK(m != NULL);
        hits = 0;
        for (int round = 0; round < 30; round++) {
            uint32_t i = next(2), n = 6 + next(20), k = 0;
            for (uint32_t j = 0; j < np && k < n; j++)
                if (j != i && next(3) == 0)
                    ids[k++] = j;
            n = k;
            for (uint32_t a = 0; a < n; a++)
                rev[a] = ids[n - 1 - a];
            ask(m, s, i, ids, n);
            ask(m, s, i, ids, n);     /* again: a hit */
            ask(m, s, i, rev, n);     /* other order: other first labels */
            ask(m, s, i, ids, n - 1); /* a prefix */
            ask(m, t, i, ids, n);     /* another set: rank 4 */
            ask(m, s, i, ids, n);     /* back: the memo started again */
            uint32_t i2 = i ^ 1u;     /* another base, where the labels allow */
            int has = 0;
            for (uint32_t a = 0; a < n; a++)
                has |= ids[a] == i2;
            if (!has)
                ask(m, s, i2, ids, n);
        }
        CHECK(hits >= 30); /* at least the repeats */
        vbq_cluster_memo_free(m);
        vb_spheres_free(s);
        vb_spheres_free(t);
    }
    VB_TEST_END();
}
