/* The vertex pipeline's counters as `vorball vertices --stats` prints them
 * (vb_vertices_write_stats): one "name<TAB>value" line each, for the
 * command and the bindings alike. */
#include <stdio.h>

#include "vb_vertices.h"

void vb_vertices_write_stats(vb_ctx *ctx, FILE *f, const vb_vertices_result *r)
{
    const vb_proposal *s = &r->proposal;
    static const vb_stats none;
    const vb_stats *st = vb_ctx_stats(ctx) ? vb_ctx_stats(ctx) : &none;
    fprintf(f,
            "backend\t%s\ndevice\t%s\nsamples\t%u\ntiles\t%u\ntol\t%.6g\nclip\t%.6g\n"
            "rays\t%llu\nbisectors\t%llu\nraw_candidates\t%llu\nvertices_matched\t%llu\n"
            "complete_first_pass\t%llu\ntargeted_searches\t%llu\ntargeted_found\t%llu\n"
            "incomplete_after_search\t%llu\nsampled_vertices\t%llu\n"
            "vertices_incomplete\t%llu\ndropped_tangent_test\t%llu\nfrom_sampling\t%llu\n"
            "swaps\t%llu\nring_tries\t%llu\nfirst_cell\t%llu\ncandidates_certified\t%llu\n"
            "certifier_rejected\t%zu\nrepair_candidates\t%zu\ncertified_vertices\t%zu\n"
            "max_candidate_distance\t%.3g\n"
            "filter_calls\t%llu\nfilter_failures\t%llu\nexact_evals\t%llu\n",
            r->backend, r->device, s->samples, s->tiles, s->tol, s->clip,
            (unsigned long long)s->rays, (unsigned long long)s->bisectors,
            (unsigned long long)s->raw_candidates, (unsigned long long)s->clusters,
            (unsigned long long)s->complete_first, (unsigned long long)s->targeted_searches,
            (unsigned long long)s->targeted_found, (unsigned long long)s->incomplete,
            (unsigned long long)s->sampled_vertices, (unsigned long long)s->vertices_incomplete,
            (unsigned long long)s->dropped, (unsigned long long)s->from_sampling,
            (unsigned long long)s->swaps, (unsigned long long)s->ring_tries,
            (unsigned long long)s->first_cell, (unsigned long long)s->candidates.n,
            r->rejected.n, r->repaired_candidates, r->certified.n, r->max_dist,
            (unsigned long long)st->filter_calls, (unsigned long long)st->filter_failures,
            (unsigned long long)st->exact_evals);
    /* The cover's counters (zero for the sampling proposer). */
    fprintf(f, "cover_cells\t%llu\ncover_patches\t%llu\ncover_host_cells\t%llu\n"
               "cover_handed_cells\t%llu\ncover_quadruples\t%llu\n",
            (unsigned long long)s->cover_cells, (unsigned long long)s->cover_patches,
            (unsigned long long)s->cover_host_cells, (unsigned long long)s->cover_handed_cells,
            (unsigned long long)s->cover_quads);
    /* The device buffers the proposer held at once (vbg_buffer.h; 0 on the
     * host), without what the OpenCL driver keeps for itself. */
    fprintf(f, "device_bytes_peak\t%llu\n", (unsigned long long)s->device_bytes_peak);
    /* The certification beside the proposer (timings: they vary run to
     * run): parts certified while the cover went on, the seconds of that
     * overlap, and the seconds certification took after the proposer. */
    fprintf(f, "certify_parts\t%zu\ncertify_overlap_s\t%.6f\ncertify_after_s\t%.6f\n",
            r->certify_parts, r->t_certify_overlap, r->t_certify);
    /* The run's own clock (wall seconds): the device set-up on its thread,
     * the time the proposer waited for it, the proposer's call (that wait
     * included), the whole run up to the certified list (set-up, proposer,
     * certification), then closing the device. */
    fprintf(f, "setup_s\t%.6f\nsetup_wait_s\t%.6f\npropose_s\t%.6f\nrun_s\t%.6f\nrelease_s\t%.6f\n",
            r->t_setup, r->t_setup_wait, r->t_propose, r->t_total, r->t_release);
    /* The certification filter before the certifier (vb_cert_filter.h):
     * roots it decided (vertex, not a vertex), roots it sent to the host's
     * exact stage, and its seconds (wall, summed over the parts; zero
     * counters when VORBALL_DEVICE_CERT=0). */
    fprintf(f, "judged_vertex\t%llu\njudged_not\t%llu\njudged_open\t%llu\njudge_s\t%.6f\n",
            (unsigned long long)st->judged_vertex, (unsigned long long)st->judged_not,
            (unsigned long long)st->judged_open, s->t_cert_filter);
}
