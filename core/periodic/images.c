/* The images a periodic diagram needs, and the proof of their reach.
 *
 * S is the infinite periodic set (every atom translated by every lattice
 * vector); f(x) = min over S of |x - c_j| - R_j is the radius of the
 * largest empty sphere centred at x (a vertex's tangent radius t is f at
 * its point).
 *
 * 1. A bound rho >= max f. f is periodic, so its maximum over space is its
 *    maximum over the box's cell P = {u A : u in [0,1)^3}. Cut P into
 *    N0 x N1 x N2 sub-cells with centres g; every point of a sub-cell lies
 *    within delta of its centre, delta half the longest diagonal of the
 *    sub-cell (|x - g| is convex in the sub-cell's coordinates, so its
 *    maximum is at a corner). f is 1-Lipschitz (a minimum of 1-Lipschitz
 *    functions), and f(g) <= |g - y| - R for any image y of any atom, so
 *        max f <= max over g of (min over nearby images of |g - y| - R) + delta.
 *    Which images are "nearby" only changes how tight the bound is, never
 *    its truth. The doubles' errors (atom and image positions, g, the
 *    distances: a few units in the last place of the coordinates'
 *    magnitude, times the box matrix's condition number for the wrapped
 *    images) are covered by an added margin of 1e-9 of that magnitude.
 *
 * 2. The reach. Write a periodic vertex v (point p, radius t <= rho) as its
 *    canonical translate, which has a member i at shift 0: an atom, with
 *    |p - c_i| = t + R_i. A sphere j of S that touches or enters v's
 *    tangent sphere has |c_j - p| <= t + R_j, so |c_j - c_i| <= 2 (rho +
 *    Rmax) =: D. So with every image within D of some atom:
 *    - every periodic vertex's canonical translate has all its members in
 *      the finite set S' (atoms + images) and is empty there (S' is part
 *      of S): a vertex of S''s diagram, found by the cover in the cell of
 *      its atom of smallest id (which is also its smallest index in S',
 *      images being numbered after the atoms): completeness;
 *    - conversely a certified vertex of S' with a member at shift 0 and
 *      t <= rho is empty in S too (every sphere of S that could enter it
 *      lies in S'): a periodic vertex. One with t > rho cannot be one
 *      (rho >= max f), and is dropped.
 *    The images kept are those whose fractional coordinates lie within
 *    D / h_k (h_k: the box's height across edge k, plus a margin) of the
 *    atoms' range: a superset of the D-neighbourhood, since a move of
 *    length d changes fractional coordinate k by at most d / h_k. */
#include "vb_periodic.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbi_input.h"

#define MAX_LAYERS 4.0 /* reach past this many box heights: E135 */

typedef struct bins {
    const vb_sphere_set *s;
    const vb_box *box;
    int nb[3];          /* bins per edge */
    int ng[3];          /* grid points per edge */
    size_t *off;        /* nb0 nb1 nb2 + 1 offsets into ids */
    uint32_t *ids;
    double *w;          /* 3 per atom: wrapped fractional coordinates in [0, 1) */
    double *rowmax;     /* per grid row (i0, i1): the bound's maximum over the row */
} bins;

static int wrap(int q, int n, int *off)
{
    int r = q % n;
    if (r < 0)
        r += n;
    *off = (q - r) / n;
    return r;
}

/* min over the images in the bins within `rad` of bin b of |g - y| - R. */
static double near_bound(const bins *bn, const double g[3], const int b[3], int rad)
{
    const double *A = bn->box->v;
    double best = INFINITY;
    for (int d0 = -rad; d0 <= rad; d0++)
        for (int d1 = -rad; d1 <= rad; d1++)
            for (int d2 = -rad; d2 <= rad; d2++) {
                int o[3], q[3];
                q[0] = wrap(b[0] + d0, bn->nb[0], &o[0]);
                q[1] = wrap(b[1] + d1, bn->nb[1], &o[1]);
                q[2] = wrap(b[2] + d2, bn->nb[2], &o[2]);
                size_t cell = ((size_t)q[0] * bn->nb[1] + q[1]) * bn->nb[2] + q[2];
                for (size_t k = bn->off[cell]; k < bn->off[cell + 1]; k++) {
                    uint32_t i = bn->ids[k];
                    double u[3] = {bn->w[3 * i] + o[0], bn->w[3 * i + 1] + o[1],
                                   bn->w[3 * i + 2] + o[2]};
                    double dx = u[0] * A[0] + u[1] * A[3] + u[2] * A[6] - g[0];
                    double dy = u[0] * A[1] + u[1] * A[4] + u[2] * A[7] - g[1];
                    double dz = u[0] * A[2] + u[1] * A[5] + u[2] * A[8] - g[2];
                    double v = sqrt(dx * dx + dy * dy + dz * dz) - bn->s->r[i];
                    best = v < best ? v : best;
                }
            }
    return best;
}

/* One row of grid points (i0, i1 fixed): the largest bound along it. */
static void bound_row(void *arg, size_t row, int tid)
{
    (void)tid;
    bins *bn = arg;
    const double *A = bn->box->v;
    int i0 = (int)(row / (size_t)bn->ng[1]), i1 = (int)(row % (size_t)bn->ng[1]);
    double mx = -INFINITY;
    for (int i2 = 0; i2 < bn->ng[2]; i2++) {
        double u[3] = {(i0 + 0.5) / bn->ng[0], (i1 + 0.5) / bn->ng[1], (i2 + 0.5) / bn->ng[2]};
        double g[3];
        for (int a = 0; a < 3; a++)
            g[a] = u[0] * A[a] + u[1] * A[3 + a] + u[2] * A[6 + a];
        int b[3];
        for (int a = 0; a < 3; a++) {
            b[a] = (int)(u[a] * bn->nb[a]);
            b[a] = b[a] >= bn->nb[a] ? bn->nb[a] - 1 : b[a];
        }
        double v = INFINITY;
        for (int rad = 1; !isfinite(v); rad++)
            v = near_bound(bn, g, b, rad);
        mx = v > mx ? v : mx;
    }
    bn->rowmax[row] = mx;
}

/* Step 1 of the argument above: *rho >= max f. */
static int empty_radius_bound(const vb_sphere_set *s, const vb_box *box, const double inv[9],
                              const double h[3], double margin, double *rho)
{
    bins bn;
    memset(&bn, 0, sizeof bn);
    bn.s = s;
    bn.box = box;
    double vol = h[0];
    {
        const double *A = box->v;
        double cx = A[4] * A[8] - A[5] * A[7], cy = A[5] * A[6] - A[3] * A[8],
               cz = A[3] * A[7] - A[4] * A[6];
        vol = fabs(A[0] * cx + A[1] * cy + A[2] * cz);
    }
    /* Bins of about one atom each; three grid points per bin and edge
     * (at least 8 per edge). */
    double spacing = cbrt(vol / (double)s->n);
    size_t nbins = 1;
    for (int a = 0; a < 3; a++) {
        double q = floor(h[a] / spacing);
        bn.nb[a] = q < 1.0 ? 1 : q > 512.0 ? 512 : (int)q;
        int mult = (8 + 3 * bn.nb[a] - 1) / (3 * bn.nb[a]);
        bn.ng[a] = 3 * bn.nb[a] * mult;
        nbins *= (size_t)bn.nb[a];
    }
    bn.off = calloc(nbins + 1, sizeof *bn.off);
    bn.ids = malloc(s->n * sizeof *bn.ids);
    bn.w = malloc(3 * s->n * sizeof *bn.w);
    size_t *cellof = malloc(s->n * sizeof *cellof);
    size_t rows = (size_t)bn.ng[0] * bn.ng[1];
    bn.rowmax = malloc(rows * sizeof *bn.rowmax);
    int rc = bn.off && bn.ids && bn.w && cellof && bn.rowmax ? VB_OK : VB_ENOMEM;
    for (size_t i = 0; rc == VB_OK && i < s->n; i++) {
        size_t cell = 0;
        for (int a = 0; a < 3; a++) {
            double f = s->x[i] * inv[a] + s->y[i] * inv[3 + a] + s->z[i] * inv[6 + a];
            double w = f - floor(f);
            w = w >= 1.0 ? 0.0 : w;
            bn.w[3 * i + a] = w;
            int b = (int)(w * bn.nb[a]);
            cell = cell * (size_t)bn.nb[a] + (size_t)(b >= bn.nb[a] ? bn.nb[a] - 1 : b);
        }
        cellof[i] = cell;
        bn.off[cell + 1]++;
    }
    if (rc == VB_OK) {
        for (size_t c = 0; c < nbins; c++)
            bn.off[c + 1] += bn.off[c];
        size_t *fill = malloc((nbins ? nbins : 1) * sizeof *fill);
        if (!fill) {
            rc = VB_ENOMEM;
        } else {
            memcpy(fill, bn.off, nbins * sizeof *fill);
            for (size_t i = 0; i < s->n; i++)
                bn.ids[fill[cellof[i]]++] = (uint32_t)i;
            free(fill);
        }
    }
    if (rc == VB_OK) {
        vb_parallel_for(bound_row, &bn, rows, vb_threads(0));
        double mx = -INFINITY;
        for (size_t r = 0; r < rows; r++)
            mx = bn.rowmax[r] > mx ? bn.rowmax[r] : mx;
        /* delta: half the longest of the sub-cell's four diagonals. */
        const double *A = box->v;
        double delta = 0.0;
        for (int sg = 0; sg < 4; sg++) {
            double sb = (sg & 1) ? -1.0 : 1.0, sc = (sg & 2) ? -1.0 : 1.0, d2 = 0.0;
            for (int a = 0; a < 3; a++) {
                double e = A[a] / bn.ng[0] + sb * A[3 + a] / bn.ng[1] + sc * A[6 + a] / bn.ng[2];
                d2 += e * e;
            }
            delta = fmax(delta, 0.5 * sqrt(d2));
        }
        *rho = mx + delta + margin;
    }
    free(bn.off);
    free(bn.ids);
    free(bn.w);
    free(cellof);
    free(bn.rowmax);
    return rc;
}

/* out = base + s0 v[0] + s1 v[1] + s2 v[2], exactly (VB_EINPUT_MAGNITUDE
 * beyond 18 digits). */
static int dec_image(vb_decimal base, const int s[3], const vb_decimal v[3], vb_decimal *out)
{
    vb_decimal t[4] = {base, v[0], v[1], v[2]};
    const int64_t k[4] = {1, s[0], s[1], s[2]};
    int32_t emin = INT32_MAX;
    for (int a = 0; a < 4; a++)
        if (t[a].mant != 0 && k[a] != 0 && t[a].exp10 < emin)
            emin = t[a].exp10;
    if (emin == INT32_MAX) {
        *out = (vb_decimal){0, 0};
        return VB_OK;
    }
    __int128 sum = 0;
    for (int a = 0; a < 4; a++) {
        if (t[a].mant == 0 || k[a] == 0)
            continue;
        int32_t d = t[a].exp10 - emin;
        if (d > 18)
            return VB_EINPUT_MAGNITUDE;
        __int128 m = t[a].mant;
        for (int32_t q = 0; q < d; q++)
            m *= 10;
        sum += m * k[a];
    }
    int32_t e = emin;
    while (sum != 0 && sum % 10 == 0) {
        sum /= 10;
        e++;
    }
    const __int128 lim = (__int128)1000000000000000000LL;
    if (sum >= lim || sum <= -lim)
        return VB_EINPUT_MAGNITUDE;
    *out = (vb_decimal){(int64_t)sum, sum == 0 ? 0 : e};
    return VB_OK;
}


void vb_periodic_images_free(vb_periodic_images *img)
{
    vb_spheres_free(img->set);
    free(img->atom);
    free(img->shift);
    memset(img, 0, sizeof *img);
}

/* Allocates the arrays of a set of n spheres with exact decimals. */
static int alloc_set(const vb_sphere_set *atoms, size_t n, vb_sphere_set **out)
{
    vb_sphere_set *s = calloc(1, sizeof *s);
    if (!s)
        return VB_ENOMEM;
    *out = s;
    s->n = n;
    s->x = malloc(n * sizeof *s->x);
    s->y = malloc(n * sizeof *s->y);
    s->z = malloc(n * sizeof *s->z);
    s->r = malloc(n * sizeof *s->r);
    s->ex = malloc(n * sizeof *s->ex);
    s->ey = malloc(n * sizeof *s->ey);
    s->ez = malloc(n * sizeof *s->ez);
    s->er = malloc(n * sizeof *s->er);
    s->line = malloc(n * sizeof *s->line);
    s->info = atoms->info ? malloc(n * sizeof *s->info) : NULL;
    s->allows_zero_radius = atoms->allows_zero_radius;
    s->source = strdup(atoms->source ? atoms->source : "<spheres>");
    if (!s->x || !s->y || !s->z || !s->r || !s->ex || !s->ey || !s->ez || !s->er || !s->line ||
        (atoms->info && !s->info) || !s->source)
        return VB_ENOMEM;
    return VB_OK;
}

int vb_periodic_images_build(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                             vb_periodic_images *out)
{
    memset(out, 0, sizeof *out);
    size_t n0 = atoms->n;
    if (!atoms->ex || n0 == 0 || n0 > UINT32_MAX / 64)
        return vb_error(ctx, VB_EMISUSE, atoms->source, 0,
                        "periodic images need a read sphere set with exact decimals");
    double inv[9], h[3], lo[3], hi[3], scale = 0.0, rmax = 0.0;
    vb_box_inverse(box, inv);
    for (int a = 0; a < 3; a++) {
        h[a] = 1.0 / sqrt(inv[a] * inv[a] + inv[3 + a] * inv[3 + a] + inv[6 + a] * inv[6 + a]);
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
        scale += sqrt(box->v[3 * a] * box->v[3 * a] + box->v[3 * a + 1] * box->v[3 * a + 1] +
                      box->v[3 * a + 2] * box->v[3 * a + 2]);
    }
    double cmax = 0.0;
    for (size_t i = 0; i < n0; i++) {
        for (int a = 0; a < 3; a++) {
            double f = atoms->x[i] * inv[a] + atoms->y[i] * inv[3 + a] + atoms->z[i] * inv[6 + a];
            lo[a] = f < lo[a] ? f : lo[a];
            hi[a] = f > hi[a] ? f : hi[a];
        }
        cmax = fmax(cmax, fmax(fabs(atoms->x[i]), fmax(fabs(atoms->y[i]), fabs(atoms->z[i]))));
        rmax = fmax(rmax, atoms->r[i]);
    }
    scale += cmax;
    double margin = 1e-9 * scale;
    int rc = empty_radius_bound(atoms, box, inv, h, margin, &out->rho);
    if (rc != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic reach)");
    out->reach = 2.0 * (out->rho + rmax) + margin;
    double hmin = fmin(h[0], fmin(h[1], h[2]));
    if (out->reach > MAX_LAYERS * hmin)
        return vb_error(ctx, VB_EINPUT_BOX_SMALL, atoms->source, 0,
                        "periodic box too small for its atoms: a cell may reach %.6g, more than "
                        "%g box heights (the smallest is %.6g; empty spheres up to %.6g)",
                        out->reach, MAX_LAYERS, hmin, out->rho);
    /* The kept range of fractional coordinates, per edge, with a margin
     * for the doubles (a superset keeps more images, never fewer). */
    double klo[3], khi[3];
    int L[3];
    for (int a = 0; a < 3; a++) {
        double ext = out->reach / h[a] + 1e-9 * (1.0 + hi[a] - lo[a]);
        klo[a] = lo[a] - ext;
        khi[a] = hi[a] + ext;
        L[a] = (int)ceil(khi[a] - lo[a]) + 1;
        out->layers[a] = L[a];
    }
    /* Count, then fill: atoms first, then the images shift by shift. */
    size_t total = n0;
    for (int pass = 0; pass < 2; pass++) {
        size_t w = n0;
        for (int s0 = -L[0]; s0 <= L[0]; s0++)
            for (int s1 = -L[1]; s1 <= L[1]; s1++)
                for (int s2 = -L[2]; s2 <= L[2]; s2++) {
                    if (s0 == 0 && s1 == 0 && s2 == 0)
                        continue;
                    const int sh[3] = {s0, s1, s2};
                    for (size_t i = 0; i < n0; i++) {
                        int in = 1;
                        for (int a = 0; a < 3 && in; a++) {
                            double f = atoms->x[i] * inv[a] + atoms->y[i] * inv[3 + a] +
                                       atoms->z[i] * inv[6 + a] + sh[a];
                            in = f >= klo[a] && f <= khi[a];
                        }
                        if (!in)
                            continue;
                        if (pass == 1) {
                            out->atom[w] = (uint32_t)i;
                            for (int a = 0; a < 3; a++)
                                out->shift[w][a] = (int16_t)sh[a];
                        }
                        w++;
                    }
                }
        if (pass == 0) {
            total = w;
            if (total > (size_t)UINT32_MAX - 2)
                return vb_error(ctx, VB_EINPUT_TOOLARGE, atoms->source, 0,
                                "%zu spheres with the periodic images", total);
            out->atom = malloc(total * sizeof *out->atom);
            out->shift = calloc(total, sizeof *out->shift);
            if (!out->atom || !out->shift || alloc_set(atoms, total, &out->set) != VB_OK) {
                vb_periodic_images_free(out);
                return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (%zu periodic spheres)",
                                total);
            }
            for (size_t i = 0; i < n0; i++)
                out->atom[i] = (uint32_t)i;
        }
    }
    out->n0 = n0;
    vb_sphere_set *s = out->set;
    const vb_decimal ax[3] = {box->ev[0], box->ev[3], box->ev[6]};
    const vb_decimal ay[3] = {box->ev[1], box->ev[4], box->ev[7]};
    const vb_decimal az[3] = {box->ev[2], box->ev[5], box->ev[8]};
    for (size_t k = 0; k < total; k++) {
        uint32_t i = out->atom[k];
        const int sh[3] = {out->shift[k][0], out->shift[k][1], out->shift[k][2]};
        if (dec_image(atoms->ex[i], sh, ax, &s->ex[k]) != VB_OK ||
            dec_image(atoms->ey[i], sh, ay, &s->ey[k]) != VB_OK ||
            dec_image(atoms->ez[i], sh, az, &s->ez[k]) != VB_OK) {
            vb_periodic_images_free(out);
            return vb_error(ctx, VB_EINPUT_MAGNITUDE, atoms->source, atoms->line ? atoms->line[i] : 0,
                            "an image of atom %u has a coordinate beyond 18 digits", (unsigned)i);
        }
        int same = k < n0;
        s->x[k] = same ? atoms->x[i] : vb_decimal_double(s->ex[k]);
        s->y[k] = same ? atoms->y[i] : vb_decimal_double(s->ey[k]);
        s->z[k] = same ? atoms->z[i] : vb_decimal_double(s->ez[k]);
        s->r[k] = atoms->r[i];
        s->er[k] = atoms->er[i];
        s->line[k] = atoms->line ? atoms->line[i] : 0;
        if (s->info)
            s->info[k] = atoms->info[i];
    }
    /* The atoms' own validation warned of contained atoms (W701) once;
     * their images repeat them, silently. */
    rc = vbi_spheres_validate(ctx, s, 4, 0);
    if (rc != VB_OK)
        vb_periodic_images_free(out);
    return rc;
}
