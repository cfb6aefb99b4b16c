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

/* Frees the parents; the structure holds no element again. */
void vb_uf_free(vb_uf *u);

#ifdef __cplusplus
}
#endif

#endif
