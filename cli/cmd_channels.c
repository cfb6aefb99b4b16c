/* `vorball channels`: channels and cavities of a molecule or of every frame
 * of a trajectory (multi-model PDB/PQR/mmCIF/GRO, or a DCD, XTC or TRR with
 * its topology),
 * by the discrete-Voronoi pipeline of the Facet-JFA paper (Sec. 4) on
 * OpenCL or its C reference, with components, centrelines, bottlenecks and
 * lining residues. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "jfa_png.h"
#include "progress.h"
#include "vb_default.h"
#include "vb_diag.h"
#include "vb_frames.h"
#include "vbc_frame.h"

static const char *cmd = "channels";

typedef struct {
    const char *input, *out, *dcd, *centrelines, *pymol, *volume, *stats, *png;
    int json, cavities, png_axis, stats_stderr;
    double probe;
    int grid;
    long f0, f1, fstep;   /* --frames a:b:step (f1 < 0: to the end) */
    int repeat;
    unsigned volume_bit;
    vbj_variant variant;
    vb_device_kind device;
    vbc_options opt;
    vb_cli_input_opts in;
} ch_args;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: vorball channels [options] INPUT|-\n"
            "\n"
            "Channels (Voronoi edges inside the molecule that reach its surface) and cavities\n"
            "(those that do not) of every frame of INPUT: PDB, PQR, mmCIF, GRO or XYZR (gzip\n"
            "or bzip2 compressed too); several MODELs or GRO frames are a trajectory. With\n"
            "--traj, INPUT is the topology (PDB, GRO, mmCIF, PQR or a CHARMM/NAMD PSF) of a\n"
            "DCD, XTC or TRR trajectory.\n"
            "Per frame, on OpenCL (or its C reference, --device ref): Facet-JFA labels of the\n"
            "atom centres on an n^3 grid, Voronoi edge voxels, atomic mask (balls r + probe),\n"
            "molecular mask (rays along x, y, z), interior = atomic xor molecular, channels =\n"
            "edges and interior; then components, centrelines (widest path between the\n"
            "openings) with the clearance radius (distance to the nearest atom surface) at\n"
            "each point, bottleneck and lining residues.\n"
            "\n"
            "options:\n"
            "  -o FILE             channel table (CSV; default stdout); columns below\n"
            "  --json              the table as JSON, with centrelines\n"
            "  --stats             per-frame statistics (CSV: counts and timings) on stderr\n"
            "  --stats-file FILE   the same statistics to FILE\n"
            "  --probe R           solvent radius in A (default 1.4)\n"
            "  --grid N            grid side, a power of two 16..1024 (default 128)\n"
            "  --frames A:B:S      frames A, A+S, ... before B (from 0, B excluded; parts optional)\n"
            "  --traj FILE         coordinates from a DCD, XTC or TRR trajectory (INPUT = its\n"
            "                      topology; told apart by magic number); --dcd is the same\n"
            "  --min-length L      prune centrelines shorter than L A (default 5)\n"
            "  --min-radius R      prune channels whose bottleneck is below R A (default 0)\n"
            "  --lining-tol T      an atom lines a point when its surface is within radius + T A\n"
            "                      (default 1)\n"
            "  --cavities          report cavities too (components that do not reach the surface)\n"
            "  --centerlines FILE  centrelines as PDB pseudo-atoms, radius in the B-factor\n"
            "  --pymol FILE        PyMOL script drawing them (needs --centerlines)\n"
            "  --volume FILE       mask volume, .mrc/.map (MRC) or .vtk; '%%d' in the name writes\n"
            "                      one per frame, else the first frame only\n"
            "  --volume-mask M     channel (default), interior, molecular, atomic, edge\n"
            "  --png FILE          the 2D pipeline stages (paper Fig. 5) on the slice through the\n"
            "                      centroid of the first frame\n"
            "  --png-normal x|y|z  normal of that slice (default x: the slice holds the z axis)\n"
            "  --jfa VARIANT       facet (default), jfa, jfa+1, jfa+2, 1+jfa\n"
            "  --device D          auto (default: GPU, else the CPU OpenCL device), gpu, cpu\n"
            "                      or ref (plain C, same output). If that OpenCL device cannot\n"
            "                      be used, the reference runs after warning W804 (W806:\n"
            "                      OpenCL failed mid-run, that frame and the rest rerun on\n"
            "                      the reference)\n"
            "  --repeat N          run every frame N times (timings; outputs written once)\n"
            "\n"
            "The channel table (CSV), one row per channel or cavity of each frame:\n"
            "%s"
            "\n",
            vbc_table_columns_help());
    vb_cli_input_help(f);
}

/* Parses "A:B:S" with each part optional ("10", ":50", "::5", "2:40:2"). */
static int parse_frames(const char *s, long *a, long *b, long *step)
{
    char buf[96];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *parts[3] = {buf, NULL, NULL};
    char *c1 = strchr(buf, ':');
    if (c1) {
        *c1 = '\0';
        parts[1] = c1 + 1;
        char *c2 = strchr(parts[1], ':');
        if (c2) {
            *c2 = '\0';
            parts[2] = c2 + 1;
        }
    }
    long v[3] = {0, -1, 1};
    for (int i = 0; i < 3; i++) {
        if (!parts[i] || !*parts[i])
            continue;
        size_t x;
        if (vb_cli_parse_size(parts[i], &x) != 0 || x > 1000000000)
            return -1;
        v[i] = (long)x;
    }
    if (!c1)
        v[1] = v[0] + 1; /* a single number is one frame */
    if (v[2] < 1 || (v[1] >= 0 && v[1] <= v[0]))
        return -1;
    *a = v[0];
    *b = v[1];
    *step = v[2];
    return 0;
}

static int parse_args(int argc, char **argv, ch_args *A)
{
    memset(A, 0, sizeof *A);
    vb_cli_input_defaults(&A->in);
    A->probe = 1.4;
    A->grid = 128;
    A->f1 = -1;
    A->fstep = 1;
    A->repeat = 1;
    A->volume_bit = VBC_F_CHANNEL;
    A->variant = VBJ_FACET;
    A->png_axis = 0;
    A->opt.min_length = 5.0;
    A->opt.min_radius = 0.0;
    A->opt.lining_tol = 1.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int r = vb_cli_input_option(&A->in, argc, argv, &i);
        if (r < 0)
            return -1;
        if (r > 0)
            continue;
        if (vb_cli_is_help(a)) {
            usage(stdout);
            return 1;
        }
        if (a[0] != '-' || strcmp(a, "-") == 0) {
            if (A->input)
                return vb_cli_usage_error(cmd, "one input only ('%s' and '%s')", A->input, a), -1;
            A->input = a;
            continue;
        }
        /* Flags first; then options with a value; anything else is not an
         * option of this command (a typo is never taken for a value). */
        static const char *const flags[] = {"--json", "--cavities", "--stats"};
        static const char *const valued[] = {
            "-o", "--stats-file", "--traj", "--dcd", "--centerlines", "--centrelines", "--pymol",
            "--volume", "--png", "--probe", "--grid", "--frames", "--repeat", "--min-length",
            "--min-radius", "--lining-tol", "--volume-mask", "--png-normal", "--jfa", "--device"};
        int flag = 0, takes = 0;
        for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++)
            flag |= strcmp(a, flags[k]) == 0;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            takes |= strcmp(a, valued[k]) == 0;
        if (!flag && !takes)
            return vb_cli_usage_error(cmd, "unknown option '%s' (see --help)", a), -1;
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (takes && !v)
            return vb_cli_usage_error(cmd, "%s needs a value", a), -1;
        if (takes)
            i++;
        size_t z;
        if (strcmp(a, "-o") == 0) A->out = v;
        else if (strcmp(a, "--json") == 0) A->json = 1;
        else if (strcmp(a, "--cavities") == 0) A->opt.keep_cavities = 1;
        else if (strcmp(a, "--stats") == 0) A->stats_stderr = 1;
        else if (strcmp(a, "--stats-file") == 0) A->stats = v;
        else if (strcmp(a, "--dcd") == 0 || strcmp(a, "--traj") == 0) A->dcd = v;
        else if (strcmp(a, "--centerlines") == 0 || strcmp(a, "--centrelines") == 0) A->centrelines = v;
        else if (strcmp(a, "--pymol") == 0) A->pymol = v;
        else if (strcmp(a, "--volume") == 0) A->volume = v;
        else if (strcmp(a, "--png") == 0) A->png = v;
        else if (strcmp(a, "--probe") == 0) {
            if (vb_cli_parse_double(v, &A->probe) != 0 || !(A->probe >= 0.0 && A->probe <= 20.0))
                return vb_cli_usage_error(cmd, "--probe needs a radius in 0..20 A, not '%s'", v), -1;
        } else if (strcmp(a, "--grid") == 0) {
            if (vb_cli_parse_size(v, &z) != 0 || z < 16 || z > 1024 || (z & (z - 1)))
                return vb_cli_usage_error(cmd, "--grid needs a power of two in 16..1024, not '%s'", v), -1;
            A->grid = (int)z;
        } else if (strcmp(a, "--frames") == 0) {
            if (parse_frames(v, &A->f0, &A->f1, &A->fstep) != 0)
                return vb_cli_usage_error(cmd, "--frames needs A:B:S (from 0, B > A, S >= 1), not '%s'", v), -1;
        } else if (strcmp(a, "--repeat") == 0) {
            if (vb_cli_parse_size(v, &z) != 0 || z < 1 || z > 100000)
                return vb_cli_usage_error(cmd, "--repeat needs 1..100000, not '%s'", v), -1;
            A->repeat = (int)z;
        } else if (strcmp(a, "--min-length") == 0 || strcmp(a, "--min-radius") == 0 ||
                   strcmp(a, "--lining-tol") == 0) {
            double d;
            if (vb_cli_parse_double(v, &d) != 0 || !(d >= 0.0 && d <= 1e4))
                return vb_cli_usage_error(cmd, "%s needs a length >= 0 in A, not '%s'", a, v), -1;
            if (a[2] == 'l' && a[3] == 'i')
                A->opt.lining_tol = d;
            else if (a[6] == 'l')
                A->opt.min_length = d;
            else
                A->opt.min_radius = d;
        } else if (strcmp(a, "--volume-mask") == 0) {
            static const struct { const char *name; unsigned bit; } m[] = {
                {"channel", VBC_F_CHANNEL}, {"interior", VBC_F_INTERIOR}, {"molecular", VBC_F_MOLECULAR},
                {"atomic", VBC_F_ATOMIC}, {"edge", VBC_F_EDGE}};
            A->volume_bit = 0;
            for (size_t k = 0; k < sizeof m / sizeof m[0]; k++)
                if (strcmp(v, m[k].name) == 0)
                    A->volume_bit = m[k].bit;
            if (!A->volume_bit)
                return vb_cli_usage_error(cmd, "--volume-mask: channel, interior, molecular, atomic or edge, not '%s'", v), -1;
        } else if (strcmp(a, "--png-normal") == 0) {
            if (strlen(v) != 1 || !strchr("xyz", v[0]))
                return vb_cli_usage_error(cmd, "--png-normal needs x, y or z, not '%s'", v), -1;
            A->png_axis = v[0] - 'x';
        } else if (strcmp(a, "--jfa") == 0) {
            if (vbj_variant_parse(NULL, v, &A->variant) != VB_OK || A->variant == VBJ_FACET_FULL)
                return vb_cli_usage_error(cmd, "--jfa: facet, jfa, jfa+1, jfa+2 or 1+jfa, not '%s'", v), -1;
        } else if (strcmp(a, "--device") == 0) {
            if (vb_device_kind_parse(NULL, v, &A->device) != VB_OK)
                return vb_cli_usage_error(cmd, "--device: auto, gpu, cpu or ref, not '%s'", v), -1;
        } else {
            return vb_cli_usage_error(cmd, "unknown option '%s' (see --help)", a), -1;
        }
    }
    if (!A->input)
        return vb_cli_usage_error(cmd, "no input (see --help)"), -1;
    if (A->pymol && !A->centrelines)
        return vb_cli_usage_error(cmd, "--pymol draws the --centerlines file: give both"), -1;
    if (A->dcd && strcmp(A->input, "-") == 0)
        return vb_cli_usage_error(cmd, "the trajectory's topology must be a file"), -1;
    if (A->stats && A->stats_stderr)
        return vb_cli_usage_error(cmd, "--stats (stderr) or --stats-file FILE, not both"), -1;
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

typedef struct {
    FILE *table, *stats, *cl;
    long frames_done;
    double sum_total, sum_masks;
    int json_first;
} sinks;

/* Writes the eight pipeline stages of the first frame (--png). */
static int write_stages(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, const vb_sphere_set *s)
{
    vbc_image img;
    int rc = vbc_stages_render(ctx, pipe, s, A->probe, A->grid, A->png_axis, &A->opt, &img);
    if (rc == VB_OK)
        rc = vb_png_write_rgb(ctx, A->png, img.w, img.h, img.rgb);
    vbc_image_free(&img);
    return rc;
}

/* Runs one frame through the pipeline `repeat` times and writes its outputs. */
static int do_frame(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, long index, int model,
                    const vb_sphere_set *s, sinks *S)
{
    vbc_grid g;
    int rc = vbc_grid_fit(ctx, s, A->probe, A->grid, 3, &g);
    if (rc != VB_OK)
        return rc;
    /* A voxel wider than the probe cannot resolve the necks that matter. */
    if (S->frames_done == 0 && g.h > fmax(A->probe, 0.5))
        vb_warn(ctx, VB_W_VOXEL_COARSE, A->input, 0,
                "voxel edge %.2f A is coarser than the probe radius %.2f A: narrow channels may be "
                "missed (raise --grid)", g.h, A->probe);
    int want_volume = A->volume && (strstr(A->volume, "%d") || S->frames_done == 0);
    vbc_frame F;
    memset(&F, 0, sizeof F);
    vbc_frame_info fi = {index, model, s->n, 0, 0, 0, 0, 0, 0};
    for (int r = 0; r < A->repeat && rc == VB_OK; r++) {
        rc = vbc_frame_run(ctx, pipe, &g, s, A->probe, want_volume ? VBC_WANT_FLAGS : 0, &A->opt,
                           &F);
        fi.ms_upload += F.out.ms_upload;
        fi.ms_jfa += F.out.ms_jfa;
        fi.ms_masks += F.out.ms_masks;
        fi.ms_analysis += F.ms_analysis;
        fi.ms_total += F.ms_masks + F.ms_analysis;
        S->sum_masks += F.ms_masks;
        S->sum_total += F.ms_masks + F.ms_analysis;
    }
    if (rc != VB_OK) {
        vbc_frame_free(&F);
        return rc;
    }
    double inv = 1.0 / A->repeat;
    fi.ms_upload *= inv;
    fi.ms_jfa *= inv;
    fi.ms_masks *= inv;
    fi.ms_analysis *= inv;
    fi.ms_total *= inv;
    fi.channel_voxels = F.out.nvoxels;
    if (A->json)
        vbc_write_json_frame(S->table, S->json_first, &fi, &g, s, &F.result);
    else
        vbc_write_csv_rows(S->table, &fi, &g, s, &F.result);
    S->json_first = 0;
    if (S->stats)
        vbc_write_stats_row(S->stats, &fi, &g, &F.result);
    if (S->cl)
        vbc_write_centrelines_pdb(S->cl, model, &F.result);
    if (want_volume) {
        char name[4096];
        if (volume_name(A->volume, index, name, sizeof name) != 0)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "volume file name too long");
        else
            rc = vbc_write_volume(ctx, name, &g, F.out.flags, A->volume_bit);
    }
    if (rc == VB_OK && A->png && S->frames_done == 0)
        rc = write_stages(ctx, A, pipe, s);
    vbc_frame_free(&F);
    S->frames_done++;
    return rc;
}

int vb_cmd_channels(int argc, char **argv)
{
    ch_args A;
    int pr = parse_args(argc, argv, &A);
    if (pr != 0)
        return pr > 0 ? VB_EXIT_OK : VB_EXIT_USAGE;
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK) {
        fprintf(stderr, "vorball: out of memory\n");
        return VB_EXIT_NOMEM;
    }
    int rc = VB_OK;
    vb_radii_table *radii = NULL;
    vbc_pipe *pipe = NULL;
    vb_frame_source *F = NULL;
    sinks S = {NULL, NULL, NULL, 0, 0.0, 0.0, 1};
    FILE *pml = NULL;
    if (A.in.radii_path)
        rc = vb_radii_load(ctx, A.in.radii_path, &radii);
    if (rc == VB_OK)
        rc = vbc_pipe_open(ctx, vb_default_devices(), A.device, A.variant, &pipe);
    vb_read_options ro;
    vb_cli_input_read_options(&A.in, radii, &ro);
    if (rc == VB_OK)
        rc = vb_frame_source_open(ctx, A.input, A.dcd, &ro, &F);
    if (rc == VB_OK && !(S.table = vb_cli_open_output(ctx, A.out)))
        rc = vb_errcode(ctx);
    if (rc == VB_OK && A.stats && !(S.stats = vb_cli_open_output(ctx, A.stats)))
        rc = vb_errcode(ctx);
    if (rc == VB_OK && A.stats_stderr)
        S.stats = stderr;
    if (rc == VB_OK && A.centrelines && !(S.cl = vb_cli_open_output(ctx, A.centrelines)))
        rc = vb_errcode(ctx);
    if (rc != VB_OK)
        goto done;
    if (A.json)
        vbc_write_json_begin(S.table, A.dcd ? A.dcd : A.input, A.probe, A.grid,
                             vbc_pipe_device_name(pipe));
    else
        vbc_write_csv_header(S.table);
    if (S.stats)
        vbc_write_stats_header(S.stats);
    double t0 = vb_now();
    vb_cli_status_start("channels: reading the first frame");
    for (long index = 0; A.f1 < 0 || index < A.f1; index++) {
        vb_sphere_set *s = NULL;
        int model;
        if ((rc = vb_frame_source_next(ctx, F, &s, &model)) != VB_OK || !s)
            break;
        vb_cli_status_set("channels: frame %ld (%ld analysed) on %s", index, S.frames_done,
                          vbc_pipe_device_name(pipe));
        if (index >= A.f0 && (index - A.f0) % A.fstep == 0)
            rc = do_frame(ctx, &A, pipe, index, model, s, &S);
        vb_spheres_free(s);
        if (rc != VB_OK)
            break;
    }
    double wall = vb_now() - t0;
    vb_cli_status_stop();
    if (rc == VB_OK && S.frames_done == 0)
        rc = vb_error(ctx, VB_EINPUT_MODEL, A.input, 0, "no frame selected (--frames / --model)");
    if (rc == VB_OK && A.volume && !strstr(A.volume, "%d") && S.frames_done > 1)
        vb_warn(ctx, VB_W_VOLUME_FIRST_FRAME, A.volume, 0, "volume holds the first of %ld frames ('%%d' in the name "
                "writes one per frame)", S.frames_done);
    if (rc == VB_OK && A.json)
        vbc_write_json_end(S.table);
    if (rc == VB_OK && A.pymol) {
        if (!(pml = vb_cli_open_output(ctx, A.pymol)))
            rc = vb_errcode(ctx);
        else {
            vbc_write_pymol(pml, strcmp(A.input, "-") == 0 ? NULL : A.input, A.centrelines);
            rc = vb_cli_close_output(ctx, pml, A.pymol);
        }
    }
    if (rc == VB_OK) {
        long runs = S.frames_done * A.repeat;
        const char *device = vbc_pipe_device_name(pipe); /* where the last frame ran */
        vb_info(ctx, "channels: %ld frames on %s in %.3f s", S.frames_done, device, wall);
        fprintf(stderr, "vorball channels: %ld frame(s), %ld run(s) on %s: %.3f ms/run "
                        "(%.1f FPS), of which GPU stages %.3f ms (%.1f FPS)\n",
                S.frames_done, runs, device, S.sum_total / runs, 1e3 * runs / S.sum_total,
                S.sum_masks / runs, 1e3 * runs / S.sum_masks);
    }
done:
    if (S.table) {
        int c = vb_cli_close_output(ctx, S.table, A.out);
        rc = rc == VB_OK ? c : rc;
    }
    if (S.stats && S.stats != stderr) {
        int c = vb_cli_close_output(ctx, S.stats, A.stats);
        rc = rc == VB_OK ? c : rc;
    }
    if (S.cl) {
        int c = vb_cli_close_output(ctx, S.cl, A.centrelines);
        rc = rc == VB_OK ? c : rc;
    }
    /* A failing command leaves no partial table behind (the rows of the
     * frames before the failure are not an answer). */
    if (rc != VB_OK) {
        const char *made[3] = {S.table ? A.out : NULL, S.stats && S.stats != stderr ? A.stats : NULL,
                               S.cl ? A.centrelines : NULL};
        for (int k = 0; k < 3; k++)
            if (made[k] && strcmp(made[k], "-") != 0)
                remove(made[k]);
    }
    vb_frame_source_close(F);
    vbc_pipe_close(pipe);
    vb_radii_free(radii);
    int exit_code = rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
    vb_close(ctx);
    return exit_code;
}
