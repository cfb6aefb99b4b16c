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
#include "vbc_frame.h"
#include "vbc_page.h"
#include "frame_rounds.h"

static const char *cmd = "channels";

#define MAX_IGNORE 64

typedef struct {
    const char *input, *out, *dcd, *centrelines, *pymol, *volume, *stats, *png;
    const char *profile, *plot, *occupancy, *html;
    int json, cavities, png_axis, fixed_grid, stats_stderr;
    vbc_pore_request pore;
    char ignore_buf[1024];
    const char *ignore[MAX_IGNORE];
    size_t nignore;
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
            "Per frame, on OpenCL (or its C reference, --device ref): the exact discrete\n"
            "Voronoi labels of the atom centres on an n^3 grid (--jfa), Voronoi edge voxels,\n"
            "atomic mask (balls r + probe), molecular mask (rays along x, y, z), interior =\n"
            "atomic xor molecular, channels = edges and interior; then components,\n"
            "centrelines (widest path between the openings) with the clearance radius\n"
            "(distance to the nearest atom surface) at each point, bottleneck and lining\n"
            "residues.\n"
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
            "  --jfa VARIANT       exact (default: the exact diagram by tiles, the fastest\n"
            "                      engine too), facet (Facet-JFA), jfa, jfa+1, jfa+2, 1+jfa\n"
            "                      (approximations: a few voxels may take a wrong label)\n"
            "  --device D          auto (default: GPU, else the CPU OpenCL device), gpu, cpu\n"
            "                      or ref (plain C, same output). If that OpenCL device cannot\n"
            "                      be used, the reference runs after warning W804 (W806:\n"
            "                      OpenCL failed mid-run, that frame and the rest rerun on\n"
            "                      the reference)\n"
            "  --repeat N          run every frame N times (timings; outputs written once)\n"
            "\n"
            "the pore (HOLE-style, on by default): one point per plane normal to an axis, each\n"
            "the centre of the largest sphere in its plane that overlaps no atom; it passes\n"
            "constrictions narrower than the probe; the probe's molecular surface ends it.\n"
            "  --axis X,Y,Z        the pore axis (HOLE's cvect); default: the symmetry axis of\n"
            "                      the chains, else a through channel, else a principal axis\n"
            "  --through X,Y,Z     a point in the pore where the sweep starts (HOLE's cpoint)\n"
            "  --sample S          A between planes (default 0.25, HOLE's sample)\n"
            "  --end-radius R      end a side where the radius exceeds R A (HOLE's endrad;\n"
            "                      default: none, the molecular surface ends it)\n"
            "  --no-pore           channels only, no pore sweep\n"
            "  --ignore RES,...    leave out atoms of these residue names (ligands, ions, ...)\n"
            "  --profile FILE      radius profile of every channel and frame (CSV: axial s,\n"
            "                      arc length, point, radius, nearest and touching atoms)\n"
            "  --html FILE         a results page that opens offline in a browser: the\n"
            "                      molecule, channels coloured by radius, the pore's profile,\n"
            "                      the figures of each frame and a frame slider\n"
            "  --plot FILE.png     the pore's radius profile (first frame; with several\n"
            "                      frames also its smallest radius per frame) drawn by gnuplot\n"
            "                      from FILE.png.gp (kept; W807 without gnuplot)\n"
            "  --fixed-grid        one grid for every frame, fitted to the first with 5 A to\n"
            "                      spare (E1 when an atom leaves it), so volumes add up\n"
            "  --occupancy FILE    per voxel the fraction of frames in which it is in a channel\n"
            "                      or inside a pore sphere (.mrc/.map float32 or .vtk; needs\n"
            "                      --fixed-grid)\n"
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

/* Parses "X,Y,Z" (three numbers). */
static int parse_vec3(const char *s, double v[3])
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *p = buf;
    for (int k = 0; k < 3; k++) {
        char *c = strchr(p, ',');
        if ((k < 2) != (c != NULL))
            return -1;
        if (c)
            *c = '\0';
        if (vb_cli_parse_double(p, &v[k]) != 0 || !isfinite(v[k]) || fabs(v[k]) > 1e6)
            return -1;
        p = c ? c + 1 : p;
    }
    return 0;
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
    A->variant = VBJ_EXACT;
    A->png_axis = 0;
    A->opt.min_length = 5.0;
    A->opt.min_radius = 0.0;
    A->opt.lining_tol = 1.0;
    A->pore.enabled = 1;
    A->pore.sweep.step = 0.25;
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
        static const char *const flags[] = {"--json", "--cavities", "--stats", "--no-pore", "--fixed-grid"};
        static const char *const valued[] = {
            "-o", "--stats-file", "--traj", "--dcd", "--centerlines", "--centrelines", "--pymol",
            "--volume", "--png", "--probe", "--grid", "--frames", "--repeat", "--min-length",
            "--min-radius", "--lining-tol", "--volume-mask", "--png-normal", "--jfa", "--device",
            "--axis", "--through", "--sample", "--end-radius", "--ignore", "--profile", "--plot", "--html",
            "--occupancy"};
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
        else if (strcmp(a, "--no-pore") == 0) A->pore.enabled = 0;
        else if (strcmp(a, "--fixed-grid") == 0) A->fixed_grid = 1;
        else if (strcmp(a, "--profile") == 0) A->profile = v;
        else if (strcmp(a, "--html") == 0) A->html = v;
        else if (strcmp(a, "--plot") == 0) A->plot = v;
        else if (strcmp(a, "--occupancy") == 0) A->occupancy = v;
        else if (strcmp(a, "--axis") == 0 || strcmp(a, "--through") == 0) {
            double *t = a[2] == 'a' ? A->pore.u : A->pore.c;
            if (parse_vec3(v, t) != 0)
                return vb_cli_usage_error(cmd, "%s needs X,Y,Z (three numbers), not '%s'", a, v), -1;
            if (a[2] == 'a') {
                double n = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
                if (!(n > 0.0) || !isfinite(n))
                    return vb_cli_usage_error(cmd, "--axis needs a nonzero vector, not '%s'", v), -1;
                for (int k = 0; k < 3; k++)
                    t[k] /= n;
                A->pore.have_axis = 1;
            } else {
                A->pore.have_through = 1;
            }
        } else if (strcmp(a, "--sample") == 0 || strcmp(a, "--end-radius") == 0) {
            double d;
            int sample = a[2] == 's';
            if (vb_cli_parse_double(v, &d) != 0 || !(sample ? d >= 0.01 && d <= 5.0 : d >= 0.0 && d <= 1e3))
                return vb_cli_usage_error(cmd, "%s needs %s, not '%s'", a,
                                          sample ? "0.01..5 A" : "a radius >= 0 in A", v), -1;
            if (sample)
                A->pore.sweep.step = d;
            else
                A->pore.sweep.end_radius = d;
        } else if (strcmp(a, "--ignore") == 0) {
            if (strlen(v) >= sizeof A->ignore_buf)
                return vb_cli_usage_error(cmd, "--ignore: list too long"), -1;
            strcpy(A->ignore_buf, v);
            A->nignore = 0;
            for (char *tok = strtok(A->ignore_buf, ","); tok; tok = strtok(NULL, ",")) {
                if (A->nignore == MAX_IGNORE)
                    return vb_cli_usage_error(cmd, "--ignore: at most %d names", MAX_IGNORE), -1;
                A->ignore[A->nignore++] = tok;
            }
            if (A->nignore == 0)
                return vb_cli_usage_error(cmd, "--ignore needs residue names, not '%s'", v), -1;
        }
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
            /* exact-boundary counts boundary pixels the masks never read. */
            if (vbj_variant_parse(NULL, v, &A->variant) != VB_OK || A->variant == VBJ_FACET_FULL ||
                A->variant == VBJ_EXACT_BOUNDARY)
                return vb_cli_usage_error(cmd, "--jfa: exact, facet, jfa, jfa+1, jfa+2 or 1+jfa, not '%s'", v), -1;
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
    if (A->occupancy && !A->fixed_grid)
        return vb_cli_usage_error(cmd, "--occupancy adds frames on one grid: give --fixed-grid"), -1;
    if (A->plot && !A->pore.enabled)
        return vb_cli_usage_error(cmd, "--plot draws the pore: drop --no-pore"), -1;
    if ((A->pore.have_through || A->pore.sweep.end_radius > 0.0) && !A->pore.enabled)
        return vb_cli_usage_error(cmd, "--axis/--through/--end-radius set the pore sweep: drop --no-pore"), -1;
    A->opt.pore = &A->pore;
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
    long frames_done;       /* this rank's frames */
    double sum_total, sum_masks;
    vbc_grid fixed;         /* --fixed-grid: fitted on the first frame */
    float *occupancy;       /* --occupancy: frames per voxel */
    vbc_result first;       /* the first frame's result (CONECT records, the plot) */
    vbc_series series;      /* the pore's smallest radius per frame (the plot) */
    size_t ignored;         /* atoms left out by --ignore, over this rank's frames */
    vb_page *page;          /* --html: made from the first frame's atoms */
} sinks;

/* Adds the frame to the results page (--html), made on the first frame. */
static int page_frame(vb_ctx *ctx, const ch_args *A, sinks *S, const vb_sphere_set *s, long index,
                      int model, const vbc_result *res)
{
    char label[64];
    if (!S->page) {
        char title[512];
        snprintf(title, sizeof title, "vorball channels %s%s%s", A->input, A->dcd ? " + " : "",
                 A->dcd ? A->dcd : "");
        if (!(S->page = vb_page_new(ctx, title, s)))
            return vb_errcode(ctx);
    }
    snprintf(label, sizeof label, "frame %ld (model %d)", index, model);
    return vbc_page_add(S->page, label, s, res);
}

/* Writes the eight pipeline stages of the first frame (--png). */
static int write_stages(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, const vb_sphere_set *s)
{
    vbc_image img;
    vbc_options o = A->opt;
    o.pore = NULL;
    int rc = vbc_stages_render(ctx, pipe, s, A->probe, A->grid, A->png_axis, &o, &img);
    if (rc == VB_OK)
        rc = vb_png_write_rgb(ctx, A->png, img.w, img.h, img.rgb);
    vbc_image_free(&img);
    return rc;
}

/* Appends the frame's pore minimum to the series. */
static int series_add(vb_ctx *ctx, vbc_series *S, long frame, const vbc_result *res)
{
    if (!res->pore.present)
        return VB_OK;
    if (S->n == S->cap) {
        size_t c = S->cap ? 2 * S->cap : 64;
        long *f = realloc(S->frame, c * sizeof *f);
        if (f)
            S->frame = f;
        double *r = realloc(S->rmin, c * sizeof *r);
        if (r)
            S->rmin = r;
        double *z = realloc(S->s, c * sizeof *z);
        if (z)
            S->s = z;
        if (!f || !r || !z)
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
static int frame_grid(vb_ctx *ctx, const ch_args *A, const vb_sphere_set *s, long index, sinks *S,
                      vbc_grid *g)
{
    if (!A->fixed_grid)
        return vbc_grid_fit(ctx, s, A->probe, A->grid, 3, g);
    if (S->frames_done == 0) {
        int rc = vbc_grid_fit(ctx, s, A->probe + 5.0, A->grid, 3, &S->fixed);
        if (rc != VB_OK)
            return rc;
    }
    *g = S->fixed;
    /* Every atom must stay where the JFA seeds can be placed. */
    for (size_t i = 0; i < s->n; i++) {
        double c[3] = {s->x[i], s->y[i], s->z[i]};
        for (int a = 0; a < 3; a++) {
            double t = (c[a] - g->origin[a]) / g->h;
            if (!(t >= 0.0 && t < (double)g->nx))
                return vb_error(ctx, VB_EINPUT, A->dcd ? A->dcd : A->input, 0,
                                "frame %ld: atom %zu leaves the fixed grid fitted to the first frame",
                                index, i + 1);
        }
    }
    return VB_OK;
}

/* The spheres a frame analyses (s0 without the --ignore residues: *kept
 * holds them when any were left out, else NULL and *s is s0) and its grid.
 * On failure nothing is held. */
static int frame_prepare(vb_ctx *ctx, ch_args *A, const vb_sphere_set *s0, long index, sinks *S,
                         vb_sphere_set **kept, const vb_sphere_set **s, vbc_grid *g)
{
    int rc = VB_OK;
    *kept = NULL;
    *s = s0;
    if (A->nignore) {
        size_t dropped;
        if ((rc = vbc_spheres_without(ctx, s0, A->ignore, A->nignore, kept, &dropped)) != VB_OK)
            return rc;
        S->ignored += dropped;
        *s = *kept;
    }
    if ((rc = frame_grid(ctx, A, *s, index, S, g)) != VB_OK) {
        vb_spheres_free(*kept);
        *kept = NULL;
    }
    return rc;
}

/* Later frames sweep the first frame's pore axis (HOLE's fixed cvect and
 * cpoint): kept in A once a frame found a pore along a free axis. */
static void keep_pore_axis(ch_args *A, const vbc_frame *F)
{
    if (!A->pore.enabled || !F->result.pore.present || A->pore.have_axis)
        return;
    memcpy(A->pore.u, F->axis.u, sizeof A->pore.u);
    memcpy(A->pore.c, F->axis.c, sizeof A->pore.c);
    A->pore.have_axis = A->pore.have_through = 1;
    A->pore.found_source = F->axis.source;
    A->pore.found_chains = F->axis.chains;
}

/* Runs one frame through the pipeline `repeat` times and writes its outputs;
 * `first`: it is the first frame of the selection (volume, picture, the
 * voxel warning, the pore's axis for the later frames). Under MPI the
 * options that need every frame in one process are refused before. */
static int do_frame(vb_ctx *ctx, ch_args *A, vbc_pipe *pipe, long index, int model, int first,
                    const vb_sphere_set *s0, sinks *S)
{
    vb_sphere_set *kept;
    const vb_sphere_set *s;
    vbc_grid g;
    int rc = frame_prepare(ctx, A, s0, index, S, &kept, &s, &g);
    if (rc != VB_OK)
        return rc;
    /* A voxel wider than the probe cannot resolve the necks that matter. */
    if (first && g.h > fmax(A->probe, 0.5))
        vb_warn(ctx, VB_W_VOXEL_COARSE, A->input, 0,
                "voxel edge %.2f A is coarser than the probe radius %.2f A: narrow channels may be "
                "missed (raise --grid)", g.h, A->probe);
    int want_volume = A->volume && (strstr(A->volume, "%d") || first);
    unsigned want = want_volume || A->occupancy ? VBC_WANT_FLAGS : 0;
    vbc_frame F;
    memset(&F, 0, sizeof F);
    vbc_frame_info fi = {index, model, s->n, 0, 0, 0, 0, 0, 0, 0};
    for (int r = 0; r < A->repeat && rc == VB_OK; r++) {
        rc = vbc_frame_run(ctx, pipe, &g, s, A->probe, want, &A->opt, &F);
        fi.ms_upload += F.out.ms_upload;
        fi.ms_jfa += F.out.ms_jfa;
        fi.ms_masks += F.out.ms_masks;
        fi.ms_analysis += F.ms_analysis;
        fi.ms_pore += F.ms_pore;
        fi.ms_total += F.ms_masks + F.ms_analysis + F.ms_pore;
        S->sum_masks += F.ms_masks;
        S->sum_total += F.ms_masks + F.ms_analysis + F.ms_pore;
    }
    if (rc != VB_OK) {
        vbc_frame_free(&F);
        vb_spheres_free(kept);
        return rc;
    }
    double inv = 1.0 / A->repeat;
    fi.ms_upload *= inv;
    fi.ms_jfa *= inv;
    fi.ms_masks *= inv;
    fi.ms_analysis *= inv;
    fi.ms_pore *= inv;
    fi.ms_total *= inv;
    fi.channel_voxels = F.out.nvoxels;
    if (A->pore.enabled && !F.result.pore.present && first)
        vb_warn(ctx, VB_W_PORE_NOT_FOUND, A->input, 0, "no pore found along any axis candidate");
    keep_pore_axis(A, &F);
    FILE *table = vb_cli_rounds_stream(S->rounds, SINK_TABLE);
    if (A->json)
        vbc_write_json_frame(table, first, &fi, &g, s, &F.result);
    else
        vbc_write_csv_rows(table, &fi, &g, s, &F.result);
    if (S->stats)
        vbc_write_stats_row(vb_cli_rounds_stream(S->rounds, SINK_STATS), &fi, &g, &F.result);
    if (S->cl)
        vbc_write_centrelines_pdb(vb_cli_rounds_stream(S->rounds, SINK_CL), model, &F.result);
    rc = vb_cli_rounds_frame_done(ctx, S->rounds);
    if (rc == VB_OK && S->profile)
        vbc_write_profile_rows(S->profile, &fi, s, &F.result);
    if (rc == VB_OK && A->html)
        rc = page_frame(ctx, A, S, s, index, model, &F.result);
    if (rc == VB_OK && A->plot)
        rc = series_add(ctx, &S->series, index, &F.result);
    if (rc == VB_OK && A->occupancy) {
        if (!S->occupancy && !(S->occupancy = calloc(vbc_grid_voxels(&g), sizeof *S->occupancy)))
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "occupancy map");
        else
            rc = vbc_occupancy_add(ctx, &g, F.out.flags, &F.result, S->occupancy);
    }
    if (rc == VB_OK && want_volume) {
        char name[4096];
        if (volume_name(A->volume, index, name, sizeof name) != 0)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "volume file name too long");
        else if ((rc = vb_cli_check_output(ctx, name)) == VB_OK)
            rc = vbc_write_volume(ctx, name, &g, F.out.flags, A->volume_bit);
    }
    if (rc == VB_OK && A->png && first)
        rc = write_stages(ctx, A, pipe, s);
    if (first) { /* kept for CONECT and the plot */
        vbc_result_free(&S->first);
        S->first = F.result;
        memset(&F.result, 0, sizeof F.result);
    }
    vbc_frame_free(&F);
    vb_spheres_free(kept);
    S->frames_done++;
    return rc;
}

/* Under MPI the first selected frame belongs to rank 0, but every rank's
 * later frames sweep its pore axis: a rank that does not own it runs the
 * same analysis of it (no output) and keeps the axis, so each rank holds the
 * axis one process would. Without a pore on that frame the axis stays free,
 * as in one process. */
static int first_frame_axis(vb_ctx *ctx, ch_args *A, vbc_pipe *pipe, long index,
                            const vb_sphere_set *s0, sinks *S)
{
    vb_sphere_set *kept;
    const vb_sphere_set *s;
    vbc_grid g;
    size_t ignored = S->ignored; /* counted by the rank that owns the frame */
    int rc = frame_prepare(ctx, A, s0, index, S, &kept, &s, &g);
    S->ignored = ignored;
    if (rc != VB_OK)
        return rc;
    vbc_frame F;
    memset(&F, 0, sizeof F);
    if ((rc = vbc_frame_run(ctx, pipe, &g, s, A->probe, 0, &A->opt, &F)) == VB_OK)
        keep_pore_axis(A, &F);
    vbc_frame_free(&F);
    vb_spheres_free(kept);
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
            if (A->f1 >= 0 && index >= A->f1) {
                end = 1;
                break;
            }
            vb_sphere_set *s = NULL;
            int model, quiet = vb_world_quiet(ctx);
            frc = vb_frame_source_next(ctx, F, &s, &model);
            vb_world_loud(ctx, quiet);
            if (frc != VB_OK || !s) {
                end = 1;
                break;
            }
            vb_cli_status_set("channels: frame %ld (%ld analysed) on %s", index, S->frames_done,
                              vbc_pipe_device_name(pipe));
            if (index >= A->f0 && (index - A->f0) % A->fstep == 0) {
                if (vb_cli_rounds_mine(j))
                    frc = do_frame(ctx, A, pipe, index, model, j == 0, s, S);
                else if (j == 0 && A->pore.enabled && !A->pore.have_axis)
                    frc = first_frame_axis(ctx, A, pipe, index, s, S);
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

/* The closing line on stderr: this process's frames, or under MPI every
 * rank's (per-run times are means over the ranks' runs, and the frame rate
 * of the whole job is on the wall clock). */
static int report(vb_ctx *ctx, const ch_args *A, vbc_pipe *pipe, const sinks *S, double wall)
{
    double sum[2] = {S->sum_total, S->sum_masks};
    uint64_t frames = (uint64_t)S->frames_done;
    int rc = vb_world_sum_u64(ctx, &frames, 1);
    if (rc == VB_OK)
        rc = vb_world_sum_double(ctx, sum, 2);
    if (rc != VB_OK || vb_world_rank() != 0)
        return rc;
    long runs = (long)frames * A->repeat;
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
    const char *path[VB_CLI_ROUND_SINKS] = {A->out, A->stats, A->centrelines};
    if (A->stats_stderr)
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
    const char *path[VB_CLI_ROUND_SINKS] = {A->out, A->stats, A->centrelines};
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (out[k] == stderr)
            fflush(stderr);
        else if (out[k])
            rc = vb_cli_finish_output(ctx, out[k], path[k], rc);
    return rc;
}

/* An absolute, normalised form of path (".", ".." and repeated '/' removed). */
static void abs_path(const char *path, char *out, size_t len)
{
    char buf[8192];
    if (path[0] == '/' || !getcwd(buf, sizeof buf - 2))
        snprintf(buf, sizeof buf, "%s", path);
    else
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "/%s", path);
    char *parts[1024];
    int n = 0;
    for (char *t = strtok(buf, "/"); t && n < 1024; t = strtok(NULL, "/")) {
        if (strcmp(t, ".") == 0)
            continue;
        if (strcmp(t, "..") == 0) {
            n -= n > 0;
            continue;
        }
        parts[n++] = t;
    }
    size_t o = 0;
    out[0] = '\0';
    for (int k = 0; k < n && o + 1 < len; k++)
        o += (size_t)snprintf(out + o, len - o, "/%s", parts[k]);
    if (n == 0)
        snprintf(out, len, "/");
}

/* target as a path relative to the folder of `from` (both as given, taken
 * from the working directory), so a script finds its files wherever the
 * folder moves. */
static void relative_to(const char *from, const char *target, char *out, size_t len)
{
    char a[8192], b[8192];
    abs_path(from, a, sizeof a);
    abs_path(target, b, sizeof b);
    char *slash = strrchr(a, '/');
    if (slash)
        slash[1] = '\0'; /* the folder of `from`, with its '/' */
    size_t common = 0;
    for (size_t k = 0; a[k] && a[k] == b[k]; k++)
        if (a[k] == '/')
            common = k + 1;
    size_t o = 0;
    out[0] = '\0';
    for (size_t k = common; a[k]; k++)
        if (a[k] == '/' && o + 4 < len)
            o += (size_t)snprintf(out + o, len - o, "../");
    snprintf(out + o, len - o, "%s", b + common);
}

int vb_cmd_channels(int argc, char **argv)
{
    ch_args A;
    int pr = parse_args(argc, argv, &A);
    if (pr != 0)
        return pr > 0 ? VB_EXIT_OK : VB_EXIT_USAGE;
    int code = vb_world_check_input(cmd, A.input);
    if (code)
        return code;
    /* The profile, plot, fixed grid and occupancy gather every frame in one
     * process (the pore axis of the first frame is found by every rank:
     * first_frame_axis). */
    if (vb_world_size() > 1 && (A.profile || A.plot || A.fixed_grid || A.occupancy || A.html)) {
        if (vb_world_rank() == 0)
            fprintf(stderr, "vorball channels: E%d: --profile, --plot, --fixed-grid, "
                            "--occupancy and --html run on one process only (not under MPI)\n",
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
    S.stats = A.stats != NULL || A.stats_stderr;
    S.cl = A.centrelines != NULL;
    FILE *out[VB_CLI_ROUND_SINKS] = {NULL, NULL, NULL}, *pml = NULL;
    /* Every rank reads the input; rank 0 alone prints its warnings. */
    int quiet = vb_world_quiet(ctx);
    if (A.in.radii_path)
        rc = vb_radii_load(ctx, A.in.radii_path, &radii);
    vb_world_loud(ctx, quiet);
    if (rc == VB_OK)
        rc = vbc_pipe_open(ctx, vb_default_devices(), A.device, A.variant, &pipe);
    vb_read_options ro;
    vb_cli_input_read_options(&A.in, radii, &ro);
    quiet = vb_world_quiet(ctx);
    if (rc == VB_OK)
        rc = vb_frame_source_open(ctx, A.input, A.dcd, &ro, &F);
    vb_world_loud(ctx, quiet);
    if (rc == VB_OK)
        rc = vb_cli_rounds_open(ctx, &S.rounds);
    if (rc == VB_OK && rank0)
        rc = open_outputs(ctx, &A, out);
    if (rc == VB_OK && A.profile && !(S.profile = vb_cli_open_output(ctx, A.profile)))
        rc = vb_errcode(ctx);
    if ((rc = vb_world_agree(ctx, rc)) != VB_OK)
        goto done;
    if (rank0 && A.json)
        vbc_write_json_begin(out[SINK_TABLE], A.dcd ? A.dcd : A.input, A.probe, A.grid,
                             vbc_pipe_device_name(pipe));
    else if (rank0)
        vbc_write_csv_header(out[SINK_TABLE]);
    if (rank0 && out[SINK_STATS])
        vbc_write_stats_header(out[SINK_STATS]);
    if (S.profile)
        vbc_write_profile_header(S.profile);
    double t0 = vb_now();
    long selected = 0;
    /* The status line shares stderr with --stats: the rows would cut it. */
    if (rank0 && !A.stats_stderr)
        vb_cli_status_start("channels: reading the first frame");
    rc = run_frames(ctx, &A, pipe, F, &S, out, &selected);
    double wall = vb_now() - t0;
    vb_cli_status_stop();
    if (rc == VB_OK && selected == 0)
        /* Of a trajectory, the frames are the trajectory's (a DCD cut
         * inside its first frame has none): name it, not the topology. */
        rc = vb_error(ctx, VB_EINPUT_MODEL, A.dcd ? A.dcd : A.input, 0,
                      A.dcd ? "no whole frame selected from the trajectory (--frames / --model)"
                            : "no frame selected (--frames / --model)");
    /* The collectives first, while every rank agrees on rc; then rank 0's
     * own writing. */
    if (rc == VB_OK)
        rc = report(ctx, &A, pipe, &S, wall);
    if (rc == VB_OK && rank0 && A.volume && !strstr(A.volume, "%d") && selected > 1)
        vb_warn(ctx, VB_W_VOLUME_FIRST_FRAME, A.volume, 0, "volume holds the first of %ld frames ('%%d' in the name "
                "writes one per frame)", selected);
    if (rc == VB_OK && S.ignored)
        vb_warn(ctx, VB_W_ATOMS_IGNORED, A.input, 0, "%zu atoms left out by --ignore", S.ignored);
    if (rc == VB_OK && rank0 && A.json)
        vbc_write_json_end(out[SINK_TABLE]);
    if (rc == VB_OK && rank0 && out[SINK_CL])
        vbc_write_centrelines_conect(out[SINK_CL], &S.first);
    if (rc == VB_OK && rank0 && A.pymol) {
        if (!(pml = vb_cli_open_output(ctx, A.pymol)))
            rc = vb_errcode(ctx);
        else {
            char mol[8192], cl[8192];
            relative_to(A.pymol, A.input, mol, sizeof mol);
            relative_to(A.pymol, A.centrelines, cl, sizeof cl);
            vbc_write_pymol(pml, strcmp(A.input, "-") == 0 ? NULL : mol, cl);
            rc = vb_cli_close_output(ctx, pml, A.pymol);
        }
    }
    if (rc == VB_OK && A.occupancy)
        rc = vbc_write_volume_f32(ctx, A.occupancy, &S.fixed, S.occupancy, 1.0 / (double)S.frames_done);
    if (rc == VB_OK && A.plot)
        rc = vb_channels_plot(ctx, A.plot, A.input, &S.first, &S.series);
    if (rc == VB_OK && A.html)
        rc = vb_page_write(S.page, A.html);
done:
    rc = close_outputs(ctx, &A, out, rc);
    if (S.profile)
        rc = vb_cli_finish_output(ctx, S.profile, A.profile, rc);
    vb_cli_rounds_close(S.rounds);
    vbc_result_free(&S.first);
    vb_page_free(S.page);
    free(S.occupancy);
    free(S.series.frame);
    free(S.series.rmin);
    free(S.series.s);
    vb_frame_source_close(F);
    vbc_pipe_close(pipe);
    vb_radii_free(radii);
    int exit_code = vb_world_end(ctx, rc);
    vb_close(ctx);
    return exit_code;
}
