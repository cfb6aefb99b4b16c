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

int vbc_plane_walled_raster(const vbc_cells *c, const double u[3], const double p[3], double r,
                            int m, const uint32_t *blocked, const uint32_t *unsure, void **scratch,
                            size_t *scratch_len)
{
    double a[3], b[3];
    vbc_plane_basis(u, a, b);
    double rr = r > 0.0 ? r : 0.0;
    int n = vbc_plane_raster_half(r);
    size_t side = (size_t)(2 * n + 1), npix = side * side;
    size_t need = npix * (sizeof(double) + sizeof(int32_t) + sizeof(uint8_t));
    if (*scratch_len < need) {
        void *m = realloc(*scratch, need);
        if (!m)
            return -1;
        *scratch = m;
        *scratch_len = need;
    }
    /* Per pixel: a lower bound of its distance to every atom surface (set
     * when the pixel is stacked), the stack, whether it was seen. */
    double *low = *scratch;
    int32_t *stack = (int32_t *)(low + npix);
    uint8_t *seen = (uint8_t *)(stack + npix);
    memset(seen, 0, npix);
    size_t top = 0;
    int32_t start = (int32_t)((size_t)n * side + (size_t)n), hint = -1;
    stack[top++] = start;
    seen[start] = 1;
    low[start] = -INFINITY;
    double edge2 = (double)(n - 1) * (double)(n - 1);
    /* Whether the free pixels connected to the sphere reach the edge does
     * not depend on the order they are visited in (a pixel's freedom is
     * its own: the bound below only spares the query whose answer it
     * proves), so the search goes depth first, the outward step last
     * pushed (first taken): an open plane is left in about n steps instead
     * of the breadth-first disc of ~2 n^2 pixels; a walled one visits the
     * same free region either way. */
    while (top > 0) {
        int32_t v = stack[--top];
        int i = (int)(v / (int32_t)side) - n, j = (int)(v % (int32_t)side) - n;
        if ((double)i * i + (double)j * j >= edge2)
            return 0; /* a disc of the wall probe got out: not walled */
        /* A neighbour is one pixel from v: its distance to the atoms is at
         * least v's less a pixel (the distance moves no faster than the
         * point), so when that still clears the probe it is free unasked. */
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
            int32_t w = (int32_t)((size_t)(ii + n) * side + (size_t)(jj + n));
            if (seen[w])
                continue;
            seen[w] = 1;
            double x = ii * VBC_WALL_PIXEL, y = jj * VBC_WALL_PIXEL;
            low[w] = -INFINITY;
            /* Inside the pore's own sphere the way is free; elsewhere a
             * pixel is free when no atom surface comes within the probe. */
            if (x * x + y * y > rr * rr && blocked && abs(ii) <= m && abs(jj) <= m) {
                /* The raster's answer; the cell list's where it is unsure. */
                size_t rv = (size_t)(ii + m) * (size_t)(2 * m + 1) + (size_t)(jj + m);
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
            } else if (x * x + y * y > rr * rr) {
                if (near > VBC_WALL_PROBE + FREE_EPS) {
                    low[w] = near;
                } else {
                    double q[3], lw;
                    for (int d = 0; d < 3; d++)
                        q[d] = p[d] + x * a[d] + y * b[d];
                    if (vbc_cells_any_within(c, q, VBC_WALL_PROBE, &hint, &lw))
                        continue;
                    low[w] = lw - FREE_EPS;
                }
            }
            stack[top++] = w;
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

/* The planes [k0, k0 + n) of a pore flooded at once: plane k0 + i on
 * thread i mod nt, each thread with its own scratch; walled[i] gets
 * vbc_plane_walled's answer (a plane's answer is its own, so the verdict
 * scanning them in order is the one-plane-at-a-time verdict). */
typedef struct {
    const vbc_cells *c;
    const vbc_pore *p;
    const vbc_walls_input *in; /* with R: the planes' rasters (NULL: none) */
    const vbc_walls_raster *R;
    size_t k0;
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
    B->walled[i] = (int8_t)vbc_plane_walled_raster(B->c, B->p->axis.u, at, q->r, m, bl, un,
                                                   &B->scratch[tid], &B->len[tid]);
}

/* Planes flooded at once per thread before the run is scanned: the scan
 * may stop early (enough), so a block is what the threads share, not the
 * whole pore; a thread costs a start and a join (tens of microseconds,
 * milliseconds on a loaded machine) against a few to tens of microseconds
 * a plane, so each takes this many at least, and a pore of fewer planes
 * is judged on fewer threads (on one: plane by plane, as it stops). */
#define JUDGE_PLANES_PER_THREAD 32

/* vbc_pore_judge, the pixels from the rasters R of in when R is not NULL. */
static int judge(const vbc_cells *c, const vbc_pore *p, const vbc_walls_input *in,
                 const vbc_walls_raster *R, double enough, vbc_pore_verdict *v)
{
    memset(v, 0, sizeof *v);
    int nt = vbc_pore_threads(p->n, JUDGE_PLANES_PER_THREAD);
    size_t block = nt > 1 ? (size_t)nt * JUDGE_PLANES_PER_THREAD : 1;
    int8_t *walled = malloc(block);
    judge_block B = {c, p, in, R, 0, walled, {NULL}, {0}};
    size_t lo = 0, last = 0;
    int in_run = 0, have = 0, rc = walled ? 0 : -1, done = 0;
    for (size_t k0 = 0; rc == 0 && !done && k0 < p->n; k0 += block) {
        size_t m = p->n - k0 < block ? p->n - k0 : block;
        B.k0 = k0;
        if (m > 1)
            vb_parallel_for(judge_plane, &B, m, (int)((m + JUDGE_PLANES_PER_THREAD - 1) /
                                                      JUDGE_PLANES_PER_THREAD));
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
