/* The state of the cover's OpenCL backend (private to its files: gpu/cover_ocl.c,
 * cover_mem.c, cover_launch.c, cover_knobs.c, cover_plan.c):
 * its tiers of arena slices, their capacities and the step budget.
 *
 * Device memory (issue #30) stays within the device layer's budget
 * (vbg_runtime_memory_budget; VORBALL_DEVICE_MEMORY_MIB sets it), counted
 * by a meter (vbg_buffer.h, --stats device_bytes_peak), and follows the
 * input (gpu/cover_plan.c sizes it all; tests/gpu/test_cover_plan.c checks
 * the sizes on a made-up H100):
 *   input      32 n + 56 * 2 first + 4 m + 16 bytes (centres, radii, the
 *              tree's boxes and radii, its ids, the counters), held for the run;
 *   pool       one device buffer per arena array (records, labels, stack,
 *              quadruples, caches) that every tier passes to its kernel,
 *              one tier after the other: the tiers run one after the other
 *              on one queue and no launch reads what an earlier one left in
 *              its slices, so each array holds the largest tier's, not
 *              their sum (until stop 49 each tier had buffers of its own:
 *              on an H100 the 211,440-atom tiling held its first tier,
 *              1.1 GB, beside the large or huge one). No sub-buffers: cut
 *              from one buffer, overlapping ones crashed NVIDIA's OpenCL
 *              (stop 49, H100: capsid, fcc 10,976) and slowed the tiling
 *              2x;
 *   first tier S0 slices of P0 bytes, P0 = 48 NB + 4 LAB + 16 Q (+ 48 ST on
 *              the work-item kernel; the group kernel keeps one stack of
 *              48 ST), NB/LAB/ST/Q the tier's capacities below: 144 KiB a
 *              work-item on a GPU, 452 KiB a group (226 KiB with the
 *              arenas a sample fitted, COV_FIT_NB; 258 KiB on a small
 *              input, COV_FIT_SMALL); a CPU device's slice
 *              (one per compute unit, COV_CPU_NB) 4.0 MiB and 2.1 MiB of
 *              caches (8 LAB + 56 VBQ_MEMO), its capacities halved while
 *              the slices exceed the share below;
 *              S0 = min(the device's occupancy, n (the group kernel:
 *              n / COV_CELLS_PER_SLICE), 3/4 of the budget left after the
 *              input / P0);
 *   launches   per launch of C tasks: 4 C (cells) + 4 C (roots) + 48 C (results)
 *              + 16 qper C (quadruples, qper 24 on the first tier,
 *              COV_BIG_QPER on the large ones) + the handed patches' words
 *              (COV_HAND_WORDS a cell, at most COV_HAND_CAP in all, or what
 *              an earlier launch asked), at most 1/8 of the budget left
 *              after the input: a batch larger than that runs in several
 *              launches;
 *   large tier S1 slices of 2.0 MiB, made on the first cell that needs them,
 *              S1 = min(the device's occupancy, the tasks waiting / 64 on
 *              the group kernel (COV_BIG_TASKS), what the pool may hold /
 *              P1); with no room the cells go to the host threads;
 *   huge tier  S3 slices of 7.0 MiB for the large tier's tasks that ran out of
 *              its records (those tasks only, not their cells' others), made
 *              in the large tier's place, S3 = min(the device's compute
 *              units x 2, the tasks waiting, what the pool may hold / P3);
 *   the pool may hold what the budget leaves after the input and the
 *              launch room, but no more than the first tier or
 *              COV_POOL_PER_SPHERE bytes a sphere (COV_POOL_FLOOR at least),
 *              whichever is more.
 * A budget that cannot hold the input, one first-tier slice and one task's
 * launch stops the run at once with E142, saying how much is needed. */
#ifndef VBG_COVER_STATE_H
#define VBG_COVER_STATE_H

#include "vbg_buffer.h"
#include "vbg_cover.h"

/* Arena slices of one tier: `slices` of them (work-items, or work-groups). */
typedef struct cov_tier {
    vbg_buf nb, lab, st, q;  /* the pool's arrays while bound (not owned: s->arr owns them) */
    vbg_buf hi, memo, memo_tag; /* with caches: lab_cap doubles, VBQ_MEMO records and
                                   2 VBQ_MEMO tags per slice */
    cl_kernel k;             /* its kernel (cov_state's) */
    int caches;              /* 1: hi, memo, memo_tag made (the first tier of a CPU device) */
    int solo;                /* 1: a work-group of one work-item per slice (the first tier of
                                a CPU device: a slice per compute unit) */
    uint32_t nb_want, lab_want; /* solo: the capacities vbg_cov_split halves from */
    int wg;                  /* 1: k is the group kernel, a work-group of COV_WG per slice */
    uint32_t budget;         /* the group kernel's step budget per cell (0: none) */
    uint32_t qper;           /* output room per task, in quadruples */
    size_t slices;           /* slices made (0: none yet) */
    size_t want;             /* slices that keep the device busy (vbg_cover_open) */
    uint64_t pool_gen;       /* the pool its views were cut from (0: none) */
    size_t bound_slices;     /* slices and capacities of its views */
    uint32_t bound_nb, bound_lab;
    uint32_t nb_cap, lab_cap, st_cap, q_cap;
} cov_tier;

/* The tiers: first launch, large slices, and the hand-off tier (the
 * work-item kernel beside the group kernel: slices made on first use). */
#define COV_FIRST 0
#define COV_BIG 1
#define COV_HAND 2
#define COV_HUGE 3
#define COV_TIERS VB_COVER_TIERS
/* Arrays of a tier's slices (nb, lab, st, q and the three caches). */
#define COV_ARRAYS 7

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
    vbg_buf arr[COV_ARRAYS]; /* the pool: the tiers' arena arrays (vbg_cov_tier_bind) */
    uint64_t pool_gen;       /* counts the pool's changes (a tier's views name theirs) */
    size_t pool_room;        /* bytes the pool may hold this run (vbg_cov_split) */
    size_t pool_per_sphere;  /* COV_POOL_PER_SPHERE (0: the budget alone bounds the pool) */
    size_t cells_per_slice;  /* COV_CELLS_PER_SLICE: the group kernel's first tier */
    size_t hand_cap_words;   /* COV_HAND_CAP: handed-patch words a launch reserves at most */
    size_t hand_floor_words; /* COV_HAND_FLOOR: ... at least (0 where a knob sets the cell's) */
    int fit;                 /* 1: the first tier's arenas follow the input (vbg_cov_fit) */
    int fitted;              /* this run's first tier has the fitted arenas: COV_FITTED_SAMPLE
                                (its sample said so) or COV_FITTED_SMALL (a small input);
                                COV_FITTED_NONE (0): its defaults */
    size_t last_n;           /* spheres of the last run begun (trim) */
    unsigned task_split;     /* levels below the roots a cell's tasks split at (COV_TASK_SPLIT) */
    int task_order;          /* a tier's tasks costliest cell first: 1 up to VBG_ORDER_CELLS
                                cells, 2 always, 0 never (vbg_tasks_ordered) */
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
 * (2.6 MiB); its labels stayed (262,144; 131,072 since stop 54, COV_BIG_LAB). */
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
 * down to 2,048 / 8,192 (vbg_cov_split). 4yvs first 14,070 (2-core, PoCL one
 * thread): no cell left to the host (240 at 4,096 / 16,384, each covered
 * again after the device's work on it was lost), device buffers 12.6 MB
 * instead of 40.5; papers/gpu-voronoi-cells-of-spheres/results/
 * cpu_vs_voronota_stop46.md. */
#define COV_CPU_NB 65536u
#define COV_CPU_LAB 262144u
/* The group kernel's first tier: 8,192 records and 16,384 labels a slice
 * (452 KiB with its quadruples). Labels were 32,768 until stop 54 (520
 * KiB with 512 quadruples): host covers of every cell (tests/verify/bench_cover_cells, stop
 * 54; the group kernel's walk keeps the same labels) hold at most 8,164
 * labels on fcc 10,976 exact, 5,578 on its random twin, 3,166 on sc 4,096
 * jittered 1e-12, 2,414 on its random twin and 8,009 on EXTREMESET
 * Polysized 300, twice over within 16,384; the capsid's cells past it
 * (28,225 labels at most) are past its records too. The hand-off tier
 * keeps 32,768 (COV_HANDOFF_LAB). */
#define COV_WG_NB 8192u
#define COV_WG_LAB 16384u
#define COV_HANDOFF_LAB 32768u
#define COV_HANDOFF_Q 512u
/* Quadruples a first-tier slice holds (a cell's own, ids past its sphere,
 * sorted and unique: vbq_quad_insert, the host's and the kernels' code).
 * Host covers of every cell (stop 54): at most 88 a cell on fcc 10,976
 * exact (median 20), 62 on the capsid, 50 on sc 4,096 jittered 1e-12 and
 * on fcc 10,976 jittered 1e-9, 53 on EXTREMESET Polysized 300, 38 on 1crn;
 * 256 (4 KiB a slice; 512 until stop 54) is 2.9 times the largest, and
 * COV_FIT_Q where the arenas are fitted (the capsid's 62: twice over). A
 * cell past it runs on the large tier (COV_BIG_Q). */
#define COV_WG_Q 256u
#define COV_FIT_Q 128u
/* The large tier: 32,768 records, 131,072 labels and 512 quadruples a
 * slice (2.0 MiB; 262,144 labels and 4,096 quadruples, 2.6 MiB, until stop
 * 54). It borrows the first tier's arrays (the pool holds no more than the
 * first tier, or COV_POOL_PER_SPHERE a sphere), so its slices are those
 * arrays over its own: the capsid's fitted first tier (labels 66 MiB,
 * quadruples 4.1) holds 132 large slices of these, as it held 132 of the
 * old ones at stop 53 (labels 132 MiB); the old ones would have had 66.
 * Host covers of all 2,537,280 root-patch tasks of the capsid's cells
 * (bench_cover_cells capsid 2 1 32768 262144 4096, stop 54): at most 20,483
 * records and 28,225 labels a task; a task's quadruples are its cell's, at
 * most 88 a cell on every input measured. The huge tier keeps 262,144
 * labels (COV_HUGE_LAB: its tasks hold up to 131,072 records). */
#define COV_BIG_NB 32768u
#define COV_BIG_LAB 131072u
#define COV_HUGE_LAB 262144u
#define COV_BIG_Q 512u
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
 * (vbq_hand_patch; a patch is 12 words and its list's ids), an eighth of
 * it on a GPU (cov_state.hand_cell_words; a quarter until stop 49): a cell
 * that finds no room runs again with what the launch asked. Measured
 * (words asked a cell, all cells): EXTREMESET Congruent 300 ~900, fcc
 * 1,372 exact ~180, fcc 10,976 exact ~450, its jitter 1e-9 ~40; the
 * 211,440-atom tiling on an H100 about 73 (stop 49: capped at 8 Mi words
 * in all, 40 a cell, its launch came up short, its cells ran again and
 * its hand buffer grew to 74 MiB), so 128 a cell leaves it room twice
 * over at 108 MiB instead of 216. */
#define COV_HAND_WORDS 1024u
/* Words of handed patches a first launch gets at least, where its cells
 * at COV_HAND_WORDS each would take that many (8 Mi words, 32 MiB): a cell
 * that finds no room runs its whole cover again (rerun_hand_short), which
 * cost more than the room (stop 50, merged stop-49 head). On an H100: sc
 * 4,096 jittered 1e-12 asked ~150 words a cell, 128 left 2 reruns (0.036
 * s of kernel, bench 0.165-0.172 s), 512 or 2,048 none (0.130-0.132 s);
 * EXTREMESET Congruent 300 ~900 a cell, 2 reruns (0.059 s) beside a 0.043
 * s first launch. On an H200 with 4 Mi words: sc 0.162-0.167 -> 0.139-0.140
 * s, no rerun; fcc 10,976 exact (~450 a cell, 4.9 Mi in all) still reran
 * 676 cells (0.047 s of kernel), hence 8 Mi. From 65,536 cells the 128 a
 * cell pass it (the tiling's 108 MiB as before). A run whose sample fitted
 * the arenas (few large cells: the capsid, the tiling, whose cells asked
 * about 73 words each) has no floor (stop 54): the capsid's 26,430 cells
 * 12.9 MiB instead of 32. */
#define COV_HAND_FLOOR (8u << 20)
/* Words of handed patches a launch reserves at most before a launch asks
 * for more (VORBALL_COVER_HAND_CAP; by default none). */
#define COV_HAND_CAP SIZE_MAX
/* The group kernel's first tier: a slice per COV_CELLS_PER_SLICE spheres
 * at most (its groups take cells from a shared counter, one after the
 * other). 1crn (327 atoms) on an H100: 82 slices, 42 MB, where it held
 * one a sphere (170 MB) before stop 49; from 8,448 spheres on the
 * device's occupancy (2,112 slices) bounds it as before. */
#define COV_CELLS_PER_SLICE 4u
/* The pool (the tiers' arrays) holds no more than the first tier or this
 * many bytes a sphere (5.75 KiB), whichever is more: the large and huge
 * tiers of a large input take what this leaves (on an H100 the
 * 211,440-atom tiling's 1,187 MiB: 372 large slices of 528, 132 huge of
 * 264; its plan 1,398 MiB in all, the TOG 2025 peer's own 1,442), instead
 * of the budget's whole rest. COV_POOL_FLOOR: a small input's bound. */
#define COV_POOL_PER_SPHERE 5888u
#define COV_POOL_FLOOR ((size_t)32 << 20)
/* The group kernel's first-tier arenas per input (vbg_cov_fit): before the
 * first launch the host covers COV_FIT_SAMPLE cells spread over the input
 * in arenas of half COV_FIT_NB records and half COV_FIT_LAB labels
 * (vb_cover_sample_over: each cell cut where it runs out); when fewer than
 * one in COV_FIT_SHARE of them runs out, the first tier gets COV_FIT_NB /
 * COV_FIT_LAB (half the defaults), else the defaults. Only where the first
 * tier at its defaults would hold COV_FIT_MIN bytes or more (smaller inputs
 * keep their few slices). Host covers of every cell (tests/verify/
 * bench_cover_cells, stop 51), cells past 2,048 records / p99 / largest:
 * the capsid 552 (2 %) / 4,493 / 50,546 (117 past 8,192: its large tier
 * runs whichever), fcc 10,976 exact 2,188 (20 %, its face cells) / 6,648 /
 * 13,452, its random twin 91 / 1,935 / 6,412, sc 4,096 jittered 1e-12 61
 * / 2,192 / 4,790. The sample (128 cells, past 2,048): fcc 10,976 exact
 * 44, jittered 1e-9 6-7, sc 4,096 jittered 5-8, the capsid 2, the random
 * twins 0; 14-51 ms of CPU on one thread of the 2-core machine. On an
 * H100 (stop 50, run 2) the halved arenas held the capsid in 576 MiB
 * instead of 1,104 at the same speed (0.265 s) and cost fcc 10,976 exact
 * 0.222 s against 0.189-0.193 on the H200 (run 3), whose cells past 4,096
 * records then ran on the large tier. */
#define COV_FIT_SAMPLE 128u
/* Labels: 8,192 where the sample fitted the arenas (16,384 until stop 54;
 * the capsid's cells: p99 1,186, past 8,192 31 of 26,430, past 4,096
 * records 288, on the host), COV_FIT_SMALL_LAB for a small input. The
 * sample tests half of each (2,048 records, 4,096 labels). */
#define COV_FIT_NB 4096u
#define COV_FIT_LAB 8192u
#define COV_FIT_SMALL_LAB 16384u
#define COV_FIT_SHARE 8u
#define COV_FIT_MIN ((size_t)256 << 20)
/* ... and only from this many spheres on: below it `--device auto` covers on
 * the host's threads, and on the H100 (stop 51, run 2, fitted against
 * main) the sample and halved arenas cost sc 4,096 jittered 1e-12 0.171-
 * 0.175 s against 0.146-0.155 (539 -> 281 MiB), the random twins 5-7 %,
 * and fcc 10,976 exact, which keeps its defaults, 0.205-0.209 against
 * 0.193-0.196 (the sample alone); the capsid 1,119 -> 591 MiB in 0.236-
 * 0.250 s against 0.234-0.241. */
#define COV_FIT_SPHERES 20000u
/* Below this many spheres the first tier gets the fitted arenas without a
 * sample (COV_FITTED_SMALL): its slices are few (a slice per
 * COV_CELLS_PER_SLICE spheres, 255 at most, 130 MiB at the defaults), and a
 * sample of 128 of them would cost a few per cent of a run that takes 0.02-
 * 0.07 s on the H100. Host covers of every cell (tests/verify/
 * bench_cover_cells, stop 54): records per cell at most 3,147 (EXTREMESET
 * Congruent 300), 3,263 (Polysized 300) and 2,059 (1crn), labels 1,764,
 * 8,009 and 357: within 4,096 records and COV_FIT_SMALL_LAB labels. On the H100
 * (stop 50, h100_stop50.txt, VORBALL_COVER_NB=4096 VORBALL_COVER_LAB=16384)
 * the two 300-ball sets held 20.7 MiB instead of 39.2 / 38.5 in 0.062 /
 * 0.072 s against 0.060 / 0.076 s (TOG 2025 peer: 34 MiB). A cell past the
 * arenas goes on as a fitted run's does (COV_FIT_HOST). */
#define COV_FIT_SMALL 1024u
#define COV_FITTED_NONE 0
#define COV_FITTED_SAMPLE 1
#define COV_FITTED_SMALL 2
/* A fitted run's cells past its first tier, when no more than this many,
 * go to the host threads instead of a large tier of their own: a large
 * launch lasts as long as its longest task (0.026 s for fcc 10,976 exact's
 * 384 tasks on an H100, stop 50), a host thread covers such a cell (4,096
 * to 6,412 records in the random twin) in a few ms (2-core machine, host
 * cover of every cell: 0.3 ms a face cell on average). */
#define COV_FIT_HOST 32u
/* Output room per large or huge task, in quadruples (the tasks share one
 * output array: only the launch's sum matters; a task past it runs again
 * on the huge tier or the host). Measured on PoCL with the GPU's
 * first-tier arenas (VORBALL_COVER_NB=8192 _LAB=32768, stop 49): the
 * capsid's 11,232 large tasks found 2,881 quadruples (0.26 a task), fcc
 * 14^3 jittered 1e-9's 384 found 38. It was 256 until stop 49: the
 * 211,440-atom tiling's launches held 848 MiB of quadruple room on an
 * H100, 77 MiB now (its first tier's 24 a cell). */
#define COV_BIG_QPER 16u
/* A cell past the first tier runs again as tasks split this many levels
 * below its 6 T^2 root patches (vbg_cover_tasks.h): 1, one per child (24
 * T^2); VORBALL_COVER_TASK_SPLIT=2, one per grandchild (96 T^2), for
 * measurements on a GPU. A large launch lasts as long as its longest task:
 * host covers of the capsid's 288 cells past the fitted arenas (4,096
 * records, 16,384 labels) in large arenas, their tasks in cell order on
 * 210 slices (stop 52, papers/gpu-voronoi-cells-of-spheres/results/
 * kern52_stop52.md): split 1, 27,648 tasks, 266,820 patches, the longest
 * 1,906, 2,838 patches on the slowest slice; split 2, 110,592 tasks,
 * 411,540 patches (each repeats its root and child), the longest 895, 2,360
 * on the slowest slice, and four times the tasks' neighbour gathers. The
 * large tier's slices (COV_BIG_TASKS) and output room a task
 * (COV_BIG_QPER) count per 24 T^2 of a cell's tasks, so a cell gets the
 * slices and room either way. */
#define COV_TASK_SPLIT 1u

/* Applies the environment's test and measurement knobs to s's tiers
 * (gpu/cover_knobs.c: VORBALL_COVER_NB, _LAB, _FIT, _TIER2, _TIER3, _BIG_NB, _HAND_WORDS,
 * _HUGE_NB, _CELLS_PER_SLICE, _POOL_PER_SPHERE, _HAND_CAP, _TASK_SPLIT, _TASK_ORDER,
 * _BIG_QPER), after
 * vbg_cover_open set their defaults. */
void vbg_cover_knobs(cov_state *s);

/* ---- sizes (gpu/cover_plan.c: no OpenCL call) ----------------------------- */

/* Sets s's tiers' capacities, kernels' kinds and wanted slices for a device
 * of `units` compute units (cpu: a CPU device), with s->wg chosen: the
 * first tier's caches (caches) and handed patches (hand) as built. */
void vbg_cov_caps(cov_state *s, int cpu, int caches, int hand, size_t units);

/* Bytes of each of tier t's COV_ARRAYS arrays for w slices (0: not made;
 * the first four take 16 at least). */
void vbg_cov_tier_arrays(const cov_tier *t, size_t w, size_t bytes[COV_ARRAYS]);

/* Bytes the pool's arrays take once grown for w slices of tier t (each
 * array the larger of what s holds and what t needs). */
size_t vbg_cov_pool_need(const cov_state *s, const cov_tier *t, size_t w);

/* Bytes of the input of n spheres and a tree of `first` leaves and m ids. */
size_t vbg_cov_input_bytes(size_t n, size_t first, size_t m);

/* Bytes of one task of a launch on tier t: its cell, root and result, and
 * its room for quadruples. */
size_t vbg_cov_task_bytes(const cov_tier *t);

/* Splits s->budget for a run of n spheres whose input takes `input`
 * bytes: the first tier's slices (and a solo tier's capacities), the
 * launch room and the pool's room. 0, or the bytes the run needs at least
 * when the budget cannot hold them. */
size_t vbg_cov_split(cov_state *s, size_t n, size_t input);

/* Tasks of a cell split at s->task_split levels per task of the split
 * at one level (24 T^2 a cell): 1 or 4. */
size_t vbg_cov_task_share(const cov_state *s);

/* Sets the large and huge tiers' output room a task from qper quadruples
 * per 24 T^2 of a cell's tasks (vbg_cov_task_share; 1 at least). */
void vbg_cov_big_qper(cov_state *s, uint32_t qper);

/* Slices of tier t (the large, huge or hand-off tier) for `tasks` tasks:
 * at most its wanted slices and what the pool's room holds, in whole
 * groups of 64 on the work-item kernel; the group kernel's large tier one
 * per COV_BIG_TASKS tasks. 0: none fits. */
size_t vbg_cov_tier_slices(const cov_state *s, const cov_tier *t, size_t tasks);

/* Bytes the launch buffers hold for a launch of ncells tasks, but the
 * quadruples' (s's buffers or the launch's needs, whichever is more). */
size_t vbg_cov_launch_held(const cov_state *s, size_t ncells);

/* A launch of tier t over ncells tasks: its room for quadruples (*qroom)
 * and handed-patch words (*hwords, 0 but on the first tier; no
 * COV_HAND_FLOOR where the sample fitted the arenas) within the launch
 * room. Grows s->qout_cap to qper a task. */
void vbg_cov_launch_sizes(cov_state *s, const cov_tier *t, size_t ncells, size_t *qroom,
                          size_t *hwords);

/* The device bytes a run of n spheres (input bytes `input`) holds at its
 * peak by the sizes above: its first batch of `batch` cells, then
 * big_tasks tasks on the large tier and huge_tasks on the huge one.
 * Uses s's budget, capacities and buffer sizes (a state of sizes alone:
 * its buffers' mem may be NULL; their sizes are changed). 0: the budget
 * cannot hold the run. */
size_t vbg_cov_peak_plan(cov_state *s, size_t n, size_t input, size_t batch, size_t big_tasks,
                         size_t huge_tasks);

/* 1 when a run of n spheres samples its cells for the first tier's
 * arenas: s->fit is set, n >= COV_FIT_SPHERES and the first tier at its default arenas would
 * hold COV_FIT_MIN bytes or more (its slices as vbg_cov_split makes them
 * with no budget to bound them). */
int vbg_cov_fit_wanted(const cov_state *s, size_t n);

/* The first tier's arenas for a run of n spheres from a sample
 * (vb_cover_sample_over at half COV_FIT_NB / COV_FIT_LAB; covered 0: none
 * taken): `over` of `covered` cells ran out of them. Sets the first tier's
 * nb_cap / lab_cap / q_cap to COV_FIT_NB / COV_FIT_LAB / COV_FIT_Q and
 * s->fitted to COV_FITTED_SAMPLE when over * COV_FIT_SHARE < covered, else
 * (labels COV_FIT_SMALL_LAB) to COV_FITTED_SMALL when n < COV_FIT_SMALL;
 * otherwise to nb_want / lab_want / COV_WG_Q (the defaults, or what a knob
 * set) and s->fitted to COV_FITTED_NONE.
 * A run fitted by its sample gets no handed-patch floor
 * (vbg_cov_launch_sizes). */
void vbg_cov_fit(cov_state *s, size_t n, size_t covered, size_t over);

/* ---- device buffers (gpu/cover_mem.c) ---------------------------------- */

/* Releases b's device memory (the meter counts it). */
void vbg_cov_release(cov_state *s, vbg_buf *b);

/* Makes b hold at least `need` bytes (its contents are lost when it
 * grows). VB_OK, or VB_EDEVICE / the meter's status. */
int vbg_cov_ensure(vb_ctx *ctx, cov_state *s, vbg_buf *b, size_t need, cl_mem_flags flags);

/* Copies bytes of src into b (grown when too small). */
int vbg_cov_upload(vb_ctx *ctx, cov_state *s, vbg_buf *b, const void *src, size_t bytes);

/* Drops tier t's hold on the pool's arrays (t->slices is left to the caller). */
void vbg_cov_tier_release(cov_state *s, cov_tier *t);

/* Tier t (the large, huge or hand-off tier) with slices for `tasks` tasks,
 * made on first use in the pool. VB_OK with no slices when none fits: the
 * cells then go to the host. */
int vbg_cov_tier_grow(vb_ctx *ctx, cov_state *s, cov_tier *t, size_t tasks);

/* Gives tier t the pool's arrays for its t->slices slices (each grown
 * when too small, which drops every tier's hold on them), unless it holds
 * them already. VB_OK or VB_EDEVICE / the meter's status. */
int vbg_cov_tier_bind(vb_ctx *ctx, cov_state *s, cov_tier *t);

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
