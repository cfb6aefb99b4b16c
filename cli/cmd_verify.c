/* `vorball verify SPHERES VERTICES`: parses the options, judges the vertex
 * file with vb_verify_file (verify/judge/vb_verify_file.h) and writes its report. */
#include <math.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "progress.h"
#include "vb_arc.h"
#include "vb_verify_file.h"
#include "verify_periodic.h"

static const char *const usage_text =
    "usage: vorball verify SPHERES VERTICES [--tol T] [--complete] [--arcs] [--json]\n"
    "                      [--threads N]\n"
    "                      [-o FILE] [input options]\n"
    "\n"
    "Checks every line of VERTICES (tsv, json or Voronota's 'q1 q2 q3 q4 x y z r',\n"
    "detected by content; '-' reads stdin) exactly against SPHERES. Each line is\n"
    "  certified          its ids are tangent to one empty sphere at its point\n"
    "  not a vertex       a sphere cuts the tangent sphere, no tangent sphere exists,\n"
    "                     or the ids do not determine a point\n"
    "  wrong coordinates  the exact vertex is farther than T from the line's x y z\n"
    "                     (or its t differs by more than T), in input units\n"
    "  missing members    the line's ids are a strict subset of the vertex's spheres\n"
    "  duplicate          an earlier line names the same exact vertex\n"
    "Voronota lists a vertex of degree > 4 as several quadruple lines: its lines\n"
    "are grouped by exact vertex and membership is judged on the group's union.\n"
    "\n"
    "  --tol T      distance tolerance, > 0 (default 1e-6)\n"
    "  --periodic, --box ...  VERTICES is a periodic vertex file (vorball vertices\n"
    "               --periodic): each line must be its vertex's canonical translate,\n"
    "               within the images' proven reach, and certified against the atoms\n"
    "               and their images, once (classes: not canonical, not a vertex, ...);\n"
    "               the box as for vertices (the file's, or --box)\n"
    "  --complete   also compute all vertices exactly (vorball reference) and list\n"
    "               those the file misses (brute force: small inputs)\n"
    "  --arcs       exact arc closure (any size): trace every Voronoi edge of the\n"
    "               certified vertices to its next vertex exactly, list each vertex\n"
    "               the file misses on the way, and print the counts (half arcs\n"
    "               closed, to infinity, undecided; components; with --json a\n"
    "               member \"arcs\")\n"
    "  --json       report as JSON with counts per class\n"
    "  --threads N  host threads of the arc closure (default: VORBALL_THREADS or\n"
    "               all CPUs); the report does not depend on it\n"
    "  -o FILE      write the report to FILE (default stdout)\n";

static const char *const usage_tail =
    "\n"
    "Exit status: 0 when every line is certified (and, with --complete or --arcs,\n"
    "nothing is missed and no arc is undecided), 1 when a problem was found, 15 (E105) when VERTICES has no vertex\n"
    "line (nothing verified), 11 (E101) for a line that names a sphere twice, 20\n"
    "(E110) for a vertex file over 2 GiB, other codes as for every command.\n";

typedef struct {
    const char *spheres_path, *vertices_path, *out_path;
    double tol;
    int complete, arcs, json;
    unsigned threads;
    vb_cli_input_opts in;
    vb_cli_periodic per;
} options;

static int parse_args(int argc, char **argv, options *o)
{
    const char *pos[2];
    int npos = 0;
    o->tol = 1e-6;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int used = vb_cli_input_option(&o->in, argc, argv, &i);
        if (used < 0)
            return VB_EXIT_USAGE;
        if (used > 0)
            continue;
        if ((used = vb_cli_periodic_option("verify", argc, argv, &i, &o->per)) != 0) {
            if (used < 0)
                return VB_EXIT_USAGE;
            continue;
        }
        if (strcmp(a, "--tol") == 0) {
            if (i + 1 >= argc || vb_cli_parse_double(argv[++i], &o->tol) || !(o->tol > 0) ||
                !isfinite(o->tol))
                return vb_cli_usage_error("verify", "--tol needs a positive number");
        } else if (strcmp(a, "--arcs") == 0) {
            o->arcs = 1;
        } else if (strcmp(a, "--threads") == 0) {
            size_t t;
            if (i + 1 >= argc || vb_cli_parse_size(argv[++i], &t) || t < 1 || t > VB_MAX_THREADS)
                return vb_cli_usage_error("verify", "--threads needs an integer in 1..%d",
                                          VB_MAX_THREADS);
            o->threads = (unsigned)t;
        } else if (strcmp(a, "--complete") == 0) {
            o->complete = 1;
        } else if (strcmp(a, "--json") == 0) {
            o->json = 1;
        } else if (strcmp(a, "-o") == 0) {
            if (i + 1 >= argc)
                return vb_cli_usage_error("verify", "-o needs a file name");
            o->out_path = argv[++i];
        } else if (a[0] == '-' && a[1] != '\0') {
            return vb_cli_usage_error("verify", "unknown option '%s'", a);
        } else if (npos < 2) {
            pos[npos++] = a;
        } else {
            return vb_cli_usage_error("verify", "too many arguments ('%s')", a);
        }
    }
    if (npos != 2)
        return vb_cli_usage_error("verify", "needs SPHERES and VERTICES");
    if (o->per.on && (o->complete || o->arcs))
        return vb_cli_usage_error("verify", "--periodic judges each line: without --complete "
                                            "and --arcs");
    if (strcmp(pos[0], "-") == 0 && strcmp(pos[1], "-") == 0)
        return vb_cli_usage_error("verify", "only one of SPHERES and VERTICES can be '-'");
    o->spheres_path = pos[0];
    o->vertices_path = pos[1];
    return VB_EXIT_OK;
}

static int run(vb_ctx *ctx, const options *o, int *mismatch)
{
    vb_sphere_set *set = NULL;
    vb_verify_report r;
    memset(&r, 0, sizeof r);
    FILE *out = NULL;
    int rc = vb_cli_load_spheres(ctx, o->spheres_path, &o->in, 4, &set);
    if (rc == VB_OK && o->per.on) {
        if (!(out = vb_cli_open_output(ctx, o->out_path)))
            rc = vb_errcode(ctx);
        if (rc == VB_OK)
            rc = vb_cli_verify_periodic(ctx, set, &o->per, o->vertices_path, o->tol, o->json,
                                        out, mismatch);
        if (out) {
            int rc2 = vb_cli_close_output(ctx, out, o->out_path);
            rc = rc ? rc : rc2;
        }
        vb_spheres_free(set);
        return rc;
    }
    if (rc == VB_OK)
        rc = vb_verify_file(ctx, set, o->vertices_path, o->tol, o->complete, &r);
    if (rc == VB_OK && !(out = vb_cli_open_output(ctx, o->out_path)))
        rc = vb_errcode(ctx);
    vb_arc_report ar;
    memset(&ar, 0, sizeof ar);
    vb_vertex_list_init(&ar.added);
    if (rc == VB_OK && o->arcs)
        rc = vb_verify_arcs(ctx, set, &r, o->threads, &ar);
    if (rc == VB_OK) {
        if (o->json && o->arcs)
            rc = vb_verify_write_json_arcs(ctx, out, o->spheres_path, o->vertices_path, set, &r,
                                           &ar);
        else if (o->json)
            rc = vb_verify_write_json(ctx, out, o->spheres_path, o->vertices_path, set, &r);
        else
            rc = vb_verify_write_text(ctx, out, o->vertices_path, set, &r);
        if (rc == VB_OK && o->arcs && !o->json)
            rc = vb_arc_write_text(ctx, out, o->vertices_path, &ar);
        *mismatch = !vb_verify_report_ok(&r) || (o->arcs && !vb_arc_report_complete(&ar));
    }
    if (out) {
        int rc2 = vb_cli_close_output(ctx, out, o->out_path);
        rc = rc ? rc : rc2;
    }
    vb_arc_report_free(&ar);
    vb_verify_report_free(&r);
    vb_spheres_free(set);
    return rc;
}

void vb_cmd_verify_help(FILE *f)
{
    vb_cli_input_help_between(f, usage_text, usage_tail);
}

int vb_cmd_verify(int argc, char **argv)
{
    options o;
    memset(&o, 0, sizeof o);
    vb_cli_input_defaults(&o.in);
    int ex = parse_args(argc, argv, &o);
    if (ex != VB_EXIT_OK)
        return ex;
    vb_ctx *ctx;
    vb_config cfg = {.verbosity = 1};
    if (vb_open(&ctx, &cfg) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        return VB_EXIT_NOMEM;
    }
    vb_cli_progress_attach(ctx);
    int mismatch = 0;
    int rc = run(ctx, &o, &mismatch);
    vb_cli_progress_clear();
    ex = rc == VB_OK ? (mismatch ? VB_EXIT_MISMATCH : VB_EXIT_OK) : vb_cli_fail(ctx, rc);
    vb_close(ctx);
    return ex;
}
