/* The channels handle over every frame of a source (vb_channels.h): the
 * frame loop of `vorball channels` (read, select, run, write each frame;
 * frames in flight on a reader thread, vbc_ahead.h, or dealt to processes
 * in rounds through the caller's hooks), the heads and the tails of its
 * outputs. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "channels_handle.h"
#include "vb_diag.h"
#include "vb_output.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"
#include "vbc_flight.h"
#include "vbc_page.h"
#include "vbc_paths.h"

static FILE *frame_stream(const vb_channels_io *io, int k)
{
    return io->stream ? io->stream(io->user, k) : io->sink[k];
}

static int check_output(vb_ctx *ctx, const vb_channels_io *io, const char *path)
{
    return io->check_output ? io->check_output(ctx, path) : VB_OK;
}

static FILE *open_output(vb_ctx *ctx, const vb_channels_io *io, const char *path)
{
    return io->open_output ? io->open_output(ctx, path) : vb_output_open(ctx, path);
}

static int close_output(vb_ctx *ctx, const vb_channels_io *io, FILE *f, const char *path)
{
    return io->close_output ? io->close_output(ctx, f, path) : vb_output_commit(ctx, f);
}

void vb_channels_write_head(const vb_channels *ch, const vb_channels_io *io, const char *options)
{
    const vbc_channels_config *c = &ch->cfg;
    FILE *table = io->sink[VB_CHANNELS_SINK_TABLE], *stats = io->sink[VB_CHANNELS_SINK_STATS];
    if (table && c->json)
        vbc_write_json_begin_prov(table, options, c->traj ? c->traj : io->input, c->probe, c->grid,
                                  vb_channels_device_name(ch));
    else if (table)
        vbc_write_csv_header(table);
    if (stats)
        vbc_write_stats_header(stats);
    if (io->profile)
        vbc_write_profile_header(io->profile);
}

/* The per-frame volume name: '%d' replaced by the frame index. */
static int volume_name(const char *pattern, long frame, char *buf, size_t len)
{
    const char *p = strstr(pattern, "%d");
    if (!p)
        return snprintf(buf, len, "%s", pattern) < (int)len ? 0 : -1;
    int n = snprintf(buf, len, "%.*s%ld%s", (int)(p - pattern), pattern, frame, p + 2);
    return n >= 0 && n < (int)len ? 0 : -1;
}

/* Adds the frame to the results page (--html), made on the first frame. */
static int page_frame(vb_ctx *ctx, vb_channels *ch, const vb_channels_io *io,
                      const vb_sphere_set *s, long index, int model, const vbc_result *res)
{
    const vbc_channels_config *c = &ch->cfg;
    char label[64];
    if (!ch->page) {
        char title[512];
        snprintf(title, sizeof title, "vorball channels %s%s%s", io->input, c->traj ? " + " : "",
                 c->traj ? c->traj : "");
        if (!(ch->page = vb_page_new(ctx, title, s)))
            return vb_errcode(ctx);
    }
    snprintf(label, sizeof label, "frame %ld (model %d)", index, model);
    return vbc_page_add(ch->page, label, s, res);
}

/* The first frame as PDB beside the PyMOL script (vbc_pymol_needs_frame0). */
static int write_frame0(vb_ctx *ctx, const vb_channels_io *io, const char *path,
                        const vb_sphere_set *s)
{
    FILE *f = open_output(ctx, io, path);
    if (!f)
        return vb_errcode(ctx);
    vbc_write_molecule_pdb(f, s);
    return close_output(ctx, io, f, path);
}

/* The eight pipeline stages of the first frame (--png), kept in the
 * handle for the caller to write. */
static int make_stages(vb_ctx *ctx, vb_channels *ch, const vb_sphere_set *s)
{
    const vbc_channels_config *c = &ch->cfg;
    vbc_options o = c->opt;
    o.pore = NULL;
    vbc_image_free(&ch->stages);
    memset(&ch->stages, 0, sizeof ch->stages);
    return vbc_stages_render(ctx, ch->pipe, s, c->probe, c->grid, c->png_axis, &o, &ch->stages);
}

/* Runs one frame (vbc_run_frame; with `front`, the back half of a frame
 * whose front half the reader ran: vbc_run_back) and writes its outputs;
 * `first`: it is the first frame of the selection (volume, picture).
 * ms_read: the frame's reading (negative: from t_read to now). */
static int do_frame(vb_ctx *ctx, vb_channels *ch, const vb_channels_io *io, long index,
                    int model, int first, const vb_sphere_set *s0, double t_read,
                    double cpu_read, double ms_read, vbc_run_out *front)
{
    vbc_run_out o;
    double t_run = vb_now();
    int rc;
    if (front) {
        o = *front;
        rc = vbc_run_back(ctx, &ch->run, &o);
    } else
        rc = vbc_run_frame(ctx, &ch->run, s0, index, model, first, &o);
    if (rc != VB_OK)
        return rc;
    o.fi.ms_read = ms_read >= 0.0 ? ms_read : 1e3 * (t_run - t_read); /* the JSON's clocks */
    o.fi.t_start = t_read;
    o.fi.cpu_start = cpu_read;
    const vbc_channels_config *c = &ch->cfg;
    const vbc_result *res = &o.F.result;
    FILE *table = frame_stream(io, VB_CHANNELS_SINK_TABLE), *f;
    if (table && c->json)
        vbc_write_json_frame(table, first, &o.fi, &o.g, o.s, res);
    else if (table)
        vbc_write_csv_rows(table, &o.fi, &o.g, o.s, res);
    if ((c->stats || c->stats_stderr) && (f = frame_stream(io, VB_CHANNELS_SINK_STATS)))
        vbc_write_stats_row(f, &o.fi, &o.g, res);
    if (c->centrelines && (f = frame_stream(io, VB_CHANNELS_SINK_CENTRELINES)))
        vbc_write_centrelines_pdb(f, model, res);
    rc = io->frame_done ? io->frame_done(ctx, io->user) : VB_OK;
    if (rc == VB_OK && io->profile)
        vbc_write_profile_rows(io->profile, &o.fi, o.s, res);
    if (rc == VB_OK && c->html)
        rc = page_frame(ctx, ch, io, o.s, index, model, res);
    if (rc == VB_OK && first && io->first_frame)
        rc = io->first_frame(ctx, io->user, s0, o.s);
    if (rc == VB_OK && c->volume && (strstr(c->volume, "%d") || first)) {
        char name[4096];
        if (volume_name(c->volume, index, name, sizeof name) != 0)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "volume file name too long");
        else if ((rc = check_output(ctx, io, name)) == VB_OK)
            rc = vbc_write_volume(ctx, name, &o.g, o.F.out.flags, c->volume_bit);
    }
    if (rc == VB_OK && c->png && first)
        rc = make_stages(ctx, ch, o.s);
    if (rc == VB_OK && first && ch->frame0[0])
        rc = write_frame0(ctx, io, ch->frame0, s0);
    vbc_run_frame_done(&ch->run, first, &o);
    return rc;
}

/* The end of a round: the status every process agrees on. */
static int round_end(vb_ctx *ctx, const vb_channels_io *io, int rc, long j0, long j1)
{
    return io->round_end ? io->round_end(ctx, io->user, rc, j0, j1) : rc;
}

static void status(const vb_channels *ch, const vb_channels_io *io, long index)
{
    if (io->status)
        io->status(io->user, index, ch->run.frames_done, vb_channels_device_name(ch));
}

/* The frames of F in rounds: every process reads every frame, runs the
 * selected ones that are its own, and the round's end writes them in
 * frame order. *selected gets the frames selected. */
static int run_rounds(vb_ctx *ctx, vb_channels *ch, vb_frame_source *F, const vb_channels_io *io,
                      long *selected)
{
    const vbc_channels_config *c = &ch->cfg;
    long index = 0, j = 0, j0 = 0, round = io->round_end && io->round > 0 ? io->round : LONG_MAX;
    int rc = VB_OK, end = 0;
    while (rc == VB_OK && !end) {
        int frc = VB_OK;
        while (frc == VB_OK && j - j0 < round) {
            if (c->f1 >= 0 && index >= c->f1) {
                end = 1;
                break;
            }
            vb_sphere_set *s = NULL;
            double t_read = vb_now(), cpu_read = vb_cpu_now();
            int model, quiet = io->quiet_read ? vb_set_verbosity(ctx, 0) : -1;
            frc = vb_frame_source_next(ctx, F, &s, &model);
            if (quiet >= 0)
                vb_set_verbosity(ctx, quiet);
            if (frc != VB_OK || !s) {
                end = 1;
                break;
            }
            status(ch, io, index);
            if (index >= c->f0 && (index - c->f0) % c->fstep == 0) {
                if (!io->mine || io->mine(io->user, j))
                    frc = do_frame(ctx, ch, io, index, model, j == 0, s, t_read, cpu_read, -1.0,
                                   NULL);
                else if (j == 0 && c->pore.enabled && !c->pore.have_axis)
                    frc = vbc_run_axis(ctx, &ch->run, s, index);
                j++;
            }
            vb_spheres_free(s);
            index++;
        }
        /* A process that failed comes here at once; the others at the end
         * of the round: the same collective, so every one stops together. */
        rc = round_end(ctx, io, frc, j0, j);
        j0 = j;
    }
    *selected = j;
    return rc;
}

/* The frames in flight on one process: the reader (vbc_ahead.h: a thread
 * `depth` frames ahead, or with depth 0 this thread) reads the frames and
 * runs their front half (the pipe), the window (vbc_flight.h) analyses up
 * to its width of them at once, and this thread takes the oldest out, runs
 * its back half and writes it: the bytes and the lines of run_rounds. */
typedef struct flight {
    vbc_ahead *ah;
    vbc_flight *fl;
    int depth, width, width_given, fitted;
    size_t budget;
    int end, tail_rc;       /* the reader's end met, its status */
    vbc_held *tail;         /* and what it said after the last frame */
} flight;

/* The window's width fitted to the memory budget on the first frame f
 * (vbc_flight_fit): E127 when even the width asked for does not fit. */
static int flight_fit(vb_ctx *ctx, flight *S, const vbc_ahead_frame *f)
{
    int width;
    size_t per = vbc_flight_frame_bytes(&f->o, f->s0);
    int rc = vbc_flight_fit(ctx, S->width, S->width_given, S->budget, per,
                            S->depth > 0 ? 2 * S->depth + 1 : 0, &width);
    if (rc == VB_OK)
        vbc_flight_shrink(S->fl, width);
    S->fitted = 1;
    return rc;
}

/* The next frame to write into *f (*have = 1): the window filled from the
 * reader while it has room, then its oldest frame out. At the end *have = 0,
 * after the reader's last lines and its failure are said. */
static int flight_next(vb_ctx *ctx, vb_channels *ch, const vb_channels_io *io, flight *S,
                       vbc_ahead_frame *f, int *have)
{
    *have = 0;
    while (!S->end && vbc_flight_room(S->fl)) {
        vbc_ahead_frame g;
        int got, rc = vbc_ahead_next(S->ah, &g, &got);
        if (!got) {
            S->end = 1;
            S->tail = g.held;
            S->tail_rc = rc;
            break;
        }
        if (!S->fitted && (rc = flight_fit(ctx, S, &g)) != VB_OK) {
            vbc_held_free(g.held);
            vbc_run_front_drop(&g.o);
            vb_spheres_free(g.s0);
            return rc;
        }
        status(ch, io, g.index);
        if ((rc = vbc_flight_push(ctx, S->fl, &g)) != VB_OK)
            return rc;
    }
    if (vbc_flight_count(S->fl) > 0) {
        int rc = vbc_flight_pop(ctx, S->fl, f);
        *have = rc == VB_OK;
        return rc;
    }
    int rc = vbc_held_replay(ctx, S->tail, S->tail_rc);
    vbc_held_free(S->tail);
    S->tail = NULL;
    return rc;
}

static int run_flight(vb_ctx *ctx, vb_channels *ch, vb_frame_source *F, const vb_channels_io *io,
                      long *selected, int depth)
{
    flight S;
    memset(&S, 0, sizeof S);
    S.depth = depth;
    S.width = vbc_flight_width(&S.width_given);
    int budget_given;
    S.budget = vbc_flight_budget(&budget_given);
    /* VORBALL_DEVICE_PATHS runs the analysis on the pipe's engine: it stays
     * with the pipe, on the reader. */
    int front = vbc_paths_mode() ? VBC_FRONT_ANALYSE : VBC_FRONT_MASKS;
    long j = 0, j0 = 0, round = io->round_end && io->round > 0 ? io->round : LONG_MAX;
    int rc = vbc_ahead_open(ctx, &ch->run, F, depth, front, &S.ah);
    if (rc == VB_OK)
        rc = vbc_flight_open(ctx, &ch->run, S.width, &S.fl);
    int end = rc != VB_OK;
    while (rc == VB_OK && !end) {
        int frc = VB_OK;
        while (frc == VB_OK && j - j0 < round) {
            vbc_ahead_frame f;
            int have;
            frc = flight_next(ctx, ch, io, &S, &f, &have);
            if (frc != VB_OK || !have) {
                end = 1;
                break;
            }
            frc = do_frame(ctx, ch, io, f.index, f.o.fi.model, f.j == 0, f.s0, f.t_read,
                           f.cpu_read, f.ms_read, &f.o);
            vb_spheres_free(f.s0);
            j++;
        }
        rc = round_end(ctx, io, frc, j0, j);
        j0 = j;
    }
    /* The reader first: it may be running a front on the pipe. */
    vbc_ahead_close(ctx, S.ah);
    vbc_flight_close(ctx, S.fl);
    vbc_held_free(S.tail);
    *selected = j;
    return rc;
}

int vb_channels_run_frames(vb_ctx *ctx, vb_channels *ch, vb_frame_source *F,
                           const vb_channels_io *io, long *selected)
{
    vbc_channels_config *c = &ch->cfg;
    *selected = 0;
    vb_channels_drop_run(ch);
    if (!ch->pipe)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "channels: no engine (vb_channels_open)");
    ch->frame0[0] = '\0';
    if (c->pymol && vbc_pymol_needs_frame0(io->input, c->traj) &&
        snprintf(ch->frame0, sizeof ch->frame0, "%s.frame0.pdb", c->pymol) >= (int)sizeof ch->frame0)
        ch->frame0[0] = '\0'; /* a name too long for a file anyway: the input is named */
    vbc_run_init(&ch->run, c, ch->pipe, io->input);
    ch->run_live = 1;
    /* --frames a:b:step with an end: the number of frames is known. */
    if (c->f1 > c->f0 && c->fstep > 0)
        ch->run.frames_total = (c->f1 - c->f0 + c->fstep - 1) / c->fstep;
    ch->t_frames = vb_now();
    ch->cpu_frames = vb_cpu_now();
    /* Frames in flight on one process; the picture (--png) runs the pipe
     * on this thread, so it keeps the loop that reads frame by frame, as
     * does one frame at a time without a reader thread (the reference). */
    int depth = vbc_ahead_depth(), given, rc;
    if (!io->mine && !c->png && (depth > 0 || vbc_flight_width(&given) > 1))
        rc = run_flight(ctx, ch, F, io, selected, depth);
    else
        rc = run_rounds(ctx, ch, F, io, selected);
    if (rc == VB_OK && *selected == 0)
        /* Of a trajectory, the frames are the trajectory's (a DCD cut
         * inside its first frame has none): name it, not the topology. */
        rc = vb_error(ctx, VB_EINPUT_MODEL, c->traj ? c->traj : io->input, 0,
                      c->traj ? "no whole frame selected from the trajectory (--frames / --model)"
                              : "no frame selected (--frames / --model)");
    return rc;
}

int vb_channels_finish(vb_ctx *ctx, vb_channels *ch, const vb_channels_io *io, int writer,
                       long selected)
{
    const vbc_channels_config *c = &ch->cfg;
    int rc = VB_OK;
    if (writer && c->volume && !strstr(c->volume, "%d") && selected > 1)
        vb_warn(ctx, VB_W_VOLUME_FIRST_FRAME, c->volume, 0, "volume holds the first of %ld frames "
                "('%%d' in the name writes one per frame)", selected);
    vbc_run_report_left_out(ctx, &ch->run);
    FILE *table = io->sink[VB_CHANNELS_SINK_TABLE], *cl = io->sink[VB_CHANNELS_SINK_CENTRELINES];
    if (writer && c->json && table)
        vbc_write_json_end_clock(table, selected, 1e3 * (vb_now() - ch->t_frames),
                                 1e3 * (vb_cpu_now() - ch->cpu_frames));
    if (writer && cl)
        vbc_write_centrelines_conect(cl, &ch->run.first);
    if (writer && c->pymol) {
        FILE *pml = open_output(ctx, io, c->pymol);
        if (!pml)
            return vb_errcode(ctx);
        vbc_write_pymol(pml, c->pymol, ch->frame0[0] ? ch->frame0 : io->input, c->centrelines,
                        c->traj);
        rc = close_output(ctx, io, pml, c->pymol);
    }
    if (rc == VB_OK && c->occupancy)
        rc = vbc_write_volume_f32(ctx, c->occupancy, &ch->run.fixed, ch->run.occupancy,
                                  1.0 / (double)ch->run.frames_done);
    if (rc == VB_OK && c->html)
        rc = vb_page_write(ch->page, c->html);
    return rc;
}

void vb_channels_totals_get(const vb_channels *ch, vb_channels_totals *t)
{
    t->frames = ch->run_live ? ch->run.frames_done : 0;
    t->repeat = ch->cfg.repeat;
    t->ms_total = ch->run_live ? ch->run.sum_total : 0;
    t->ms_masks = ch->run_live ? ch->run.sum_masks : 0;
}

int vb_channels_stages(const vb_channels *ch, uint32_t *w, uint32_t *h, const uint8_t **rgb)
{
    if (!ch->stages.rgb)
        return -1;
    *w = ch->stages.w;
    *h = ch->stages.h;
    *rgb = ch->stages.rgb;
    return 0;
}

size_t vb_channels_series(const vb_channels *ch, size_t k, long *frame, double *rmin, double *s)
{
    const vbc_series *S = &ch->run.series;
    if (!ch->run_live)
        return 0;
    if (k < S->n) {
        if (frame)
            *frame = S->frame[k];
        if (rmin)
            *rmin = S->rmin[k];
        if (s)
            *s = S->s[k];
    }
    return S->n;
}
