/* The hash table (vb_hash.h). */
#include <stdlib.h>
#include <string.h>

#include "vb_hash.h"

int vb_hash_fit(vb_hash *t, size_t n, vb_hash_of_fn hash_of, const void *arg)
{
    size_t cap = t->cap ? t->cap : 64;
    while (cap < 2 * (n + 1)) {
        if (cap > SIZE_MAX / (4 * sizeof *t->slot))
            return VB_ENOMEM;
        cap *= 2;
    }
    if (cap == t->cap)
        return VB_OK;
    size_t *slot = calloc(cap, sizeof *slot);
    if (!slot)
        return VB_ENOMEM;
    for (size_t i = 0; i < t->cap; i++) {
        size_t s = t->slot[i];
        if (!s)
            continue;
        size_t j = (size_t)hash_of(arg, s - 1) & (cap - 1);
        while (slot[j])
            j = (j + 1) & (cap - 1);
        slot[j] = s;
    }
    free(t->slot);
    t->slot = slot;
    t->cap = cap;
    return VB_OK;
}

int vb_hash_put(vb_hash *t, size_t *s, size_t item, vb_hash_of_fn hash_of, const void *arg)
{
    if (!*s)
        t->n++;
    *s = item + 1;
    return 2 * (t->n + 1) > t->cap ? vb_hash_fit(t, t->n, hash_of, arg) : VB_OK;
}

void vb_hash_clear(vb_hash *t)
{
    if (t->n)
        memset(t->slot, 0, t->cap * sizeof *t->slot);
    t->n = 0;
}

void vb_hash_free(vb_hash *t)
{
    free(t->slot);
    t->slot = NULL;
    t->cap = 0;
    t->n = 0;
}
