/* The vertex pipeline's counters as `vorball vertices --stats` prints them:
 * one table (vb_vertices_stats) that the command prints and the bindings
 * read as typed values. */
#include "vb_vertices.h"

void vb_vertices_stats(vb_ctx *ctx, const vb_vertices_result *r, vb_stat_fields *fs)
{
    const vb_proposal *s = &r->proposal;
    static const vb_stats none;
    const vb_stats *st = vb_ctx_stats(ctx) ? vb_ctx_stats(ctx) : &none;
    vb_stat_text(fs, "backend", r->backend);
    vb_stat_text(fs, "device", r->device);
    vb_stat_uint(fs, "samples", s->samples);
    vb_stat_uint(fs, "tiles", s->tiles);
    vb_stat_real(fs, "tol", "%.6g", s->tol);
    vb_stat_real(fs, "clip", "%.6g", s->clip);
    vb_stat_uint(fs, "rays", s->rays);
    vb_stat_uint(fs, "bisectors", s->bisectors);
    vb_stat_uint(fs, "raw_candidates", s->raw_candidates);
    vb_stat_uint(fs, "vertices_matched", s->clusters);
    vb_stat_uint(fs, "complete_first_pass", s->complete_first);
    vb_stat_uint(fs, "targeted_searches", s->targeted_searches);
    vb_stat_uint(fs, "targeted_found", s->targeted_found);
    vb_stat_uint(fs, "incomplete_after_search", s->incomplete);
    vb_stat_uint(fs, "sampled_vertices", s->sampled_vertices);
    vb_stat_uint(fs, "vertices_incomplete", s->vertices_incomplete);
    vb_stat_uint(fs, "dropped_tangent_test", s->dropped);
    vb_stat_uint(fs, "from_sampling", s->from_sampling);
    vb_stat_uint(fs, "swaps", s->swaps);
    vb_stat_uint(fs, "ring_tries", s->ring_tries);
    vb_stat_uint(fs, "first_cell", s->first_cell);
    vb_stat_uint(fs, "candidates_certified", s->candidates.n);
    vb_stat_uint(fs, "certifier_rejected", r->rejected.n);
    vb_stat_uint(fs, "repair_candidates", r->repaired_candidates);
    vb_stat_uint(fs, "certified_vertices", r->certified.n);
    vb_stat_real(fs, "max_candidate_distance", "%.3g", r->max_dist);
    vb_stat_uint(fs, "filter_calls", st->filter_calls);
    vb_stat_uint(fs, "filter_failures", st->filter_failures);
    vb_stat_uint(fs, "exact_evals", st->exact_evals);
    /* The cover's counters (zero for the sampling proposer). */
    vb_stat_uint(fs, "cover_cells", s->cover_cells);
    vb_stat_uint(fs, "cover_patches", s->cover_patches);
    vb_stat_uint(fs, "cover_host_cells", s->cover_host_cells);
    vb_stat_uint(fs, "cover_handed_cells", s->cover_handed_cells);
    vb_stat_uint(fs, "cover_resumed_patches", s->cover_resumed_patches);
    vb_stat_uint(fs, "cover_quadruples", s->cover_quads);
    /* The neighbour records the cover built (every sphere a cell's tree
     * walks kept), in all and the most for one cell: a hull cell whose
     * rings fetch the whole input shows in the second. */
    vb_stat_uint(fs, "cover_neighbours", s->cover_neighbours);
    vb_stat_uint(fs, "cover_max_cell_neighbours", s->cover_max_cell_neighbours);
    /* The cover's device time (timings: they vary run to run): its
     * batches' wall seconds, then per step (first launch, large slices,
     * hand-off, huge slices, the first launch's reruns for handed patches
     * that found no room) the seconds its kernels ran on the device, the
     * host's wall seconds of its launches (kernel, transfers, arguments),
     * launches and tasks; the rest of cover_device_s is the driver's host
     * work between launches. */
    vb_stat_real(fs, "cover_device_s", "%.6f", s->t_cover_device);
    static const char *const step[VB_COVER_STEPS][4] = {
        {"cover_kernel_first_s", "cover_launch_first_s", "cover_launches_first",
         "cover_tasks_first"},
        {"cover_kernel_large_s", "cover_launch_large_s", "cover_launches_large",
         "cover_tasks_large"},
        {"cover_kernel_handoff_s", "cover_launch_handoff_s", "cover_launches_handoff",
         "cover_tasks_handoff"},
        {"cover_kernel_huge_s", "cover_launch_huge_s", "cover_launches_huge", "cover_tasks_huge"},
        {"cover_kernel_rerun_s", "cover_launch_rerun_s", "cover_launches_rerun",
         "cover_tasks_rerun"}};
    for (int i = 0; i < VB_COVER_STEPS; i++) {
        vb_stat_real(fs, step[i][0], "%.6f", s->cover_clocks.kernel_s[i]);
        vb_stat_real(fs, step[i][1], "%.6f", s->cover_clocks.launch_s[i]);
        vb_stat_uint(fs, step[i][2], s->cover_clocks.launches[i]);
        vb_stat_uint(fs, step[i][3], s->cover_clocks.tasks[i]);
    }
    /* The work of each step's tasks (vb_cover_clocks, issue #30): patches
     * popped, the most one task popped, and the patches and tasks of those
     * that ran out of room and were covered again from their roots. */
    static const char *const work[VB_COVER_STEPS][4] = {
        {"cover_patches_first", "cover_task_max_patches_first", "cover_wasted_patches_first",
         "cover_wasted_tasks_first"},
        {"cover_patches_large", "cover_task_max_patches_large", "cover_wasted_patches_large",
         "cover_wasted_tasks_large"},
        {"cover_patches_handoff", "cover_task_max_patches_handoff",
         "cover_wasted_patches_handoff", "cover_wasted_tasks_handoff"},
        {"cover_patches_huge", "cover_task_max_patches_huge", "cover_wasted_patches_huge",
         "cover_wasted_tasks_huge"},
        {"cover_patches_rerun", "cover_task_max_patches_rerun", "cover_wasted_patches_rerun",
         "cover_wasted_tasks_rerun"}};
    for (int i = 0; i < VB_COVER_STEPS; i++) {
        vb_stat_uint(fs, work[i][0], s->cover_clocks.patches[i]);
        vb_stat_uint(fs, work[i][1], s->cover_clocks.task_max[i]);
        vb_stat_uint(fs, work[i][2], s->cover_clocks.wasted_patches[i]);
        vb_stat_uint(fs, work[i][3], s->cover_clocks.wasted_tasks[i]);
    }
    /* What the first tier's arenas held (vb_cover_clocks): the most
     * records, labels and quadruples of a task, and its tasks past half
     * its records or labels. */
    vb_stat_uint(fs, "cover_first_records_max", s->cover_clocks.first_nb_max);
    vb_stat_uint(fs, "cover_first_labels_max", s->cover_clocks.first_lab_max);
    vb_stat_uint(fs, "cover_first_quadruples_max", s->cover_clocks.first_q_max);
    vb_stat_uint(fs, "cover_first_past_half", s->cover_clocks.first_past_half);
    /* The host's side of a device cover (vb_cover_steps; timings): the
     * batches, the device's thread's work after each read-back, the sinks,
     * the CPU of the host threads' whole cells and of the handed patches
     * resumed (and how many cells the host threads resumed), the host
     * threads' wait for work (the host waiting on the device) and the tail
     * after the device's last batch (the device waiting on the host). */
    const vb_cover_steps *cs = &s->cover_steps;
    vb_stat_uint(fs, "cover_batches", cs->batches);
    vb_stat_real(fs, "cover_dispatch_s", "%.6f", cs->dispatch_s);
    vb_stat_real(fs, "cover_sink_s", "%.6f", cs->sink_s);
    vb_stat_real(fs, "cover_host_cells_cpu_s", "%.6f", cs->host_cells_cpu_s);
    vb_stat_real(fs, "cover_resume_cpu_s", "%.6f", cs->resume_cpu_s);
    vb_stat_uint(fs, "cover_resume_queued", cs->resume_queued);
    vb_stat_real(fs, "cover_host_wait_s", "%.6f", cs->host_wait_s);
    vb_stat_real(fs, "cover_tail_s", "%.6f", cs->tail_s);
    /* The device buffers the proposer held at once (vbg_buffer.h; 0 on the
     * host), without what the OpenCL driver keeps for itself. */
    vb_stat_uint(fs, "device_bytes_peak", s->device_bytes_peak);
    /* The certification beside the proposer (timings: they vary run to
     * run): parts certified while the cover went on, the seconds of that
     * overlap, and the seconds certification took after the proposer. */
    vb_stat_uint(fs, "certify_parts", r->certify_parts);
    vb_stat_real(fs, "certify_overlap_s", "%.6f", r->t_certify_overlap);
    vb_stat_real(fs, "certify_after_s", "%.6f", r->t_certify);
    /* The work on certified parts (arc closure's early tracing), where it
     * ran: its seconds while the proposer ran and after it returned (the
     * certification waited for them; certify_overlap_s leaves them out). */
    if (r->part_work_on) {
        vb_stat_real(fs, "part_work_overlap_s", "%.6f", r->t_part_overlap);
        vb_stat_real(fs, "part_work_after_s", "%.6f", r->t_part_after);
    }
    /* The run's own clock (wall seconds): the device set-up on its thread
     * (from its start: at the input's read where the command opened it
     * early), the time the proposer waited for it once its host work that
     * needs no device was done (cover_prepare_s: the cover's tree and
     * certification filter),
     * the proposer's call (that wait included), the whole run up to the certified list (set-up, proposer,
     * certification), then closing the device. */
    vb_stat_real(fs, "cover_prepare_s", "%.6f", s->t_cover_prepare);
    vb_stat_real(fs, "setup_s", "%.6f", r->t_setup);
    vb_stat_real(fs, "setup_wait_s", "%.6f", r->t_setup_wait);
    vb_stat_real(fs, "propose_s", "%.6f", r->t_propose);
    vb_stat_real(fs, "run_s", "%.6f", r->t_total);
    vb_stat_real(fs, "release_s", "%.6f", r->t_release);
    /* The certification filter before the certifier (vb_cert_filter.h):
     * roots it decided (vertex, not a vertex), roots it sent to the host's
     * exact stage, and its seconds (wall, summed over the parts; zero
     * counters when VORBALL_DEVICE_CERT=0). */
    vb_stat_uint(fs, "judged_vertex", st->judged_vertex);
    vb_stat_uint(fs, "judged_not", st->judged_not);
    vb_stat_uint(fs, "judged_open", st->judged_open);
    vb_stat_real(fs, "judge_s", "%.6f", s->t_cert_filter);
}

void vb_vertices_write_stats(vb_ctx *ctx, FILE *f, const vb_vertices_result *r)
{
    vb_stat_fields fs;
    fs.n = 0;
    vb_vertices_stats(ctx, r, &fs);
    vb_stat_fields_write(f, &fs, 0);
}
