/* `vorball jfa`: discrete Voronoi diagrams on [n]^d grids by the JFA variants
 * and Facet-JFA, checked against the exact diagram, timed, pictured. */
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "jfa_png.h"
#include "vb_default.h"
#include "vbj_runs.h"
#include "vb_diag.h"

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

typedef struct {
    int dim_given, check, json, nv;
    vbj_setup set;
    vbj_distribution dist;
    vbj_variant v[VBJ_MAX_VARIANTS];
    const char *seeds_path, *protein, *png, *out, *slices, *device;
    vb_cli_input_opts io;
} jfa_args;

/* The field of the setup a numeric option sets, or NULL (--margin, a
 * double, is parsed beside them). */
static uint64_t *setup_number(vbj_setup *s, const char *o)
{
    return strcmp(o, "-d") == 0 || strcmp(o, "--dim") == 0     ? &s->dim
           : strcmp(o, "-n") == 0 || strcmp(o, "--size") == 0  ? &s->n
           : strcmp(o, "-k") == 0 || strcmp(o, "--seeds") == 0 ? &s->k
           : strcmp(o, "-m") == 0                              ? &s->m
           : strcmp(o, "--fuse-cells") == 0                    ? &s->fuse_cells
           : strcmp(o, "--repeat") == 0                        ? &s->repeat
                                                               : NULL;
}

static int parse_args(vb_ctx *ctx, int argc, char **argv, jfa_args *a, int *exit_code)
{
    memset(a, 0, sizeof *a);
    vbj_setup_defaults(&a->set);
    vbj_setup set = a->set;
    a->device = "auto";
    vbj_variants_parse(ctx, VBJ_VARIANTS_DEFAULT, a->v, &a->nv);
    vb_cli_input_defaults(&a->io);
    *exit_code = -1;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        int r = vb_cli_input_option(&a->io, argc, argv, &i);
        if (r < 0) {
            *exit_code = VB_EXIT_USAGE;
            return 0;
        }
        if (r > 0)
            continue;
        int flag = strcmp(o, "--check") == 0 || strcmp(o, "--json") == 0;
        if (o[0] == '-' && o[1] && !flag && i + 1 >= argc) {
            *exit_code = vb_cli_usage_error("jfa", "option %s needs a value", o);
            return 0;
        }
        size_t sz;
        uint64_t *num = NULL;
        if (strcmp(o, "--check") == 0)
            a->check = 1;
        else if (strcmp(o, "--json") == 0)
            a->json = 1;
        else if ((num = setup_number(&set, o)) != NULL || strcmp(o, "--margin") == 0) {
            /* The ranges are the library's (vbj_setup_check): a value that
             * does not parse, and an explicit 0 where 0 means "not given",
             * are stored as one the check refuses. */
            const char *v = argv[++i];
            if (num) {
                if (vb_cli_parse_size(v, &sz))
                    sz = num == &set.k ? 0 : SIZE_MAX;
                else if (sz == 0 && (num == &set.m || num == &set.fuse_cells))
                    sz = SIZE_MAX;
                *num = sz;
            } else if (vb_cli_parse_double(v, &set.margin))
                set.margin = -1.0;
            if (vbj_setup_check(ctx, &set) != VB_OK) {
                *exit_code = num == &set.dim ? vb_cli_usage_error("jfa", "%s", vb_errmsg(ctx))
                                             : vb_cli_usage_error("jfa", "%s '%s'",
                                                                  vb_errmsg(ctx), v);
                return 0;
            }
            a->dim_given |= num == &set.dim;
        } else if (strcmp(o, "--dist") == 0) {
            if (vbj_distribution_parse(ctx, argv[++i], &a->dist)) {
                *exit_code = vb_cli_usage_error("jfa", "%s", vb_errmsg(ctx));
                return 0;
            }
        } else if (strcmp(o, "--rng") == 0) {
            if (vb_cli_parse_size(argv[++i], &sz)) {
                *exit_code = vb_cli_usage_error("jfa", "bad --rng '%s'", argv[i]);
                return 0;
            }
            set.rng = sz;
        } else if (strcmp(o, "--protein") == 0)
            a->protein = argv[++i];
        else if (strcmp(o, "-V") == 0 || strcmp(o, "--variant") == 0) {
            if (vbj_variants_parse(ctx, argv[++i], a->v, &a->nv)) {
                *exit_code = vb_cli_usage_error("jfa", "%s", vb_errmsg(ctx));
                return 0;
            }
        } else if (strcmp(o, "--device") == 0)
            a->device = argv[++i];
        else if (strcmp(o, "--png") == 0)
            a->png = argv[++i];
        else if (strcmp(o, "--slice") == 0)
            a->slices = argv[++i];
        else if (strcmp(o, "-o") == 0)
            a->out = argv[++i];
        else if (o[0] == '-' && o[1]) {
            *exit_code = vb_cli_usage_error("jfa", "unknown option %s", o);
            return 0;
        } else if (a->seeds_path) {
            *exit_code = vb_cli_usage_error("jfa", "more than one seed file");
            return 0;
        } else
            a->seeds_path = o;
    }
    if (a->protein) {
        if (a->seeds_path) {
            *exit_code = vb_cli_usage_error("jfa", "give either SEEDS or --protein");
            return 0;
        }
        if (a->dim_given && set.dim != 3) {
            *exit_code = vb_cli_usage_error("jfa", "--protein needs --dim 3");
            return 0;
        }
        set.dim = 3;
    }
    a->set = set;
    return 1;
}

/* --slice Z[,Z..] into the setup (3D only; else the picture is the
 * diagram or slice n/2): a value that does not parse is stored as one
 * vbj_setup_check refuses. */
static void parse_slices(const char *text, vbj_setup *set)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", text);
    set->nslices = 0;
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        size_t z;
        if (set->nslices == VBJ_MAX_SLICES) {
            set->nslices++; /* one too many */
            return;
        }
        set->slice[set->nslices++] = vb_cli_parse_size(t, &z) ? UINT64_MAX : z;
    }
    if (set->nslices == 0)
        set->slice[set->nslices++] = UINT64_MAX;
}

int vb_cmd_jfa(int argc, char **argv)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL))
        return vb_cli_fail(NULL, VB_ENOMEM);
    jfa_args a;
    int ec;
    if (!parse_args(ctx, argc, argv, &a, &ec)) {
        vb_close(ctx);
        return ec;
    }
    if (a.set.dim == 3 && a.slices) {
        parse_slices(a.slices, &a.set);
        if (vbj_setup_check(ctx, &a.set) != VB_OK) {
            vb_close(ctx);
            return vb_cli_usage_error("jfa", "bad --slice '%s' (z values below n)", a.slices);
        }
    }
    vb_device_kind kind;
    int rc = vb_device_kind_parse(ctx, a.device, &kind);
    if (rc) {
        ec = vb_cli_usage_error("jfa", "%s", vb_errmsg(ctx));
        vb_close(ctx);
        return ec;
    }

    /* Only the centres make seeds, but a protein is checked as every
     * command checks its input (radii, duplicates, magnitudes: the same
     * numbered errors); PQR's radius-0 points are legal. */
    vb_sphere_set *set = NULL;
    if (a.protein)
        rc = vb_cli_load_spheres(ctx, a.protein, &a.io, 1, &set);
    vbj_seed_source src = {set, a.protein, NULL, 0, a.seeds_path, a.dist};
    vbj_seeds s = {0};
    char source[512];
    if (!rc)
        rc = vbj_seeds_make(ctx, &a.set, &src, &s, source, sizeof source);
    vb_spheres_free(set);
    vbj_backend *e = NULL;
    vb_device *dev = NULL;
    if (!rc)
        rc = vbj_backend_open(ctx, vb_default_devices(), kind, &dev, &e);
    vbj_runs runs;
    memset(&runs, 0, sizeof runs);
    if (!rc)
        rc = vbj_runs_run(ctx, e, &s, &a.set, a.v, a.nv, a.check, &runs);
    if (!rc && a.png) {
        uint8_t *rgb = NULL;
        uint32_t w = 0;
        rc = vbj_picture(ctx, &s, runs.run[runs.n - 1].r.labels, &a.set, &rgb, &w);
        if (!rc)
            rc = vb_png_write_rgb(ctx, a.png, w, s.n, rgb);
        free(rgb);
    }
    if (!rc) {
        FILE *f = vb_cli_open_output(ctx, a.out);
        if (!f)
            rc = vb_errcode(ctx);
        else {
            vbj_runs_write(f, &runs, &s, source, a.json);
            rc = vb_cli_close_output(ctx, f, a.out);
        }
    }
    ec = rc ? vb_cli_fail(ctx, rc) : VB_EXIT_OK;
    vbj_runs_free(&runs);
    vbj_backend_close(e);
    if (dev)
        vb_default_devices()->close(dev);
    vbj_seeds_free(&s);
    vb_close(ctx);
    return ec;
}
