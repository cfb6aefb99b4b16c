/* The channel analysis of a sequence of frames (vbc_run.h). */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_diag.h"
#include "vb_parallel.h"
#include "vbc_run.h"

void vbc_run_init(vbc_run *r, vbc_channels_config *cfg, vbc_pipe *pipe, const char *input)
{
    memset(r, 0, sizeof *r);
    r->cfg = cfg;
    r->pipe = pipe;
    r->input = input;
}

void vbc_run_free(vbc_run *r)
{
    vbc_result_free(&r->first);
    free(r->occupancy);
    free(r->series.frame);
    free(r->series.rmin);
    free(r->series.s);
    memset(r, 0, sizeof *r);
}

/* Appends the frame's pore minimum to the series. */
static int series_add(vb_ctx *ctx, vbc_series *S, long frame, const vbc_result *res)
{
    if (!res->pore.present)
        return VB_OK;
    if (S->n == S->cap) {
        size_t c = vb_array_capacity(S->cap, S->n + 1, 64);
        int bad = vb_array_resize((void **)&S->frame, c, sizeof *S->frame);
        bad |= vb_array_resize((void **)&S->rmin, c, sizeof *S->rmin);
        bad |= vb_array_resize((void **)&S->s, c, sizeof *S->s);
        if (bad)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "pore series");
        S->cap = c;
    }
    const vbc_channel *c = &res->channels[0];
    const vbc_point *b = res->points + c->first_point + c->bottleneck_at;
    S->frame[S->n] = frame;
    S->rmin[S->n] = c->bottleneck;
    S->s[S->n++] = b->x * res->pore.u[0] + b->y * res->pore.u[1] + b->z * res->pore.u[2];
    return VB_OK;
}

/* The frame's grid: fitted to it, or the fixed grid of the first frame. */
static int frame_grid(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s, long index, vbc_grid *g)
{
    const vbc_channels_config *A = r->cfg;
    if (!A->fixed_grid)
        return vbc_grid_fit(ctx, s, A->probe, A->grid, 3, g);
    if (!r->fixed_fitted) {
        int rc = vbc_grid_fit(ctx, s, A->probe + 5.0, A->grid, 3, &r->fixed);
        if (rc != VB_OK)
            return rc;
        r->fixed_fitted = 1;
    }
    *g = r->fixed;
    /* Every atom must stay where the JFA seeds can be placed. */
    for (size_t i = 0; i < s->n; i++) {
        double c[3] = {s->x[i], s->y[i], s->z[i]};
        for (int a = 0; a < 3; a++) {
            double t = (c[a] - g->origin[a]) / g->h;
            if (!(t >= 0.0 && t < (double)g->nx))
                return vb_error(ctx, VB_EINPUT, A->traj ? A->traj : r->input, 0,
                                "frame %ld: atom %zu leaves the fixed grid fitted to the first frame",
                                index, i + 1);
        }
    }
    return VB_OK;
}

/* The spheres a frame analyses (s0 without the --ignore residues: o->kept
 * holds them when any were left out) and its grid. On failure nothing is
 * held. */
static int frame_prepare(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index,
                         vbc_run_out *o)
{
    const vbc_channels_config *A = r->cfg;
    int rc = VB_OK;
    o->kept = NULL;
    o->s = s0;
    if (A->nignore || A->nmembrane || !A->keep_ligands) {
        const char *names[2 * VBC_MAX_NAMES];
        size_t n = 0, dropped;
        for (size_t k = 0; k < A->nmembrane; k++)
            names[n++] = A->membrane[k];
        for (size_t k = 0; k < A->nignore; k++)
            names[n++] = A->ignore[k];
        size_t lig0 = r->ligands.atoms, mem0 = 0, mem1 = 0;
        for (size_t k = 0; k < A->nmembrane; k++)
            mem0 += r->left_out[k];
        rc = vbc_spheres_without(ctx, s0, names, n, r->left_out,
                                 A->keep_ligands ? NULL : &r->ligands, &o->kept, &dropped);
        if (rc != VB_OK)
            return rc;
        for (size_t k = 0; k < A->nmembrane; k++)
            mem1 += r->left_out[k];
        /* The membrane's normal, the pore's first axis candidate. */
        o->membrane_out = mem1 > mem0;
        if (o->membrane_out && A->pore.enabled) {
            int m = vbc_membrane_normal(s0, A->membrane, A->nmembrane, &o->membrane);
            if (m < 0) {
                vb_spheres_free(o->kept);
                o->kept = NULL;
                return vb_error(ctx, VB_ENOMEM, NULL, 0, "membrane normal: out of memory");
            }
            o->have_membrane = m;
        }
        r->ignored += dropped - (r->ligands.atoms - lig0);
        o->s = o->kept;
    }
    if ((rc = frame_grid(ctx, r, o->s, index, &o->g)) != VB_OK) {
        vb_spheres_free(o->kept);
        o->kept = NULL;
    }
    return rc;
}

/* The source of `first` fitted again on the frame o (its spheres o->s):
 * vbc_axis_refit, or the frame's membrane normal through the centroid of
 * its spheres. Returns 1 with *out filled, else 0. */
static int refit_source(const vbc_run_out *o, const vbc_axis *first, vbc_axis *out)
{
    if (first->source != VBC_AXIS_MEMBRANE)
        return vbc_axis_refit(o->s, first, out);
    if (!o->have_membrane)
        return 0;
    vbc_axis p[3];
    vbc_axis_principal(o->s, p);
    *out = o->membrane;
    memcpy(out->c, p[0].c, sizeof out->c);
    if (out->u[0] * first->u[0] + out->u[1] * first->u[1] + out->u[2] * first->u[2] < 0.0)
        for (int k = 0; k < 3; k++)
            out->u[k] = -out->u[k];
    return 1;
}

/* Later frames sweep the first frame's pore axis (HOLE's fixed cvect and
 * cpoint): kept in the request once a frame found a pore along a free axis. */
static void keep_pore_axis(vbc_channels_config *A, const vbc_frame *F, const vbc_run_out *o)
{
    if (!A->pore.enabled || !F->result.pore.present || A->pore.have_axis)
        return;
    /* --axis-refit: the source refitted on this frame, the base of later frames'. */
    if (A->axis_refit && !refit_source(o, &F->axis, &A->refit0))
        memset(&A->refit0, 0, sizeof A->refit0);
    memcpy(A->u0, F->axis.u, sizeof A->u0);
    memcpy(A->c0, F->axis.c, sizeof A->c0);
    memcpy(A->pore.u, F->axis.u, sizeof A->pore.u);
    memcpy(A->pore.c, F->axis.c, sizeof A->pore.c);
    A->pore.have_axis = A->pore.have_through = 1;
    A->pore.found_source = F->axis.source;
    A->pore.found_chains = F->axis.chains;
    memcpy(A->pore.found_why, F->axis.why, sizeof A->pore.found_why);
}

/* --axis-refit: the first frame's axis source fitted again on the frame o
 * (refit_source). The pore axis turns with it and the sweep's start moves by as
 * much as the refitted axis' point: u = the refit's direction, c = c0 +
 * (refit.c - refit0.c). From the first frame's values only, so a frame's
 * axis does not depend on which frames a process ran before it (MPI). */
static void refit_pore_axis(vbc_channels_config *A, const vbc_run_out *o)
{
    vbc_axis now;
    if (!A->axis_refit || !A->refit0.source || !refit_source(o, &A->refit0, &now))
        return;
    /* The chosen direction keeps its angle to the refitted one (a barrel's
     * pore tilted off its fitted axis): turned by the rotation taking
     * refit0.u to now.u (Rodrigues). */
    const double *a = A->refit0.u, *b = now.u;
    double k[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], u[3];
    const double *v = A->u0;
    double kv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    double kdv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2], n = 0.0;
    for (int i = 0; i < 3; i++) {
        u[i] = v[i] * c + kv[i] + k[i] * kdv / (1.0 + c);
        n += u[i] * u[i];
    }
    if (!(c > -0.999) || !(n > 0.0))
        return;
    for (int i = 0; i < 3; i++) {
        A->pore.u[i] = u[i] / sqrt(n);
        A->pore.c[i] = A->c0[i] + (now.c[i] - A->refit0.c[i]);
    }
}

/* The options of A with the frame's membrane normal in the pore request
 * (a copy in *req) when the frame has one and no axis is fixed. */
static void membrane_options(const vbc_channels_config *A, const vbc_run_out *o, vbc_options *opt,
                             vbc_pore_request *req)
{
    *opt = A->opt;
    if (!o->have_membrane || !A->opt.pore || A->opt.pore->have_axis)
        return;
    *req = *A->opt.pore;
    req->have_membrane = 1;
    req->membrane = o->membrane;
    opt->pore = req;
}

/* A front's pore stage on a thread of its own: the frame (moved out of
 * the front's vbc_run_out, whose copies travel through the ring of
 * frames in flight), its options and a worker context. */
struct vbc_pore_job {
    vbc_frame F;
    const vb_sphere_set *s;
    vbc_options opt;
    vbc_pore_request req;
    vb_ctx *w;
    int rc;
    vb_jobs th;
};

static void *pore_job_run(void *arg)
{
    vbc_pore_job *J = arg;
    J->rc = vbc_frame_pore(J->w, J->s, &J->opt, &J->F);
    return NULL;
}

/* Starts the pore stage of the front o on a thread when the request is
 * fixed; else (or when no thread or context can be had) the back half
 * runs it. The pore stage reads the frame, its spheres and the fixed
 * request only, so it gives what the back half would. */
static void pore_job_start(vb_ctx *ctx, vbc_run *r, vbc_run_out *o)
{
    if (!atomic_load(&r->pore_fixed))
        return;
    vbc_pore_job *J = calloc(1, sizeof *J);
    if (!J || vb_open_worker(&J->w, ctx) != VB_OK) {
        free(J);
        return;
    }
    membrane_options(r->cfg, o, &J->opt, &J->req);
    J->F = o->F;
    J->s = o->s;
    memset(&o->F, 0, sizeof o->F);
    o->pore = J;
    vb_jobs_start(&J->th, pore_job_run, J, sizeof *J, 1);
}

/* Waits for o's pore job and takes its frame back, its counters and its
 * error into ctx (when not NULL), as if the stage had run there. Returns
 * its status; after a failure the frame holds nothing (vbc_frame_pore). */
static int pore_job_join(vb_ctx *ctx, vbc_run_out *o)
{
    vbc_pore_job *J = o->pore;
    vb_jobs_join(&J->th);
    int rc = J->rc;
    if (ctx) {
        vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(J->w));
        vb_diag_record e;
        if (rc != VB_OK && vb_error_record(J->w, &e) == VB_OK)
            vb_error(ctx, rc, e.file, e.line, "%s", e.message);
    }
    o->F = J->F;
    vb_close(J->w);
    free(J);
    o->pore = NULL;
    return rc;
}

/* Test knob: VORBALL_TEST_FAIL_FRAME=N fails the analysis of frame N (E6,
 * "failure injected"), where the sequential loop and the frames in
 * analysis at once both run it, so that their failures can be compared. */
static int analysis_fault(vb_ctx *ctx, long index)
{
    const char *e = getenv("VORBALL_TEST_FAIL_FRAME");
    char *end;
    if (!e || !*e || strtol(e, &end, 10) != index || *end)
        return VB_OK;
    return vb_error(ctx, VB_EINTERNAL, NULL, 0,
                    "failure injected in the analysis of frame %ld (VORBALL_TEST_FAIL_FRAME)", index);
}

/* The pipeline `repeat` times (the first run's masks already made when
 * o->masked, its analysis when o->analysed, its pore stage running in
 * o->pore), the per-run mean timings in o->fi. */
static int frame_repeat(vb_ctx *ctx, vbc_run *r, vbc_run_out *o)
{
    const vbc_channels_config *A = r->cfg;
    vbc_frame_info *fi = &o->fi;
    int rc = VB_OK;
    vbc_options opt;
    vbc_pore_request req;
    membrane_options(A, o, &opt, &req);
    for (int k = 0; k < A->repeat && rc == VB_OK; k++) {
        int pored = k == 0 && (o->pore || o->pored);
        if (k == 0 && o->pore)
            rc = pore_job_join(ctx, o);
        if (rc == VB_OK && (k > 0 || !o->masked))
            rc = vbc_frame_masks(ctx, r->pipe, &o->g, o->s, A->probe, o->want, &A->opt, &o->F);
        if (rc == VB_OK && k == 0 && !o->analysed)
            rc = analysis_fault(ctx, o->fi.frame);
        int analyse = k > 0 || !o->analysed, pore = k > 0 || !pored;
        if (rc == VB_OK && analyse && pore)
            rc = vbc_frame_analyse(ctx, o->s, &opt, &o->F);
        else if (rc == VB_OK && analyse)
            rc = vbc_frame_components(ctx, o->s, &opt, &o->F);
        else if (rc == VB_OK && pore)
            rc = vbc_frame_pore(ctx, o->s, &opt, &o->F);
        fi->ms_upload += o->F.out.ms_upload;
        fi->ms_jfa += o->F.out.ms_jfa;
        fi->ms_masks += o->F.out.ms_masks;
        fi->ms_analysis += o->F.ms_analysis;
        fi->ms_graph += o->F.result.ms_graph;
        fi->ms_voxels += o->F.result.ms_voxels;
        fi->ms_clear += o->F.result.ms_clear;
        fi->ms_trace += o->F.result.ms_trace;
        fi->ms_pore += o->F.ms_pore;
        fi->ms_cells += o->F.pore_ms.cells;
        fi->ms_refine += o->F.pore_ms.refine;
        fi->ms_sweep += o->F.pore_ms.sweep;
        fi->ms_verdict += o->F.pore_ms.verdict;
        fi->ms_lining += o->F.pore_ms.lining;
        fi->ms_beside += o->F.ms_beside;
        fi->ms_total += o->F.ms_masks + o->F.ms_analysis + o->F.ms_pore - o->F.ms_beside;
        r->sum_masks += o->F.ms_masks;
        r->sum_total += o->F.ms_masks + o->F.ms_analysis + o->F.ms_pore - o->F.ms_beside;
    }
    double inv = 1.0 / A->repeat;
    fi->ms_upload *= inv;
    fi->ms_jfa *= inv;
    fi->ms_masks *= inv;
    fi->ms_analysis *= inv;
    fi->ms_graph *= inv;
    fi->ms_voxels *= inv;
    fi->ms_clear *= inv;
    fi->ms_trace *= inv;
    fi->ms_pore *= inv;
    fi->ms_cells *= inv;
    fi->ms_refine *= inv;
    fi->ms_sweep *= inv;
    fi->ms_verdict *= inv;
    fi->ms_lining *= inv;
    fi->ms_beside *= inv;
    fi->ms_total *= inv;
    fi->channel_voxels = o->F.out.nvoxels;
    return rc;
}

void vbc_run_frame_done(vbc_run *r, int first, vbc_run_out *o)
{
    if (first) { /* kept for CONECT and the plot */
        vbc_result_free(&r->first);
        r->first = o->F.result;
        memset(&o->F.result, 0, sizeof o->F.result);
    }
    vbc_frame_free(&o->F);
    vb_spheres_free(o->kept);
    memset(o, 0, sizeof *o);
}

int vbc_run_front(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index, int model,
                  int first, int mode, vbc_run_out *o)
{
    const vbc_channels_config *A = r->cfg;
    memset(o, 0, sizeof *o);
    double t0 = vb_now();
    int rc = frame_prepare(ctx, r, s0, index, o);
    if (rc != VB_OK)
        return rc;
    int want_volume = A->volume && (strstr(A->volume, "%d") || first);
    o->want = r->want | (want_volume || A->occupancy ? VBC_WANT_FLAGS : 0) |
              (want_volume && (A->volume_bit & VBC_F_EDGE) ? VBC_WANT_EDGES : 0);
    o->fi.frame = index;
    o->fi.model = model;
    o->fi.atoms = o->s->n;
    o->fi.ms_prepare = 1e3 * (vb_now() - t0);
    o->first = first;
    if (mode == VBC_FRONT_PREPARE)
        return VB_OK;
    rc = vbc_frame_masks(ctx, r->pipe, &o->g, o->s, A->probe, o->want, &A->opt, &o->F);
    /* The analysis reads no pore axis (the back half's): it runs here too,
     * so on the reader's thread it overlaps the pore stage of the frames before. */
    if (rc == VB_OK && mode == VBC_FRONT_ANALYSE)
        rc = vbc_frame_components(ctx, o->s, &A->opt, &o->F);
    if (rc != VB_OK) {
        vbc_run_front_drop(o);
        return rc;
    }
    o->masked = 1;
    if (mode == VBC_FRONT_ANALYSE) {
        o->analysed = 1;
        pore_job_start(ctx, r, o);
    }
    return VB_OK;
}

/* Whether o's pore stage may run in vbc_run_analyse, the request it reads
 * being the one its back half would read: 1 once the request is fixed, or
 * (gate) once the frames before o ran their back halves and no refit turns
 * the axis in o's own (--axis-refit); 0 when it is left to the back half
 * (the first frame: its lines come after W803's), or the run stops. */
static int request_final(vbc_run *r, const vbc_run_out *o, const vbc_run_gate *gate)
{
    if (atomic_load(&r->pore_fixed))
        return 1;
    if (o->first || !gate || r->cfg->axis_refit)
        return 0;
    return gate->wait(gate->arg);
}

int vbc_run_analyse(vb_ctx *ctx, vbc_run *r, vbc_run_out *o, const vbc_run_gate *gate)
{
    int rc = VB_OK;
    if (!o->masked)
        return VB_OK;
    /* Reads only what the back halves leave as it is: the request's
     * `enabled`, not its axis. */
    int beside = !o->analysed && !o->pore && !o->pored && vbc_frame_beside(&r->cfg->opt, &o->F);
    if (beside) {
        /* The analysis beside the pore stage (vbc_frame_analyse) once the
         * request is o's: the wait costs less than the pore stages on the
         * caller's thread, one frame after the other, would. Else both in
         * the back half, beside there too. */
        if (request_final(r, o, gate) != 1)
            return VB_OK;
        vbc_options opt;
        vbc_pore_request req;
        membrane_options(r->cfg, o, &opt, &req);
        if ((rc = analysis_fault(ctx, o->fi.frame)) != VB_OK ||
            (rc = vbc_frame_analyse(ctx, o->s, &opt, &o->F)) != VB_OK)
            return rc;
        o->analysed = o->pored = 1;
        return VB_OK;
    }
    if (!o->analysed) {
        if ((rc = analysis_fault(ctx, o->fi.frame)) != VB_OK ||
            (rc = vbc_frame_components(ctx, o->s, &r->cfg->opt, &o->F)) != VB_OK)
            return rc;
        o->analysed = 1;
    }
    if (!o->pore && !o->pored && request_final(r, o, gate) == 1) {
        vbc_options opt;
        vbc_pore_request req;
        membrane_options(r->cfg, o, &opt, &req);
        if ((rc = vbc_frame_pore(ctx, o->s, &opt, &o->F)) == VB_OK)
            o->pored = 1;
    }
    return rc;
}

/* Drops what a front half holds (a run stopped before its back half). */
void vbc_run_front_drop(vbc_run_out *o)
{
    if (o->pore)
        pore_job_join(NULL, o);
    vbc_frame_free(&o->F);
    vb_spheres_free(o->kept);
    memset(o, 0, sizeof *o);
}

int vbc_run_frame(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index, int model,
                  int first, vbc_run_out *o)
{
    int rc = vbc_run_front(ctx, r, s0, index, model, first, 0, o);
    return rc == VB_OK ? vbc_run_back(ctx, r, o) : rc;
}

int vbc_run_back(vb_ctx *ctx, vbc_run *r, vbc_run_out *o)
{
    vbc_channels_config *A = r->cfg;
    int first = o->first, rc;
    long index = o->fi.frame;
    double t0 = vb_now();
    if (!first)
        refit_pore_axis(A, o);
    o->fi.ms_prepare += 1e3 * (vb_now() - t0);
    /* A voxel wider than the probe cannot resolve the necks that matter. */
    if (first && o->g.h > fmax(A->probe, 0.5))
        vb_warn(ctx, VB_W_VOXEL_COARSE, r->input, 0,
                "voxel edge %.2f A is coarser than the probe radius %.2f A: narrow channels may be "
                "missed (raise --grid)", o->g.h, A->probe);
    rc = frame_repeat(ctx, r, o);
    if (rc == VB_OK && first && o->membrane_out && !o->have_membrane && A->pore.enabled &&
        !A->pore.have_axis)
        vb_warn(ctx, VB_W_MEMBRANE_NOT_FLAT, r->input, 0,
                "the membrane atoms left out make no flat, wide membrane (vbc_membrane_normal): its "
                "normal is no axis candidate");
    const vbc_pore_summary *ps = &o->F.result.pore;
    if (rc == VB_OK && A->pore.enabled && !ps->present && first && ps->judged)
        vb_warn(ctx, VB_W_PORE_NOT_FOUND, r->input, 0,
                "no pore: the widest path along the %s axis is walled by the molecule's atoms for "
                "%.1f A only (a pore needs %.0f A: vbc_pore.h); the table has none",
                vbc_axis_source_name(ps->rejected_source), ps->buried, VBC_PORE_MIN_BURIED);
    else if (rc == VB_OK && A->pore.enabled && !ps->present && first)
        vb_warn(ctx, VB_W_PORE_NOT_FOUND, r->input, 0, "no pore found along any axis candidate");
    if (rc == VB_OK && first && ps->present && ps->source != VBC_AXIS_GIVEN)
        vb_warn(ctx, VB_W_PORE_AXIS_FOUND, r->input, 0, "pore axis (%s): %s",
                vbc_axis_source_name(ps->source), ps->why);
    if (rc == VB_OK)
        keep_pore_axis(A, &o->F, o);
    /* From here on the request stays as it is: later fronts may run their
     * pore stage (its writes above happen before the flag is seen set). */
    if (rc == VB_OK && (!A->pore.enabled || (A->pore.have_axis && !A->axis_refit)))
        atomic_store(&r->pore_fixed, 1);
    if (rc == VB_OK && A->plot)
        rc = series_add(ctx, &r->series, index, &o->F.result);
    if (rc == VB_OK && A->occupancy) {
        if (!r->occupancy && !(r->occupancy = calloc(vbc_grid_voxels(&o->g), sizeof *r->occupancy)))
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "occupancy map");
        else
            rc = vbc_occupancy_add(ctx, &o->g, o->F.out.flags, &o->F.result, r->occupancy);
    }
    if (rc != VB_OK) {
        vbc_run_front_drop(o);
        return rc;
    }
    r->frames_done++;
    vb_progress(ctx, "frames", (uint64_t)r->frames_done,
                r->frames_total > 0 ? (uint64_t)r->frames_total : 0);
    return VB_OK;
}

void vbc_run_report_left_out(vb_ctx *ctx, const vbc_run *r)
{
    const vbc_channels_config *A = r->cfg;
    char text[2048];
    size_t o = 0;
    const vbc_ligands *L = &r->ligands;
    if (L->atoms) {
        for (size_t k = 0; k < L->n && o + 32 < sizeof text; k++)
            o += (size_t)snprintf(text + o, sizeof text - o, "%s%s %zu", k ? ", " : "", L->name[k],
                                  L->count[k]);
        vb_warn(ctx, VB_W_LIGANDS_LEFT_OUT, r->input, 0,
                "%zu ligand atoms left out (HETATM residues of no polymer; --keep-ligands keeps "
                "them): %s", L->atoms, text);
        o = 0;
    }
    if (!r->ignored)
        return;
    text[0] = '\0';
    for (int part = 0; part < 2; part++) {
        size_t n = part ? A->nignore : A->nmembrane, base = part ? A->nmembrane : 0, shown = 0;
        const char *const *names = part ? A->ignore : A->membrane;
        for (size_t k = 0; k < n && o + 64 < sizeof text; k++) {
            if (!r->left_out[base + k])
                continue;
            o += (size_t)snprintf(text + o, sizeof text - o, "%s%s%s %zu",
                                  shown ? ", " : o ? "; " : "",
                                  shown ? "" : part ? "--ignore: " : "membrane (--membrane none keeps it): ",
                                  names[k], r->left_out[base + k]);
            shown++;
        }
    }
    vb_warn(ctx, VB_W_ATOMS_IGNORED, r->input, 0, "%zu atoms left out: %s", r->ignored, text);
}

int vbc_run_axis(vb_ctx *ctx, vbc_run *r, const vb_sphere_set *s0, long index)
{
    vbc_run_out o;
    memset(&o, 0, sizeof o);
    /* Counted by the rank that owns the frame. */
    size_t ignored = r->ignored, left_out[2 * VBC_MAX_NAMES];
    vbc_ligands ligands = r->ligands;
    memcpy(left_out, r->left_out, sizeof left_out);
    int rc = frame_prepare(ctx, r, s0, index, &o);
    r->ignored = ignored;
    r->ligands = ligands;
    memcpy(r->left_out, left_out, sizeof left_out);
    if (rc != VB_OK)
        return rc;
    vbc_options opt;
    vbc_pore_request req;
    membrane_options(r->cfg, &o, &opt, &req);
    if ((rc = vbc_frame_run(ctx, r->pipe, &o.g, o.s, r->cfg->probe, 0, &opt, &o.F)) == VB_OK)
        keep_pore_axis(r->cfg, &o.F, &o);
    vbc_frame_free(&o.F);
    vb_spheres_free(o.kept);
    return rc;
}
