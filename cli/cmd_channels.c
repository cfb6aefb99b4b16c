/* `vorball channels`: channels and cavities of a molecule or of every frame
 * of a trajectory (multi-model PDB/PQR/mmCIF/GRO, or a DCD, XTC or TRR with
 * its topology), by the discrete-Voronoi pipeline of the Facet-JFA paper
 * (Sec. 4) on OpenCL or its C reference, with components, centrelines,
 * bottlenecks and lining residues. The command parses its line into the
 * library's channels handle (lib/vb_channels.h), opens its outputs, deals
 * frames to MPI ranks through the hooks of the library's run over frames
 * (vb_channels_run_frames), and writes the closing line and the pictures. */
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "channels_plot.h"
#include "jfa_png.h"
#include "progress.h"
#include "vb_channels.h"
#include "vb_diag.h"
#include "vb_frames.h"
#include "vb_world.h"
#include "frame_rounds.h"

static const char *cmd = "channels";

typedef struct {
    const char *input;
    vb_channels *ch;        /* every option of the command but the input's (vb_channels.h) */
    vb_channels_request r;  /* what the command reads of them */
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
    vb_channels_help(f, VB_CHANNELS_HELP_MAIN);
    fprintf(f,
            "\n"
            "the pore (HOLE-style, on by default): one point per plane normal to an axis, each\n"
            "the centre of the largest sphere in its plane that overlaps no atom; it passes\n"
            "constrictions narrower than the probe; the probe's molecular surface ends it.\n");
    vb_channels_help(f, VB_CHANNELS_HELP_PORE);
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
            vb_channels_columns_help());
    vb_cli_input_help(f);
}

/* Parses argv into *A; A->ch is made here (free it with vb_channels_free,
 * also after a failure). 0, or -1 after the usage error is said. */
static int parse_args(int argc, char **argv, ch_args *A)
{
    memset(A, 0, sizeof *A);
    vb_cli_input_defaults(&A->in);
    if (vb_channels_new(NULL, &A->ch) != VB_OK)
        return vb_cli_usage_error(cmd, "out of memory"), -1;
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
        vb_channels_option o;
        if (vb_channels_option_find(a, &o) != 0)
            return vb_cli_usage_error(cmd, "unknown option '%s' (see --help)", a), -1;
        const char *v = NULL;
        if (o.type != VB_OPT_FLAG) {
            if (i + 1 >= argc)
                return vb_cli_usage_error(cmd, "%s needs a value", a), -1;
            v = argv[++i];
        }
        if (vb_channels_set(A->ch, a, v, err, sizeof err) != 0)
            return vb_cli_usage_error(cmd, "%s", err), -1;
    }
    vb_channels_request_get(A->ch, &A->r);
    if (!A->input)
        return vb_cli_usage_error(cmd, "no input (see --help)"), -1;
    if (A->r.traj && strcmp(A->input, "-") == 0)
        return vb_cli_usage_error(cmd, "the trajectory's topology must be a file"), -1;
    if (vb_channels_check(A->ch, err, sizeof err) != 0)
        return vb_cli_usage_error(cmd, "%s", err), -1;
    return 0;
}

/* The hooks of the library's run over frames (vb_channels_io): the frames
 * dealt to the ranks in rounds (frame_rounds.h), rank 0's sinks, --atoms. */
typedef struct {
    vb_cli_rounds *rounds;
    FILE **out;             /* rank 0's table, statistics, centrelines (the sinks' order) */
    const char *atoms_path; /* --atoms */
} hooks;

static int hook_mine(void *user, long j)
{
    (void)user;
    return vb_cli_rounds_mine(j);
}

/* Every rank agrees on rc; rank 0 writes the round's frames in order. */
static int hook_round_end(vb_ctx *ctx, void *user, int rc, long j0, long j1)
{
    const hooks *H = user;
    return vb_cli_rounds_flush(ctx, H->rounds, rc, j0, j1, H->out);
}

static FILE *hook_stream(void *user, int k)
{
    return vb_cli_rounds_stream(((hooks *)user)->rounds, k);
}

static int hook_frame_done(vb_ctx *ctx, void *user)
{
    return vb_cli_rounds_frame_done(ctx, ((hooks *)user)->rounds);
}

/* --atoms: the atoms the analysis used (after --ignore and --membrane),
 * whose ids the lining lists give. */
static int hook_first_frame(vb_ctx *ctx, void *user, const vb_sphere_set *read,
                            const vb_sphere_set *analysed)
{
    (void)read;
    const hooks *H = user;
    return H->atoms_path ? vb_cli_write_atoms(ctx, H->atoms_path, analysed) : VB_OK;
}

static void hook_status(void *user, long index, long done, const char *device)
{
    (void)user;
    vb_cli_status_set("channels: frame %ld (%ld analysed) on %s", index, done, device);
}

/* The closing line on stderr: this process's frames, or under MPI every
 * rank's (per-run times are means over the ranks' runs, and the frame rate
 * of the whole job is on the wall clock). */
static int report(vb_ctx *ctx, const ch_args *A, double wall)
{
    vb_channels_totals t;
    vb_channels_totals_get(A->ch, &t);
    double sum[2] = {t.ms_total, t.ms_masks};
    uint64_t frames = (uint64_t)t.frames;
    int rc = vb_world_sum_u64(ctx, &frames, 1);
    if (rc == VB_OK)
        rc = vb_world_sum_double(ctx, sum, 2);
    if (rc != VB_OK || vb_world_rank() != 0)
        return rc;
    long runs = (long)frames * t.repeat;
    const char *device = vb_channels_device_name(A->ch); /* where the last frame ran */
    vb_info(ctx, "channels: %ld frames on %s in %.3f s", (long)frames, device, wall);
    if (vb_world_size() < 2)
        fprintf(stderr, "vorball channels: %ld frame(s), %ld run(s) on %s: %.3f ms/run "
                        "(%.1f FPS), of which GPU stages %.3f ms (%.1f FPS); %.1f frames/s in all "
                        "(%.3f s wall, reading included)\n",
                (long)frames, runs, device, sum[0] / runs, 1e3 * runs / sum[0], sum[1] / runs,
                1e3 * runs / sum[1], frames / wall, wall);
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
    const char *path[VB_CLI_ROUND_SINKS] = {A->r.out, A->r.stats, A->r.centrelines};
    if (A->r.stats_stderr)
        out[VB_CHANNELS_SINK_STATS] = stderr;
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (!out[k] && (k == VB_CHANNELS_SINK_TABLE || path[k]) &&
            !(out[k] = vb_cli_open_output(ctx, path[k])))
            return vb_errcode(ctx);
    return VB_OK;
}

/* Closes rank 0's outputs; after a failure (of any rank: rc is agreed)
 * they are discarded (vb_cli_finish_output), so no table of part of the
 * frames is left behind. */
static int close_outputs(vb_ctx *ctx, const ch_args *A, FILE *out[VB_CLI_ROUND_SINKS], int rc)
{
    const char *path[VB_CLI_ROUND_SINKS] = {A->r.out, A->r.stats, A->r.centrelines};
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (out[k] == stderr)
            fflush(stderr);
        else if (out[k])
            rc = vb_cli_finish_output(ctx, out[k], path[k], rc);
    return rc;
}

/* The first frame's stage picture (--png) and the pore plot (--plot),
 * after the frames: the command's pictures. */
static int write_pictures(vb_ctx *ctx, const ch_args *A)
{
    uint32_t w, h;
    const uint8_t *rgb;
    int rc = VB_OK;
    if (A->r.png && vb_channels_stages(A->ch, &w, &h, &rgb) == 0)
        rc = vb_png_write_rgb(ctx, A->r.png, w, h, rgb);
    if (rc == VB_OK && A->r.plot)
        rc = vb_cli_channels_plot(ctx, A->r.plot, A->input, A->ch);
    return rc;
}

/* The run: the engine, the frame source, rank 0's outputs, the library's
 * run over frames, the closing line; rc: the status so far (a failure
 * still agrees with the other ranks before it returns). */
static int run(vb_ctx *ctx, ch_args *A, vb_radii_table *radii, int rc)
{
    int rank0 = vb_world_rank() == 0;
    vb_frame_source *F = NULL;
    FILE *out[VB_CLI_ROUND_SINKS] = {NULL, NULL, NULL}, *profile = NULL;
    hooks H = {NULL, out, A->in.atoms_path};
    if (rc == VB_OK)
        rc = vb_channels_open(ctx, A->ch);
    vb_read_options ro;
    vb_cli_input_read_options(&A->in, radii, &ro);
    int quiet = vb_world_quiet(ctx);
    if (rc == VB_OK)
        rc = vb_frame_source_open(ctx, A->input, A->r.traj, &ro, &F);
    vb_world_loud(ctx, quiet);
    if (rc == VB_OK)
        rc = vb_cli_rounds_open(ctx, &H.rounds);
    if (rc == VB_OK && rank0)
        rc = open_outputs(ctx, A, out);
    if (rc == VB_OK && A->r.profile && !(profile = vb_cli_open_output(ctx, A->r.profile)))
        rc = vb_errcode(ctx);
    if ((rc = vb_world_agree(ctx, rc)) != VB_OK)
        goto done;
    vb_channels_io io = {
        .user = &H, .input = A->input, .profile = profile, .quiet_read = !rank0,
        .mine = vb_world_size() > 1 ? hook_mine : NULL, .round = vb_cli_rounds_length(),
        .round_end = hook_round_end, .stream = hook_stream, .frame_done = hook_frame_done,
        .first_frame = hook_first_frame, .check_output = vb_cli_check_output,
        .open_output = vb_cli_open_output, .close_output = vb_cli_close_output,
        .status = hook_status};
    memcpy(io.sink, out, sizeof io.sink);
    /* Progress shares stderr with --stats as the status line does: not then. */
    if (!A->r.stats_stderr)
        vb_cli_progress_attach(ctx);
    char opts[4096];
    vb_provenance prov;
    vb_cli_provenance(&prov, opts, sizeof opts, A->input, 0);
    vb_channels_write_head(A->ch, &io, prov.options);
    double t0 = vb_now();
    long selected = 0;
    /* The status line shares stderr with --stats: the rows would cut it. */
    if (rank0 && !A->r.stats_stderr)
        vb_cli_status_start("channels: reading the first frame");
    rc = vb_channels_run_frames(ctx, A->ch, F, &io, &selected);
    double wall = vb_now() - t0;
    vb_cli_status_stop();
    /* The collectives first, while every rank agrees on rc; then rank 0's
     * own writing. */
    if (rc == VB_OK)
        rc = report(ctx, A, wall);
    if (rc == VB_OK)
        rc = vb_channels_finish(ctx, A->ch, &io, rank0, selected);
    if (rc == VB_OK)
        rc = write_pictures(ctx, A);
done:
    rc = close_outputs(ctx, A, out, rc);
    if (profile)
        rc = vb_cli_finish_output(ctx, profile, A->r.profile, rc);
    vb_cli_rounds_close(H.rounds);
    vb_frame_source_close(F);
    return rc;
}

int vb_cmd_channels(int argc, char **argv)
{
    ch_args A;
    int pr = parse_args(argc, argv, &A);
    if (pr != 0) {
        vb_channels_free(A.ch);
        return VB_EXIT_USAGE;
    }
    int code = vb_world_check_input(cmd, A.input);
    /* The profile, plot, fixed grid and occupancy gather every frame in one
     * process (the pore axis of the first frame is found by every rank). */
    if (!code && vb_world_size() > 1 &&
        (A.r.profile || A.r.plot || A.r.fixed_grid || A.r.occupancy || A.r.html ||
         A.in.atoms_path)) {
        if (vb_world_rank() == 0)
            fprintf(stderr, "vorball channels: E%d: --profile, --plot, --fixed-grid, "
                            "--occupancy, --html and --atoms run on one process only (not under MPI)\n",
                    VB_E_MPI_COMMAND);
        code = VB_EXIT_USAGE;
    }
    vb_ctx *ctx;
    if (!code && vb_world_open_ctx(&ctx) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        code = VB_EXIT_NOMEM;
    }
    if (code) {
        vb_channels_free(A.ch);
        return code;
    }
    vb_radii_table *radii = NULL;
    /* Every rank reads the input; rank 0 alone prints its warnings. */
    int quiet = vb_world_quiet(ctx), rc = VB_OK;
    if (A.in.radii_path)
        rc = vb_radii_load(ctx, A.in.radii_path, &radii);
    vb_world_loud(ctx, quiet);
    rc = run(ctx, &A, radii, rc);
    vb_channels_free(A.ch);
    vb_radii_free(radii);
    int exit_code = vb_world_end(ctx, rc);
    vb_close(ctx);
    return exit_code;
}
