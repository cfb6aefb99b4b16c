/* `vorball vertices`: certified Voronoi vertices of spheres (the direction
 * cover by default, the seed paper's sampling on request), completed by the
 * library (arc closure, topology, the certificate) on request. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "pipeline_options.h"
#include "progress.h"
#include "vorball.h"
#include "vb_page.h"
#include "vb_stage_clock.h"
#include "vb_vertex_page.h"
#include "vb_world.h"
#include "vertex_parts.h"
#include "vertices_periodic.h"

void vb_cmd_vertices_help(FILE *f)
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
            "  --output-format F    tsv (default), json, voronota or npz (NumPy arrays)\n"
            "  --device D           auto (default: a GPU, on host threads below 20,000\n"
            "                       spheres; else PoCL on the CPU), gpu, cpu, or ref\n"
            "                       (plain-C reference backend); the same output on each\n"
            "  --proposer P         how candidates are proposed: cover (default; a direction\n"
            "                       cover of every cell that proves no vertex is missing)\n"
            "                       or sampling (the seed paper's rays; proves nothing about\n"
            "                       completeness); the vertices written are the same\n"
            "  --samples S          S x S rays per cube face, 6 S^2 per sphere (default %u)\n"
            "  --tol T              Newton / matching tolerance in input units\n"
            "                       (default 1e-5 of the bounding-box diagonal)\n"
            "  --topology FILE      write faces (sphere pairs) and edges (vertex pairs):\n"
            "                       exact, from arc closure (implies --arcs); with\n"
            "                       --proposer sampling and no --arcs, from the sampling's\n"
            "                       evidence in doubles as the seed paper's Sec. 4\n"
            "  --tiles T            culling tiles per cube face side, a power of two\n"
            "                       (default: from S)\n"
            "  --all-pairs          no neighbour culling (every cell tests all bisectors)\n"
            "  --threads N          host threads (default: VORBALL_THREADS or all CPUs);\n"
            "                       the output does not depend on it\n"
            "  --stats              pipeline and certifier counters on stderr\n"
            "  --arcs               after the proposer, trace every Voronoi edge of the\n"
            "                       certified vertices exactly to its next vertex (arc\n"
            "                       closure); vertices found on the way are certified and\n"
            "                       written, and one more header line gives the counts\n"
            "  --html FILE          a results page that opens offline in a browser: the\n"
            "                       spheres and their certified vertices, with the counts\n"
            "                       (inputs of at most 2000 spheres; over that E133)\n"
            "Under mpirun -np N (a build with VORBALL_WITH_MPI) every rank reads INPUT,\n"
            "the cover's cells are split over the ranks (--proposer sampling runs on\n"
            "rank 0 alone, W830) and rank 0 writes the merged output, byte-identical to\n"
            "one process's.\n",
            VB_SAMPLER_DEFAULT_SAMPLES);
    vb_cli_periodic_help(f);
    vb_cli_input_help(f);
    fprintf(f,
            "\nCells of spheres on the hull are unbounded: the cover treats infinity as one\n"
            "more label; with --proposer sampling rays are clipped at a distance derived\n"
            "from the input (see README) and a vertex beyond it is never written.\n"
            "Warnings W760-W779 come from this command.\n");
}

/* The library's counters (vb_vertices_write_stats), and under MPI the
 * ranks' totals and the merge. */
static void print_stats(vb_ctx *ctx, const vb_vertices_result *r, const vb_cli_vertex_totals *tot)
{
    vb_vertices_write_stats(ctx, stderr, r);
    if (vb_world_size() > 1)
        fprintf(stderr,
                "ranks\t%d\nranks_candidates_certified\t%zu\nranks_certifier_rejected\t%zu\n"
                "ranks_repair_candidates\t%zu\nmerged_repeats\t%zu\ncombine_s\t%.3f\n",
                vb_world_size(), tot->candidates, tot->rejected, tot->repaired, tot->repeats,
                tot->t_combine);
}

/* The topology file, built by the completion (vb_complete.h). */
static int write_topology(vb_ctx *ctx, const char *path, const vb_topology *topo)
{
    FILE *f = vb_cli_open_output(ctx, path);
    int rc = f ? vb_topology_write(ctx, f, topo) : vb_errcode(ctx);
    return vb_cli_finish_output(ctx, f, path, rc);
}

int vb_cmd_vertices(int argc, char **argv)
{
    vb_pipeline_opts po;
    vb_pipeline_opts_defaults(&po);
    const char *outpath = NULL, *input = NULL, *topo_path = NULL, *html = NULL;
    vb_vertex_format vfmt = VB_VFMT_TSV;
    int stats = 0;
    vb_completion_opts co = {0};
    vb_cli_periodic per = {0};
    vb_ctx *ctx;
    if (vb_world_open_ctx(&ctx))
        return vb_cli_fail(NULL, VB_ENOMEM);
    int code = VB_EXIT_OK;
    for (int i = 1; i < argc && code == VB_EXIT_OK; i++) {
        const char *a = argv[i];
        int r;
        if ((r = vb_pipeline_option("vertices", argc, argv, &i, &po, ctx)) != 0) {
            code = r < 0 ? VB_EXIT_USAGE : code;
        } else if ((r = vb_cli_periodic_option("vertices", argc, argv, &i, &per)) != 0) {
            code = r < 0 ? VB_EXIT_USAGE : code;
        } else if (strcmp(a, "-o") == 0 && i + 1 < argc) {
            outpath = argv[++i];
        } else if (strcmp(a, "--output-format") == 0 && i + 1 < argc) {
            if (vb_vertex_format_parse(ctx, argv[++i], &vfmt) != VB_OK)
                code = vb_cli_usage_error("vertices", "%s", vb_errmsg(ctx));
        } else if (strcmp(a, "--topology") == 0 && i + 1 < argc) {
            topo_path = argv[++i];
            co.topology = 1;
        } else if (strcmp(a, "--html") == 0 && i + 1 < argc) {
            html = argv[++i];
        } else if (strcmp(a, "--stats") == 0) {
            stats = 1;
        } else if (strcmp(a, "--arcs") == 0) {
            co.arcs = 1;
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
    if (code == VB_EXIT_OK && per.on && (co.arcs || topo_path || vb_world_size() > 1 ||
                                         vfmt == VB_VFMT_VORONOTA || vfmt == VB_VFMT_NPZ))
        code = vb_cli_usage_error("vertices", "--periodic runs on one process, without --arcs, "
                                              "--topology and the voronota and npz formats");
    if (code == VB_EXIT_OK && per.on && html)
        code = vb_cli_usage_error("vertices", "--html does not run with --periodic");
    vb_completion_plan(&po.cfg, &co);
    if (code == VB_EXIT_OK)
        code = vb_world_check_input("vertices", input);
    if (code != VB_EXIT_OK) {
        vb_close(ctx);
        return code;
    }
    if (per.traj || per.frames) {
        if (vfmt == VB_VFMT_JSON) {
            vb_close(ctx);
            return vb_cli_usage_error("vertices", "--traj and --frames write tsv only");
        }
        code = vb_world_end(ctx, vb_cli_vertices_periodic_frames(ctx, input, &po.in, &per,
                                                                 &po.cfg, outpath, stats));
        vb_close(ctx);
        return code;
    }
    /* The whole process by stage (--stats, after the output is freed). */
    vb_stage_clock clk;
    vb_stage_clock_start(&clk);
    vb_sphere_set *set = NULL;
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    vb_cli_vertex_totals tot;
    /* Every rank reads the input; rank 0 alone prints its warnings. */
    int quiet = vb_world_quiet(ctx);
    int rc = vb_cli_check_output(ctx, html);
    if (rc == VB_OK && html)
        rc = vb_page_check(ctx, html);
    /* The device opens on its own thread while the input is read, where
     * the file's size says the run will use one (vb_vertices_open_early). */
    vb_vertices_early *early = NULL;
    if (rc == VB_OK && !per.on)
        rc = vb_vertices_open_early(ctx, vb_default_backends(), &po.cfg,
                                    vb_spheres_count_hint(input), &early);
    po.cfg.early = early;
    if (rc == VB_OK)
        rc = vb_cli_load_spheres_clocked(ctx, input, &po.in, 4, &set, &clk);
    /* A page too big is refused before the work, as every rank sees. */
    if (rc == VB_OK && html)
        rc = vb_vertex_page_check(ctx, set);
    vb_world_loud(ctx, quiet);
    if (per.on) {
        vb_vertices_early_free(early);
        if (rc == VB_OK)
            rc = vb_cli_vertices_periodic(ctx, set, &per, &po.cfg, input, outpath,
                                          vfmt == VB_VFMT_JSON, stats);
        code = vb_world_end(ctx, rc);
        vb_spheres_free(set);
        vb_close(ctx);
        return code;
    }
    vb_cover_options share;
    int busy = vb_cli_vertices_part(ctx, &po.cfg, &share);
    vb_cli_progress_attach(ctx);
    if (rc == VB_OK && busy)
        rc = vb_vertices_run_default(ctx, set, &po.cfg, &res);
    vb_cli_progress_clear();
    /* Rank 0 writes once every rank's part is certified and merged. */
    rc = vb_world_agree(ctx, rc);
    if (rc == VB_OK)
        rc = vb_world_agree(ctx, vb_cli_vertices_combine(ctx, &res, &tot));
    vb_stage_lap(&clk, VB_STAGE_RUN);
    int writer = rc == VB_OK && vb_world_rank() == 0;
    if (writer && stats)
        print_stats(ctx, &res, &tot);
    /* Rank 0 holds the merged list: it completes it (arc closure, faces
     * and edges, the certificate). */
    co.stats = stats ? stderr : NULL;
    vb_completion done;
    vb_completion_init(&done);
    if (writer) {
        rc = vb_vertices_complete(ctx, set, &res, tot.rejected, &co, &done);
        writer = rc == VB_OK;
    }
    vb_stage_lap(&clk, VB_STAGE_COMPLETE);
    int timed = writer && stats;
    if (writer) {
        const char *note = done.certificate;
        char opts[4096];
        vb_provenance prov;
        vb_cli_provenance(&prov, opts, sizeof opts, input, set->n);
        FILE *out = vb_cli_open_output(ctx, outpath);
        rc = out ? vb_vertex_write_prov(ctx, out, &res.certified, vfmt, &prov,
                                        note[0] ? note : NULL)
                 : vb_errcode(ctx);
        rc = vb_cli_finish_output(ctx, out, outpath, rc);
    }
    if (writer && rc == VB_OK && topo_path)
        rc = write_topology(ctx, topo_path, &done.topology);
    if (writer && rc == VB_OK && html) {
        char title[512];
        snprintf(title, sizeof title, "vorball vertices %s", input);
        rc = vb_vertex_page_write(ctx, html, title, set, &res.certified, done.certificate);
    }
    vb_cli_progress_clear();
    vb_stage_lap(&clk, VB_STAGE_WRITE);
    code = vb_world_end(ctx, rc);
    vb_completion_free(&done);
    vb_vertices_early_free(early);
    vb_vertices_result_free(&res);
    vb_spheres_free(set);
    vb_close(ctx);
    vb_stage_lap(&clk, VB_STAGE_FREE);
    if (timed && code == VB_EXIT_OK)
        vb_stage_clock_write(stderr, &clk);
    return code;
}
