/* Internal to the OpenCL JFA backend (gpu/jfa*.c): the engine, its buffers
 * and kernels, and the host toolbox the dense, Facet-JFA and exact runs
 * share (gpu/jfa.c). The preparation both backends share is in
 * core/discrete/vbj_prep.h. */
#ifndef VBJ_INTERNAL_H
#define VBJ_INTERNAL_H

#include "vb_parallel.h"
#include "vbg_runtime.h"
#include "vbj_prep.h"

/* The OpenCL engine: a runtime (borrowed) with the programs, kernels and
 * buffers of every run. */
typedef struct vbj_engine vbj_engine;

/* Opens an engine on a runtime (borrowed: close it after the engine). Builds
 * facet_jfa.cl, jfa_exact.cl and jfa_tiles.cl; jfa.cl's builds wait for
 * their first use (runs fetch their kernels before their clocks start).
 * VB_EDEVICE / VB_ENOMEM. */
int vbj_engine_open_runtime(vb_ctx *ctx, vbg_runtime *rt, vbj_engine **out);
void vbj_engine_close(vbj_engine *e);

/* vbj_run on the engine (after vbj_run's checks; want never 0). With
 * VBJ_WANT_DEVICE the label grid stays on the device: vbj_engine_labels_device. */
#define VBJ_WANT_DEVICE 4u
int vbj_cl_run(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, const vbj_options *o,
               unsigned want, vbj_result *out);

/* The label grid of the last run with VBJ_WANT_DEVICE (n^dim cl_uint, seed
 * indices), owned by the engine, valid until the next run or close; NULL
 * when not wanted. */
cl_mem vbj_engine_labels_device(const vbj_engine *e);

/* Buffers the OpenCL engine keeps between runs (grown, never shrunk). */
typedef struct vbj_clbuf {
    cl_mem mem;
    size_t bytes;
} vbj_clbuf;

/* Kernels, created on first use and kept by the engine. jfa.cl is built six
 * ways (its programs, too, are built on first use): the build number says
 * 16-bit labels (VBJ_JFA_LABEL16) and the distances: exact 64-bit integers
 * (VBJ_JFA_DIST64), a float filter with exact fallback (VBJ_JFA_FLOAT), else
 * exact doubles; kernel `k` of build `b` is b * VBJ_KJFA + k. */
enum {
    VBJ_K_PLACE = 0,
    VBJ_K_STEP2,
    VBJ_K_STEP3,
    VBJ_K_COUNT,
    VBJ_K_WIDEN,
    VBJ_K_BOUNDARY,
    VBJ_KJFA /* kernels per jfa.cl build */
};
#define VBJ_JFA_LABEL16 1
#define VBJ_JFA_DIST64 2
#define VBJ_JFA_FLOAT 4
#define VBJ_JFA_BUILDS 6
enum {
    VBJ_K_FSTEP = VBJ_JFA_BUILDS * VBJ_KJFA, /* first kernel of facet_jfa.cl */
    VBJ_K_MARKREFINE,
    VBJ_K_STRIP,
    VBJ_K_FSMALL,
    VBJ_K_EXACT, /* jfa_exact.cl */
    VBJ_K_TILES, /* jfa_tiles.cl */
    VBJ_NKERNELS
};

/* The distance build of jfa.cl for an [n]^dim grid: VBJ_JFA_FLOAT where
 * every coordinate is an exact float, else 0 (doubles) where every squared
 * distance is an exact double, else VBJ_JFA_DIST64 (see gpu/jfa.cl). */
int vbj_dist_build(int dim, uint32_t n);

struct vbj_engine {
    vbg_runtime *rt;
    cl_program jfa[VBJ_JFA_BUILDS], facet, exact, tiles; /* owned by the runtime's program cache */
    cl_kernel kernels[VBJ_NKERNELS];
    vbj_clbuf seeds, seeds_fp, pairs, grid[2], store[2], tmp, list[2], counter, labels, cells_start,
        cells_items, cells_ring0, tcounters;
    cl_mem device_labels; /* one of the buffers above, or NULL */
    /* Profiling events of the timed commands of a run (vbj_cl_event). */
    cl_event *events;
    int nevents, cap_events, recording;
};

/* Where the next enqueued command should leave its event: a slot of the
 * engine's list while recording (grows it), else NULL. */
cl_event *vbj_cl_event(vbj_engine *e);

/* Starts recording events / stops and returns the summed device time (ms)
 * of the recorded commands, releasing them. Call after the queue drained. */
void vbj_cl_record(vbj_engine *e);
double vbj_cl_recorded_ms(vbj_engine *e);

/* A kernel argument: its size and address. */
typedef struct vbj_arg {
    size_t size;
    const void *ptr;
} vbj_arg;
#define VBJ_ARG(v) {sizeof(v), &(v)}

/* Makes sure b holds at least `bytes` (contents are lost when it grows). */
int vbj_clbuf_reserve(vb_ctx *ctx, vbj_engine *e, vbj_clbuf *b, size_t bytes);

/* The engine's kernel number `which` (VBJ_K_*). */
int vbj_cl_kernel(vb_ctx *ctx, vbj_engine *e, int which, cl_kernel *out);

/* Sets nargs arguments of k; `what` names the kernel in errors. */
int vbj_cl_set_args(vb_ctx *ctx, cl_kernel k, const char *what, int nargs, const vbj_arg *args);

/* Enqueues k over `global` (dims 1..3): local size up to 64 along the
 * contiguous axis on GPUs (global rounded up; kernels bound-check), the
 * runtime's choice on CPU devices. */
int vbj_cl_launch(vb_ctx *ctx, vbj_engine *e, cl_kernel k, int dims, const size_t *global,
                  const char *what);

/* Index of kernel `kernel` (VBJ_K_PLACE ..) in the build of jfa.cl for s's
 * grid, with 16-bit labels when narrow. */
int vbj_cl_jfa_kernel_index(const vbj_seeds *s, int narrow, int kernel);

/* Reserves b for `bytes` and writes `data` into it, blocking; `what` names
 * the transfer in a device error. VB_ENOMEM / VB_EDEVICE. */
int vbj_cl_upload(vb_ctx *ctx, vbj_engine *e, vbj_clbuf *b, const void *data, size_t bytes,
                  const char *what);

/* Uploads the seeds as int2 (2D) or int4 (3D) into e->seeds and, unless
 * vbj_dist_build is VBJ_JFA_DIST64, in the step kernels' coordinate type
 * (float or double, 2 or 4 per seed) into e->seeds_fp. */
int vbj_cl_upload_seeds(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s);

/* Places the seeds on the grid of cells of f pixels (vbj_place) and uploads
 * the (cell, seed) pairs into e->pairs. */
int vbj_cl_upload_pairs(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t f,
                        size_t *count, uint32_t *collisions);

/* Dense JFA on the (n/f)^d grid of cells of f pixels from the uploaded pairs;
 * the result ends in e->grid[*which], with 16-bit labels when narrow (fewer
 * than 65535 seeds), else 32-bit. Adds to counts. Asynchronous. */
int vbj_cl_dense(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t f, size_t npairs,
                 int narrow, const uint32_t *steps, int nsteps, vbj_counts *counts, int *which);

/* A dense run on OpenCL: JFA with the step lengths of variant v on the n^d
 * grid (prepared untimed, run timed; 16-bit labels below 65535 seeds, widened
 * to the 32-bit grid *result afterwards as ms_fill). With boundary, the run
 * also counts the boundary pixels (jfa_boundary) into out->counts.boundary:
 * Facet-JFA when it starts at m = n. */
int vbj_cl_dense_run(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, vbj_variant v, int boundary,
                     vbj_result *out, cl_mem *result);

/* OpenCL Facet-JFA (gpu/jfa_facet.c): fills out's counts and times; the
 * label grid of the last level is *result (one of the engine's buffers). */
int vbj_cl_facet(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, const vbj_options *opt,
                 vbj_result *out, cl_mem *result);

/* Counts the boundary pixels of label grid `lab` (16-bit when narrow) into
 * counts->boundary; the read of the count waits for the queue. */
int vbj_cl_count_boundary(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, int narrow, cl_mem lab,
                          vbj_counts *counts);

/* The exact tiled engine (gpu/jfa_tiles.c): variant VBJ_EXACT or
 * VBJ_EXACT_BOUNDARY; fills out's counts and times; the 32-bit label grid
 * is *result (the engine's labels buffer). */
int vbj_cl_tiles(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, vbj_variant v, vbj_result *out,
                 cl_mem *result);

/* OpenCL exact reference (gpu/jfa_exact.c) into host labels. */
int vbj_cl_exact(vb_ctx *ctx, vbj_engine *e, const vbj_seeds *s, uint32_t *labels);

/* Per-pixel distinct-label counts on the device, into host out. */
int vbj_cl_count_labels(vb_ctx *ctx, vbj_engine *e, int dim, uint32_t n, cl_mem labels,
                        uint8_t *out);


#endif
