/* The exact tiled engine ("exact", "exact-boundary"): the host preparation
 * both backends share (the seed grid in bucket order) and the plain-C twin
 * of gpu/jfa_tiles.cl, tile by tile with the decisions of vbj_tiles.h (the
 * proofs are there). Tiles are independent, so they run on threads; labels
 * and counts do not depend on the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbj_prep.h"
#include "vbj_tiles.h"

void vbj_tiles_prep_free(vbj_tiles_prep *p)
{
    free(p->start);
    free(p->recs);
    memset(p, 0, sizeof *p);
}

int vbj_tiles_prep_build(vb_ctx *ctx, const vbj_seeds *s, vbj_tiles_prep *out)
{
    memset(out, 0, sizeof *out);
    uint32_t logn = vbj_log2u(s->n), dim = (uint32_t)s->dim;
    out->ts = vbj_xt_tile_shift(dim, logn);
    vbj_cells c;
    int rc = vbj_cells_build_min(ctx, s, out->ts, &c);
    if (rc)
        return rc;
    out->bs = c.shift;
    out->g = c.g;
    out->nbuckets = (size_t)c.g * c.g * (dim == 3 ? c.g : 1);
    out->start = c.start; /* taken over */
    out->recs = malloc(s->k * 4 * sizeof *out->recs);
    if (!out->recs) {
        free(c.items);
        vbj_tiles_prep_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seed grid: out of memory");
    }
    for (size_t j = 0; j < s->k; j++) {
        uint32_t v = c.items[j];
        out->recs[4 * j] = s->x[v];
        out->recs[4 * j + 1] = s->y[v];
        out->recs[4 * j + 2] = dim == 3 ? s->z[v] : 0;
        out->recs[4 * j + 3] = (int32_t)v;
    }
    free(c.items);
    return VB_OK;
}

/* One run of the twin. */
typedef struct {
    int32_t *surv; /* survivors: rx, ry, rz, index */
    size_t cap;
    uint64_t cnt[VBJ_XT_NC];
    int failed;
} scratch;

typedef struct {
    const vbj_tiles_prep *p;
    uint32_t n, dim, T; /* T tiles per axis */
    uint32_t *labels;
    scratch th[VB_MAX_THREADS];
} job;

static int push(scratch *w, size_t i, const int32_t r[4])
{
    if (i == w->cap) {
        size_t cap = w->cap ? 2 * w->cap : 256;
        int32_t *a = realloc(w->surv, cap * 4 * sizeof *a);
        if (!a)
            return -1;
        w->surv = a;
        w->cap = cap;
    }
    memcpy(w->surv + 4 * i, r, 4 * sizeof *r);
    return 0;
}

/* The exact label of voxel offset (x, y, z) of the tile among the n
 * survivors: 64-bit integer distances, ties to the lowest index. */
static uint32_t exact_among(const int32_t *sv, size_t n, int32_t x, int32_t y, int32_t z)
{
    uint32_t best = VBJ_NONE;
    uint64_t bd = UINT64_MAX;
    for (size_t i = 0; i < n; i++) {
        const int32_t *e = sv + 4 * i;
        uint64_t d = vbj_dist2(x, y, z, e[0], e[1], e[2]);
        if (vbj_better(d, (uint32_t)e[3], bd, best)) {
            bd = d;
            best = (uint32_t)e[3];
        }
    }
    return best;
}

static void tile(void *arg, size_t t, int tid)
{
    job *J = arg;
    scratch *w = &J->th[tid];
    const vbj_tiles_prep *p = J->p;
    uint32_t dim = J->dim, T = J->T, S = 1u << p->ts;
    uint32_t tc[3] = {(uint32_t)(t % T), (uint32_t)(t / T % T),
                      dim == 3 ? (uint32_t)(t / ((size_t)T * T)) : 0};
    vbj_xt_box box = vbj_xt_tile_box(tc[0], tc[1], tc[2], p->ts, dim);
    int32_t cen[3];
    for (int a = 0; a < 3; a++)
        cen[a] = a < (int)dim ? box.lo[a] + (int32_t)(S / 2) * VBJ_FIX_ONE : 0;
    int32_t g = (int32_t)p->g, b0[3], lo[3], hi[3];
    for (int a = 0; a < 3; a++)
        b0[a] = a < (int)dim ? (int32_t)((tc[a] << p->ts) >> p->bs) : 0;

    /* Rings: U^2 and the centre's owner. */
    uint64_t u2 = UINT64_MAX, cd = UINT64_MAX;
    uint32_t cs = VBJ_NONE;
    const int32_t *c = NULL; /* the centre owner's record */
    int32_t R = 0;
    for (;; R++) {
        for (int a = 0; a < 3; a++) {
            lo[a] = a < (int)dim ? (b0[a] - R < 0 ? 0 : b0[a] - R) : 0;
            hi[a] = a < (int)dim ? (b0[a] + R >= g ? g - 1 : b0[a] + R) : 0;
        }
        for (int32_t bz = lo[2]; bz <= hi[2]; bz++)
            for (int32_t by = lo[1]; by <= hi[1]; by++)
                for (int32_t bx = lo[0]; bx <= hi[0]; bx++) {
                    int32_t cheb = abs(bx - b0[0]);
                    cheb = abs(by - b0[1]) > cheb ? abs(by - b0[1]) : cheb;
                    cheb = abs(bz - b0[2]) > cheb ? abs(bz - b0[2]) : cheb;
                    if (cheb != R)
                        continue;
                    size_t b = ((size_t)bz * p->g + (size_t)by) * p->g + (size_t)bx;
                    for (uint32_t j = p->start[b]; j < p->start[b + 1]; j++) {
                        const int32_t *e = p->recs + 4 * (size_t)j;
                        uint64_t n2, f2;
                        vbj_xt_bounds(box, e[0], e[1], e[2], dim, &n2, &f2);
                        u2 = f2 < u2 ? f2 : u2;
                        uint64_t d = vbj_dist2(cen[0], cen[1], cen[2], e[0], e[1], e[2]);
                        if (vbj_better(d, (uint32_t)e[3], cd, cs)) {
                            cd = d;
                            cs = (uint32_t)e[3];
                            c = e;
                        }
                        w->cnt[VBJ_XT_C_VISITED]++;
                    }
                }
        if (vbj_xt_done(vbj_xt_gap(box, b0[0], b0[1], b0[2], R, p->bs, g, dim), u2))
            break;
    }

    /* The block again: candidates, then survivors of the dominance test. */
    size_t ns = 0;
    int far = 0;
    for (int32_t bz = lo[2]; bz <= hi[2]; bz++)
        for (int32_t by = lo[1]; by <= hi[1]; by++)
            for (int32_t bx = lo[0]; bx <= hi[0]; bx++) {
                size_t b = ((size_t)bz * p->g + (size_t)by) * p->g + (size_t)bx;
                for (uint32_t j = p->start[b]; j < p->start[b + 1]; j++) {
                    const int32_t *e = p->recs + 4 * (size_t)j;
                    uint64_t n2, f2;
                    uint32_t v = (uint32_t)e[3];
                    w->cnt[VBJ_XT_C_VISITED]++;
                    vbj_xt_bounds(box, e[0], e[1], e[2], dim, &n2, &f2);
                    if (n2 > u2)
                        continue;
                    w->cnt[VBJ_XT_C_CAND]++;
                    if (v != cs &&
                        vbj_xt_dominated(box, c[0], c[1], c[2], cs, e[0], e[1], e[2], v, dim))
                        continue;
                    int32_t r[4] = {e[0] - box.lo[0], e[1] - box.lo[1], e[2] - box.lo[2],
                                    (int32_t)v};
                    far |= !vbj_xt_float_ok(r[0], r[1], r[2]);
                    if (push(w, ns++, r)) {
                        w->failed = 1;
                        return;
                    }
                }
            }
    w->cnt[VBJ_XT_C_SURV] += ns;
    w->cnt[VBJ_XT_C_UNIFORM] += ns == 1;
    w->cnt[VBJ_XT_C_CHUNKED] += ns > VBJ_XT_CAP;

    /* Every voxel of the tile. */
    uint32_t n = J->n, sz = dim == 3 ? S : 1;
    for (uint32_t z = 0; z < sz; z++)
        for (uint32_t y = 0; y < S; y++) {
            uint32_t *row = J->labels + ((size_t)((tc[2] << p->ts) + z) * n + (tc[1] << p->ts) + y) * n +
                            (tc[0] << p->ts);
            for (uint32_t x = 0; x < S; x++) {
                if (ns == 1) {
                    row[x] = cs;
                    continue;
                }
                int32_t vx = (int32_t)x * VBJ_FIX_ONE, vy = (int32_t)y * VBJ_FIX_ONE;
                int32_t vz = (int32_t)z * VBJ_FIX_ONE;
                uint32_t b = VBJ_NONE;
                int decided = 0;
                if (!far) {
                    float d1 = INFINITY, d2 = INFINITY;
                    for (size_t i = 0; i < ns; i++) {
                        const int32_t *e = w->surv + 4 * i;
                        float yz = vbj_xt_yz((float)vy - (float)e[1], (float)vz - (float)e[2]);
                        vbj_xt_offer(vbj_xt_dist((float)vx - (float)e[0], yz), (uint32_t)e[3], &d1,
                                     &d2, &b);
                    }
                    w->cnt[VBJ_XT_C_EVALS] += ns;
                    decided = vbj_xt_decided(d1, d2);
                }
                if (!decided) {
                    b = exact_among(w->surv, ns, vx, vy, vz);
                    w->cnt[VBJ_XT_C_EXACT]++;
                }
                row[x] = b;
            }
        }
}

int vbj_tiles_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_tiles_prep *p, vbj_result *out)
{
    job *J = calloc(1, sizeof *J);
    out->labels = malloc(out->pixels * sizeof *out->labels);
    if (!J || !out->labels) {
        free(J);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "exact engine: out of memory");
    }
    J->p = p;
    J->n = s->n;
    J->dim = (uint32_t)s->dim;
    J->T = s->n >> p->ts;
    J->labels = out->labels;
    size_t tiles = (size_t)J->T * J->T * (s->dim == 3 ? J->T : 1);
    int nt = vb_threads(0);
    vb_parallel_for(tile, J, tiles, nt);
    int rc = VB_OK;
    uint64_t cnt[VBJ_XT_NC] = {0};
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        if (J->th[t].failed)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "exact engine: out of memory");
        for (int i = 0; i < VBJ_XT_NC; i++)
            cnt[i] += J->th[t].cnt[i];
        free(J->th[t].surv);
    }
    free(J);
    vbj_tiles_counts(s, p, cnt, &out->counts);
    return rc;
}

void vbj_tiles_counts(const vbj_seeds *s, const vbj_tiles_prep *p, const uint64_t *cnt,
                      vbj_counts *c)
{
    uint32_t T = s->n >> p->ts, S = 1u << p->ts;
    uint64_t tiles = (uint64_t)T * T * (s->dim == 3 ? T : 1);
    uint64_t per = (uint64_t)S * S * (s->dim == 3 ? S : 1);
    uint64_t row = S < VBJ_XT_ROW ? S : VBJ_XT_ROW;
    c->steps = 1;
    c->tiles = tiles;
    c->tiles_uniform = cnt[VBJ_XT_C_UNIFORM];
    c->candidates = cnt[VBJ_XT_C_CAND];
    c->survivors = cnt[VBJ_XT_C_SURV];
    c->evals = cnt[VBJ_XT_C_EVALS];
    c->exact_voxels = cnt[VBJ_XT_C_EXACT];
    c->tiles_chunked = cnt[VBJ_XT_C_CHUNKED];
    c->visited = cnt[VBJ_XT_C_VISITED];
    c->step_pixels = (tiles - c->tiles_uniform) * per;
    c->threads += tiles * (per / row);
}
