/* bench_cover_handoff: what the GPU's hand-off tier would get, simulated on
 * the host.
 *
 *   bench_cover_handoff INPUT BUDGET NB LAB Q
 *
 * Covers every cell on one thread (vbq_cover_cell, large arenas); each cell
 * with more than BUDGET patches (the group kernel's step budget,
 * gpu/cover_ocl.c) is covered again as its 24 T^2 root-patch tasks in
 * arenas of NB records, LAB labels and Q quadruples, without the host's
 * scratch (as on a device). Prints the cells handed, the tasks, the largest
 * task's patches (the longest work-item of the hand-off launch) and how
 * many tasks ran out of which arena. Tie clusters are decided on the host
 * here (a device leaves them to the host). A benchmark, not a test. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_spheres.h"

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: bench_cover_handoff INPUT BUDGET NB LAB Q\n");
        return 2;
    }
    uint32_t budget = (uint32_t)strtoul(argv[2], NULL, 10);
    uint32_t cnb = (uint32_t)strtoul(argv[3], NULL, 10), clab = (uint32_t)strtoul(argv[4], NULL, 10);
    uint32_t cq = (uint32_t)strtoul(argv[5], NULL, 10);
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_sphere_set *set = NULL;
    vb_cover_tree *tree = NULL;
    vbq_env env;
    vb_cover_options o;
    memset(&o, 0, sizeof o);
    o.threads = 1;
    if (vb_spheres_read_file(ctx, argv[1], &ro, &set) != VB_OK ||
        vb_spheres_validate(ctx, set, 4) != VB_OK ||
        vb_cover_prepare(ctx, set, &o, &tree, &env) != VB_OK) {
        fprintf(stderr, "bench_cover_handoff: %s\n", vb_errmsg(ctx));
        return 1;
    }
    vbq_arena big, small;
    memset(&big, 0, sizeof big);
    memset(&small, 0, sizeof small);
    if (vbq_arena_make(&big, 1u << 18, 1u << 21, 4096u, 1u << 16) != VB_OK ||
        vbq_arena_make(&small, cnb, clab, 256u, cq) != VB_OK)
        return 1;
    double *scratch = small.hi;
    small.hi = NULL; /* a device keeps no upper ends per label */
    size_t handed = 0, tasks = 0, status[8] = {0}, failed = 0;
    uint32_t largest_cell = 0, largest_task = 0;
    for (uint32_t i = 0; i < set->n; i++) {
        if (set->contained[i])
            continue;
        vbq_cell_out out;
        vbq_cover_cell(&env, &big, i, VBQ_ALL_ROOTS, &out);
        if (out.status != VBQ_OK || out.patches <= budget)
            continue;
        handed++;
        largest_cell = out.patches > largest_cell ? out.patches : largest_cell;
        int bad = 0;
        for (uint32_t r = 0; r < 24u * env.T * env.T; r++) {
            vbq_cell_out t;
            vbq_cover_cell(&env, &small, i, VBQ_TASK(r / 4u, r % 4u + 1u), &t);
            tasks++;
            status[t.status & 7u]++;
            bad |= t.status != VBQ_OK;
            largest_task = t.patches > largest_task ? t.patches : largest_task;
        }
        failed += (size_t)bad;
    }
    printf("%s\tbudget %u\tarenas %u/%u/%u\thanded %zu cells (largest %u patches)\t%zu tasks, "
           "largest %u patches\tran out: nb %zu, lab %zu, st %zu, q %zu (%zu cells)\n",
           argv[1], budget, cnb, clab, cq, handed, largest_cell, tasks, largest_task,
           status[VBQ_OVER_NB], status[VBQ_OVER_LAB], status[VBQ_OVER_ST], status[VBQ_OVER_Q],
           failed);
    small.hi = scratch;
    vbq_arena_free(&small);
    vbq_arena_free(&big);
    vb_cover_tree_free(tree);
    vb_spheres_free(set);
    vb_close(ctx);
    return 0;
}
