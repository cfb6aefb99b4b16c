/* `vorball channels`: channels and cavities of a molecule or of every frame
 * of a trajectory (multi-model PDB/PQR/mmCIF/GRO, or a DCD, XTC or TRR with
 * its topology),
 * by the discrete-Voronoi pipeline of the Facet-JFA paper (Sec. 4) on
 * OpenCL or its C reference, with components, centrelines, bottlenecks and
 * lining residues. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "channels_plot.h"
#include "jfa_png.h"
#include "progress.h"
#include "vb_default.h"
#include "vb_diag.h"
#include "vb_frames.h"
#include "vb_world.h"
#include "vbc_page.h"
#include "vbc_ahead.h"
#include "vbc_run.h"
#include "frame_rounds.h"

static const char *cmd = "channels";

typedef struct {
    const char *input;
    vbc_channels_config c; /* every option of the command but the input's (vbc_channels_config.h) */
    vb_cli_input_opts in;
} ch_args;

void vb_cmd_channels_help(FILE *f)
{
    fprintf(f,
            "usage: vorball channels [options] INPUT|-\n"
            "\n"
            "Channels (Voronoi edges inside the molecule that reach its surface) and cavities\n"
            "(those that do not) of every frame of INPUT: PDB, PQR, mmCIF, GRO or XYZR (gzip\n"
            "or bzip2 compressed too); several MODELs or GRO frames are a trajectory. With\n"
            "--traj, INPUT is the topology (PDB, GRO, mmCIF, PQR or a CHARMM/NAMD PSF) of a\n"
            "DCD, XTC or TRR trajectory.\n"
            "Per frame, on OpenCL (or its C reference, --device ref): the exact discrete\n"
            "Voronoi labels of the atom centres on an n^3 grid (--jfa), Voronoi edge voxels,\n"
            "atomic mask (balls r + probe), molecular mask (rays along x, y, z), interior =\n"
            "atomic xor molecular, channels = edges and interior; then components,\n"
            "centrelines (widest path between the openings) with the clearance radius\n"
            "(distance to the nearest atom surface) at each point, bottleneck and lining\n"
            "residues.\n"
            "\n"
            "options:\n");
    vbc_channels_help(f, VBC_SECT_MAIN);
    fprintf(f,
            "\n"
            "the pore (HOLE-style, on by default): one point per plane normal to an axis, each\n"
            "the centre of the largest sphere in its plane that overlaps no atom; it passes\n"
            "constrictions narrower than the probe; the probe's molecular surface ends it.\n");
    vbc_channels_help(f, VBC_SECT_PORE);
    fprintf(f,
            "Under mpirun -np N (a build with VORBALL_WITH_MPI) the selected frames are dealt\n"
            "round-robin over the ranks (each reads INPUT), and rank 0 writes the tables in\n"
            "frame order: the same bytes as one process (timings aside). Volumes and the\n"
            "picture are written by the rank that ran their frame. Every rank finds the\n"
            "first frame's pore axis itself; --profile, --plot, --fixed-grid and\n"
            "--occupancy run on one process only (E151).\n"
            "\n"
            "The channel table (CSV), one row per pore, channel or cavity of each frame:\n"
            "%s"
            "\n",
            vbc_table_columns_help());
    vb_cli_input_help(f);
}

static int parse_args(int argc, char **argv, ch_args *A)
{
    memset(A, 0, sizeof *A);
    vb_cli_input_defaults(&A->in);
    vbc_channels_defaults(&A->c);
    char err[512];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int r = vb_cli_input_option(&A->in, argc, argv, &i);
        if (r < 0)
            return -1;
        if (r > 0)
            continue;
        if (a[0] != '-' || strcmp(a, "-") == 0) {
            if (A->input)
                return vb_cli_usage_error(cmd, "one input only ('%s' and '%s')", A->input, a), -1;
            A->input = a;
            continue;
        }
        /* Anything not in the table is not an option of this command (a
         * typo is never taken for a value). */
        const vbc_opt_spec *o = vbc_channels_option(a);
        if (!o)
            return vb_cli_usage_error(cmd, "unknown option '%s' (see --help)", a), -1;
        const char *v = NULL;
        if (o->type != VBC_OPT_FLAG) {
            if (i + 1 >= argc)
                return vb_cli_usage_error(cmd, "%s needs a value", a), -1;
            v = argv[++i];
        }
        if (vbc_channels_set(&A->c, o, v, err, sizeof err) != 0)
            return vb_cli_usage_error(cmd, "%s", err), -1;
    }
    if (!A->input)
        return vb_cli_usage_error(cmd, "no input (see --help)"), -1;
    if (A->c.traj && strcmp(A->input, "-") == 0)
        return vb_cli_usage_error(cmd, "the trajectory's topology must be a file"), -1;
    if (vbc_channels_check(&A->c, err, sizeof err) != 0)
        return vb_cli_usage_error(cmd, "%s", err), -1;
    return 0;
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

/* Where a frame's outputs go: the streams of its round (frame_rounds.h),
 * table, statistics and centrelines, in the sinks' order. */
enum { SINK_TABLE, SINK_STATS, SINK_CL };

typedef struct {
    vb_cli_rounds *rounds;
    int stats, cl;          /* those sinks are wanted */
    FILE *profile;          /* --profile (one process only) */
    vbc_run run;            /* the library's state over the frames (vbc_run.h) */
    char frame0[4200];      /* --pymol: the first frame as PDB, when PyMOL needs it; else "" */
    vb_page *page;          /* --html: made from the first frame's atoms */
} sinks;

/* Adds the frame to the results page (--html), made on the first frame. */
static int page_frame(vb_ctx *ctx, const ch_args *A, sinks *S, const vb_sphere_set *s, long index,
                      int model, const vbc_result *res)
{
    char label[64];
    if (!S->page) {
        char title[512];
        snprintf(title, sizeof title, "vorball channels %s%s%s", A->input, A->c.traj ? " + " : "",
                 A->c.traj ? A->c.traj : "");
        if (!(S->page = vb_page_new(ctx, title, s)))
            return vb_errcode(ctx);
    }
    snprintf(label, sizeof label, "frame %ld (model %d)", index, model);
    return vbc_page_add(S->page, label, s, res);
}

/* The first frame as PDB beside the PyMOL script (vbc_pymol_needs_frame0). */
static int write_frame0(vb_ctx *ctx, const char *path, const vb_sphere_set *s)
{
    FILE *f = vb_cli_open_output(ctx, path);
    if (!f)
        return vb_errcode(ctx);
    vbc_write_molecule_pdb(f, s);
    return vb_cli_close_output(ctx, f, path);
}

/* Writes the eight pipeline stages of the first frame (--png). */
static int write_stages(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, const vb_sphere_set *s)
{
    vbc_image img;
    vbc_options o = A->c.opt;
    o.pore = NULL;
    int rc = vbc_stages_render(ctx, pipe, s, A->c.probe, A->c.grid, A->c.png_axis, &o, &img);
    if (rc == VB_OK)
        rc = vb_png_write_rgb(ctx, A->c.png, img.w, img.h, img.rgb);
    vbc_image_free(&img);
    return rc;
}

/* Runs one frame (vbc_run_frame; with `front`, the back half of a frame
 * whose front half the reader ran: vbc_run_back) and writes its outputs;
 * `first`: it is the first frame of the selection (volume, picture). Under
 * MPI the options that need every frame in one process are refused before. */
static int do_frame(vb_ctx *ctx, ch_args *A, vbc_pipe *pipe, long index, int model, int first,
                    const vb_sphere_set *s0, double t_read, double cpu_read, sinks *S,
                    vbc_run_out *front)
{
    vbc_run_out o;
    double t_run = vb_now();
    int rc;
    if (front) {
        o = *front;
        rc = vbc_run_back(ctx, &S->run, &o);
    } else
        rc = vbc_run_frame(ctx, &S->run, s0, index, model, first, &o);
    if (rc != VB_OK)
        return rc;
    o.fi.ms_read = 1e3 * (t_run - t_read); /* the JSON's clocks: from the reading on */
    o.fi.t_start = t_read;
    o.fi.cpu_start = cpu_read;
    const vbc_channels_config *c = &A->c;
    const vbc_result *res = &o.F.result;
    FILE *table = vb_cli_rounds_stream(S->rounds, SINK_TABLE);
    if (c->json)
        vbc_write_json_frame(table, first, &o.fi, &o.g, o.s, res);
    else
        vbc_write_csv_rows(table, &o.fi, &o.g, o.s, res);
    if (S->stats)
        vbc_write_stats_row(vb_cli_rounds_stream(S->rounds, SINK_STATS), &o.fi, &o.g, res);
    if (S->cl)
        vbc_write_centrelines_pdb(vb_cli_rounds_stream(S->rounds, SINK_CL), model, res);
    rc = vb_cli_rounds_frame_done(ctx, S->rounds);
    if (rc == VB_OK && S->profile)
        vbc_write_profile_rows(S->profile, &o.fi, o.s, res);
    if (rc == VB_OK && c->html)
        rc = page_frame(ctx, A, S, o.s, index, model, res);
    /* --atoms: the atoms the analysis used (after --ignore and --membrane),
     * whose ids the lining lists give. */
    if (rc == VB_OK && first && A->in.atoms_path)
        rc = vb_cli_write_atoms(ctx, A->in.atoms_path, o.s);
    if (rc == VB_OK && c->volume && (strstr(c->volume, "%d") || first)) {
        char name[4096];
        if (volume_name(c->volume, index, name, sizeof name) != 0)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "volume file name too long");
        else if ((rc = vb_cli_check_output(ctx, name)) == VB_OK)
            rc = vbc_write_volume(ctx, name, &o.g, o.F.out.flags, c->volume_bit);
    }
    if (rc == VB_OK && c->png && first)
        rc = write_stages(ctx, A, pipe, o.s);
    if (rc == VB_OK && first && S->frame0[0])
        rc = write_frame0(ctx, S->frame0, s0);
    vbc_run_frame_done(&S->run, first, &o);
    return rc;
}

/* The frames of F in rounds (frame_rounds.h): every rank reads every frame,
 * runs the selected ones that are its own, and rank 0 writes each round's
 * outputs to out[] in frame order. *selected gets the frames selected.
 * Returns the status agreed by every rank. */
static int run_frames(vb_ctx *ctx, ch_args *A, vbc_pipe *pipe, vb_frame_source *F,
                      sinks *S, FILE *out[VB_CLI_ROUND_SINKS], long *selected)
{
    long index = 0, j = 0, j0 = 0, round = vb_cli_rounds_length();
    int rc = VB_OK, end = 0;
    while (rc == VB_OK && !end) {
        int frc = VB_OK;
        while (frc == VB_OK && j < j0 + round) {
            if (A->c.f1 >= 0 && index >= A->c.f1) {
                end = 1;
                break;
            }
            vb_sphere_set *s = NULL;
            double t_read = vb_now(), cpu_read = vbc_cpu_now();
            int model, quiet = vb_world_quiet(ctx);
            frc = vb_frame_source_next(ctx, F, &s, &model);
            vb_world_loud(ctx, quiet);
            if (frc != VB_OK || !s) {
                end = 1;
                break;
            }
            vb_cli_status_set("channels: frame %ld (%ld analysed) on %s", index, S->run.frames_done,
                              vbc_pipe_device_name(pipe));
            if (index >= A->c.f0 && (index - A->c.f0) % A->c.fstep == 0) {
                if (vb_cli_rounds_mine(j))
                    frc = do_frame(ctx, A, pipe, index, model, j == 0, s, t_read, cpu_read, S, NULL);
                else if (j == 0 && A->c.pore.enabled && !A->c.pore.have_axis)
                    frc = vbc_run_axis(ctx, &S->run, s, index);
                j++;
            }
            vb_spheres_free(s);
            index++;
        }
        /* A rank that failed comes here at once; the others at the end of
         * the round: the same collective, so every rank stops together. */
        rc = vb_cli_rounds_flush(ctx, S->rounds, frc, j0, j, out);
        j0 = j;
    }
    *selected = j;
    return rc;
}

/* run_frames with the frames in flight (vbc_ahead.h; one process): the
 * reader thread reads and runs the front half of the next frames while
 * this thread runs the back half of the current one and writes it; the
 * same bytes. A frame's "read" clock is the time this thread waited for
 * the reader. */
static int run_frames_ahead(vb_ctx *ctx, ch_args *A, vbc_pipe *pipe, vb_frame_source *F,
                            sinks *S, FILE *out[VB_CLI_ROUND_SINKS], long *selected, int depth)
{
    vbc_ahead *ah = NULL;
    long j = 0, j0 = 0, round = vb_cli_rounds_length();
    int rc = vbc_ahead_open(ctx, &S->run, F, depth, &ah), end = rc != VB_OK;
    while (rc == VB_OK && !end) {
        int frc = VB_OK;
        while (frc == VB_OK && j < j0 + round) {
            vbc_ahead_frame f;
            int have;
            double t_read = vb_now(), cpu_read = vbc_cpu_now();
            frc = vbc_ahead_next(ctx, ah, &f, &have);
            if (frc != VB_OK || !have) {
                end = 1;
                break;
            }
            vb_cli_status_set("channels: frame %ld (%ld analysed) on %s", f.index,
                              S->run.frames_done, vbc_pipe_device_name(pipe));
            frc = do_frame(ctx, A, pipe, f.index, f.o.fi.model, f.j == 0, f.s0, t_read, cpu_read,
                           S, &f.o);
            vb_spheres_free(f.s0);
            j++;
        }
        rc = vb_cli_rounds_flush(ctx, S->rounds, frc, j0, j, out);
        j0 = j;
    }
    vbc_ahead_close(ctx, ah);
    *selected = j;
    return rc;
}

/* The closing line on stderr: this process's frames, or under MPI every
 * rank's (per-run times are means over the ranks' runs, and the frame rate
 * of the whole job is on the wall clock). */
static int report(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, const sinks *S, double wall)
{
    double sum[2] = {S->run.sum_total, S->run.sum_masks};
    uint64_t frames = (uint64_t)S->run.frames_done;
    int rc = vb_world_sum_u64(ctx, &frames, 1);
    if (rc == VB_OK)
        rc = vb_world_sum_double(ctx, sum, 2);
    if (rc != VB_OK || vb_world_rank() != 0)
        return rc;
    long runs = (long)frames * A->c.repeat;
    const char *device = vbc_pipe_device_name(pipe); /* where the last frame ran */
    vb_info(ctx, "channels: %ld frames on %s in %.3f s", (long)frames, device, wall);
    if (vb_world_size() < 2)
        fprintf(stderr, "vorball channels: %ld frame(s), %ld run(s) on %s: %.3f ms/run "
                        "(%.1f FPS), of which GPU stages %.3f ms (%.1f FPS)\n",
                (long)frames, runs, device, sum[0] / runs, 1e3 * runs / sum[0], sum[1] / runs,
                1e3 * runs / sum[1]);
    else
        fprintf(stderr, "vorball channels: %ld frame(s), %ld run(s) on %d ranks (rank 0: %s): "
                        "%.3f ms/run, of which GPU stages %.3f ms; %.1f frames/s in all "
                        "(%.3f s wall)\n",
                (long)frames, runs, vb_world_size(), device, sum[0] / runs, sum[1] / runs,
                frames / wall, wall);
    return VB_OK;
}

/* Rank 0's output files: table, statistics, centrelines (the sinks' order);
 * --stats (no file) sends the statistics to stderr. */
static int open_outputs(vb_ctx *ctx, const ch_args *A, FILE *out[VB_CLI_ROUND_SINKS])
{
    const char *path[VB_CLI_ROUND_SINKS] = {A->c.out, A->c.stats, A->c.centrelines};
    if (A->c.stats_stderr)
        out[SINK_STATS] = stderr;
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (!out[k] && (k == SINK_TABLE || path[k]) && !(out[k] = vb_cli_open_output(ctx, path[k])))
            return vb_errcode(ctx);
    return VB_OK;
}

/* Closes rank 0's outputs; after a failure (of any rank: rc is agreed)
 * they are discarded (vb_cli_finish_output), so no table of part of the
 * frames is left behind. */
static int close_outputs(vb_ctx *ctx, const ch_args *A, FILE *out[VB_CLI_ROUND_SINKS], int rc)
{
    const char *path[VB_CLI_ROUND_SINKS] = {A->c.out, A->c.stats, A->c.centrelines};
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (out[k] == stderr)
            fflush(stderr);
        else if (out[k])
            rc = vb_cli_finish_output(ctx, out[k], path[k], rc);
    return rc;
}

int vb_cmd_channels(int argc, char **argv)
{
    ch_args A;
    int pr = parse_args(argc, argv, &A);
    if (pr != 0)
        return VB_EXIT_USAGE;
    int code = vb_world_check_input(cmd, A.input);
    if (code)
        return code;
    /* The profile, plot, fixed grid and occupancy gather every frame in one
     * process (the pore axis of the first frame is found by every rank:
     * vbc_run_axis). */
    if (vb_world_size() > 1 &&
        (A.c.profile || A.c.plot || A.c.fixed_grid || A.c.occupancy || A.c.html || A.in.atoms_path)) {
        if (vb_world_rank() == 0)
            fprintf(stderr, "vorball channels: E%d: --profile, --plot, --fixed-grid, "
                            "--occupancy, --html and --atoms run on one process only (not under MPI)\n",
                    VB_E_MPI_COMMAND);
        return VB_EXIT_USAGE;
    }
    vb_ctx *ctx;
    if (vb_world_open_ctx(&ctx) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        return VB_EXIT_NOMEM;
    }
    int rc = VB_OK, rank0 = vb_world_rank() == 0;
    vb_radii_table *radii = NULL;
    vbc_pipe *pipe = NULL;
    vb_frame_source *F = NULL;
    sinks S;
    memset(&S, 0, sizeof S);
    S.stats = A.c.stats != NULL || A.c.stats_stderr;
    S.cl = A.c.centrelines != NULL;
    if (A.c.pymol && vbc_pymol_needs_frame0(A.input, A.c.traj) &&
        snprintf(S.frame0, sizeof S.frame0, "%s.frame0.pdb", A.c.pymol) >= (int)sizeof S.frame0)
        S.frame0[0] = '\0'; /* a name too long for a file anyway: the input is named */
    FILE *out[VB_CLI_ROUND_SINKS] = {NULL, NULL, NULL}, *pml = NULL;
    /* Every rank reads the input; rank 0 alone prints its warnings. */
    int quiet = vb_world_quiet(ctx);
    if (A.in.radii_path)
        rc = vb_radii_load(ctx, A.in.radii_path, &radii);
    vb_world_loud(ctx, quiet);
    if (rc == VB_OK)
        rc = vbc_pipe_open(ctx, vb_default_devices(),
                           vbc_channels_device(A.c.device, vb_default_devices()), A.c.variant,
                           &pipe);
    vb_read_options ro;
    vb_cli_input_read_options(&A.in, radii, &ro);
    quiet = vb_world_quiet(ctx);
    if (rc == VB_OK)
        rc = vb_frame_source_open(ctx, A.input, A.c.traj, &ro, &F);
    vb_world_loud(ctx, quiet);
    if (rc == VB_OK)
        rc = vb_cli_rounds_open(ctx, &S.rounds);
    if (rc == VB_OK && rank0)
        rc = open_outputs(ctx, &A, out);
    if (rc == VB_OK && A.c.profile && !(S.profile = vb_cli_open_output(ctx, A.c.profile)))
        rc = vb_errcode(ctx);
    if ((rc = vb_world_agree(ctx, rc)) != VB_OK)
        goto done;
    vbc_run_init(&S.run, &A.c, pipe, A.input);
    /* --frames a:b:step with an end: the number of frames is known. */
    if (A.c.f1 > A.c.f0 && A.c.fstep > 0)
        S.run.frames_total = (A.c.f1 - A.c.f0 + A.c.fstep - 1) / A.c.fstep;
    /* Progress shares stderr with --stats as the status line does: not then. */
    if (!A.c.stats_stderr)
        vb_cli_progress_attach(ctx);
    if (rank0 && A.c.json) {
        char opts[4096];
        vb_provenance prov;
        vb_cli_provenance(&prov, opts, sizeof opts, A.input, 0);
        vbc_write_json_begin_prov(out[SINK_TABLE], prov.options, A.c.traj ? A.c.traj : A.input,
                                  A.c.probe, A.c.grid, vbc_pipe_device_name(pipe));
    } else if (rank0)
        vbc_write_csv_header(out[SINK_TABLE]);
    if (rank0 && out[SINK_STATS])
        vbc_write_stats_header(out[SINK_STATS]);
    if (S.profile)
        vbc_write_profile_header(S.profile);
    double t0 = vb_now();
    long selected = 0;
    /* The status line shares stderr with --stats: the rows would cut it. */
    if (rank0 && !A.c.stats_stderr)
        vb_cli_status_start("channels: reading the first frame");
    /* Frames in flight on one process; the picture (--png) runs the pipe
     * on this thread, so it keeps the loop that reads frame by frame. */
    int depth = vbc_ahead_depth();
    if (vb_world_size() == 1 && depth > 0 && !A.c.png)
        rc = run_frames_ahead(ctx, &A, pipe, F, &S, out, &selected, depth);
    else
        rc = run_frames(ctx, &A, pipe, F, &S, out, &selected);
    double wall = vb_now() - t0;
    vb_cli_status_stop();
    if (rc == VB_OK && selected == 0)
        /* Of a trajectory, the frames are the trajectory's (a DCD cut
         * inside its first frame has none): name it, not the topology. */
        rc = vb_error(ctx, VB_EINPUT_MODEL, A.c.traj ? A.c.traj : A.input, 0,
                      A.c.traj ? "no whole frame selected from the trajectory (--frames / --model)"
                            : "no frame selected (--frames / --model)");
    /* The collectives first, while every rank agrees on rc; then rank 0's
     * own writing. */
    if (rc == VB_OK)
        rc = report(ctx, &A, pipe, &S, wall);
    if (rc == VB_OK && rank0 && A.c.volume && !strstr(A.c.volume, "%d") && selected > 1)
        vb_warn(ctx, VB_W_VOLUME_FIRST_FRAME, A.c.volume, 0, "volume holds the first of %ld frames ('%%d' in the name "
                "writes one per frame)", selected);
    if (rc == VB_OK)
        vbc_run_report_left_out(ctx, &S.run);
    if (rc == VB_OK && rank0 && A.c.json)
        vbc_write_json_end(out[SINK_TABLE]);
    if (rc == VB_OK && rank0 && out[SINK_CL])
        vbc_write_centrelines_conect(out[SINK_CL], &S.run.first);
    if (rc == VB_OK && rank0 && A.c.pymol) {
        if (!(pml = vb_cli_open_output(ctx, A.c.pymol)))
            rc = vb_errcode(ctx);
        else {
            vbc_write_pymol(pml, A.c.pymol, S.frame0[0] ? S.frame0 : A.input, A.c.centrelines,
                            A.c.traj);
            rc = vb_cli_close_output(ctx, pml, A.c.pymol);
        }
    }
    if (rc == VB_OK && A.c.occupancy)
        rc = vbc_write_volume_f32(ctx, A.c.occupancy, &S.run.fixed, S.run.occupancy, 1.0 / (double)S.run.frames_done);
    if (rc == VB_OK && A.c.plot)
        rc = vb_channels_plot(ctx, A.c.plot, A.input, &S.run.first, &S.run.series);
    if (rc == VB_OK && A.c.html)
        rc = vb_page_write(S.page, A.c.html);
done:
    rc = close_outputs(ctx, &A, out, rc);
    if (S.profile)
        rc = vb_cli_finish_output(ctx, S.profile, A.c.profile, rc);
    vb_cli_rounds_close(S.rounds);
    vb_page_free(S.page);
    vbc_run_free(&S.run);
    vb_frame_source_close(F);
    vbc_pipe_close(pipe);
    vb_radii_free(radii);
    int exit_code = vb_world_end(ctx, rc);
    vb_close(ctx);
    return exit_code;
}
