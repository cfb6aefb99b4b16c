/* Internal to the JFA module: the host-side preparation both backends share
 * (core/discrete/jfa_prep.c) and the plain-C backend's entry points
 * (core/discrete/jfa_ref.c). */
#ifndef VBJ_PREP_H
#define VBJ_PREP_H

#include "vb_grid.h"
#include "vbj_jfa.h"

/* Step lengths of a dense variant on a q^d grid (JFA family only): writes at
 * most 2 + log2(q) lengths to steps and returns their number. */
int vbj_schedule(vbj_variant v, uint32_t q, uint32_t *steps);

/* Seeds placed on a grid of cells of f fine pixels (side n/f): pairs[2i] is a
 * cell's linear index, pairs[2i+1] the seed it starts with (the seed nearest
 * to the cell centre, ties to the lower index). *collisions counts seeds that
 * lost their cell. Allocates *pairs (free()). */
int vbj_place(vb_ctx *ctx, const vbj_seeds *s, uint32_t f, uint32_t **pairs, size_t *count,
              uint32_t *collisions);

/* A uniform bucket grid over the seeds for the exact search: bucket b holds
 * the seeds items[start[b] .. start[b+1]) (ascending index) whose nearest
 * pixel p has p >> shift == b's coordinates; g buckets per axis. */
typedef struct vbj_cells {
    uint32_t shift, g;
    uint32_t *start; /* g^d + 1 */
    uint32_t *items; /* k */
} vbj_cells;

int vbj_cells_build(vb_ctx *ctx, const vbj_seeds *s, vbj_cells *out);
/* The same with buckets of at least 2^min_shift pixels per axis. */
int vbj_cells_build_min(vb_ctx *ctx, const vbj_seeds *s, uint32_t min_shift, vbj_cells *out);
void vbj_cells_free(vbj_cells *c);

/* The seed grid of the exact tiled engine (vbj_tiles.h), for both backends:
 * tiles of 2^ts voxels per axis, buckets of 2^bs >= 2^ts pixels (g per
 * axis, about one seed each), bucket b's seeds at records start[b] ..
 * start[b + 1], each record (x, y, z, index) as int32 (z 0 in 2D), seeds
 * of a bucket in ascending index; ring0[b] the Chebyshev distance in
 * buckets from b to the nearest bucket holding a seed, at most
 * VBJ_XT_RING0_MAX (where b's ring search starts). */
typedef struct vbj_tiles_prep {
    uint32_t ts, bs, g;
    size_t nbuckets;  /* g^d */
    uint32_t *start;  /* nbuckets + 1 */
    int32_t *recs;    /* 4 k */
    uint8_t *ring0;   /* nbuckets */
} vbj_tiles_prep;

/* Builds the seed grid of s. Allocates; VB_ENOMEM. */
int vbj_tiles_prep_build(vb_ctx *ctx, const vbj_seeds *s, vbj_tiles_prep *out);
void vbj_tiles_prep_free(vbj_tiles_prep *p);

/* The plain-C twin of the tiled engine: the exact labels of every voxel
 * into out->labels (allocated; out->pixels set by the caller) and the work
 * counts. need NULL, or one byte per voxel (x fastest): then only the
 * voxels whose byte is nonzero get their label (every other entry is left
 * as malloc gave it), and a tile without such a voxel is skipped whole
 * (its counts too); a tile's searches and tests then run on the box of its
 * wanted voxels, which vbj_tiles.h's bounds allow for any box inside the
 * tile. A voxel's exact label never depends on the others', so the wanted
 * ones are those of the full run. VB_ENOMEM. */
int vbj_tiles_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_tiles_prep *p, const uint8_t *need,
                      vbj_result *out);


/* The counts of a tiled run from its counters (VBJ_XT_C_*, summed over
 * tiles): the exact-engine fields of c, steps = 1, step_pixels = voxels of
 * the tiles not filled as uniform, threads += one work-item per row of
 * VBJ_XT_ROW voxels. */
void vbj_tiles_counts(const vbj_seeds *s, const vbj_tiles_prep *p, const uint64_t *cnt,
                      vbj_counts *c);

/* The plain-C backend (core/discrete/jfa_ref.c). */
int vbj_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *opt, vbj_result *out);
int vbj_ref_exact(vb_ctx *ctx, const vbj_seeds *s, uint32_t *labels);

/* log2 of a power of two (the floor of log2 for others; 0 for 0 and 1). */
uint32_t vbj_log2u(uint32_t v);

#endif
