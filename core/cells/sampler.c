/* The sampling pipeline driver: options, batches of bases for the backend,
 * deterministic order of the candidates, then matching (matching.c). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbs_internal.h"
#include "vb_diag.h"

/* Culling of one batch on worker threads, started while the previous batch
 * is assembled and runs on the device: bases are handed out one at a time
 * (their costs differ a hundredfold between buried and hull spheres), each
 * into its own slot; the batch is then assembled in base order, so the
 * result does not depend on the thread count or the schedule. */
typedef struct cull_async {
    vb_ctx *ctx;
    const vbs_culler *cu;
    vbs_base_data *slots;
    size_t b0, b1;
    atomic_size_t next;
    atomic_int failed;
    int nt, active;
    vb_jobs jobs;
    int rc[VB_MAX_THREADS];
    struct cull_arg {
        struct cull_async *a;
        int t;
    } arg[VB_MAX_THREADS];
} cull_async;

static void *cull_worker(void *p)
{
    struct cull_arg *w = p;
    cull_async *a = w->a;
    for (;;) {
        size_t i = atomic_fetch_add(&a->next, 1);
        if (i >= a->b1 || atomic_load(&a->failed))
            break;
        int rc = vbs_cull_base(a->ctx, a->cu, (uint32_t)i, &a->slots[i - a->b0]);
        if (rc != VB_OK) {
            a->rc[w->t] = rc;
            atomic_store(&a->failed, 1);
            break;
        }
    }
    return NULL;
}

static void cull_start(cull_async *a, vb_ctx *ctx, const vbs_culler *cu, vbs_base_data *slots,
                       size_t b0, size_t b1, int nthreads)
{
    a->ctx = ctx;
    a->cu = cu;
    a->slots = slots;
    a->b0 = b0;
    a->b1 = b1;
    atomic_store(&a->next, b0);
    atomic_store(&a->failed, 0);
    a->nt = nthreads;
    a->active = 1;
    for (int t = 0; t < nthreads; t++) {
        a->rc[t] = VB_OK;
        a->arg[t] = (struct cull_arg){a, t};
    }
    vb_jobs_start(&a->jobs, cull_worker, a->arg, sizeof a->arg[0], nthreads);
}

/* Waits for the batch; a thread that could not start has its share (what
 * is left) done here. Returns the first error. */
static int cull_join(cull_async *a)
{
    if (!a->active)
        return VB_OK;
    a->active = 0;
    vb_jobs_join(&a->jobs);
    int bad = vb_jobs_first_error(a->rc, sizeof a->rc[0], a->nt, 0, VB_JOBS_UNORDERED);
    return bad < 0 ? VB_OK : a->rc[bad];
}

static int store_add(vbs_bis_store *st, uint32_t i, const vbs_base_data *bd)
{
    if (VB_ARRAY_FIT(st->bis, st->cap, st->nbis + bd->nbis, 4096) != VB_OK)
        return VB_ENOMEM;
    if (bd->nbis)
        memcpy(st->bis + st->nbis, bd->bis, bd->nbis * sizeof *bd->bis);
    st->off[i] = st->nbis;
    st->nbis += bd->nbis;
    st->off[i + 1] = st->nbis;
    /* Coarse lists: the culler's coarse T may be finer than the store's
     * nominal VBS_COARSE_T only when the finest level is coarser. */
    size_t nt = 6u * (size_t)st->T * st->T;
    if (VB_ARRAY_FIT(st->co_idx, st->co_cap, st->nco + bd->nco, 4096) != VB_OK)
        return VB_ENOMEM;
    for (size_t k = 0; k < nt; k++)
        st->co_off[(size_t)i * nt + k] = (uint32_t)(st->nco + bd->co_off[k]);
    if (bd->nco)
        memcpy(st->co_idx + st->nco, bd->co_idx, bd->nco * sizeof *bd->co_idx);
    st->nco += bd->nco;
    st->co_off[((size_t)i + 1) * nt] = (uint32_t)st->nco;
    return VB_OK;
}

/* Ratio of the extent to the smallest positive radius above which the
 * sampler refuses the input (E131), and the finest --tol it takes, as a
 * fraction of the extent (E132).
 *
 * Radii. In the frame of sphere i (scale s = R_i, vb_geom_shared.h) a
 * neighbour is e = (c_j - c_i)/s, delta = (R_j - R_i)/s, both at most
 * rho = D/s in size (D: the diagonal of the spheres' box, which bounds
 * |c_j - c_i| and |R_j - R_i|). Newton (Eq. 3) evaluates L = |e|^2 -
 * delta^2 - 2 P.e and L^2 - 4 delta^2 |P|^2. At points within 1e25 D of the
 * sphere (|P| <= 1e25 rho) |L| <= (2 + 2e25) rho^2 < 3e25 rho^2, so both
 * terms stay below 9e50 rho^4 + 4e50 rho^4 < 1.3e51 rho^4, finite (below
 * 1.8e308) for rho <= 1e50 with a factor 1e50 to spare, and the gradient
 * terms (4 L e, 8 delta^2 P) are smaller still. At rho = 1e78 (radius 1e-77
 * in a 10 A box) L^2 is 1e312 and overflows: every vertex was lost without a
 * word. The exact reference (`vorball reference`) has no such limit.
 *
 * Tolerance. Candidates are accepted when their equidistance defect is
 * within tol/s in the frame; Newton stops once its step is below 1e-13
 * (|P| + 1) and rounds each iterate to 1.1e-16 of |P|, so for vertices
 * within the box it cannot promise a defect below about 1e-13 rho, i.e.
 * 1e-13 D in world units. On the corpus, vertices start to be lost below
 * about 1e-15 D (coplanar_centres: 24 of 26 at tol = 7e-16 D; crambin_fragment
 * 272 of 349 at 1e-18), silently. tol >= 1e-12 D keeps ten times the
 * stopping rule. */
#define VBS_MAX_EXTENT_OVER_RADIUS 1e50
#define VBS_MIN_TOL_OVER_EXTENT 1e-12

/* VB_EINPUT_SCALE when a radius is too small for the double-precision
 * frame, VB_EINPUT_TOL when a given tol is finer than the candidates can be
 * (see above). */
static int check_double_range(vb_ctx *ctx, const vb_sphere_set *set, double tol)
{
    double D = vb_sampler_default_tol(set) / 1e-5;
    size_t small = SIZE_MAX;
    for (size_t i = 0; i < set->n; i++)
        if (set->r[i] > 0.0 && (small == SIZE_MAX || set->r[i] < set->r[small]))
            small = i;
    const char *src = set->source ? set->source : "<spheres>";
    if (small != SIZE_MAX && D / set->r[small] > VBS_MAX_EXTENT_OVER_RADIUS)
        return vb_error(ctx, VB_EINPUT_SCALE, src, set->line ? set->line[small] : 0,
                        "radius %.3g is below 1e-50 of the input's extent %.3g: beyond the "
                        "double precision of the sampling proposer (the cover proposer, the "
                        "default, and `vorball reference` compute it)",
                        set->r[small], D);
    if (tol > 0.0 && tol < VBS_MIN_TOL_OVER_EXTENT * D)
        return vb_error(ctx, VB_EINPUT_TOL, src, 0,
                        "--tol %.3g is below 1e-12 of the input's extent %.3g: finer than the "
                        "sampling proposer's candidates can be (the default is 1e-5 of it)",
                        tol, D);
    return VB_OK;
}

/* Candidates in the order (base, grid cell, rank in cell): independent of the
 * order in which a device appended them. */
static int cmp_cand(const void *pa, const void *pb)
{
    const vbs_cand *a = pa, *b = pb;
    if (a->ids[0] != b->ids[0])
        return a->ids[0] < b->ids[0] ? -1 : 1;
    if (a->cell != b->cell)
        return a->cell < b->cell ? -1 : 1;
    return (a->seq > b->seq) - (a->seq < b->seq);
}

/* Growable batch arrays. */
typedef struct batch_buf {
    vbs_base *bases;
    vbs_bisector *bis;
    uint32_t *tile_off, *tile_idx;
    size_t nbases, nbis, noff, nidx;
    size_t cap_bis, cap_idx;
} batch_buf;

static int batch_add(batch_buf *bb, const vb_sphere_set *s, uint32_t i, double clip,
                     const vbs_base_data *bd, size_t ntiles)
{
    if (VB_ARRAY_FIT(bb->bis, bb->cap_bis, bb->nbis + bd->nbis, 1024) != VB_OK ||
        VB_ARRAY_FIT(bb->tile_idx, bb->cap_idx, bb->nidx + bd->tile_off[ntiles], 1024) != VB_OK)
        return VB_ENOMEM;
    vbs_base *b = bb->bases + bb->nbases;
    b->cx = s->x[i];
    b->cy = s->y[i];
    b->cz = s->z[i];
    b->r = s->r[i];
    b->scale = vbs_frame_scale(s->r[i]);
    b->clip = clip / b->scale;
    b->id = i;
    b->bis_start = (uint32_t)bb->nbis;
    b->bis_count = (uint32_t)bd->nbis;
    b->tile_start = (uint32_t)(bb->nbases * ntiles);
    if (bd->nbis)
        memcpy(bb->bis + bb->nbis, bd->bis, bd->nbis * sizeof *bd->bis);
    for (size_t k = 0; k < ntiles; k++)
        bb->tile_off[bb->nbases * ntiles + k] = (uint32_t)(bb->nidx + bd->tile_off[k]);
    for (size_t k = 0; k < bd->tile_off[ntiles]; k++)
        bb->tile_idx[bb->nidx + k] = (uint32_t)bb->nbis + bd->tile_idx[k];
    bb->nbis += bd->nbis;
    bb->nidx += bd->tile_off[ntiles];
    bb->nbases++;
    bb->tile_off[bb->nbases * ntiles] = (uint32_t)bb->nidx;
    return VB_OK;
}

/* Finer tiles shorten the rays' lists but cost culling time per base. */
static unsigned auto_tiles(unsigned S)
{
    return S <= 20u ? 2u : S <= 48u ? 4u : 8u;
}

int vb_sampler_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_sampler_options *opt,
                   vb_sampler_backend *be, vb_proposal *res)
{
    vb_sampler_options o = *opt;
    if (o.samples == 0)
        o.samples = VB_SAMPLER_DEFAULT_SAMPLES;
    if (o.samples < VB_SAMPLES_MIN || o.samples > VB_SAMPLES_MAX)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--samples must be in %u..%u (got %u)",
                        VB_SAMPLES_MIN, VB_SAMPLES_MAX, o.samples);
    if (o.max_depth == 0)
        o.max_depth = VB_SAMPLER_DEFAULT_DEPTH;
    if (o.max_depth > VBS_MAX_DEPTH_LIMIT)
        o.max_depth = VBS_MAX_DEPTH_LIMIT;
    if (o.max_iter == 0)
        o.max_iter = VB_SAMPLER_DEFAULT_ITER;
    if (o.target_depth == 0)
        o.target_depth = VB_SAMPLER_DEFAULT_TARGET_DEPTH;
    if (o.tiles == 0)
        o.tiles = auto_tiles(o.samples);
    if (o.tiles > VB_TILES_MAX || (o.tiles & (o.tiles - 1u)) != 0)
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "culling tiles must be a power of two up to 64 (got %u)", o.tiles);
    int rc = set->n ? check_double_range(ctx, set, o.tol) : VB_OK;
    if (rc != VB_OK)
        return rc;
    if (!(o.tol > 0.0))
        o.tol = vb_sampler_default_tol(set);
    if (set->n > 0xfffffff0u)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "too many spheres for 32-bit ids");
    res->tol = o.tol;
    res->samples = o.samples;
    res->tiles = o.tiles;
    res->clip = vbs_clip_distance(set);


    vbs_params params = {o.tol, 1e-12, o.samples, o.tiles, o.max_depth, o.max_iter};
    size_t S = o.samples, rays_per_base = 6 * S * S;
    size_t ntiles = 6u * (size_t)o.tiles * o.tiles;
    if (!be && (!o.await_backend || !o.batch_rays))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "no sampling backend");
    size_t want = o.batch_rays ? o.batch_rays : be->batch_rays;
    size_t per_batch = want / rays_per_base;
    if (per_batch < 1)
        per_batch = 1;
    if (per_batch > set->n)
        per_batch = set->n;

    vbs_hash hash;
    vbs_tiles levels[8];
    int nlevels = 0;
    memset(levels, 0, sizeof levels);
    /* Two sets of slots: batch k + 1 is culled into one while batch k, in
     * the other, is assembled and runs on the backend. */
    vbs_base_data *slots = calloc(2 * per_batch, sizeof *slots);
    cull_async *ca = calloc(1, sizeof *ca);
    unsigned coarse_t = o.tiles < VBS_COARSE_T ? o.tiles : VBS_COARSE_T;
    vbs_bis_store store = {calloc(set->n + 1, sizeof(size_t)), NULL, 0, 0, coarse_t,
                           malloc((set->n * 6u * coarse_t * coarse_t + 1) * sizeof(uint32_t)),
                           NULL, 0, 0};
    int nthreads = vb_threads(o.threads);
    batch_buf bb;
    memset(&bb, 0, sizeof bb);
    vb_cand_vec raw = {0};
    vbs_topo_acc topo;
    memset(&topo, 0, sizeof topo);
    rc = vbs_hash_build(ctx, set, &hash);
    if (rc != VB_OK)
        return rc;
    for (unsigned T = 1; rc == VB_OK && T <= o.tiles; T *= 2)
        rc = vbs_tiles_build(ctx, T, &levels[nlevels++]);
    vbs_culler cu = {set, &hash, levels, nlevels, res->clip, o.all_pairs, &store};
    /* Waiting for a device, the first batch may grow (see backend_ready). */
    size_t max_bases = per_batch * (!be && o.backend_ready ? VB_SAMPLER_MAX_AHEAD : 1u);
    bb.bases = malloc(max_bases * sizeof *bb.bases);
    bb.tile_off = malloc((max_bases * ntiles + 1) * sizeof *bb.tile_off);
    if (rc == VB_OK &&
        (!bb.bases || !bb.tile_off || !slots || !ca || !store.off || !store.co_off))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (batch buffers)");
    int pending = 0; /* bb holds culled bases not yet run */
    /* Bases culled at a time (`step`): before the backend is known, an
     * eighth of per_batch, joined into the first batch while the device is
     * still being set up (up to per_batch, and beyond while the batch holds
     * less than VB_SAMPLER_AHEAD_BYTES); then what the backend prefers. A
     * batch sized for a GPU when the device turns out to be PoCL held the
     * culled data of thousands of bases more than PoCL runs at once (the
     * 26k-atom capsid took 11 GB on PoCL against 6.4 GB on the reference).
     * The culling of the next range is under way while a batch runs:
     * `cull_end` ends the range it covers. */
    size_t step = be ? per_batch : (per_batch + VB_SAMPLER_MAX_AHEAD - 1) / VB_SAMPLER_MAX_AHEAD;
    size_t cull_end = step;
    int be_known = be != NULL;
    if (rc == VB_OK && set->n > 0)
        cull_start(ca, ctx, &cu, slots, 0, cull_end, nthreads);
    for (size_t b0 = 0, cur = 0; rc == VB_OK && b0 < set->n; cur ^= 1) {
        size_t b1 = cull_end;
        vbs_base_data *sl = slots + cur * per_batch;
        double t0 = vb_now();
        if (!pending) {
            bb.nbases = bb.nbis = bb.nidx = 0;
            bb.tile_off[0] = 0;
        }
        rc = cull_join(ca);
        if (rc == VB_OK && b1 < set->n) {
            cull_end = b1 + step < set->n ? b1 + step : set->n;
            cull_start(ca, ctx, &cu, slots + (cur ^ 1) * per_batch, b1, cull_end, nthreads);
        }
        for (size_t i = b0; i < b1 && rc == VB_OK; i++)
            if (batch_add(&bb, set, (uint32_t)i, res->clip, &sl[i - b0], ntiles) ||
                store_add(&store, (uint32_t)i, &sl[i - b0]))
                rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (batch)");
        res->times.cull += vb_now() - t0;
        if (rc != VB_OK)
            break;
        /* The device is still being set up: cull on, into the same batch,
         * up to per_batch, and beyond while the batch is small in bytes. */
        size_t bytes = bb.nbases * (sizeof *bb.bases + ntiles * sizeof *bb.tile_off) +
                       bb.nbis * sizeof *bb.bis + bb.nidx * sizeof *bb.tile_idx;
        pending = !be && o.backend_ready && b1 < set->n &&
                  bb.nbases + (cull_end - b1) <= max_bases &&
                  (bb.nbases + (cull_end - b1) <= per_batch || bytes < VB_SAMPLER_AHEAD_BYTES) &&
                  !o.backend_ready(o.await_user);
        b0 = b1;
        if (pending)
            continue;
        res->bisectors += bb.nbis;
        vb_sampler_batch batch = {bb.nbases, bb.bases, bb.nbis, bb.bis, bb.nbases * ntiles + 1,
                                  bb.tile_off, bb.nidx, bb.tile_idx, params};
        vb_sampler_batch_out out = {&raw, 0, &res->times};
        if (!be && !(be = o.await_backend(o.await_user))) {
            rc = vb_errcode(ctx) != VB_OK ? vb_errcode(ctx) : VB_EDEVICE;
            break;
        }
        if (!be_known) {
            size_t pref = be->batch_rays ? be->batch_rays / rays_per_base : per_batch;
            step = pref < 1 ? 1 : pref > per_batch ? per_batch : pref;
            be_known = 1;
        }
        rc = be->run_batch(ctx, be, &batch, &out);
        if (rc != VB_OK)
            break;
        res->overflow += out.overflow;
        res->rays += bb.nbases * rays_per_base;
        if (o.topology)
            for (size_t k = 0; k < bb.nbases && rc == VB_OK; k++)
                if (vbs_topo_collect(&topo, &batch, k))
                    rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (topology)");
        vb_progress(ctx, "sampling", b1, set->n);
        if (o.progress)
            o.progress(o.progress_user, (double)b1 / (double)set->n);
    }
    int crc = ca ? cull_join(ca) : VB_OK; /* a batch culled ahead of an error */
    if (rc == VB_OK)
        rc = crc;
    free(ca);
    free(bb.bases);
    free(bb.bis);
    free(bb.tile_off);
    free(bb.tile_idx);
    for (size_t k = 0; slots && k < 2 * per_batch; k++)
        vbs_base_data_free(&slots[k]);
    free(slots);
    if (rc == VB_OK && o.topology && vbs_topo_finish(&topo, &res->topo))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (topology)");
    free(topo.faces);
    free(topo.triples);
    if (rc == VB_OK) {
        if (res->overflow)
            vb_warn(ctx, VB_W_CAND_OVERFLOW, NULL, 0,
                    "%llu candidate(s) did not fit the %d per grid cell; raise --samples",
                    (unsigned long long)res->overflow, VBS_MAX_CAND);
        double t0 = vb_now();
        res->raw_candidates = raw.n;
        rc = vb_psort(raw.v, raw.n, sizeof *raw.v, cmp_cand, nthreads);
        if (rc != VB_OK)
            rc = vb_error(ctx, rc, NULL, 0, "out of memory (sorting candidates)");
        else
            rc = vbs_match(ctx, set, &cu, &params, o.target_depth, nthreads, &raw, res);
        res->times.matching += vb_now() - t0;
    }
    vb_cand_vec_free(&raw);
    free(store.off);
    free(store.bis);
    free(store.co_off);
    free(store.co_idx);
    for (int l = 0; l < nlevels; l++)
        vbs_tiles_free(&levels[l]);
    vbs_hash_free(&hash);
    return rc;
}
