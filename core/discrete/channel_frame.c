/* One frame of the channel analysis: pack, pipe, analyse (vbc_frame.h). */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb_parallel.h"
#include "vbc_frame.h"

double vbc_cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

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
    f->ms_masks = f->ms_analysis = f->ms_pore = 0.0;
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

int vbc_frame_analyse(vb_ctx *ctx, const vb_sphere_set *s, const vbc_options *opt, vbc_frame *f)
{
    const vbc_grid *g = &f->grid;
    const vbc_pore_request *req = opt->pore && opt->pore->enabled ? opt->pore : NULL;
    double t1 = vb_now();
    int rc = vbc_analyse_given(ctx, g, s, f->out.voxels, f->out.clearance, f->out.comp,
                               f->out.nvoxels, opt, &f->result);
    double t2 = vb_now();
    if (rc == VB_OK)
        rc = vbc_pore_stage(ctx, g, f->out.flags, s, req, opt->lining_tol, &f->result, &f->axis,
                            &f->pore_ms);
    double t3 = vb_now();
    f->ms_analysis = 1e3 * (t2 - t1);
    f->ms_pore = 1e3 * (t3 - t2);
    if (rc != VB_OK) {
        vbc_frame_out_free(&f->out);
        vbc_result_free(&f->result);
        memset(&f->result, 0, sizeof f->result);
    }
    return rc;
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
