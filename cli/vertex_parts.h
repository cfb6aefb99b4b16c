/* The vertex pipeline over the ranks of a world (vb_world.h): which part of
 * the work a rank takes, and how rank 0 puts the parts together. With one
 * process both are trivial. */
#ifndef VB_CLI_VERTEX_PARTS_H
#define VB_CLI_VERTEX_PARTS_H

#include "vb_cover.h"
#include "vb_vertices.h"

/* Sets cfg's share of the work for this rank and says whether the rank has
 * any: the direction cover covers part `rank` of `size` of the cells (runs
 * of the cover tree's curve, balanced by count: vb_cover.h), written to
 * *share (the caller's, alive while cfg is used) with cfg->cover pointed at
 * it (NULL with one process), so every rank works; the sampling proposer does not split, so rank 0 runs it whole and
 * the others idle (rank 0 warns W830). Returns 1 when this rank runs the
 * pipeline, 0 when it idles. */
int vb_cli_vertices_part(vb_ctx *ctx, vb_vertices_config *cfg, vb_cover_options *share);

/* What the command reports beside the vertices, as counts over the ranks
 * (the lists themselves stay on their ranks). */
typedef struct vb_cli_vertex_totals {
    size_t rejected;        /* candidates / roots the certifier refused */
    size_t candidates;      /* candidates handed to the certifier */
    size_t repaired;        /* intruder-swap candidates certified */
    size_t repeats;         /* vertices certified by two ranks, merged (degree > 4) */
    double t_combine;       /* seconds of the gather and merge on rank 0 */
} vb_cli_vertex_totals;

/* Collective, after every rank's run succeeded (vb_world_agree): rank 0
 * gets the certified vertices of every rank merged canonically in
 * res->certified (sorted, one line per exact vertex: the same vertex of
 * degree > 4 certified by two ranks, with the same members and the same
 * rounded point, is kept once), the proposer's counters summed (the cover
 * certificate counts every rank's cells and quadruples) and the context's
 * predicate counters summed; stage times and max_dist are the maxima over
 * the ranks, on every rank. The other ranks' certified lists are emptied.
 * Every rank takes part in its collectives whatever fails, so the caller
 * agrees on the status (vb_world_agree) before rank 0 writes anything.
 * VB_OK, VB_ENOMEM, VB_EINTERNAL (a garbled part). */
int vb_cli_vertices_combine(vb_ctx *ctx, vb_vertices_result *res, vb_cli_vertex_totals *tot);

#endif
