/* Shared input options of the subcommands. */
#include "input_options.h"

#include <limits.h>
#include <string.h>

#include "cli_common.h"
#include "vb_stage_clock.h"
#include "vb_world.h"

void vb_cli_input_defaults(vb_cli_input_opts *o)
{
    memset(o, 0, sizeof *o);
    o->format = VB_FMT_AUTO;
}

/* The value of an option taking one, or NULL (message printed). */
static const char *option_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        vb_cli_usage_error(argv[0], "%s needs a value", argv[*i]);
        return NULL;
    }
    return argv[++*i];
}

int vb_cli_input_option(vb_cli_input_opts *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (strcmp(a, "--water") == 0) {
        o->keep_water = 1;
        return 1;
    }
    if (strcmp(a, "--no-hydrogens") == 0) {
        o->drop_hydrogens = 1;
        return 1;
    }
    if (strcmp(a, "--strict-elements") == 0) {
        o->strict_elements = 1;
        return 1;
    }
    if (strcmp(a, "--format") == 0) {
        const char *v = option_value(argc, argv, i);
        if (!v)
            return -1;
        if (vb_format_parse(NULL, v, &o->format) != VB_OK) {
            vb_cli_usage_error(argv[0], "unknown format '%s' (auto, xyzr, pdb, pqr, cif, gro)", v);
            return -1;
        }
        return 1;
    }
    if (strcmp(a, "--zero-radius") == 0) {
        static const char *const names[] = {"error", "point", "drop"};
        static const int values[] = {VB_ZERO_RADIUS_ERROR, VB_ZERO_RADIUS_POINT,
                                     VB_ZERO_RADIUS_DROP};
        const char *v = option_value(argc, argv, i);
        if (!v)
            return -1;
        for (int k = 0; k < 3; k++)
            if (strcmp(v, names[k]) == 0) {
                o->zero_radius = values[k];
                return 1;
            }
        vb_cli_usage_error(argv[0], "--zero-radius takes error, point or drop, not '%s'", v);
        return -1;
    }
    int *number = strcmp(a, "--model") == 0      ? &o->model
                  : strcmp(a, "--assembly") == 0 ? &o->assembly
                                                 : NULL;
    if (number) {
        /* The ranges are the library's (vb_read_options_check): 0 and a
         * value that does not parse are stored as one it refuses. */
        const char *v = option_value(argc, argv, i);
        size_t n;
        if (!v)
            return -1;
        *number = vb_cli_parse_size(v, &n) != 0 || n == 0 || n > INT_MAX ? -1 : (int)n;
        vb_read_options ro = {.model = o->model, .assembly = o->assembly};
        vb_ctx *ctx;
        if (vb_open(&ctx, NULL) != VB_OK) {
            vb_cli_fail(NULL, VB_ENOMEM);
            return -1;
        }
        int rc = vb_read_options_check(ctx, &ro);
        if (rc != VB_OK)
            vb_cli_usage_error(argv[0], "%s, not '%s'", vb_errmsg(ctx), v);
        vb_close(ctx);
        return rc == VB_OK ? 1 : -1;
    }
    if (strcmp(a, "--radii") == 0) {
        const char *v = option_value(argc, argv, i);
        if (!v)
            return -1;
        o->radii_path = v;
        return 1;
    }
    if (strcmp(a, "--atoms") == 0) {
        const char *v = option_value(argc, argv, i);
        if (!v)
            return -1;
        o->atoms_path = v;
        return 1;
    }
    if (strcmp(a, "--select") == 0) {
        const char *v = option_value(argc, argv, i);
        if (!v)
            return -1;
        o->select = v;
        return 1;
    }
    return 0;
}

void vb_cli_input_help_between(FILE *f, const char *head, const char *tail)
{
    fputs(head, f);
    vb_cli_input_help(f);
    if (tail)
        fputs(tail, f);
}

void vb_cli_input_help(FILE *f)
{
    fputs("input options:\n"
          "  --format F          input format: auto (default, by content), xyzr (also\n"
          "                      Voronota balls), pdb, pqr, cif|mmcif, gro; gzip and\n"
          "                      bzip2 files (and stdin) are decompressed whatever the name\n"
          "  --model N           read model N of a multi-model PDB/mmCIF/GRO (default: the\n"
          "                      first; channels reads every model as a frame unless given)\n"
          "  --assembly N        mmCIF: biological assembly N (_pdbx_struct_assembly_gen),\n"
          "                      its copies moved by the operators exactly\n"
          "  --radii FILE        element radii, lines 'ELEMENT RADIUS' ('#' comments),\n"
          "                      for PDB/mmCIF/GRO; unlisted elements keep the built-in radii\n"
          "  --atoms FILE        the sphere table: what each 0-based id of the output\n"
          "                      stands for (chain, residue, number, atom name, element,\n"
          "                      source line, the exact x y z r used), TSV\n"
          "  --water             keep water (HOH, WAT, ...; dropped by default, counted)\n"
          "  --no-hydrogens      drop H/D atoms (kept by default)\n"
          "  --strict-elements   refuse what would be guessed: an element without a radius\n"
          "                      (E108; else radius 1.70, W707) and an element the file\n"
          "                      does not give (E112; else inferred from atom and residue\n"
          "                      names, W714/W715)\n"
          "  --zero-radius M     radius-0 spheres: error, point (a point site) or drop;\n"
          "                      default point for PQR (PARSE polar hydrogens), else error\n"
          "  --select EXPR       keep the atoms EXPR selects: chain, segid, resname, resid\n"
          "                      (N, a:b), name, element (then values; ? and * wildcards in\n"
          "                      names), protein, water, all, and, or, not, ( ); E118 when\n"
          "                      malformed (its position) or nothing is selected\n",
          f);
}

void vb_cli_input_read_options(const vb_cli_input_opts *o, const vb_radii_table *radii,
                               vb_read_options *ro)
{
    memset(ro, 0, sizeof *ro);
    ro->format = o->format;
    ro->model = o->model;
    ro->keep_water = o->keep_water;
    ro->drop_hydrogens = o->drop_hydrogens;
    ro->strict_elements = o->strict_elements;
    ro->zero_radius = o->zero_radius;
    ro->assembly = o->assembly;
    ro->select = o->select;
    ro->radii = radii;
}

int vb_cli_load_spheres(vb_ctx *ctx, const char *path, const vb_cli_input_opts *o,
                        size_t min_count, vb_sphere_set **out)
{
    return vb_cli_load_spheres_clocked(ctx, path, o, min_count, out, NULL);
}

int vb_cli_load_spheres_clocked(vb_ctx *ctx, const char *path, const vb_cli_input_opts *o,
                                size_t min_count, vb_sphere_set **out, vb_stage_clock *clk)
{
    vb_read_options ro;
    vb_cli_input_read_options(o, NULL, &ro);
    int rc = vb_spheres_load_clocked(ctx, path, &ro, o->radii_path, min_count, out, clk);
    /* The table of what was read, written by the process that writes the
     * outputs (rank 0 under MPI). */
    if (rc == VB_OK && o->atoms_path && vb_world_rank() == 0)
        rc = vb_cli_write_atoms(ctx, o->atoms_path, *out);
    return rc;
}

int vb_cli_write_atoms(vb_ctx *ctx, const char *path, const vb_sphere_set *s)
{
    FILE *f = vb_cli_open_output(ctx, path);
    int rc = f ? vb_atoms_write(ctx, f, s) : vb_errcode(ctx);
    return vb_cli_finish_output(ctx, f, path, rc);
}
