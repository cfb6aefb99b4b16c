/* The growable array of the library (one for every room): an array is a
 * pointer and a capacity in elements that the caller keeps beside its own
 * count. VB_ARRAY_FIT makes room, doubling the capacity from a first size,
 * so n appends cost O(n) copies; the elements already there keep their
 * values (realloc). */
#ifndef VB_ARRAY_H
#define VB_ARRAY_H

#include <stddef.h>

#include "vb.h"

/* Makes room for `need` elements in the array (arr, cap): arr an lvalue of
 * type T *, cap an lvalue of type size_t (its capacity in elements), first
 * the capacity of the first block (used when cap is 0). Evaluates to VB_OK,
 * or VB_ENOMEM with arr and cap unchanged (still valid: the caller frees
 * arr as before). arr and cap are evaluated more than once: pass plain
 * lvalues without side effects. */
#define VB_ARRAY_FIT(arr, cap, need, first)                                                    \
    ((size_t)(need) <= (cap)                                                                   \
         ? VB_OK                                                                               \
         : ((arr) = vb_array_grow((arr), &(cap), (size_t)(need), sizeof *(arr), (first)),      \
            (size_t)(need) <= (cap) ? VB_OK : VB_ENOMEM))

/* The growth behind VB_ARRAY_FIT: returns a block of at least `need`
 * elements of `elem` bytes that holds the *cap elements of arr (arr itself
 * when *cap >= need), and sets *cap to its capacity: first (at least 1) when
 * *cap is 0, else *cap doubled, doubled again until it holds need. On
 * failure (no memory, or a size beyond SIZE_MAX bytes) returns arr and
 * leaves *cap unchanged. */
void *vb_array_grow(void *arr, size_t *cap, size_t need, size_t elem, size_t first);

/* For a struct of arrays that share one capacity (vb_vertex_list, the
 * sphere builder): the capacity VB_ARRAY_FIT would choose for `need`
 * elements from cap (cap itself when it holds need; first, at least 1,
 * when cap is 0; else cap doubled until it holds need; SIZE_MAX at the
 * most). Allocates nothing. */
size_t vb_array_capacity(size_t cap, size_t need, size_t first);

/* Reallocates *arr to n elements of elem bytes (n = 0: left as it is).
 * VB_OK, or VB_ENOMEM with *arr unchanged (still valid) when there is no
 * memory or n * elem exceeds SIZE_MAX. */
int vb_array_resize(void **arr, size_t n, size_t elem);

#endif
