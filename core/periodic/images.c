/* The images a periodic diagram needs, and the proof of their reach.
 *
 * S is the infinite periodic set (every atom translated by every lattice
 * vector); f(x) = min over S of |x - c_j| - R_j is the radius of the
 * largest empty sphere centred at x (a vertex's tangent radius t is f at
 * its point).
 *
 * 1. A bound rho >= max f: the largest of the per-bin bounds of bins.c.
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
 *    length d changes fractional coordinate k by at most d / h_k.
 *
 * 3. Of that layer only the images that the per-bin reach needs are built
 *    (reach.c: a sharper bound of t where the vertex lies, so far fewer
 *    images around a protein in vacuum); a vertex is then kept when t is
 *    at most vb_periodic_bound_at its point. Both filters keep every sphere
 *    that can touch or enter a periodic vertex, so their intersection does
 *    too, and the vertices are the same as with the full layer. */
#include "vb_periodic.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vbi_input.h"
#include "vbp_bins.h"
#include "vb_parallel.h"

#define MAX_LAYERS 4.0 /* reach past this many box heights: E135 */

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
    if (img->bins)
        vbp_bins_free(img->bins);
    free(img->bins);
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

static int fill_layer(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                      const double inv[9], const double h[3], const double lo[3],
                      const double hi[3], double rmax, double margin,
                      const vb_periodic_image_opt *opt, vb_periodic_images *out);

double vb_periodic_bound_at(const vb_periodic_images *img, double x, double y, double z)
{
    const vbp_bins *bn = img->bins;
    if (!bn)
        return img->rho;
    double f[3];
    for (int a = 0; a < 3; a++)
        f[a] = x * bn->inv[a] + y * bn->inv[3 + a] + z * bn->inv[6 + a];
    double F = bn->F[vbp_bins_index(bn, f)];
    return F < img->rho ? F : img->rho;
}

int vb_periodic_images_build(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                             vb_periodic_images *out)
{
    return vb_periodic_images_build_opt(ctx, atoms, box, NULL, out);
}

int vb_periodic_images_build_opt(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                                 const vb_periodic_image_opt *opt, vb_periodic_images *out)
{
    memset(out, 0, sizeof *out);
    double slack = opt ? opt->slack : 0.0;
    out->slack = slack;
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
    if (opt && opt->reach > 0.0) {
        /* A caller's reach: every image within it, no bound of t. */
        out->reach = opt->reach + margin;
        return fill_layer(ctx, atoms, box, inv, h, lo, hi, rmax, margin, NULL, out);
    }
    vbp_bins *bn = calloc(1, sizeof *bn);
    int rc = bn ? vbp_bins_build(atoms, box, slack + margin, slack, margin, bn) : VB_ENOMEM;
    if (rc != VB_OK) {
        free(bn);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic reach)");
    }
    out->bins = bn;
    out->rho = bn->rho;
    out->reach = 2.0 * (out->rho + rmax) + margin;
    return fill_layer(ctx, atoms, box, inv, h, lo, hi, rmax, margin, opt, out);
}

/* The images within out->reach of the atoms (fractional ranges lo, hi of
 * the atoms, heights h), of them those the per-bin reach of out->bins
 * needs (unless opt->full or no bins), then their decimals; validated. */
#define LAYER_CHUNK 8192 /* atoms of one item of the layer's count and fill */

/* The layer's items: item q is shift q / nchunk (s0, s1, s2 from -L
 * upwards, s2 fastest; shift 0 adds nothing) and the atoms of chunk
 * q % nchunk. Without out: counts into kept[q] and layer[q]; with out:
 * writes the kept images from index kept[q] on. */
typedef struct layer_job {
    const vb_sphere_set *atoms;
    const double *inv, *klo, *khi;
    const vbp_bins *bn;
    const vbp_reach *reach;
    int L[3];
    size_t nchunk;
    size_t *kept, *layer;
    vb_periodic_images *out;
} layer_job;

static void layer_item(void *ctx, size_t q, int tid)
{
    (void)tid;
    const layer_job *jb = ctx;
    const vb_sphere_set *atoms = jb->atoms;
    const double *inv = jb->inv;
    size_t sq = q / jb->nchunk, i0 = q % jb->nchunk * LAYER_CHUNK;
    size_t i1 = i0 + LAYER_CHUNK < atoms->n ? i0 + LAYER_CHUNK : atoms->n;
    size_t n1 = (size_t)(2 * jb->L[1] + 1), n2 = (size_t)(2 * jb->L[2] + 1);
    const int sh[3] = {(int)(sq / (n1 * n2)) - jb->L[0], (int)(sq / n2 % n1) - jb->L[1],
                       (int)(sq % n2) - jb->L[2]};
    if (sh[0] == 0 && sh[1] == 0 && sh[2] == 0)
        return;
    size_t w = jb->out ? jb->kept[q] : 0, lay = 0;
    for (size_t i = i0; i < i1; i++) {
        int in = 1;
        double f[3];
        for (int a = 0; a < 3 && in; a++) {
            f[a] = atoms->x[i] * inv[a] + atoms->y[i] * inv[3 + a] + atoms->z[i] * inv[6 + a] +
                   sh[a];
            in = f[a] >= jb->klo[a] && f[a] <= jb->khi[a];
        }
        if (!in)
            continue;
        lay++;
        if (jb->reach->need && !vbp_reach_keeps(jb->reach, jb->bn, f))
            continue;
        if (jb->out) {
            jb->out->atom[w] = (uint32_t)i;
            for (int a = 0; a < 3; a++)
                jb->out->shift[w][a] = (int16_t)sh[a];
        }
        w++;
    }
    if (!jb->out) {
        jb->kept[q] = w;
        jb->layer[q] = lay;
    }
}

/* The decimals and doubles of spheres [q LAYER_CHUNK, ...) of the set;
 * bad[q]: the first whose image is beyond 18 digits, or SIZE_MAX. */
typedef struct dec_job {
    const vb_sphere_set *atoms;
    vb_periodic_images *out;
    vb_decimal v[3][3]; /* the box's edge vectors' x, y, z components */
    size_t total;
    size_t *bad;
} dec_job;

static void dec_chunk(void *ctx, size_t q, int tid)
{
    (void)tid;
    const dec_job *dj = ctx;
    const vb_sphere_set *atoms = dj->atoms;
    vb_periodic_images *out = dj->out;
    vb_sphere_set *s = out->set;
    size_t k1 = (q + 1) * LAYER_CHUNK < dj->total ? (q + 1) * LAYER_CHUNK : dj->total;
    dj->bad[q] = SIZE_MAX;
    for (size_t k = q * LAYER_CHUNK; k < k1; k++) {
        uint32_t i = out->atom[k];
        const int sh[3] = {out->shift[k][0], out->shift[k][1], out->shift[k][2]};
        if (dec_image(atoms->ex[i], sh, dj->v[0], &s->ex[k]) != VB_OK ||
            dec_image(atoms->ey[i], sh, dj->v[1], &s->ey[k]) != VB_OK ||
            dec_image(atoms->ez[i], sh, dj->v[2], &s->ez[k]) != VB_OK) {
            dj->bad[q] = k;
            return;
        }
        int same = k < out->n0;
        s->x[k] = same ? atoms->x[i] : vb_decimal_double(s->ex[k]);
        s->y[k] = same ? atoms->y[i] : vb_decimal_double(s->ey[k]);
        s->z[k] = same ? atoms->z[i] : vb_decimal_double(s->ez[k]);
        s->r[k] = atoms->r[i];
        s->er[k] = atoms->er[i];
        s->line[k] = atoms->line ? atoms->line[i] : 0;
        if (s->info)
            s->info[k] = atoms->info[i];
    }
}

static int fill_layer(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                      const double inv[9], const double h[3], const double lo[3],
                      const double hi[3], double rmax, double margin,
                      const vb_periodic_image_opt *opt, vb_periodic_images *out)
{
    size_t n0 = atoms->n;
    vbp_bins *bn = out->bins;
    int rc;
    double hmin = fmin(h[0], fmin(h[1], h[2]));
    if (out->reach > MAX_LAYERS * hmin) {
        double rho_msg = out->rho;
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_EINPUT_BOX_SMALL, atoms->source, 0,
                        "periodic box too small for its atoms: a cell may reach %.6g, more than "
                        "%g box heights (the smallest is %.6g; empty spheres up to %.6g)",
                        out->reach, MAX_LAYERS, hmin, rho_msg);
    }
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
    vbp_reach reach;
    memset(&reach, 0, sizeof reach);
    int full = !bn || (opt && opt->full);
    rc = full ? 1 : vbp_reach_build(bn, box, atoms, klo, khi, rmax, margin, &reach);
    if (rc == VB_ENOMEM) {
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic reach)");
    }
    if (rc != VB_OK && bn) { /* the full layer: rho alone bounds t */
        vbp_bins_free(bn);
        free(bn);
        out->bins = NULL;
    }
    /* Count, then fill: atoms first, then the images shift by shift, each
     * shift's atoms in chunks of LAYER_CHUNK (layer_job: counted on the
     * threads, placed by the prefix sums of the counts in item order, the
     * order one thread would take). */
    int nt = vb_threads(0);
    layer_job jb = {.atoms = atoms, .inv = inv, .klo = klo, .khi = khi, .bn = bn,
                    .reach = &reach, .L = {L[0], L[1], L[2]}};
    jb.nchunk = (n0 + LAYER_CHUNK - 1) / LAYER_CHUNK;
    size_t nshift = (size_t)(2 * L[0] + 1) * (size_t)(2 * L[1] + 1) * (size_t)(2 * L[2] + 1);
    size_t items = nshift * jb.nchunk;
    jb.kept = calloc(items + 1, sizeof *jb.kept);
    jb.layer = calloc(items, sizeof *jb.layer);
    if (!jb.kept || !jb.layer) {
        free(jb.kept);
        free(jb.layer);
        vbp_reach_free(&reach);
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic images)");
    }
    vb_parallel_for(layer_item, &jb, items, nt);
    size_t total = n0, layer = n0;
    for (size_t q = 0; q < items; q++) {
        size_t c = jb.kept[q];
        jb.kept[q] = total;
        total += c;
        layer += jb.layer[q];
    }
    jb.kept[items] = total;
    out->layer_spheres = layer;
    if (total > (size_t)UINT32_MAX - 2) {
        free(jb.kept);
        free(jb.layer);
        vbp_reach_free(&reach);
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_EINPUT_TOOLARGE, atoms->source, 0,
                        "%zu spheres with the periodic images", total);
    }
    out->atom = malloc(total * sizeof *out->atom);
    out->shift = calloc(total, sizeof *out->shift);
    if (!out->atom || !out->shift || alloc_set(atoms, total, &out->set) != VB_OK) {
        free(jb.kept);
        free(jb.layer);
        vbp_reach_free(&reach);
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (%zu periodic spheres)", total);
    }
    for (size_t i = 0; i < n0; i++)
        out->atom[i] = (uint32_t)i;
    jb.out = out;
    vb_parallel_for(layer_item, &jb, items, nt);
    free(jb.kept);
    free(jb.layer);
    vbp_reach_free(&reach);
    out->n0 = n0;
    vb_sphere_set *s = out->set;
    dec_job dj = {atoms,
                  out,
                  {{box->ev[0], box->ev[3], box->ev[6]},
                   {box->ev[1], box->ev[4], box->ev[7]},
                   {box->ev[2], box->ev[5], box->ev[8]}},
                  total,
                  NULL};
    size_t nck = (total + LAYER_CHUNK - 1) / LAYER_CHUNK;
    dj.bad = malloc(nck * sizeof *dj.bad);
    if (!dj.bad) {
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic images)");
    }
    vb_parallel_for(dec_chunk, &dj, nck, nt);
    size_t bad = SIZE_MAX;
    for (size_t q = 0; q < nck && bad == SIZE_MAX; q++)
        bad = dj.bad[q];
    free(dj.bad);
    if (bad != SIZE_MAX) {
        uint32_t i = out->atom[bad];
        vb_periodic_images_free(out);
        return vb_error(ctx, VB_EINPUT_MAGNITUDE, atoms->source, atoms->line ? atoms->line[i] : 0,
                        "an image of atom %u has a coordinate beyond 18 digits", (unsigned)i);
    }
    /* The atoms' own validation warned of contained atoms (W701) once;
     * their images repeat them, silently. */
    rc = vbi_spheres_validate(ctx, s, 4, 0);
    if (rc != VB_OK)
        vb_periodic_images_free(out);
    return rc;
}
