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
            "\n"
            "  -d, --dim 2|3          grid dimension (default 2; 3 with --protein)\n"
            "  -n, --size N           grid side, a power of two (default 512)\n"
            "  -k, --seeds K          generate K seeds (default 100)\n"
            "      --dist D           uniform|clustered|shell (default uniform)\n"
            "      --rng S            generator seed (default 1)\n"
            "      --protein FILE     seeds at the atom centres of FILE (PDB, mmCIF, PQR, XYZR)\n"
            "                         fitted into an [n]^3 grid\n"
            "      --margin A         protein: margin around the atoms in Angstrom (default 2)\n"
            "  -V, --variant V[,V..]  jfa|jfa+1|jfa+2|1+jfa|facet|facet-full|exact|\n"
            "                         exact-boundary|all (default jfa+1; all: the first five\n"
            "                         and exact). exact: the exact diagram by tiles (complete\n"
            "                         seed lists per tile, exact decisions); exact-boundary:\n"
            "                         the same and its boundary pixels counted\n"
            "  -m M                   Facet-JFA start resolution (default: smallest without\n"
            "                         seed collisions)\n"
            "      --fuse-cells C     Facet-JFA on OpenCL: the coarse JFA and the levels of at\n"
            "                         most C cells run in one launch (default 4096 in 2D,\n"
            "                         1024 in 3D; 1: one launch per phase, as the paper)\n"
            "      --device D         auto|gpu|cpu|ref (default auto: GPU, else PoCL, else ref)\n"
            "      --check            compare with the exact diagram (wrong pixels, distance\n"
            "                         errors, boundary pixels)\n"
            "      --repeat R         run each variant R times after one warm-up run; times\n"
            "                         are mean and minimum\n"
            "                         (time: wall clock of the algorithm on the device; gpu:\n"
            "                         the summed execution of its commands)\n"
            "      --json             print the figures as JSON\n"
            "      --png FILE         picture: 2D diagram coloured by label, boundaries black;\n"
            "                         3D: the slices of --slice side by side\n"
            "      --slice Z[,Z..]    3D slices for --png (default n/2)\n"
            "  -o FILE                output of the figures (default stdout)\n");
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
