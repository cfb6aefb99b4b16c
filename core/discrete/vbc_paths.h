/* The channel graph's sweeps as batches (issue 33): one batch sweeps many
 * components of the frame's channel voxel graph at once, one source in
 * each, by rounds of relaxation, which suit a GPU (gpu/channel_paths.cl)
 * as well as host threads; channel_paths.c is the plain-C twin that
 * --device ref runs. Internal to core/discrete and gpu/.
 *
 * Why a batch gives vbc_sweep's bytes. Path costs are folded from the
 * source, d' = fl(d + step), with every step > 0; fl(d + step) is
 * nondecreasing in d and, while d < 2^52 * step, larger than d (the
 * analysis checks this bound per frame: steps are at least 1 / R^2 for R
 * the largest clearance, distances below 693 per voxel; a frame past it,
 * R^2 n > 1.4e12, sweeps one component at a time, channel_waves.c). Under those two
 * properties Dijkstra and any relaxation run to its fixed point give the
 * same distance per voxel: the least folded cost over all paths (each
 * value ever held is some path's cost; Dijkstra settles in increasing
 * (distance, position) order and relaxation stops only when no step
 * improves a voxel). vbc_sweep sets pred[q] when a settled u improves q
 * strictly, so pred[q] is the first voxel in settling order with
 * fl(dist[u] + step(u, q)) == dist[q]: the smallest (dist[u], u) among
 * q's neighbours that reach it at its distance (vbc_path_pred_before).
 * A batch computes that rule from the fixed point, so pred is the same
 * whatever the order of the rounds, the number of threads or the device.
 * Farthest members and the paths are then read as vbc_farthest and the
 * analysis do. */
#ifndef VBC_PATHS_H
#define VBC_PATHS_H

#include <stddef.h>
#include <stdint.h>

#include "vbc_channel.h"

/* The frame's channel voxel graph as the batches read it. */
typedef struct vbc_paths_graph {
    const vbc_grid *g;
    const uint32_t *v;       /* voxel index per position, ascending, mouth bit clear */
    size_t n;                /* positions */
    const double *clear;     /* clearance per position, Å */
    const size_t *adj_start; /* the host's 26-connected CSR adjacency (vbc_graph) */
    const uint32_t *adj;
    const uint8_t *adj_len;  /* 1 face, 2 edge, 3 corner */
} vbc_paths_graph;

/* One batch: sources in distinct components (no two in one). */
typedef struct vbc_paths_batch {
    const uint32_t *src;
    size_t nsrc;
    int weighted;            /* vbc_path_step's weighting */
    double *dist;            /* out per position: least folded cost from its
                                component's source; INFINITY in components
                                without a source */
    uint32_t *pred;          /* out per position: the rule above; UINT32_MAX at
                                sources and off the swept components */
    size_t rounds;           /* out: relaxation rounds (statistics only) */
} vbc_paths_batch;

/* An engine that runs batches elsewhere (a device). begin uploads the
 * graph of one frame's analysis, sweep runs a batch on it, end releases
 * it; begin and sweep return VB_OK, or another status after which the
 * analysis runs that batch (and, after begin fails, every batch of the
 * frame) on the twin, which gives the same bytes. Calls for one frame come
 * from one thread; an engine serves frames from several threads by
 * locking inside. */
typedef struct vbc_paths_engine {
    void *user;
    int (*begin)(void *user, const vbc_paths_graph *G);
    int (*sweep)(void *user, const vbc_paths_graph *G, vbc_paths_batch *b);
    void (*end)(void *user);
} vbc_paths_engine;

/* The plain-C twin: b's distances by rounds over a frontier (the voxels
 * improved in the round before) until none improves, one component per
 * task on the VORBALL_THREADS threads, then the predecessors by the rule
 * on slices of positions. b->rounds: the most rounds a thread ran
 * (statistics). Returns 0, or -1 when out of memory. */
int vbc_paths_sweep_ref(const vbc_paths_graph *G, vbc_paths_batch *b);

/* The engine of --device ref: every batch on the twin (begin, sweep, end
 * do nothing of their own). */
const vbc_paths_engine *vbc_paths_engine_ref(void);

/* Whether the analysis's independent steps run beside each other (the
 * cells and support atoms beside the voxels' steps in vbc_analyse_paths;
 * the analysis beside the pore stage, vbc_frame_beside): from
 * VBC_PORE_MIN_THREADS threads, unless VORBALL_ANALYSIS_BESIDE is 0 (the
 * steps one after the other, for timing both ways in one session). The
 * result is the same bytes either way. */
int vbc_analysis_beside(void);

/* As vbc_analyse_given, with the ends and sweeps of the components run as
 * batches on `paths` (vbc_paths_engine_ref(): the twin) when it is not
 * NULL (channel_waves.c), else one component at a time on host threads;
 * res->ms_graph the batches' wall time. The result is the same bytes
 * either way. */
int vbc_analyse_paths(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, const uint32_t *comp, size_t nvox,
                      const vbc_options *opt, const vbc_paths_engine *paths, vbc_result *res);

/* How the analysis runs its sweeps, from VORBALL_DEVICE_PATHS: 0 (unset,
 * or anything else) the per-component Dijkstra on host threads (the
 * default); 1 as batches, on the kernels when the pipe's device is a GPU,
 * else on the twin (a CPU device gains nothing from them: PoCL spent about
 * 1 ms of CPU per round launch, 0.3 s a frame of adk_oplsaa); 2 as batches
 * on the kernels of any OpenCL device (tests of the kernels on PoCL). The
 * bytes of every table are the same whichever runs. */
int vbc_paths_mode(void);

#endif
