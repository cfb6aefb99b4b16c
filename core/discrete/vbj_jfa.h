/* Discrete Voronoi diagrams on [n]^d grids (d = 2, 3): the Jump Flooding
 * Algorithm and its variants, Facet-JFA (paper "facet-jfa-and-channels",
 * Sec. 2), the exact nearest-seed reference and the error figures.
 *
 * Backends (vbj_backend): OpenCL (gpu/jfa*.cl, gpu/facet_jfa.cl) or the
 * plain-C reference (core/discrete/jfa_ref.c). Both run the same algorithms
 * with the same exact integer distance math (core/discrete/vb_grid.h), so
 * they return identical labels.
 *
 * Typical use (channels):
 *   vbj_grid_fit fit;  vbj_seeds s;  vbj_result r;
 *   vbj_fit_grid(ctx, x, y, z, k, 256, 3.0, &fit);
 *   vbj_seeds_from_world(ctx, &fit, x, y, z, k, &s);
 *   vbj_backend_open(ctx, &vbg_device_layer, VB_DEVICE_AUTO, &dev, &e);
 *   vbj_options o = {0};  o.variant = VBJ_FACET;  o.want = VBJ_WANT_LABELS | VBJ_WANT_NLABELS;
 *   vbj_run(ctx, e, &s, &o, &r);      // r.labels[(z*n + y)*n + x], r.nlabels[...]
 *   ... vbj_result_free(&r); vbj_seeds_free(&s); vbj_backend_close(e);
 *   layer->close(dev); */
#ifndef VBJ_JFA_H
#define VBJ_JFA_H

#include <stddef.h>
#include <stdint.h>

#include "vb.h"
#include "vb_device.h"
#include "vbj_limits.h"

/* Algorithms. Steps l run n/2, n/4, ..., 1 (gather form: each pixel reads its
 * 3^d - 1 neighbours at distance l). */
typedef enum vbj_variant {
    VBJ_JFA = 0,   /* plain JFA */
    VBJ_JFA1,      /* JFA+1: one more step with l = 1 */
    VBJ_JFA2,      /* JFA+2: two more steps, l = 2 then 1 */
    VBJ_1JFA,      /* 1+JFA: one step with l = 1 first */
    VBJ_FACET,     /* Facet-JFA (Algorithm 1) with compaction of unmarked pixels */
    VBJ_FACET_FULL, /* Facet-JFA without skipping marked pixels (the run Facet-JFA
                       refines; for tests and counts) */
    VBJ_EXACT,      /* the exact diagram by tiles (vbj_tiles.h): per tile a provably
                       complete list of seeds from a seed grid, each voxel decided
                       exactly (float filter, 64-bit integer fallback) */
    VBJ_EXACT_BOUNDARY /* the same labels and, as Facet-JFA reports them, the
                          boundary pixels counted (counts.boundary) */
} vbj_variant;
#define VBJ_NVARIANTS 8

/* True for the two exact variants. */
#define VBJ_IS_EXACT(v) ((v) == VBJ_EXACT || (v) == VBJ_EXACT_BOUNDARY)

/* Parses "jfa|jfa+1|jfa+2|1+jfa|facet|facet-full|exact|exact-boundary".
 * VB_OK or VB_EMISUSE. */
int vbj_variant_parse(vb_ctx *ctx, const char *s, vbj_variant *out);
/* Static name of a variant ("jfa+1", ...). */
const char *vbj_variant_name(vbj_variant v);

/* Seeds in fixed-point grid coordinates (see vb_grid.h): pixel p has its
 * centre at p * VBJ_FIX_ONE; every coordinate lies in [-0.5, n - 0.5) pixels.
 * z is all zeros when dim == 2. Struct of arrays, owned (vbj_seeds_free). */
typedef struct vbj_seeds {
    int dim;        /* 2 or 3 */
    uint32_t n;     /* grid side: a power of two, 2 .. VBJ_MAX_N */
    size_t k;       /* number of seeds, 1 .. VBJ_MAX_SEEDS */
    int32_t *x, *y, *z;
} vbj_seeds;

/* Allocates k zeroed seeds for an [n]^dim grid. VB_EMISUSE for a bad dim, n
 * (not a power of two in 2..VBJ_MAX_N) or k; VB_ENOMEM. */
int vbj_seeds_alloc(vb_ctx *ctx, int dim, uint32_t n, size_t k, vbj_seeds *out);
void vbj_seeds_free(vbj_seeds *s);

/* Sets seed i from grid coordinates in pixels (rounded to 1/65536 px).
 * VB_EINPUT when a coordinate is not finite or outside [-0.5, n - 0.5). */
int vbj_seed_set(vb_ctx *ctx, vbj_seeds *s, size_t i, double gx, double gy, double gz);

/* Seed generators (deterministic for a given `seed`): */
typedef enum vbj_distribution {
    VBJ_DIST_UNIFORM = 0, /* uniform in the grid box */
    VBJ_DIST_CLUSTERED,   /* Gaussian clusters (about sqrt(k) of them) */
    VBJ_DIST_SHELL        /* on a sphere (circle in 2D) of radius 0.4 n: JFA's worst case */
} vbj_distribution;
int vbj_distribution_parse(vb_ctx *ctx, const char *s, vbj_distribution *out);
const char *vbj_distribution_name(vbj_distribution d);
/* Fills a new seed set with k seeds drawn from `dist`. Allocates *out. */
int vbj_seeds_generate(vb_ctx *ctx, int dim, uint32_t n, size_t k, vbj_distribution dist,
                       uint64_t seed, vbj_seeds *out);

/* Reads seeds from text: one seed per line, "x y" (2D) or "x y z" (3D) in grid
 * pixels, '#' comments. Allocates *out. VB_EINPUT_* with file:line. */
int vbj_seeds_read(vb_ctx *ctx, const char *path, int dim, uint32_t n, vbj_seeds *out);

/* Mapping between world coordinates (Angstrom) and a 3D grid:
 * grid = (world - origin) / pitch, pixel p with its centre AT p (the JFA
 * paper's convention, that of seed files and of vb_grid.h). The channel
 * grid (vbc_grid_fit) puts voxel i's centre at i + 0.5 instead, the
 * convention of its mask arithmetic (channel_math.h); both are kept because
 * each is what its kernels and outputs compute in, and vbc_frame_seeds
 * converts between them (minus half a voxel). */
typedef struct vbj_grid_fit {
    uint32_t n;
    double origin[3]; /* world position of pixel (0,0,0)'s centre */
    double pitch;     /* world length of one pixel */
} vbj_grid_fit;

/* Fits an [n]^3 grid around points (bounding box grown by `margin` world
 * units on every side, centred, cubic pixels) so every point lies inside the
 * pixel-centre box [0, n-1]^3. VB_EINPUT_EMPTY when k == 0. */
int vbj_fit_grid(vb_ctx *ctx, const double *x, const double *y, const double *z, size_t k,
                 uint32_t n, double margin, vbj_grid_fit *out);

/* Seeds (dim 3) at the world points mapped by `fit`. Allocates *out.
 * VB_EINPUT when a point falls outside the grid. */
int vbj_seeds_from_world(vb_ctx *ctx, const vbj_grid_fit *fit, const double *x, const double *y,
                         const double *z, size_t k, vbj_seeds *out);

/* What vbj_run returns besides timings and counts. */
enum {
    VBJ_WANT_LABELS = 1,  /* full label grid */
    VBJ_WANT_NLABELS = 2  /* per pixel, number of distinct labels among the pixel and
                             its 3^d - 1 neighbours: 1 interior, 2 on a Voronoi facet
                             (a boundary pixel, Definition 6), >= 3 near a Voronoi
                             edge (3D; a vertex in 2D), >= 4 near a vertex (3D) */
};

/* The numbers a `vorball jfa` run is set up with, as given (0 where not
 * given, except as noted). */
typedef struct vbj_setup {
    uint64_t dim;        /* 2 or 3 */
    uint64_t n;          /* grid side, <= VBJ_MAX_N (a power of two: vbj_seeds_* check it) */
    uint64_t k;          /* seeds generated, >= 1 */
    double margin;       /* world units around a protein's atoms, >= 0 */
    uint64_t m;          /* Facet-JFA start resolution: 0 (not given) or 1..VBJ_MAX_N */
    uint64_t fuse_cells; /* 0 (not given) or 1..UINT32_MAX (vbj_options.fuse_cells) */
    uint64_t repeat;     /* timed runs, 1..100000 */
    uint64_t rng;        /* generator seed (any) */
    uint32_t nslices;    /* 3D picture slices given, 0..VBJ_MAX_SLICES (0: n/2) */
    uint64_t slice[VBJ_MAX_SLICES]; /* each below n */
} vbj_setup;

/* The command's defaults: dim 2, n 512, k 100, margin 2, repeat 1, rng 1,
 * the rest 0 (not given). */
void vbj_setup_defaults(vbj_setup *s);

/* The setup's ranges, the one check of the command: VB_OK, or VB_EMISUSE
 * with ctx's message naming the first option refused, in the order of the
 * fields ("--dim must be 2 or 3", else "bad --size", "bad --seeds",
 * "bad --margin", "bad -m", "bad --fuse-cells", "bad --repeat",
 * "bad --slice": the caller adds the value as it was given). */
int vbj_setup_check(vb_ctx *ctx, const vbj_setup *s);

typedef struct vbj_options {
    vbj_variant variant;
    uint32_t m;    /* Facet-JFA start resolution; 0 = smallest without seed collisions */
    unsigned want; /* VBJ_WANT_* bits; 0 = labels only */
    uint32_t fuse_cells; /* Facet-JFA on OpenCL: the coarse JFA and the levels of at most
                            this many cells run in one launch (one work-group); 0 = the
                            default (VBJ_FUSE_CELLS_2D or _3D), VBJ_FUSE_NONE = a launch per
                            phase (as the paper). Labels and counts do not depend on it. */
} vbj_options;
/* Defaults of fuse_cells, the fastest on an H200 (papers/facet-jfa-and-channels/results/jfa/
 * kernels/h200_fuse/sweep.md). */
#define VBJ_FUSE_CELLS_2D 4096u
#define VBJ_FUSE_CELLS_3D 1024u
#define VBJ_FUSE_NONE 1u

/* Work done, as in the paper's supplement: a "pixel processed" is one
 * work-item running a JFA step on one pixel or cell. */
typedef struct vbj_counts {
    uint64_t step_pixels;    /* work-items of JFA steps (dense and l = 1 refinement steps) */
    uint64_t threads;        /* all work-items launched (steps, refine, mark, seeding) */
    uint32_t steps;          /* number of JFA steps (dense, and Facet-JFA's per doubling) */
    uint32_t m;              /* Facet-JFA: start resolution used (0 otherwise) */
    uint64_t boundary;       /* Facet-JFA: unmarked pixels at the end (= boundary pixels) */
    uint32_t collisions;     /* seeds that shared their start pixel with a nearer seed */
    /* The exact variants (0 for the others): */
    uint64_t tiles;          /* tiles of S^d voxels (S = 8 in 3D, 16 in 2D) */
    uint64_t tiles_uniform;  /* tiles filled without per-voxel work (one survivor) */
    uint64_t candidates;     /* seeds within the distance bound, summed over tiles */
    uint64_t survivors;      /* seeds left by the dominance test, summed over tiles */
    uint64_t evals;          /* voxel x survivor distances in float (the filter) */
    uint64_t exact_voxels;   /* voxels decided with 64-bit integers (near ties, far seeds) */
    uint64_t tiles_chunked;  /* tiles with more survivors than one local-memory stage */
    uint64_t visited;        /* seed records read by the searches of the tiles */
} vbj_counts;

typedef struct vbj_result {
    int dim;
    uint32_t n;
    size_t pixels;       /* n^dim */
    uint32_t *labels;    /* pixels entries, seed index (VBJ_NONE never remains); NULL unless wanted */
    uint8_t *nlabels;    /* pixels entries (see VBJ_WANT_NLABELS); NULL unless wanted */
    vbj_counts counts;
    double ms_kernel;    /* device time of the algorithm: seeding, steps, refinement,
                            marking (wall clock between queue drains); excludes uploads,
                            downloads and making the full 32-bit label grid */
    double ms_fill;      /* after the algorithm, making the full 32-bit label grid:
                            Facet-JFA's pass that drops the marks; for dense runs with
                            fewer than 65535 seeds (16-bit labels on the device) the
                            widening; 0 otherwise */
    double ms_gpu;       /* OpenCL backend: sum of the device execution times (profiling
                            events) of the commands behind ms_kernel; ms_kernel - ms_gpu
                            is launch and synchronisation overhead */
    double ms_transfer;  /* host preparation (seed placement, start resolution), seed
                            upload and label download */
    double ms_prep;      /* the exact variants: the host's part of ms_transfer, building
                            the seed grid (vbj_tiles_prep_build); 0 for the others */
} vbj_result;

void vbj_result_free(vbj_result *r);

/* The JFA backends table, as the sampler's: one interface, the plain-C
 * reference (vbj_ref_open) and OpenCL (the device layer's jfa_open). */
typedef struct vbj_backend vbj_backend;
struct vbj_backend {
    const char *name;        /* "ref", "opencl" */
    char device[160];        /* "reference (C)" or the OpenCL device name */
    void *state;
    /* Nonzero (W751) on a device backend that vbj_backend_open opened: a
     * device failure mid-run warns it and that run and the rest go to the
     * reference, which gives the same labels. 0: the failure is reported and
     * the backend's owner falls back (channels: W806). */
    int fallback_warning;
    /* vbj_run after its checks: out is zeroed with dim, n and pixels set;
     * want is never 0. VB_ENOMEM, VB_EDEVICE (message in ctx). */
    int (*run)(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, const vbj_options *opt,
               unsigned want, vbj_result *out);
    /* vbj_exact. */
    int (*exact)(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, uint32_t *labels);
    void (*close)(vbj_backend *be);
};

/* The exact labels (VBJ_EXACT's, on the plain-C twin, on host threads) of
 * the voxels that `need` marks (one byte per pixel, x fastest, nonzero =
 * wanted), into out (zeroed first; dim, n, pixels set; free with
 * vbj_result_free): every other pixel's entry is unspecified (never
 * written), and tiles without a wanted pixel are skipped, so their work
 * counts are left out. A pixel's
 * exact label never depends on another's: the wanted ones are those of
 * vbj_run's VBJ_EXACT. What a caller that reads few labels runs instead
 * (the channel reference engine, vbc_channel_pipe.h). VB_ENOMEM. */
int vbj_ref_exact_need(vb_ctx *ctx, const vbj_seeds *s, const uint8_t *need, vbj_result *out);

/* Opens the plain-C reference backend. Close with vbj_backend_close. */
int vbj_ref_open(vb_ctx *ctx, vbj_backend **out);

/* Opens the backend for a device kind by the device layer's one fallback
 * rule (vb_device.h): on VB_EDEVICE warning W781 and the reference.
 * *dev gets the device to close after the backend (NULL on the
 * reference). layer may be NULL (reference only). A device that fails
 * during a later vbj_run or vbj_exact is dropped with W751 and the backend
 * becomes the reference for that run and the rest. */
int vbj_backend_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device_kind kind,
                     vb_device **dev, vbj_backend **out);

/* Closes any backend; NULL is allowed. */
void vbj_backend_close(vbj_backend *be);

/* Computes the discrete Voronoi diagram of `s` on [n]^dim with options `opt`
 * (NULL = JFA+1, labels). Fills *out (zeroed first; free with vbj_result_free).
 * VB_EMISUSE on bad options, VB_ENOMEM, VB_EDEVICE. */
int vbj_run(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, const vbj_options *opt,
            vbj_result *out);

/* The exact discrete Voronoi diagram: labels[p] = nearest seed to pixel p,
 * ties to the lowest index (cell-list search; on the backend's device, or in
 * C for the reference). labels has n^dim entries (caller-owned). */
int vbj_exact(vb_ctx *ctx, vbj_backend *be, const vbj_seeds *s, uint32_t *labels);

/* Error figures of a label grid against the exact one. Tie-tolerant: a pixel
 * is wrong only if its seed is strictly farther than the nearest one. */
typedef struct vbj_metrics {
    size_t pixels;
    size_t wrong;            /* pixels whose seed is strictly farther than the nearest */
    size_t differ;           /* pixels whose label is not the exact one (ties included) */
    double wrong_rate;       /* wrong / pixels */
    double max_err;          /* max over pixels of |p - s(p)| - |p - nearest|, in pixels */
    double mean_err;         /* the same, averaged over all pixels */
    size_t boundary_exact;   /* boundary pixels (Definition 6) of the exact diagram */
    size_t boundary_found;   /* boundary pixels of the given diagram */
    size_t boundary_missed;  /* exact boundary pixels that are not boundary in the given one */
    size_t boundary_extra;   /* given boundary pixels that are not exact boundary pixels */
} vbj_metrics;

/* Computes the figures (host, single pass). labels/exact have n^dim entries.
 * VB_EMISUSE if a label is out of range. */
int vbj_compare(vb_ctx *ctx, const vbj_seeds *s, const uint32_t *labels, const uint32_t *exact,
                vbj_metrics *out);

/* Boundary pixels (Definition 6) of a label grid: out[p] = 1 when a neighbour
 * has another label. out has n^dim entries. */
void vbj_boundary_mask(int dim, uint32_t n, const uint32_t *labels, uint8_t *out);

/* The number of boundary pixels (Definition 6) of a label grid. */
uint64_t vbj_boundary_count(int dim, uint32_t n, const uint32_t *labels);

/* Per-pixel distinct-label counts (see VBJ_WANT_NLABELS) of a label grid. */
void vbj_count_labels(int dim, uint32_t n, const uint32_t *labels, uint8_t *out);

/* Facet-JFA's default start resolution, in *m: the smallest power of two
 * such that no two seeds fall into the same cell of the m^dim grid (n when
 * two seeds share a fine pixel). Returns VB_OK, or VB_ENOMEM (message in
 * ctx; *m untouched): a start guessed without the seeds' order would give
 * another diagram, so none is. Allocates only scratch. */
int vbj_start_resolution(vb_ctx *ctx, const vbj_seeds *s, uint32_t *m);

#endif
