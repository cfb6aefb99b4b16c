/* `vorball crosscheck SPHERES`: CGAL as an independent witness. With equal
 * radii the Voronoi diagram of spheres is the Voronoi diagram of the centres;
 * CGAL computes it exactly (verify/cgal/cgal_bridge.cpp) and this command compares
 * it with vorball's certified vertices, computed here or read from a file. */
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "vb_cgal.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"
#include "pipeline_options.h"
#include "progress.h"
#include "vb_default.h"
#include "vb_diag.h"

static const char *const usage_head =
    "usage: vorball crosscheck [--with vertices|reference | --vertices FILE] [--power]\n"
    "                          [--cgal-out FILE] [--time] [-o FILE] [pipeline options]\n"
    "                          [input options] SPHERES|-\n"
    "\n"
    "Compares vorball's Voronoi vertices of SPHERES with CGAL's, exactly. All radii\n"
    "must be equal: then the diagram is the Voronoi diagram of the centres, which\n"
    "CGAL's Delaunay_triangulation_3 over an exact-constructions kernel (Epeck)\n"
    "computes from the input decimals as exact rationals. A CGAL vertex is the\n"
    "circumcentre of a Delaunay cell; cells with one circumsphere are one vertex.\n"
    "\n"
    "Two vertices are equal when\n"
    "  - their sphere-id sets are equal,\n"
    "  - their points are the same rational point: vorball's point is re-derived\n"
    "    in GMP integers from its ids alone (the point equidistant from four\n"
    "    affinely independent member centres; every other member must be at the\n"
    "    same distance), and must equal CGAL's exact circumcentre, coordinate by\n"
    "    coordinate, as rationals; and\n"
    "  - vorball's printed x, y, z, t are those exact values rounded to the\n"
    "    nearest double (t = |p - c| - R is irrational in general; it is rounded\n"
    "    from 512 bits, or exactly when rational).\n"
    "\n"
    "The report has one line per difference, tab-separated, by category:\n"
    "  missing     a CGAL vertex at a point where vorball has none\n"
    "  extra       a vorball vertex at a point where CGAL has none\n"
    "  membership  same point, different ids (both lists printed)\n"
    "  rounding    same point and ids, a printed coordinate is not the rounding\n"
    "  split       one vertex written as several lines (allowed in Voronota files,\n"
    "              which write a vertex of degree > 4 as quadruples)\n"
    "  invalid     a vorball line whose ids define no point\n"
    "then a '#' summary line and 'identical' or 'different'.\n"
    "\n"
    "  --with vertices  compute vorball's vertices as `vorball vertices` does (the\n"
    "                   direction cover, or --proposer), on the device of --device\n"
    "                   (default)\n"
    "  --with reference compute them with `vorball reference` (exact brute force:\n"
    "                   small inputs)\n"
    "  --vertices FILE  read vorball's vertices from FILE instead (tsv, json or\n"
    "                   voronota, as `vorball vertices` and `vorball reference` write\n"
    "                   them; '-' is stdin); lines marked rejected are skipped\n"
    "  --power          compare CGAL's power diagram (Regular_triangulation_3, weights\n"
    "                   R^2) instead; any radii. Only with equal radii is it the\n"
    "                   diagram vorball computes: with unequal radii the report says\n"
    "                   so, points are matched as power vertices of vorball's ids, and\n"
    "                   printed coordinates are not compared\n"
    "  --cgal-out FILE  also write CGAL's vertices (tsv, canonical order)\n"
    "  --time           print the seconds taken by CGAL, vorball and the comparison\n"
    "                   to stderr\n"
    "  -o FILE          write the report to FILE (default stdout)\n"
    "pipeline options (for --with vertices, as in `vorball vertices`):\n"
    "  --device D       auto (default), gpu, cpu or ref\n"
    "  --proposer P     cover (default) or sampling\n"
    "  --samples S, --tol T, --tiles T, --threads N, --all-pairs\n";

static const char *const usage_tail =
    "\n"
    "Exit status: 0 when the sets are identical, 1 when they differ, 2 usage,\n"
    "10 + detail for bad input (unequal radii without --power: 10), others as for\n"
    "every command. CGAL's Triangulation_3 is GPL-3+.\n";

typedef struct {
    const char *spheres, *vertices, *out, *cgal_out;
    int power, timing, reference;
    vb_pipeline_opts po;
} options;

static int parse_args(vb_ctx *ctx, int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    vb_pipeline_opts_defaults(&o->po);
    const char *with = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int used = vb_pipeline_option("crosscheck", argc, argv, &i, &o->po, ctx);
        if (used < 0)
            return VB_EXIT_USAGE;
        if (used > 0)
            continue;
        const char **value = NULL;
        if (strcmp(a, "--with") == 0)
            value = &with;
        else if (strcmp(a, "--vertices") == 0)
            value = &o->vertices;
        else if (strcmp(a, "--cgal-out") == 0)
            value = &o->cgal_out;
        else if (strcmp(a, "-o") == 0)
            value = &o->out;
        if (value) {
            if (i + 1 >= argc)
                return vb_cli_usage_error("crosscheck", "%s needs a value", a);
            *value = argv[++i];
        } else if (strcmp(a, "--power") == 0) {
            o->power = 1;
        } else if (strcmp(a, "--time") == 0) {
            o->timing = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            return vb_cli_usage_error("crosscheck", "unknown option '%s'", a);
        } else if (o->spheres) {
            return vb_cli_usage_error("crosscheck", "one SPHERES file only ('%s' and '%s')",
                                      o->spheres, a);
        } else {
            o->spheres = a;
        }
    }
    if (!o->spheres)
        return vb_cli_usage_error("crosscheck", "no SPHERES file (see --help)");
    if (with && o->vertices)
        return vb_cli_usage_error("crosscheck", "--with and --vertices exclude each other");
    if (with && strcmp(with, "reference") == 0)
        o->reference = 1;
    else if (with && strcmp(with, "vertices") != 0)
        return vb_cli_usage_error("crosscheck", "--with takes vertices or reference, not '%s'",
                                  with);
    return VB_EXIT_OK;
}

/* Drops the lines a vertex file marks as rejected: they claim nothing. */
static int keep_claimed(vb_ctx *ctx, vb_vertex_list *v, long **lines, const char *path)
{
    vb_vertex_list kept;
    vb_vertex_list_init(&kept);
    size_t dropped = 0, k = 0;
    for (size_t i = 0; i < v->n; i++) {
        if (v->status[i] == VB_VERTEX_REJECTED) {
            dropped++;
            continue;
        }
        int rc = vb_vertex_list_push(&kept, v->ids + v->start[i], v->start[i + 1] - v->start[i],
                                     v->x[i], v->y[i], v->z[i], v->t[i], v->dist[i],
                                     v->status[i]);
        if (rc != VB_OK) {
            vb_vertex_list_free(&kept);
            return vb_error(ctx, rc, NULL, 0, "out of memory reading %s", path);
        }
        if (*lines)
            (*lines)[k] = (*lines)[i];
        k++;
    }
    if (dropped)
        vb_warn(ctx, VB_W_CROSSCHECK_REJECTED, path, 0, "%zu lines marked rejected are not compared", dropped);
    vb_vertex_list_free(v);
    *v = kept;
    return VB_OK;
}

static void print_summary(FILE *f, const vb_cgal_diff *d)
{
    fprintf(f,
            "# cgal %zu vertices, vorball %zu; matched %zu, missing %zu, extra %zu, "
            "membership %zu, rounding %zu, split %zu, invalid %zu\n%s\n",
            d->cgal, d->theirs, d->matched, d->missing, d->extra, d->membership, d->rounding,
            d->split, d->invalid, vb_cgal_identical(d) ? "identical" : "different");
}

static int run(vb_ctx *ctx, const options *o)
{
    vb_sphere_set *set = NULL;
    vb_cgal_diagram *cgal = NULL;
    vb_vertex_list mine;
    vb_vertex_list_init(&mine);
    long *lines = NULL;
    FILE *out = NULL;
    int ex = VB_EXIT_OK;
    int rc = vb_cli_load_spheres(ctx, o->spheres, &o->po.in, 4, &set);
    if (rc != VB_OK)
        goto fail;

    int mode = o->power ? VB_CGAL_POWER : VB_CGAL_VORONOI;
    double t0 = vb_now();
    rc = vb_cgal_build(ctx, set, mode, &cgal);
    if (rc != VB_OK)
        goto fail;
    double t_cgal = vb_now() - t0;
    int equal = 1;
    for (size_t i = 1; i < set->n && equal; i++)
        equal = vb_decimal_cmp(set->er[i], set->er[0]) == 0;
    if (o->power && !equal)
        vb_warn(ctx, VB_W_CROSSCHECK_POWER, o->spheres, 0,
                "radii differ: comparing with CGAL's power diagram, which is not the "
                "diagram of spheres vorball computes; only ids are compared");

    if (o->cgal_out) {
        vb_vertex_list cl;
        vb_vertex_list_init(&cl);
        char opts[4096];
        vb_provenance prov;
        vb_cli_provenance(&prov, opts, sizeof opts, o->spheres, set->n);
        FILE *f = vb_cli_open_output(ctx, o->cgal_out);
        rc = f ? vb_cgal_to_list(ctx, cgal, &cl) : vb_errcode(ctx);
        if (rc == VB_OK)
            rc = vb_vertex_write_prov(ctx, f, &cl, VB_VFMT_TSV, &prov,
                                 o->power ? "CGAL power diagram (Regular_triangulation_3, Epeck)"
                                          : "CGAL Delaunay_triangulation_3 circumcentres, Epeck");
        rc = vb_cli_finish_output(ctx, f, o->cgal_out, rc);
        vb_vertex_list_free(&cl);
        if (rc != VB_OK)
            goto fail;
    }

    char source[256];
    unsigned flags = 0;
    t0 = vb_now();
    if (o->vertices) {
        vb_vertex_format fmt;
        rc = vb_vertex_read_file(ctx, o->vertices, &mine, &fmt, &lines);
        if (rc == VB_OK)
            rc = keep_claimed(ctx, &mine, &lines, o->vertices);
        if (rc != VB_OK)
            goto fail;
        if (fmt == VB_VFMT_VORONOTA)
            flags |= VB_CGAL_ALLOW_SPLIT;
        snprintf(source, sizeof source, "%s", o->vertices);
    } else if (o->reference) {
        rc = vb_reference(ctx, set, &mine);
        if (rc != VB_OK)
            goto fail;
        snprintf(source, sizeof source, "vorball reference");
    } else {
        vb_vertices_result res;
        vb_vertices_result_init(&res);
        vb_vertices_config cfg = o->po.cfg;
        vb_cli_progress_attach(ctx);
        rc = vb_vertices_run_default(ctx, set, &cfg, &res);
        vb_cli_progress_clear();
        if (rc == VB_OK) {
            /* The certified list moves over; the rest of the result goes. */
            mine = res.certified;
            vb_vertex_list_init(&res.certified);
            snprintf(source, sizeof source, "vorball vertices (backend %s, %s)", res.backend,
                     res.device);
        }
        vb_vertices_result_free(&res);
        if (rc != VB_OK)
            goto fail;
    }
    double t_mine = vb_now() - t0;

    out = vb_cli_open_output(ctx, o->out);
    if (!out) {
        rc = vb_errcode(ctx);
        goto fail;
    }
    fprintf(out, "# vorball crosscheck of %s (%zu spheres) against CGAL %s %s\n", o->spheres,
            set->n, vb_cgal_version(),
            o->power ? "Regular_triangulation_3 (power diagram, weights R^2)"
                     : "Delaunay_triangulation_3 (Voronoi diagram of the centres)");
    if (o->power && !equal)
        fprintf(out, "# radii differ: CGAL's power diagram is not vorball's diagram; "
                     "ids compared, coordinates not\n");
    fprintf(out, "# vorball's vertices: %s\n", source);
    vb_cgal_diff diff;
    t0 = vb_now();
    rc = vb_cgal_compare(ctx, cgal, set, &mine, lines, flags, out, &diff);
    if (rc != VB_OK)
        goto fail;
    double t_cmp = vb_now() - t0;
    print_summary(out, &diff);
    rc = vb_cli_close_output(ctx, out, o->out);
    out = NULL;
    if (rc != VB_OK)
        goto fail;
    if (o->timing)
        fprintf(stderr,
                "crosscheck: %zu spheres, %zu vertices; CGAL %.3f s, %s %.3f s, "
                "comparison %.3f s\n",
                set->n, diff.cgal, t_cgal,
                o->vertices ? "reading vorball's file"
                            : o->reference ? "vorball reference" : "vorball vertices",
                t_mine, t_cmp);
    ex = vb_cgal_identical(&diff) ? VB_EXIT_OK : VB_EXIT_MISMATCH;
    goto done;
fail:
    ex = vb_cli_fail(ctx, rc);
    vb_cli_finish_output(ctx, out, o->out, rc);
done:
    free(lines);
    vb_vertex_list_free(&mine);
    vb_cgal_free(cgal);
    vb_spheres_free(set);
    return ex;
}

void vb_cmd_crosscheck_help(FILE *f)
{
    vb_cli_input_help_between(f, usage_head, usage_tail);
}

int vb_cmd_crosscheck(int argc, char **argv)
{
    vb_ctx *ctx = NULL;
    if (vb_open(&ctx, NULL) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        return VB_EXIT_NOMEM;
    }
    options o;
    int ex = parse_args(ctx, argc, argv, &o);
    if (ex == VB_EXIT_OK)
        ex = run(ctx, &o);
    vb_close(ctx);
    return ex;
}
