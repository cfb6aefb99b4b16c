/* JFA module: the exact search against brute force, every variant against the
 * exact diagram (zero error where they must agree, bounded otherwise; the
 * exact tiled variants label for label), Facet-JFA against the uncompacted
 * run it refines, and the OpenCL kernels (PoCL when no GPU) against the C
 * reference, bit for bit and count for count. */
#include <stdlib.h>
#include <string.h>

#include "vb_grid.h"
#include "vb_test.h"
#include "vbg_jfa.h"

/* Facet-JFA's uncompacted run last: random_seeds leaves it out. */
static const vbj_variant all_variants[] = {VBJ_JFA,   VBJ_JFA1,  VBJ_JFA2,           VBJ_1JFA,
                                           VBJ_FACET, VBJ_EXACT, VBJ_EXACT_BOUNDARY, VBJ_FACET_FULL};
#define NVAR 8

static size_t npix(const vbj_seeds *s) { return (size_t)s->n * s->n * (s->dim == 3 ? s->n : 1); }

/* Nearest seed by scanning every seed: the definition itself. */
static void brute(const vbj_seeds *s, uint32_t *out)
{
    for (size_t i = 0; i < npix(s); i++) {
        int32_t px = (int32_t)(i % s->n) * VBJ_FIX_ONE;
        int32_t py = (int32_t)((i / s->n) % s->n) * VBJ_FIX_ONE;
        int32_t pz = s->dim == 3 ? (int32_t)(i / ((size_t)s->n * s->n)) * VBJ_FIX_ONE : 0;
        uint32_t best = 0;
        uint64_t bd = UINT64_MAX;
        for (uint32_t v = 0; v < s->k; v++) {
            uint64_t d = vbj_dist2(px, py, pz, s->x[v], s->y[v], s->z[v]);
            if (vbj_better(d, v, bd, best)) {
                bd = d;
                best = v;
            }
        }
        out[i] = best;
    }
}

static int run(vb_ctx *ctx, vbj_backend *e, const vbj_seeds *s, vbj_variant v, vbj_result *r)
{
    vbj_options o = {v, 0, VBJ_WANT_LABELS, 0};
    int rc = vbj_run(ctx, e, s, &o, r);
    if (rc)
        fprintf(stderr, "vbj_run %s on %s: %s\n", vbj_variant_name(v),
                e->device, vb_errmsg(ctx));
    return rc;
}

static void two_seeds(vb_ctx *ctx, vbj_backend *e, int dim, uint32_t n)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_alloc(ctx, dim, n, 2, &s), VB_OK);
    CHECK_INT(vbj_seed_set(ctx, &s, 0, 0.3 * n, 0.37 * n, 0.41 * n), VB_OK);
    CHECK_INT(vbj_seed_set(ctx, &s, 1, 0.71 * n, 0.66 * n, 0.52 * n), VB_OK);
    uint32_t *ex = malloc(npix(&s) * 4);
    CHECK_INT(vbj_exact(ctx, e, &s, ex), VB_OK);
    for (int i = 0; i < NVAR; i++) {
        vbj_result r;
        if (run(ctx, e, &s, all_variants[i], &r)) {
            CHECK(0);
            continue;
        }
        vbj_metrics m;
        CHECK_INT(vbj_compare(ctx, &s, r.labels, ex, &m), VB_OK);
        CHECK_INT(m.wrong, 0);
        CHECK_INT(m.boundary_missed, 0);
        CHECK_INT(m.boundary_extra, 0);
        CHECK(m.boundary_exact > 0);
        vbj_result_free(&r);
    }
    free(ex);
    vbj_seeds_free(&s);
}

/* Random seeds (chosen so that no two share a pixel, which no JFA variant
 * can repair): exact == brute force; each variant's error bounded;
 * Facet-JFA from a given coarse m equals its uncompacted run and its unmarked
 * pixels are exactly the boundary pixels of its diagram. */
static void random_seeds(vb_ctx *ctx, vbj_backend *e, int dim, uint32_t n, size_t k,
                         vbj_distribution dist, uint64_t rng)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, dim, n, k, dist, rng, &s), VB_OK);
    size_t P = npix(&s);
    uint32_t *ex = malloc(P * 4), *bf = malloc(P * 4);
    uint8_t *bm = malloc(P);
    CHECK_INT(vbj_exact(ctx, e, &s, ex), VB_OK);
    brute(&s, bf);
    CHECK(memcmp(ex, bf, P * 4) == 0);
    for (int i = 0; i < NVAR - 1; i++) {
        vbj_result r;
        if (run(ctx, e, &s, all_variants[i], &r)) {
            CHECK(0);
            continue;
        }
        CHECK_INT(r.counts.collisions, 0);
        vbj_metrics m;
        CHECK_INT(vbj_compare(ctx, &s, r.labels, ex, &m), VB_OK);
        /* Rong & Tan report JFA errors well below 1% of the pixels, each a
         * fraction of the distance to the seed. */
        CHECK(m.wrong_rate < 0.01);
        CHECK(m.max_err < 0.1 * n);
        CHECK(m.wrong == 0 || m.max_err > 0);
        if (VBJ_IS_EXACT(all_variants[i])) {
            CHECK(memcmp(r.labels, ex, P * 4) == 0);
            CHECK_INT(m.differ, 0);
            CHECK_INT(r.counts.tiles, P >> (dim == 3 ? 9 : 8));
            CHECK(r.counts.survivors >= r.counts.tiles);
            CHECK(r.counts.candidates >= r.counts.survivors);
            CHECK_INT(r.counts.boundary,
                      all_variants[i] == VBJ_EXACT_BOUNDARY ? m.boundary_exact : 0);
        }
        vbj_result_free(&r);
    }
    vbj_result f, full;
    vbj_options o = {VBJ_FACET, n / 8, VBJ_WANT_LABELS, 0};
    CHECK_INT(vbj_run(ctx, e, &s, &o, &f), VB_OK);
    o.variant = VBJ_FACET_FULL;
    CHECK_INT(vbj_run(ctx, e, &s, &o, &full), VB_OK);
    if (f.labels && full.labels) {
        CHECK(memcmp(f.labels, full.labels, P * 4) == 0);
        CHECK_INT(f.counts.boundary, full.counts.boundary);
        CHECK_INT(f.counts.m, n / 8);
        CHECK(f.counts.step_pixels < full.counts.step_pixels);
        vbj_boundary_mask(dim, n, f.labels, bm);
        size_t nb = 0;
        for (size_t i = 0; i < P; i++)
            nb += bm[i];
        CHECK_INT(f.counts.boundary, nb);
    }
    vbj_result_free(&f);
    vbj_result_free(&full);
    free(ex);
    free(bf);
    free(bm);
    vbj_seeds_free(&s);
}

/* The exact engine's work counts: the twin and the kernel make the same
 * decisions (rings, bounds, dominance, float filter, fallbacks). */
static void exact_counts_agree(const vbj_counts *x, const vbj_counts *y)
{
    CHECK_INT(x->tiles, y->tiles);
    CHECK_INT(x->tiles_uniform, y->tiles_uniform);
    CHECK_INT(x->candidates, y->candidates);
    CHECK_INT(x->survivors, y->survivors);
    CHECK_INT(x->evals, y->evals);
    CHECK_INT(x->exact_voxels, y->exact_voxels);
    CHECK_INT(x->tiles_chunked, y->tiles_chunked);
    CHECK_INT(x->visited, y->visited);
}

/* The OpenCL kernels against the C reference: same labels, same counts. */
static void backends_agree(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl, int dim, uint32_t n,
                           size_t k, vbj_distribution dist)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, dim, n, k, dist, 777u, &s), VB_OK);
    size_t P = npix(&s);
    uint32_t *a = malloc(P * 4), *b = malloc(P * 4);
    CHECK_INT(vbj_exact(ctx, ref, &s, a), VB_OK);
    CHECK_INT(vbj_exact(ctx, cl, &s, b), VB_OK);
    CHECK(memcmp(a, b, P * 4) == 0);
    for (int i = 0; i < NVAR; i++) {
        vbj_result x, y;
        vbj_options o = {all_variants[i], 0, VBJ_WANT_LABELS | VBJ_WANT_NLABELS, 0};
        int rx = vbj_run(ctx, ref, &s, &o, &x), ry = vbj_run(ctx, cl, &s, &o, &y);
        CHECK_INT(rx, VB_OK);
        CHECK_INT(ry, VB_OK);
        if (rx || ry) {
            fprintf(stderr, "%s: %s\n", vbj_variant_name(all_variants[i]), vb_errmsg(ctx));
            continue;
        }
        CHECK(memcmp(x.labels, y.labels, P * 4) == 0);
        CHECK(memcmp(x.nlabels, y.nlabels, P) == 0);
        CHECK_INT(x.counts.step_pixels, y.counts.step_pixels);
        CHECK_INT(x.counts.boundary, y.counts.boundary);
        CHECK_INT(x.counts.steps, y.counts.steps);
        CHECK_INT(x.counts.m, y.counts.m);
        exact_counts_agree(&x.counts, &y.counts);
        vbj_result_free(&x);
        vbj_result_free(&y);
    }
    free(a);
    free(b);
    vbj_seeds_free(&s);
}

/* Seeds on a lattice of pitch 4 pixels at integer positions: every pixel
 * between two lattice points is equally far from both, so the labels test
 * the tie rule (lowest index) in every kernel. Seed i sits at lattice point
 * 37 i mod k (k a power of two, so a permutation): indices do not follow the
 * order in which kernels read neighbours, so the first seed offered is not
 * always the lowest. jitter (units of 2^-16 px) then moves seed i by
 * (i mod 3 - 1) jitter along x: the ties become near ties that only exact
 * arithmetic separates (the float filter's fallback). Returns the number of
 * seeds. */
static size_t lattice(vb_ctx *ctx, int dim, uint32_t n, int jitter, vbj_seeds *s)
{
    uint32_t m = n / 4, k = m * m * (dim == 3 ? m : 1);
    if (vbj_seeds_alloc(ctx, dim, n, k, s))
        return 0;
    for (uint32_t i = 0; i < k; i++) {
        uint32_t p = (uint32_t)(37u * i) % k;
        double dx = ((int)(i % 3) - 1) * jitter / 65536.0;
        vbj_seed_set(ctx, s, i, 4.0 * (p % m) + 1 + dx, 4.0 * ((p / m) % m) + 1,
                     dim == 3 ? 4.0 * (p / (m * m)) + 1 : 0);
    }
    return k;
}

/* Every variant (all), or JFA+1, Facet-JFA and exact only (for large
 * grids); the exact variant equals brute force (every tie and near tie to
 * the nearest, then lowest index), on both backends. */
static void ties(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl, int dim, uint32_t n, int all,
                 int jitter)
{
    static const vbj_variant some[] = {VBJ_JFA1, VBJ_FACET, VBJ_EXACT};
    vbj_seeds s;
    if (!lattice(ctx, dim, n, jitter, &s)) {
        CHECK(0);
        return;
    }
    /* Brute force on the small grids; the cell search (vbj_exact) on the
     * 2048^2 lattice, where brute force would take 10^12 distances. */
    uint32_t *bf = malloc(npix(&s) * 4);
    if (npix(&s) <= 65536)
        brute(&s, bf);
    else
        CHECK_INT(vbj_exact(ctx, ref, &s, bf), VB_OK);
    for (int i = 0; i < (all ? NVAR : 3); i++) {
        vbj_result x, y;
        vbj_options o = {all ? all_variants[i] : some[i], 0, VBJ_WANT_LABELS, 0};
        CHECK_INT(vbj_run(ctx, ref, &s, &o, &x), VB_OK);
        CHECK_INT(vbj_run(ctx, cl, &s, &o, &y), VB_OK);
        if (x.labels && y.labels)
            CHECK(memcmp(x.labels, y.labels, npix(&s) * 4) == 0);
        if (VBJ_IS_EXACT(o.variant) && y.labels) {
            CHECK(memcmp(y.labels, bf, npix(&s) * 4) == 0);
            CHECK(y.counts.exact_voxels > 0); /* the ties reached the integer fallback */
            exact_counts_agree(&x.counts, &y.counts);
        }
        vbj_result_free(&x);
        vbj_result_free(&y);
    }
    free(bf);
    vbj_seeds_free(&s);
}

/* Two cases that only the rule itself gets right (a mutant of it fails
 * here): at pixel (0, 0) of a 256^2 grid, seed 1 = (128, 1/16) px is nearer
 * than seed 0 = (128 + 2^-16, 0) px by one unit of 2^-32 px^2 in squared
 * distances of about 2^46 units, where floats see no difference (their ulp
 * there is 2^23: float distances would tie and give seed 0); seed 2 =
 * (1/16, 128) px is exactly as near as seed 1 (ties to the higher index
 * would give seed 2). Seed 3 keeps the rest of the grid busy. The exact
 * variants on either backend must say 1 there, and equal brute force
 * everywhere. */
static void rule_mutants(vb_ctx *ctx, vbj_backend *be)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_alloc(ctx, 2, 256, 4, &s), VB_OK);
    s.x[0] = 8388609; /* 128 px + 1 unit: D = 8388609^2 */
    s.y[0] = 0;
    s.x[1] = 8388608; /* D = 8388608^2 + 4096^2 = 8388609^2 - 1 */
    s.y[1] = 4096;
    s.x[2] = 4096; /* the same D as seed 1 */
    s.y[2] = 8388608;
    s.x[3] = 200 * VBJ_FIX_ONE;
    s.y[3] = 190 * VBJ_FIX_ONE;
    CHECK(vbj_dist2(0, 0, 0, s.x[1], s.y[1], 0) + 1 == vbj_dist2(0, 0, 0, s.x[0], s.y[0], 0));
    CHECK(vbj_dist2(0, 0, 0, s.x[1], s.y[1], 0) == vbj_dist2(0, 0, 0, s.x[2], s.y[2], 0));
    CHECK((float)vbj_dist2(0, 0, 0, s.x[0], s.y[0], 0) ==
          (float)vbj_dist2(0, 0, 0, s.x[1], s.y[1], 0));
    uint32_t *bf = malloc(npix(&s) * 4);
    brute(&s, bf);
    CHECK_INT(bf[0], 1);
    for (int v = VBJ_EXACT; v <= VBJ_EXACT_BOUNDARY; v++) {
        vbj_result r;
        if (run(ctx, be, &s, (vbj_variant)v, &r)) {
            CHECK(0);
            continue;
        }
        CHECK_INT(r.labels[0], 1);
        CHECK(memcmp(r.labels, bf, npix(&s) * 4) == 0);
        vbj_result_free(&r);
    }
    free(bf);
    vbj_seeds_free(&s);
}

/* A shell of seeds: near its centre every seed's bisector with the centre
 * owner crosses the tile, so tiles hold more survivors than one local-memory
 * stage (tiles_chunked); labels and counts as the reference's. */
static void chunked_tiles(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl, int dim, uint32_t n,
                          size_t k)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, dim, n, k, VBJ_DIST_SHELL, 4, &s), VB_OK);
    vbj_result x, y;
    vbj_options o = {VBJ_EXACT, 0, VBJ_WANT_LABELS, 0};
    CHECK_INT(vbj_run(ctx, ref, &s, &o, &x), VB_OK);
    CHECK_INT(vbj_run(ctx, cl, &s, &o, &y), VB_OK);
    if (x.labels && y.labels) {
        uint32_t *ex = malloc(npix(&s) * 4);
        CHECK_INT(vbj_exact(ctx, ref, &s, ex), VB_OK);
        CHECK(memcmp(x.labels, ex, npix(&s) * 4) == 0);
        CHECK(memcmp(y.labels, ex, npix(&s) * 4) == 0);
        CHECK(x.counts.tiles_chunked > 0);
        exact_counts_agree(&x.counts, &y.counts);
        free(ex);
    }
    vbj_result_free(&x);
    vbj_result_free(&y);
    vbj_seeds_free(&s);
}

/* 65535 seeds or more take the 32-bit label kernels on the device. */
static void wide_labels(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, 2, 512, 70000, VBJ_DIST_UNIFORM, 5, &s), VB_OK);
    vbj_result x, y;
    vbj_options o = {VBJ_JFA1, 0, VBJ_WANT_LABELS, 0};
    CHECK_INT(vbj_run(ctx, ref, &s, &o, &x), VB_OK);
    CHECK_INT(vbj_run(ctx, cl, &s, &o, &y), VB_OK);
    if (x.labels && y.labels)
        CHECK(memcmp(x.labels, y.labels, npix(&s) * 4) == 0);
    CHECK_INT(y.ms_fill, 0);
    vbj_result_free(&x);
    vbj_result_free(&y);
    vbj_seeds_free(&s);
}

/* Grids past the exact range of doubles (2D n > 1024) take the kernels with
 * 64-bit integer distances: the same labels as the reference there too. */
static void integer_distances(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, 2, 2048, 40, VBJ_DIST_CLUSTERED, 9, &s), VB_OK);
    static const vbj_variant vs[] = {VBJ_JFA1, VBJ_FACET, VBJ_EXACT};
    for (int i = 0; i < 3; i++) {
        vbj_result x, y;
        vbj_options o = {vs[i], 0, VBJ_WANT_LABELS, 0};
        CHECK_INT(vbj_run(ctx, ref, &s, &o, &x), VB_OK);
        CHECK_INT(vbj_run(ctx, cl, &s, &o, &y), VB_OK);
        if (x.labels && y.labels)
            CHECK(memcmp(x.labels, y.labels, npix(&s) * 4) == 0);
        /* Seeds hundreds of pixels from most tiles: the integer path. */
        if (vs[i] == VBJ_EXACT) {
            CHECK(y.counts.exact_voxels > 0);
            exact_counts_agree(&x.counts, &y.counts);
        }
        vbj_result_free(&x);
        vbj_result_free(&y);
    }
    vbj_seeds_free(&s);
}

/* Facet-JFA on OpenCL runs its small levels in one launch (fuse_cells):
 * with none, some (the rest a launch per phase) or all of the levels there,
 * labels and counts equal the reference's. k seeds, few enough that the
 * run starts coarse and doubles several times (the thresholds give the
 * test cases none, the coarse JFA only, or the first one or two doublings
 * too in one launch). */
static void fused_levels(vb_ctx *ctx, vbj_backend *ref, vbj_backend *cl, int dim, uint32_t n,
                         size_t k, vbj_distribution dist)
{
    static const uint32_t fuse[] = {VBJ_FUSE_NONE, 64, 512, 0, UINT32_MAX};
    static const vbj_variant vs[] = {VBJ_FACET, VBJ_FACET_FULL};
    vbj_seeds s;
    CHECK_INT(vbj_seeds_generate(ctx, dim, n, k, dist, 31u, &s), VB_OK);
    for (int v = 0; v < 2; v++) {
        vbj_result x;
        vbj_options o = {vs[v], 0, VBJ_WANT_LABELS, 0};
        if (vbj_run(ctx, ref, &s, &o, &x)) {
            CHECK(0);
            continue;
        }
        CHECK(x.counts.m <= n / 4); /* two doublings at least */
        for (int f = 0; f < 5; f++) {
            vbj_result y;
            o.fuse_cells = fuse[f];
            CHECK_INT(vbj_run(ctx, cl, &s, &o, &y), VB_OK);
            if (!y.labels)
                continue;
            CHECK(memcmp(x.labels, y.labels, npix(&s) * 4) == 0);
            CHECK_INT(x.counts.step_pixels, y.counts.step_pixels);
            CHECK_INT(x.counts.boundary, y.counts.boundary);
            CHECK_INT(x.counts.steps, y.counts.steps);
            vbj_result_free(&y);
        }
        vbj_result_free(&x);
    }
    vbj_seeds_free(&s);
}

static uint32_t start_of(vb_ctx *ctx, const vbj_seeds *s)
{
    uint32_t m = 0;
    CHECK_INT(vbj_start_resolution(ctx, s, &m), VB_OK);
    return m;
}

static void start_resolution(vb_ctx *ctx)
{
    vbj_seeds s;
    CHECK_INT(vbj_seeds_alloc(ctx, 2, 64, 2, &s), VB_OK);
    vbj_seed_set(ctx, &s, 0, 0, 0, 0);
    vbj_seed_set(ctx, &s, 1, 63, 63, 0);
    CHECK_INT(start_of(ctx, &s), 2);
    vbj_seed_set(ctx, &s, 1, 1, 0, 0); /* neighbouring pixels: only the fine grid separates */
    CHECK_INT(start_of(ctx, &s), 64);
    vbj_seed_set(ctx, &s, 1, 0.4, 0.2, 0); /* same pixel: no level separates them */
    CHECK_INT(start_of(ctx, &s), 64);
    vbj_seed_set(ctx, &s, 1, 8, 0, 0);
    CHECK_INT(start_of(ctx, &s), 8);
    vbj_seeds_free(&s);
    /* Out-of-grid coordinates are input errors. */
    CHECK_INT(vbj_seeds_alloc(ctx, 3, 32, 1, &s), VB_OK);
    CHECK_INT(vbj_seed_set(ctx, &s, 0, -0.6, 0, 0), VB_EINPUT);
    CHECK_INT(vbj_seed_set(ctx, &s, 0, 31.5, 0, 0), VB_EINPUT);
    CHECK_INT(vbj_seed_set(ctx, &s, 0, -0.5, 31.49, 0), VB_OK);
    vbj_seeds_free(&s);
    CHECK_INT(vbj_seeds_alloc(ctx, 2, 48, 1, &s), VB_EMISUSE);
}

int main(void)
{
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg))
        return 1;
    vbj_backend *ref = NULL, *cl = NULL;
    CHECK_INT(vbj_ref_open(ctx, &ref), VB_OK);
    start_resolution(ctx);
    two_seeds(ctx, ref, 2, 64);
    two_seeds(ctx, ref, 3, 16);
    random_seeds(ctx, ref, 2, 128, 60, VBJ_DIST_UNIFORM, 1);
    random_seeds(ctx, ref, 2, 128, 30, VBJ_DIST_SHELL, 2);
    random_seeds(ctx, ref, 2, 128, 40, VBJ_DIST_CLUSTERED, 3);
    random_seeds(ctx, ref, 3, 32, 30, VBJ_DIST_UNIFORM, 1);
    random_seeds(ctx, ref, 3, 32, 20, VBJ_DIST_SHELL, 2);
    rule_mutants(ctx, ref);
    vbg_runtime *rt = NULL;
    int have_device = vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt) == VB_OK;
    if (have_device && vbg_jfa_open(ctx, rt, &cl) == VB_OK) {
        printf("OpenCL device: %s\n", cl->device);
        two_seeds(ctx, cl, 2, 64);
        two_seeds(ctx, cl, 3, 16);
        backends_agree(ctx, ref, cl, 2, 64, 50, VBJ_DIST_UNIFORM);
        backends_agree(ctx, ref, cl, 2, 32, 300, VBJ_DIST_CLUSTERED);
        backends_agree(ctx, ref, cl, 3, 32, 40, VBJ_DIST_SHELL);
        backends_agree(ctx, ref, cl, 3, 16, 1, VBJ_DIST_UNIFORM);
        wide_labels(ctx, ref, cl);
        integer_distances(ctx, ref, cl);
        ties(ctx, ref, cl, 2, 64, 1, 0);
        ties(ctx, ref, cl, 3, 32, 1, 0);
        ties(ctx, ref, cl, 2, 2048, 0, 0);
        ties(ctx, ref, cl, 2, 64, 0, 1);
        ties(ctx, ref, cl, 3, 32, 0, 1);
        fused_levels(ctx, ref, cl, 2, 256, 12, VBJ_DIST_UNIFORM);
        fused_levels(ctx, ref, cl, 2, 512, 30, VBJ_DIST_UNIFORM);
        fused_levels(ctx, ref, cl, 3, 64, 10, VBJ_DIST_UNIFORM);
        rule_mutants(ctx, cl);
        chunked_tiles(ctx, ref, cl, 3, 64, 2000);
        chunked_tiles(ctx, ref, cl, 2, 256, 3000);
        vbj_backend_close(cl);
    } else {
        /* A device whose kernels do not build is a failure, not a skip. */
        CHECK(!have_device);
        printf("no OpenCL device: %s (reference backend only)\n", vb_errmsg(ctx));
    }
    vbg_runtime_close(rt);
    vbj_backend_close(ref);
    vb_close(ctx);
    VB_TEST_END();
}
