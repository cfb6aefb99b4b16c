/* vb_psort (core/parallel.c): the same array as qsort for every thread count, on sizes
 * around the threshold where it starts using threads, with repeated keys
 * (ties broken by an index, as its callers do), and stable on equal
 * elements. */
#include <stdint.h>
#include <stdlib.h>

#include "vb_test.h"
#include "vb_parallel.h"

typedef struct item {
    uint32_t key, idx;
} item;

static int cmp_item(const void *pa, const void *pb)
{
    const item *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

/* Orders by key only: equal keys are equal elements. */
static int cmp_key(const void *pa, const void *pb)
{
    const item *a = pa, *b = pb;
    return (a->key > b->key) - (a->key < b->key);
}

static uint32_t next(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*s >> 33);
}

int main(void)
{
    const size_t sizes[] = {0, 1, 2, 100, 8191, 8192, 8193, 50000, 131071};
    const int threads[] = {1, 2, 3, 7, 16, 64, 100};
    uint64_t seed = 42;
    for (size_t si = 0; si < sizeof sizes / sizeof *sizes; si++) {
        size_t n = sizes[si];
        item *ref = malloc((n + 1) * sizeof *ref), *got = malloc((n + 1) * sizeof *got);
        for (size_t k = 0; k < n; k++)
            ref[k] = (item){next(&seed) % (uint32_t)(n / 4 + 1), (uint32_t)k};
        item *orig = malloc((n + 1) * sizeof *orig);
        memcpy(orig, ref, n * sizeof *ref);
        qsort(ref, n, sizeof *ref, cmp_item);
        for (size_t ti = 0; ti < sizeof threads / sizeof *threads; ti++) {
            memcpy(got, orig, n * sizeof *got);
            CHECK_INT(vb_psort(got, n, sizeof *got, cmp_item, threads[ti]), VB_OK);
            CHECK(memcmp(got, ref, n * sizeof *got) == 0);
            /* Key-only order: sorted by key, and equal keys keep their
             * input order (the idx of the input). */
            memcpy(got, orig, n * sizeof *got);
            CHECK_INT(vb_psort(got, n, sizeof *got, cmp_key, threads[ti]), VB_OK);
            size_t bad = 0;
            for (size_t k = 1; k < n; k++)
                bad += got[k - 1].key > got[k].key ||
                       (got[k - 1].key == got[k].key && got[k - 1].idx > got[k].idx);
            CHECK_INT(bad, 0);
        }
        free(ref);
        free(got);
        free(orig);
    }
    VB_TEST_END();
}
