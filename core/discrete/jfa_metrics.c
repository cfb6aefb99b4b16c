/* Error figures of a discrete Voronoi diagram against the exact one, and the
 * neighbourhood classifications (boundary pixels, distinct-label counts). */
#include <math.h>
#include <string.h>

#include "vb_grid.h"
#include "vbj_jfa.h"

/* Writes the indices of pixel i's 3^d - 1 neighbours that lie inside the
 * grid; returns their number. */
static size_t neighbours(int dim, uint32_t n, size_t i, size_t out[26])
{
    uint32_t x = (uint32_t)(i % n), y = (uint32_t)((i / n) % n);
    uint32_t z = dim == 3 ? (uint32_t)(i / ((size_t)n * n)) : 0;
    size_t c = 0;
    int rz = dim == 3 ? 1 : 0;
    for (int dz = -rz; dz <= rz; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                if (!dx && !dy && !dz)
                    continue;
                int64_t nx = (int64_t)x + dx, ny = (int64_t)y + dy, nz = (int64_t)z + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= n || ny >= n ||
                    nz >= (dim == 3 ? (int64_t)n : 1))
                    continue;
                out[c++] = ((size_t)nz * n + (size_t)ny) * n + (size_t)nx;
            }
    return c;
}

void vbj_boundary_mask(int dim, uint32_t n, const uint32_t *labels, uint8_t *out)
{
    size_t total = (size_t)n * n * (dim == 3 ? n : 1), nb[26];
    for (size_t i = 0; i < total; i++) {
        size_t c = neighbours(dim, n, i, nb);
        uint8_t b = 0;
        for (size_t j = 0; j < c && !b; j++)
            b = labels[nb[j]] != labels[i];
        out[i] = b;
    }
}

uint64_t vbj_boundary_count(int dim, uint32_t n, const uint32_t *labels)
{
    size_t total = (size_t)n * n * (dim == 3 ? n : 1), nb[26];
    uint64_t count = 0;
    for (size_t i = 0; i < total; i++) {
        size_t c = neighbours(dim, n, i, nb);
        int b = 0;
        for (size_t j = 0; j < c && !b; j++)
            b = labels[nb[j]] != labels[i];
        count += (uint64_t)b;
    }
    return count;
}

void vbj_count_labels(int dim, uint32_t n, const uint32_t *labels, uint8_t *out)
{
    size_t total = (size_t)n * n * (dim == 3 ? n : 1), nb[26];
    for (size_t i = 0; i < total; i++) {
        size_t c = neighbours(dim, n, i, nb);
        uint32_t seen[27];
        int ns = 0;
        seen[ns++] = labels[i];
        for (size_t j = 0; j < c; j++) {
            uint32_t v = labels[nb[j]];
            int dup = 0;
            for (int t = 0; t < ns && !dup; t++)
                dup = seen[t] == v;
            if (!dup)
                seen[ns++] = v;
        }
        out[i] = (uint8_t)ns;
    }
}

int vbj_compare(vb_ctx *ctx, const vbj_seeds *s, const uint32_t *labels, const uint32_t *exact,
                vbj_metrics *out)
{
    memset(out, 0, sizeof *out);
    uint32_t n = s->n;
    size_t total = (size_t)n * n * (s->dim == 3 ? n : 1), nb[26];
    double sum = 0;
    for (size_t i = 0; i < total; i++) {
        uint32_t a = labels[i], e = exact[i];
        if (a >= s->k || e >= s->k)
            return vb_error(ctx, VB_EMISUSE, NULL, 0, "pixel %zu: label %u or %u out of range",
                            i, a, e);
        if (a != e) {
            out->differ++;
            int32_t px = (int32_t)(i % n) * VBJ_FIX_ONE, py = (int32_t)((i / n) % n) * VBJ_FIX_ONE;
            int32_t pz = s->dim == 3 ? (int32_t)(i / ((size_t)n * n)) * VBJ_FIX_ONE : 0;
            uint64_t da = vbj_dist2(px, py, pz, s->x[a], s->y[a], s->z[a]);
            uint64_t de = vbj_dist2(px, py, pz, s->x[e], s->y[e], s->z[e]);
            if (da > de) {
                out->wrong++;
                double err = (sqrt((double)da) - sqrt((double)de)) / VBJ_FIX_ONE;
                sum += err;
                out->max_err = err > out->max_err ? err : out->max_err;
            }
        }
        size_t c = neighbours(s->dim, n, i, nb);
        int bl = 0, be = 0;
        for (size_t j = 0; j < c; j++) {
            bl |= labels[nb[j]] != a;
            be |= exact[nb[j]] != e;
        }
        out->boundary_found += bl;
        out->boundary_exact += be;
        out->boundary_missed += be && !bl;
        out->boundary_extra += bl && !be;
    }
    out->pixels = total;
    out->wrong_rate = (double)out->wrong / (double)total;
    out->mean_err = sum / (double)total;
    return VB_OK;
}
