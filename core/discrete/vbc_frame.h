/* One frame of the channel analysis as a library call: the spheres packed
 * on a fitted grid, the frame pipeline (labels, masks, channel voxels),
 * then the analysis (components, centrelines, bottlenecks, lining). The
 * `channels` command runs it per frame, the pipeline stages of its --png
 * picture on a planar cut of the molecule. */
#ifndef VBC_FRAME_H
#define VBC_FRAME_H

#include "vbc_channel_pipe.h"
#include "vbc_pore_frame.h"

typedef struct vbc_frame {
    vbc_grid grid;
    float *atoms4;          /* the packed spheres (vbc_atoms_pack), grid units */
    size_t atoms_cap;
    vbc_frame_out out;      /* channel voxels, flags / labels as wanted, device times */
    vbc_result result;      /* the analysis */
    double ms_masks;        /* packing and the frame pipeline */
    double ms_analysis;     /* components and centrelines */
    double ms_pore;         /* the pore stage (vbc_pore_stage), refinement and ranking */
    double ms_beside;       /* of ms_analysis, what ran within ms_pore's span (vbc_frame_analyse) */
    vbc_pore_ms pore_ms;    /* its steps */
    vbc_axis axis;          /* the pore's axis (source VBC_AXIS_NONE without a pore) */
    vbc_pipe *pipe;         /* the pipe of the last vbc_frame_masks (its paths engine) */
} vbc_frame;

/* Zero-initialised is empty; vbc_frame_free releases. */
void vbc_frame_free(vbc_frame *f);

/* Runs one frame of the spheres s on grid g (a vbc_grid_fit grid for
 * `probe`) through the pipe and the analysis with opt; `want` as for
 * vbc_pipe_frame; then the pore stage (vbc_pore_stage with opt->pore, which
 * needs the flag volume: it is fetched and kept whatever `want` says), or
 * without opt->pore the refinement and ranking alone. *f is refilled (its buffers reused); on failure it holds
 * nothing of the frame. VB_OK, VB_ENOMEM, VB_EMISUSE, VB_EDEVICE. */
int vbc_frame_run(vb_ctx *ctx, vbc_pipe *pipe, const vbc_grid *g, const vb_sphere_set *s,
                  double probe, unsigned want, const vbc_options *opt, vbc_frame *f);

/* vbc_frame_run in two halves, which may run on two threads for two
 * frames (frames in flight, vbc_ahead.h): vbc_frame_masks packs the
 * spheres and runs the pipe (f->out, f->ms_masks; the flag volume fetched
 * when opt->pore asks for the pore stage), vbc_frame_analyse then runs the
 * analysis and the pore stage on f->out (f->result, f->axis, the other
 * times). vbc_frame_analyse reads opt->pore when it runs, so the pore axis
 * an earlier frame found counts. Statuses and what *f holds after a
 * failure as for vbc_frame_run. */
int vbc_frame_masks(vb_ctx *ctx, vbc_pipe *pipe, const vbc_grid *g, const vb_sphere_set *s,
                    double probe, unsigned want, const vbc_options *opt, vbc_frame *f);
int vbc_frame_analyse(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f);

/* Whether vbc_frame_analyse runs the analysis beside the pore stage
 * (f->ms_beside then says how much of it): opt asks for the pore,
 * vbc_analysis_beside() holds, and the analysis's sweeps do
 * not run on f's pipe (VORBALL_DEVICE_PATHS). The analysis then runs on a
 * thread of the pore stage (vbc_pore_stage_after) with a context of its
 * own, whose counters and error become ctx's: the same result, the same
 * status and error as one after the other. */
int vbc_frame_beside(const vbc_options *opt, const vbc_frame *f);

/* vbc_frame_analyse in its two steps: vbc_frame_components, the analysis
 * of f->out (f->result, f->ms_analysis), which reads opt but not opt->pore,
 * so it may run on the reader's thread ahead of the frames before (vbc_run_front);
 * then vbc_frame_pore, the pore stage (f->axis, f->ms_pore, f->pore_ms),
 * in frame order. Statuses and what *f holds after a failure as for
 * vbc_frame_run. */
int vbc_frame_components(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f);
int vbc_frame_pore(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f);

/* The planar cut of s by the plane through its centroid normal to axis
 * `normal` (0 x, 1 y, 2 z): every sphere the plane crosses becomes a disk
 * of its cross-section radius, in the plane's two other axes (z 0).
 * *out has no atom records. VB_EINPUT_EMPTY when the plane meets no
 * sphere, VB_ENOMEM. */
int vbc_planar_cut(vb_ctx *ctx, const vb_sphere_set *s, int normal, vb_sphere_set **out);

/* An RGB picture: h rows of w pixels, 3 bytes each, row 0 at the top. */
typedef struct vbc_image {
    uint32_t w, h;
    uint8_t *rgb;
} vbc_image;

void vbc_image_free(vbc_image *img);

/* The eight panels of the 2D pipeline (the paper's Fig. 5), 4 x 2, for the
 * planar cut of s normal to `normal` on an n x n grid: input disks, disks
 * grown by the probe, Voronoi regions, Voronoi edges, atomic region,
 * molecular region, interior, channels (cavities kept: in a cut a pore is
 * often closed) with their centrelines. Fills *img (free with
 * vbc_image_free). VB_EINPUT_EMPTY when the plane meets no atom; VB_ENOMEM,
 * VB_EDEVICE. */
int vbc_stages_render(vb_ctx *ctx, vbc_pipe *pipe, const vb_sphere_set *s, double probe, int n,
                      int normal, const vbc_options *opt, vbc_image *img);

#endif
