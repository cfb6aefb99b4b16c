/* The text outputs of frames that several ranks computed, written by rank 0
 * in frame order (`channels` under mpirun; with one process the same path
 * and the same bytes).
 *
 * Selected frames are dealt round-robin: frame j of the selection (0, 1,
 * ...) belongs to rank j mod size. They are taken in rounds of
 * VB_CLI_ROUND_FRAMES frames per rank: a rank writes the outputs of each of
 * its frames to the round's streams (one per sink: table, statistics,
 * centrelines) and marks the frame's end; at the end of the round every
 * rank agrees on the status and rank 0 gathers the frames and writes them
 * to its sinks in selection order. Memory follows the round, not the run. */
#ifndef VB_CLI_FRAME_ROUNDS_H
#define VB_CLI_FRAME_ROUNDS_H

#include <stdio.h>

#include "vb.h"

#define VB_CLI_ROUND_FRAMES 8
#define VB_CLI_ROUND_SINKS 3

typedef struct vb_cli_rounds vb_cli_rounds;

/* Opens the rounds (streams for the first one). VB_OK or VB_ENOMEM. */
int vb_cli_rounds_open(vb_ctx *ctx, vb_cli_rounds **out);

/* Frames per round over every rank: VB_CLI_ROUND_FRAMES times the ranks. */
long vb_cli_rounds_length(void);

/* Whether frame j of the selection is this rank's. */
int vb_cli_rounds_mine(long j);

/* The stream of sink k (0 .. VB_CLI_ROUND_SINKS - 1) for this rank's
 * current frame; owned by the rounds. */
FILE *vb_cli_rounds_stream(vb_cli_rounds *r, int k);

/* Ends this rank's current frame. VB_OK or VB_ENOMEM. */
int vb_cli_rounds_frame_done(vb_ctx *ctx, vb_cli_rounds *r);

/* Collective, after the round's frames [j0, j1) of the selection: agrees
 * on rc (vb_world_agree); when every rank succeeded, rank 0 writes the
 * frames to sinks[k] (NULL: that sink is not wanted) in selection order.
 * Streams are then ready for the next round. Returns the agreed status
 * (VB_ENOMEM, VB_EINTERNAL for a garbled round). */
int vb_cli_rounds_flush(vb_ctx *ctx, vb_cli_rounds *r, int rc, long j0, long j1,
                        FILE *sinks[VB_CLI_ROUND_SINKS]);

/* NULL is allowed. */
void vb_cli_rounds_close(vb_cli_rounds *r);

#endif
