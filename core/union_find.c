/* The union-find (vb_uf.h). */
#include <stdlib.h>

#include "vb_array.h"
#include "vb_uf.h"

int vb_uf_fit(vb_uf *u, size_t n)
{
    if (n <= u->n)
        return VB_OK;
    if (n > UINT32_MAX)
        return VB_ENOMEM;
    if (VB_ARRAY_FIT(u->p, u->cap, n, n) != VB_OK) /* a first fit: exactly n */
        return VB_ENOMEM;
    for (size_t i = u->n; i < n; i++)
        u->p[i] = (uint32_t)i;
    u->n = n;
    return VB_OK;
}

void vb_uf_free(vb_uf *u)
{
    free(u->p);
    u->p = NULL;
    u->n = 0;
    u->cap = 0;
}
