/* The growable array (vb_array.h). */
#include <stdint.h>
#include <stdlib.h>

#include "vb_array.h"

size_t vb_array_capacity(size_t cap, size_t need, size_t first)
{
    if (need <= cap)
        return cap;
    size_t c = cap ? cap : (first ? first : 1);
    if (cap)
        c = c > SIZE_MAX / 2 ? SIZE_MAX : 2 * c;
    while (c < need)
        c = c > SIZE_MAX / 2 ? SIZE_MAX : 2 * c;
    return c;
}

int vb_array_resize(void **arr, size_t n, size_t elem)
{
    if (n == 0)
        return VB_OK;
    if (elem && n > SIZE_MAX / elem)
        return VB_ENOMEM;
    void *p = realloc(*arr, n * elem);
    if (!p)
        return VB_ENOMEM;
    *arr = p;
    return VB_OK;
}

void *vb_array_grow(void *arr, size_t *cap, size_t need, size_t elem, size_t first)
{
    if (need <= *cap)
        return arr;
    size_t c = vb_array_capacity(*cap, need, first);
    if (vb_array_resize(&arr, c, elem) != VB_OK)
        return arr;
    *cap = c;
    return arr;
}
