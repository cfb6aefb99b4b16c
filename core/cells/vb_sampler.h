/* The sampling pipeline of the seed paper: culling, backends, matching.
 *
 * vb_sampler_run takes a validated sphere set and a backend (the plain-C
 * reference below, or the OpenCL one in gpu/vbg_sampler.h), runs the ray
 * envelope and vertex stages batch by batch, matches the candidates across
 * the cells of all their spheres (Sec. 5.4), runs the targeted search for
 * incompletely matched vertices (5.5) and the tangent-sphere test, and hands
 * back candidates for the exact certifier. Both backends evaluate the same
 * functions of vb_geom_shared.h. */
#ifndef VB_SAMPLER_H
#define VB_SAMPLER_H

#include "vb.h"
#include "vb_geom_shared.h"
#include "vb_proposer.h"
#include "vb_spheres.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults (the samples' in vb_proposer.h). */
#define VB_SAMPLER_DEFAULT_DEPTH 4u
#define VB_SAMPLER_DEFAULT_ITER 40u
#define VB_SAMPLER_DEFAULT_TARGET_DEPTH 10u

typedef struct vb_sampler_options {
    unsigned samples;        /* S >= 2 (0: default) */
    unsigned tiles;          /* culling tiles per face side (0: automatic) */
    unsigned max_depth;      /* subdivision depth (0: default) */
    unsigned max_iter;       /* Newton iterations (0: default) */
    unsigned target_depth;   /* levels of the targeted search (0: default) */
    double tol;              /* world units; <= 0: 1e-5 of the bounding-box diagonal */
    int all_pairs;           /* 1: no culling, every cell tests all n - 1 bisectors */
    int topology;            /* 1: collect face adjacency and edge evidence */
    unsigned batch_rays;     /* rays per backend batch (0: backend's choice); with
                                await_backend, of the batches culled before the
                                backend is known (then at most its choice) */
    unsigned threads;        /* host threads (0: VORBALL_THREADS or online CPUs);
                                the output does not depend on it */
    void (*progress)(void *user, double fraction); /* may be NULL */
    void *progress_user;
    /* When vb_sampler_run gets no backend: called once, before the first
     * batch, to obtain it, so that a device's set-up (context, program
     * build) overlaps the culling of that batch; batch_rays must then be
     * set. Returns the backend (still owned by the caller) or NULL with an
     * error in the context. */
    struct vb_sampler_backend *(*await_backend)(void *user);
    /* May be NULL: nonzero once await_backend would return at once. While
     * it says 0, further batches are culled and joined to the first one
     * (up to VB_SAMPLER_MAX_AHEAD batches), so the set-up hides more
     * culling; the output does not depend on how bases are batched. */
    int (*backend_ready)(void *user);
    void *await_user;
} vb_sampler_options;

#define VB_SAMPLER_MAX_AHEAD 8u
/* Host bytes of batch data (bases, bisectors, tiles) beyond which the first
 * batch stops growing while the device is set up. */
#define VB_SAMPLER_AHEAD_BYTES ((size_t)256 << 20)

/* One batch for a backend: the bases, their bisectors and culling tiles. */
typedef struct vb_sampler_batch {
    size_t nbases;
    const vbs_base *bases;
    size_t nbis;
    const vbs_bisector *bis;
    size_t ntile_off;        /* nbases * 6 * T * T + 1 */
    const uint32_t *tile_off;
    size_t ntile_idx;
    const uint32_t *tile_idx;
    vbs_params params;
} vb_sampler_batch;

/* Growable array of candidates. */
typedef struct vb_cand_vec {
    vbs_cand *v;
    size_t n, cap;
} vb_cand_vec;

int vb_cand_vec_push(vb_cand_vec *cv, const vbs_cand *c);
void vb_cand_vec_free(vb_cand_vec *cv);

/* What a backend returns for one batch: candidates appended to cand in any
 * order (the driver sorts them), overflow counts candidates that did not
 * fit VBS_MAX_CAND of their grid cell, stage times are added to *times. */
typedef struct vb_sampler_batch_out {
    vb_cand_vec *cand;
    uint64_t overflow;
    vb_stage_times *times;
} vb_sampler_batch_out;

/* The backends table: one interface, two implementations (ref, OpenCL). */
typedef struct vb_sampler_backend vb_sampler_backend;
struct vb_sampler_backend {
    const char *name;        /* "ref", "opencl" */
    char device[160];        /* human-readable device */
    unsigned batch_rays;     /* preferred rays per batch */
    uint64_t device_bytes_peak; /* the most bytes of device buffers held at once so far */
    void *state;
    /* Runs envelope (Sec. 3.3) and vertices (Sec. 4-5) for one batch.
     * Returns VB_OK, VB_ENOMEM or VB_EDEVICE (message in ctx). */
    int (*run_batch)(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
                     vb_sampler_batch_out *out);
    void (*close)(vb_sampler_backend *be);
};

/* The batch-size policy, one copy for every backend: rays per batch on a
 * GPU (large launches) or on a CPU (the reference, or an OpenCL CPU device,
 * gains little beyond a few million rays and keeps memory small). The
 * output does not depend on it. */
unsigned vb_sampler_batch_rays(int gpu);

/* Opens the plain-C reference backend. Free with vb_sampler_backend_close. */
int vb_sampler_ref_open(vb_ctx *ctx, vb_sampler_backend **out);

/* Closes any backend; NULL is allowed. */
void vb_sampler_backend_close(vb_sampler_backend *be);

/* Runs the pipeline up to (not including) certification. set must be
 * validated (contained spheres flagged). be may be NULL when
 * opt->await_backend and opt->batch_rays are set. Returns VB_OK, VB_EMISUSE
 * (bad options), VB_EINPUT_SCALE (a radius below 1e-50 of the input's
 * extent: beyond the doubles of the normalised frames), VB_EINPUT_TOL
 * (opt->tol below 1e-12 of the extent), VB_ENOMEM or the backend's
 * VB_EDEVICE. */
int vb_sampler_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_sampler_options *opt,
                   vb_sampler_backend *be, vb_proposal *res);

/* Candidates for the four quadruples that swap one of ids[0..3] for
 * `intruder` (a sphere that cuts the tangent sphere of ids, as the exact
 * certifier reports it): near a (nearly) degenerate vertex the sampled
 * quadruple is often the wrong one of several that meet there. Each gets
 * both of its tangent spheres (double), or p when the double solver cannot
 * separate them. Appended to out with status CANDIDATE. VB_OK or VB_ENOMEM. */
int vb_sampler_swap_candidates(const vb_sphere_set *set, const uint32_t ids[4],
                               uint32_t intruder, const double p[4], vb_vertex_list *out);

/* Default tolerance: 1e-5 of the diagonal of the spheres' bounding box. */
double vb_sampler_default_tol(const vb_sphere_set *set);

#ifdef __cplusplus
}
#endif
#endif
