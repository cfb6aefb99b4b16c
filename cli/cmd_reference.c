/* `vorball reference IN`: every Voronoi vertex of the spheres, exactly, by
 * brute force over quadruples (verify/judge/reference.c). Small inputs only. */
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "progress.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"

static const char *const usage_text =
    "usage: vorball reference IN [-o FILE] [--output-format tsv|json|voronota|npz]\n"
    "                         [--stats] [--force] [input options]\n"
    "\n"
    "Computes every vertex of the additively weighted Voronoi diagram of the\n"
    "spheres in IN ('-' reads stdin) exactly: all quadruples, a proven interval\n"
    "filter, GMP for what it cannot decide. Each vertex is listed once with all\n"
    "the spheres it touches; coordinates are the exact values rounded to the\n"
    "nearest double. Cost grows as n^4: meant for inputs of a few hundred spheres;\n"
    "above 500 it refuses (E130, exit 40) unless --force.\n"
    "\n"
    "  -o FILE          write the vertices to FILE (default stdout)\n"
    "  --output-format F  tsv (default), json, voronota or npz, as for `vorball vertices`\n"
    "                   (--format, as for every command, is the input format)\n"
    "  --stats          print filter and exact-evaluation counts and the time to stderr\n"
    "  --force          run on more than 500 spheres (minutes to hours)\n";

void vb_cmd_reference_help(FILE *f)
{
    vb_cli_input_help_between(f, usage_text, NULL);
}

int vb_cmd_reference(int argc, char **argv)
{
    const char *in_path = NULL, *out_path = NULL, *fmt_name = "tsv";
    int stats = 0, force = 0;
    vb_cli_input_opts in;
    vb_cli_input_defaults(&in);
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0) {
            if (++i >= argc)
                return vb_cli_usage_error(argv[0], "-o needs a file name");
            out_path = argv[i];
        } else if (strcmp(argv[i], "--output-format") == 0) {
            if (++i >= argc)
                return vb_cli_usage_error(argv[0],
                                          "--output-format needs tsv, json, voronota or npz");
            fmt_name = argv[i];
        } else if (strcmp(argv[i], "--stats") == 0) {
            stats = 1;
        } else if (strcmp(argv[i], "--force") == 0) {
            force = 1;
        } else {
            int used = vb_cli_input_option(&in, argc, argv, &i);
            if (used < 0)
                return VB_EXIT_USAGE;
            if (used)
                continue;
            if (argv[i][0] == '-' && argv[i][1] != '\0')
                return vb_cli_usage_error(argv[0], "unknown option '%s'", argv[i]);
            if (in_path)
                return vb_cli_usage_error(argv[0], "one input file only ('%s' and '%s')",
                                          in_path, argv[i]);
            in_path = argv[i];
        }
    }
    if (!in_path)
        return vb_cli_usage_error(argv[0], "no input file (use '-' for stdin)");

    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK) {
        fprintf(stderr, "vorball: E%d: out of memory\n", vb_diag_number(VB_ENOMEM));
        return VB_EXIT_NOMEM;
    }
    vb_cli_progress_attach(ctx);
    vb_vertex_format fmt;
    int rc = vb_vertex_format_parse(ctx, fmt_name, &fmt);
    if (rc != VB_OK) {
        vb_close(ctx);
        return vb_cli_usage_error(argv[0], "unknown output format '%s'", fmt_name);
    }
    vb_sphere_set *set = NULL;
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    int exit_code = VB_EXIT_OK;
    double t0 = vb_now();
    rc = vb_cli_load_spheres(ctx, in_path, &in, 4, &set);
    if (rc == VB_OK)
        rc = vb_reference_run(ctx, set, force, in_path, &out);
    double t1 = vb_now();
    if (rc == VB_OK) {
        FILE *f = vb_cli_open_output(ctx, out_path);
        if (!f) {
            rc = vb_errcode(ctx);
        } else {
            char comment[256];
            snprintf(comment, sizeof comment, "vorball reference %s: %zu spheres, %zu vertices",
                     in_path, set->n, out.n);
            char opts[4096];
            vb_provenance prov;
            vb_cli_provenance(&prov, opts, sizeof opts, in_path, set->n);
            rc = vb_vertex_write_prov(ctx, f, &out, fmt, &prov, comment);
            rc = vb_cli_finish_output(ctx, f, out_path, rc);
        }
    }
    if (rc == VB_OK && stats) {
        const vb_stats *st = vb_ctx_stats(ctx);
        fprintf(stderr,
                "reference: %zu spheres, %zu vertices, %.3f s\n"
                "quadruples: %llu, refuted by the filter %llu\n"
                "filter: %llu calls, %llu undecided (%.4f%%), exact evaluations %llu\n",
                set->n, out.n, t1 - t0, (unsigned long long)st->candidates,
                (unsigned long long)st->rejected, (unsigned long long)st->filter_calls,
                (unsigned long long)st->filter_failures,
                st->filter_calls ? 100.0 * (double)st->filter_failures / (double)st->filter_calls
                                 : 0.0,
                (unsigned long long)st->exact_evals);
    }
    if (rc != VB_OK)
        exit_code = vb_cli_fail(ctx, rc);
    vb_vertex_list_free(&out);
    vb_spheres_free(set);
    vb_cli_progress_clear();
    vb_close(ctx);
    return exit_code;
}
