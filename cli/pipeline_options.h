/* The options of the commands that run the vertex pipeline (vertices,
 * bench, crosscheck); their progress goes through progress.h. */
#ifndef VB_CLI_PIPELINE_OPTIONS_H
#define VB_CLI_PIPELINE_OPTIONS_H

#include "input_options.h"
#include "vb_vertices.h"

/* How the input is read, and the pipeline's configuration. */
typedef struct vb_pipeline_opts {
    vb_cli_input_opts in;
    vb_vertices_config cfg;
} vb_pipeline_opts;

/* Sets the defaults: input defaults, sampler options zero (their own
 * defaults), device auto, the default proposer. */
void vb_pipeline_opts_defaults(vb_pipeline_opts *o);

/* Parses an input option (vb_cli_input_option) or one of the pipeline's
 * (--device, --proposer, --samples, --tol, --tiles, --threads, --all-pairs)
 * at argv[*i], advancing *i past a value. Returns 1 if consumed, 0 if not
 * one of them, -1 on a bad value (usage message printed naming cmd, or
 * argv[0] for an input option). */
int vb_pipeline_option(const char *cmd, int argc, char **argv, int *i, vb_pipeline_opts *o,
                       vb_ctx *ctx);

#endif
