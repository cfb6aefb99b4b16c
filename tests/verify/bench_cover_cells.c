/* bench_cover_cells: where the direction cover spends its time, by cell.
 *
 *   bench_cover_cells INPUT [MARGIN [BUDGET NB LAB Q]]
 *
 * Covers every cell of INPUT on one thread (vb_cover_cell_host, the
 * host's cover in the build vorball runs: AVX2 where the CPU has it; this
 * file's own vbq_cover_cell, built plain, measured 2.8 times slower on a
 * crystal's face cells, stop 47) and sums, for the cells whose centre
 * lies within MARGIN (default 2) of the bounding box of the centres
 * ("boundary") and for the others
 * ("interior"): thread CPU seconds, patches, label evaluations, neighbour
 * records, leaves at the deepest level and quadruples. A crystal's flat
 * faces make its boundary cells the expensive ones (papers/degenerate-input/
 * README.md). A last line gives the spread of patches per cell (median,
 * 99th and 99.9th percentiles, largest, cells over 1024/2048/4096 and their
 * share of all patches): the GPU group kernel's step budget
 * (gpu/cover_ocl.c) is set from it. With BUDGET, the GPU's hand-off
 * simulated: each cell of more than BUDGET patches is covered again as its
 * 24 T^2 root-patch tasks in arenas of NB records, LAB labels and Q
 * quadruples without the host's scratch (as the work-item kernel does),
 * and a line gives the cells handed, the tasks, the largest task's patches
 * (the longest work-item of the hand-off launch) and the tasks that ran out
 * of each arena (tie clusters are decided on the host here, where a device
 * leaves them to the host). A first line gives the sample a GPU sizes its
 * first tier's arenas from (vb_cover_sample_over) and its CPU time. A
 * benchmark, not a test. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb_cover.h"
#include "vb_spheres.h"
#include "vt_bench.h"

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

typedef struct sums {
    double cells, cpu, patches, evals, nb, deep, quads;
} sums;

/* The hand-off simulated (BUDGET NB LAB Q). */
typedef struct handoff {
    uint32_t budget;
    vbq_arena ar;              /* the work-item's arenas, no scratch */
    size_t cells, tasks, failed_cells, status[8];
    uint32_t largest_cell, largest_task;
    uint32_t task_nnb, task_lab; /* the largest task's records: neighbours, labels */
} handoff;

static void handoff_cell(const vbq_env *env, handoff *h, uint32_t i, uint32_t patches)
{
    h->cells++;
    h->largest_cell = patches > h->largest_cell ? patches : h->largest_cell;
    int bad = 0;
    for (uint32_t r = 0; r < 24u * env->T * env->T; r++) {
        vbq_cell_out t;
        vbq_cover_cell(env, &h->ar, i, VBQ_TASK(r / 4u, r % 4u + 1u), &t);
        h->tasks++;
        h->status[t.status & 7u]++;
        bad |= t.status != VBQ_OK;
        h->largest_task = t.patches > h->largest_task ? t.patches : h->largest_task;
        if (t.status == VBQ_OK) {
            h->task_nnb = t.nnb > h->task_nnb ? t.nnb : h->task_nnb;
            h->task_lab = t.lab_hw > h->task_lab ? t.lab_hw : h->task_lab;
        }
    }
    h->failed_cells += (size_t)bad;
}

/* Prints the spread of one per-cell record count (sorts v): median,
 * 99th and 99.9th percentiles, largest, cells over 2048 and over 8192 (the
 * GPU arenas' sizes, gpu/cover_ocl.c). */
static void spread(const char *input, const char *what, uint32_t *v, uint32_t n)
{
    if (!n)
        return;
    qsort(v, n, sizeof *v, cmp_u32);
    uint32_t o2 = 0, o8 = 0;
    for (uint32_t k = 0; k < n; k++) {
        o2 += v[k] > 2048u;
        o8 += v[k] > 8192u;
    }
    printf("%s\t%s per cell\tmedian %u\tp99 %u\tp99.9 %u\tmax %u\tover 2048/8192 %u/%u cells\n",
           input, what, v[n / 2], v[(size_t)n * 99 / 100], v[(size_t)n * 999 / 1000], v[n - 1], o2,
           o8);
}

/* The group kernel's step budget a cell (gpu/vbg_cover_state.h, COV_BUDGET). */
#define FIRST_BUDGET 2048u

/* The first tier's launch time in steps for S slices: each slice takes the
 * next cell in the tree's order when it is free (the kernel's shared
 * counter), each cell takes its patches' steps up to the budget; the last
 * slice to finish ends the launch. An upper bound on what fewer slices
 * cost where a step takes as long whatever the slices (on a GPU it takes
 * less with fewer of them in flight). steps: by sphere (0: none). */
static void first_makespan(const char *input, const vbq_env *env, const uint32_t *steps)
{
    /* the H100's 16 a compute unit and fewer; one a sphere and one per 2,
     * 4 (COV_CELLS_PER_SLICE) and 8 spheres */
    size_t m = env->m, slices[] = {2112, 1584, 1056, 528, 264, 132, m, m / 2, m / 4, m / 8};
    printf("%s\tfirst-tier launch in steps (slices: steps)", input);
    for (size_t k = 0; k < sizeof slices / sizeof *slices; k++) {
        size_t S = slices[k] ? slices[k] : 1;
        uint64_t *free_at = calloc(S, sizeof *free_at), end = 0;
        if (!free_at)
            return;
        for (size_t j = 0; j < env->m; j++) {
            size_t best = 0;
            for (size_t s = 1; s < S; s++)
                best = free_at[s] < free_at[best] ? s : best;
            free_at[best] += steps[env->ids[j]];
            end = free_at[best] > end ? free_at[best] : end;
        }
        printf("\t%zu: %llu", S, (unsigned long long)end);
        free(free_at);
    }
    printf("\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_cover_cells INPUT [MARGIN [BUDGET NB LAB Q]]\n");
        return 2;
    }
    double margin = argc > 2 ? strtod(argv[2], NULL) : 2.0;
    vb_ctx *ctx;
    vb_sphere_set *set;
    if (vt_bench_open("bench_cover_cells", argv[1], &ctx, &set))
        return 1;
    vb_cover_tree *tree = NULL;
    vbq_env env;
    vb_cover_options o;
    memset(&o, 0, sizeof o);
    o.threads = 1;
    if (vb_cover_prepare(ctx, set, &o, &tree, &env) != VB_OK) {
        fprintf(stderr, "bench_cover_cells: %s\n", vb_errmsg(ctx));
        return 1;
    }
    double lo[3] = {set->x[0], set->y[0], set->z[0]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (size_t i = 0; i < set->n; i++) {
        double c[3] = {set->x[i], set->y[i], set->z[i]};
        for (int k = 0; k < 3; k++) {
            lo[k] = c[k] < lo[k] ? c[k] : lo[k];
            hi[k] = c[k] > hi[k] ? c[k] : hi[k];
        }
    }
    /* The sample a GPU sizes its first tier from (gpu/vbg_cover_state.h,
     * COV_FIT_*: 128 cells in arenas of 2,048 records and 4,096 labels
     * since stop 54), with its CPU seconds on one thread. */
    size_t sampled, ran_out;
    double f0 = thread_cpu();
    if (vb_cover_sample_over(&env, 128, 2048u, 4096u, 1, &sampled, &ran_out) != VB_OK)
        return 1;
    printf("%s\tsample\t%zu cells in 2048 records / 4096 labels: %zu ran out\tcpu_s %.4f\n",
           argv[1], sampled, ran_out, thread_cpu() - f0);
    vbq_arena ar;
    memset(&ar, 0, sizeof ar);
    uint32_t cap[4] = {1024u, 8192u, 512u, 512u};
    if (vbq_arena_make(&ar, cap[0], cap[1], cap[2], cap[3]) != VB_OK)
        return 1;
    handoff h;
    memset(&h, 0, sizeof h);
    double *scratch = NULL;
    if (argc > 6) {
        h.budget = (uint32_t)strtoul(argv[3], NULL, 10);
        if (vbq_arena_make(&h.ar, (uint32_t)strtoul(argv[4], NULL, 10),
                           (uint32_t)strtoul(argv[5], NULL, 10), 256u,
                           (uint32_t)strtoul(argv[6], NULL, 10)) != VB_OK)
            return 1;
        scratch = h.ar.hi;
        h.ar.hi = NULL; /* a device keeps no upper ends per label */
    }
    sums s[2];
    memset(s, 0, sizeof s);
    uint32_t *per = calloc(set->n ? set->n : 1, sizeof *per), np = 0;
    uint32_t *nnb = calloc(set->n ? set->n : 1, sizeof *nnb);
    uint32_t *lab = calloc(set->n ? set->n : 1, sizeof *lab);
    uint32_t *nq = calloc(set->n ? set->n : 1, sizeof *nq);
    uint32_t *steps = calloc(set->n ? set->n : 1, sizeof *steps); /* by sphere */
    if (!per || !nnb || !lab || !nq || !steps)
        return 1;
    for (uint32_t i = 0; i < set->n; i++) {
        if (set->contained[i])
            continue;
        double c[3] = {set->x[i], set->y[i], set->z[i]};
        int b = 0;
        for (int k = 0; k < 3; k++)
            b |= c[k] - lo[k] < margin || hi[k] - c[k] < margin;
        vbq_cell_out out;
        double t0 = thread_cpu();
        for (;;) {
            vb_cover_cell_host(&env, &ar, i, VBQ_ALL_ROOTS, &out);
            if (out.status == VBQ_OK)
                break;
            int g = out.status == VBQ_OVER_NB ? 0 : out.status == VBQ_OVER_LAB ? 1
                    : out.status == VBQ_OVER_ST ? 2 : 3;
            cap[g] *= 2u;
            if (cap[g] >= (1u << 30) || vbq_arena_make(&ar, cap[0], cap[1], cap[2], cap[3]) != VB_OK)
                return 1;
        }
        s[b].cpu += thread_cpu() - t0;
        s[b].cells++;
        s[b].patches += out.patches;
        nnb[np] = out.nnb;
        lab[np] = out.lab_hw;
        nq[np] = out.nq;
        steps[i] = out.patches < FIRST_BUDGET ? out.patches : FIRST_BUDGET;
        per[np++] = out.patches;
        s[b].evals += 1000.0 * out.evals_k;
        s[b].nb += out.nnb;
        s[b].deep += out.deep;
        s[b].quads += out.nq;
        if (h.budget && out.patches > h.budget)
            handoff_cell(&env, &h, i, out.patches);
    }
    for (int b = 0; b < 2; b++)
        printf("%s\t%s\tcells %.0f\tcpu_s %.3f\tpatches %.0f\tevals %.0f\tneighbours %.0f\t"
               "deep_leaves %.0f\tquadruples %.0f\n",
               argv[1], b ? "boundary" : "interior", s[b].cells, s[b].cpu, s[b].patches,
               s[b].evals, s[b].nb, s[b].deep, s[b].quads);
    qsort(per, np, sizeof *per, cmp_u32);
    double over[3] = {0, 0, 0}, over_p[3] = {0, 0, 0}, all = 0;
    for (uint32_t k = 0; k < np; k++) {
        all += per[k];
        for (int g = 0; g < 3; g++)
            if (per[k] > (1024u << g)) {
                over[g]++;
                over_p[g] += per[k];
            }
    }
    if (np)
        printf("%s\tpatches per cell\tmedian %u\tp99 %u\tp99.9 %u\tmax %u\t"
               "over 1024/2048/4096 %.0f/%.0f/%.0f cells, %.1f/%.1f/%.1f %% of patches\n",
               argv[1], per[np / 2], per[np * 99 / 100], per[(size_t)np * 999 / 1000], per[np - 1],
               over[0], over[1], over[2], 100 * over_p[0] / all, 100 * over_p[1] / all,
               100 * over_p[2] / all);
    /* The records a cell holds (neighbours, label high-water mark): what
     * the device's arena slices are sized from. */
    spread(argv[1], "neighbour records", nnb, np);
    spread(argv[1], "labels (high water)", lab, np);
    spread(argv[1], "quadruples", nq, np); /* the slices' quadruple room (COV_WG_Q) */
    first_makespan(argv[1], &env, steps);
    if (h.budget) {
        printf("%s\thand-off\tlargest task: %u neighbour records, %u labels\n", argv[1],
               h.task_nnb, h.task_lab);
        printf("%s\thand-off\tbudget %u\tarenas %s/%s/%s\thanded %zu cells (largest %u patches)\t"
               "%zu tasks, largest %u patches\tran out: nb %zu, lab %zu, st %zu, q %zu (%zu cells)\n",
               argv[1], h.budget, argv[4], argv[5], argv[6], h.cells, h.largest_cell, h.tasks,
               h.largest_task, h.status[VBQ_OVER_NB], h.status[VBQ_OVER_LAB],
               h.status[VBQ_OVER_ST], h.status[VBQ_OVER_Q], h.failed_cells);
        h.ar.hi = scratch;
        vbq_arena_free(&h.ar);
    }
    free(per);
    free(nnb);
    free(lab);
    free(nq);
    free(steps);
    vbq_arena_free(&ar);
    vb_cover_tree_free(tree);
    vb_spheres_free(set);
    vb_close(ctx);
    return 0;
}
