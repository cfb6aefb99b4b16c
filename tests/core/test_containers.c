/* The container set of core/ (vb_array.h, vb_hash.h, vb_uf.h): the growth
 * of the array (capacities, kept values, failure leaves it as it was), the
 * hash table against a brute-force search over 20,000 keys with collisions
 * forced by a weak hash (lookups, later equal items winning, growth), and
 * the union-find's roots (smallest element of each set) against sets
 * merged by relabelling, and the same joins made by four threads at once
 * (vb_uf_join_shared) giving the same roots. */
#include <stdint.h>
#include <stdlib.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vb_parallel.h"
#include "vb_test.h"
#include "vb_uf.h"

static void test_array(void)
{
    int *a = NULL;
    size_t cap = 0, n = 0, none = 0;
    CHECK_INT(VB_ARRAY_FIT(a, cap, none, 16), VB_OK);
    CHECK(a == NULL);
    CHECK_INT(cap, 0);
    CHECK_INT(VB_ARRAY_FIT(a, cap, 1, 16), VB_OK);
    CHECK_INT(cap, 16);
    for (int i = 0; i < 1000; i++) {
        if (VB_ARRAY_FIT(a, cap, n + 1, 16) != VB_OK)
            break;
        a[n++] = 3 * i;
    }
    CHECK_INT(n, 1000);
    CHECK_INT(cap, 1024); /* 16 doubled six times */
    int ok = 1;
    for (size_t i = 0; i < n; i++)
        ok &= a[i] == 3 * (int)i;
    CHECK(ok);
    /* a jump past twice the capacity doubles until it fits */
    CHECK_INT(VB_ARRAY_FIT(a, cap, 5000, 16), VB_OK);
    CHECK_INT(cap, 8192);
    CHECK_INT(a[999], 2997);
    /* a size beyond SIZE_MAX bytes fails and leaves the array as it was */
    int *keep = a;
    CHECK_INT(VB_ARRAY_FIT(a, cap, SIZE_MAX / 2, 16), VB_ENOMEM);
    CHECK(a == keep);
    CHECK_INT(cap, 8192);
    CHECK_INT(a[999], 2997);
    free(a);
    /* first 0 means 1 */
    double *d = NULL;
    size_t dc = 0;
    CHECK_INT(VB_ARRAY_FIT(d, dc, 1, 0), VB_OK);
    CHECK_INT(dc, 1);
    free(d);
}

/* Keys are (a, b) pairs in the caller's array; the weak hash (a mod 37)
 * makes long runs of collisions. */
typedef struct kv {
    uint32_t a, b;
} kv;

typedef struct keys {
    const kv *k;
} keys;

static const kv *g_items;

static int same_kv(const void *key, size_t item)
{
    const kv *q = key;
    return g_items[item].a == q->a && g_items[item].b == q->b;
}

static uint64_t weak(const kv *q)
{
    return q->a % 37;
}

static uint64_t hash_item(const void *arg, size_t item)
{
    const keys *k = arg;
    return weak(&k->k[item]);
}

static void test_hash(void)
{
    enum { N = 20000 };
    kv *it = malloc(N * sizeof *it);
    uint64_t s = 12345;
    for (size_t i = 0; i < N; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        it[i].a = (uint32_t)(s >> 40) % 3000; /* repeats: equal keys */
        it[i].b = (uint32_t)(s >> 20) % 3;
    }
    g_items = it;
    keys arg = {it};
    vb_hash t = {0};
    CHECK_INT(vb_hash_get(&t, 0, same_kv, &it[0]), SIZE_MAX);
    CHECK_INT(vb_hash_fit(&t, 0, hash_item, &arg), VB_OK);
    CHECK_INT(t.cap, 64);
    int ok = 1;
    size_t distinct = 0;
    for (size_t i = 0; i < N && ok; i++) {
        size_t *slot = vb_hash_slot(&t, weak(&it[i]), same_kv, &it[i]);
        distinct += *slot == 0;
        ok &= vb_hash_put(&t, slot, i, hash_item, &arg) == VB_OK;
        ok &= 2 * t.n < t.cap;
    }
    CHECK(ok);
    CHECK_INT(t.n, distinct);
    /* every key finds its last item (brute force) */
    size_t bad = 0;
    for (size_t i = 0; i < N; i++) {
        size_t last = SIZE_MAX;
        for (size_t j = 0; j < N; j++)
            if (it[j].a == it[i].a && it[j].b == it[i].b)
                last = j;
        bad += vb_hash_get(&t, weak(&it[i]), same_kv, &it[i]) != last;
    }
    CHECK_INT(bad, 0);
    kv absent = {3000, 0};
    CHECK_INT(vb_hash_get(&t, weak(&absent), same_kv, &absent), SIZE_MAX);
    /* fitting for fewer items keeps the table; for more, places them again */
    size_t cap = t.cap;
    CHECK_INT(vb_hash_fit(&t, 10, hash_item, &arg), VB_OK);
    CHECK_INT(t.cap, cap);
    CHECK_INT(vb_hash_fit(&t, 4 * cap, hash_item, &arg), VB_OK);
    CHECK(t.cap >= 8 * cap);
    bad = 0;
    for (size_t i = 0; i < N; i += 7)
        bad += !same_kv(&it[i], vb_hash_get(&t, weak(&it[i]), same_kv, &it[i]));
    CHECK_INT(bad, 0);
    CHECK(vb_hash_mix(0, 1) != vb_hash_mix(0, 2));
    CHECK(vb_hash_mix(1, 2) != vb_hash_mix(2, 1));
    /* cleared: no item found, the slots kept, usable again at once */
    size_t cap2 = t.cap;
    vb_hash_clear(&t);
    CHECK_INT(t.n, 0);
    CHECK_INT(t.cap, cap2);
    bad = 0;
    for (size_t i = 0; i < N; i += 7)
        bad += vb_hash_get(&t, weak(&it[i]), same_kv, &it[i]) != SIZE_MAX;
    CHECK_INT(bad, 0);
    size_t *s0 = vb_hash_slot(&t, weak(&it[0]), same_kv, &it[0]);
    CHECK_INT(*s0, 0);
    CHECK_INT(vb_hash_put(&t, s0, 0, hash_item, &arg), VB_OK);
    CHECK_INT(vb_hash_get(&t, weak(&it[0]), same_kv, &it[0]), 0);
    vb_hash_free(&t);
    CHECK_INT(t.cap, 0);
    free(it);
}

static void test_uf(void)
{
    enum { N = 3000 };
    vb_uf u = {0};
    CHECK_INT(vb_uf_fit(&u, N / 2), VB_OK);
    CHECK_INT(vb_uf_fit(&u, N), VB_OK); /* grows, new elements alone */
    CHECK_INT(vb_uf_fit(&u, 10), VB_OK); /* never shrinks */
    CHECK_INT(u.n, N);
    CHECK_INT(vb_uf_fit(&u, (size_t)UINT32_MAX + 1), VB_ENOMEM);
    CHECK_INT(u.n, N);
    uint32_t *label = malloc(N * sizeof *label);
    for (uint32_t i = 0; i < N; i++)
        label[i] = i;
    uint64_t s = 99;
    for (int r = 0; r < 2500; r++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        uint32_t a = (uint32_t)(s >> 33) % N, b = (uint32_t)(s >> 13) % N;
        uint32_t la = label[a], lb = label[b], lo = la < lb ? la : lb, hi = la < lb ? lb : la;
        for (uint32_t i = 0; i < N; i++)
            if (label[i] == hi)
                label[i] = lo;
        CHECK_INT(vb_uf_join(&u, a, b), lo);
    }
    /* each set's root is its smallest element: the relabelled sets' label */
    size_t bad = 0, roots = 0, sets = 0;
    for (uint32_t i = 0; i < N; i++) {
        bad += vb_uf_root(&u, i) != label[i];
        roots += vb_uf_root(&u, i) == i;
        sets += label[i] == i;
    }
    CHECK_INT(bad, 0);
    CHECK_INT(roots, sets);
    CHECK(sets > 1 && sets < N);
    /* a new element joins an old set below its root */
    CHECK_INT(vb_uf_fit(&u, N + 1), VB_OK);
    CHECK_INT(vb_uf_root(&u, N), N);
    CHECK_INT(vb_uf_join(&u, N, 0), label[0]);
    free(label);
    vb_uf_free(&u);
    CHECK_INT(u.n, 0);
}

/* Thread tid's share of the joins (every 4th pair from tid on). */
typedef struct shared_joins {
    vb_uf *u;
    const uint32_t (*pairs)[2];
    size_t n;
} shared_joins;

static void join_share(void *arg, size_t tid, int t)
{
    (void)t;
    const shared_joins *j = arg;
    for (size_t i = tid; i < j->n; i += 4)
        vb_uf_join_shared(j->u, j->pairs[i][0], j->pairs[i][1]);
}

static void test_uf_shared(void)
{
    enum { N = 20000, J = 15000 };
    uint32_t(*pairs)[2] = malloc(J * sizeof *pairs);
    uint64_t s = 7;
    for (size_t i = 0; i < J; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        pairs[i][0] = (uint32_t)(s >> 33) % N;
        pairs[i][1] = (uint32_t)(s >> 13) % N;
    }
    vb_uf one = {0}, four = {0};
    CHECK_INT(vb_uf_fit(&one, N), VB_OK);
    CHECK_INT(vb_uf_fit(&four, N), VB_OK);
    for (size_t i = 0; i < J; i++)
        vb_uf_join(&one, pairs[i][0], pairs[i][1]);
    shared_joins j = {&four, (const uint32_t(*)[2])pairs, J};
    vb_parallel_for(join_share, &j, 4, 4);
    size_t bad = 0, roots = 0;
    for (uint32_t i = 0; i < N; i++) {
        bad += vb_uf_root(&four, i) != vb_uf_root(&one, i);
        roots += four.p[i] == i;
    }
    CHECK_INT(bad, 0);
    CHECK(roots > 1 && roots < N);
    vb_uf_free(&one);
    vb_uf_free(&four);
    free(pairs);
}

int main(void)
{
    test_array();
    test_hash();
    test_uf();
    test_uf_shared();
    VB_TEST_END();
}
