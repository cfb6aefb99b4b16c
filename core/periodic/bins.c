/* Spatial bins of a periodic box and a proven bound of the largest empty
 * sphere per bin.
 *
 * S is the infinite periodic set (every atom translated by every lattice
 * vector); f(x) = min over S of |x - c_j| - R_j is the radius of the
 * largest empty sphere centred at x (a vertex's tangent radius t is f at
 * its point). f is periodic and 1-Lipschitz (a minimum of 1-Lipschitz
 * functions).
 *
 * The box's cell P = {u A : u in [0,1)^3} is cut into nb[0] x nb[1] x nb[2]
 * bins along u, and each bin into sub[0] x sub[1] x sub[2] sub-cells with
 * centres g; every point of a sub-cell lies within delta of its centre,
 * delta half the longest diagonal of a sub-cell (|x - g| is convex in the
 * sub-cell's coordinates, so its maximum is at a corner). f(g) <= |g - y|
 * - R for any image y of any atom, so over a bin B
 *     max_B f <= max over B's centres g of (min over nearby images of
 *                |g - y| - R) + delta,
 * and over B grown by a distance e (every point within e of B), e more.
 * Which images are "nearby" only changes how tight the bound is, never
 * its truth. F[B] is that bound plus e (grow), plus a margin for the
 * doubles' errors (atom and image positions, g, the distances: a few units
 * in the last place of the coordinates' magnitude, times the box matrix's
 * condition number for the wrapped images; the caller's margin, 1e-9 of
 * that magnitude), plus 2 slack. The bins' largest F bounds f everywhere. */
#include "vbp_bins.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"

typedef struct job {
    const vb_sphere_set *s;
    const vb_box *box;
    vbp_bins *bn;
    int sub[3];         /* sub-cells per bin and edge */
    size_t *off;        /* bins + 1 offsets into ids */
    uint32_t *ids;
    double *w;          /* 3 per atom: wrapped fractional coordinates in [0, 1) */
    int32_t *cand;      /* per bin: an atom whose image is near the bin (-1: none yet) */
    int (*coff)[3];     /* per bin: that image's shift (boxes) from the wrapped atom */
    double *cval;       /* per bin: |g - y| - R of that image at the bin's centre */
} job;

static int wrap(int q, int n, int *off)
{
    int r = q % n;
    if (r < 0)
        r += n;
    *off = (q - r) / n;
    return r;
}

/* min over the atoms' images in the bins within `rad` of bin b of
 * |g - y| - R (INFINITY when none), or, once it is at most `enough`, a
 * value at most `enough` that is at least that minimum (the caller keeps
 * a maximum above `enough`: it cannot change). */
static double near_bound(const job *jb, const double g[3], const int b[3], int rad,
                         double enough)
{
    const double *A = jb->box->v;
    const int *nb = jb->bn->nb;
    double best = INFINITY;
    for (int d0 = -rad; d0 <= rad; d0++)
        for (int d1 = -rad; d1 <= rad; d1++)
            for (int d2 = -rad; d2 <= rad; d2++) {
                int o[3], q[3];
                q[0] = wrap(b[0] + d0, nb[0], &o[0]);
                q[1] = wrap(b[1] + d1, nb[1], &o[1]);
                q[2] = wrap(b[2] + d2, nb[2], &o[2]);
                size_t cell = ((size_t)q[0] * nb[1] + q[1]) * nb[2] + q[2];
                for (size_t k = jb->off[cell]; k < jb->off[cell + 1]; k++) {
                    uint32_t i = jb->ids[k];
                    double u[3] = {jb->w[3 * i] + o[0], jb->w[3 * i + 1] + o[1],
                                   jb->w[3 * i + 2] + o[2]};
                    double dx = u[0] * A[0] + u[1] * A[3] + u[2] * A[6] - g[0];
                    double dy = u[0] * A[1] + u[1] * A[4] + u[2] * A[7] - g[1];
                    double dz = u[0] * A[2] + u[1] * A[5] + u[2] * A[8] - g[2];
                    double v = sqrt(dx * dx + dy * dy + dz * dz) - jb->s->r[i];
                    best = v < best ? v : best;
                    if (best <= enough)
                        return best;
                }
            }
    return best;
}

/* |g - y| - R for the image of atom i shifted by o (boxes) from its
 * wrapped position. */
static double image_value(const job *jb, const double g[3], uint32_t i, const int o[3])
{
    const double *A = jb->box->v;
    double u[3] = {jb->w[3 * i] + o[0], jb->w[3 * i + 1] + o[1], jb->w[3 * i + 2] + o[2]};
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double d = u[0] * A[a] + u[1] * A[3 + a] + u[2] * A[6 + a] - g[a];
        d2 += d * d;
    }
    return sqrt(d2) - jb->s->r[i];
}

static size_t bin_at(const vbp_bins *bn, const int q[3])
{
    return ((size_t)q[0] * bn->nb[1] + q[1]) * bn->nb[2] + q[2];
}

static void bin_centre(const job *jb, const int b[3], double g[3])
{
    const double *A = jb->box->v;
    double u[3];
    for (int a = 0; a < 3; a++)
        u[a] = (b[a] + 0.5) / jb->bn->nb[a];
    for (int a = 0; a < 3; a++)
        g[a] = u[0] * A[a] + u[1] * A[3 + a] + u[2] * A[6 + a];
}

/* The best of the candidates of bin b and its 26 neighbours at g, or
 * (improve) the candidate of b replaced by a better neighbour's: 1 when
 * it changed. Any image bounds f from above, so which candidate a bin
 * holds only changes how tight its bound is. */
static double cand_scan(const job *jb, const double g[3], const int b[3], int32_t *best_i,
                        int best_o[3])
{
    const int *nb = jb->bn->nb;
    double best = INFINITY;
    for (int d0 = -1; d0 <= 1; d0++)
        for (int d1 = -1; d1 <= 1; d1++)
            for (int d2 = -1; d2 <= 1; d2++) {
                int o[3], q[3];
                q[0] = wrap(b[0] + d0, nb[0], &o[0]);
                q[1] = wrap(b[1] + d1, nb[1], &o[1]);
                q[2] = wrap(b[2] + d2, nb[2], &o[2]);
                size_t c = bin_at(jb->bn, q);
                if (jb->cand[c] < 0)
                    continue;
                int sh[3];
                for (int a = 0; a < 3; a++)
                    sh[a] = jb->coff[c][a] + o[a];
                double v = image_value(jb, g, (uint32_t)jb->cand[c], sh);
                if (v < best) {
                    best = v;
                    if (best_i) {
                        *best_i = jb->cand[c];
                        memcpy(best_o, sh, sizeof sh);
                    }
                }
            }
    return best;
}

static double cand_bound(const job *jb, const double g[3], const int b[3])
{
    return cand_scan(jb, g, b, NULL, NULL);
}

/* Every bin gets a candidate image near it: the best atom of its own bin,
 * then sweeps that take a neighbour's candidate when it is nearer the
 * bin's centre, until none changes (a brushfire over the bins). */
static void candidates(job *jb)
{
    const vbp_bins *bn = jb->bn;
    size_t nbins = (size_t)bn->nb[0] * bn->nb[1] * bn->nb[2];
    int b[3];
    for (b[0] = 0; b[0] < bn->nb[0]; b[0]++)
        for (b[1] = 0; b[1] < bn->nb[1]; b[1]++)
            for (b[2] = 0; b[2] < bn->nb[2]; b[2]++) {
                size_t c = bin_at(bn, b);
                double g[3];
                bin_centre(jb, b, g);
                jb->cand[c] = -1;
                jb->cval[c] = INFINITY;
                memset(jb->coff[c], 0, sizeof jb->coff[c]);
                for (size_t k = jb->off[c]; k < jb->off[c + 1]; k++) {
                    static const int zero[3] = {0, 0, 0};
                    double v = image_value(jb, g, jb->ids[k], zero);
                    if (v < jb->cval[c]) {
                        jb->cval[c] = v;
                        jb->cand[c] = (int32_t)jb->ids[k];
                    }
                }
            }
    for (int changed = 1; changed;) {
        changed = 0;
        for (size_t c = 0; c < nbins; c++) {
            b[0] = (int)(c / ((size_t)bn->nb[1] * bn->nb[2]));
            b[1] = (int)(c / (size_t)bn->nb[2] % (size_t)bn->nb[1]);
            b[2] = (int)(c % (size_t)bn->nb[2]);
            double g[3];
            bin_centre(jb, b, g);
            int32_t i = -1;
            int o[3];
            double v = cand_scan(jb, g, b, &i, o);
            if (i >= 0 && v < jb->cval[c]) {
                jb->cand[c] = i;
                memcpy(jb->coff[c], o, sizeof o);
                jb->cval[c] = v;
                changed = 1;
            }
        }
    }
}

/* One row of bins (b0, b1 fixed): each bin's largest bound at its
 * sub-cell centres (delta and the rest are added after). */
static void bound_row(void *arg, size_t row, int tid)
{
    (void)tid;
    job *jb = arg;
    vbp_bins *bn = jb->bn;
    const double *A = jb->box->v;
    int b[3] = {(int)(row / (size_t)bn->nb[1]), (int)(row % (size_t)bn->nb[1]), 0};
    for (b[2] = 0; b[2] < bn->nb[2]; b[2]++) {
        double mx = -INFINITY;
        for (int i0 = 0; i0 < jb->sub[0]; i0++)
            for (int i1 = 0; i1 < jb->sub[1]; i1++)
                for (int i2 = 0; i2 < jb->sub[2]; i2++) {
                    const int ii[3] = {i0, i1, i2};
                    double u[3], g[3];
                    for (int a = 0; a < 3; a++)
                        u[a] = (b[a] + (ii[a] + 0.5) / jb->sub[a]) / bn->nb[a];
                    for (int a = 0; a < 3; a++)
                        g[a] = u[0] * A[a] + u[1] * A[3 + a] + u[2] * A[6 + a];
                    /* A sub-cell whose bound falls to mx cannot raise it:
                     * the scan of the near images stops there. */
                    double v = cand_bound(jb, g, b);
                    if (v > mx)
                        v = fmin(v, near_bound(jb, g, b, 1, mx));
                    mx = v > mx ? v : mx;
                }
        bn->F[row * (size_t)bn->nb[2] + (size_t)b[2]] = mx;
    }
}

size_t vbp_bins_index(const vbp_bins *bn, const double f[3])
{
    size_t cell = 0;
    for (int a = 0; a < 3; a++) {
        double w = f[a] - floor(f[a]);
        int b = (int)(w * bn->nb[a]);
        b = b < 0 ? 0 : b >= bn->nb[a] ? bn->nb[a] - 1 : b;
        cell = cell * (size_t)bn->nb[a] + (size_t)b;
    }
    return cell;
}

void vbp_bins_free(vbp_bins *bn)
{
    free(bn->F);
    bn->F = NULL;
}

int vbp_bins_build(const vb_sphere_set *s, const vb_box *box, double grow, double slack,
                   double margin, vbp_bins *bn)
{
    memset(bn, 0, sizeof *bn);
    vb_box_inverse(box, bn->inv);
    const double *A = box->v, *inv = bn->inv;
    for (int a = 0; a < 3; a++)
        bn->h[a] = 1.0 / sqrt(inv[a] * inv[a] + inv[3 + a] * inv[3 + a] + inv[6 + a] * inv[6 + a]);
    double cx = A[4] * A[8] - A[5] * A[7], cy = A[5] * A[6] - A[3] * A[8],
           cz = A[3] * A[7] - A[4] * A[6];
    double vol = fabs(A[0] * cx + A[1] * cy + A[2] * cz);
    /* Bins of about one atom each, at least 216 in all (a few atoms in a
     * large box still get a reach per region); three sub-cells per bin and
     * edge (at least 8 per edge). */
    double spacing = cbrt(vol / (double)(s->n > 216 ? s->n : 216));
    job jb = {.s = s, .box = box, .bn = bn};
    size_t nbins = 1;
    for (int a = 0; a < 3; a++) {
        double q = floor(bn->h[a] / spacing);
        bn->nb[a] = q < 1.0 ? 1 : q > 512.0 ? 512 : (int)q;
        jb.sub[a] = 3 * ((8 + 3 * bn->nb[a] - 1) / (3 * bn->nb[a]));
        nbins *= (size_t)bn->nb[a];
    }
    bn->F = malloc(nbins * sizeof *bn->F);
    jb.off = calloc(nbins + 1, sizeof *jb.off);
    jb.ids = malloc(s->n * sizeof *jb.ids);
    jb.w = malloc(3 * s->n * sizeof *jb.w);
    size_t *cellof = malloc(s->n * sizeof *cellof);
    size_t *fill = malloc(nbins * sizeof *fill);
    jb.cand = malloc(nbins * sizeof *jb.cand);
    jb.coff = malloc(nbins * sizeof *jb.coff);
    jb.cval = malloc(nbins * sizeof *jb.cval);
    int rc = bn->F && jb.off && jb.ids && jb.w && cellof && fill && jb.cand && jb.coff && jb.cval
                 ? VB_OK
                 : VB_ENOMEM;
    for (size_t i = 0; rc == VB_OK && i < s->n; i++) {
        double f[3];
        for (int a = 0; a < 3; a++) {
            f[a] = s->x[i] * inv[a] + s->y[i] * inv[3 + a] + s->z[i] * inv[6 + a];
            double w = f[a] - floor(f[a]);
            jb.w[3 * i + a] = w >= 1.0 ? 0.0 : w;
        }
        cellof[i] = vbp_bins_index(bn, f);
        jb.off[cellof[i] + 1]++;
    }
    if (rc == VB_OK) {
        for (size_t c = 0; c < nbins; c++)
            jb.off[c + 1] += jb.off[c];
        memcpy(fill, jb.off, nbins * sizeof *fill);
        for (size_t i = 0; i < s->n; i++)
            jb.ids[fill[cellof[i]]++] = (uint32_t)i;
        candidates(&jb);
        vb_parallel_for(bound_row, &jb, (size_t)bn->nb[0] * bn->nb[1], vb_threads(0));
        /* delta: half the longest of the sub-cell's four diagonals. */
        double delta = 0.0;
        for (int sg = 0; sg < 4; sg++) {
            double sb = (sg & 1) ? -1.0 : 1.0, sc = (sg & 2) ? -1.0 : 1.0, d2 = 0.0;
            for (int a = 0; a < 3; a++) {
                double e = A[a] / (jb.sub[0] * bn->nb[0]) + sb * A[3 + a] / (jb.sub[1] * bn->nb[1]) +
                           sc * A[6 + a] / (jb.sub[2] * bn->nb[2]);
                d2 += e * e;
            }
            delta = fmax(delta, 0.5 * sqrt(d2));
        }
        bn->grow = grow;
        bn->rho = -INFINITY;
        for (size_t c = 0; c < nbins; c++) {
            bn->F[c] += delta + grow + margin + 2.0 * slack;
            bn->rho = fmax(bn->rho, bn->F[c]);
        }
    } else {
        vbp_bins_free(bn);
    }
    free(jb.off);
    free(jb.ids);
    free(jb.w);
    free(cellof);
    free(fill);
    free(jb.cand);
    free(jb.coff);
    free(jb.cval);
    return rc;
}
