/* The per-bin reach: which image spheres can matter for some atom's cell.
 *
 * Claim. Let v be a periodic vertex written as a translate with a member
 * i at shift 0 (the canonical translate has one), point p, radius t. Let
 * U be any unwrapped bin whose region grown by e = bins.grow contains p
 * (the bin that p's doubles fall in is one: e covers their error). Then
 * (a) t <= F[U] (bins.c: F bounds f over U grown by e, and t = f(p));
 * (b) U is active: dist(c_i, U) <= |c_i - p| + e = t + R_i + e
 *     <= F[U] + R_i + e;
 * (c) every sphere j of S touching or entering v's tangent sphere has
 *     |c_j - p| <= t + R_j, so dist(c_j, U) <= F[U] + Rmax + e: the bin W
 *     of c_j has dist(W, U) <= F[U] + Rmax + e, and need[W] is set below.
 * So keeping the images whose bin has need[] set (and within the global
 * layer of images.c, which holds them by the same argument with the one
 * bound rho) keeps every sphere that any periodic vertex touches or that
 * could enter it: completeness as in images.c. Conversely a certified
 * vertex of the kept set with a member at shift 0 and t <= F[U] for the
 * bin U that its point falls in is empty in S: (b) and (c) hold for it
 * with the same steps, so every sphere of S that could enter it was kept.
 * One with t > F[U] is not empty in S (f(p) <= F[U] < t) and is dropped
 * (vb_periodic_bound_at).
 *
 * Distances between bins are bounded below exactly: two points of bins
 * whose indices differ by D have fractional difference u with u_k in
 * [(D_k - 1) / nb_k, (D_k + 1) / nb_k], and the distance |u A| is at
 * least the minimum of the convex quadratic u A A^T u^T over that box,
 * found among its KKT points (each coordinate free or at a bound: 27
 * linear solves, the least feasible value). It depends on D alone: one
 * table. An atom is taken as any point of its bin. The doubles' error of
 * these bounds is covered by the margin added to every threshold and a
 * relative 1e-9 taken off each distance. */
#include "vbp_bins.h"
#include "vb_parallel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_BINS ((size_t)1 << 27) /* past this, no reach: the full layer */

/* The table of lower bounds of bin-to-bin distances by index offset, and
 * the offsets in increasing order of that bound (a scan stops at the
 * first bound above its threshold). */
typedef struct doff {
    double d;
    long D[3];
} doff;

typedef struct dtab {
    long k[3];   /* offsets -k .. k per edge */
    doff *by_d;  /* every offset, bound ascending */
    size_t n;
} dtab;

static int cmp_doff(const void *pa, const void *pb)
{
    const doff *a = pa, *b = pb;
    if (a->d != b->d)
        return a->d < b->d ? -1 : 1;
    for (int k = 0; k < 3; k++)
        if (a->D[k] != b->D[k])
            return a->D[k] < b->D[k] ? -1 : 1;
    return 0;
}

/* min of u G u^T over lo <= u <= hi (G symmetric positive definite). */
static double box_qp(const double G[9], const double lo[3], const double hi[3])
{
    double best = INFINITY;
    for (int pat = 0; pat < 27; pat++) {
        int st[3] = {pat % 3, pat / 3 % 3, pat / 9}; /* 0 free, 1 lo, 2 hi */
        double u[3] = {0.0, 0.0, 0.0};
        int fr[3], nf = 0;
        for (int a = 0; a < 3; a++) {
            if (st[a] == 0)
                fr[nf++] = a;
            else
                u[a] = st[a] == 1 ? lo[a] : hi[a];
        }
        /* G_FF u_F = -G_FX u_X */
        double M[9], r[3];
        for (int i = 0; i < nf; i++) {
            r[i] = 0.0;
            for (int a = 0; a < 3; a++)
                if (st[a] != 0)
                    r[i] -= G[3 * fr[i] + a] * u[a];
            for (int j = 0; j < nf; j++)
                M[3 * i + j] = G[3 * fr[i] + fr[j]];
        }
        double x[3] = {0, 0, 0};
        if (nf == 1) {
            x[0] = r[0] / M[0];
        } else if (nf == 2) {
            double det = M[0] * M[4] - M[1] * M[3];
            x[0] = (r[0] * M[4] - M[1] * r[1]) / det;
            x[1] = (M[0] * r[1] - M[3] * r[0]) / det;
        } /* nf == 3: r = 0, x = 0 */
        int ok = 1;
        for (int i = 0; i < nf; i++) {
            int a = fr[i];
            double tol = 1e-9 * (1.0 + fabs(lo[a]) + fabs(hi[a]));
            ok &= x[i] >= lo[a] - tol && x[i] <= hi[a] + tol;
            u[a] = x[i];
        }
        if (!ok)
            continue;
        double q = 0.0;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                q += u[a] * G[3 * a + c] * u[c];
        best = fmin(best, q);
    }
    return best > 0.0 ? sqrt(best) * (1.0 - 1e-9) : 0.0;
}

typedef struct dtab_job {
    const vbp_bins *bn;
    dtab *t;
    const double *G;
} dtab_job;

/* The table's entries with D[0] = i - k[0], in the order of the offsets
 * (sorted by their bound after). */
static void dtab_slab(void *ctx, size_t i, int tid)
{
    (void)tid;
    const dtab_job *jb = ctx;
    const dtab *t = jb->t;
    const vbp_bins *bn = jb->bn;
    long D[3] = {(long)i - t->k[0], 0, 0};
    size_t w = i * (size_t)(2 * t->k[1] + 1) * (size_t)(2 * t->k[2] + 1);
    for (D[1] = -t->k[1]; D[1] <= t->k[1]; D[1]++)
        for (D[2] = -t->k[2]; D[2] <= t->k[2]; D[2]++) {
            double lo[3], hi[3];
            for (int a = 0; a < 3; a++) {
                lo[a] = (double)(D[a] - 1) / bn->nb[a];
                hi[a] = (double)(D[a] + 1) / bn->nb[a];
            }
            t->by_d[w++] = (doff){box_qp(jb->G, lo, hi), {D[0], D[1], D[2]}};
        }
}

static int dtab_build(const vbp_bins *bn, const vb_box *box, double thr, dtab *t)
{
    const double *A = box->v;
    double G[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            G[3 * r + c] = A[3 * r] * A[3 * c] + A[3 * r + 1] * A[3 * c + 1] +
                           A[3 * r + 2] * A[3 * c + 2];
    size_t n = 1;
    for (int a = 0; a < 3; a++) {
        t->k[a] = (long)ceil(thr / bn->h[a] * bn->nb[a]) + 1;
        n *= (size_t)(2 * t->k[a] + 1);
    }
    t->by_d = malloc(n * sizeof *t->by_d);
    t->n = n;
    if (!t->by_d)
        return VB_ENOMEM;
    dtab_job jb = {bn, t, G};
    vb_parallel_for(dtab_slab, &jb, (size_t)(2 * t->k[0] + 1), vb_threads(0));
    qsort(t->by_d, n, sizeof *t->by_d, cmp_doff);
    return VB_OK;
}

static int wrapi(long q, int n)
{
    long r = q % n;
    return (int)(r < 0 ? r + n : r);
}

static double bin_F(const vbp_bins *bn, const long b[3])
{
    size_t c = ((size_t)wrapi(b[0], bn->nb[0]) * bn->nb[1] + wrapi(b[1], bn->nb[1])) * bn->nb[2] +
               wrapi(b[2], bn->nb[2]);
    return bn->F[c];
}

static size_t at(const vbp_reach *r, const long b[3])
{
    return ((size_t)(b[0] - r->lo[0]) * r->n[1] + (size_t)(b[1] - r->lo[1])) * r->n[2] +
           (size_t)(b[2] - r->lo[2]);
}

static int inside(const vbp_reach *r, const long b[3])
{
    for (int a = 0; a < 3; a++)
        if (b[a] < r->lo[a] || b[a] >= r->lo[a] + r->n[a])
            return 0;
    return 1;
}

/* For every bin U within the table of bin v (holding an atom of radius up
 * to R): mark[U] = 1 when dist(v, U) <= F[U] + R + extra (active), or,
 * with need, when dist(v, U) <= F[v] + R + extra. The offsets come in
 * increasing order of their bound, so the scan stops at the first beyond
 * the largest threshold (F[v] with need, rho without). Several threads may
 * mark at once: a mark only ever goes from 0 to 1 (relaxed atomic bytes),
 * so the marks after a pass are the OR of every bin's, in any order, and
 * the test skipped for a marked bin could only have marked it again. */
static void mark_around(const vbp_bins *bn, const dtab *t, vbp_reach *r, uint8_t *mark,
                        const long v[3], double R, double extra, int need)
{
    double thr_v = bin_F(bn, v) + R + extra, stop = need ? thr_v : bn->rho + R + extra;
    long u[3];
    for (size_t q = 0; q < t->n && t->by_d[q].d <= stop; q++) {
        const long *D = t->by_d[q].D;
        for (int a = 0; a < 3; a++)
            u[a] = v[a] + D[a];
        if (!inside(r, u))
            continue;
        size_t k = at(r, u);
        if (__atomic_load_n(&mark[k], __ATOMIC_RELAXED))
            continue;
        double thr = need ? thr_v : bin_F(bn, u) + R + extra;
        if (t->by_d[q].d <= thr)
            __atomic_store_n(&mark[k], 1, __ATOMIC_RELAXED);
    }
}

typedef struct mark_job {
    const vbp_bins *bn;
    const dtab *t;
    vbp_reach *r;
    const uint8_t *occ;
    const double *occr;
    uint8_t *act;
    double rmax, extra;
    int need; /* 0: mark act around occupied bins; 1: need around active ones */
} mark_job;

/* One row of bins (u[0], u[1]) of a pass of vbp_reach_build. */
static void mark_row(void *ctx, size_t row, int tid)
{
    (void)tid;
    const mark_job *jb = ctx;
    vbp_reach *r = jb->r;
    long u[3] = {r->lo[0] + (long)(row / (size_t)r->n[1]), r->lo[1] + (long)(row % (size_t)r->n[1]),
                 0};
    for (u[2] = r->lo[2]; u[2] < r->lo[2] + r->n[2]; u[2]++) {
        size_t k = at(r, u);
        if (jb->need ? jb->act[k] : jb->occ[k])
            mark_around(jb->bn, jb->t, r, jb->need ? r->need : jb->act, u,
                        jb->need ? jb->rmax : jb->occr[k], jb->extra, jb->need);
    }
}

int vbp_reach_build(const vbp_bins *bn, const vb_box *box, const vb_sphere_set *atoms,
                    const double klo[3], const double khi[3], double rmax, double margin,
                    vbp_reach *r)
{
    memset(r, 0, sizeof *r);
    size_t total = 1;
    for (int a = 0; a < 3; a++) {
        r->lo[a] = (long)floor(klo[a] * bn->nb[a]);
        r->n[a] = (long)floor(khi[a] * bn->nb[a]) - r->lo[a] + 1;
        if ((double)total * (double)r->n[a] > (double)MAX_BINS)
            return 1;
        total *= (size_t)r->n[a];
    }
    double extra = bn->grow + margin;
    dtab t;
    uint8_t *act = calloc(total, 1), *occ = calloc(total, 1);
    double *occr = calloc(total, sizeof *occr);
    r->need = calloc(total, 1);
    int rc = act && occ && occr && r->need ? dtab_build(bn, box, bn->rho + rmax + extra, &t)
                                           : VB_ENOMEM;
    if (rc == VB_OK) {
        /* The bins of the atoms at shift 0, each with its largest radius. */
        const double *inv = bn->inv;
        for (size_t i = 0; i < atoms->n; i++) {
            double f[3];
            long b[3];
            for (int a = 0; a < 3; a++) {
                f[a] = atoms->x[i] * inv[a] + atoms->y[i] * inv[3 + a] + atoms->z[i] * inv[6 + a];
                b[a] = (long)floor(f[a] * bn->nb[a]);
            }
            if (!inside(r, b))
                continue; /* cannot happen: the range holds the atoms */
            size_t k = at(r, b);
            occ[k] = 1;
            occr[k] = fmax(occr[k], atoms->r[i]);
        }
        mark_job jb = {bn, &t, r, occ, occr, act, rmax, extra, 0};
        size_t rows = (size_t)r->n[0] * (size_t)r->n[1];
        for (jb.need = 0; jb.need < 2; jb.need++)
            vb_parallel_for(mark_row, &jb, rows, vb_threads(0));
        free(t.by_d);
    }
    free(act);
    free(occ);
    free(occr);
    if (rc != VB_OK)
        vbp_reach_free(r);
    return rc;
}

int vbp_reach_keeps(const vbp_reach *r, const vbp_bins *bn, const double f[3])
{
    long b[3];
    for (int a = 0; a < 3; a++) {
        b[a] = (long)floor(f[a] * bn->nb[a]);
        if (b[a] < r->lo[a] || b[a] >= r->lo[a] + r->n[a])
            return 0;
    }
    return r->need[at(r, b)];
}

void vbp_reach_free(vbp_reach *r)
{
    free(r->need);
    memset(r, 0, sizeof *r);
}
