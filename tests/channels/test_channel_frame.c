/* The analysis beside the pore stage (vbc_frame_analyse, issue 33): from
 * VBC_PORE_MIN_THREADS threads the components and centrelines run on a
 * thread of the pore stage (vbc_pore_stage_after) while the pore's search
 * runs; the table must be the bytes of one after the other, and a failure
 * of the analysis the stage's status. The pore's lining atoms (made while
 * the stage waits for the analysis) against a brute-force scan. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "synth.h"
#include "vb_test.h"
#include "vbc_frame.h"
#include "vbc_paths.h"

static void set_threads(int n)
{
    char b[16];
    snprintf(b, sizeof b, "%d", n);
    setenv("VORBALL_THREADS", b, 1);
}

/* One frame of s through the reference pipe and vbc_frame_analyse on
 * `threads` threads into *f. */
static void frame(vb_ctx *ctx, vbc_pipe *pipe, const vb_sphere_set *s, const vbc_options *opt,
                  int threads, vbc_frame *f)
{
    set_threads(threads);
    vbc_grid g;
    CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 64, 3, &g), VB_OK);
    CHECK_INT(vbc_frame_masks(ctx, pipe, &g, s, 1.4, 0, opt, f), VB_OK);
    CHECK_INT(vbc_frame_beside(opt, f), threads >= VBC_PORE_MIN_THREADS);
    CHECK_INT(vbc_frame_analyse(ctx, s, opt, f), VB_OK);
}

/* The pore's lining atoms (made before the stage waits for the analysis,
 * vbc_pore_lining): every atom whose surface is within r + tol of a pore
 * point (the expression vbc_cells_within tests), ascending, by brute force. */
static void pore_lining_check(const vbc_result *res, const vb_sphere_set *s, double tol)
{
    CHECK(res->nchannels > 0 && res->channels[0].kind == VBC_PORE);
    if (!res->nchannels || res->channels[0].kind != VBC_PORE)
        return;
    const vbc_channel *c = &res->channels[0];
    const vbc_point *P = res->points + c->first_point;
    size_t n = 0, differ = 0;
    for (size_t a = 0; a < s->n; a++) {
        int in = 0;
        for (size_t k = 0; k < c->npoints && !in; k++) {
            double dx = P[k].x - s->x[a], dy = P[k].y - s->y[a], dz = P[k].z - s->z[a];
            in = sqrt(dx * dx + dy * dy + dz * dz) - s->r[a] <= P[k].r + tol;
        }
        if (!in)
            continue;
        differ += n >= c->nlining || res->lining[c->first_lining + n] != (int32_t)a;
        n++;
    }
    CHECK_INT(n, c->nlining);
    CHECK_INT(differ, 0);
    CHECK(n > 10);
}

/* Every field of every channel, point and lining atom the same bits. */
static void same_result(const vbc_result *a, const vbc_result *b)
{
    CHECK_INT(a->nchannels, b->nchannels);
    CHECK_INT(a->components, b->components);
    CHECK_INT(a->pruned, b->pruned);
    CHECK_INT(a->pore.present, b->pore.present);
    if (a->nchannels != b->nchannels)
        return;
    size_t np = 0, nl = 0;
    for (size_t t = 0; t < a->nchannels; t++) {
        const vbc_channel *x = &a->channels[t], *y = &b->channels[t];
        CHECK_INT(x->kind, y->kind);
        CHECK_INT(x->npoints, y->npoints);
        CHECK_INT(x->nlining, y->nlining);
        CHECK(x->length == y->length && x->bottleneck == y->bottleneck);
        if (x->npoints != y->npoints || x->nlining != y->nlining)
            return;
        if (x->first_point + x->npoints > np)
            np = x->first_point + x->npoints;
        if (x->first_lining + x->nlining > nl)
            nl = x->first_lining + x->nlining;
    }
    size_t differ = 0;
    for (size_t t = 0; t < np; t++) {
        const vbc_point *x = &a->points[t], *y = &b->points[t];
        differ += x->x != y->x || x->y != y->y || x->z != y->z || x->r != y->r || x->atom != y->atom;
    }
    CHECK_INT(differ, 0);
    CHECK(memcmp(a->lining, b->lining, nl * sizeof *a->lining) == 0);
}

/* The analysis of frame f into *res, 50 ms late: a search that did not
 * wait for it would rank or add its pore before it is there. */
typedef struct {
    vb_ctx *w;
    const vbc_frame *f;
    const vb_sphere_set *s;
    const vbc_options *opt;
    vbc_result *res;
} slow_job;

static int slow_analysis(void *arg)
{
    slow_job *J = arg;
    struct timespec ts = {0, 50000000};
    nanosleep(&ts, NULL);
    const vbc_frame *f = J->f;
    return vbc_analyse_given(J->w, &f->grid, J->s, f->out.voxels, f->out.clearance, f->out.comp,
                             f->out.nvoxels, J->opt, J->res);
}

/* The pore stage of frame f with request req on `threads` threads, its
 * analysis the late one above on a worker context, into *res. */
static void late_stage(vb_ctx *ctx, const vbc_frame *f, const vb_sphere_set *s, const vbc_options *opt,
                       const vbc_pore_request *req, int threads, vbc_result *res)
{
    set_threads(threads);
    vb_ctx *w;
    CHECK_INT(vb_open_worker(&w, ctx), VB_OK);
    memset(res, 0, sizeof *res);
    slow_job J = {w, f, s, opt, res};
    vbc_pore_before B = {slow_analysis, &J};
    CHECK_INT(vbc_pore_stage_after(ctx, &f->grid, f->out.flags, s, req, NULL, 1.0, res, NULL, NULL, &B),
              VB_OK);
    vb_close(w);
}

static int fail_enomem(void *arg)
{
    (void)arg;
    return VB_ENOMEM;
}

int main(void)
{
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    unsetenv("VORBALL_ANALYSIS_BESIDE");
    vbc_pipe *pipe;
    CHECK_INT(vbc_pipe_open(ctx, NULL, VB_DEVICE_REF, VBJ_EXACT, &pipe), VB_OK);
    /* A pore through a barrel of eight rings and a shell's cavities. */
    vb_sphere_set *s = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    vbc_pore_request req;
    memset(&req, 0, sizeof req);
    req.enabled = 1;
    req.sweep.step = 0.25;
    vbc_options opt = {2.0, 0.0, 1.0, 1, &req};
    vbc_frame one, four;
    memset(&one, 0, sizeof one);
    memset(&four, 0, sizeof four);
    frame(ctx, pipe, s, &opt, 1, &one);
    frame(ctx, pipe, s, &opt, 4, &four);
    CHECK(one.result.nchannels >= 2);
    CHECK_INT(one.result.pore.present, 1);
    pore_lining_check(&one.result, s, opt.lining_tol);
    same_result(&one.result, &four.result);
    CHECK(memcmp(&one.axis, &four.axis, sizeof one.axis) == 0);
    /* The clocks: one after the other nothing beside; at four threads the
     * whole analysis within the pore stage's span. */
    CHECK(one.ms_beside == 0.0);
    CHECK(four.ms_beside == four.ms_analysis && four.ms_analysis > 0.0);
    CHECK(four.ms_pore >= four.ms_analysis);
    /* VORBALL_ANALYSIS_BESIDE=0: one after the other at four threads too. */
    setenv("VORBALL_ANALYSIS_BESIDE", "0", 1);
    vbc_frame off;
    memset(&off, 0, sizeof off);
    set_threads(4);
    CHECK_INT(vbc_analysis_beside(), 0);
    vbc_grid g;
    CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 64, 3, &g), VB_OK);
    CHECK_INT(vbc_frame_masks(ctx, pipe, &g, s, 1.4, 0, &opt, &off), VB_OK);
    CHECK_INT(vbc_frame_beside(&opt, &off), 0);
    CHECK_INT(vbc_frame_analyse(ctx, s, &opt, &off), VB_OK);
    CHECK(off.ms_beside == 0.0);
    same_result(&one.result, &off.result);
    vbc_frame_free(&off);
    unsetenv("VORBALL_ANALYSIS_BESIDE");
    /* Run again on the frame's buffers (--repeat): the same again. The
     * result is the caller's to free before it is filled again (the CLI's
     * repeat makes the masks again first, which frees it). */
    vbc_result_free(&four.result);
    memset(&four.result, 0, sizeof four.result);
    CHECK_INT(vbc_frame_analyse(ctx, s, &opt, &four), VB_OK);
    same_result(&one.result, &four.result);

    /* A late analysis: the stage waits for it (the refinement, the pore's
     * place in the table, the ranking), on one thread and on four. */
    for (int th = 1; th <= 4; th += 3) {
        vbc_result res;
        late_stage(ctx, &one, s, &opt, &req, th, &res);
        same_result(&one.result, &res);
        vbc_result_free(&res);
    }
    /* Along an axis given, the search never reads the channels: only the
     * steps after the sweep wait (the pore reported as swept, unjudged). */
    vbc_pore_request given = req;
    given.have_axis = 1;
    given.u[2] = 1.0;
    vbc_result seq, res;
    late_stage(ctx, &one, s, &opt, &given, 1, &seq);
    CHECK_INT(seq.pore.present, 1);
    CHECK(seq.nchannels >= 2);
    late_stage(ctx, &one, s, &opt, &given, 4, &res);
    same_result(&seq, &res);
    vbc_result_free(&res);
    vbc_result_free(&seq);

    /* A failure of what fills res: its status, on one thread (first) and
     * on four (beside the search); the refinement and the ranking skipped
     * (res as it left it: empty here). */
    for (int th = 1; th <= 4; th += 3) {
        set_threads(th);
        vbc_pore_before B = {fail_enomem, NULL};
        vbc_result res;
        memset(&res, 0, sizeof res);
        vbc_pore_ms ms;
        CHECK_INT(vbc_pore_stage_after(ctx, &one.grid, one.out.flags, s, &req, NULL, 1.0, &res, NULL,
                                       &ms, &B),
                  VB_ENOMEM);
        CHECK_INT(res.nchannels, 0);
        CHECK_INT(res.pore.present, 0);
        CHECK(ms.refine == 0.0);
        vbc_result_free(&res);
    }
    vbc_frame_free(&one);
    vbc_frame_free(&four);
    vb_spheres_free(s);
    vbc_pipe_close(pipe);
    vb_close(ctx);
    VB_TEST_END();
}
