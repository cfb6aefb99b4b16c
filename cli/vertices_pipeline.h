/* The vertex pipeline as `vorball vertices` and `vorball bench` run it:
 * backend choice (with fallback to the reference backend), sampling,
 * matching, exact certification. Orchestration only; the geometry lives in
 * core/ and verify/. */
#ifndef VB_CLI_VERTICES_PIPELINE_H
#define VB_CLI_VERTICES_PIPELINE_H

#include "input_options.h"
#include "vb_sampler.h"
#include "vb_verify.h"
#include "vbg_runtime.h"

typedef struct vb_pipeline_result {
    vb_sampler_result sampler;
    vb_vertex_list certified;   /* canonical, sorted */
    vb_vertex_list rejected;    /* candidates the certifier refused */
    double t_setup;             /* OpenCL runtime + program, on its own thread */
    double t_setup_wait;        /* of that, the time sampling waited for it */
    double t_certify, t_total;
    double max_dist;            /* largest candidate-to-exact distance certified */
    size_t repaired_candidates; /* intruder-swap candidates certified (see repair) */
    char backend[16];
    char device[160];
} vb_pipeline_result;

void vb_pipeline_result_init(vb_pipeline_result *r);
void vb_pipeline_result_free(vb_pipeline_result *r);

/* Runs the pipeline on a validated set with the requested device kind. When
 * OpenCL is unavailable or fails, warns (W760/W762) and runs the reference
 * backend, whose output is the same. progress (may be false) draws a bar on
 * stderr when it is a terminal and the run takes more than a second.
 * Returns VB_OK or an error status (message in ctx). */
int vb_pipeline_run(vb_ctx *ctx, const vb_sphere_set *set, vb_device_kind kind,
                    const vb_sampler_options *opt, int progress, vb_pipeline_result *res);

/* A sampling backend opened once for several runs (bench): the OpenCL
 * context, queue and programs, or the reference backend. */
typedef struct vb_pipeline_device {
    vbg_runtime *rt;            /* NULL on the reference backend */
    vb_sampler_backend *be;
    double t_open;              /* seconds the opening took */
} vb_pipeline_device;

/* Opens the backend for `kind`; when OpenCL is unavailable, warns (W760)
 * and opens the reference backend instead. Returns VB_OK or an error
 * status; close with vb_pipeline_device_close. */
int vb_pipeline_device_open(vb_ctx *ctx, vb_device_kind kind, vb_pipeline_device *dev);
void vb_pipeline_device_close(vb_pipeline_device *dev);

/* vb_pipeline_run on an opened backend: the same output, without the
 * set-up (t_setup stays 0). A device that fails mid-run is closed with
 * warning W762 and the run, and later runs on dev, use the reference
 * backend. */
int vb_pipeline_run_on(vb_ctx *ctx, const vb_sphere_set *set, vb_pipeline_device *dev,
                       const vb_sampler_options *opt, int progress, vb_pipeline_result *res);

/* The options of the commands that run the pipeline (vertices, bench,
 * crosscheck): how the input is read, the backend and the sampling. */
typedef struct vb_pipeline_opts {
    vb_cli_input_opts in;
    vb_sampler_options so;
    vb_device_kind kind;
} vb_pipeline_opts;

/* Sets the defaults: input defaults, sampler options zero (their own
 * defaults), device auto. */
void vb_pipeline_opts_defaults(vb_pipeline_opts *o);

/* Parses an input option (vb_cli_input_option) or one of the pipeline's
 * (--device, --samples, --tol, --tiles, --threads, --all-pairs) at argv[*i],
 * advancing *i past a value. Returns 1 if consumed, 0 if not one of them, -1
 * on a bad value (usage message printed naming cmd, or argv[0] for an input
 * option). */
int vb_pipeline_option(const char *cmd, int argc, char **argv, int *i, vb_pipeline_opts *o,
                       vb_ctx *ctx);

#endif
