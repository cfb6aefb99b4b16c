/* Internal to the JFA module: the host-side preparation both backends share
 * (core/discrete/jfa_prep.c) and the plain-C backend's entry points
 * (core/discrete/jfa_ref.c). */
#ifndef VBJ_PREP_H
#define VBJ_PREP_H

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
void vbj_cells_free(vbj_cells *c);

/* The plain-C backend (core/discrete/jfa_ref.c). */
int vbj_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_options *opt, vbj_result *out);
int vbj_ref_exact(vb_ctx *ctx, const vbj_seeds *s, uint32_t *labels);

/* log2 of a power of two (the floor of log2 for others; 0 for 0 and 1). */
uint32_t vbj_log2u(uint32_t v);

#endif
