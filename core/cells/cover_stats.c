/* The cover's counters (vb_cover_stats, vb_cover.h): one cover's added to
 * a worker's, and the workers' and parts' added together. */
#include "vb_cover.h"

void vb_cover_stats_cell(vb_cover_stats *st, const vbq_cell_out *o)
{
    st->neighbours += o->nnb;
    st->far_neighbours += o->far;
    if (o->nnb > st->max_cell_neighbours)
        st->max_cell_neighbours = o->nnb;
    st->patches += o->patches;
    st->evals += 1000u * (uint64_t)o->evals_k;
    st->leaves += o->leaves;
    st->max_level_leaves += o->deep;
    if (o->maxlev > st->max_level_seen)
        st->max_level_seen = o->maxlev;
}

/* The host's steps of a device cover (vb_cover_steps) added. */
static void steps_sum(vb_cover_steps *s, const vb_cover_steps *w)
{
    s->batches += w->batches;
    s->dispatch_s += w->dispatch_s;
    s->sink_s += w->sink_s;
    s->host_cells_cpu_s += w->host_cells_cpu_s;
    s->resume_cpu_s += w->resume_cpu_s;
    s->resume_queued += w->resume_queued;
    s->host_wait_s += w->host_wait_s;
    s->tail_s += w->tail_s;
}

void vb_cover_stats_sum(vb_cover_stats *st, const vb_cover_stats *ws)
{
    st->cells += ws->cells;
    st->neighbours += ws->neighbours;
    st->far_neighbours += ws->far_neighbours;
    if (ws->max_cell_neighbours > st->max_cell_neighbours)
        st->max_cell_neighbours = ws->max_cell_neighbours;
    st->patches += ws->patches;
    st->evals += ws->evals;
    st->leaves += ws->leaves;
    st->max_level_leaves += ws->max_level_leaves;
    st->retries += ws->retries;
    st->quads += ws->quads;
    st->stream_parts += ws->stream_parts;
    st->host_cells += ws->host_cells;
    st->handed_cells += ws->handed_cells;
    st->resumed_patches += ws->resumed_patches;
    st->resumed_cells += ws->resumed_cells;
    st->t_device += ws->t_device;
    st->t_host += ws->t_host;
    steps_sum(&st->steps, &ws->steps);
    if (ws->max_level_seen > st->max_level_seen)
        st->max_level_seen = ws->max_level_seen;
}
