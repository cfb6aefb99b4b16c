/* `vorball cells IN`: per-atom volume and SAS area of the additively
 * weighted cell inside the probe-expanded ball, and contact areas, as
 * proven enclosures (verify/measures/), of one structure or of the frames of
 * a trajectory (--traj, --frames). Parse, call (vb_cells.h), write. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "progress.h"
#include "vb_cells.h"
#include "vb_measures_page.h"
#include "vb_parallel.h"
#include "vb_periodic_frames.h"
#include "vertices_periodic.h"

static const char *const usage_text =
    "usage: vorball cells IN [-o FILE] [--json] [--contacts FILE] [--probe R] [--tolerance T]\n"
    "                     [--max-patches N] [--threads N] [--traj FILE] [--frames A:B:S]\n"
    "                     [--html FILE] [--stats] [--periodic] [--box ...] [input options]\n"
    "\n"
    "For every atom: the volume of its additively weighted Voronoi cell inside its\n"
    "expanded ball (radius R + probe) and its SAS area (the part of the expanded\n"
    "sphere inside the cell); with --contacts, the area of each face two cells share\n"
    "inside the expanded balls. Each value is an enclosure lo <= exact <= hi proven by\n"
    "interval arithmetic; the value printed is its midpoint. Atoms whose cell is\n"
    "empty (inside a larger sphere) get 0 (W850).\n"
    "\n"
    "  -o FILE          per-atom TSV (default stdout): id chain resname resseq atom\n"
    "                   volume volume_lo volume_hi sas sas_lo sas_hi ('.' = no such field)\n"
    "  --json           -o as JSON: per-atom rows (the TSV's digits) and per-residue and\n"
    "                   per-chain sums, each an interval sum rounded outward\n"
    "  --contacts FILE  TSV id1 id2 area area_lo area_hi (id1 < id2)\n"
    "  --traj FILE      coordinates from a DCD, XTC or TRR trajectory (IN = its topology)\n"
    "  --frames A:B:S   frames A (from 0) to B (excluded) every S; with --traj or --frames\n"
    "                   every model of IN is a frame (--model picks one) and each table\n"
    "                   has a `frame` column first (JSON: an array of frames)\n"
    "  --probe R        solvent radius added to every radius (default 1.4, >= 0)\n"
    "  --tolerance T    relative width asked of each value, in (0, 1) (default 1e-6;\n"
    "                   values below 1e-3 of the ball's volume or area are held to\n"
    "                   T times that floor)\n"
    "  --max-patches N  direction patches per atom before a value is left wider\n"
    "                   than asked (W851; default 5000)\n"
    "  --threads N      worker threads (default: all cores)\n"
    "  --html FILE      a results page that opens offline in a browser: the molecule\n"
    "                   with atoms coloured by volume, SAS or contact area (a selector),\n"
    "                   a frame slider over --traj/--frames, the counts of each frame\n"
    "  --stats          atoms, patches, empty and loose counts, the time, the atoms\n"
    "                   measured in closed form and the CPU seconds per stage (every\n"
    "                   thread summed) on stderr\n"
    "  --periodic       the atoms repeated by the box of the file (GRO's last line, PDB's\n"
    "                   CRYST1) or --box: each atom once, its cell cut by the images\n"
    "                   too; contacts across the box name the second atom j@(dx,dy,dz)\n"
    "                   (atom j moved by dx a + dy b + dz c), each periodic face once;\n"
    "                   with --traj/--frames each frame in the box it carries (or --box's)\n"
    "  --box a b c [alpha beta gamma] | --box ax ay az bx by bz cx cy cz\n"
    "                   the periodic box (implies --periodic), in input units\n";

/* The provenance of the outputs (issue 35): the input, its sphere count
 * and the command line that shaped them. */
typedef struct {
    vb_provenance prov;
    char options[4096];
} cells_prov;

static void prov_make(cells_prov *p, const char *input, size_t spheres)
{
    vb_cli_provenance(&p->prov, p->options, sizeof p->options, input, spheres);
}

/* The provenance lines of a table's header ("# tool/# input/# options"). */
static int prov_comments(vb_ctx *ctx, FILE *f, const vb_provenance *p)
{
    if (vb_provenance_write_comments(f, "# ", p, NULL) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing a table's header)");
    return VB_OK;
}

static int write_file(vb_ctx *ctx, const char *path, const vb_sphere_set *set,
                      const vb_cell_measures *m, int contacts, int json, const cells_prov *cp)
{
    FILE *f = vb_cli_open_output(ctx, path);
    if (!f)
        return vb_errcode(ctx);
    int rc;
    if (json) {
        rc = vb_cell_measures_write_json_prov(ctx, f, set, m, -1, 0, &cp->prov);
        fputc('\n', f);
    } else if ((rc = prov_comments(ctx, f, &cp->prov)) != VB_OK) {
        /* nothing more: the file is discarded */
    } else if (contacts) {
        vb_cell_measures_write_contacts(f, m);
    } else {
        vb_cell_measures_write_atoms(f, set, m);
    }
    return vb_cli_finish_output(ctx, f, path, rc);
}

/* Adds a frame's measures to the results page (--html), made on the first
 * frame; `page` NULL: no page asked. */
static int page_add(vb_ctx *ctx, vb_page **page, const char *title, const char *label,
                    const vb_sphere_set *set, const vb_cell_measures *m, int contacts)
{
    if (!title)
        return VB_OK;
    if (!*page && !(*page = vb_page_new(ctx, title, set)))
        return vb_errcode(ctx);
    return vb_cell_measures_page_add(ctx, *page, label, set, m, contacts);
}

/* The outputs of a run over frames: one table of all frames each, and the
 * results page. */
typedef struct {
    vb_ctx *ctx;
    FILE *out, *contacts;
    int json;
    long written;
    size_t atoms, patches, nempty, nloose, ncontacts, nclosed;
    const char *title; /* --html: the page's title; NULL: no page */
    vb_page *page;
    const char *input;
    cells_prov prov; /* made on the first frame (its sphere count) */
    double stage_s[VB_CELL_NSTAGE]; /* every frame's, summed */
} frames_sink;

/* --stats' second line: the seconds of each stage of the measures. */
static void print_stages(const double *stage_s)
{
    fputs("cells stages (CPU s, every thread summed):", stderr);
    for (int k = 0; k < VB_CELL_NSTAGE; k++)
        fprintf(stderr, " %s %.3f", vb_cell_stage_name[k], stage_s[k]);
    fputc('\n', stderr);
}

/* The tables' headers, on the first frame: the provenance, then the
 * column names (JSON: the array opens; each frame's object carries the
 * provenance). */
static int write_headers(frames_sink *S, size_t spheres)
{
    prov_make(&S->prov, S->input, spheres);
    int rc = VB_OK;
    if (S->json)
        fputs("[\n", S->out);
    else if ((rc = prov_comments(S->ctx, S->out, &S->prov.prov)) == VB_OK)
        vb_cell_measures_write_atoms_header(S->out, 1);
    if (rc == VB_OK && S->contacts)
        rc = prov_comments(S->ctx, S->contacts, &S->prov.prov);
    if (rc == VB_OK && S->contacts)
        vb_cell_measures_write_contacts_header(S->contacts, 1);
    return rc;
}

static int write_frame(void *arg, long frame, int model, const vb_sphere_set *set,
                       const vb_cell_measures *m)
{
    frames_sink *S = arg;
    int rc = S->written ? VB_OK : write_headers(S, set->n);
    if (rc != VB_OK) {
        return rc;
    } else if (S->json) {
        fputs(S->written ? ",\n" : "", S->out);
        rc = vb_cell_measures_write_json_prov(S->ctx, S->out, set, m, frame, model, &S->prov.prov);
    } else {
        vb_cell_measures_write_atom_rows(S->out, set, m, frame);
    }
    if (S->contacts)
        vb_cell_measures_write_contact_rows(S->contacts, m, frame);
    char label[64];
    snprintf(label, sizeof label, "frame %ld (model %d)", frame, model);
    if (rc == VB_OK)
        rc = page_add(S->ctx, &S->page, S->title, label, set, m, S->contacts != NULL);
    S->written++;
    S->atoms += m->n, S->patches += m->patches, S->nempty += m->nempty;
    S->nclosed += m->nclosed;
    for (int k = 0; k < VB_CELL_NSTAGE; k++)
        S->stage_s[k] += m->stage_s[k];
    S->nloose += m->nloose, S->ncontacts += m->ncontacts;
    return rc;
}

/* `cells` over the frames of IN (or of --traj): the tables of every frame. */
static int run_frames(vb_ctx *ctx, const char *in_path, const char *traj,
                      const vb_cli_input_opts *in, const vb_frame_range *range,
                      const vb_cli_periodic *per, const vb_measure_options *opt,
                      const char *out_path,
                      const char *contacts_path, int json, int stats, const char *title,
                      const char *html)
{
    vb_radii_table *radii = NULL;
    frames_sink S = {ctx, NULL, NULL, json, 0, 0, 0, 0, 0, 0, 0, title, NULL, in_path, {{0}, ""}, {0}};
    int rc = in->radii_path ? vb_radii_load(ctx, in->radii_path, &radii) : VB_OK;
    vb_read_options ro;
    vb_cli_input_read_options(in, radii, &ro);
    if (rc == VB_OK && !(S.out = vb_cli_open_output(ctx, out_path)))
        rc = vb_errcode(ctx);
    if (rc == VB_OK && contacts_path && !(S.contacts = vb_cli_open_output(ctx, contacts_path)))
        rc = vb_errcode(ctx);
    long frames = 0;
    double t0 = vb_now();
    /* --periodic: each frame in its own box, or --box's for all. */
    vb_box box;
    if (rc == VB_OK && per->on && per->nbox)
        rc = vb_box_parse_args(ctx, per->box, per->nbox, &box);
    if (rc == VB_OK && per->on)
        rc = vb_cells_run_frames_periodic(ctx, in_path, traj, &ro, range,
                                          per->nbox ? &box : NULL, opt, write_frame, &S, &frames);
    else if (rc == VB_OK)
        rc = vb_cells_run_frames(ctx, in_path, traj, &ro, range, opt, write_frame, &S, &frames);
    double t1 = vb_now();
    if (rc == VB_OK && json)
        fputs("\n]\n", S.out);
    /* A failed run leaves no partial table. */
    int crc = S.contacts ? vb_cli_finish_output(ctx, S.contacts, contacts_path, rc) : rc;
    int orc = S.out ? vb_cli_finish_output(ctx, S.out, out_path, rc) : rc;
    rc = rc != VB_OK ? rc : crc != VB_OK ? crc : orc;
    if (rc == VB_OK && html)
        rc = vb_page_write(S.page, html);
    vb_page_free(S.page);
    if (rc == VB_OK && stats)
        fprintf(stderr,
                "cells: %ld frames, %zu atoms, %zu patches, %zu empty, %zu loose, %zu contacts, "
                "%.3f s (%.3f frames/s), %zu atoms in closed form\n",
                frames, S.atoms, S.patches, S.nempty, S.nloose, S.ncontacts, t1 - t0,
                t1 > t0 ? (double)frames / (t1 - t0) : 0.0, S.nclosed);
    if (rc == VB_OK && stats)
        print_stages(S.stage_s);
    vb_radii_free(radii);
    return rc;
}

void vb_cmd_cells_help(FILE *f)
{
    vb_cli_input_help_between(f, usage_text, NULL);
}

int vb_cmd_cells(int argc, char **argv)
{
    const char *in_path = NULL, *out_path = NULL, *contacts_path = NULL, *traj = NULL;
    const char *html = NULL;
    int stats = 0, json = 0, frames = 0;
    vb_frame_range range = {0, -1, 1};
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    vb_cli_input_opts in;
    vb_cli_input_defaults(&in);
    vb_cli_periodic per;
    memset(&per, 0, sizeof per);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has_value = strcmp(a, "-o") == 0 || strcmp(a, "--contacts") == 0 ||
                        strcmp(a, "--probe") == 0 || strcmp(a, "--tolerance") == 0 ||
                        strcmp(a, "--max-patches") == 0 || strcmp(a, "--threads") == 0 ||
                        strcmp(a, "--traj") == 0 || strcmp(a, "--frames") == 0 ||
                        strcmp(a, "--html") == 0;
        if (has_value && i + 1 >= argc)
            return vb_cli_usage_error(argv[0], "%s needs a value", a);
        size_t sz;
        if (strcmp(a, "-o") == 0) {
            out_path = argv[++i];
        } else if (strcmp(a, "--contacts") == 0) {
            contacts_path = argv[++i];
        } else if (strcmp(a, "--html") == 0) {
            html = argv[++i];
        } else if (strcmp(a, "--probe") == 0) {
            if (vb_cli_parse_double(argv[++i], &opt.probe) != 0)
                return vb_cli_usage_error(argv[0], "--probe '%s' is not a number", argv[i]);
        } else if (strcmp(a, "--tolerance") == 0) {
            if (vb_cli_parse_double(argv[++i], &opt.tolerance) != 0)
                return vb_cli_usage_error(argv[0], "--tolerance '%s' is not a number", argv[i]);
        } else if (strcmp(a, "--max-patches") == 0) {
            /* The ranges are the library's (vb_measure_options_check, after
             * the loop): a value that does not parse is stored as one the
             * check refuses, so that its message names the range. */
            if (vb_cli_parse_size(argv[++i], &opt.max_patches) != 0 || opt.max_patches == 0)
                opt.max_patches = 1;
        } else if (strcmp(a, "--threads") == 0) {
            opt.threads = vb_cli_parse_size(argv[++i], &sz) != 0 || sz == 0 || sz > INT_MAX
                              ? -1
                              : (int)sz;
        } else if (strcmp(a, "--stats") == 0) {
            stats = opt.clock = 1;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--traj") == 0) {
            traj = argv[++i];
            frames = 1;
        } else if (strcmp(a, "--frames") == 0) {
            if (vb_frame_range_parse(argv[++i], &range) != 0)
                return vb_cli_usage_error(argv[0],
                                          "--frames needs A:B:S (from 0, B > A, S >= 1), not '%s'",
                                          argv[i]);
            frames = 1;
        } else {
            int used = vb_cli_periodic_option(argv[0], argc, argv, &i, &per);
            if (used == 0)
                used = vb_cli_input_option(&in, argc, argv, &i);
            if (used < 0)
                return VB_EXIT_USAGE;
            if (used)
                continue;
            if (a[0] == '-' && a[1] != '\0')
                return vb_cli_usage_error(argv[0], "unknown option '%s'", a);
            if (in_path)
                return vb_cli_usage_error(argv[0], "one input file only ('%s' and '%s')",
                                          in_path, a);
            in_path = a;
        }
    }
    if (!in_path)
        return vb_cli_usage_error(argv[0], "no input file (use '-' for stdin)");
    if (traj && strcmp(in_path, "-") == 0)
        return vb_cli_usage_error(argv[0], "the trajectory's topology must be a file");
    opt.contacts = contacts_path != NULL;

    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        return VB_EXIT_NOMEM;
    }
    if (vb_measure_options_check(ctx, &opt) != VB_OK) {
        vb_cli_usage_error(argv[0], "%s", vb_errmsg(ctx));
        vb_close(ctx);
        return VB_EXIT_USAGE;
    }
    vb_cli_progress_attach(ctx);
    vb_sphere_set *set = NULL;
    vb_cell_measures m;
    memset(&m, 0, sizeof m);
    double t0 = vb_now();
    int rc = vb_cli_check_output(ctx, out_path);
    if (rc == VB_OK)
        rc = vb_cli_check_output(ctx, contacts_path);
    if (rc == VB_OK)
        rc = vb_cli_check_output(ctx, html);
    if (rc == VB_OK && html)
        rc = vb_page_check(ctx, html);
    char title[512];
    snprintf(title, sizeof title, "vorball cells %s%s%s", in_path, traj ? " + " : "",
             traj ? traj : "");
    if (rc == VB_OK && frames) {
        rc = run_frames(ctx, in_path, traj, &in, &range, &per, &opt, out_path, contacts_path, json,
                        stats, html ? title : NULL, html);
        int code = rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
        vb_cli_progress_clear();
        vb_close(ctx);
        return code;
    }
    if (rc == VB_OK)
        rc = vb_cli_load_spheres(ctx, in_path, &in, 1, &set);
    vb_box box;
    if (rc == VB_OK && per.on)
        rc = vb_cli_periodic_box(ctx, set, &per, &box);
    if (rc == VB_OK)
        rc = per.on ? vb_cells_run_periodic(ctx, set, &box, &opt, &m)
                    : vb_cells_run(ctx, set, &opt, &m);
    double t1 = vb_now();
    cells_prov cp;
    if (rc == VB_OK)
        prov_make(&cp, in_path, set->n);
    if (rc == VB_OK && contacts_path)
        rc = write_file(ctx, contacts_path, set, &m, 1, 0, &cp);
    if (rc == VB_OK)
        rc = write_file(ctx, out_path, set, &m, 0, json, &cp);
    if (rc == VB_OK && html)
        rc = vb_cells_page_write(ctx, html, title, set, &m, contacts_path != NULL);
    if (rc == VB_OK && stats)
        fprintf(stderr,
                "cells: %zu atoms, %zu patches, %zu empty, %zu loose, %zu contacts, %.3f s, "
                "%zu atoms in closed form\n",
                m.n, m.patches, m.nempty, m.nloose, m.ncontacts, t1 - t0, m.nclosed);
    if (rc == VB_OK && stats)
        print_stages(m.stage_s);
    int exit_code = rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
    vb_cell_measures_free(&m);
    vb_spheres_free(set);
    vb_cli_progress_clear();
    vb_close(ctx);
    return exit_code;
}
