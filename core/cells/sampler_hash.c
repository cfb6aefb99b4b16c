/* Uniform grid of sphere centres for radius queries (culling, tangent test). */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbs_internal.h"

/* Cells are sized for about two centres each so that the short queries of
 * the culling touch few empty cells; the grid has at most ~4n cells. */
int vbs_hash_build(vb_ctx *ctx, const vb_sphere_set *set, vbs_hash *g)
{
    memset(g, 0, sizeof *g);
    g->set = set;
    double hi[3];
    for (int a = 0; a < 3; a++) {
        const double *c = a == 0 ? set->x : a == 1 ? set->y : set->z;
        g->lo[a] = hi[a] = c[0];
        for (size_t i = 1; i < set->n; i++) {
            if (c[i] < g->lo[a])
                g->lo[a] = c[i];
            if (c[i] > hi[a])
                hi[a] = c[i];
        }
    }
    for (size_t i = 0; i < set->n; i++)
        if (set->r[i] > g->rmax)
            g->rmax = set->r[i];
    double vol = 1.0;
    for (int a = 0; a < 3; a++)
        vol *= (hi[a] - g->lo[a]) + g->rmax;
    g->h = cbrt(2.0 * vol / (double)set->n);
    if (!(g->h > 0.0))
        g->h = 1.0;
    size_t cells = 1;
    for (int a = 0; a < 3; a++) {
        double w = (hi[a] - g->lo[a]) / g->h;
        g->dim[a] = (int)(w > 1e6 ? 1e6 : w) + 1;
        cells *= (size_t)g->dim[a];
    }
    while (cells > 4 * set->n + 64) { /* flat or extreme sets: coarser cells */
        g->h *= 2.0;
        cells = 1;
        for (int a = 0; a < 3; a++) {
            g->dim[a] = (int)((hi[a] - g->lo[a]) / g->h) + 1;
            cells *= (size_t)g->dim[a];
        }
    }
    g->start = calloc(cells + 1, sizeof *g->start);
    g->idx = malloc(set->n * sizeof *g->idx);
    uint32_t *cellof = malloc(set->n * sizeof *cellof);
    if (!g->start || !g->idx || !cellof) {
        free(cellof);
        vbs_hash_free(g);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (sphere grid)");
    }
    for (size_t i = 0; i < set->n; i++) {
        const double p[3] = {set->x[i], set->y[i], set->z[i]};
        size_t k = 0;
        for (int a = 2; a >= 0; a--) {
            int c = (int)((p[a] - g->lo[a]) / g->h);
            if (c < 0)
                c = 0;
            if (c >= g->dim[a])
                c = g->dim[a] - 1;
            k = k * (size_t)g->dim[a] + (size_t)c;
        }
        cellof[i] = (uint32_t)k;
        g->start[k + 1]++;
    }
    for (size_t k = 0; k < cells; k++)
        g->start[k + 1] += g->start[k];
    uint32_t *fill = malloc((cells + 1) * sizeof *fill);
    if (!fill) {
        free(cellof);
        vbs_hash_free(g);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (sphere grid)");
    }
    memcpy(fill, g->start, (cells + 1) * sizeof *fill);
    for (size_t i = 0; i < set->n; i++)
        g->idx[fill[cellof[i]]++] = (uint32_t)i;
    free(fill);
    free(cellof);
    return VB_OK;
}

void vbs_hash_free(vbs_hash *g)
{
    free(g->start);
    free(g->idx);
    g->start = g->idx = NULL;
}

int vbs_hash_query(const vbs_hash *g, const double p[3], double radius, uint32_t **out,
                   size_t *n, size_t *cap)
{
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        double l = (p[a] - radius - g->lo[a]) / g->h, h = (p[a] + radius - g->lo[a]) / g->h;
        lo[a] = l < 0.0 ? 0 : l >= (double)g->dim[a] ? g->dim[a] : (int)l;
        hi[a] = h < 0.0 ? -1 : h >= (double)g->dim[a] ? g->dim[a] - 1 : (int)h;
    }
    const vb_sphere_set *s = g->set;
    double r2 = radius * radius;
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int x = lo[0]; x <= hi[0]; x++) {
                size_t k = ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0] +
                           (size_t)x;
                for (uint32_t q = g->start[k]; q < g->start[k + 1]; q++) {
                    uint32_t j = g->idx[q];
                    double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
                    if (dx * dx + dy * dy + dz * dz > r2)
                        continue;
                    if (VB_ARRAY_FIT(*out, *cap, *n + 1, 256) != VB_OK)
                        return VB_ENOMEM;
                    (*out)[(*n)++] = j;
                }
            }
    return VB_OK;
}
