/* The hash table of the library (one for every room): a set of item
 * numbers whose keys live in the caller's arrays. Open addressing with
 * linear probing; each slot holds item + 1 (0 = empty); the capacity is a
 * power of two and the table at most half full, so a probe ends soon. The
 * caller gives the hash of a key and says whether an item is that key, so
 * one table serves keys of any shape (vertices by members and point, arcs
 * by vertex and triple). Which slot an item takes never shows in a result:
 * a lookup finds the one item equal to the key wherever it lies. */
#ifndef VB_HASH_H
#define VB_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "vb.h"

typedef struct vb_hash {
    size_t *slot; /* item + 1, 0 = empty */
    size_t cap;   /* slots, a power of two; 0 before the first vb_hash_fit */
    size_t n;     /* items entered */
} vb_hash;

/* same(key, item): 1 when the caller's item is the key sought, else 0. */
typedef int (*vb_hash_same_fn)(const void *key, size_t item);
/* hash_of(arg, item): the hash of an item entered (to place it again when
 * the table grows); the same value the caller gives vb_hash_slot for it. */
typedef uint64_t (*vb_hash_of_fn)(const void *arg, size_t item);

/* Mixes x into the running hash h (a step of a 64-bit hash over words). */
static inline uint64_t vb_hash_mix(uint64_t h, uint64_t x)
{
    h ^= x + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

/* The slot of a key whose hash is `hash`: the slot holding the item for
 * which same(key, item) is 1, or else the empty slot where the key goes
 * (*slot == 0; enter it with vb_hash_put). The table must have slots
 * (vb_hash_fit). Inline so that a constant `same` is inlined too. */
static inline size_t *vb_hash_slot(const vb_hash *t, uint64_t hash, vb_hash_same_fn same,
                                   const void *key)
{
    size_t i = (size_t)hash & (t->cap - 1);
    while (t->slot[i] && !same(key, t->slot[i] - 1))
        i = (i + 1) & (t->cap - 1);
    return &t->slot[i];
}

/* The item equal to the key, or SIZE_MAX when none is (also for a table
 * without slots). */
static inline size_t vb_hash_get(const vb_hash *t, uint64_t hash, vb_hash_same_fn same,
                                 const void *key)
{
    if (!t->cap)
        return SIZE_MAX;
    size_t s = *vb_hash_slot(t, hash, same, key);
    return s ? s - 1 : SIZE_MAX;
}

/* Gives the table room for n items (at least 2n slots, at least 64),
 * placing the items entered again (hash_of(arg, item)). Returns VB_OK, or
 * VB_ENOMEM with the table unchanged. Slot pointers of vb_hash_slot are
 * invalid after it. */
int vb_hash_fit(vb_hash *t, size_t n, vb_hash_of_fn hash_of, const void *arg);

/* Enters item at slot s (from vb_hash_slot on this table): an empty slot
 * takes it and counts one more item; a slot holding an item equal to the
 * key is given the new item (the later of equal items wins). Then grows
 * the table when it is more than half full. Returns VB_OK, or VB_ENOMEM
 * (the item is entered all the same; the table is fuller than half until a
 * later vb_hash_fit succeeds, and still correct while a slot is empty). */
int vb_hash_put(vb_hash *t, size_t *s, size_t item, vb_hash_of_fn hash_of, const void *arg);

/* Empties the table, keeping its slots (a table reused for another key
 * set: no vb_hash_fit needed for as many items as before). */
void vb_hash_clear(vb_hash *t);

/* Frees the slots; the table is empty again (usable after vb_hash_fit). */
void vb_hash_free(vb_hash *t);

#endif
