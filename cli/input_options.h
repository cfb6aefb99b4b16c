/* The input options every subcommand shares (--format, --model, --radii,
 * --water, --no-hydrogens, --strict-elements, --zero-radius, --assembly) and the one call that reads
 * and validates a sphere file with them. */
#ifndef VB_CLI_INPUT_OPTIONS_H
#define VB_CLI_INPUT_OPTIONS_H

#include <stdio.h>

#include "vb_spheres.h"

typedef struct vb_cli_input_opts {
    vb_format format;        /* --format F (default auto) */
    int model;               /* --model N (default 0: the first model) */
    const char *radii_path;  /* --radii FILE (NULL: built-in table) */
    int keep_water;          /* --water */
    int drop_hydrogens;      /* --no-hydrogens */
    int strict_elements;     /* --strict-elements */
    int zero_radius;         /* --zero-radius error|point|drop (enum vb_zero_radius; default auto) */
    int assembly;            /* --assembly N (mmCIF biological assembly; default 0: as written) */
    const char *atoms_path;  /* --atoms FILE: the sphere table (vb_atoms_write), or NULL */
    const char *select;      /* --select EXPR (core/input/vb_select.h), or NULL */
} vb_cli_input_opts;

/* Zero-initialising a vb_cli_input_opts gives the defaults; this does it. */
void vb_cli_input_defaults(vb_cli_input_opts *o);

/* Consumes argv[*i] (and its value, advancing *i past it) when it is an
 * input option. Returns 1 if consumed, 0 if argv[*i] is not an input option,
 * -1 on a bad or missing value (a message is printed to stderr, naming
 * argv[0] as the subcommand). */
int vb_cli_input_option(vb_cli_input_opts *o, int argc, char **argv, int *i);

/* Prints the help lines of the input options. */
void vb_cli_input_help(FILE *f);

/* A command's --help with the input options in the middle: head, the input
 * options, then tail (NULL: none). */
void vb_cli_input_help_between(FILE *f, const char *head, const char *tail);

/* Fills read options from the CLI options. radii is the loaded --radii
 * table or NULL. */
void vb_cli_input_read_options(const vb_cli_input_opts *o, const vb_radii_table *radii,
                               vb_read_options *ro);

/* Reads `path` ("-" = stdin) with the options and validates it with
 * vb_spheres_validate(min_count). On success *out owns the set (free with
 * vb_spheres_free). Returns VB_OK or the status (message in the context);
 * on failure *out is NULL. */
int vb_cli_load_spheres(vb_ctx *ctx, const char *path, const vb_cli_input_opts *o,
                        size_t min_count, vb_sphere_set **out);

/* vb_cli_load_spheres with the reading and the checks timed on clk (may be
 * NULL; vb_spheres_load_clocked). */
struct vb_stage_clock;
int vb_cli_load_spheres_clocked(vb_ctx *ctx, const char *path, const vb_cli_input_opts *o,
                                size_t min_count, vb_sphere_set **out,
                                struct vb_stage_clock *clk);

/* Writes the sphere table of s (--atoms) to path (vb_atoms_write). */
int vb_cli_write_atoms(vb_ctx *ctx, const char *path, const vb_sphere_set *s);

#endif
