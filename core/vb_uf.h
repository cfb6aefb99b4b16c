/* The union-find of the library (one for every room): disjoint sets of the
 * elements 0 .. n-1 (n < 2^32), each set named by its smallest element, so
 * that which set is whose never depends on the order of the unions (the
 * clusters of the matching, the components of arc closure are numbered
 * from it). Path halving; no ranks (the smallest-root rule stands in for
 * them, and the trees stay shallow in practice). */
#ifndef VB_UF_H
#define VB_UF_H

#include <stddef.h>
#include <stdint.h>

#include "vb.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_uf {
    uint32_t *p; /* parent of each element; a root is its own parent */
    size_t n;    /* elements */
    size_t cap;  /* allocated parents */
} vb_uf;

/* Makes the elements [0, n) exist: those beyond the current count start as
 * sets of their own; existing sets are kept. Returns VB_OK, or VB_ENOMEM
 * (also for n >= 2^32) with the sets unchanged. */
int vb_uf_fit(vb_uf *u, size_t n);

/* The root of element i (i < n): the smallest element of its set.
 * Halves the path on the way (the sets stay the same). */
static inline uint32_t vb_uf_root(vb_uf *u, uint32_t i)
{
    while (u->p[i] != i) {
        u->p[i] = u->p[u->p[i]];
        i = u->p[i];
    }
    return i;
}

/* Joins the sets of a and b (both < n): the larger root hangs below the
 * smaller. Returns the root of the joined set. */
static inline uint32_t vb_uf_join(vb_uf *u, uint32_t a, uint32_t b)
{
    a = vb_uf_root(u, a);
    b = vb_uf_root(u, b);
    if (a == b)
        return a;
    if (a < b) {
        u->p[b] = a;
        return a;
    }
    u->p[a] = b;
    return b;
}

/* The root of element i while other threads may join (vb_uf_join_shared):
 * parents read atomically, the path halved by compare-and-swap (a parent
 * only ever moves to an ancestor, a smaller element). */
static inline uint32_t vb_uf_root_shared(vb_uf *u, uint32_t i)
{
    for (;;) {
        uint32_t p = __atomic_load_n(&u->p[i], __ATOMIC_ACQUIRE);
        if (p == i)
            return i;
        uint32_t g = __atomic_load_n(&u->p[p], __ATOMIC_ACQUIRE);
        if (g != p)
            __atomic_compare_exchange_n(&u->p[i], &p, g, 0, __ATOMIC_RELEASE, __ATOMIC_RELAXED);
        i = g;
    }
}

/* vb_uf_join for threads that join at once (nothing but this and
 * vb_uf_root_shared on u until they are done): the larger root is hung
 * below the smaller only while it is still a root (compare-and-swap), else
 * the roots are found again. Once the threads are done the sets, each
 * named by its smallest element, are those of the same joins made one by
 * one in any order. */
static inline void vb_uf_join_shared(vb_uf *u, uint32_t a, uint32_t b)
{
    for (;;) {
        a = vb_uf_root_shared(u, a);
        b = vb_uf_root_shared(u, b);
        if (a == b)
            return;
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a, expect = hi;
        if (__atomic_compare_exchange_n(&u->p[hi], &expect, lo, 0, __ATOMIC_ACQ_REL,
                                        __ATOMIC_ACQUIRE))
            return;
    }
}

/* Frees the parents; the structure holds no element again. */
void vb_uf_free(vb_uf *u);

#ifdef __cplusplus
}
#endif

#endif
