/* The plain-C reference backend: the kernels' per-ray and per-cell functions
 * of vb_geom_shared.h called in loops, in the same order of operations. */
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vb_sampler.h"

/* The reference backend's state: the colour grid of the current batch. */
typedef struct ref_state {
    uint32_t *colours;
    size_t cap;
} ref_state;

static int ref_run_batch(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
                         vb_sampler_batch_out *out)
{
    ref_state *st = be->state;
    const vbs_params *p = &b->params;
    vbs_u32 S = p->samples, T = p->tiles;
    size_t rays = 6u * (size_t)S * S;
    if (rays * b->nbases > st->cap) {
        uint32_t *c = realloc(st->colours, rays * b->nbases * sizeof *c);
        if (!c)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (colours)");
        st->colours = c;
        st->cap = rays * b->nbases;
    }
    double t0 = vb_now();
    for (size_t k = 0; k < b->nbases; k++) {
        uint32_t *col = st->colours + k * rays;
        for (vbs_u32 f = 0; f < 6u; f++)
            for (vbs_u32 iv = 0; iv < S; iv++)
                for (vbs_u32 iu = 0; iu < S; iu++)
                    col[((size_t)f * S + iv) * S + iu] = vbs_ray_colour(
                        b->bases + k, b->bis, b->tile_off, b->tile_idx, T, S, f, iu, iv);
    }
    double t1 = vb_now();
    vbs_u32 cells = 6u * (S - 1u) * (S - 1u);
    vbs_cand buf[VBS_MAX_CAND];
    for (size_t k = 0; k < b->nbases; k++) {
        const uint32_t *col = st->colours + k * rays;
        for (vbs_u32 cell = 0; cell < cells; cell++) {
            vbs_emit em = {buf, VBS_MAX_CAND, 0u, 0u, cell};
            vbs_cell_vertices(b->bases + k, b->bis, b->tile_off, b->tile_idx, p, col, cell,
                              &em);
            out->overflow += em.overflow;
            for (vbs_u32 q = 0; q < em.n; q++)
                if (vb_cand_vec_push(out->cand, buf + q))
                    return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (candidates)");
        }
    }
    double t2 = vb_now();
    out->times->envelope += t1 - t0;
    out->times->vertices += t2 - t1;
    return VB_OK;
}

static void ref_close(vb_sampler_backend *be)
{
    ref_state *st = be->state;
    if (st)
        free(st->colours);
    free(st);
    free(be);
}

int vb_sampler_ref_open(vb_ctx *ctx, vb_sampler_backend **out)
{
    vb_sampler_backend *be = calloc(1, sizeof *be);
    ref_state *st = calloc(1, sizeof *st);
    *out = NULL;
    if (!be || !st) {
        free(be);
        free(st);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    be->state = st;
    be->name = "ref";
    snprintf(be->device, sizeof be->device, "plain C reference (host CPU, 1 thread)");
    be->batch_rays = vb_sampler_batch_rays(0);
    be->run_batch = ref_run_batch;
    be->close = ref_close;
    *out = be;
    return VB_OK;
}

void vb_sampler_backend_close(vb_sampler_backend *be)
{
    if (be)
        be->close(be);
}
