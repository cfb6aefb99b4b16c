/* The proposer's side of the vertex pipeline (vb_vertices.h): what a
 * proposer of candidate vertices takes (vb_propose_options: what any
 * proposer needs; vb_propose_args: what the driver adds), what it hands
 * back (vb_proposal) and its table (vb_proposer). Plain data only: no
 * kernel math comes in through here (the sampler's batches and backends
 * are in vb_sampler.h, the cover's settings in vb_cover.h). */
#ifndef VB_PROPOSER_H
#define VB_PROPOSER_H

#include <stdint.h>

#include "vb_device.h"
#include "vb_spheres.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A device's arena tiers (gpu/vbg_cover_state.h): the first launch, the
 * large slices, the group kernel's hand-off, the huge slices. */
#define VB_COVER_TIERS 4
/* The clocks' steps: the tiers, then the first tier's reruns of cells that
 * found no room for their handed patches (gpu/cover_ocl.c,
 * rerun_hand_short), counted apart from its first launches. */
#define VB_COVER_RERUN VB_COVER_TIERS
#define VB_COVER_STEPS (VB_COVER_TIERS + 1)

/* Per step of a device's launches (the tiers, the reruns): seconds its
 * kernels ran on the device (profiling events; transfers and host work
 * excluded), the host's wall seconds of its launches (arguments, uploads,
 * the kernel and the read-backs: launch_s - kernel_s is what the launches
 * spent besides the kernels), its launches and its tasks (cells, or
 * root-patch tasks); the work (issue #30): the patches its tasks popped,
 * the most one task popped (a launch lasts as long as its slowest slice),
 * and the patches of its tasks that ran out of room (an arena, the output,
 * a tie cluster's handed-patch room), whose cells or tasks a later step or
 * the host covers again from their roots: work done twice. */
typedef struct vb_cover_clocks {
    double kernel_s[VB_COVER_STEPS], launch_s[VB_COVER_STEPS];
    uint64_t launches[VB_COVER_STEPS], tasks[VB_COVER_STEPS];
    uint64_t patches[VB_COVER_STEPS], task_max[VB_COVER_STEPS];
    uint64_t wasted_patches[VB_COVER_STEPS], wasted_tasks[VB_COVER_STEPS];
    /* What the first tier's arenas had to hold (issue #30, its memory
     * plan): the most records, labels and quadruples one of its tasks held
     * among those that finished or met the group kernel's budget, and how
     * many of them held more than half its records or half its labels
     * (tasks that would have run out of arenas half as large). */
    uint64_t first_nb_max, first_lab_max, first_q_max, first_past_half;
} vb_cover_clocks;

/* Where a device run's cover time went on the host (vb_cover.h's
 * vb_cover_run with a backend; zero on host threads alone). Wall seconds
 * unless named CPU (the thread's own CPU clock, summed over threads). */
typedef struct vb_cover_steps {
    uint64_t batches;        /* device batches run (be->run calls) */
    double dispatch_s;       /* the device's thread after each batch's read-back: its cells'
                                quadruples and handed patches sorted out, queued, or resumed
                                there (resume_cpu_s counts those), sinks not included */
    double sink_s;           /* in the sinks (certification filter, streamed parts), on the
                                cover's threads, summed */
    double host_cells_cpu_s; /* CPU of the cells the host threads covered whole beside the
                                device (cover_host_cells) */
    double resume_cpu_s;     /* CPU of the handed patches resumed (cover_resumed_patches),
                                on whichever thread resumed them */
    uint64_t resume_queued;  /* cells whose patches the device's thread queued for the host
                                threads (the rest it resumed itself) */
    double host_wait_s;      /* host threads waiting for work while the device ran (the host
                                waited on the device), summed over threads */
    double tail_s;           /* after the device's last batch until the cover ended (the device
                                idle, waiting on the host threads) */
} vb_cover_steps;

struct vb_quad_list;     /* vb_cover.h */
struct vb_cover_options; /* vb_cover.h: the cover's own settings */

/* The sampling's default budget: S = 30 rays per face side reached 100 %
 * recall on the corpus and the proteins of shared/data (see
 * papers/gpu-voronoi-cells-of-spheres). */
#define VB_SAMPLER_DEFAULT_SAMPLES 30u

/* What a caller chooses for any proposer; a proposer reads what applies to
 * it (the cover: tol and threads) and ignores the rest. Zero everywhere is
 * the default. */
typedef struct vb_propose_options {
    double tol;        /* world units; <= 0: 1e-5 of the bounding-box diagonal */
    unsigned threads;  /* host threads (0: VORBALL_THREADS or online CPUs); the output
                          does not depend on it */
    unsigned samples;  /* the budget per cell: rays per face side of the sampling,
                          S >= 2 (0: its default) */
    unsigned tiles;    /* culling tiles per face side of the sampling (0: automatic) */
    int all_pairs;     /* 1: no culling, every cell tests all n - 1 bisectors (sampling) */
    int topology;      /* 1: collect face adjacency and edge evidence (sampling) */
} vb_propose_options;

/* What the driver hands a proposer's run: the caller's options, the
 * cover's own settings and, for a proposer of quadruples, where to stream
 * them. */
typedef struct vb_propose_args {
    vb_propose_options opt;
    /* The cover's settings (vb_cover_options: the work split over MPI
     * ranks, the periodic base limit, its levels), threads taken from opt;
     * NULL: its defaults. Other proposers ignore it. */
    const struct vb_cover_options *cover;
    /* May be NULL. A proposer of quadruples (the cover) hands them to it
     * part by part as they are proposed, sorted and unique (the contract
     * of vb_cover_sink: parts disjoint, the sink may take a part's array),
     * and leaves the result's quads empty; a sink's error stops the
     * proposer and is returned. */
    int (*quads_sink)(void *user, struct vb_quad_list *part);
    void *quads_user;
} vb_propose_args;

/* Seconds spent per stage (wall clock; device stages as the backend measures). */
typedef struct vb_stage_times {
    double cull, upload, envelope, vertices, matching;
    /* Parts of matching: targeted search (5.5), tangent spheres of the
     * sampled quadruples with their swaps, neighbourhood completion. */
    double targeted, tangent, completion;
} vb_stage_times;

/* Topology evidence from the samples (Sec. 4): faces seen (i, j), i < j, and
 * triples (i < j < k) seen as two-colour grid cells of one of their spheres,
 * each sorted and unique. */
typedef struct vb_topology_evidence {
    uint32_t *faces;          /* 2 per face */
    size_t nfaces;
    uint32_t *triples;        /* 3 per triple */
    size_t ntriples;
} vb_topology_evidence;

/* What a proposer hands back: candidates, or quadruples, and its counters
 * (the sampling's first, the cover's after them; zero for the path not
 * taken). */
typedef struct vb_proposal {
    vb_vertex_list candidates;    /* one per (vertex, quadruple), status CANDIDATE */
    vb_stage_times times;
    double tol;                   /* tolerance used (world units) */
    double clip;                  /* clip distance used (world units) */
    unsigned samples, tiles;
    uint64_t rays;                /* rays shot in the batches */
    uint64_t raw_candidates;      /* from the vertex stage */
    uint64_t overflow;            /* candidates lost to VBS_MAX_CAND (warned) */
    uint64_t clusters;            /* distinct vertices after matching */
    uint64_t complete_first;      /* found from all their spheres before 5.5 */
    uint64_t targeted_searches;   /* (vertex, sphere) searches run */
    uint64_t targeted_found;      /* of those, successful */
    uint64_t incomplete;          /* still not found from all their spheres after 5.5 */
    uint64_t sampled_vertices;    /* clusters with an empty tangent sphere: the vertices
                                     sampling and 5.5 saw */
    uint64_t vertices_incomplete; /* of those, not found from all their spheres after 5.5 */
    uint64_t dropped;             /* tangent spheres (quadruple roots) that were not empty */
    uint64_t swaps;               /* quadruples tried by swapping in an intruder */
    uint64_t ring_tries;          /* quadruples tried by the neighbourhood completion */
    uint64_t first_cell;          /* vertices found from the cell of sphere 0 (Fig. 13): sampled,
                                     with an empty tangent sphere */
    uint64_t from_sampling;       /* candidates from the sampled cells (after 5.5 and the
                                     tangent test), before the neighbourhood completion */
    uint64_t bisectors;           /* bisectors kept by the culling */
    vb_topology_evidence topo;    /* filled when options.topology */
    /* A proposer of quadruples (the direction cover) leaves candidates
     * empty and these instead: sorted unique sphere quadruples whose exact
     * roots hold every vertex (certify each root). complete says that the
     * proposer proves that no vertex is missing. */
    struct {
        uint32_t (*q)[4];
        size_t n, cap;
        uint8_t *verdict;         /* NULL, or the certification filter's verdicts
                                     (vb_quad_list.verdict) */
    } quads;
    int complete;
    uint64_t cover_cells, cover_patches, cover_host_cells; /* the cover's counters */
    uint64_t cover_neighbours;    /* neighbour records the cover built, all cells */
    uint64_t cover_max_cell_neighbours; /* the most that one cell built */
    uint64_t cover_handed_cells;  /* cells the GPU's group kernel handed to its work-item
                                     kernel (past the step budget) */
    uint64_t cover_resumed_patches; /* patches a CPU device's kernel handed to the host,
                                       which covered them alone (cover_resume.c) */
    uint64_t cover_quads;         /* quadruples proposed (in quads, or handed to the sink),
                                     a counter that processes which covered parts of the
                                     cells can add up */
    double t_cover_device;        /* seconds in the cover's device batches */
    double t_cover_prepare;       /* seconds of the cover's host work before it waits for
                                     the device (tree, certification filter) */
    vb_cover_clocks cover_clocks; /* the device's tiers in this run (vb_cover.h; 0 on
                                     host threads) */
    vb_cover_steps cover_steps;   /* where the host's side of a device cover went */
    double t_cert_filter;         /* seconds judging the quadruples (vb_cert_filter.h),
                                     summed over the parts */
    uint64_t device_bytes_peak;   /* the most bytes of device buffers the proposer's
                                     backend held at once (0 on host threads) */
} vb_proposal;

/* Zeroes r (an empty candidate list). */
void vb_proposal_init(vb_proposal *r);
/* Frees what r holds and zeroes it again. */
void vb_proposal_free(vb_proposal *r);

/* How a proposer obtains its device-side state when the driver opens the
 * device on a thread of its own: state() waits for the opening (or falls
 * back) and returns the state, or NULL with an error in the context;
 * ready() says whether state() would return at once. kind is the device
 * asked for (a hint for sizes chosen before the device is known); gpu is
 * nonzero where that is likely a GPU (kind gpu, or auto with one present),
 * a hint for host work done ahead of the device (it may open elsewhere). */
typedef struct vb_proposer_await {
    void *(*state)(void *user);
    int (*ready)(void *user);
    void *user;
    vb_device_kind kind;
    int gpu;
} vb_proposer_await;

/* A proposer of candidate vertices: candidates (ids, approximate point and
 * tangent radius) for the certifier, from which every vertex of the
 * diagram must be reachable by certification and the repair rounds. */
typedef struct vb_proposer {
    const char *name;  /* "sampling" */
    /* Opens the proposer on an opened device of `layer`, or its plain-C
     * twin when dev is NULL. Called on the opener thread for a device (it
     * may build programs). VB_OK, VB_ENOMEM, VB_EDEVICE. */
    int (*open)(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void **state);
    /* Proposes candidates for the validated set into res (candidates and
     * the counters it has); state is NULL when `await` must supply it.
     * VB_OK, VB_EMISUSE, VB_ENOMEM, VB_EDEVICE (the driver then reruns it on
     * the twin). */
    int (*run)(vb_ctx *ctx, void *state, const vb_proposer_await *await,
               const vb_sphere_set *set, const vb_propose_args *args, vb_proposal *res);
    const char *(*backend)(const void *state); /* "ref", "opencl" */
    const char *(*device)(const void *state);  /* human-readable device */
    void (*close)(void *state);
} vb_proposer;

/* The ray sampling of the seed paper (vb_sampler_run) as a proposer. */
extern const vb_proposer vb_proposer_sampling;

/* The direction cover (vb_cover_run): quadruples proven to hold every
 * vertex; the default. */
extern const vb_proposer vb_proposer_cover;

/* The proposers of the library, NULL-terminated; the first is the default. */
extern const vb_proposer *const vb_proposers[];

/* The proposer called `name` (NULL: the default), or NULL. */
const vb_proposer *vb_proposer_find(const char *name);

/* The ranges of the options, declared once for every caller (the commands'
 * parsers, the sampler): samples 0 (the default) or VB_SAMPLES_MIN..
 * VB_SAMPLES_MAX; tiles 0 (from samples) or a power of two up to
 * VB_TILES_MAX; threads 0 (VORBALL_THREADS or all CPUs) up to
 * VB_MAX_THREADS; tol > 0, or 0 for its default. Returns VB_OK, or
 * VB_EMISUSE with a message that names the option as the command spells
 * it (--samples, --tiles, --threads, --tol) and its range. */
#define VB_SAMPLES_MIN 2u
#define VB_SAMPLES_MAX 4096u
#define VB_TILES_MAX 64u
int vb_propose_options_check(vb_ctx *ctx, const vb_propose_options *o);

#ifdef __cplusplus
}
#endif
#endif
