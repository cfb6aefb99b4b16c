/* The memory the vertex pipeline will need, estimated before it starts,
 * and the early refusal when it cannot have it (vb_vertices.h; issue 28
 * item 7: 2e6 spheres under a 4 GB limit ran 8 minutes before E4).
 *
 * The model: what is alive at once at the pipeline's peak, the merge at the
 * end of the certifier's quadruple judge (verify/certify/certify_quads.c), with
 * every count taken at the low end of what was measured, so that the
 * estimate stays below the true need: a run it refuses would not have fit.
 *
 * Per sphere (all n, alive for the whole run), 365 bytes (the input set,
 * 105 bytes a sphere, is already mapped when the room is measured):
 *   exact data      4 x (mpz_t 16 + its limb 8 + enclosure 16 + double 8) = 192
 *   quad filter     4 x int64 = 32; certifier scratch ids, members, is_def = 9
 *   spatial index   ids 4 + 4 enclosures 64 + 4 doubles 32 + nodes >= 28 = 128
 *   cover tree      curve-ordered ids = 4
 * Per vertex (per cell: 6.5 vertices, each vertex counted once), 191 bytes:
 *   judge record    qrec: 4 doubles, quad, offset, count, sign = 56
 *   merge refs      two vref arrays of the records' length (24 B each) = 48
 *   output list     start 8 + 4 ids 16 + x, y, z, t, dist 40 + status 1 = 65
 *   quadruples      16 B per proposed quadruple, >= 1.4 per vertex = 22.4
 * The output list grows by doubling from 64 (vertex_list.c): its capacity
 * is the power of two reached for the estimated count, which is below the
 * true count's. The judge's records grow per worker: counted at their
 * length only. Measured vertices per cell: 6.52 (3000 random spheres), 6.60
 * (3pqr, 3432 cells), 6.65 (10^4 random), 6.74 (2 10^5 random); the
 * Poisson-Voronoi mean is 27.07 / 4 = 6.77. Quadruples per vertex: 1.40
 * (random), 1.52 (3pqr). Measured peak resident set, base subtracted:
 * 2.08-2.32 KB per sphere on random spheres, 2.6 KB per cell on 3pqr; this
 * model gives 1.74-1.93 KB per cell.
 *
 * The address space (ulimit -v) also holds, untouched, each worker
 * thread's stack (8 MiB) and glibc malloc arena (64 MiB reserved):
 * measured 73 MB of VmPeak per thread; and an OpenCL runtime opened after
 * this check (PoCL with LLVM: 420 MB of VmPeak, 80 MB resident over
 * --device ref): 256 MiB and 64 MiB counted. Only the cover's terms are
 * known for the sampling proposer: it is estimated as the spheres and the
 * output list alone. */
#include "vb_vertices.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_diag.h"
#include "vb_memory.h"
#include "vb_parallel.h"

#define PER_SPHERE 365.0
#define PER_VERTEX_COVER (56.0 + 48.0 + 22.4)
#define PER_VERTEX_LIST 65.0
#define VERTICES_PER_CELL 6.5
#define THREAD_RESERVED (72.0 * 1048576.0)
#define DEVICE_RESERVED (256.0 * 1048576.0)
#define DEVICE_RESIDENT (64.0 * 1048576.0)

/* The capacity vb_vertex_list reaches for n vertices. */
static double list_capacity(double n)
{
    double cap = 64.0;
    while (cap < n)
        cap *= 2.0;
    return cap;
}

void vb_vertices_memory_estimate(const vb_sphere_set *set, const vb_vertices_config *cfg,
                                 int device_open, vb_vertices_memory *out)
{
    size_t cells = 0;
    for (size_t i = 0; i < set->n; i++)
        cells += !set->contained || !set->contained[i];
    unsigned nparts = cfg->cover && cfg->cover->nparts > 1 ? cfg->cover->nparts : 1;
    const vb_proposer *p = vb_proposer_find(cfg->proposer);
    int cover = p == &vb_proposer_cover;
    /* A rank of nparts certifies its share of the cells; rank 0 merges
     * every vertex (the list terms stay whole). */
    double v = VERTICES_PER_CELL * (double)cells;
    double bytes = PER_SPHERE * (double)set->n + PER_VERTEX_LIST * list_capacity(v);
    if (cover)
        bytes += PER_VERTEX_COVER * v / nparts;
    double resident = bytes, reserved = bytes;
    reserved += THREAD_RESERVED * (double)vb_threads(cfg->propose.threads);
    if (cfg->device != VB_DEVICE_REF && !device_open) {
        resident += DEVICE_RESIDENT;
        reserved += DEVICE_RESERVED;
    }
    out->resident = resident >= (double)SIZE_MAX ? SIZE_MAX : (size_t)resident;
    out->address_space = reserved >= (double)SIZE_MAX ? SIZE_MAX : (size_t)reserved;
    out->cells = cells;
}

/* Bytes as "1.23 GB" or "456 MB" (10^9 and 10^6 bytes). */
static void human(size_t b, char *buf, size_t size)
{
    double x = (double)b;
    if (x >= 1e9)
        snprintf(buf, size, "%.2f GB", x / 1e9);
    else
        snprintf(buf, size, "%.0f MB", x / 1e6);
}

int vb_vertices_memory_check(vb_ctx *ctx, const vb_sphere_set *set,
                             const vb_vertices_config *cfg, int device_open)
{
    vb_vertices_memory need;
    vb_memory_room room;
    vb_vertices_memory_estimate(set, cfg, device_open, &need);
    vb_memory_room_get(&room);
    size_t want = need.address_space;
    const vb_memory_limit *lim = &room.address;
    if (want <= lim->bytes) {
        want = need.resident;
        lim = &room.resident;
        if (want <= lim->bytes)
            return VB_OK;
    }
    char n[32], a[32];
    human(want, n, sizeof n);
    human(lim->bytes, a, sizeof a);
    return vb_error(ctx, VB_ENOMEM_ESTIMATE, set->source, 0,
                    "%zu spheres (%zu cells) need at least %s for vertices, %s available "
                    "under %s: refused before starting",
                    set->n, need.cells, n, a, lim->limit);
}
