/* `vorball jfa`: discrete Voronoi diagrams on [n]^d grids by the JFA variants
 * and Facet-JFA, checked against the exact diagram, timed, pictured. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "jfa_png.h"
#include "vb_json.h"
#include "vb_default.h"
#include "vbj_jfa.h"
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
    vbj_variant v[8];
    int nv;
} variant_list;

static int parse_variants(vb_ctx *ctx, const char *s, variant_list *out)
{
    out->nv = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int all = strcmp(tok, "all") == 0;
        int need = all ? VBJ_FACET + 2 : 1;
        if (out->nv + need > 8)
            return vb_error(ctx, VB_EMISUSE, NULL, 0, "too many variants");
        if (all) {
            for (int i = 0; i <= VBJ_FACET; i++)
                out->v[out->nv++] = (vbj_variant)i;
            out->v[out->nv++] = VBJ_EXACT;
            continue;
        }
        int rc = vbj_variant_parse(ctx, tok, &out->v[out->nv]);
        if (rc)
            return rc;
        out->nv++;
    }
    return out->nv ? VB_OK : vb_error(ctx, VB_EMISUSE, NULL, 0, "no variant given");
}

/* Seeds from a protein's atom centres, fitted into an [n]^3 grid. */
static int protein_seeds(vb_ctx *ctx, const char *path, const vb_cli_input_opts *io, uint32_t n,
                         double margin, vbj_seeds *s)
{
    /* Only the centres make seeds, but the input is checked as every
     * command checks it (radii, duplicates, magnitudes: the same numbered
     * errors); PQR's radius-0 points are legal. */
    vb_sphere_set *set = NULL;
    int rc = vb_cli_load_spheres(ctx, path, io, 1, &set);
    if (rc)
        return rc;
    vbj_grid_fit fit;
    rc = vbj_fit_grid(ctx, set->x, set->y, set->z, set->n, n, margin, &fit);
    if (!rc)
        rc = vbj_seeds_from_world(ctx, &fit, set->x, set->y, set->z, set->n, s);
    if (!rc)
        vb_info(ctx, "protein %s: %zu atoms, pitch %.4f A, origin (%.3f, %.3f, %.3f)", path,
                set->n, fit.pitch, fit.origin[0], fit.origin[1], fit.origin[2]);
    vb_spheres_free(set);
    return rc;
}

static int write_png(vb_ctx *ctx, const char *path, const vbj_seeds *s, const uint32_t *labels,
                     const uint32_t *slices, int nslices)
{
    uint32_t n = s->n, w = n * (uint32_t)nslices;
    uint8_t *rgb = malloc((size_t)w * n * 3);
    if (!rgb)
        return vb_error(ctx, VB_ENOMEM, path, 0, "picture: out of memory");
    for (int i = 0; i < nslices; i++)
        vb_jfa_render_slice(s->dim, n, labels, s->dim == 3 ? slices[i] : 0, rgb + (size_t)i * n * 3,
                            (size_t)w * 3);
    int rc = vb_png_write_rgb(ctx, path, w, n, rgb);
    free(rgb);
    return rc;
}

typedef struct {
    vbj_variant v;
    vbj_result r;      /* last run */
    double mean_ms, min_ms, mean_gpu_ms;
    int checked;
    vbj_metrics m;
} run_figures;

static void print_json(FILE *f, const char *device, const vbj_seeds *s, const char *source,
                       const run_figures *runs, int nruns, int repeat, double exact_ms)
{
    fprintf(f, "{\"device\": ");
    vb_json_write_string(f, device);
    fprintf(f, ", \"dim\": %d, \"n\": %u, \"seeds\": %zu, \"source\": ", s->dim, s->n, s->k);
    vb_json_write_string(f, source);
    fprintf(f, ", \"repeat\": %d", repeat);
    if (exact_ms >= 0)
        fprintf(f, ", \"exact_ms\": %.4f", exact_ms);
    fprintf(f, ",\n \"runs\": [");
    for (int i = 0; i < nruns; i++) {
        const run_figures *x = &runs[i];
        const vbj_counts *c = &x->r.counts;
        fprintf(f,
                "%s\n  {\"variant\": \"%s\", \"time_ms\": %.4f, \"time_ms_min\": %.4f, "
                "\"gpu_ms\": %.4f, \"fill_ms\": %.4f, \"prep_transfer_ms\": %.4f, \"prep_ms\": %.4f, "
                "\"steps\": %u, "
                "\"pixels_processed\": %llu, \"threads\": %llu, \"m\": %u, \"boundary\": %llu, "
                "\"collisions\": %u",
                i ? "," : "", vbj_variant_name(x->v), x->mean_ms, x->min_ms, x->mean_gpu_ms,
                x->r.ms_fill,
                x->r.ms_transfer, x->r.ms_prep, c->steps, (unsigned long long)c->step_pixels,
                (unsigned long long)c->threads, c->m, (unsigned long long)c->boundary,
                c->collisions);
        if (VBJ_IS_EXACT(x->v))
            fprintf(f,
                    ", \"tiles\": %llu, \"tiles_uniform\": %llu, \"candidates\": %llu, "
                    "\"survivors\": %llu, \"evals\": %llu, \"exact_voxels\": %llu, "
                    "\"tiles_chunked\": %llu, \"visited\": %llu",
                    (unsigned long long)c->tiles, (unsigned long long)c->tiles_uniform,
                    (unsigned long long)c->candidates, (unsigned long long)c->survivors,
                    (unsigned long long)c->evals, (unsigned long long)c->exact_voxels,
                    (unsigned long long)c->tiles_chunked, (unsigned long long)c->visited);
        if (x->checked)
            fprintf(f,
                    ", \"wrong\": %zu, \"differ\": %zu, \"wrong_rate\": %.8g, \"max_err\": %.6g, "
                    "\"mean_err\": %.6g, \"boundary_exact\": %zu, \"boundary_found\": %zu, "
                    "\"boundary_missed\": %zu, \"boundary_extra\": %zu",
                    x->m.wrong, x->m.differ, x->m.wrong_rate, x->m.max_err, x->m.mean_err,
                    x->m.boundary_exact, x->m.boundary_found, x->m.boundary_missed,
                    x->m.boundary_extra);
        fprintf(f, "}");
    }
    fprintf(f, "\n]}\n");
}

static void print_text(FILE *f, const char *device, const vbj_seeds *s, const char *source,
                       const run_figures *runs, int nruns)
{
    fprintf(f, "# device: %s\n# grid: %u^%d, %zu seeds (%s)\n", device, s->n, s->dim, s->k,
            source);
    fprintf(f, "%-14s %10s %10s %14s %6s %12s %12s %12s %10s\n", "variant", "ms", "ms_min",
            "pixels", "m", "boundary", "wrong", "wrong_rate", "max_err");
    for (int i = 0; i < nruns; i++) {
        const run_figures *x = &runs[i];
        fprintf(f, "%-14s %10.3f %10.3f %14llu %6u %12llu", vbj_variant_name(x->v), x->mean_ms,
                x->min_ms, (unsigned long long)x->r.counts.step_pixels, x->r.counts.m,
                (unsigned long long)x->r.counts.boundary);
        if (x->checked)
            fprintf(f, " %12zu %12.3e %10.4f\n", x->m.wrong, x->m.wrong_rate, x->m.max_err);
        else
            fprintf(f, " %12s %12s %10s\n", "-", "-", "-");
    }
}

typedef struct {
    int dim, dim_given, check, json, repeat;
    uint32_t n, m, fuse_cells;
    size_t k;
    uint64_t rng;
    double margin;
    vbj_distribution dist;
    variant_list vl;
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
    vbj_setup set = {.dim = 2, .n = 512, .k = 100, .margin = 2.0, .repeat = 1};
    a->rng = 1;
    a->device = "auto";
    a->vl.nv = 1;
    a->vl.v[0] = VBJ_JFA1;
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
            a->rng = sz;
        } else if (strcmp(o, "--protein") == 0)
            a->protein = argv[++i];
        else if (strcmp(o, "-V") == 0 || strcmp(o, "--variant") == 0) {
            if (parse_variants(ctx, argv[++i], &a->vl)) {
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
    a->dim = (int)set.dim;
    a->n = (uint32_t)set.n;
    a->k = (size_t)set.k;
    a->margin = set.margin;
    a->m = (uint32_t)set.m;
    a->fuse_cells = (uint32_t)set.fuse_cells;
    a->repeat = (int)set.repeat;
    if (a->protein) {
        if (a->seeds_path) {
            *exit_code = vb_cli_usage_error("jfa", "give either SEEDS or --protein");
            return 0;
        }
        if (a->dim_given && a->dim != 3) {
            *exit_code = vb_cli_usage_error("jfa", "--protein needs --dim 3");
            return 0;
        }
        a->dim = 3;
    }
    return 1;
}

static int parse_slices(const jfa_args *a, uint32_t *sl, int *ns)
{
    *ns = 1;
    sl[0] = a->n / 2;
    if (a->dim != 3 || !a->slices)
        return 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", a->slices);
    *ns = 0;
    for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
        size_t z;
        if (*ns == 16 || vb_cli_parse_size(t, &z) || z >= a->n)
            return -1;
        sl[(*ns)++] = (uint32_t)z;
    }
    return *ns ? 0 : -1;
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
    uint32_t slices[16];
    int nslices;
    if (parse_slices(&a, slices, &nslices)) {
        vb_close(ctx);
        return vb_cli_usage_error("jfa", "bad --slice '%s' (z values below n)", a.slices);
    }
    vb_device_kind kind;
    int rc = vb_device_kind_parse(ctx, a.device, &kind);
    if (rc) {
        ec = vb_cli_usage_error("jfa", "%s", vb_errmsg(ctx));
        vb_close(ctx);
        return ec;
    }

    vbj_seeds s = {0};
    char source[512];
    if (a.protein) {
        rc = protein_seeds(ctx, a.protein, &a.io, a.n, a.margin, &s);
        snprintf(source, sizeof source, "protein %s", a.protein);
    } else if (a.seeds_path) {
        rc = vbj_seeds_read(ctx, a.seeds_path, a.dim, a.n, &s);
        snprintf(source, sizeof source, "file %s", a.seeds_path);
    } else {
        rc = vbj_seeds_generate(ctx, a.dim, a.n, a.k, a.dist, a.rng, &s);
        snprintf(source, sizeof source, "%s, rng %llu", vbj_distribution_name(a.dist),
                 (unsigned long long)a.rng);
    }
    vbj_backend *e = NULL;
    vb_device *dev = NULL;
    if (!rc)
        rc = vbj_backend_open(ctx, vb_default_devices(), kind, &dev, &e);
    run_figures runs[8];
    memset(runs, 0, sizeof runs);
    uint32_t *exact = NULL;
    double exact_ms = -1;
    if (!rc && a.check) {
        exact = malloc((size_t)s.n * s.n * (s.dim == 3 ? s.n : 1) * sizeof *exact);
        if (!exact)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "exact labels: out of memory");
        else {
            double t0 = vb_now();
            rc = vbj_exact(ctx, e, &s, exact);
            exact_ms = (vb_now() - t0) * 1e3;
        }
    }
    int warned_collision = 0, warned_m = 0;
    for (int i = 0; !rc && i < a.vl.nv; i++) {
        run_figures *x = &runs[i];
        x->v = a.vl.v[i];
        vbj_options o = {x->v, a.m, VBJ_WANT_LABELS, a.fuse_cells};
        double sum = 0, mn = 0, gpu = 0;
        /* Timed runs follow an untimed one that allocates the device buffers. */
        if (a.repeat > 1 && !(rc = vbj_run(ctx, e, &s, &o, &x->r)))
            vbj_result_free(&x->r);
        for (int t = 0; !rc && t < a.repeat; t++) {
            vbj_result_free(&x->r);
            rc = vbj_run(ctx, e, &s, &o, &x->r);
            sum += x->r.ms_kernel;
            gpu += x->r.ms_gpu;
            mn = t == 0 || x->r.ms_kernel < mn ? x->r.ms_kernel : mn;
        }
        if (rc)
            break;
        x->mean_ms = sum / a.repeat;
        x->mean_gpu_ms = gpu / a.repeat;
        x->min_ms = mn;
        if (x->r.counts.collisions && !warned_collision) {
            vb_warn(ctx, VB_W_JFA_SEEDS_LOST, NULL, 0,
                    "%u seed(s) share their start pixel with a nearer seed and cannot own "
                    "any pixel",
                    x->r.counts.collisions);
            warned_collision = 1;
        }
        if ((x->v == VBJ_FACET || x->v == VBJ_FACET_FULL) && x->r.counts.m == s.n && s.n > 1 &&
            !warned_m) {
            vb_warn(ctx, VB_W_FACET_START_FINE, NULL, 0,
                    "Facet-JFA starts at m = n = %u (seeds too close): it does the work of "
                    "JFA and more",
                    s.n);
            warned_m = 1;
        }
        if (exact) {
            rc = vbj_compare(ctx, &s, x->r.labels, exact, &x->m);
            x->checked = 1;
        }
    }
    if (!rc && a.png) {
        int last = a.vl.nv - 1;
        rc = write_png(ctx, a.png, &s, runs[last].r.labels, slices, nslices);
    }
    if (!rc) {
        FILE *f = vb_cli_open_output(ctx, a.out);
        if (!f)
            rc = vb_errcode(ctx);
        else {
            const char *device = e->device;
            if (a.json)
                print_json(f, device, &s, source, runs, a.vl.nv, a.repeat, exact_ms);
            else
                print_text(f, device, &s, source, runs, a.vl.nv);
            rc = vb_cli_close_output(ctx, f, a.out);
        }
    }
    ec = rc ? vb_cli_fail(ctx, rc) : VB_EXIT_OK;
    for (int i = 0; i < 8; i++)
        vbj_result_free(&runs[i].r);
    free(exact);
    vbj_backend_close(e);
    if (dev)
        vb_default_devices()->close(dev);
    vbj_seeds_free(&s);
    vb_close(ctx);
    return ec;
}
