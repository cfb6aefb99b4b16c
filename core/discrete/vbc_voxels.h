/* The channel analysis's voxel stage, shared by channel_components.c and
 * channel_voxels.c (private to core/discrete): one frame's channel voxels
 * sorted, linked into the 26-connected voxel graph and grouped into
 * connected components. */
#ifndef VBC_VOXELS_H
#define VBC_VOXELS_H

#include <stddef.h>
#include <stdint.h>

#include "vb_uf.h"
#include "vbc_graph.h"

/* The analysis of one frame's channel voxels: the voxel graph and its
 * scratch, shared by the steps below. */
typedef struct {
    vbc_graph A;
    const vbc_grid *g;
    const vbc_options *opt;
    size_t nvox;
    uint32_t *sorted;   /* voxel indices, ascending, mouth bit cleared */
    uint8_t *mouth;
    vb_uf uf;           /* union-find, then scratch of vbc_channel_ends */
    uint32_t *order;    /* positions grouped by component */
    size_t *cstart;     /* component c holds order[cstart[c] .. cstart[c + 1]) */
    uint32_t *comp;
    size_t ncomp;
    double *clear;      /* clearance per position (given, or computed per component) */
    int32_t *near;
    int given_clear;    /* the clearances came with the voxels */
    uint32_t *vcomp;    /* given component labels per position (voxel indices), or NULL */
    int comp_bad;       /* a given label failed a check: the union-find decides */
    vbc_cells *cells;
    /* The batch path (vbc_paths_trace): per component its line's ends and
     * through flag, the predecessors of the weighted sweeps from the
     * first end in A.pred; NULL on the per-component path. */
    const struct vbc_paths_engine *paths;
    uint32_t *end_a, *end_b;
    uint8_t *end_through;
    double ms_graph;    /* the batch path's wall time (ends and sweeps), ms */
} analysis;

/* Frees what vbc_analysis_alloc and the stages allocated (W's arrays and the
 * graph's); W itself is the caller's. */
void vbc_analysis_free(analysis *W);

/* The per-position arrays of W->nvox voxels. Returns 0, or -1 when out of
 * memory. */
int vbc_analysis_alloc(analysis *W);

/* The voxels vox[0..W->nvox) in increasing index order (with their given
 * clearances when vclear is not NULL, and component labels when comp is
 * not NULL), the mouth bit split off, each its own union-find root.
 * Returns 0, or -1 when out of memory. */
int vbc_voxels_load(analysis *W, const uint32_t *vox, const float *vclear, const uint32_t *comp);

/* The voxel graph (26-connectivity) as CSR adjacency, built on slices over
 * the threads, the union-find joined along its edges. Returns 0, or -1 when
 * out of memory. */
int vbc_voxels_link(analysis *W);

/* The components from the given labels (W->vcomp), checked; where a check
 * fails W->comp_bad is set and the union-find's components are used. */
void vbc_components_given(analysis *W);

/* The components of the union-find as CSR over W->order, numbered by their
 * lowest voxel. */
void vbc_components_group(analysis *W);

/* The ends and sweeps of the components work[0..nwork) (low 32 bits: the
 * component; nm[c] its mouth voxels, 0 for a cavity) as batches on
 * W->paths (vbc_paths.h), nt threads for the openings: per component c
 * W->end_a[c], W->end_b[c], W->end_through[c] and, along W->A.pred from
 * end_b, the centreline, as vbc_channel_ends, vbc_sweep and vbc_farthest
 * give them one component at a time (channel_components.c's trace_path).
 * Returns 0, or -1 when out of memory. */
int vbc_paths_trace(analysis *W, const uint64_t *work, size_t nwork, const size_t *nm, int nt);

#endif
