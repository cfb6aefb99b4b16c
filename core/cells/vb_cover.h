/* The direction-cover proposer: candidate quadruples that provably hold
 * every vertex of the diagram (see vb_cover_shared.h for the argument).
 *
 * For each sphere i (not contained in another) the cover subdivides the
 * sphere of directions around c_i until, in every patch, the neighbours that
 * can be nearest there are few; the quadruples {i, j, k, l} with j, k, l
 * among those labels and all > i are proposed. Every vertex belongs to the
 * cell of its smallest member, so proposing only quadruples whose smallest
 * id is the base covers every vertex once, with no matching between cells.
 * The proposals are quadruples, not points: the exact certifier solves each
 * and keeps the roots whose tangent sphere is empty. */
#ifndef VB_COVER_H
#define VB_COVER_H

#include <stdatomic.h>

#include "vb.h"
#include "vb_cover_shared.h"
#include "vb_proposer.h" /* vb_cover_clocks */
#include "vb_spheres.h"

struct vb_cert_filter; /* vb_cert_filter.h */

#ifdef __cplusplus
extern "C" {
#endif

#define VB_COVER_DEFAULT_TILES 2u    /* root squares per face side */
#define VB_COVER_DEFAULT_MIN_LEVEL 2u
#define VB_COVER_MAX_LEVEL 48u        /* deepest subdivision (then enumerate): near-ties of
                                         1e-12 (jittered crystals, tangency to 1e-6)
                                         separate by level 45; 2^48 T squares per
                                         face side stay exact doubles for T <= 16 */

typedef struct vb_cover_options {
    unsigned tiles;      /* root squares per face side, power of two (0: default) */
    unsigned min_level;  /* subdivide owned patches at least to this level (0: default) */
    unsigned max_level;  /* enumerate whatever is left at this level (0: VB_COVER_MAX_LEVEL) */
    unsigned enum_max;   /* enumerate a patch once it has at most this many owned labels (0: 3) */
    unsigned threads;    /* host threads (0: VORBALL_THREADS or online CPUs) */
    /* Work split across processes (MPI ranks): this run covers part `part`
     * of `nparts` (0 or 1: everything). The parts are runs of cells along
     * the tree's curve, balanced by count, the same for every process; the
     * union of the parts' quadruples is the whole run's. */
    unsigned part, nparts;
    /* Nonzero: cover only the cells of spheres with id < base_limit (the
     * other spheres stay neighbours). Periodic boxes put the box's atoms
     * first and their images after them (core/periodic/). */
    uint32_t base_limit;
    /* > 0: only vertices of tangent radius <= tmax are sought (the cover
     * stays complete for them; vbq_floor); 0: every vertex. Periodic boxes
     * pass their proven bound rho. */
    double tmax;
    /* Cells per device batch (0: vb_cover_batch_cells's default). Only
     * speed depends on it; tests force many batches with a small one. */
    size_t batch_cells;
    /* Nonzero (vb_cover_run_parts with a backend): each device batch's
     * quadruples go to the sink as a part of their own as soon as they are
     * read back, so that the sink (the certifier) works while the device
     * covers the next batch; a host thread's go to it whenever it holds
     * about a batch's worth (8 quadruples a cell), the rest as each run's
     * last part. The sink is then called from several threads at once. */
    int stream_batches;
    /* Not NULL: the tree's environment for this set and these options,
     * made by the caller with vb_cover_prepare (its tree kept until the run
     * returns), e.g. while a device opens (core/cells/proposer_cover.c);
     * NULL: vb_cover_run_parts makes its own. */
    const vbq_env *env;
} vb_cover_options;

typedef struct vb_cover_stats {
    uint64_t cells;          /* base spheres covered */
    uint64_t neighbours;     /* neighbour records built */
    uint64_t far_neighbours; /* of those, beyond the near radius (hull patches) */
    uint64_t max_cell_neighbours; /* the most records one cell built (a hull cell's ring
                                     fetches: tests/pipeline/hull_fetch.sh bounds it); a
                                     cell a device split into root-patch tasks counts
                                     their sum (each task fetches its own lists) */
    uint64_t patches;        /* patches evaluated */
    uint64_t evals;          /* label enclosures evaluated */
    uint64_t leaves;         /* patches that enumerated quadruples */
    uint64_t max_level_leaves; /* of those, at the deepest level */
    uint64_t quads;          /* distinct quadruples proposed */
    uint64_t retries;        /* cells covered again with a larger arena */
    uint64_t host_cells;     /* cells a device left to the host */
    uint64_t stream_parts;   /* parts streamed to the sink during a run (stream_batches) */
    uint64_t handed_cells;   /* cells a device's group kernel handed to its work-item
                                kernel (the step budget, gpu/cover_ocl.c) */
    uint64_t resumed_patches; /* patches a CPU device's kernel handed to the host, which
                                 covered them alone (cover_resume.c) */
    uint64_t resumed_cells;  /* cells with such patches (not counted in host_cells) */
    double t_device;         /* seconds in the device's batches (wall) */
    double t_host;           /* seconds of the whole cover (wall) */
    vb_cover_steps steps;    /* the host's side of a device cover, step by step */
    unsigned max_level_seen;
} vb_cover_stats;

/* Adds one cover's counters o (a cell, a task or a resume) to st; the
 * caller counts the cell. */
void vb_cover_stats_cell(vb_cover_stats *st, const vbq_cell_out *o);

/* Adds a worker's (or a part's) stats ws to st: counts and seconds added,
 * maxima kept. */
void vb_cover_stats_sum(vb_cover_stats *st, const vb_cover_stats *ws);

/* Quadruples, 4 sorted ids each, sorted lexicographically, no repeats.
 * verdict, when not NULL, holds n verdicts of the certification filter
 * (vbd_cert_shared.h: VBD_ROOT(verdict[k], r) for root r of q[k]), and the
 * list is then sorted and unique. */
typedef struct vb_quad_list {
    uint32_t (*q)[4];
    size_t n, cap;
    uint8_t *verdict;
} vb_quad_list;

void vb_quad_list_free(vb_quad_list *l);

/* The order of vb_quad_list (qsort/bsearch comparator on uint32_t[4]):
 * lexicographic on the four ids; <0, 0 or >0. */
int vb_quad_cmp(const void *pa, const void *pb);

/* One cell's n quadruples q made unique (a device's root-patch tasks or
 * resumed patches may repeat some): sorted where not already increasing,
 * repeats dropped; returns how many are left. */
size_t vb_quad_cell_unique(uint32_t (*q)[4], size_t n);

/* Appends n quadruples q to l (grown as needed). VB_OK or VB_ENOMEM. */
int vb_quad_list_append(vb_quad_list *l, const uint32_t *q, size_t n);

/* A device that covers cells (gpu/cover_ocl.c): the same vbq_cover_cell on
 * the device, with fixed arenas. */
typedef struct vb_cover_backend vb_cover_backend;
struct vb_cover_backend {
    const char *name;        /* "opencl" */
    char device[160];        /* human-readable device */
    size_t batch_cells;      /* cells per run call */
    uint64_t handed_cells;   /* cells the runs' group kernel left, past its step budget,
                                to the device's work-item kernel (a running count) */
    uint64_t device_bytes_peak; /* the most bytes of device buffers the last run (begin
                                   and its runs) held at once */
    uint64_t judge_bytes_peak;  /* the same for the certification filter's buffers (judge;
                                   written by the judge's calls only) */
    vb_cover_clocks clocks;     /* running counts since open */
    void *state;
    /* The last run's handed patches (vbq_hand_patch's entries, each frame's
     * off the cell's sphere), all of cells whose status is VBQ_OK: the host
     * covers each such patch (VBQ_RESUME) and adds its quadruples to the
     * cell's. Owned by the backend, valid until the next run; NULL: none. */
    const uint32_t *hand;
    size_t hand_words;
    /* 1: the host threads resume the handed patches (a GPU, whose host
     * threads are idle); 0: the device's thread does, beside a CPU device
     * that keeps the other cores busy (2-core machine, PoCL, sc 4,096
     * jittered 1e-12: 1.69-1.73 CPU s on that thread, 1.91-1.95 spread). */
    int resume_spread;
    /* The run's host threads (--threads after vb_threads), set by the cover
     * before begin: a backend's host-side work (the arena sample) uses as
     * many; 0: vb_threads(0). */
    unsigned host_threads;
    /* Uploads the input shared by every cell (env's arrays, n spheres) for
     * the runs that follow. VB_OK, VB_ENOMEM or VB_EDEVICE (message in ctx). */
    int (*begin)(vb_ctx *ctx, vb_cover_backend *be, const vbq_env *env, size_t n);
    /* Covers cells[0 .. ncells): out[k] gets cell k's counters and status;
     * when the status is VBQ_OK its out[k].nq quadruples are at
     * (*quads) + 4 out[k].qoff (owned by the backend, valid until the next
     * call). A cell with another status has no quadruples and is covered on
     * the host. VB_OK, VB_ENOMEM or VB_EDEVICE. */
    int (*run)(vb_ctx *ctx, vb_cover_backend *be, const uint32_t *cells, size_t ncells,
               vbq_cell_out *out, const uint32_t **quads);
    void (*close)(vb_cover_backend *be);
    /* May be NULL (none on this device). The certification filter of
     * vbd_cert_shared.h on the device: verdict[k] for quadruples q[0 .. n)
     * over f's spheres (uploaded when f->serial is new). Safe to call from
     * one thread while another runs the cover (its own queue). VB_OK,
     * VB_ENOMEM or VB_EDEVICE (verdict then undefined). */
    int (*judge)(vb_ctx *ctx, vb_cover_backend *be, const struct vb_cert_filter *f,
                 const uint32_t (*q)[4], size_t n, uint8_t *verdict);
    void *judge_state;       /* the judge's own (gpu/cert_filter_ocl.c) */
    void (*judge_close)(vb_cover_backend *be); /* NULL, or frees judge_state
                                                  (vb_cover_backend_close) */
    /* Set by the caller before a run (NULL: none; cover.c sets it when
     * vb_cover_early_on says so). run calls it once, after its first tier
     * and before the tiers that take the cells the first did not finish,
     * with out[0 .. ncells) as they stand then: a cell whose status is
     * VBQ_OK is final (its quadruples at quads + 4 out[k].qoff, its handed
     * patches among hand[0 .. hand_words)), so the caller can hand those
     * cells on while the later tiers run. The pointers are valid during the
     * call only. A status other than VB_OK stops the run and is returned. */
    int (*early)(void *user, const vbq_cell_out *out, size_t ncells, const uint32_t *quads,
                 const uint32_t *hand, size_t hand_words);
    void *early_user;
    /* 1 while a run's later tiers take many cells (set by the caller's
     * early take, cleared when run returns): the judge is then left to the
     * host's twin, since a list judged on the device would wait for those
     * tiers' kernels (H100, stop 51: the capsid's early part judged there
     * was certified only after its large tier, 0.08 s; judged by the twin,
     * 0.24 s warm instead of 0.27-0.31). Where few cells are left (fcc
     * 10,976 exact: 48, a 0.026 s tier) the device's judge is the faster. */
    atomic_int running;
};

/* A run's handed patches (vb_cover_backend's hand) by cell, for the host
 * to resume (core/cells/cover_resume.c). Zero it before the first make. */
typedef struct vb_hand_index {
    const uint32_t *hand;
    uint64_t *key;           /* (cell << 32 | word position), sorted */
    size_t n, cap;
    uint32_t *scratch;       /* one cell's entries, together */
    size_t scap;
} vb_hand_index;

/* Indexes the entries hand[0 .. words) (kept by pointer). VB_OK or
 * VB_ENOMEM. */
int vb_hand_index_make(vb_hand_index *x, const uint32_t *hand, size_t words);

/* Cell i's entries, together in *words (nwords words, *patches entries;
 * owned by x, valid until the next call); none: *nwords 0. VB_OK or
 * VB_ENOMEM. */
int vb_hand_index_cell(vb_hand_index *x, uint32_t i, const uint32_t **words, size_t *nwords,
                       size_t *patches);

void vb_hand_index_free(vb_hand_index *x);

/* Of a launch's handed patches h[0 .. words) (vbq_hand_patch's entries,
 * each frame's off the task's index k < ntasks in the launch), keeps those
 * of tasks that finished (out[k].status VBQ_OK) at the front of h, each
 * off made the task's sphere cells[k]: a task with another status goes
 * whole to the host, and its entries with it. *kept: their words. VB_OK,
 * or VB_EINTERNAL for an entry that names no task or runs past words
 * (nothing kept). The device's driver (gpu/cover_launch.c) and the group
 * kernel's emulation (tests/gpu/test_cover.c) read entries through it. */
int vb_hand_keep_finished(uint32_t *h, size_t words, const uint32_t *cells, size_t ntasks,
                          const vbq_cell_out *out, size_t *kept);

/* Closes a backend; NULL is allowed. */
void vb_cover_backend_close(vb_cover_backend *be);

/* Frees a host cover arena's buffers and zeroes it (safe on a zeroed one). */
void vbq_arena_free(vbq_arena *a);

/* (Re)allocates a host cover arena with the given capacities (neighbours,
 * labels, stack, quadruples), freeing what it held; VB_OK or VB_ENOMEM (the
 * arena then holds what could be allocated and must still be freed). */
int vbq_arena_make(vbq_arena *a, uint32_t nb, uint32_t lab, uint32_t st, uint32_t q);

/* vbq_cover_cell on the host, in the widest build this CPU runs
 * (core/cells/cover_cell.c: AVX2 where the CPU has it); the same output as
 * vbq_cover_cell on every CPU. */
void vb_cover_cell_host(const vbq_env *e, const vbq_arena *ar, uint32_t i, uint32_t root,
                        vbq_cell_out *o);

/* Of `want` cells spread evenly over the tree's order of env (all of its
 * env->m cells when fewer), covered on the host (vb_cover_cell_host) in
 * arenas of nb records and lab labels, on `threads` host threads: *over of
 * them ran out of one of the two (a cell stops where it runs out, so none
 * costs more than nb records), *covered counts those and the cells that
 * fit (a cell past the arenas' stack or quadruples counts in neither). The
 * counts do not depend on the threads. Allocates nothing that outlives the
 * call. VB_OK or VB_ENOMEM (the counts then partial). */
int vb_cover_sample_over(const vbq_env *env, size_t want, uint32_t nb, uint32_t lab, int threads,
                         size_t *covered, size_t *over);

/* The shared input of every cell: the tree over the centres and the
 * parameters, in *env (its arrays belong to *tree and to set). For
 * backends and tests that run vbq_cover_cell themselves; vb_cover_run
 * calls it. VB_OK, VB_EMISUSE (bad options, set not validated),
 * VB_EINPUT_TOOLARGE, VB_ENOMEM. Free with vb_cover_tree_free. */
typedef struct vb_cover_tree vb_cover_tree;
int vb_cover_prepare(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                     vb_cover_tree **tree, vbq_env *env);
void vb_cover_tree_free(vb_cover_tree *tree);

/* Runs the cover on a validated set (contained spheres flagged) and appends
 * the proposed quadruples to out (sorted, unique). be NULL covers every cell
 * on host threads; otherwise be covers them batch by batch and the host
 * covers the cells whose arenas ran out on the device. Returns VB_OK,
 * VB_ENOMEM, VB_EMISUSE (bad options), VB_EINPUT_TOOLARGE or the backend's
 * VB_EDEVICE (out is then unchanged); stats may be NULL. The quadruples do
 * not depend on the backend or the thread count. */
int vb_cover_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                 vb_cover_backend *be, vb_quad_list *out, vb_cover_stats *stats);

/* Sorts l on nt threads (vb_quad_cmp) and drops repeats. VB_OK or
 * VB_ENOMEM. */
int vb_quad_list_canonical(vb_quad_list *l, int nt);

/* A consumer of the cover's quadruples, part by part: part is unique,
 * sorted unless it is a streamed device batch (stream_batches; the sink
 * sorts it, vb_quad_list_canonical), and the sink may take its array
 * (leaving *part zeroed). Parts are disjoint (a quadruple is proposed by
 * the cell of its smallest id), but a vertex of degree > 4 is the root of
 * quadruples of several of its members' cells, which may lie in different
 * parts. Returns VB_OK or an error that stops the cover (returned by
 * vb_cover_run_parts). */
typedef int (*vb_cover_sink)(void *user, vb_quad_list *part);

/* Cells per device batch: opt->batch_cells when nonzero, else
 * VORBALL_COVER_BATCH (1 to 2^30) when set, else 0 (the backend's own:
 * 2^18 on a GPU, 2^14 on a CPU device). */
size_t vb_cover_batch_cells(const vb_cover_options *opt);

/* Parts for a pipelined run: VORBALL_COVER_PARTS (1-64)
 * when set, else 1. Only speed depends on it. One part is the default
 * because it was the fastest measured: on an NVIDIA H200 with 16 host
 * cores, the 211,440-sphere tiled capsid took 1.38 s in 1 part, 1.85 s in
 * 4 and 1.83 s in 8 (each part's device batches end on their slowest
 * cells, and the certifier's threads take the host threads that help the
 * device). */
unsigned vb_cover_pipeline_parts(void);

/* Whether a run on be takes each batch's finished cells early (be->early):
 * VORBALL_COVER_EARLY=1 on, =0 off, else on where the host threads resume
 * handed patches (be->resume_spread: a GPU, whose host threads wait on the
 * device while its later tiers run; they then certify and resume the
 * first tier's cells meanwhile). Only speed depends on it. */
int vb_cover_early_on(const vb_cover_backend *be);

/* vb_cover_run in `parts` runs of cells along the tree's curve (of this
 * process's share, opt->part of opt->nparts), the tree built once: each
 * part's quadruples go to sink as soon as its cells are covered, so that
 * a consumer (the certifier) works on one part while the next is covered.
 * The union of the parts is vb_cover_run's list. Returns VB_OK, the sink's
 * error, VB_EMISUSE (parts not 1-64, no sink, bad options), VB_ENOMEM,
 * VB_EINPUT_TOOLARGE or the backend's VB_EDEVICE; stats (may be NULL) sum
 * the parts. */
int vb_cover_run_parts(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                       vb_cover_backend *be, unsigned parts, vb_cover_sink sink, void *user,
                       vb_cover_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
