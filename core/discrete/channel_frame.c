/* One frame of the channel analysis: pack, pipe, analyse (vbc_frame.h). */
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_parallel.h"
#include "vbc_frame.h"
#include "vbc_paths.h"

void vbc_frame_free(vbc_frame *f)
{
    free(f->atoms4);
    vbc_frame_out_free(&f->out);
    vbc_result_free(&f->result);
    memset(f, 0, sizeof *f);
}

int vbc_frame_masks(vb_ctx *ctx, vbc_pipe *pipe, const vbc_grid *g, const vb_sphere_set *s,
                    double probe, unsigned want, const vbc_options *opt, vbc_frame *f)
{
    vbc_frame_out_free(&f->out);
    vbc_result_free(&f->result);
    memset(&f->result, 0, sizeof f->result);
    f->grid = *g;
    f->pipe = pipe;
    f->ms_masks = f->ms_analysis = f->ms_pore = f->ms_beside = 0.0;
    memset(&f->pore_ms, 0, sizeof f->pore_ms);
    memset(&f->axis, 0, sizeof f->axis);
    if (opt->pore && opt->pore->enabled)
        want |= VBC_WANT_FLAGS;
    if (f->atoms_cap < s->n) {
        float *a = realloc(f->atoms4, 4 * s->n * sizeof *a);
        if (!a)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "frame of %zu atoms", s->n);
        f->atoms4 = a;
        f->atoms_cap = s->n;
    }
    double t0 = vb_now();
    vbc_atoms_pack(g, s, probe, f->atoms4);
    int rc = vbc_pipe_frame(ctx, pipe, g, f->atoms4, s->n, probe, want, &f->out);
    f->ms_masks = 1e3 * (vb_now() - t0);
    return rc;
}

/* Drops what a failed half of the analysis leaves in *f. */
static int analyse_failed(vbc_frame *f, int rc)
{
    if (rc != VB_OK) {
        vbc_frame_out_free(&f->out);
        vbc_result_free(&f->result);
        memset(&f->result, 0, sizeof f->result);
    }
    return rc;
}

int vbc_frame_components(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f)
{
    double t1 = vb_now();
    /* VORBALL_DEVICE_PATHS: the sweeps as batches on the pipe's engine. */
    const vbc_paths_engine *paths = f->pipe && vbc_paths_mode() ? vbc_pipe_paths(f->pipe) : NULL;
    int rc = vbc_analyse_paths(ctx, &f->grid, s, f->out.voxels, f->out.clearance, f->out.comp,
                               f->out.nvoxels, opt, paths, &f->result);
    f->ms_analysis = 1e3 * (vb_now() - t1);
    return analyse_failed(f, rc);
}

int vbc_frame_pore(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f)
{
    const vbc_pore_request *req = opt->pore && opt->pore->enabled ? opt->pore : NULL;
    double t2 = vb_now();
    const struct vbc_walls_engine *walls = f->pipe ? vbc_pipe_walls_hold(f->pipe) : NULL;
    int rc = vbc_pore_stage(ctx, &f->grid, f->out.flags, s, req, walls, opt->lining_tol,
                            &f->result, &f->axis, &f->pore_ms);
    if (f->pipe)
        vbc_pipe_walls_release(f->pipe);
    f->ms_pore = 1e3 * (vb_now() - t2);
    return analyse_failed(f, rc);
}

/* The analysis as vbc_pore_stage_after's first step: on context w (its
 * own: the pore's search speaks through the frame's at once). */
typedef struct {
    vb_ctx *w;
    const vb_sphere_set *s;
    const vbc_options *opt;
    vbc_frame *f;
} components_job;

static int components_run(void *arg)
{
    components_job *J = arg;
    vbc_frame *f = J->f;
    double t = vb_now();
    int rc = vbc_analyse_paths(J->w, &f->grid, J->s, f->out.voxels, f->out.clearance, f->out.comp,
                               f->out.nvoxels, J->opt, NULL, &f->result);
    f->ms_analysis = 1e3 * (vb_now() - t);
    return rc;
}

int vbc_frame_beside(const vbc_options *opt, const vbc_frame *f)
{
    /* Where the refinement runs beside the search (vbc_pore_stage_after);
     * the analysis's batch sweeps on the pipe (VORBALL_DEVICE_PATHS) keep
     * the order of old. */
    return opt->pore && opt->pore->enabled && vbc_analysis_beside() && !(f->pipe && vbc_paths_mode());
}

int vbc_frame_analyse(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f)
{
    f->ms_pore = f->ms_beside = 0.0;
    vb_ctx *w = NULL;
    if (!vbc_frame_beside(opt, f) || vb_open_worker(&w, ctx) != VB_OK) {
        int rc = vbc_frame_components(ctx, s, opt, f);
        return rc == VB_OK ? vbc_frame_pore(ctx, s, opt, f) : rc;
    }
    components_job J = {w, s, opt, f};
    vbc_pore_before B = {components_run, &J};
    double t = vb_now();
    const struct vbc_walls_engine *walls = f->pipe ? vbc_pipe_walls_hold(f->pipe) : NULL;
    int rc = vbc_pore_stage_after(ctx, &f->grid, f->out.flags, s, opt->pore, walls, opt->lining_tol,
                                  &f->result, &f->axis, &f->pore_ms, &B);
    if (f->pipe)
        vbc_pipe_walls_release(f->pipe);
    f->ms_pore = 1e3 * (vb_now() - t);
    /* The analysis ran within the stage's span: the frame took the span. */
    f->ms_beside = f->ms_analysis;
    /* Its counters and its failure are the frame's, as on one thread. */
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(w));
    vb_diag_record e;
    if (rc != VB_OK && vb_error_record(w, &e) == VB_OK)
        vb_error(ctx, rc, e.file, e.line, "%s", e.message);
    vb_close(w);
    return analyse_failed(f, rc);
}

int vbc_frame_run(vb_ctx *ctx, vbc_pipe *pipe, const vbc_grid *g, const vb_sphere_set *s,
                  double probe, unsigned want, const vbc_options *opt, vbc_frame *f)
{
    int rc = vbc_frame_masks(ctx, pipe, g, s, probe, want, opt, f);
    if (rc != VB_OK) {
        vbc_frame_out_free(&f->out);
        return rc;
    }
    return vbc_frame_analyse(ctx, s, opt, f);
}
