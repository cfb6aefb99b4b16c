/* `vorball jfa`: discrete Voronoi diagrams on [n]^d grids by the JFA variants
 * and Facet-JFA, checked against the exact diagram, timed, pictured. */
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "jfa_png.h"
#include "vb_diag.h"
#include "vb_jfa.h"

void vb_cmd_jfa_help(FILE *f)
{
    fprintf(f,
            "usage: vorball jfa [options] [SEEDS|-]\n"
            "\n"
            "Discrete Voronoi diagram of seeds on an [n]^d grid (pixel p has its centre at p)\n"
            "by Jump Flooding (gather form) or Facet-JFA; ties go to the lowest seed index.\n"
            "SEEDS: text, one seed per line, 'x y' (2D) or 'x y z' (3D) in pixels,\n"
            "each coordinate in [-0.5, n-0.5). Without SEEDS or --protein, seeds are generated.\n"
            "\n");
    vb_jfa_help(f);
    vb_cli_input_help(f);
    fprintf(f,
            "\nCounts: 'pixels' is the number of work-items that ran a JFA step (the\n"
            "paper's pixels processed; exact: the voxels decided one by one, those of\n"
            "tiles left with one seed are filled); 'boundary' (Facet-JFA) the pixels left\n"
            "unmarked (exact-boundary: the boundary pixels). With --check, 'wrong' counts\n"
            "pixels whose seed is strictly farther than the nearest, 'differ' (JSON) those\n"
            "whose label is not the exact diagram's (ties to the lowest index).\n"
            "Warnings: W780 seeds lost to a shared start pixel, W781 no OpenCL device\n"
            "(reference backend used), W782 Facet-JFA cannot start coarser than n,\n"
            "W751 OpenCL failed mid-run (that run and the rest on the reference).\n");
}

/* The command line into the handle: the input options, then each of the
 * handle's options by name (the library checks its value), the seed file. */
static int parse_args(int argc, char **argv, vb_jfa *j, vb_cli_input_opts *io, int *exit_code)
{
    vb_cli_input_defaults(io);
    *exit_code = -1;
    const char *seeds_path = NULL;
    char err[512];
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        int r = vb_cli_input_option(io, argc, argv, &i);
        if (r < 0) {
            *exit_code = VB_EXIT_USAGE;
            return 0;
        }
        if (r > 0)
            continue;
        vb_option opt;
        int known = o[0] == '-' && o[1] && vb_jfa_option_find(o, &opt) == 0;
        int flag = known && opt.type == VB_OPT_FLAG;
        if (o[0] == '-' && o[1] && !flag && i + 1 >= argc) {
            *exit_code = vb_cli_usage_error("jfa", "option %s needs a value", o);
            return 0;
        }
        if (known) {
            if (vb_jfa_set(j, o, flag ? NULL : argv[++i], err, sizeof err) != 0) {
                *exit_code = vb_cli_usage_error("jfa", "%s", err);
                return 0;
            }
        } else if (o[0] == '-' && o[1]) {
            *exit_code = vb_cli_usage_error("jfa", "unknown option %s", o);
            return 0;
        } else if (seeds_path) {
            *exit_code = vb_cli_usage_error("jfa", "more than one seed file");
            return 0;
        } else
            vb_jfa_source_file(j, seeds_path = o);
    }
    if (vb_jfa_check(j, err, sizeof err) != 0) {
        *exit_code = vb_cli_usage_error("jfa", "%s", err);
        return 0;
    }
    return 1;
}

/* The picture of the last variant's labels into `path`. */
static int write_png(vb_ctx *ctx, const vb_jfa *j, const char *path)
{
    vb_jfa_info info;
    vb_jfa_info_get(j, &info);
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    int rc = vb_jfa_picture(ctx, j, NULL, &rgb, &w);
    if (!rc)
        rc = vb_png_write_rgb(ctx, path, w, info.n, rgb);
    free(rgb);
    return rc;
}

int vb_cmd_jfa(int argc, char **argv)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return vb_cli_fail(NULL, VB_ENOMEM);
    vb_jfa *j = NULL;
    vb_cli_input_opts io;
    int ec;
    if (vb_jfa_new(ctx, &j) != VB_OK) {
        ec = vb_cli_fail(ctx, VB_ENOMEM);
        vb_close(ctx);
        return ec;
    }
    if (!parse_args(argc, argv, j, &io, &ec)) {
        vb_jfa_free(j);
        vb_close(ctx);
        return ec;
    }
    vb_jfa_request q;
    vb_jfa_request_get(j, &q);
    /* Only the centres make seeds, but a protein is checked as every
     * command checks its input (radii, duplicates, magnitudes: the same
     * numbered errors); PQR's radius-0 points are legal. */
    vb_sphere_set *set = NULL;
    int rc = 0;
    if (q.protein && !(rc = vb_cli_load_spheres(ctx, q.protein, &io, 1, &set)))
        vb_jfa_source_spheres(j, set, q.protein);
    if (!rc)
        rc = vb_jfa_run(ctx, j);
    vb_spheres_free(set);
    if (!rc && q.png)
        rc = write_png(ctx, j, q.png);
    if (!rc) {
        FILE *f = vb_cli_open_output(ctx, q.out);
        if (!f)
            rc = vb_errcode(ctx);
        else {
            vb_jfa_write(j, f, q.json);
            rc = vb_cli_close_output(ctx, f, q.out);
        }
    }
    ec = rc ? vb_cli_fail(ctx, rc) : VB_EXIT_OK;
    vb_jfa_free(j);
    vb_close(ctx);
    return ec;
}
