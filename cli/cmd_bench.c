/* `vorball bench`: per-stage timings of the vertex pipeline on one or more
 * inputs (the seed paper's Table 1), as a table or JSON. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "pipeline_options.h"
#include "vb_json.h"
#include "vb_default.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: vorball bench [options] INPUT... \n\n"
            "Runs the certified vertex pipeline on each input and prints, per input and\n"
            "sample count: atoms, samples, certified vertices, per-stage seconds (cull,\n"
            "upload, envelope, vertices, matching, certification) and the total.\n\n"
            "  --samples S[,S...]   sample counts to run (default %u)\n"
            "  --repeat N           runs per configuration; the fastest total is kept (1);\n"
            "                       JSON also gives the first run's total (cold caches)\n"
            "  --cold               open the OpenCL device for every run, as `vertices`\n"
            "                       does (its set-up then counts in the total); by default\n"
            "                       it is opened once and its set-up time reported apart\n"
            "  --device D           auto, gpu, cpu or ref (as for vertices)\n"
            "  --tol T, --tiles T, --threads N, --all-pairs  as for vertices\n"
            "  --json               JSON array instead of the table\n"
            "  -o FILE              output file (default stdout)\n"
            "A progress bar goes to stderr when it is a terminal and a run is slow.\n",
            VB_SAMPLER_DEFAULT_SAMPLES);
    vb_cli_input_help(f);
}

/* Parses "30,60,80" into at most 32 sample counts; returns the count or -1. */
static int parse_samples(const char *s, unsigned *out)
{
    int n = 0;
    while (*s && n < 32) {
        char *end;
        unsigned long v = strtoul(s, &end, 10);
        if (end == s || v < 2 || v > 4096 || (*end != ',' && *end != '\0'))
            return -1;
        out[n++] = (unsigned)v;
        s = *end ? end + 1 : end;
    }
    return *s ? -1 : n;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

static void row(FILE *f, int json, int first, const char *input, size_t atoms,
                const vb_vertices_result *r, double first_total, double device_setup)
{
    const vb_stage_times *t = &r->sampler.times;
    if (json) {
        fprintf(f, "%s\n  {\"input\": ", first ? "" : ",");
        vb_json_write_string(f, input);
        fprintf(f, ", \"atoms\": %zu, \"samples\": %u, \"backend\": ", atoms, r->sampler.samples);
        vb_json_write_string(f, r->backend);
        fputs(", \"device\": ", f);
        vb_json_write_string(f, r->device);
        fprintf(f,
                ", \"vertices\": %zu, \"first_cell\": %llu, \"from_sampling\": %llu, "
                "\"rejected\": %zu, \"incomplete\": %llu, \"sampled_vertices\": %llu, "
                "\"vertices_incomplete\": %llu, \"targeted_found\": %llu, "
                "\"cull\": %.6f, \"upload\": %.6f, \"envelope\": %.6f, \"vertices_s\": %.6f, "
                "\"matching\": %.6f, \"targeted\": %.6f, \"tangent\": %.6f, \"completion\": %.6f, "
                "\"certification\": %.6f, \"setup\": %.6f, \"setup_wait\": %.6f, \"total\": %.6f, "
                "\"total_first_run\": %.6f, \"device_setup\": %.6f}",
                r->certified.n, (unsigned long long)r->sampler.first_cell,
                (unsigned long long)r->sampler.from_sampling, r->rejected.n,
                (unsigned long long)r->sampler.incomplete,
                (unsigned long long)r->sampler.sampled_vertices,
                (unsigned long long)r->sampler.vertices_incomplete,
                (unsigned long long)r->sampler.targeted_found, t->cull, t->upload, t->envelope,
                t->vertices, t->matching, t->targeted, t->tangent, t->completion, r->t_certify,
                r->t_setup, r->t_setup_wait, r->t_total,
                first_total, device_setup);
    } else {
        if (first && device_setup > 0.0)
            fprintf(f, "# backend %s: %s (opened once, in %.3f s)\n", r->backend, r->device,
                    device_setup);
        else if (first)
            fprintf(f, "# backend %s: %s (opened for every run)\n", r->backend, r->device);
        fprintf(f, "%-18s %6zu %7u %9zu %8.3f %8.3f %9.3f %9.3f %9.3f %9.3f %9.3f\n", input,
                atoms, r->sampler.samples, r->certified.n, t->cull, t->upload, t->envelope,
                t->vertices, t->matching, r->t_certify, r->t_total);
    }
}

int vb_cmd_bench(int argc, char **argv)
{
    vb_pipeline_opts po;
    vb_pipeline_opts_defaults(&po);
    unsigned samples[32] = {VB_SAMPLER_DEFAULT_SAMPLES};
    int nsamples = 1, json = 0, cold = 0;
    size_t repeat = 1;
    const char *outpath = NULL;
    const char **inputs = calloc((size_t)argc, sizeof *inputs);
    int ninputs = 0;
    vb_ctx *ctx;
    if (!inputs || vb_open(&ctx, NULL)) {
        free(inputs);
        return VB_EXIT_NOMEM;
    }
    int code = VB_EXIT_OK;
    for (int i = 1; i < argc && code == VB_EXIT_OK; i++) {
        const char *a = argv[i];
        int r;
        if (vb_cli_is_help(a)) {
            help(stdout);
            free(inputs);
            vb_close(ctx);
            return VB_EXIT_OK;
        } else if (strcmp(a, "--samples") == 0 && i + 1 < argc) {
            if ((nsamples = parse_samples(argv[++i], samples)) < 1)
                code = vb_cli_usage_error("bench", "--samples needs S or S1,S2,... in 2..4096");
        } else if ((r = vb_pipeline_option("bench", argc, argv, &i, &po, ctx)) != 0) {
            code = r < 0 ? VB_EXIT_USAGE : code;
        } else if (strcmp(a, "--repeat") == 0 && i + 1 < argc) {
            if (vb_cli_parse_size(argv[++i], &repeat) || repeat < 1)
                code = vb_cli_usage_error("bench", "--repeat needs a positive integer");
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (strcmp(a, "--cold") == 0) {
            cold = 1;
        } else if (strcmp(a, "-o") == 0 && i + 1 < argc) {
            outpath = argv[++i];
        } else if (a[0] == '-' && a[1] != '\0') {
            code = vb_cli_usage_error("bench", "unknown option '%s'", a);
        } else {
            inputs[ninputs++] = a;
        }
    }
    if (code == VB_EXIT_OK && ninputs == 0)
        code = vb_cli_usage_error("bench", "no input file");
    if (code != VB_EXIT_OK) {
        free(inputs);
        vb_close(ctx);
        return code;
    }
    FILE *out = vb_cli_open_output(ctx, outpath);
    int rc = out ? VB_OK : vb_errcode(ctx);
    vb_vertices_engine *dev = NULL;
    if (rc == VB_OK && !cold)
        rc = vb_vertices_open(ctx, vb_default_backends(), &po.cfg, &dev);
    if (rc == VB_OK && json)
        fputs("[", out);
    else if (rc == VB_OK)
        fprintf(out, "%-18s %6s %7s %9s %8s %8s %9s %9s %9s %9s %9s\n", "input", "atoms",
                "samples", "vertices", "cull", "upload", "envelope", "vertices", "matching",
                "certify", "total");
    int first = 1;
    for (int k = 0; k < ninputs && rc == VB_OK; k++) {
        vb_sphere_set *set = NULL;
        rc = vb_cli_load_spheres(ctx, inputs[k], &po.in, 4, &set);
        for (int s = 0; s < nsamples && rc == VB_OK; s++) {
            vb_vertices_result best;
            vb_vertices_result_init(&best);
            double first_total = 0.0;
            for (size_t rep = 0; rep < repeat && rc == VB_OK; rep++) {
                vb_vertices_result r;
                vb_vertices_result_init(&r);
                po.cfg.sampler.samples = samples[s];
                vb_vertices_config cfg = po.cfg;
                vb_cli_bar bar;
                vb_cli_bar_attach(&bar, &cfg.sampler);
                rc = cold ? vb_vertices_run_default(ctx, set, &cfg, &r)
                          : vb_vertices_run_on(ctx, dev, set, &cfg, &r);
                vb_cli_bar_clear(&bar);
                if (rep == 0)
                    first_total = r.t_total;
                if (rc == VB_OK && (rep == 0 || r.t_total < best.t_total)) {
                    vb_vertices_result_free(&best);
                    best = r;
                } else {
                    vb_vertices_result_free(&r);
                }
            }
            if (rc == VB_OK) {
                row(out, json, first, base_name(inputs[k]), set->n, &best, first_total,
                    cold ? 0.0 : vb_vertices_open_seconds(dev));
                fflush(out);
                first = 0;
            }
            vb_vertices_result_free(&best);
        }
        vb_spheres_free(set);
    }
    vb_vertices_close(dev);
    if (rc == VB_OK && json)
        fputs("\n]\n", out);
    rc = vb_cli_finish_output(ctx, out, outpath, rc);
    code = rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
    free(inputs);
    vb_close(ctx);
    return code;
}
