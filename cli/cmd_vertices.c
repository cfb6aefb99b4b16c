/* `vorball vertices`: certified Voronoi vertices of spheres by the seed
 * paper's sampling pipeline, optionally with the cell topology. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "vb_topology.h"
#include "vb_vertex_io.h"
#include "pipeline_options.h"
#include "vb_default.h"
#include "vb_diag.h"

static void help(FILE *f)
{
    fprintf(f,
            "usage: vorball vertices [options] INPUT|-\n\n"
            "Voronoi vertices of the spheres (additively weighted diagram). By default a\n"
            "direction cover of every cell (rigorous bounds of the lower envelope of the\n"
            "bisectors over patches of directions) proves which neighbours can meet in the\n"
            "cell; every quadruple of them is solved exactly and each root certified (it\n"
            "touches its four spheres and no sphere enters it). Every line written is a\n"
            "certified vertex with all the spheres it touches, and the header says whether\n"
            "the list is proven complete.\n\n"
            "  -o FILE              output file (default stdout)\n"
            "  --output-format F    tsv (default), json or voronota\n"
            "  --device D           auto (default: a GPU, else PoCL on the CPU), gpu, cpu, or\n"
            "                       ref (plain-C reference backend; same output)\n"
            "  --proposer P         how candidates are proposed: cover (default; a direction\n"
            "                       cover of every cell that proves no vertex is missing)\n"
            "                       or sampling (the seed paper's rays; proves nothing about\n"
            "                       completeness); the vertices written are the same\n"
            "  --samples S          S x S rays per cube face, 6 S^2 per sphere (default %u)\n"
            "  --tol T              Newton / matching tolerance in input units\n"
            "                       (default 1e-5 of the bounding-box diagonal)\n"
            "  --topology FILE      write faces (sphere pairs) and edges (vertex pairs)\n"
            "                       from the sampling's evidence (implies --proposer sampling)\n"
            "  --tiles T            culling tiles per cube face side, a power of two\n"
            "                       (default: from S)\n"
            "  --all-pairs          no neighbour culling (every cell tests all bisectors)\n"
            "  --threads N          host threads (default: VORBALL_THREADS or all CPUs);\n"
            "                       the output does not depend on it\n"
            "  --stats              pipeline and certifier counters on stderr\n",
            VB_SAMPLER_DEFAULT_SAMPLES);
    vb_cli_input_help(f);
    fprintf(f,
            "\nCells of spheres on the hull are unbounded: the cover treats infinity as one\n"
            "more label; with --proposer sampling rays are clipped at a distance derived\n"
            "from the input (see README) and a vertex beyond it is never written.\n"
            "Warnings W760-W779 come from this command.\n");
}

static void print_stats(vb_ctx *ctx, const vb_vertices_result *r)
{
    const vb_sampler_result *s = &r->sampler;
    const vb_stats *st = vb_ctx_stats(ctx);
    fprintf(stderr,
            "backend\t%s\ndevice\t%s\nsamples\t%u\ntiles\t%u\ntol\t%.6g\nclip\t%.6g\n"
            "rays\t%llu\nbisectors\t%llu\nraw_candidates\t%llu\nvertices_matched\t%llu\n"
            "complete_first_pass\t%llu\ntargeted_searches\t%llu\ntargeted_found\t%llu\n"
            "incomplete_after_search\t%llu\nsampled_vertices\t%llu\n"
            "vertices_incomplete\t%llu\ndropped_tangent_test\t%llu\nfrom_sampling\t%llu\n"
            "swaps\t%llu\nring_tries\t%llu\nfirst_cell\t%llu\ncandidates_certified\t%llu\n"
            "certifier_rejected\t%zu\nrepair_candidates\t%zu\ncertified_vertices\t%zu\n"
            "max_candidate_distance\t%.3g\n"
            "filter_calls\t%llu\nfilter_failures\t%llu\nexact_evals\t%llu\n",
            r->backend, r->device, s->samples, s->tiles, s->tol, s->clip,
            (unsigned long long)s->rays, (unsigned long long)s->bisectors,
            (unsigned long long)s->raw_candidates, (unsigned long long)s->clusters,
            (unsigned long long)s->complete_first, (unsigned long long)s->targeted_searches,
            (unsigned long long)s->targeted_found, (unsigned long long)s->incomplete,
            (unsigned long long)s->sampled_vertices, (unsigned long long)s->vertices_incomplete,
            (unsigned long long)s->dropped, (unsigned long long)s->from_sampling,
            (unsigned long long)s->swaps, (unsigned long long)s->ring_tries,
            (unsigned long long)s->first_cell, (unsigned long long)s->candidates.n,
            r->rejected.n, r->repaired_candidates, r->certified.n, r->max_dist,
            (unsigned long long)st->filter_calls, (unsigned long long)st->filter_failures,
            (unsigned long long)st->exact_evals);
}

static int write_topology(vb_ctx *ctx, const char *path, const vb_sphere_set *set,
                          const vb_vertices_result *r)
{
    vb_topology topo;
    int rc = vb_topology_build(ctx, set, &r->sampler.topo, &r->certified, &topo);
    if (rc != VB_OK)
        return rc;
    if (topo.unresolved)
        vb_warn(ctx, VB_W_TOPO_UNPAIRED, NULL, 0,
                "%zu trisector(s) whose edges could not be paired (no trisector curve for "
                "the triple in doubles, or a closed edge through one vertex)",
                topo.unresolved);
    FILE *f = vb_cli_open_output(ctx, path);
    rc = f ? vb_topology_write(ctx, f, &topo) : VB_EIO;
    if (f)
        rc = rc ? rc : vb_cli_close_output(ctx, f, path);
    vb_topology_free(&topo);
    return rc;
}

int vb_cmd_vertices(int argc, char **argv)
{
    vb_pipeline_opts po;
    vb_pipeline_opts_defaults(&po);
    const char *outpath = NULL, *input = NULL, *topo_path = NULL;
    vb_vertex_format vfmt = VB_VFMT_TSV;
    int stats = 0;
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return VB_EXIT_NOMEM;
    int code = VB_EXIT_OK;
    for (int i = 1; i < argc && code == VB_EXIT_OK; i++) {
        const char *a = argv[i];
        int r;
        if (vb_cli_is_help(a)) {
            help(stdout);
            vb_close(ctx);
            return VB_EXIT_OK;
        } else if ((r = vb_pipeline_option("vertices", argc, argv, &i, &po, ctx)) != 0) {
            code = r < 0 ? VB_EXIT_USAGE : code;
        } else if (strcmp(a, "-o") == 0 && i + 1 < argc) {
            outpath = argv[++i];
        } else if (strcmp(a, "--output-format") == 0 && i + 1 < argc) {
            if (vb_vertex_format_parse(ctx, argv[++i], &vfmt) != VB_OK)
                code = vb_cli_usage_error("vertices", "%s", vb_errmsg(ctx));
        } else if (strcmp(a, "--topology") == 0 && i + 1 < argc) {
            topo_path = argv[++i];
            po.cfg.sampler.topology = 1;
        } else if (strcmp(a, "--stats") == 0) {
            stats = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            code = vb_cli_usage_error("vertices", "unknown option '%s'", a);
        } else if (!input) {
            input = a;
        } else {
            code = vb_cli_usage_error("vertices", "more than one input ('%s')", a);
        }
    }
    if (code == VB_EXIT_OK && !input)
        code = vb_cli_usage_error("vertices", "no input file (use - for stdin)");
    /* Faces and edges come from the sampling's evidence. */
    if (code == VB_EXIT_OK && topo_path && !po.cfg.proposer)
        po.cfg.proposer = "sampling";
    if (code == VB_EXIT_OK && topo_path && strcmp(po.cfg.proposer, "sampling") != 0)
        code = vb_cli_usage_error("vertices", "--topology needs --proposer sampling");
    if (code != VB_EXIT_OK) {
        vb_close(ctx);
        return code;
    }
    vb_sphere_set *set = NULL;
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    int rc = vb_cli_load_spheres(ctx, input, &po.in, 4, &set);
    vb_cli_bar bar;
    vb_cli_bar_attach(&bar, &po.cfg.sampler);
    if (rc == VB_OK)
        rc = vb_vertices_run_default(ctx, set, &po.cfg, &res);
    vb_cli_bar_clear(&bar);
    if (rc == VB_OK && stats)
        print_stats(ctx, &res);
    /* A cover's refused roots are quadruples that hold no vertex: expected,
     * and no warning. */
    if (rc == VB_OK && res.rejected.n && !res.sampler.complete)
        vb_warn(ctx, VB_W_CERT_REJECTED, NULL, 0, "the certifier rejected %zu candidate(s)", res.rejected.n);
    char note[512];
    vb_vertices_certificate(&res, note, sizeof note);
    if (rc == VB_OK) {
        FILE *out = vb_cli_open_output(ctx, outpath);
        rc = out ? vb_vertex_write(ctx, out, &res.certified, vfmt, note[0] ? note : NULL) : VB_EIO;
        if (out)
            rc = rc ? rc : vb_cli_close_output(ctx, out, outpath);
    }
    if (rc == VB_OK && topo_path)
        rc = write_topology(ctx, topo_path, set, &res);
    code = rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
    vb_vertices_result_free(&res);
    vb_spheres_free(set);
    vb_close(ctx);
    return code;
}
