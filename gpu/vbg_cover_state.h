/* The state of the cover's OpenCL backend (private to its files: gpu/cover_ocl.c,
 * cover_mem.c, cover_launch.c, cover_knobs.c):
 * its tiers of arena slices, their capacities and the step budget.
 *
 * Device memory (issue #30) stays within the device layer's budget
 * (vbg_runtime_memory_budget; VORBALL_DEVICE_MEMORY_MIB sets it), counted
 * by a meter (vbg_buffer.h, --stats device_bytes_peak):
 *   input      32 n + 56 * 2 first + 4 m + 8 bytes (centres, radii, the
 *              tree's boxes and radii, its ids, the counters), held for the run;
 *   first tier S0 slices of P0 bytes, P0 = 48 NB + 4 LAB + 16 Q (+ 48 ST on
 *              the work-item kernel; the group kernel keeps one stack of
 *              48 ST), NB/LAB/ST/Q the tier's capacities below: 144 KiB a
 *              work-item on a GPU, 520 KiB a group; a CPU device's slice
 *              (one per compute unit, COV_CPU_NB) 4.0 MiB and 2.1 MiB of
 *              caches (8 LAB + 56 VBQ_MEMO), its capacities halved while
 *              the slices exceed the share below;
 *              S0 = min(the device's occupancy,
 *              n, 3/4 of the budget left after the input / P0);
 *   launches   per launch of C tasks: 4 C (cells) + 4 C (roots) + 48 C (results)
 *              + 16 qper C (quadruples, qper 24 on the first tier, 256 on the
 *              large one), at most 1/8 of the budget left after the input:
 *              a batch larger than that runs in several launches;
 *   large tier S1 slices of 2.6 MiB, made on the first cell that needs them,
 *              S1 = min(the device's occupancy, the tasks waiting / 64 on
 *              the group kernel (COV_BIG_TASKS), the rest of the budget /
 *              P1) (half of it with the hand-off tier beside);
 *              with no room the cells go to the host threads;
 *   huge tier  S3 slices of 7.1 MiB for the large tier's tasks that ran out of
 *              its records (those tasks only, not their cells' others), made
 *              in the large tier's place (released first,
 *              and released after the batch), S3 = min(the device's compute
 *              units x 2, the tasks waiting, the rest of the budget / P3).
 * A budget that cannot hold the input, one first-tier slice and one task's
 * launch stops the run at once with E142, saying how much is needed. */
#ifndef VBG_COVER_STATE_H
#define VBG_COVER_STATE_H

#include "vbg_buffer.h"
#include "vbg_cover.h"

/* A cell whose quadruples did not fit the output array (cover*.cl). */
#define COV_OVER_OUT 5u

/* Arena slices of one tier: `slices` of them (work-items, or work-groups). */
typedef struct cov_tier {
    vbg_buf nb, lab, st, q;
    vbg_buf hi, memo, memo_tag; /* with caches: lab_cap doubles, VBQ_MEMO records and
                                   2 VBQ_MEMO tags per slice */
    cl_kernel k;             /* its kernel (cov_state's) */
    int caches;              /* 1: hi, memo, memo_tag made (the first tier of a CPU device) */
    int solo;                /* 1: a work-group of one work-item per slice (the first tier of
                                a CPU device: a slice per compute unit) */
    uint32_t nb_want, lab_want; /* solo: the capacities budget_split halves from */
    int wg;                  /* 1: k is the group kernel, a work-group of COV_WG per slice */
    uint32_t budget;         /* the group kernel's step budget per cell (0: none) */
    uint32_t qper;           /* output room per task, in quadruples */
    size_t slices;           /* slices made (0: none yet) */
    size_t want;             /* slices that keep the device busy (vbg_cover_open) */
    uint32_t nb_cap, lab_cap, st_cap, q_cap;
} cov_tier;

/* The tiers: first launch, large slices, and the hand-off tier (the
 * work-item kernel beside the group kernel: slices made on first use). */
#define COV_FIRST 0
#define COV_BIG 1
#define COV_HAND 2
#define COV_HUGE 3
#define COV_TIERS VB_COVER_TIERS

typedef struct cov_state {
    vbg_runtime *rt;
    cl_kernel k, k_item;     /* k_item: the work-item kernel beside the group kernel */
    int wg;                  /* 1: one work-group of 32 per cell (cover_wg.cl) */
    int k_caches;            /* 1: k built with VBQ_CACHES_CL (three more arguments; a tier
                                without caches passes NULL buffers) */
    int k_hand;              /* 1: k built with VBQ_HANDOFF (VBQ_WALK_V4_CL on a CPU device,
                                -DVBQ_HANDOFF for the group kernel; two more arguments,
                                last: the handed patches, NULL but on the first tier, and
                                their room) */
    uint32_t hand_cell_words; /* words of handed patches a cell gets at least (COV_HAND_WORDS) */
    vbg_buf hand;            /* the first tier's handed patches (vbq_hand_patch) */
    size_t hand_want;        /* words it holds at least (what an earlier launch needed) */
    int hand_short;          /* 1: a launch since it was last cleared asked for more words */
    int rerun;               /* 1: the first tier runs again for such cells (its launches
                                count in the clocks' VB_COVER_RERUN step) */
    uint32_t *host_hand;     /* read-back of a batch's handed patches, of cells that finished
                                (each entry's frame off: the cell's sphere) */
    size_t host_hand_cap, host_hand_n;
    vbg_buf x, y, z, r, box, rmax, ids;
    vbg_buf cells, roots, outs, qout, counters;
    cov_tier tier[COV_TIERS];
    size_t qout_cap;         /* quadruples the output array holds */
    uint32_t *host_q;        /* read-back of the quadruples of a batch */
    size_t host_q_cap, host_nq;
    vbq_cell_out *outs2;     /* results of the second tier, a task per root patch */
    uint32_t *cells2, *roots2, *hroots;
    size_t cap2, hroots_cap;
    vbq_env env;             /* scalars of the uploaded input */
    vbg_meter meter;         /* device bytes held now and at most */
    size_t budget;           /* device bytes the cover may hold (vbg_runtime_memory_budget) */
    size_t launch_room;      /* bytes of one launch's task, result and quadruple buffers */
    size_t tier_room;        /* bytes left for the large tier (and the hand-off tier) */
    size_t last_n;           /* spheres of the last run begun (trim) */
    vb_cover_clocks *clocks; /* the backend's, per tier (indexed by COV_*) */
} cov_state;

/* Arena capacities. The first tier fits almost every cell of the proteins
 * and the capsid measured; the second takes the exposed cells whose ring
 * fetches hold thousands of spheres, as root-patch tasks, each of which
 * fetches only its patch's. Measured on the host (tests/verify/
 * bench_cover_cells, every cell's 96 tasks): neighbour records per cell on
 * the 26,430-atom capsid median 96, p99 4,493, max 50,546 (117 cells past
 * 8,192), per task at most 20,483 (all 2,537,280 tasks fit 32,768; 2 ran
 * out of 16,384); 3pqr per cell max 12,396, per task 2,303. The large
 * tier's 131,072 records (7.1 MiB a slice with its labels) became 32,768
 * (2.6 MiB); its labels stay (the group kernel walks breadth-first). */
#define COV_NB 2048u
#define COV_LAB 8192u
#define COV_ST 256u
#define COV_Q 256u
/* A CPU device's work-items (PoCL): it has no large tier, so a cell past
 * the first tier's arenas is covered again on the host after the device's
 * work on it is lost. fcc 10,976 jittered (stop 43, 2-core, PoCL CPU s,
 * ref 5.3-5.5): 2,048 / 8,192 records / labels left 2,114 of its 10,976
 * cells (its face cells, 1,849 out of records) to the host, 8.45 s;
 * 4,096 / 16,384: 191 cells, 7.00 s; 8,192 / 32,768: 42 cells, 6.68 s at
 * twice the memory (a slice 528 KiB against 272 KiB). */
/* Stop 46: a CPU device runs its work-items one after the other, each to
 * the end of the batch (the kernel's loop over a shared counter), so only
 * the first work-item of each work-group ever covers a cell: the first
 * tier of a CPU device is a slice per compute unit, a work-group of one
 * (cov_tier.solo), and a slice gets the records and labels the 64 slices of
 * a group held before, times 16 and 16: 65,536 / 262,144 (6.1 MiB with its
 * caches), halved while the slices do not fit their share of the budget,
 * down to 2,048 / 8,192 (budget_split). 4yvs first 14,070 (2-core, PoCL one
 * thread): no cell left to the host (240 at 4,096 / 16,384, each covered
 * again after the device's work on it was lost), device buffers 12.6 MB
 * instead of 40.5; papers/gpu-voronoi-cells-of-spheres/results/
 * cpu_vs_voronota_stop46.md. */
#define COV_CPU_NB 65536u
#define COV_CPU_LAB 262144u
#define COV_WG_NB 8192u
#define COV_WG_LAB 32768u
#define COV_WG_Q 512u
#define COV_BIG_NB 32768u
#define COV_BIG_LAB 262144u
#define COV_BIG_Q 4096u
/* Tasks per large slice at least: below that the large tier's kernel time
 * is its longest task's. On an H100 (stop 44, run B) the capsid's 11,040
 * tasks took 0.078 / 0.082 / 0.083 s of large-tier kernel on 528 / 264 /
 * 132 slices (2.6 MiB each: its device buffers 2,477 / 1,800 MiB at 528 /
 * 264), while the 211,440-atom tiling's 217,056 tasks took 0.296 / 0.465 /
 * 0.783 s. With 64 the capsid takes 170 slices (run C: 0.081 s of
 * large-tier kernel, cover and certification 0.259-0.276 s against run B's
 * 0.255 s, device buffers 1,559 MiB, nvidia-smi's peak 2,086 MiB) and the
 * tiling keeps its 528 (4x the compute units). */
#define COV_BIG_TASKS 64u
/* The huge tier: the large tier's tasks that ran out of its records, again
 * with four times as many (the large tier's capacity before stop 42: 7.1 MiB
 * a slice with its labels). On an H100 (stop 43, the 211,440-atom tiling)
 * the 32,768-record large tier left 1,834 cells to the host threads and
 * 131,072 records 1,458: cover and certification 2.41 s against 1.77 s
 * (run B); with the huge tier 1.76 s, 1.87 s without it (run C), while the
 * capsid, whose tasks all fit 32,768, keeps 2.5 GB of buffers. */
#define COV_HUGE_NB 131072u
#define COV_WG 32u
/* The group kernel's step budget per cell (VORBALL_COVER_BUDGET overrides;
 * 0: none). A group walks a cell's patches one after the other, so a launch
 * lasts as long as its longest cell: on an H100 about 45 us a step (fcc
 * 10,976 jittered: 4.71 s for its longest cell's 106,804 patches; the random
 * twin: 0.07 s for 1,508). Patches per cell on the host's cover
 * (tests/verify/bench_cover_cells): the random twin's largest is 1,508,
 * 3pqr's 99th percentile 1,264 (13 of its cells pass 2,048), the jittered
 * crystal's 99th 1,112 but 60 cells past 2,048 hold 19 % of its patches.
 * 2,048 hands off none of the twin's cells and caps the group launch near
 * 0.1 s; the cells past it run side by side as 24 T^2 tasks each. */
#define COV_BUDGET 2048u
/* Words of handed patches a cell gets in a CPU device's first launch
 * (vbq_hand_patch; a patch is 12 words and its list's ids), a quarter of
 * it on a GPU (cov_state.hand_cell_words): a cell that finds no room runs
 * again with what the launch asked. Measured (words asked a cell, all
 * cells): EXTREMESET Congruent 300 ~900, fcc 1,372 exact ~180, fcc 10,976
 * exact ~450, its jitter 1e-9 ~40. */
#define COV_HAND_WORDS 1024u

/* Applies the environment's test and measurement knobs to s's tiers
 * (gpu/cover_knobs.c: VORBALL_COVER_NB, _LAB, _TIER2, _TIER3, _BIG_NB, _HAND_WORDS,
 * _HUGE_NB), after vbg_cover_open set their defaults. */
void vbg_cover_knobs(cov_state *s);

/* ---- device buffers (gpu/cover_mem.c) ---------------------------------- */

/* Releases b's device memory (the meter counts it). */
void vbg_cov_release(cov_state *s, vbg_buf *b);

/* Makes b hold at least `need` bytes (its contents are lost when it
 * grows). VB_OK, or VB_EDEVICE / the meter's status. */
int vbg_cov_ensure(vb_ctx *ctx, cov_state *s, vbg_buf *b, size_t need, cl_mem_flags flags);

/* Copies bytes of src into b (grown when too small). */
int vbg_cov_upload(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes);

/* Bytes of one task of a launch on tier t: its cell, root and result, and
 * its room for quadruples. */
size_t vbg_cov_task_bytes(const cov_tier *t);

/* Releases tier t's arena slices (t->slices is left to the caller). */
void vbg_cov_tier_release(cov_state *s, cov_tier *t);

/* Tier t (the large or the hand-off tier) with slices for `tasks` tasks,
 * made on first use within its share of the budget. VB_OK with no slices
 * when none fits: the cells then go to the host. */
int vbg_cov_tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks);

/* The backend's begin (vb_cover_backend): splits the budget, uploads the
 * input env of n spheres and makes the first tier's slices. VB_OK, E142
 * (VB_ENOMEM_DEVICE) when the budget cannot hold one slice, VB_EDEVICE. */
int vbg_cov_begin(vb_ctx *ctx, vb_cover_backend *be, const vbq_env *env, size_t n);

/* ---- launches (gpu/cover_launch.c) --------------------------------------- */

/* Appends room for n more quadruples to s->host_q. VB_OK or VB_ENOMEM. */
int vbg_cov_host_q_room(vb_ctx *ctx, cov_state *s, size_t n);

/* Tier t over the tasks (cells[k], roots[k]) for k < ncells, in as many
 * launches as the launch room needs: out[k] and the quadruples appended to
 * s->host_q (out[k].qoff relative to it). VB_OK, or VB_EDEVICE with
 * nothing half-done. */
int vbg_cov_run_tier(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                     const uint32_t *roots, size_t ncells, vbq_cell_out *out);

#endif
