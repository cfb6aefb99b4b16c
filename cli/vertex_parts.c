/* The vertex pipeline over the ranks of a world (vertex_parts.h). */
#include "vertex_parts.h"

#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_parallel.h"
#include "vb_world.h"

int vb_cli_vertices_part(vb_ctx *ctx, vb_vertices_config *cfg, vb_cover_options *share)
{
    int rank = vb_world_rank(), size = vb_world_size();
    const vb_proposer *p = vb_proposer_find(cfg->proposer);
    memset(share, 0, sizeof *share);
    cfg->cover = NULL;
    if (size < 2)
        return 1;
    if (p == &vb_proposer_cover) {
        share->part = (unsigned)rank;
        share->nparts = (unsigned)size;
        cfg->cover = share;
        return 1;
    }
    if (rank == 0)
        vb_warn(ctx, VB_W_MPI_SAMPLING_RANK0, NULL, 0,
                "the %s proposer does not split its work: rank 0 runs it alone, %d rank(s) idle "
                "(the default cover splits)",
                p ? p->name : "?", size - 1);
    return rank == 0;
}

/* The counters that add up over the ranks. */
#define SUMMED(X)                                                                                  \
    X(s->rays) X(s->raw_candidates) X(s->overflow) X(s->clusters) X(s->complete_first)            \
    X(s->targeted_searches) X(s->targeted_found) X(s->incomplete) X(s->sampled_vertices)          \
    X(s->vertices_incomplete) X(s->dropped) X(s->swaps) X(s->ring_tries) X(s->first_cell)         \
    X(s->from_sampling) X(s->bisectors) X(s->cover_cells) X(s->cover_patches)                     \
    X(s->cover_host_cells) X(s->cover_handed_cells) X(s->cover_resumed_patches)                 \
    X(s->cover_quads) X(s->cover_neighbours)                                                      \
    X(st->filter_calls) X(st->filter_failures) X(st->exact_evals) X(st->candidates)               \
    X(st->certified) X(st->rejected) X(st->judged_vertex) X(st->judged_not) X(st->judged_open)    \
    X(tot->rejected) X(tot->candidates) X(tot->repaired) X(s->cover_clocks.launches[0])           \
    X(s->cover_clocks.launches[1]) X(s->cover_clocks.launches[2])                               \
    X(s->cover_clocks.launches[3]) X(s->cover_clocks.launches[4]) X(s->cover_clocks.tasks[0])   \
    X(s->cover_clocks.tasks[1]) X(s->cover_clocks.tasks[2]) X(s->cover_clocks.tasks[3])         \
    X(s->cover_clocks.tasks[4]) X(s->cover_steps.batches) X(s->cover_steps.resume_queued)     \
    X(s->cover_clocks.patches[0]) X(s->cover_clocks.patches[1]) X(s->cover_clocks.patches[2])   \
    X(s->cover_clocks.patches[3]) X(s->cover_clocks.patches[4])                                 \
    X(s->cover_clocks.wasted_patches[0]) X(s->cover_clocks.wasted_patches[1])                   \
    X(s->cover_clocks.wasted_patches[2]) X(s->cover_clocks.wasted_patches[3])                   \
    X(s->cover_clocks.wasted_patches[4]) X(s->cover_clocks.wasted_tasks[0])                     \
    X(s->cover_clocks.wasted_tasks[1]) X(s->cover_clocks.wasted_tasks[2])                       \
    X(s->cover_clocks.wasted_tasks[3]) X(s->cover_clocks.wasted_tasks[4])                       \
    X(s->cover_clocks.first_past_half)

/* The times whose maximum over the ranks is the job's. */
#define MAXED(X)                                                                                   \
    X(s->times.cull) X(s->times.upload) X(s->times.envelope) X(s->times.vertices)                 \
    X(s->times.matching) X(s->times.targeted) X(s->times.tangent) X(s->times.completion)          \
    X(s->t_cover_device) X(s->t_cert_filter) X(res->t_setup) X(res->t_setup_wait)                \
    X(res->t_certify) X(res->t_total) X(res->t_certify_overlap) X(s->device_bytes_peak)           \
    X(s->cover_max_cell_neighbours) X(res->max_dist) X(s->cover_clocks.kernel_s[0])           \
    X(s->cover_clocks.kernel_s[1]) X(s->cover_clocks.kernel_s[2])                               \
    X(s->cover_clocks.kernel_s[3]) X(s->cover_clocks.kernel_s[4])                               \
    X(s->cover_clocks.launch_s[0]) X(s->cover_clocks.launch_s[1])                               \
    X(s->cover_clocks.launch_s[2]) X(s->cover_clocks.launch_s[3])                               \
    X(s->cover_clocks.launch_s[4]) X(s->cover_steps.dispatch_s) X(s->cover_steps.sink_s)        \
    X(s->cover_steps.host_cells_cpu_s) X(s->cover_steps.resume_cpu_s)                           \
    X(s->cover_steps.host_wait_s) X(s->cover_steps.tail_s) X(s->cover_clocks.task_max[0])       \
    X(s->cover_clocks.task_max[1]) X(s->cover_clocks.task_max[2])                               \
    X(s->cover_clocks.task_max[3]) X(s->cover_clocks.task_max[4])                               \
    X(s->cover_clocks.first_nb_max) X(s->cover_clocks.first_lab_max)                            \
    X(s->cover_clocks.first_q_max)

static int sum_counters(vb_ctx *ctx, vb_vertices_result *res, vb_cli_vertex_totals *tot)
{
    vb_proposal *s = &res->proposal;
    vb_stats *st = vb_ctx_stats(ctx);
    uint64_t u[96];
    double d[64];
    int nu = 0, nd = 0;
#define TO_U(field) u[nu++] = (uint64_t)(field);
#define FROM_U(field) field = u[nu++];
#define TO_D(field) d[nd++] = (field);
#define FROM_D(field) field = d[nd++];
    SUMMED(TO_U)
    MAXED(TO_D)
    int rc = vb_world_sum_u64(ctx, u, nu);
    if (rc == VB_OK)
        rc = vb_world_max_double(ctx, d, nd);
    nu = nd = 0;
    SUMMED(FROM_U)
    MAXED(FROM_D)
#undef TO_U
#undef FROM_U
#undef TO_D
#undef FROM_D
    return rc;
}

/* Rank 0: the parts of every rank, merged canonically. */
static int merge_parts(vb_ctx *ctx, unsigned char **parts, const size_t *lens,
                       vb_vertices_result *res, vb_cli_vertex_totals *tot)
{
    vb_vertex_list all;
    vb_vertex_list_init(&all);
    int rc = VB_OK;
    for (int r = 0; r < vb_world_size() && rc == VB_OK; r++)
        rc = vb_vertex_list_unpack(ctx, parts[r], lens[r], &all);
    if (rc == VB_OK)
        rc = vb_vertex_list_canonical(&all, &tot->repeats);
    if (rc != VB_OK) {
        vb_vertex_list_free(&all);
        return rc == VB_ENOMEM ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (merge)") : rc;
    }
    vb_vertex_list_free(&res->certified);
    res->certified = all;
    return VB_OK;
}

int vb_cli_vertices_combine(vb_ctx *ctx, vb_vertices_result *res, vb_cli_vertex_totals *tot)
{
    memset(tot, 0, sizeof *tot);
    tot->rejected = res->rejected.n;
    tot->candidates = res->proposal.candidates.n;
    tot->repaired = res->repaired_candidates;
    if (vb_world_size() < 2)
        return VB_OK;
    double t0 = vb_now();
    unsigned char *mine = NULL, **parts = NULL;
    size_t len = 0, *lens = NULL;
    /* Every rank takes part in both collectives whatever happened before,
     * so that none waits for another; a rank that could not pack sends an
     * empty message, which rank 0 refuses (the caller agrees on the
     * statuses before anything is written). */
    int rc = vb_vertex_list_pack(&res->certified, &mine, &len);
    if (rc != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (packing %zu vertices)",
                      res->certified.n);
    int rg = vb_world_gather(ctx, mine, rc == VB_OK ? len : 0, &parts, &lens);
    rc = rc == VB_OK ? rg : rc;
    free(mine);
    if (rc == VB_OK && parts)
        rc = merge_parts(ctx, parts, lens, res, tot);
    if (vb_world_rank() > 0)
        vb_vertex_list_free(&res->certified);
    for (int r = 0; parts && r < vb_world_size(); r++)
        free(parts[r]);
    free(parts);
    free(lens);
    int rs = sum_counters(ctx, res, tot);
    rc = rc == VB_OK ? rs : rc;
    tot->t_combine = vb_now() - t0;
    return rc;
}
