/* The channel analysis of a sequence of frames, as `vorball channels` and
 * the Python binding run it: per frame the residues left out (--ignore),
 * the grid (fitted, or fixed on the first frame), the frame pipeline and
 * pore stage `repeat` times with their timings, the pore axis carried from
 * the first frame to the later ones, the pore series and the occupancy.
 * The callers write what a frame gives (channel_write.c's writers). */
#ifndef VBC_RUN_H
#define VBC_RUN_H

#include "vbc_channels_config.h"
#include "vbc_frame.h"

/* The pore's smallest radius per frame of a trajectory (the plot). */
typedef struct vbc_series {
    long *frame;
    double *rmin, *s;
    size_t n, cap;
} vbc_series;

typedef struct vbc_run {
    vbc_channels_config *cfg; /* the caller's: its pore request takes the first frame's axis */
    vbc_pipe *pipe;           /* the caller's */
    const char *input;        /* named in warnings */
    long frames_done;         /* frames analysed */
    long frames_total;        /* frames to analyse when known (progress), else 0 */
    double sum_total, sum_masks; /* ms over every run of every frame */
    vbc_grid fixed;           /* --fixed-grid: fitted on the first frame run */
    int fixed_fitted;         /* `fixed` holds it (the front half's: vbc_run_front) */
    float *occupancy;         /* --occupancy: frames per voxel */
    vbc_result first;         /* the first frame's result (CONECT records, the plot) */
    vbc_series series;        /* the pore's smallest radius per frame (with --plot) */
    size_t ignored;           /* atoms left out by --membrane and --ignore, over the frames */
    size_t left_out[2 * VBC_MAX_NAMES]; /* per name: cfg's membrane names, then its ignore names */
    vbc_ligands ligands;      /* ligands left out (unless --keep-ligands), over the frames */
    unsigned want;            /* VBC_WANT_* the caller wants of every frame besides cfg's */
    _Atomic int pore_fixed;   /* the pore request will not change again (vbc_run_back sets it):
                               * a front may start the frame's pore stage on a thread */
} vbc_run;

typedef struct vbc_pore_job vbc_pore_job; /* a front's pore stage on a thread (channel_run.c) */

/* What one frame gives its writers. */
typedef struct vbc_run_out {
    vbc_frame F;              /* result, flags (when wanted), axis */
    vbc_frame_info fi;        /* per-run mean timings */
    vbc_grid g;
    const vb_sphere_set *s;   /* the spheres analysed: the frame's, or `kept` */
    vb_sphere_set *kept;      /* the frame without the --ignore residues, or NULL */
    unsigned want;            /* VBC_WANT_* of this frame (vbc_run_front) */
    int first;                /* the first frame of the selection */
    int masked;               /* F.out holds the first run's masks (vbc_run_front) */
    int analysed;             /* and F.result its analysis (vbc_frame_components) */
    vbc_pore_job *pore;       /* the pore stage running on F (moved there), or NULL */
    int pored;                /* F.result holds the first run's pore stage (vbc_run_analyse) */
    int membrane_out;         /* membrane atoms (--membrane) were left out of this frame */
    int have_membrane;        /* and `membrane` is their normal (vbc_membrane_normal) */
    vbc_axis membrane;
} vbc_run_out;

/* Starts a run of cfg (checked by vbc_channels_check) on pipe; input is
 * the name warnings give. Nothing is allocated until the first frame. */
void vbc_run_init(vbc_run *r, vbc_channels_config *cfg, vbc_pipe *pipe, const char *input);

/* Releases what the run holds (not cfg, not the pipe). */
void vbc_run_free(vbc_run *r);

/* Analyses frame `index` (MODEL `model`) with spheres s0; `first`: the
 * first frame of the selection (the voxel warning W803, the fixed grid,
 * the pore axis for the later frames, the flag volume when cfg asks for a
 * volume of the first frame only). Fills *o (free with
 * vbc_run_frame_done). On failure *o holds nothing. VB_ENOMEM, VB_EINPUT
 * (an atom leaves the fixed grid), VB_EINPUT_EMPTY, VB_EDEVICE. */
int vbc_run_frame(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index, int model,
                  int first, vbc_run_out *o);

/* vbc_run_front's modes: the spheres left out and the grid only; and the
 * first run's pipe (labels, masks, channel voxels), the analysis left to
 * vbc_run_analyse (on any thread); and the analysis too, with the pore
 * stage started on a thread once the pore request is fixed. */
enum { VBC_FRONT_PREPARE = 0, VBC_FRONT_MASKS = 1, VBC_FRONT_ANALYSE = 2 };

/* vbc_run_frame in two halves, so that a reader thread can run the front
 * of frame N+1 while the caller runs the back of frame N (frames in flight,
 * vbc_ahead.h); the tables are the same bytes as vbc_run_frame's.
 * vbc_run_front: the spheres left out, the grid and, by `mode` (above), the
 * first run's pipe and its analysis (components, centrelines:
 * vbc_frame_components), and once the pore request is fixed (the axis
 * found, not refitted per frame: pore_fixed) it starts the pore stage on a
 * thread of its own, which the back half joins (so the pore stages of the
 * frames in flight run at once); it touches the run's counts of atoms left
 * out and its fixed grid (fitted on the first front), and nothing the back
 * half touches. vbc_run_back, on the caller's thread in frame order: the
 * axis refit, the analysis (unless the front or vbc_run_analyse ran it),
 * the pore stage (unless run already), the series, the occupancy,
 * frames_done. Fronts run in frame order too. Each fills or finishes *o as
 * vbc_run_frame; on failure *o holds nothing (a front whose back will not
 * run: vbc_run_front_drop). */
int vbc_run_front(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index, int model,
                  int first, int mode, vbc_run_out *o);
int vbc_run_back(vb_ctx *ctx, vbc_run *r, vbc_run_out *o);
void vbc_run_front_drop(vbc_run_out *o);

/* What vbc_run_analyse waits on for a frame whose pore request is not
 * fixed yet (frames in analysis at once, vbc_flight.h): wait(arg) returns
 * 1 once r->pore_fixed is set or every frame before this one has run its
 * back half (vbc_run_back), 0 when the run stops first. */
typedef struct vbc_run_gate {
    int (*wait)(void *arg);
    void *arg;
} vbc_run_gate;

/* Between a VBC_FRONT_MASKS front and its back, on any thread (frames in
 * analysis at once, vbc_flight.h): the first run's analysis and its pore
 * stage once the request the stage reads is the one the back half would
 * read: fixed (pore_fixed), or, through `gate` (may be NULL: no waiting),
 * every frame before this one backed and no --axis-refit. Where the
 * analysis runs beside the pore stage (vbc_frame_beside) both wait for
 * that (not on the first frame, nor under --axis-refit: both are left to
 * the back half); else the analysis runs at once and the pore stage
 * waits. They read the frame, its spheres and the request only, so they
 * give what the back half would. Touches nothing of r but reads. VB_OK,
 * or the analysis' failure (then o->F holds no result; vbc_run_front_drop
 * o). */
int vbc_run_analyse(vb_ctx *ctx, vbc_run *r, vbc_run_out *o, const vbc_run_gate *gate);

/* After the frame's outputs are written: keeps the first frame's result in
 * r->first, frees the rest of *o. */
void vbc_run_frame_done(vbc_run *r, int first, vbc_run_out *o);

/* W809 for the atoms the run left out (nothing when none): the count, and
 * per residue name of the membrane and of --ignore how many; W811 for the
 * ligands left out, per residue name. */
void vbc_run_report_left_out(vb_ctx *ctx, const vbc_run *r);

/* The pore axis of the first frame without its outputs or counts (under
 * MPI, a rank that does not own the first frame still sweeps its axis on
 * the later ones). VB_OK or a failure of vbc_run_frame. */
int vbc_run_axis(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index);

#endif
