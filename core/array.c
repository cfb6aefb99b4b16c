/* The growable array (vb_array.h). */
#include <stdint.h>
#include <stdlib.h>

#include "vb_array.h"

void *vb_array_grow(void *arr, size_t *cap, size_t need, size_t elem, size_t first)
{
    if (need <= *cap)
        return arr;
    size_t c = *cap ? *cap : (first ? first : 1);
    if (*cap)
        c = c > SIZE_MAX / 2 ? SIZE_MAX : 2 * c;
    while (c < need)
        c = c > SIZE_MAX / 2 ? SIZE_MAX : 2 * c;
    if (elem && c > SIZE_MAX / elem)
        return arr;
    void *p = realloc(arr, c * elem);
    if (!p)
        return arr;
    *cap = c;
    return p;
}
