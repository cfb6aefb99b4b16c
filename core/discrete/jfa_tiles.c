/* The exact tiled engine ("exact", "exact-boundary"): the host preparation
 * both backends share (the seed grid in bucket order) and the plain-C twin
 * of gpu/jfa_tiles.cl, tile by tile with the decisions of vbj_tiles.h (the
 * proofs are there). Tiles are independent, so they run on threads; labels
 * and counts do not depend on the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbj_prep.h"
#include "vbj_tiles.h"

void vbj_tiles_prep_free(vbj_tiles_prep *p)
{
    free(p->start);
    free(p->recs);
    free(p->ring0);
    memset(p, 0, sizeof *p);
}

/* ring0: the chessboard distance transform of the occupied buckets on the
 * g^d bucket grid, saturated at VBJ_XT_RING0_MAX. Two raster passes with the
 * unit 3^d mask (Rosenfeld and Pfaltz): the forward pass takes the
 * neighbours before a bucket in raster order, the backward pass those after
 * it; with unit weights this is the chessboard distance exactly (a shortest
 * king's path to the nearest occupied bucket is monotone in every axis, so
 * one of the two passes carries it), and saturation only lowers values
 * above the cap to the cap. */
static void ring0_build(const vbj_tiles_prep *p, uint32_t dim)
{
    int32_t g = (int32_t)p->g, gz = dim == 3 ? g : 1;
    uint8_t *d = p->ring0;
    for (size_t b = 0; b < p->nbuckets; b++)
        d[b] = p->start[b + 1] > p->start[b] ? 0 : (uint8_t)VBJ_XT_RING0_MAX;
    for (int pass = 0; pass < 2; pass++) {
        int32_t step = pass ? -1 : 1;
        for (int32_t zi = 0; zi < gz; zi++)
            for (int32_t yi = 0; yi < g; yi++)
                for (int32_t xi = 0; xi < g; xi++) {
                    int32_t z = pass ? gz - 1 - zi : zi, y = pass ? g - 1 - yi : yi;
                    int32_t x = pass ? g - 1 - xi : xi;
                    size_t b = ((size_t)z * (size_t)g + (size_t)y) * (size_t)g + (size_t)x;
                    unsigned best = d[b];
                    if (best == 0)
                        continue;
                    /* The neighbours already visited in this pass's order:
                     * the layer before (all 3^(d-1)), the row before in this
                     * layer (3), the bucket before in this row. */
                    for (int32_t dz = dim == 3 ? -1 : 0; dz <= 0; dz++)
                        for (int32_t dy = -1; dy <= (dz ? 1 : 0); dy++)
                            for (int32_t dx = -1; dx <= (dz || dy ? 1 : -1); dx++) {
                                int32_t nz = z + step * dz, ny = y + step * dy, nx = x + step * dx;
                                if (nz < 0 || nz >= gz || ny < 0 || ny >= g || nx < 0 || nx >= g)
                                    continue;
                                unsigned v = d[((size_t)nz * (size_t)g + (size_t)ny) * (size_t)g +
                                               (size_t)nx] +
                                             1u;
                                best = v < best ? v : best;
                            }
                    d[b] = (uint8_t)best;
                }
    }
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
    out->ring0 = malloc(out->nbuckets);
    if (!out->recs || !out->ring0) {
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
    ring0_build(out, dim);
    return VB_OK;
}

/* One run of the twin. */
typedef struct {
    int32_t *surv; /* survivors: rx, ry, rz, index */
    size_t cap;
    float *row;    /* per survivor of the tile: its x, then its yz of the row */
    size_t rowcap;
    uint64_t cnt[VBJ_XT_NC];
    int failed;
} scratch;

typedef struct {
    const vbj_tiles_prep *p;
    uint32_t n, dim, T; /* T tiles per axis */
    uint32_t *labels;
    const uint8_t *need; /* per voxel, nonzero where a label is wanted; NULL: all */
    uint8_t *boxes;      /* need_boxes' answer per tile (NULL: need_box asks) */
    scratch th[VB_MAX_THREADS];
} job;

static int push(scratch *w, size_t i, const int32_t r[4])
{
    w->surv = vb_array_grow(w->surv, &w->cap, i + 1, 4 * sizeof *w->surv, 256);
    if (w->cap < i + 1)
        return -1;
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

/* The bound U^2 and the centre owner (cd its distance, cs its index, c its
 * record) as a search goes. */
typedef struct {
    uint64_t u2, cd;
    uint32_t cs;
    const int32_t *c;
} bound_state;

/* Adds the seeds of the block of radius R less the block of radius Rin
 * around bucket b0 to st. */
static void bound_pass(const vbj_tiles_prep *p, vbj_xt_box box, const int32_t *cen,
                       const int32_t *b0, int32_t R, int32_t Rin, uint32_t dim, bound_state *st,
                       scratch *w)
{
    for (uint32_t u = 0, m = vbj_xt_units(R, Rin, dim); u < m; u++) {
        int32_t f, l;
        if (!vbj_xt_unit(b0[0], b0[1], b0[2], R, Rin, u, (int32_t)p->g, dim, &f, &l))
            continue;
        for (uint32_t j = p->start[f]; j < p->start[l + 1]; j++) {
            const int32_t *e = p->recs + 4 * (size_t)j;
            uint64_t n2, f2;
            vbj_xt_bounds(box, e[0], e[1], e[2], dim, &n2, &f2);
            st->u2 = f2 < st->u2 ? f2 : st->u2;
            uint64_t d = vbj_dist2(cen[0], cen[1], cen[2], e[0], e[1], e[2]);
            if (vbj_better(d, (uint32_t)e[3], st->cd, st->cs)) {
                st->cd = d;
                st->cs = (uint32_t)e[3];
                st->c = e;
            }
            w->cnt[VBJ_XT_C_VISITED]++;
        }
    }
}

/* Nonzero when one of the m bytes at b is. */
static int any_byte(const uint8_t *b, uint32_t m)
{
    uint32_t i = 0;
    for (uint64_t w; i + 8 <= m; i += 8) {
        memcpy(&w, b + i, sizeof w);
        if (w)
            return 1;
    }
    for (; i < m; i++)
        if (b[i])
            return 1;
    return 0;
}

/* The box of the wanted voxels of the tile whose first voxel is `first`:
 * 0 when it has none, else 1 with their least and greatest offsets per
 * axis in lo and hi (0 in z in 2D). */
static int need_box(const uint8_t *need, size_t first, uint32_t n, uint32_t S, uint32_t sz,
                    uint32_t lo[3], uint32_t hi[3])
{
    int any = 0;
    for (int a = 0; a < 3; a++) {
        lo[a] = S;
        hi[a] = 0;
    }
    for (uint32_t z = 0; z < sz; z++)
        for (uint32_t y = 0; y < S; y++) {
            const uint8_t *row = need + first + ((size_t)z * n + y) * n;
            if (!any_byte(row, S))
                continue;
            for (uint32_t x = 0; x < S; x++)
                if (row[x]) {
                    lo[0] = x < lo[0] ? x : lo[0];
                    hi[0] = x > hi[0] ? x : hi[0];
                }
            lo[1] = y < lo[1] ? y : lo[1];
            hi[1] = y > hi[1] ? y : hi[1];
            lo[2] = any ? lo[2] : z;
            hi[2] = z;
            any = 1;
        }
    return any;
}

/* need_box's answer for every tile in one pass over need in memory order,
 * eight voxels at a time (a tile's side is a multiple of eight, so an
 * aligned word lies in one tile): per tile lo[0..2] then hi[0..2], lo[0] =
 * 0xff when it has none. The least and greatest offsets per axis over the
 * wanted voxels do not depend on the order they are met in. The side S
 * must be 8 or 16, the grid n a multiple of it. */
static void need_boxes(const uint8_t *need, uint32_t n, uint32_t dim, uint32_t ts, uint8_t *boxes)
{
    uint32_t S = 1u << ts, T = n >> ts, nz = dim == 3 ? n : 1;
    size_t tiles = (size_t)T * T * (dim == 3 ? T : 1);
    for (size_t t = 0; t < tiles; t++) {
        uint8_t *b = boxes + 6 * t;
        b[0] = b[1] = b[2] = 0xff;
        b[3] = b[4] = b[5] = 0;
    }
    for (uint32_t z = 0; z < nz; z++)
        for (uint32_t y = 0; y < n; y++) {
            const uint8_t *row = need + ((size_t)z * n + y) * n;
            size_t trow = (size_t)T * ((y >> ts) + (size_t)T * (z >> ts));
            uint8_t oy = (uint8_t)(y & (S - 1)), oz = (uint8_t)(z & (S - 1));
            for (uint32_t x0 = 0; x0 < n; x0 += 8) {
                uint64_t w, q[4];
                /* Four words at once where none wants a label. */
                if (x0 % 32 == 0 && x0 + 32 <= n) {
                    memcpy(q, row + x0, sizeof q);
                    if (!(q[0] | q[1] | q[2] | q[3])) {
                        x0 += 24;
                        continue;
                    }
                }
                memcpy(&w, row + x0, sizeof w);
                if (!w)
                    continue;
                int first = 0, last = 7;
                while (!row[x0 + (uint32_t)first])
                    first++;
                while (!row[x0 + (uint32_t)last])
                    last--;
                uint8_t *b = boxes + 6 * (trow + (x0 >> ts)), ox = (uint8_t)(x0 & (S - 1));
                uint8_t lo = (uint8_t)(ox + first), hi = (uint8_t)(ox + last);
                if (b[0] == 0xff) { /* the tile's first: y and z grow from here */
                    b[0] = lo;
                    b[1] = oy;
                    b[2] = oz;
                }
                b[0] = lo < b[0] ? lo : b[0];
                b[3] = hi > b[3] ? hi : b[3];
                b[1] = oy < b[1] ? oy : b[1];
                b[4] = oy > b[4] ? oy : b[4];
                b[5] = oz > b[5] ? oz : b[5];
            }
        }
}

/* The filter's state (d1, d2, b of vbj_xt_offer) of the eight voxels x0
 * .. x0 + 7 of a row over the ns survivors (their x in ex, the row's yz
 * in yzs): for each voxel the very operations of one voxel's loop, in its
 * order, so the same states. The voxels are independent lanes: with GNU C
 * vectors, four at a time (IEEE single lanes, no contraction: each lane
 * rounds as the scalar does; the selects are vbj_xt_offer's, by masks). */
static void offer_block(const float *ex, const float *yzs, const int32_t *surv, size_t ns,
                        uint32_t x0, float d1[8], float d2[8], uint32_t b[8])
{
#if defined(__GNUC__)
    typedef float vf __attribute__((vector_size(16)));
    typedef int32_t vi __attribute__((vector_size(16)));
    for (int h = 0; h < 8; h += 4) {
        vf fx, e1 = {INFINITY, INFINITY, INFINITY, INFINITY}, e2 = e1;
        vi bv = {(int32_t)VBJ_NONE, (int32_t)VBJ_NONE, (int32_t)VBJ_NONE, (int32_t)VBJ_NONE};
        for (int l = 0; l < 4; l++)
            fx[l] = (float)((int32_t)(x0 + (uint32_t)(h + l)) * VBJ_FIX_ONE);
        for (size_t i = 0; i < ns; i++) {
            vf dx = fx - ex[i], d = dx * dx + yzs[i];
            vi lt = d < e1, v = (vi){0, 0, 0, 0} + surv[4 * i + 3];
            vf hi = (vf)((lt & (vi)e1) | (~lt & (vi)d));
            vi lo2 = hi < e2;
            e2 = (vf)((lo2 & (vi)hi) | (~lo2 & (vi)e2));
            bv = (lt & v) | (~lt & bv);
            e1 = (vf)((lt & (vi)d) | (~lt & (vi)e1));
        }
        for (int l = 0; l < 4; l++) {
            d1[h + l] = e1[l];
            d2[h + l] = e2[l];
            b[h + l] = (uint32_t)bv[l];
        }
    }
#else
    float fx[8];
    for (int l = 0; l < 8; l++) {
        fx[l] = (float)((int32_t)(x0 + (uint32_t)l) * VBJ_FIX_ONE);
        d1[l] = d2[l] = INFINITY;
        b[l] = VBJ_NONE;
    }
    for (size_t i = 0; i < ns; i++)
        for (int l = 0; l < 8; l++)
            vbj_xt_offer(vbj_xt_dist(fx[l] - ex[i], yzs[i]), (uint32_t)surv[4 * i + 3], &d1[l],
                         &d2[l], &b[l]);
#endif
}

static void tile(void *arg, size_t t, int tid)
{
    job *J = arg;
    scratch *w = &J->th[tid];
    const vbj_tiles_prep *p = J->p;
    uint32_t dim = J->dim, T = J->T, S = 1u << p->ts;
    uint32_t tc[3] = {(uint32_t)(t % T), (uint32_t)(t / T % T),
                      dim == 3 ? (uint32_t)(t / ((size_t)T * T)) : 0};
    uint32_t n = J->n, sz = dim == 3 ? S : 1;
    size_t first = ((size_t)(tc[2] << p->ts) * n + (tc[1] << p->ts)) * n + (tc[0] << p->ts);
    /* tb, the tile's box, places the survivors; box, the searches and
     * tests: the tile's, or with a need mask the box of its wanted voxels
     * (inside the tile, so inside bucket b0: every bound of vbj_tiles.h
     * holds for it, and the owner of each of its voxels survives). */
    vbj_xt_box tb = vbj_xt_tile_box(tc[0], tc[1], tc[2], p->ts, dim), box = tb;
    int32_t cen[3];
    for (int a = 0; a < 3; a++)
        cen[a] = a < (int)dim ? box.lo[a] + (int32_t)(S / 2) * VBJ_FIX_ONE : 0;
    if (J->need) {
        uint32_t lo[3], hi[3];
        if (J->boxes) {
            const uint8_t *b = J->boxes + 6 * t;
            if (b[0] == 0xff)
                return;
            for (int a = 0; a < 3; a++) {
                lo[a] = b[a];
                hi[a] = b[3 + a];
            }
        } else if (!need_box(J->need, first, n, S, sz, lo, hi)) {
            return;
        }
        /* cen: a voxel centre of the box, so its owner c is a candidate
         * (|cen - c| <= U) and survives. */
        for (int a = 0; a < (int)dim; a++) {
            box.lo[a] = tb.lo[a] + (int32_t)lo[a] * VBJ_FIX_ONE;
            box.hi[a] = tb.lo[a] + (int32_t)hi[a] * VBJ_FIX_ONE;
            cen[a] = tb.lo[a] + (int32_t)((lo[a] + hi[a] + 1) / 2) * VBJ_FIX_ONE;
        }
    }
    int32_t g = (int32_t)p->g, b0[3];
    for (int a = 0; a < 3; a++)
        b0[a] = a < (int)dim ? (int32_t)((tc[a] << p->ts) >> p->bs) : 0;
    int32_t r0 = p->ring0[((size_t)b0[2] * p->g + (size_t)b0[1]) * p->g + (size_t)b0[0]];

    /* (A) The block of radius r0 (more rings only past the saturation of
     * ring0), (B) grown to R1: U^2 and the centre's owner (vbj_tiles.h). */
    bound_state st = {UINT64_MAX, UINT64_MAX, VBJ_NONE, NULL};
    int32_t R = r0, Rin = -1;
    for (;;) {
        bound_pass(p, box, cen, b0, R, Rin, dim, &st, w);
        int32_t next = vbj_xt_next(box, b0[0], b0[1], b0[2], R, p->bs, g, dim, st.u2);
        if (next == R)
            break;
        Rin = R;
        R = next;
    }
    uint64_t u2 = st.u2;
    uint32_t cs = st.cs;
    const int32_t *c = st.c;
    R = vbj_xt_radius(box, b0[0], b0[1], b0[2], r0, p->bs, g, dim, u2);

    /* (C) The block of radius R2: candidates, then survivors of the
     * dominance test. */
    size_t ns = 0;
    int far = 0;
    for (uint32_t u = 0, m = vbj_xt_units(R, -1, dim); u < m; u++) {
        int32_t f, l;
        if (!vbj_xt_unit(b0[0], b0[1], b0[2], R, -1, u, g, dim, &f, &l))
            continue;
        for (uint32_t j = p->start[f]; j < p->start[l + 1]; j++) {
            const int32_t *e = p->recs + 4 * (size_t)j;
            uint64_t n2, f2;
            uint32_t v = (uint32_t)e[3];
            w->cnt[VBJ_XT_C_VISITED]++;
            vbj_xt_bounds(box, e[0], e[1], e[2], dim, &n2, &f2);
            if (n2 > u2)
                continue;
            w->cnt[VBJ_XT_C_CAND]++;
            if (v != cs && vbj_xt_dominated(box, c[0], c[1], c[2], cs, e[0], e[1], e[2], v, dim))
                continue;
            int32_t r[4] = {e[0] - tb.lo[0], e[1] - tb.lo[1], e[2] - tb.lo[2], (int32_t)v};
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

    /* The survivors' x and, per row, their yz (the same float operations
     * as per voxel, done once a row: the same distances). */
    if (ns > 1 && !far && 2 * ns > w->rowcap) {
        float *m = realloc(w->row, 2 * ns * sizeof *m);
        if (!m) {
            w->failed = 1;
            return;
        }
        w->row = m;
        w->rowcap = 2 * ns;
    }
    float *ex = w->row, *yzs = w->row + ns;
    if (ns > 1 && !far)
        for (size_t i = 0; i < ns; i++)
            ex[i] = (float)w->surv[4 * i];

    /* Every voxel of the tile (every wanted one). */
    for (uint32_t z = 0; z < sz; z++)
        for (uint32_t y = 0; y < S; y++) {
            size_t r0 = first + ((size_t)z * n + y) * n;
            uint32_t *row = J->labels + r0;
            const uint8_t *want = J->need ? J->need + r0 : NULL;
            if (want && !any_byte(want, S))
                continue;
            if (ns > 1 && !far)
                for (size_t i = 0; i < ns; i++) {
                    const int32_t *e = w->surv + 4 * i;
                    yzs[i] = vbj_xt_yz((float)((int32_t)y * VBJ_FIX_ONE) - (float)e[1],
                                       (float)((int32_t)z * VBJ_FIX_ONE) - (float)e[2]);
                }
            /* The filter eight voxels at a time where the side allows. */
            int block = ns > 1 && !far && S % 8 == 0;
            float bd1[8], bd2[8];
            uint32_t bb[8];
            for (uint32_t x = 0; x < S; x++) {
                if (block && x % 8 == 0) {
                    if (want && !any_byte(want + x, 8)) {
                        x += 7;
                        continue;
                    }
                    offer_block(ex, yzs, w->surv, ns, x, bd1, bd2, bb);
                }
                if (want && !want[x])
                    continue;
                if (ns == 1) {
                    row[x] = cs;
                    continue;
                }
                int32_t vx = (int32_t)x * VBJ_FIX_ONE, vy = (int32_t)y * VBJ_FIX_ONE;
                int32_t vz = (int32_t)z * VBJ_FIX_ONE;
                uint32_t b = VBJ_NONE;
                int decided = 0;
                if (!far) {
                    float d1 = INFINITY, d2 = INFINITY, fx = (float)vx;
                    if (block) {
                        d1 = bd1[x % 8];
                        d2 = bd2[x % 8];
                        b = bb[x % 8];
                    } else {
                        for (size_t i = 0; i < ns; i++)
                            vbj_xt_offer(vbj_xt_dist(fx - ex[i], yzs[i]),
                                         (uint32_t)w->surv[4 * i + 3], &d1, &d2, &b);
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

int vbj_tiles_ref_run(vb_ctx *ctx, const vbj_seeds *s, const vbj_tiles_prep *p, const uint8_t *need,
                      vbj_result *out)
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
    J->need = need;
    size_t tiles = (size_t)J->T * J->T * (s->dim == 3 ? J->T : 1);
    uint32_t S = 1u << p->ts;
    /* Without room for the boxes each tile finds its own (need_box). */
    if (need && (S == 8 || S == 16) && s->n % S == 0)
        J->boxes = malloc(6 * tiles);
    if (J->boxes)
        need_boxes(need, s->n, J->dim, p->ts, J->boxes);
    int nt = vb_threads(0);
    vb_parallel_for(tile, J, tiles, nt);
    free(J->boxes);
    int rc = VB_OK;
    uint64_t cnt[VBJ_XT_NC] = {0};
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        if (J->th[t].failed)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "exact engine: out of memory");
        for (int i = 0; i < VBJ_XT_NC; i++)
            cnt[i] += J->th[t].cnt[i];
        free(J->th[t].surv);
        free(J->th[t].row);
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
