/* Conservative neighbour culling: which bisectors a ray of base i must test.
 *
 * Directions are split into 6*T*T tiles (T x T per cube face); tile P is
 * contained in a cone of half-angle theta around its centre direction d0
 * (the farthest point of the spherical quadrilateral from d0 is a corner, as
 * the distance to d0 is monotone along great-circle arcs shorter than pi).
 * In the normalised frame a neighbour's ray hit is s(d) = num / (2 g(d)) with
 * g(d) = d.e + delta (vb_geom_shared.h). With alpha the angle between d0 and
 * e, over the cone
 *     g_min = |e| cos(min(pi, alpha + theta)) + delta,
 *     g_max = |e| cos(max(0, alpha - theta)) + delta.
 * Upper bound of the lower envelope on P: T_P = min over j with g_min > 0 of
 * num / (2 g_min), and the clip distance when no such j exists. A neighbour
 * can win or tie anywhere on P only if g_max > 0 and num / (2 g_max) <= T_P;
 * all others are culled, so the envelope on P, including the lowest-id rule
 * on ties, is the same as over all n - 1 bisectors. Tiles are refined as a
 * hierarchy (T = 1, 2, 4, ...): a child tile's cone lies in its parent's, so
 * whatever the parent culled cannot matter in the child, and the child only
 * filters its parent's list (outward tiles of hull spheres start huge). Which spheres to look at
 * at all: a hit point p = s d satisfies |p - e| = s + delta and |p - e| >=
 * |e| - s, so s >= (|e| - delta) / 2 and no sphere farther than
 * 2 T_max R_i + R_j - R_i from c_i can matter (the bound of issue 3).
 * The same holds per tile: bisector j can matter on tile P only if
 * s_min(j) = (|e| - delta) / 2 <= T_P. So when the first look (a shell of
 * contact distance) leaves some tile unbounded or loosely bounded and the
 * query must widen (hull spheres: to every sphere), the second look skips,
 * on each tile, the bisectors with s_min above the largest first-look T_P
 * of its finest descendants (a T_P over a subset bounds the envelope too)
 * before any cone bound is computed: only the open tiles pay for the far
 * spheres.
 * theta carries a margin of 1e-7 rad and the bounds a relative margin of
 * 1e-9, far above the rounding errors of these few operations. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbs_internal.h"

#define THETA_MARGIN 1e-7
#define REL_MARGIN 1e-9

int vbs_tiles_build(vb_ctx *ctx, unsigned T, vbs_tiles *t)
{
    size_t nt = 6u * (size_t)T * T;
    t->T = T;
    t->dir = malloc(3 * nt * sizeof *t->dir);
    t->cth = malloc(nt * sizeof *t->cth);
    t->sth = malloc(nt * sizeof *t->sth);
    if (!t->dir || !t->cth || !t->sth) {
        vbs_tiles_free(t);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (tiles)");
    }
    for (unsigned f = 0; f < 6; f++)
        for (unsigned tv = 0; tv < T; tv++)
            for (unsigned tu = 0; tu < T; tu++) {
                size_t k = ((size_t)f * T + tv) * T + tu;
                double u0 = -1.0 + 2.0 * tu / T, u1 = -1.0 + 2.0 * (tu + 1) / T;
                double v0 = -1.0 + 2.0 * tv / T, v1 = -1.0 + 2.0 * (tv + 1) / T;
                double *d0 = t->dir + 3 * k;
                vbs_face_dir(f, 0.5 * (u0 + u1), 0.5 * (v0 + v1), d0);
                double theta = 0.0;
                for (int c = 0; c < 4; c++) {
                    double dc[3];
                    vbs_face_dir(f, (c & 1) ? u1 : u0, (c & 2) ? v1 : v0, dc);
                    double cs = d0[0] * dc[0] + d0[1] * dc[1] + d0[2] * dc[2];
                    double a = acos(cs > 1.0 ? 1.0 : cs);
                    if (a > theta)
                        theta = a;
                }
                theta += THETA_MARGIN;
                t->cth[k] = cos(theta);
                t->sth[k] = sin(theta);
            }
    return VB_OK;
}

void vbs_tiles_free(vbs_tiles *t)
{
    free(t->dir);
    free(t->cth);
    free(t->sth);
    t->dir = t->cth = t->sth = NULL;
}

void vbs_base_data_free(vbs_base_data *bd)
{
    free(bd->bis);
    free(bd->norm);
    free(bd->gb);
    free(bd->tile_off);
    free(bd->tile_idx);
    free(bd->near);
    free(bd->keep);
    free(bd->remap);
    free(bd->sortkey);
    free(bd->tmp);
    free(bd->co_off);
    free(bd->co_idx);
    free(bd->lim);
    free(bd->smin);
    for (int k = 0; k < 2; k++) {
        free(bd->lvl_off[k]);
        free(bd->lvl_idx[k]);
    }
    memset(bd, 0, sizeof *bd);
}

/* Same decimal value (mantissas without trailing zeros). */
static int same_decimal(vb_decimal a, vb_decimal b)
{
    while (a.mant != 0 && a.mant % 10 == 0) {
        a.mant /= 10;
        a.exp10++;
    }
    while (b.mant != 0 && b.mant % 10 == 0) {
        b.mant /= 10;
        b.exp10++;
    }
    return a.mant == b.mant && (a.mant == 0 || a.exp10 == b.exp10);
}

/* A distance beyond every vertex, from any sphere's centre (capped at
 * 1e200). D is the bounding-box diagonal plus twice the largest radius, q
 * the finest decimal unit of the input, M = D/q; in units of q, with the
 * origin at a member c_0 of a vertex's quadruple, centres and radii are
 * integers of size at most M.
 * Equal radii: D * 128 M^3. The circumcentre of four non-coplanar centres
 * is adj(A) b / det(A) with integer det(A) >= 1, |adj| <= 8 M^2,
 * |b| <= 3 M^2 (A = 2 (c_k - c_0)).
 * Unequal radii: D * 3e4 M^7. A vertex p with tangent radius t is at
 * |p - c_0| = r_0 + t, so bounding t is enough. Subtracting the tangency
 * equations gives A p = b + t d (d_k = -2 (r_k - r_0), |d| <= 2 M). If
 * det(A) != 0, p = (u + t w) / det(A) with u = adj(A) b, w = adj(A) d
 * (|u| <= 125 M^4, |w| <= 84 M^3, |det| <= 48 M^3), and |p - c_0|^2 =
 * (r_0 + t)^2 becomes an integer quadratic alpha t^2 + beta t + gamma = 0
 * with |alpha| <= 9400 M^6, |beta| <= 25600 M^7, |gamma| <= 18000 M^8:
 * Cauchy's bound gives |t| <= 1 + 25600 M^8 (alpha != 0; else
 * |t| <= |gamma|). If the centres are coplanar, the 3 x 4 system in
 * (p, t) has a non-zero 3 x 3 minor only with t's column (the coordinate
 * columns span the plane), and Cramer's rule gives |t| <= 72 M^4. A
 * quadruple without such an isolated solution has a curve of common
 * tangent spheres and is not what makes an isolated vertex. So
 * |p - c_0| <= q (M + 1 + 25600 M^8) <= 3e4 D M^7. Rays are clipped
 * there, and a ray that meets no bisector closer is "infinite". */
double vbs_clip_distance(const vb_sphere_set *set)
{
    double lo[3] = {set->x[0], set->y[0], set->z[0]}, hi[3] = {lo[0], lo[1], lo[2]};
    double rmax = 0.0;
    int emin = 400;
    for (size_t i = 0; i < set->n; i++) {
        const double p[3] = {set->x[i], set->y[i], set->z[i]};
        for (int a = 0; a < 3; a++) {
            if (p[a] < lo[a])
                lo[a] = p[a];
            if (p[a] > hi[a])
                hi[a] = p[a];
        }
        if (set->r[i] > rmax)
            rmax = set->r[i];
        if (set->ex) {
            const vb_decimal *ds[4] = {set->ex + i, set->ey + i, set->ez + i, set->er + i};
            for (int a = 0; a < 4; a++)
                if (ds[a]->mant != 0 && ds[a]->exp10 < emin)
                    emin = ds[a]->exp10;
        }
    }
    double D = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2])) + 2.0 * rmax;
    double q = emin == 400 ? D * 1e-9 : pow(10.0, emin);
    double M = D / q;
    int equal = 1;
    for (size_t i = 1; i < set->n && equal; i++)
        equal = set->er ? same_decimal(set->er[i], set->er[0]) : set->r[i] == set->r[0];
    double L = equal ? D * 128.0 * M * M * M : D * 3e4 * pow(M, 7.0);
    if (!(L < 1e200))
        L = 1e200;
    return L;
}

/* The matching tolerance, and the rounding guards of the tangent tests
 * scaled from it, follow the input's size as the clip distance does. */
double vb_sampler_default_tol(const vb_sphere_set *set)
{
    double lo[3] = {set->x[0], set->y[0], set->z[0]}, hi[3] = {lo[0], lo[1], lo[2]};
    for (size_t i = 0; i < set->n; i++) {
        const double p[3] = {set->x[i] - set->r[i], set->y[i] - set->r[i], set->z[i] - set->r[i]};
        const double q[3] = {set->x[i] + set->r[i], set->y[i] + set->r[i], set->z[i] + set->r[i]};
        for (int a = 0; a < 3; a++) {
            if (p[a] < lo[a])
                lo[a] = p[a];
            if (q[a] > hi[a])
                hi[a] = q[a];
        }
    }
    double d2 = 0.0;
    for (int a = 0; a < 3; a++)
        d2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    return 1e-5 * sqrt(d2);
}

/* Bisectors of base i with the spheres in bd->near, with |e|
 * of each kept beside it for the cone bounds. */
static int make_bisectors(const vb_sphere_set *s, uint32_t i, vbs_base_data *bd)
{
    bd->nbis = 0;
    if (bd->bis_cap < bd->nnear) {
        vbs_bisector *b = realloc(bd->bis, bd->nnear * sizeof *b);
        double *ne = realloc(bd->norm, bd->nnear * sizeof *ne);
        if (b)
            bd->bis = b;
        if (ne)
            bd->norm = ne;
        if (!b || !ne)
            return VB_ENOMEM;
        bd->bis_cap = bd->nnear;
        double *gb = realloc(bd->gb, 2 * bd->nnear * sizeof *gb);
        if (!gb)
            return VB_ENOMEM;
        bd->gb = gb;
    }
    for (size_t k = 0; k < bd->nnear; k++) {
        uint32_t j = bd->near[k];
        if (j == i)
            continue;
        vbs_bisector *b = &bd->bis[bd->nbis];
        if (vbs_bisector_make(s->x[i], s->y[i], s->z[i], s->r[i], vbs_frame_scale(s->r[i]),
                              s->x[j], s->y[j], s->z[j], s->r[j], j, b)) {
            bd->norm[bd->nbis] = sqrt(b->ex * b->ex + b->ey * b->ey + b->ez * b->ez);
            bd->nbis++;
        }
    }
    return VB_OK;
}

static void cone_bounds(const vbs_tiles *t, size_t k, const vbs_bisector *b, double ne,
                        double *gmin, double *gmax)
{
    const double *d0 = t->dir + 3 * k;
    double c = (d0[0] * b->ex + d0[1] * b->ey + d0[2] * b->ez) / ne;
    if (c > 1.0)
        c = 1.0;
    if (c < -1.0)
        c = -1.0;
    double sn = sqrt(1.0 - c * c), ct = t->cth[k], st = t->sth[k];
    double lo = c < -ct ? -1.0 : c * ct - sn * st;
    double hi = c >= ct ? 1.0 : c * ct + sn * st;
    double m = REL_MARGIN * (ne + fabs(b->delta));
    *gmin = ne * lo + b->delta - m;
    *gmax = ne * hi + b->delta + m;
}

static int push_u32(uint32_t **v, size_t *n, size_t *cap, uint32_t x)
{
    if (VB_ARRAY_FIT(*v, *cap, *n + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    (*v)[(*n)++] = x;
    return VB_OK;
}

static int cmp_u64(const void *pa, const void *pb)
{
    uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return (a > b) - (a < b);
}

static int cmp_bis_id(const void *pa, const void *pb)
{
    const vbs_bisector *a = pa, *b = pb;
    return (a->id > b->id) - (a->id < b->id);
}

/* One level of the tile hierarchy: for each tile, the envelope bound T_P
 * over its parent's list and the parent's entries that can reach below it.
 * Level 0 (one tile per face) starts from every bisector. The lists of
 * level l go to (off, idx); the parent lists are (poff, pidx). Returns the
 * largest T_P of the level in *tmax. */
static int cull_level(const vbs_tiles *t, const vbs_base_data *bd, double *gb, const uint32_t *poff,
                      const uint32_t *pidx, unsigned pT, const double *lim, uint32_t *off,
                      uint32_t **idx, size_t *nidx, size_t *cap, double clip, double *tp_out,
                      double *tmax)
{
    unsigned T = t->T;
    size_t nt = 6u * (size_t)T * T;
    *nidx = 0;
    *tmax = 0.0;
    for (size_t k = 0; k < nt; k++) {
        size_t f = k / ((size_t)T * T), r = k % ((size_t)T * T);
        size_t tv = r / T, tu = r % T;
        size_t lo = 0, hi = bd->nbis;
        if (pidx) {
            size_t pk = (f * pT + tv * pT / T) * pT + tu * pT / T;
            lo = poff[pk];
            hi = poff[pk + 1];
        }
        double tp = clip;
        for (size_t q = lo; q < hi; q++) {
            uint32_t b = pidx ? pidx[q] : (uint32_t)q;
            if (lim && bd->smin[b] > lim[k]) { /* out of reach on every ray of the tile */
                gb[2 * (q - lo)] = gb[2 * (q - lo) + 1] = -1.0;
                continue;
            }
            cone_bounds(t, k, bd->bis + b, bd->norm[b], &gb[2 * (q - lo)], &gb[2 * (q - lo) + 1]);
            /* Divide only when the bound can improve (rounding in the
             * product test only ever leaves tp larger: still an upper bound). */
            double gmin = gb[2 * (q - lo)], num = bd->bis[b].num;
            if (gmin > 0.0 && num < 2.0 * gmin * tp) {
                double sb = num / (2.0 * gmin);
                if (sb < tp)
                    tp = sb;
            }
        }
        tp *= 1.0 + REL_MARGIN;
        if (tp_out)
            tp_out[k] = tp;
        if (tp > *tmax)
            *tmax = tp;
        off[k] = (uint32_t)*nidx;
        for (size_t q = lo; q < hi; q++) {
            uint32_t b = pidx ? pidx[q] : (uint32_t)q;
            /* num / (2 gmax) > tp, without the division and with a margin
             * over its rounding: keeping a few more is always safe. */
            double gmax = gb[2 * (q - lo) + 1];
            if (!(gmax > 0.0) || bd->bis[b].num > 2.0 * gmax * tp * (1.0 + REL_MARGIN))
                continue;
            if (push_u32(idx, nidx, cap, b))
                return VB_ENOMEM;
        }
    }
    off[nt] = (uint32_t)*nidx;
    return VB_OK;
}

/* Offset of level l's tiles in bd->lim (levels T = 1, 2, 4, ... in a row). */
static size_t lim_at(int l)
{
    size_t at = 0;
    for (int k = 0; k < l; k++)
        at += 6u * ((size_t)1 << k) * ((size_t)1 << k);
    return at;
}

/* Runs the hierarchy (T = 1, 2, 4, ..., finest) over the base's current
 * bisectors; the finest lists end in bd->tile_off / bd->tile_idx. With
 * use_lim, tiles skip bisectors beyond bd->lim (second look); otherwise the
 * finest level's T_P go to the finest part of bd->lim. Returns the finest
 * level's largest T_P in *tmax. */
static int cull_hierarchy(const vbs_culler *cu, vbs_base_data *bd, double clip, int use_lim,
                          double *tmax)
{
    uint32_t *poff = NULL, *pidx = NULL;
    unsigned pT = 0;
    for (int l = 0; l < cu->nlevels; l++) {
        const vbs_tiles *t = cu->levels + l;
        int last = l + 1 == cu->nlevels;
        uint32_t *off = last ? bd->tile_off : bd->lvl_off[l & 1];
        uint32_t **idx = last ? &bd->tile_idx : &bd->lvl_idx[l & 1];
        size_t *nidx = last ? &bd->nidx : &bd->lvl_n[l & 1];
        size_t *cap = last ? &bd->idx_cap : &bd->lvl_cap[l & 1];
        double *lim = bd->lim + lim_at(l);
        if (cull_level(t, bd, bd->gb, poff, pidx, pT, use_lim ? lim : NULL, off, idx, nidx, cap,
                       clip, !use_lim && last ? lim : NULL, tmax))
            return VB_ENOMEM;
        poff = off;
        pidx = *idx;
        pT = t->T;
    }
    return VB_OK;
}

/* The T = 2 level (or the finest, if coarser), renumbered to the kept
 * bisectors (bd->remap); entries culled everywhere at the finest level are
 * dropped, which keeps the lists sufficient (the finest tiles cover every
 * ray). */
static int coarse_lists(vbs_base_data *bd, const vbs_culler *cu)
{
    const vbs_tiles *fine = cu->levels + cu->nlevels - 1;
    int from_fine = fine->T <= VBS_COARSE_T;
    unsigned T = from_fine ? fine->T : VBS_COARSE_T;
    size_t nt = 6u * (size_t)T * T;
    const uint32_t *off = from_fine ? bd->tile_off : bd->lvl_off[1];
    const uint32_t *idx = from_fine ? bd->tile_idx : bd->lvl_idx[1];
    if (!bd->co_off && !(bd->co_off = malloc((6u * VBS_COARSE_T * VBS_COARSE_T + 1) * sizeof *bd->co_off)))
        return VB_ENOMEM;
    bd->nco = 0;
    for (size_t k = 0; k < nt; k++) {
        bd->co_off[k] = (uint32_t)bd->nco;
        for (uint32_t q = off[k]; q < off[k + 1]; q++) {
            size_t pos = from_fine ? idx[q] : bd->remap[idx[q]];
            if (pos < bd->nbis && push_u32(&bd->co_idx, &bd->nco, &bd->co_cap, (uint32_t)pos))
                return VB_ENOMEM;
        }
    }
    bd->co_off[nt] = (uint32_t)bd->nco;
    return VB_OK;
}

/* Coarse lists that name every bisector (all-pairs runs) or none (empty
 * cells). */
static int coarse_uniform(vbs_base_data *bd, const vbs_culler *cu, int all)
{
    unsigned T = cu->levels[cu->nlevels - 1].T;
    if (T > VBS_COARSE_T)
        T = VBS_COARSE_T;
    size_t nt = 6u * (size_t)T * T;
    if (!bd->co_off && !(bd->co_off = malloc((nt + 1) * sizeof *bd->co_off)))
        return VB_ENOMEM;
    bd->nco = 0;
    for (size_t k = 0; k < nt; k++) {
        bd->co_off[k] = (uint32_t)bd->nco;
        for (size_t q = 0; all && q < bd->nbis; q++)
            if (push_u32(&bd->co_idx, &bd->nco, &bd->co_cap, (uint32_t)q))
                return VB_ENOMEM;
    }
    bd->co_off[nt] = (uint32_t)bd->nco;
    return VB_OK;
}

/* The second look's limits: bd->lim of the coarser levels from the finest
 * one the first look left there (each tile: the largest of its four
 * children), and s_min of every bisector, lowered by a relative margin far
 * above its rounding error. */
static int second_look_limits(const vbs_culler *cu, vbs_base_data *bd)
{
    if (bd->smin_cap < bd->nbis) {
        double *p = realloc(bd->smin, bd->nbis * sizeof *p);
        if (!p)
            return VB_ENOMEM;
        bd->smin = p;
        bd->smin_cap = bd->nbis;
    }
    for (size_t q = 0; q < bd->nbis; q++) {
        double ne = bd->norm[q], dl = bd->bis[q].delta;
        bd->smin[q] = 0.5 * (ne - dl) - REL_MARGIN * (ne + fabs(dl));
    }
    for (int l = cu->nlevels - 2; l >= 0; l--) {
        size_t T = (size_t)1 << l;
        double *lim = bd->lim + lim_at(l), *child = bd->lim + lim_at(l + 1);
        for (size_t f = 0; f < 6; f++)
            for (size_t tv = 0; tv < T; tv++)
                for (size_t tu = 0; tu < T; tu++) {
                    double m = 0.0;
                    for (size_t c = 0; c < 4; c++) {
                        double x = child[(f * 2 * T + 2 * tv + c / 2) * 2 * T + 2 * tu + c % 2];
                        m = x > m ? x : m;
                    }
                    lim[(f * T + tv) * T + tu] = m;
                }
    }
    return VB_OK;
}

int vbs_cull_base(vb_ctx *ctx, const vbs_culler *cu, uint32_t i, vbs_base_data *bd)
{
    const vb_sphere_set *s = cu->set;
    const vbs_tiles *fine = cu->levels + cu->nlevels - 1;
    size_t nt = 6u * (size_t)fine->T * fine->T;
    if (!bd->tile_off) {
        bd->tile_off = malloc((nt + 1) * sizeof *bd->tile_off);
        bd->lvl_off[0] = malloc((nt + 1) * sizeof *bd->lvl_off[0]);
        bd->lvl_off[1] = malloc((nt + 1) * sizeof *bd->lvl_off[1]);
        bd->lim = malloc(lim_at(cu->nlevels) * sizeof *bd->lim);
        if (!bd->tile_off || !bd->lvl_off[0] || !bd->lvl_off[1] || !bd->lim)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (culling)");
    }
    bd->nbis = bd->nidx = bd->nnear = 0;
    memset(bd->tile_off, 0, (nt + 1) * sizeof *bd->tile_off);
    if (s->contained && s->contained[i]) /* empty cell: nothing matters */
        return coarse_uniform(bd, cu, 0) ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory") : VB_OK;
    const double c[3] = {s->x[i], s->y[i], s->z[i]};
    double ri = s->r[i], sc = vbs_frame_scale(ri), clip = cu->clip / sc, rmax = cu->hash->rmax;
    int rc;
    if (cu->all_pairs) {
        rc = vbs_hash_query(cu->hash, c, DBL_MAX / 4, &bd->near, &bd->nnear, &bd->near_cap);
        if (rc == VB_OK)
            rc = make_bisectors(s, i, bd);
        if (rc != VB_OK)
            return vb_error(ctx, rc, NULL, 0, "out of memory (culling)");
        if (bd->nbis)
            qsort(bd->bis, bd->nbis, sizeof *bd->bis, cmp_bis_id);
        for (size_t k = 0; k < nt; k++) {
            bd->tile_off[k] = (uint32_t)bd->nidx;
            for (size_t q = 0; q < bd->nbis; q++)
                if (push_u32(&bd->tile_idx, &bd->nidx, &bd->idx_cap, (uint32_t)q))
                    return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (culling)");
        }
        bd->tile_off[nt] = (uint32_t)bd->nidx;
        return coarse_uniform(bd, cu, 1) ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory") : VB_OK;
    }
    /* First look: a shell of typical contact distance bounds the envelope. */
    double r0 = 2.0 * (ri + rmax), tmax;
    rc = vbs_hash_query(cu->hash, c, r0, &bd->near, &bd->nnear, &bd->near_cap);
    if (rc == VB_OK)
        rc = make_bisectors(s, i, bd);
    if (rc == VB_OK)
        rc = cull_hierarchy(cu, bd, clip, 0, &tmax);
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "out of memory (culling)");
    double r1 = (sc * 2.0 * tmax + rmax - ri) * (1.0 + REL_MARGIN);
    if (r1 > r0) {
        bd->nnear = 0;
        rc = vbs_hash_query(cu->hash, c, r1, &bd->near, &bd->nnear, &bd->near_cap);
        if (rc == VB_OK)
            rc = make_bisectors(s, i, bd);
        if (rc == VB_OK)
            rc = second_look_limits(cu, bd);
        if (rc == VB_OK)
            rc = cull_hierarchy(cu, bd, clip, 1, &tmax);
        if (rc != VB_OK)
            return vb_error(ctx, rc, NULL, 0, "out of memory (culling)");
    }
    /* Compact to the bisectors some finest tile uses, sorted by id (the
     * vertex stage finds a colour's bisector by binary search). */
    uint8_t *keep = realloc(bd->keep, bd->nbis ? bd->nbis : 1);
    if (!keep)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (culling)");
    bd->keep = keep;
    memset(keep, 0, bd->nbis);
    for (size_t k = 0; k < bd->nidx; k++)
        keep[bd->tile_idx[k]] = 1;
    /* Sort the kept ones by id (ids are unique within a base) through
     * (id, old position) keys, and renumber the lists through the map old
     * position -> new position (culled ones: UINT32_MAX). */
    if (bd->remap_cap < bd->nbis) {
        uint32_t *rm = realloc(bd->remap, bd->nbis * sizeof *rm);
        uint64_t *sk = rm ? realloc(bd->sortkey, bd->nbis * sizeof *sk) : NULL;
        vbs_bisector *tb = sk ? realloc(bd->tmp, bd->nbis * sizeof *tb) : NULL;
        if (rm)
            bd->remap = rm;
        if (sk)
            bd->sortkey = sk;
        if (tb)
            bd->tmp = tb;
        if (!tb)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (culling)");
        bd->remap_cap = bd->nbis;
    }
    size_t m = 0;
    for (size_t q = 0; q < bd->nbis; q++) {
        bd->remap[q] = UINT32_MAX;
        if (keep[q])
            bd->sortkey[m++] = (uint64_t)bd->bis[q].id << 32 | (uint64_t)q;
    }
    if (m)
        qsort(bd->sortkey, m, sizeof *bd->sortkey, cmp_u64);
    if (bd->nbis)
        memcpy(bd->tmp, bd->bis, bd->nbis * sizeof *bd->bis);
    for (size_t k = 0; k < m; k++) {
        uint32_t q = (uint32_t)(bd->sortkey[k] & 0xffffffffu);
        bd->bis[k] = bd->tmp[q];
        bd->remap[q] = (uint32_t)k;
    }
    for (size_t k = 0; k < bd->nidx; k++)
        bd->tile_idx[k] = bd->remap[bd->tile_idx[k]];
    bd->nbis = m;
    return coarse_lists(bd, cu) ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (culling)")
                                : VB_OK;
}

