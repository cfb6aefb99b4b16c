/* `vorball bench`: per-stage timings of the vertex pipeline on one or more
 * inputs (the seed paper's Table 1), as a table or JSON. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "pipeline_options.h"
#include "progress.h"
#include "vb_json.h"
#include "vb_default.h"
#include "vb_world.h"
#include "vertex_parts.h"

void vb_cmd_bench_help(FILE *f)
{
    fprintf(f,
            "usage: vorball bench [options] INPUT... \n\n"
            "Runs the certified vertex pipeline on each input and prints, per input and\n"
            "sample count: atoms, samples, certified vertices, per-stage seconds (cull,\n"
            "upload, envelope, vertices, matching, certification), the total and the MiB\n"
            "of device buffers held at once (dev_MiB, 0 on host threads).\n\n"
            "  --samples S[,S...]   sample counts to run (default %u)\n"
            "  --repeat N           runs per configuration; the fastest total is kept (1);\n"
            "                       JSON also gives the first run's total (cold caches)\n"
            "  --cold               open the OpenCL device for every run, as `vertices`\n"
            "                       does (its set-up then counts in the total); by default\n"
            "                       it is opened once and its set-up time reported apart\n"
            "  --device D           auto, gpu, cpu or ref (as for vertices)\n"
            "  --proposer P         cover (default) or sampling (as for vertices)\n"
            "  --tol T, --tiles T, --threads N, --all-pairs  as for vertices\n"
            "  --json               JSON array instead of the table (it adds device_bytes_peak,\n"
            "                       the device buffers a run held at once)\n"
            "  -o FILE              output file (default stdout)\n"
            "A progress bar goes to stderr when it is a terminal and a run is slow.\n"
            "Under mpirun -np N each run is split over the ranks as `vertices` splits it:\n"
            "stage times are the slowest rank's, total is rank 0's wall clock from a\n"
            "barrier to the merged vertices (JSON adds ranks and combine, the gather\n"
            "and merge).\n",
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
        if (end == s || v < VB_SAMPLES_MIN || v > VB_SAMPLES_MAX || (*end != ',' && *end != '\0'))
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

static void row(vb_ctx *ctx, FILE *f, int json, int first, const char *input, size_t atoms,
                const vb_vertices_result *r, const vb_cli_vertex_totals *tot, double first_total,
                double device_setup)
{
    const vb_stage_times *t = &r->proposal.times;
    if (json) {
        fprintf(f, "%s\n  {\"input\": ", first ? "" : ",");
        vb_json_write_string(f, input);
        fprintf(f, ", \"atoms\": %zu, \"samples\": %u, \"backend\": ", atoms, r->proposal.samples);
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
                "\"total_first_run\": %.6f, \"device_setup\": %.6f, "
                "\"certify_overlap\": %.6f, \"certify_parts\": %zu, \"device_bytes_peak\": %llu, "
                "\"cert_filter\": %.6f",
                r->certified.n, (unsigned long long)r->proposal.first_cell,
                (unsigned long long)r->proposal.from_sampling, tot->rejected,
                (unsigned long long)r->proposal.incomplete,
                (unsigned long long)r->proposal.sampled_vertices,
                (unsigned long long)r->proposal.vertices_incomplete,
                (unsigned long long)r->proposal.targeted_found, t->cull, t->upload, t->envelope,
                t->vertices, t->matching, t->targeted, t->tangent, t->completion, r->t_certify,
                r->t_setup, r->t_setup_wait, r->t_total,
                first_total, device_setup, r->t_certify_overlap, r->certify_parts,
                (unsigned long long)r->proposal.device_bytes_peak, r->proposal.t_cert_filter);
        const vb_proposal *p = &r->proposal;
        fprintf(f,
                ", \"cover_device\": %.6f, \"cover_kernel\": [%.6f, %.6f, %.6f, %.6f], "
                "\"cover_launches\": [%llu, %llu, %llu, %llu]",
                p->t_cover_device, p->cover_clocks.kernel_s[0], p->cover_clocks.kernel_s[1], p->cover_clocks.kernel_s[2],
                p->cover_clocks.kernel_s[3], (unsigned long long)p->cover_clocks.launches[0],
                (unsigned long long)p->cover_clocks.launches[1], (unsigned long long)p->cover_clocks.launches[2],
                (unsigned long long)p->cover_clocks.launches[3]);
        /* Where the cover's time went, step by step (the --stats lines
         * cover_*: its device's launches and the host's side). */
        vb_stat_fields fs;
        fs.n = 0;
        vb_vertices_stats(ctx, r, &fs);
        fputs(", \"cover_steps\": ", f);
        vb_stat_fields_write_json(f, &fs, 0, "cover_");
        if (vb_world_size() > 1)
            fprintf(f, ", \"ranks\": %d, \"combine\": %.6f, \"merged_repeats\": %zu}",
                    vb_world_size(), tot->t_combine, tot->repeats);
        else
            fputs("}", f);
    } else {
        if (first && device_setup > 0.0)
            fprintf(f, "# backend %s: %s (opened once, in %.3f s)\n", r->backend, r->device,
                    device_setup);
        else if (first)
            fprintf(f, "# backend %s: %s (opened for every run)\n", r->backend, r->device);
        fprintf(f, "%-18s %6zu %7u %9zu %8.3f %8.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.1f\n",
                input, atoms, r->proposal.samples, r->certified.n, t->cull, t->upload,
                t->envelope, t->vertices, t->matching, r->t_certify, r->t_total,
                (double)r->proposal.device_bytes_peak / 1048576.0);
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
    if (!inputs || vb_world_open_ctx(&ctx)) {
        free(inputs);
        return vb_cli_fail(NULL, VB_ENOMEM);
    }
    int code = VB_EXIT_OK;
    for (int i = 1; i < argc && code == VB_EXIT_OK; i++) {
        const char *a = argv[i];
        int r;
        if (strcmp(a, "--samples") == 0 && i + 1 < argc) {
            if ((nsamples = parse_samples(argv[++i], samples)) < 1)
                code = vb_cli_usage_error("bench", "--samples needs S or S1,S2,... in %u..%u",
                                            VB_SAMPLES_MIN, VB_SAMPLES_MAX);
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
    for (int k = 0; k < ninputs && code == VB_EXIT_OK; k++)
        code = vb_world_check_input("bench", inputs[k]);
    if (code != VB_EXIT_OK) {
        free(inputs);
        vb_close(ctx);
        return code;
    }
    /* Rank 0 writes; every rank runs its part of each run. */
    int rank0 = vb_world_rank() == 0;
    FILE *out = rank0 ? vb_cli_open_output(ctx, outpath) : NULL;
    int rc = rank0 && !out ? vb_errcode(ctx) : VB_OK;
    vb_cover_options share;
    int busy = vb_cli_vertices_part(ctx, &po.cfg, &share);
    vb_vertices_engine *dev = NULL;
    if (rc == VB_OK && !cold && busy)
        rc = vb_vertices_open(ctx, vb_default_backends(), &po.cfg, &dev);
    rc = vb_world_agree(ctx, rc);
    if (rc == VB_OK && rank0 && json)
        fputs("[", out);
    else if (rc == VB_OK && rank0)
        fprintf(out, "%-18s %6s %7s %9s %8s %8s %9s %9s %9s %9s %9s %9s\n", "input", "atoms",
                "samples", "vertices", "cull", "upload", "envelope", "vertices", "matching",
                "certify", "total", "dev_MiB");
    int first = 1;
    for (int k = 0; k < ninputs && rc == VB_OK; k++) {
        vb_sphere_set *set = NULL;
        int quiet = vb_world_quiet(ctx);
        rc = vb_world_agree(ctx, vb_cli_load_spheres(ctx, inputs[k], &po.in, 4, &set));
        vb_world_loud(ctx, quiet);
        for (int s = 0; s < nsamples && rc == VB_OK; s++) {
            vb_vertices_result best;
            vb_vertices_result_init(&best);
            vb_cli_vertex_totals best_tot;
            memset(&best_tot, 0, sizeof best_tot);
            double first_total = 0.0;
            for (size_t rep = 0; rep < repeat && rc == VB_OK; rep++) {
                vb_vertices_result r;
                vb_vertices_result_init(&r);
                vb_cli_vertex_totals tot;
                po.cfg.propose.samples = samples[s];
                vb_vertices_config cfg = po.cfg;
                vb_cli_progress_attach(ctx);
                /* Split runs start together and end when rank 0 holds the
                 * merged vertices. */
                vb_world_barrier();
                double t0 = vb_now();
                if (busy)
                    rc = cold ? vb_vertices_run_default(ctx, set, &cfg, &r)
                              : vb_vertices_run_on(ctx, dev, set, &cfg, &r);
                vb_cli_progress_clear();
                rc = vb_world_agree(ctx, rc);
                if (rc == VB_OK)
                    rc = vb_world_agree(ctx, vb_cli_vertices_combine(ctx, &r, &tot));
                if (vb_world_size() > 1)
                    r.t_total = vb_now() - t0;
                if (rep == 0)
                    first_total = r.t_total;
                if (rc == VB_OK && (rep == 0 || r.t_total < best.t_total)) {
                    vb_vertices_result_free(&best);
                    best = r;
                    best_tot = tot;
                } else {
                    vb_vertices_result_free(&r);
                }
            }
            if (rc == VB_OK && rank0) {
                row(ctx, out, json, first, base_name(inputs[k]), set->n, &best, &best_tot,
                    first_total, cold || !dev ? 0.0 : vb_vertices_open_seconds(dev));
                fflush(out);
                first = 0;
            }
            vb_vertices_result_free(&best);
        }
        vb_spheres_free(set);
    }
    vb_vertices_close(dev);
    if (rc == VB_OK && rank0 && json)
        fputs("\n]\n", out);
    if (out)
        rc = vb_cli_finish_output(ctx, out, outpath, rc);
    code = vb_world_end(ctx, rc);
    free(inputs);
    vb_close(ctx);
    return code;
}
