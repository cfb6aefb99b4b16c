/* The pore of one frame next to its discrete channels: choose the axis
 * (given, the chains, a through channel, the principal axes), sweep it
 * (vbc_pore_sweep) inside the molecule that the probe's mask defines, put
 * the pore in the result as channel 1, rank the rest (vbc_rank) and refine
 * the discrete bottlenecks off the voxel centres. */
#ifndef VBC_PORE_FRAME_H
#define VBC_PORE_FRAME_H

#include "vbc_pore.h"

typedef struct vbc_pore_request {
    int enabled;
    int have_axis;        /* --axis: u is the axis */
    int have_through;     /* --through: the sweep starts at c */
    double u[3], c[3];
    int found_source;     /* when the axis was found on an earlier frame: its source */
    int found_chains;
    char found_why[128];  /* and its axis_why */
    int have_membrane;    /* the frame's membrane normal, the first candidate (set per frame) */
    vbc_axis membrane;
    vbc_pore_options sweep;
} vbc_pore_request;

/* Finds the pore of the spheres s on grid g with the molecular mask in
 * flags (VBC_F_MOLECULAR per voxel; NULL: the sweep ends at the molecule's
 * extent or end_radius) and the discrete channels res (for the axis of a
 * through channel). An axis from the request is swept as given; otherwise
 * candidates are tried in the order of vbc_pore.h and the first open one
 * (smallest radius > 0) is taken, the chains' axis of three or more chains
 * even when closed (a closed gate is still the pore) unless one subunit
 * holds a clearly wider open pore (vbc_pore.h; not with --through). *out is filled (free
 * with vbc_pore_free); out->n == 0 when no candidate was usable.
 * VB_ENOMEM. */
int vbc_pore_find(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_cells *cells,
                  const vb_sphere_set *s, const vbc_result *res, const vbc_pore_request *req,
                  vbc_pore *out);

/* The pore p's lining atoms (each atom whose surface is within r +
 * lining_tol of a point of p), ascending, in *out (malloc'ed, *n of them;
 * free it), read from the cell list only: so the pore stage makes them
 * while it waits for the analysis beside it. VB_OK, or VB_ENOMEM (nothing
 * reported; *out NULL). */
int vbc_pore_lining(const vbc_pore *p, const vbc_cells *cells, double lining_tol, int32_t **out,
                    size_t *n);

/* Puts the pore p at the head of res (kind VBC_PORE, its points, its
 * lining atoms: vbc_pore_lining's list of nlining, taken: freed by this
 * call whatever it returns; res->pore filled). VB_ENOMEM. */
int vbc_result_add_pore_lined(vb_ctx *ctx, vbc_result *res, const vbc_pore *p, int32_t *lining,
                              size_t nlining);

/* Moves each discrete channel's points within two of its bottleneck off the
 * voxel centre to the widest place in the plane normal to the centreline
 * there (at most one voxel edge h away), then recomputes the bottleneck and
 * the length (that of the polyline through the points as they now are).
 * The channels go to vbc_pore_threads(channels, 8) threads (each moves its
 * own points only). */
void vbc_refine_bottlenecks(vbc_result *res, const vbc_cells *cells, double h);

/* Orders the table and gives each entry its reason (enum vbc_why): the pore
 * first, then through channels (widest bottleneck first), channels that run
 * along the pore for a third of their points or more (branches), other
 * channels (longest first), cavities (longest first). */
void vbc_rank(vbc_result *res);

/* Milliseconds of the pore stage's steps (wall clock, vb_now). */
/* The end of the pore's sweep (a vbc_outside_fn, user a vbc_mask_view):
 * a point off the grid g or in a voxel of flags without the molecular bit
 * (VBC_F_MOLECULAR) lies outside the molecule. */
typedef struct vbc_mask_view {
    const vbc_grid *g;
    const uint8_t *flags;
} vbc_mask_view;

int vbc_mask_outside(void *user, const double p[3]);

typedef struct vbc_pore_ms {
    double cells;   /* the cell list over the frame's spheres */
    double refine;  /* vbc_refine_bottlenecks of the discrete channels (its own
                       wall time: from 4 threads it runs beside the sweep) */
    double sweep;   /* vbc_pore_find: the axis candidates' sweeps */
    double verdict; /* vbc_pore_judge */
    double lining;  /* vbc_result_add_pore and vbc_rank */
} vbc_pore_ms;

/* The whole pore stage of a frame: cells over s, vbc_pore_find,
 * vbc_result_add_pore, vbc_refine_bottlenecks, vbc_rank. When req is NULL
 * or disabled only the refinement and the ranking run. With
 * VBC_PORE_MIN_THREADS threads or more the refinement runs on a thread of
 * its own beside the search, which waits for it where it reads the
 * channels (the through channel's candidate), as the table's steps do:
 * the same result as one after the other. The found pore's
 * verdict takes its pixels from walls' rasters (vbc_pore_judge_on; NULL:
 * the host's flood alone, the same verdict). *found (may be NULL)
 * gets the axis used; *ms (may be NULL) the milliseconds of each step
 * (zero for a step not run). The clocks change no result. VB_ENOMEM. */
struct vbc_walls_engine;
int vbc_pore_stage(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vb_sphere_set *s,
                   const vbc_pore_request *req, const struct vbc_walls_engine *walls,
                   double lining_tol, vbc_result *res, vbc_axis *found, vbc_pore_ms *ms);

/* What vbc_pore_stage_after runs first: run(arg) fills the stage's res
 * (the analysis of the frame's channel voxels) and returns a VB status. */
typedef struct vbc_pore_before {
    int (*run)(void *arg);
    void *arg;
} vbc_pore_before;

/* vbc_pore_stage with the filling of res in it (before may be NULL: res
 * is filled). before->run runs where the refinement does, just before it:
 * from VBC_PORE_MIN_THREADS threads on a thread of its own beside the
 * cells and the search (which read res only after it, as above), else
 * first, on the caller's thread. Either way the same result as before->run
 * then vbc_pore_stage. When before->run fails, neither the refinement nor
 * the table's steps run and its status is returned (res as it left it);
 * the search may have run. before->run must not use ctx (the search does,
 * at once): give it a context of its own. Statuses as vbc_pore_stage. */
int vbc_pore_stage_after(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vb_sphere_set *s,
                         const vbc_pore_request *req, const struct vbc_walls_engine *walls,
                         double lining_tol, vbc_result *res, vbc_axis *found, vbc_pore_ms *ms,
                         const vbc_pore_before *before);

#endif
