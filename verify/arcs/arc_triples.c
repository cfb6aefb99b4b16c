/* The vertices of each triple of a vertex list, sorted (vbx_closure.h):
 * where the forward arc of a triple is first searched up to. */
#include "vb_array.h"
#include "vb_parallel.h"

#include "vbx_closure.h"

static int tent_cmp(const void *pa, const void *pb)
{
    const vbx_tent *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

int vbx_tmap_update(vbx_tmap *m, const vb_vertex_list *all, unsigned nt)
{
    for (size_t k = m->done; k < all->n; k++) {
        size_t s = all->start[k], nm = all->start[k + 1] - s;
        const uint32_t *id = all->ids + s;
        for (size_t a = 0; a < nm; a++)
            for (size_t b = a + 1; b < nm; b++)
                for (size_t c = b + 1; c < nm; c++) {
                    if (VB_ARRAY_FIT(m->e, m->cap, m->n + 1, 4096) != VB_OK) {
                        m->n = 0;
                        return VB_ENOMEM;
                    }
                    vbx_tent *e = &m->e[m->n++];
                    e->t[0] = id[a];
                    e->t[1] = id[b];
                    e->t[2] = id[c];
                    e->k = (uint32_t)k;
                }
    }
    m->done = all->n;
    /* tent_cmp is a total order (the vertex breaks ties): the same array on
     * any number of threads */
    if (vb_psort(m->e, m->n, sizeof *m->e, tent_cmp, (int)nt) != VB_OK) {
        m->n = 0;
        return VB_ENOMEM;
    }
    return VB_OK;
}

void vbx_tmap_range(const vbx_tmap *m, const uint32_t t[3], size_t *lo, size_t *hi)
{
    vbx_tent key = {{t[0], t[1], t[2]}, 0};
    size_t a = 0, b = m->n;
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        if (tent_cmp(&m->e[mid], &key) < 0)
            a = mid + 1;
        else
            b = mid;
    }
    *lo = a;
    while (a < m->n && m->e[a].t[0] == t[0] && m->e[a].t[1] == t[1] && m->e[a].t[2] == t[2])
        a++;
    *hi = a;
}
