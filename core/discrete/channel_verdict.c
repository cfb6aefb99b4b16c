/* The pore verdict (vbc_pore.h): whether a swept path crosses the molecule
 * as a pore, walled by its atoms over a buried length, or only wanders
 * through grooves and packing gaps of a molecule that has no pore. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbc_walls.h"

/* The slack of the free-distance bounds below, A: far above the rounding
 * of a pixel's position (coordinates below 1e4 A: 1e-11 A) and of a
 * distance, far below the pixel. */
#define FREE_EPS 1e-6

void vbc_plane_basis(const double u[3], double a[3], double b[3])
{
    double t[3] = {1.0, 0.0, 0.0};
    if (fabs(u[0]) > 0.9) {
        t[0] = 0.0;
        t[1] = 1.0;
    }
    a[0] = u[1] * t[2] - u[2] * t[1];
    a[1] = u[2] * t[0] - u[0] * t[2];
    a[2] = u[0] * t[1] - u[1] * t[0];
    double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= na;
    b[0] = u[1] * a[2] - u[2] * a[1];
    b[1] = u[2] * a[0] - u[0] * a[2];
    b[2] = u[0] * a[1] - u[1] * a[0];
}

int vbc_plane_walled(const vbc_cells *c, const double u[3], const double p[3], double r,
                     void **scratch, size_t *scratch_len)
{
    return vbc_plane_walled_raster(c, u, p, r, -1, NULL, NULL, scratch, scratch_len);
}

/* What a flood keeps in its scratch for the next one. The planes of a
 * pore lie a step apart along one axis, their pixels in one basis, so
 * pixel (i, j) of the next plane is the same pixel moved by exactly the
 * centres' difference d = p' - p: its distance to every atom surface
 * moves by at most |d|. A pixel the last flood proved free (lower bound
 * `low`) or blocked (an atom's surface within `high` of it) keeps its
 * answer unasked when low - |d| still clears the probe, or high + |d|
 * still falls within it: the answer the cell list would give (a bound
 * spares only the query whose answer it proves; the slack FREE_EPS
 * covers the rounding of |d| and of the pixels' positions, as in the
 * flood's own bounds). Planes with another axis, or more than
 * MEMORY_REACH apart, start afresh.
 *
 * The scratch: this header, then per pixel of a square of half side N
 * (the largest flood so far) low, high, the flood that set them (`known`),
 * the flood that saw it (`seen`), the stack. Floods are numbered: a pixel
 * is seen in this flood when seen[] holds its number (no clearing between
 * floods), known from the last when known[] holds the last number. */
typedef struct flood_memory {
    int N;                  /* half side of the arrays */
    uint32_t flood;         /* this flood's number (0: none yet) */
    int have;               /* the last flood's plane: */
    double u[3], p[3];      /* its axis and centre */
} flood_memory;

/* Beyond this the bounds carried from the last plane rarely decide a
 * pixel (it is a probe's width and more), and the lookups are spared. */
#define MEMORY_REACH 1.0

/* A pixel waiting on the flood's stack: asked when taken, with the lower
 * bound its neighbour gave (-inf beside the pore's sphere). */
typedef struct flood_item {
    double near;
    int32_t w;
} flood_item;

static size_t memory_bytes(int N)
{
    size_t side = (size_t)(2 * N + 1), npix = side * side;
    return sizeof(flood_memory) +
           npix * (2 * sizeof(double) + 2 * sizeof(uint32_t) + sizeof(flood_item));
}

/* The scratch fitted to a flood of half side n: grown (and forgotten)
 * when smaller; NULL out of memory. */
static flood_memory *memory_fit(void **scratch, size_t *scratch_len, int n)
{
    flood_memory *F = *scratch;
    if (F && *scratch_len >= sizeof *F && F->N >= n && F->flood < UINT32_MAX - 1)
        return F;
    size_t need = memory_bytes(n);
    void *m = need > *scratch_len ? realloc(*scratch, need) : *scratch;
    if (!m)
        return NULL;
    *scratch = m;
    if (need > *scratch_len)
        *scratch_len = need;
    memset(m, 0, need);
    F = m;
    F->N = n;
    return F;
}

/* Whether pixel (i, j) lies in the pore's own sphere of radius rr (its
 * pixels free whatever the atoms). Exact: i / 2 and j / 2 and their
 * squares are exact doubles. */
static inline int in_sphere(int i, int j, double rr)
{
    double x = i * VBC_WALL_PIXEL, y = j * VBC_WALL_PIXEL;
    return !(x * x + y * y > rr * rr);
}

/* The largest j >= 0 with (i, j) in the sphere, or -1. */
static int sphere_row(int i, double rr)
{
    double x = i * VBC_WALL_PIXEL, h = rr * rr - x * x;
    int j = h >= 0.0 ? (int)(sqrt(h) / VBC_WALL_PIXEL) : -1;
    while (j >= 0 && !in_sphere(i, j, rr))
        j--;
    while (in_sphere(i, j + 1, rr))
        j++;
    return j;
}

int vbc_plane_walled_raster(const vbc_cells *c, const double u[3], const double p[3], double r,
                            int m, const uint32_t *blocked, const uint32_t *unsure, void **scratch,
                            size_t *scratch_len)
{
    double a[3], b[3];
    vbc_plane_basis(u, a, b);
    double rr = r > 0.0 ? r : 0.0;
    int n = vbc_plane_raster_half(r);
    flood_memory *F = memory_fit(scratch, scratch_len, n);
    if (!F)
        return -1;
    int N = F->N;
    size_t side = (size_t)(2 * N + 1), npix = side * side;
    double *low = (double *)(F + 1), *high = low + npix;
    uint32_t *known = (uint32_t *)(high + npix), *seen = known + npix;
    flood_item *stack = (flood_item *)(seen + npix);
    /* The last flood's bounds hold here moved by |d| (and the slack). */
    uint32_t last = F->flood, now = ++F->flood;
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += (p[k] - F->p[k]) * (p[k] - F->p[k]);
    int carry = F->have && last > 0 && memcmp(F->u, u, sizeof F->u) == 0 &&
                d2 <= MEMORY_REACH * MEMORY_REACH;
    double shift = carry ? sqrt(d2) + FREE_EPS : INFINITY;
    memcpy(F->u, u, sizeof F->u);
    memcpy(F->p, p, sizeof F->p);
    F->have = 1;
    int32_t hint = -1;
    double edge2 = (double)(n - 1) * (double)(n - 1);
    /* The sphere's pixels are free and connected: the flood starts on the
     * pixels beside it (row i: past the sphere's own span, and under the
     * spans of the rows above and below), never entering it. A sphere
     * that reaches the edge itself is not walled. */
    int R = (int)(rr / VBC_WALL_PIXEL) + 1;
    for (int i = -R; i <= R; i++) {
        int here = sphere_row(i, rr);
        if (here >= 0 && (double)i * i + (double)here * here >= edge2)
            return 0;
    }
    /* Else every pixel beside it lies within the edge (and the arrays). */
    size_t top = 0;
    int below = -1, here = sphere_row(-R - 1, rr);
    for (int i = -R - 1; i <= R + 1; i++) {
        int above = i < R + 1 ? sphere_row(i + 1, rr) : -1;
        int most = below > above ? below : above;
        if (here >= 0 && here + 1 > most)
            most = here + 1;
        for (int j = here + 1; j <= most; j++)
            for (int sgn = 1; sgn >= (j > 0 ? -1 : 1); sgn -= 2) {
                int32_t w = (int32_t)((size_t)(i + N) * side + (size_t)(sgn * j + N));
                seen[w] = now;
                stack[top].near = -INFINITY;
                stack[top++].w = w;
            }
        below = here;
        here = above;
    }
    /* Whether the free pixels connected to the sphere reach the edge does
     * not depend on the order they are visited in (a pixel's freedom is
     * its own: the bounds below only spare the query whose answer they
     * prove), so the search goes depth first, a pixel asked when taken,
     * the outward step last pushed (first taken): an open plane is left in
     * about n steps. */
    while (top > 0) {
        flood_item e = stack[--top];
        int32_t v = e.w;
        int i = (int)(v / (int32_t)side) - N, j = (int)(v % (int32_t)side) - N;
        /* The last plane's bounds, moved (none: -inf, +inf). */
        double was_low = -INFINITY, was_high = INFINITY;
        if (known[v] == last && carry) {
            was_low = low[v] - shift;
            was_high = high[v] + shift;
        }
        known[v] = now;
        low[v] = -INFINITY;
        high[v] = INFINITY;
        double x = i * VBC_WALL_PIXEL, y = j * VBC_WALL_PIXEL;
        if (blocked && abs(i) <= m && abs(j) <= m) {
            /* The raster's answer; the cell list's where it is unsure. */
            size_t rv = (size_t)(i + m) * (size_t)(2 * m + 1) + (size_t)(j + m);
            uint32_t bit = 1u << (rv & 31);
            if (blocked[rv >> 5] & bit)
                continue;
            if (unsure[rv >> 5] & bit) {
                double q[3], lw;
                for (int d = 0; d < 3; d++)
                    q[d] = p[d] + x * a[d] + y * b[d];
                if (vbc_cells_any_within(c, q, VBC_WALL_PROBE, &hint, &lw))
                    continue;
            }
        } else {
            /* A pixel is free when no atom surface comes within the probe:
             * proved by a bound (its neighbour's less a pixel, the distance
             * moving no faster than the point; the last plane's), else
             * asked of the cell list. */
            double lo = e.near > was_low ? e.near : was_low;
            if (lo > VBC_WALL_PROBE + FREE_EPS) {
                low[v] = lo;
            } else if (was_high <= VBC_WALL_PROBE) {
                high[v] = was_high;
                continue;
            } else {
                double q[3], lw;
                for (int d = 0; d < 3; d++)
                    q[d] = p[d] + x * a[d] + y * b[d];
                if (vbc_cells_any_within(c, q, VBC_WALL_PROBE, &hint, &lw)) {
                    /* The atom found: its surface within `high`. */
                    const vb_sphere_set *s = vbc_cells_spheres(c);
                    double dx = q[0] - s->x[hint], dy = q[1] - s->y[hint], dz = q[2] - s->z[hint];
                    high[v] = sqrt(dx * dx + dy * dy + dz * dz) - s->r[hint] + FREE_EPS;
                    continue;
                }
                low[v] = lw - FREE_EPS;
            }
        }
        if ((double)i * i + (double)j * j >= edge2)
            return 0; /* a disc of the wall probe got out: not walled */
        double near = low[v] - VBC_WALL_PIXEL - FREE_EPS;
        /* The four steps, the outward one (along the larger of |i|, |j|,
         * away from the centre) last; then the other of that axis first. */
        int si = i >= 0 ? 1 : -1, sj = j >= 0 ? 1 : -1, step[4][2];
        if (abs(i) >= abs(j)) {
            step[0][0] = -si, step[0][1] = 0;
            step[1][0] = 0, step[1][1] = -sj;
            step[2][0] = 0, step[2][1] = sj;
            step[3][0] = si, step[3][1] = 0;
        } else {
            step[0][0] = 0, step[0][1] = -sj;
            step[1][0] = -si, step[1][1] = 0;
            step[2][0] = si, step[2][1] = 0;
            step[3][0] = 0, step[3][1] = sj;
        }
        for (int k = 0; k < 4; k++) {
            int ii = i + step[k][0], jj = j + step[k][1];
            int32_t w = (int32_t)((size_t)(ii + N) * side + (size_t)(jj + N));
            if (seen[w] == now || in_sphere(ii, jj, rr))
                continue;
            seen[w] = now;
            stack[top].near = near;
            stack[top++].w = w;
        }
    }
    return 1;
}

int vbc_pore_threads(size_t items, size_t per)
{
    int nt = vb_threads(0);
    size_t most = items / (per ? per : 1);
    if (nt < VBC_PORE_MIN_THREADS || most < 2)
        return 1;
    return (size_t)nt > most ? (int)most : nt;
}

/* The planes [k0, k0 + n) of a pore flooded at once: the planes in runs of
 * JUDGE_RUN, run t on thread t mod nt (runs dealt round, so that the walled
 * planes, which cost the most and lie together, spread over the threads),
 * each thread with its own scratch (a run's planes one after the other:
 * each flood starts from the last one's bounds, flood_memory); walled[i]
 * gets vbc_plane_walled's answer (a plane's answer is its own, so the
 * verdict scanning them in order is the one-plane-at-a-time verdict). */
typedef struct {
    const vbc_cells *c;
    const vbc_pore *p;
    const vbc_walls_input *in; /* with R: the planes' rasters (NULL: none) */
    const vbc_walls_raster *R;
    size_t k0, m;
    int nmax; /* the largest raster half side of the pore's planes */
    int8_t *walled;
    void *scratch[VB_MAX_THREADS];
    size_t len[VB_MAX_THREADS];
} judge_block;

static void judge_plane(void *ctx, size_t i, int tid)
{
    judge_block *B = ctx;
    size_t k = B->k0 + i;
    const vbc_pore_point *q = &B->p->pts[k];
    double at[3] = {q->x, q->y, q->z};
    const uint32_t *bl = B->R ? B->R->blocked + B->in->word0[k] : NULL;
    const uint32_t *un = B->R ? B->R->unsure + B->in->word0[k] : NULL;
    int m = B->R ? B->in->half[k] : -1;
    /* Sized once for every plane (a scratch that grows forgets). */
    if (!memory_fit(&B->scratch[tid], &B->len[tid], B->nmax))
        B->walled[i] = -1;
    else
        B->walled[i] = (int8_t)vbc_plane_walled_raster(B->c, B->p->axis.u, at, q->r, m, bl, un,
                                                       &B->scratch[tid], &B->len[tid]);
}

/* The threads: a thread costs a start and a join (tens of microseconds,
 * milliseconds on a loaded machine) against a few to tens of microseconds
 * a plane, so a pore of fewer than this many planes a thread is judged on
 * fewer threads (on one: plane by plane, as it stops). The scan may stop
 * early (enough), so the threads flood a block before it is scanned: the
 * first block one run (JUDGE_RUN planes) a thread, each next one twice
 * the last, up to this many planes a thread. Past the plane where the scan
 * stops at most a block is flooded in vain (#33: 1chb at 128^3 stops at
 * its 80th of 141 planes; on 4 threads, blocks of 4 x 32 planes flooded
 * 128, blocks of 32 then 64 planes flood 96), and a verdict that floods
 * every plane (no pore) waits on at most two joins more. */
#define JUDGE_PLANES_PER_THREAD 32
#define JUDGE_RUN 8

static void judge_run(void *ctx, size_t t, int tid)
{
    judge_block *B = ctx;
    for (size_t i = t * JUDGE_RUN; i < (t + 1) * JUDGE_RUN && i < B->m; i++)
        judge_plane(B, i, tid);
}

/* vbc_pore_judge, the pixels from the rasters R of in when R is not NULL. */
static int judge(const vbc_cells *c, const vbc_pore *p, const vbc_walls_input *in,
                 const vbc_walls_raster *R, double enough, vbc_pore_verdict *v)
{
    memset(v, 0, sizeof *v);
    int nt = vbc_pore_threads(p->n, JUDGE_PLANES_PER_THREAD);
    size_t block = nt > 1 ? (size_t)nt * JUDGE_RUN : 1,
           most = nt > 1 ? (size_t)nt * JUDGE_PLANES_PER_THREAD : 1;
    int8_t *walled = malloc(most);
    judge_block B = {c, p, in, R, 0, 0, 0, walled, {NULL}, {0}};
    for (size_t k = 0; k < p->n; k++) {
        int h = vbc_plane_raster_half(p->pts[k].r);
        B.nmax = h > B.nmax ? h : B.nmax;
    }
    size_t lo = 0, last = 0;
    int in_run = 0, have = 0, rc = walled ? 0 : -1, done = 0;
    for (size_t k0 = 0; rc == 0 && !done && k0 < p->n;
         k0 += block, block = 2 * block < most ? 2 * block : most) {
        size_t m = p->n - k0 < block ? p->n - k0 : block;
        B.k0 = k0;
        B.m = m;
        if (m > 1) {
            size_t runs = (m + JUDGE_RUN - 1) / JUDGE_RUN;
            vb_parallel_for(judge_run, &B, runs, (int)(runs < (size_t)nt ? runs : (size_t)nt));
        }
        else
            judge_plane(&B, 0, 0);
        for (size_t i = 0; i < m; i++) {
            size_t k = k0 + i;
            int w = walled[i];
            if (w < 0) {
                rc = -1;
                break;
            }
            v->walled += (size_t)w;
            if (!w)
                continue;
            /* A walled plane extends the run unless the open gap before
             * it is longer than VBC_WALL_GAP. */
            const vbc_pore_point *q = &p->pts[k];
            if (!in_run || q->s - p->pts[last].s > VBC_WALL_GAP + 1e-9) {
                in_run = 1;
                lo = k;
            }
            last = k;
            double span = q->s - p->pts[lo].s;
            if (!have || span > v->buried) {
                have = 1;
                v->buried = span;
                v->run_lo = lo;
                v->run_hi = k;
                if (v->buried >= enough) {
                    done = 1;
                    break;
                }
            }
        }
    }
    for (int t = 0; t < VB_MAX_THREADS; t++)
        free(B.scratch[t]);
    free(walled);
    if (rc != 0) {
        memset(v, 0, sizeof *v);
        return -1;
    }
    v->is_pore = v->buried >= VBC_PORE_MIN_BURIED;
    return 0;
}

int vbc_pore_judge(const vbc_cells *c, const vbc_pore *p, double enough, vbc_pore_verdict *v)
{
    return judge(c, p, NULL, NULL, enough, v);
}

int vbc_pore_judge_on(const vbc_walls_engine *W, const vbc_cells *c, const vbc_pore *p,
                      double enough, vbc_pore_verdict *v)
{
    vbc_walls_input in;
    if (!W || p->n == 0 || vbc_walls_prep(c, p, &in) != 0)
        return judge(c, p, NULL, NULL, enough, v);
    size_t words = in.word0[in.nplanes];
    vbc_walls_raster R = {malloc(words * sizeof *R.blocked), malloc(words * sizeof *R.unsure)};
    int rc = R.blocked && R.unsure && W->raster(W->user, &in, &R) == VB_OK
                 ? judge(c, p, &in, &R, enough, v)
                 : judge(c, p, NULL, NULL, enough, v);
    free(R.blocked);
    free(R.unsure);
    vbc_walls_input_free(&in);
    return rc;
}
