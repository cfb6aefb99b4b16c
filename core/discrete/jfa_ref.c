/* The plain-C backend of the JFA module: the same algorithms as the OpenCL
 * kernels with the same integer distance math, written for clarity (dense
 * arrays at every Facet-JFA level, no compaction) so that the kernels have an
 * independent reference to agree with bit for bit. */
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbj_prep.h"

typedef struct {
    int dim;
    uint32_t q, f; /* side of the level and fine pixels per cell */
    size_t cells;
} level;

static level make_level(const vbj_seeds *s, uint32_t q)
{
    level L = {s->dim, q, s->n / q, (size_t)q * q * (s->dim == 3 ? q : 1)};
    return L;
}

static void coords(const level *L, size_t i, uint32_t c[3])
{
    c[0] = (uint32_t)(i % L->q);
    c[1] = (uint32_t)((i / L->q) % L->q);
    c[2] = L->dim == 3 ? (uint32_t)(i / ((size_t)L->q * L->q)) : 0;
}

static size_t index_of(const level *L, const int64_t c[3])
{
    return ((size_t)c[2] * L->q + (size_t)c[1]) * L->q + (size_t)c[0];
}

/* Nearest seed among the cell's own label and those of its 3^d - 1
 * neighbours at distance l, read from src. */
static uint32_t best_around(const level *L, const vbj_seeds *s, const uint32_t *src, size_t i,
                            uint32_t l)
{
    uint32_t c[3];
    coords(L, i, c);
    int32_t p[3] = {vbj_cell_centre(c[0], L->f), vbj_cell_centre(c[1], L->f),
                    L->dim == 3 ? vbj_cell_centre(c[2], L->f) : 0};
    uint32_t best = VBJ_NONE;
    uint64_t bd = UINT64_MAX;
    int rz = L->dim == 3 ? 1 : 0;
    for (int dz = -rz; dz <= rz; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int64_t nc[3] = {(int64_t)c[0] + dx * (int64_t)l, (int64_t)c[1] + dy * (int64_t)l,
                                 (int64_t)c[2] + dz * (int64_t)l};
                if (nc[0] < 0 || nc[1] < 0 || nc[2] < 0 || nc[0] >= L->q || nc[1] >= L->q ||
                    nc[2] >= (L->dim == 3 ? L->q : 1))
                    continue;
                uint32_t v = src[index_of(L, nc)] & VBJ_LABEL_MASK;
                if (v == (VBJ_NONE & VBJ_LABEL_MASK))
                    continue;
                uint64_t d = vbj_dist2(p[0], p[1], p[2], s->x[v], s->y[v], s->z[v]);
                if (vbj_better(d, v, bd, best)) {
                    bd = d;
                    best = v;
                }
            }
    return best;
}

/* 1 when every neighbour (l = 1) carries the cell's label. */
static int all_same(const level *L, const uint32_t *lab, size_t i)
{
    uint32_t c[3];
    coords(L, i, c);
    uint32_t me = lab[i];
    int rz = L->dim == 3 ? 1 : 0;
    for (int dz = -rz; dz <= rz; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int64_t nc[3] = {(int64_t)c[0] + dx, (int64_t)c[1] + dy, (int64_t)c[2] + dz};
                if (nc[0] < 0 || nc[1] < 0 || nc[2] < 0 || nc[0] >= L->q || nc[1] >= L->q ||
                    nc[2] >= (L->dim == 3 ? L->q : 1))
                    continue;
                if (lab[index_of(L, nc)] != me)
                    return 0;
            }
    return 1;
}

/* Dense JFA on level L from the placed seeds; result in *lab (allocated). */
static int dense(vb_ctx *ctx, const vbj_seeds *s, const level *L, const uint32_t *steps,
                 int nsteps, vbj_counts *counts, uint32_t **lab)
{
    uint32_t *a = malloc(L->cells * sizeof *a), *b = malloc(L->cells * sizeof *b);
    uint32_t *pairs = NULL;
    size_t np = 0;
    uint32_t coll = 0;
    int rc = (!a || !b) ? vb_error(ctx, VB_ENOMEM, NULL, 0, "jfa: out of memory")
                        : vbj_place(ctx, s, L->f, &pairs, &np, &coll);
    if (rc) {
        free(a);
        free(b);
        return rc;
    }
    for (size_t i = 0; i < L->cells; i++)
        a[i] = VBJ_NONE;
    for (size_t i = 0; i < np; i++)
        a[pairs[2 * i]] = pairs[2 * i + 1];
    free(pairs);
    counts->collisions = coll;
    counts->threads += np;
    for (int t = 0; t < nsteps; t++) {
        for (size_t i = 0; i < L->cells; i++)
            b[i] = best_around(L, s, a, i, steps[t]);
        uint32_t *sw = a;
        a = b;
        b = sw;
        counts->steps++;
        counts->step_pixels += L->cells;
        counts->threads += L->cells;
    }
    free(b);
    *lab = a;
    return VB_OK;
}

/* Facet-JFA, Algorithm 1, one dense array per level. Marked cells keep their
 * label; their children inherit label and mark. */
static int facet(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *opt, vbj_result *out)
{
    uint32_t m = opt->m;
    int src = m ? VB_OK : vbj_start_resolution(ctx, s, &m);
    if (src != VB_OK)
        return src;
    uint32_t steps[40];
    level L = make_level(s, m);
    uint32_t *lab = NULL;
    int rc = dense(ctx, s, &L, steps, vbj_schedule(VBJ_JFA, m, steps), &out->counts, &lab);
    if (rc)
        return rc;
    out->counts.m = m;
    int compact = opt->variant == VBJ_FACET;
    uint8_t *mark = calloc(L.cells, 1);
    if (!mark) {
        free(lab);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "facet-jfa: out of memory");
    }
    for (uint32_t q = m;; q *= 2) {
        /* Marks at the last level tell the boundary; Facet-JFA also marks on
         * the way down, which is what lets it skip cells. */
        int do_mark = compact || q == s->n;
        if (do_mark) {
            uint8_t *nm = malloc(L.cells);
            if (!nm) {
                rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "facet-jfa: out of memory");
                break;
            }
            for (size_t i = 0; i < L.cells; i++) {
                nm[i] = mark[i];
                if (!mark[i] && (q > m || q == s->n)) {
                    out->counts.threads++;
                    nm[i] = (uint8_t)all_same(&L, lab, i);
                }
            }
            free(mark);
            mark = nm;
        }
        if (q == s->n)
            break;
        level F = make_level(s, 2 * q);
        uint32_t *fl = malloc(F.cells * sizeof *fl), *nl = malloc(F.cells * sizeof *nl);
        uint8_t *fm = malloc(F.cells);
        if (!fl || !nl || !fm) {
            free(fl);
            free(nl);
            free(fm);
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "facet-jfa: out of memory");
            break;
        }
        for (size_t i = 0; i < L.cells; i++)
            if (!mark[i])
                out->counts.threads++; /* refinement of an unmarked cell */
        for (size_t i = 0; i < F.cells; i++) {
            uint32_t c[3];
            coords(&F, i, c);
            int64_t pc[3] = {c[0] / 2, c[1] / 2, c[2] / 2};
            size_t pi = index_of(&L, pc);
            fl[i] = lab[pi];
            fm[i] = mark[pi];
        }
        for (size_t i = 0; i < F.cells; i++) {
            nl[i] = fl[i];
            if (!fm[i]) {
                nl[i] = best_around(&F, s, fl, i, 1);
                out->counts.step_pixels++;
                out->counts.threads++;
            }
        }
        out->counts.steps++;
        free(fl);
        free(lab);
        free(mark);
        lab = nl;
        mark = fm;
        L = F;
    }
    if (!rc) {
        for (size_t i = 0; i < L.cells; i++)
            out->counts.boundary += !mark[i];
        out->labels = lab;
        lab = NULL;
    }
    free(mark);
    free(lab);
    return rc;
}

/* The exact variants: the seed grid (host preparation, ms_transfer), the
 * tiles (ms_kernel) and for exact-boundary the boundary count. */
static int exact_tiles(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *opt, vbj_result *out)
{
    double t0 = 1e3 * vb_now();
    vbj_tiles_prep p;
    int rc = vbj_tiles_prep_build(ctx, s, &p);
    if (rc)
        return rc;
    double t1 = 1e3 * vb_now();
    rc = vbj_tiles_ref_run(ctx, s, &p, NULL, out);
    if (!rc && opt->variant == VBJ_EXACT_BOUNDARY)
        out->counts.boundary = vbj_boundary_count(s->dim, s->n, out->labels);
    out->ms_kernel = 1e3 * vb_now() - t1;
    out->ms_transfer = t1 - t0;
    out->ms_prep = t1 - t0;
    vbj_tiles_prep_free(&p);
    return rc;
}

int vbj_ref_exact_need(vb_ctx *ctx, const vbj_seeds *s, const uint8_t *need, vbj_result *out)
{
    memset(out, 0, sizeof *out);
    out->dim = s->dim;
    out->n = s->n;
    out->pixels = (size_t)s->n * s->n * (s->dim == 3 ? s->n : 1);
    vbj_tiles_prep p;
    int rc = vbj_tiles_prep_build(ctx, s, &p);
    if (rc)
        return rc;
    rc = vbj_tiles_ref_run(ctx, s, &p, need, out);
    vbj_tiles_prep_free(&p);
    if (rc)
        vbj_result_free(out);
    return rc;
}

int vbj_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *opt, vbj_result *out)
{
    if (VBJ_IS_EXACT(opt->variant))
        return exact_tiles(ctx, s, opt, out);
    double t0 = 1e3 * vb_now();
    int rc;
    if (opt->variant == VBJ_FACET || opt->variant == VBJ_FACET_FULL) {
        rc = facet(ctx, s, opt, out);
    } else {
        uint32_t steps[40];
        level L = make_level(s, s->n);
        rc = dense(ctx, s, &L, steps, vbj_schedule(opt->variant, s->n, steps), &out->counts,
                   &out->labels);
    }
    out->ms_kernel = 1e3 * vb_now() - t0;
    return rc;
}

int vbj_ref_exact(vb_ctx *ctx, const vbj_seeds *s, uint32_t *labels)
{
    vbj_cells c;
    int rc = vbj_cells_build(ctx, s, &c);
    if (rc)
        return rc;
    /* The seeds interleaved as the kernel reads them (x, y[, z], pad). */
    uint32_t stride = s->dim == 3 ? 4 : 2;
    int32_t *seeds = calloc(s->k * stride, sizeof *seeds);
    if (!seeds) {
        vbj_cells_free(&c);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory for %zu seeds", s->k);
    }
    for (size_t i = 0; i < s->k; i++) {
        seeds[stride * i] = s->x[i];
        seeds[stride * i + 1] = s->y[i];
        if (stride == 4)
            seeds[stride * i + 2] = s->z[i];
    }
    level L = make_level(s, s->n);
    for (size_t i = 0; i < L.cells; i++) {
        uint32_t px[3];
        coords(&L, i, px);
        labels[i] = vbj_exact_nearest(seeds, stride, c.start, c.items, (uint32_t)s->dim, c.shift,
                                      c.g, px[0], px[1], px[2]);
    }
    free(seeds);
    vbj_cells_free(&c);
    return VB_OK;
}
