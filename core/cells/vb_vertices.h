/* The vertex pipeline as a library call: device choice (opened on its own
 * thread while the first batch is culled) with the one fallback rule,
 * proposal of candidate vertices, exact certification, the intruder-swap
 * repair rounds and the canonical merge.
 *
 * The driver (core/cells/vertices.c) takes what it cannot build itself
 * through tables, so core/ never includes gpu/ or verify/ headers:
 *   - the device layer (vb_device.h; gpu/'s vbg_device_layer, or NULL),
 *   - the proposer of candidates (vb_proposer.h: its table, the options
 *     any proposer takes and its result; vb_proposers lists them),
 *   - the certifier (vb_certifier_ops; verify/'s vb_exact_certifier).
 * cli/vb_default.h wires the default tables for callers that want them
 * (the command, a binding): vb_vertices_run_default. */
#ifndef VB_VERTICES_H
#define VB_VERTICES_H

#include <stdio.h>

#include "vb_device.h"
#include "vb_proposer.h"
#include "vb_stat_field.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the certifier table ----------------------------------------------- */

typedef struct vb_certifier_ops {
    const char *name;
    /* Builds the certifier of a validated set (the set must outlive it),
     * judging lists on `threads` threads (0: vb_threads' default). */
    int (*open)(vb_ctx *ctx, const vb_sphere_set *set, unsigned threads, void **cert);
    /* Certifies every candidate: the canonical certified set (sorted, one
     * entry per exact vertex with all its members) to certified, refused
     * candidates to rejected. No distance limit: the exact solution nearest
     * the candidate is judged. */
    int (*certify_list)(vb_ctx *ctx, void *cert, const vb_vertex_list *cand,
                        vb_vertex_list *certified, vb_vertex_list *rejected);
    /* One candidate of four ids at p (x y z t): *intruder is the sphere
     * that cuts its tangent sphere, or UINT32_MAX when none does (or the
     * ids define no such sphere). */
    int (*intruder)(vb_ctx *ctx, void *cert, const uint32_t ids[4], const double p[4],
                    uint32_t *intruder);
    void (*close)(void *cert);
    /* May be NULL. Certifies every exact root of each sorted quadruple
     * quads[0 .. n) and writes the canonical certified set (as
     * certify_list) to certified; rejected (may be NULL) may get the roots
     * that are not vertices, or be left as it is (the exact certifier
     * counts them in the context's stats instead). Without it the driver
     * certifies one candidate per double root. */
    int (*certify_quads)(vb_ctx *ctx, void *cert, const uint32_t (*quads)[4], size_t n,
                         vb_vertex_list *certified, vb_vertex_list *rejected);
    /* May be NULL. certify_quads with the certification filter's verdicts
     * (vb_quad_list.verdict, one per quadruple): roots proven vertices or
     * not vertices are not judged again. The same vertices as
     * certify_quads. */
    int (*certify_quads_judged)(vb_ctx *ctx, void *cert, const uint32_t (*quads)[4],
                                const uint8_t *verdict, size_t n, vb_vertex_list *certified);
} vb_certifier_ops;

/* ---- the pipeline -------------------------------------------------------- */

typedef struct vb_vertices_backends {
    const vb_device_layer *devices;        /* NULL: plain-C twins only */
    const vb_certifier_ops *certifier;
} vb_vertices_backends;

typedef struct vb_vertices_early vb_vertices_early; /* vb_vertices_open_early */

/* Work on the certified vertices of each part while the proposer still
 * runs (arc closure's early tracing: lib/vertices_complete.c): open once,
 * at the first part certified, on the run's certifier (cert, of table ops;
 * *state NULL: no work for this certifier, part is then not called) and
 * the run's threads; part with the certified list of each
 * part certified before the proposer returned (sorted, borrowed for the
 * call; errors set on ctx; later parts are left to the caller); close
 * frees the state, before the certifier is closed. */
typedef struct vb_part_work {
    int (*open)(vb_ctx *owner, const vb_sphere_set *set, const struct vb_certifier_ops *ops,
                void *cert, unsigned threads, void **state);
    int (*part)(vb_ctx *ctx, void *state, const vb_vertex_list *part);
    void (*close)(void *state);
} vb_part_work;

typedef struct vb_vertices_config {
    vb_device_kind device;       /* default VB_DEVICE_AUTO (0) */
    const char *proposer;        /* vb_proposers name; NULL: the default */
    vb_propose_options propose;  /* what any proposer takes: tolerance, threads, budget */
    const struct vb_cover_options *cover; /* the cover's own settings (vb_cover.h: the
                                  * work split over MPI ranks, the periodic base
                                  * limit), owned by the caller; NULL: its defaults */
    size_t host_below;           /* VB_DEVICE_AUTO with the cover on fewer spheres than
                                  * this runs on host threads where the device would
                                  * be a GPU (vb_vertices_device); 0: the
                                  * environment's VORBALL_HOST_BELOW, else
                                  * VB_HOST_BELOW_DEFAULT; 1: always the device */
    vb_vertices_early *early;    /* a device opening started ahead of the run
                                  * (vb_vertices_open_early), or NULL: the run
                                  * takes it when it is the device it uses */
    int keep_certifier;          /* 1: a successful run leaves its certifier open in
                                  * the result (cert, cert_ops) for a later stage on
                                  * the same set (arc closure: vb_completion_plan
                                  * sets it); vb_vertices_result_free closes it */
    const vb_part_work *part_work; /* NULL, or work on each certified part while the
                                  * proposer runs (needs keep_certifier and a
                                  * certifier that streams parts); its state is
                                  * left in the result (part_state) */
} vb_vertices_config;

/* The crossover of `--device auto` on a GPU machine (issue #30): below it
 * the whole process on host threads beat the GPU's set-up, measured on an
 * H100 with 16 host cores (papers/gpu-voronoi-cells-of-spheres/results/
 * crossover_h100.tsv: 10,000 spheres 0.294 s on host threads against
 * 0.477 s on the GPU; 26,430 spheres 0.648 against 0.647 s). */
#define VB_HOST_BELOW_DEFAULT 20000

/* The device kind a run of cfg on set uses: cfg->device, except that
 * VB_DEVICE_AUTO with the cover proposer on fewer spheres than the crossover
 * (cfg->host_below, see there) is VB_DEVICE_REF, no device opened, when the
 * host shows a GPU (layer->gpu_present). Without a GPU, auto stays the CPU
 * device (PoCL), the project's embedded default, although the host threads
 * took less CPU than PoCL at every size measured there (the 2-core machine,
 * 327 to 26,430 spheres, results/process_stop43.md). The output bytes never
 * depend on it. */
vb_device_kind vb_vertices_device(const vb_sphere_set *set, const vb_vertices_config *cfg,
                                  const vb_device_layer *layer);

/* The device a run of cfg would use on n spheres (vb_vertices_device on a
 * count, before the set is read). */
vb_device_kind vb_vertices_device_for(size_t n, const vb_vertices_config *cfg,
                                      const vb_device_layer *layer);

/* Starts opening, on its own thread, the device that a run of cfg with the
 * backends be would use on at least n_hint spheres (vb_vertices_device_for;
 * 0: unknown), so that the device set-up (context, program build or cache
 * load) overlaps the reading of the input (issue #30's fixed cost). *out is
 * NULL when that is the host's twin (nothing to open) or when the opening
 * cannot start; otherwise hand it to vb_vertices_run through cfg->early,
 * on the same ctx. A run that uses another device (the count was below
 * the hint's crossover) leaves this opening going on beside it. Free with
 * vb_vertices_early_free after the run, or instead of it (it waits for an
 * opening no run took). A run that took it leaves its device to close on
 * a thread of its own while the caller completes and writes;
 * vb_vertices_early_free waits for that too. VORBALL_DEVICE_EARLY=0 in the environment leaves
 * the opening to the run (*out NULL), for timings. VB_OK, or VB_ENOMEM. */
int vb_vertices_open_early(vb_ctx *ctx, const vb_vertices_backends *be,
                           const vb_vertices_config *cfg, size_t n_hint,
                           vb_vertices_early **out);

/* Waits for an opening no run took and closes what it opened; frees e.
 * NULL is allowed. */
void vb_vertices_early_free(vb_vertices_early *e);

typedef struct vb_vertices_result {
    vb_proposal proposal;       /* what the proposer found, and its counters */
    vb_vertex_list certified;   /* canonical, sorted */
    vb_vertex_list rejected;    /* candidates the certifier refused */
    double t_setup;             /* device opening, on its own thread */
    double t_setup_wait;        /* of that, the time the proposer waited for it */
    double t_certify, t_total;  /* t_certify: after the proposer returned */
    double t_propose;           /* the proposer's call, its wait for the set-up included */
    double t_release;           /* closing the proposer's state and the device, after t_total */
    double t_certify_overlap;   /* seconds the certifier worked while the proposer ran */
    size_t certify_parts;       /* parts of quadruples certified one by one (a stream) */
    double t_part_overlap;      /* cfg->part_work: its seconds while the proposer ran */
    double t_part_after;        /* ... and after it returned (waited for) */
    int part_work_on;           /* 1: cfg->part_work was offered the parts (its
                                 * counters are printed, zero or not) */
    double max_dist;            /* largest candidate-to-exact distance certified */
    size_t repaired_candidates; /* intruder-swap candidates certified (see repair) */
    char backend[16];
    char device[160];
    void *cert;                 /* with cfg->keep_certifier: the run's certifier, still
                                 * open (its exact data and index of the run's set), */
    const vb_certifier_ops *cert_ops; /* ... and its table; NULL otherwise */
    const vb_sphere_set *cert_set;    /* ... the set it was built on */
    void *part_state;           /* with cfg->part_work and a kept certifier: its
                                 * state after the run's parts (NULL when no part
                                 * came), closed before cert */
    const vb_part_work *part_ops; /* ... its table */
} vb_vertices_result;

/* What a result proves, as one line for an output file's header (empty
 * when the proposer proves nothing about completeness): for a complete
 * proposer, the number of certified vertices, that every vertex of the
 * diagram is among them, and the cover's counts. The text depends on the
 * input alone, never on the device or the thread count. */
void vb_vertices_certificate(const vb_vertices_result *r, char *buf, size_t size);

/* Appends the counters of a finished run r to fs (vb_stat_field.h):
 * backend, device, the proposer's counters, certified and rejected counts,
 * the context's filter counters (filter_calls, filter_failures,
 * exact_evals), the cover's, device_bytes_peak, certify_*, judged_*,
 * judge_s and the run's seconds (setup_s, setup_wait_s, propose_s, run_s,
 * release_s, which vary run to run): every line `vorball vertices --stats` prints, in its order. */
void vb_vertices_stats(vb_ctx *ctx, const vb_vertices_result *r, vb_stat_fields *fs);

/* Writes vb_vertices_stats' table to f, one "name<TAB>value" line each. */
void vb_vertices_write_stats(vb_ctx *ctx, FILE *f, const vb_vertices_result *r);

void vb_vertices_result_init(vb_vertices_result *r);
void vb_vertices_result_free(vb_vertices_result *r);

/* Runs the pipeline on a validated set (contained spheres flagged): opens
 * the device cfg->device asks for on its own thread while the proposer
 * starts (warning W760 and the twin when it cannot be used), proposes,
 * reruns on the twin when the device fails mid-run (W762), certifies,
 * repairs and merges. The result does not depend on the device or the
 * thread count. Before any of it, the memory the run needs is estimated
 * (vb_vertices_memory_check). Returns VB_OK or an error status (message in
 * ctx): VB_EMISUSE (bad options, unknown proposer), VB_ENOMEM_ESTIMATE
 * (refused up front: the estimate exceeds the room), VB_ENOMEM, VB_EPREC. */
int vb_vertices_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertices_config *cfg,
                    const vb_vertices_backends *be, vb_vertices_result *res);

/* A device and proposer opened once for several runs (bench, the Python
 * Engine over a trajectory's frames). */
typedef struct vb_vertices_engine vb_vertices_engine;

/* Prepares an engine for cfg's device and proposer (VB_EMISUSE for an
 * unknown proposer). Nothing is opened yet: the device is opened at the
 * first run that needs it (W760 and the twin when it cannot be used), as
 * `--device auto`'s crossover (vb_vertices_device, with cfg->host_below)
 * depends on the input; a run the crossover keeps on host threads opens
 * the twin instead. Close with vb_vertices_close. */
int vb_vertices_open(vb_ctx *ctx, const vb_vertices_backends *be, const vb_vertices_config *cfg,
                     vb_vertices_engine **out);

/* Seconds the device's opening took (0 until a run opened it). */
double vb_vertices_open_seconds(const vb_vertices_engine *e);

/* vb_vertices_run on an engine: the same output; the engine's device
 * (opened here at the first run that needs it) replaces cfg->device, and
 * its opening is not part of the run (t_setup stays 0, t_total starts
 * after it). The same memory check first. A device that fails mid-run is
 * dropped with W762: the run, and later runs on e, use the twin. */
int vb_vertices_run_on(vb_ctx *ctx, vb_vertices_engine *e, const vb_sphere_set *set,
                       const vb_vertices_config *cfg, vb_vertices_result *res);

void vb_vertices_close(vb_vertices_engine *e);

/* The memory a vertex run of set under cfg needs at least (the model and
 * its measurements: cells/vertices_memory.c). */
typedef struct vb_vertices_memory {
    size_t resident;       /* bytes touched at the peak */
    size_t address_space;  /* resident, plus the address space reserved untouched
                            * (thread stacks and malloc arenas, an OpenCL runtime) */
    size_t cells;          /* spheres not inside another */
} vb_vertices_memory;

/* Fills *out for set (validated: contained spheres flagged) under cfg;
 * device_open: the OpenCL runtime is already mapped (not counted).
 * Allocates nothing. */
void vb_vertices_memory_estimate(const vb_sphere_set *set, const vb_vertices_config *cfg,
                                 int device_open, vb_vertices_memory *out);

/* Compares the estimate with the room left (vb_memory_room_get): the
 * address space with ulimit -v, the resident need with every other limit.
 * Returns VB_OK when it fits or no limit is known, else
 * VB_ENOMEM_ESTIMATE (E140) with a message that says how much is needed,
 * how much is available and under which limit. Allocates nothing. */
int vb_vertices_memory_check(vb_ctx *ctx, const vb_sphere_set *set,
                             const vb_vertices_config *cfg, int device_open);

#ifdef __cplusplus
}
#endif
#endif
