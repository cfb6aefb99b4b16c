/* The processes of one `vorball` run: the ranks of MPI's world when vorball
 * is built with VORBALL_WITH_MPI and started by mpirun (cli/world_mpi.c),
 * else one process (cli/world_single.c). The only place of the project
 * that talks to MPI: the library stays MPI-free, and the commands that
 * split their work (vertices, bench, channels) call these few collectives.
 *
 * The rules every rank follows:
 *   - each rank reads the input itself; warnings of that reading are
 *     printed by rank 0 only (the others read quietly: vb_world_quiet);
 *   - only rank 0 writes output files and stdout (stdout of the other
 *     ranks goes to /dev/null);
 *   - warnings of the other ranks are kept and printed by rank 0 at the
 *     end, tagged with the ranks that gave them;
 *   - a failure on any rank is seen by every rank at the next collective
 *     (vb_world_agree, vb_world_end): every rank stops, the failing rank's
 *     numbered error is printed naming it, and every rank exits with that
 *     error's exit status.
 * Collectives are called by every rank in the same order; a rank that
 * failed still calls the next one.
 *
 * With one process every call is trivial and the command behaves exactly
 * as the build without MPI does. */
#ifndef VB_WORLD_H
#define VB_WORLD_H

#include <stddef.h>
#include <stdint.h>

#include "vb.h"

/* Joins the world (MPI_Init_thread, funneled: only the main thread talks
 * to MPI) and, when several ranks share a host and the environment does
 * not say otherwise, gives each its device and its threads:
 * VORBALL_DEVICE_INDEX = the rank on its host (gpu/runtime.c opens that
 * GPU), VORBALL_THREADS and POCL_MAX_PTHREAD_COUNT = the host's CPUs (as
 * the rank's affinity allows) divided by the ranks on the host, at least 1.
 * Returns 0, or an exit status after printing E150 (MPI cannot start). */
int vb_world_init(int *argc, char ***argv);

/* Leaves the world (MPI_Finalize); returns exit_code. */
int vb_world_finish(int exit_code);

int vb_world_rank(void);
int vb_world_size(void);

/* Whether the subcommand `cmd` may run on this world: vertices, bench and
 * channels split their work; every other command runs on one process only
 * (E151 under mpirun -np N > 1). Returns 0, or the exit status after rank 0
 * printed E151. The same answer on every rank, with no message between
 * them. */
int vb_world_check_command(const char *cmd);

/* Whether the input may be read by every rank: a file, not stdin ("-"),
 * which mpirun gives to rank 0 alone (E152 under several ranks). Returns
 * 0 or the exit status after rank 0 printed E152; no message between
 * ranks. */
int vb_world_check_input(const char *cmd, const char *path);

/* Opens the command's context: as vb_open(ctx, NULL) on rank 0; on the
 * other ranks its warnings are kept for vb_world_end. VB_OK or VB_ENOMEM. */
int vb_world_open_ctx(vb_ctx **ctx);

/* Silences warnings on ranks other than 0 (input that every rank reads:
 * rank 0 prints its warnings) and returns what vb_world_loud restores. */
int vb_world_quiet(vb_ctx *ctx);
void vb_world_loud(vb_ctx *ctx, int saved);

/* Collective status check: every rank passes its own status (message in
 * ctx). Returns VB_OK when every rank succeeded; else, on every rank, a
 * failure status: a failing rank keeps its own, the others get the status
 * of the lowest failing rank (message: that it stopped them). Call
 * vb_world_end next. */
int vb_world_agree(vb_ctx *ctx, int rc);

/* The last collective of a command: agrees on rc as vb_world_agree does,
 * prints on rank 0 the warnings kept on the other ranks, then the errors:
 * each failing rank's "vorball: E<n>: rank R of N: message" (ranks with
 * the same message on one line), and W831 when rank 0 itself did not fail.
 * Returns the exit status, the same on every rank: 0, or the exit of the
 * lowest failing rank's error. With one process: vb_cli_fail's output and
 * status. */
int vb_world_end(vb_ctx *ctx, int rc);

/* A message of `len` bytes from every rank to rank 0: on rank 0, parts[r]
 * (malloc'd; the caller frees each and the array) and lens[r] get rank r's
 * bytes (rank 0's own copied); on other ranks *parts is NULL. Collective.
 * VB_OK, or VB_ENOMEM with one process; with several, running out of
 * memory or a failed MPI call aborts the job (E4, E150: the other ranks
 * would wait for ever). */
int vb_world_gather(vb_ctx *ctx, const void *buf, size_t len, unsigned char ***parts,
                    size_t **lens);

/* Element-wise sums (u64, double) or maxima (double) over the ranks, on
 * every rank, in place. Collective. VB_OK (a failed MPI call aborts the job
 * with E150). */
int vb_world_sum_u64(vb_ctx *ctx, uint64_t *v, int n);
int vb_world_sum_double(vb_ctx *ctx, double *v, int n);
int vb_world_max_double(vb_ctx *ctx, double *v, int n);

/* Waits for every rank (timings that start together). */
void vb_world_barrier(void);

#endif
