/* Host-side preprocessing shared by both JFA backends: step schedules, seed
 * placement, Facet-JFA's start resolution, the bucket grid of the exact
 * search, variant names. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbj_prep.h"

static const char *variant_names[VBJ_NVARIANTS] = {"jfa",   "jfa+1",      "jfa+2",
                                                   "1+jfa", "facet",      "facet-full",
                                                   "exact", "exact-boundary"};

int vbj_variant_parse(vb_ctx *ctx, const char *s, vbj_variant *out)
{
    for (int i = 0; i < VBJ_NVARIANTS; i++)
        if (strcmp(s, variant_names[i]) == 0) {
            *out = (vbj_variant)i;
            return VB_OK;
        }
    return vb_error(ctx, VB_EMISUSE, NULL, 0,
                    "unknown variant '%s' (jfa|jfa+1|jfa+2|1+jfa|facet|facet-full|exact|"
                    "exact-boundary)",
                    s);
}

const char *vbj_variant_name(vbj_variant v)
{
    return (unsigned)v < VBJ_NVARIANTS ? variant_names[v] : "?";
}

int vbj_schedule(vbj_variant v, uint32_t q, uint32_t *steps)
{
    int k = 0;
    if (v == VBJ_1JFA)
        steps[k++] = 1;
    for (uint32_t l = q / 2; l >= 1; l /= 2)
        steps[k++] = l;
    if (v == VBJ_JFA2 && q >= 4)
        steps[k++] = 2;
    if (v == VBJ_JFA1 || v == VBJ_JFA2)
        steps[k++] = 1;
    return k;
}

uint32_t vbj_log2u(uint32_t v)
{
    uint32_t r = 0;
    while (v > 1) {
        v >>= 1;
        r++;
    }
    return r;
}

typedef struct {
    uint64_t cell; /* linear cell index */
    uint64_t d2;   /* distance from the seed to the cell centre */
    uint32_t seed;
} placed;

static int cmp_placed(const void *a, const void *b)
{
    const placed *p = a, *q = b;
    if (p->cell != q->cell)
        return p->cell < q->cell ? -1 : 1;
    if (p->d2 != q->d2)
        return p->d2 < q->d2 ? -1 : 1;
    return p->seed < q->seed ? -1 : p->seed > q->seed;
}

int vbj_place(vb_ctx *ctx, const vbj_seeds *s, uint32_t f, uint32_t **pairs, size_t *count,
              uint32_t *collisions)
{
    uint32_t q = s->n / f, sh = vbj_log2u(f);
    placed *p = malloc(s->k * sizeof *p);
    if (!p)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed placement: out of memory");
    for (size_t i = 0; i < s->k; i++) {
        uint32_t cx = vbj_pixel_of(s->x[i]) >> sh, cy = vbj_pixel_of(s->y[i]) >> sh;
        uint32_t cz = s->dim == 3 ? vbj_pixel_of(s->z[i]) >> sh : 0;
        p[i].cell = ((uint64_t)cz * q + cy) * q + cx;
        p[i].d2 = vbj_dist2(vbj_cell_centre(cx, f), vbj_cell_centre(cy, f),
                            s->dim == 3 ? vbj_cell_centre(cz, f) : 0, s->x[i], s->y[i], s->z[i]);
        p[i].seed = (uint32_t)i;
    }
    qsort(p, s->k, sizeof *p, cmp_placed);
    uint32_t *out = malloc(2 * s->k * sizeof *out);
    if (!out) {
        free(p);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed placement: out of memory");
    }
    size_t c = 0;
    for (size_t i = 0; i < s->k; i++)
        if (i == 0 || p[i].cell != p[i - 1].cell) {
            out[2 * c] = (uint32_t)p[i].cell;
            out[2 * c + 1] = p[i].seed;
            c++;
        }
    free(p);
    *pairs = out;
    *count = c;
    *collisions = (uint32_t)(s->k - c);
    return VB_OK;
}

/* Interleaves the bits of the pixel coordinates (Morton order) so that the
 * coarsest level separating two seeds follows from their highest differing
 * bit. */
static uint64_t morton(const vbj_seeds *s, size_t i)
{
    uint32_t c[3] = {vbj_pixel_of(s->x[i]), vbj_pixel_of(s->y[i]),
                     s->dim == 3 ? vbj_pixel_of(s->z[i]) : 0};
    uint64_t key = 0;
    for (int b = 13; b >= 0; b--)
        for (int a = s->dim - 1; a >= 0; a--)
            key = (key << 1) | ((c[a] >> b) & 1u);
    return key;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

int vbj_start_resolution(vb_ctx *ctx, const vbj_seeds *s, uint32_t *m)
{
    uint32_t logn = vbj_log2u(s->n);
    if (s->k < 2) {
        *m = 1;
        return VB_OK;
    }
    uint64_t *keys = malloc(s->k * sizeof *keys);
    if (!keys)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "facet-jfa: out of memory (start resolution)");
    for (size_t i = 0; i < s->k; i++)
        keys[i] = morton(s, i);
    qsort(keys, s->k, sizeof *keys, cmp_u64);
    uint32_t need = 0; /* levels (bits per axis) needed to separate all seeds */
    for (size_t i = 1; i < s->k && need <= logn; i++) {
        uint64_t x = keys[i] ^ keys[i - 1];
        if (x == 0) {
            need = logn; /* two seeds share a fine pixel: no level separates them */
            break;
        }
        uint32_t h = 63 - (uint32_t)__builtin_clzll(x);
        uint32_t lvl = logn - h / (uint32_t)s->dim;
        need = lvl > need ? lvl : need;
    }
    free(keys);
    *m = 1u << (need > logn ? logn : need);
    return VB_OK;
}

int vbj_cells_build(vb_ctx *ctx, const vbj_seeds *s, vbj_cells *out)
{
    return vbj_cells_build_min(ctx, s, 0, out);
}

int vbj_cells_build_min(vb_ctx *ctx, const vbj_seeds *s, uint32_t min_shift, vbj_cells *out)
{
    memset(out, 0, sizeof *out);
    /* About one seed per bucket: side n / k^(1/d), a power of two. */
    double per_axis = s->dim == 3 ? cbrt((double)s->k) : sqrt((double)s->k);
    uint32_t shift = 0;
    while ((double)(s->n >> (shift + 1)) >= per_axis)
        shift++;
    if (shift < min_shift)
        shift = min_shift;
    uint32_t g = s->n >> shift;
    size_t nb = (size_t)g * g * (s->dim == 3 ? g : 1);
    out->shift = shift;
    out->g = g;
    out->start = calloc(nb + 1, sizeof *out->start);
    out->items = malloc(s->k * sizeof *out->items);
    if (!out->start || !out->items) {
        vbj_cells_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed buckets: out of memory");
    }
    uint32_t *bucket = malloc(s->k * sizeof *bucket);
    if (!bucket) {
        vbj_cells_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed buckets: out of memory");
    }
    for (size_t i = 0; i < s->k; i++) {
        uint32_t bx = vbj_pixel_of(s->x[i]) >> shift, by = vbj_pixel_of(s->y[i]) >> shift;
        uint32_t bz = s->dim == 3 ? vbj_pixel_of(s->z[i]) >> shift : 0;
        bucket[i] = (bz * g + by) * g + bx;
        out->start[bucket[i] + 1]++;
    }
    for (size_t b = 0; b < nb; b++)
        out->start[b + 1] += out->start[b];
    /* Counting sort keeps ascending seed order inside each bucket. */
    uint32_t *fill = malloc(nb * sizeof *fill);
    if (!fill) {
        free(bucket);
        vbj_cells_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed buckets: out of memory");
    }
    memcpy(fill, out->start, nb * sizeof *fill);
    for (size_t i = 0; i < s->k; i++)
        out->items[fill[bucket[i]]++] = (uint32_t)i;
    free(fill);
    free(bucket);
    return VB_OK;
}

void vbj_cells_free(vbj_cells *c)
{
    free(c->start);
    free(c->items);
    memset(c, 0, sizeof *c);
}
