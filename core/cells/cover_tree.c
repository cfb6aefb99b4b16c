/* The tree of the centres behind the direction cover (vb_cover_prepare in
 * vb_cover.h): a bounding-volume hierarchy over a Morton curve, the first
 * guess of the near lists' radius, and the cover's environment built on
 * them. */
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_cover_shared.h"

/* ---- a bounding-volume hierarchy of the centres ------------------------- */

/* Spheres (not contained) sorted along a Morton curve of their centres, in
 * leaves of VBQ_LEAF; a complete binary tree over the leaves (heap order,
 * node 1 the root, leaves from `first`), each node with the box of its
 * centres and the largest radius below it. Conservative by construction:
 * a query prunes a node only when no centre in its box can pass. */
typedef struct bvh {
    uint32_t *ids;     /* m sphere ids in curve order */
    size_t m;
    size_t first;      /* index of the first leaf node; leaves first..2 first-1 */
    double *box;       /* 6 per node: lo xyz, hi xyz (empty: lo > hi) */
    double *rmax;      /* per node */
    double rmax_all;
    double *node8;     /* the host walk's copies (vbq_env): box and rmax, 8 per node */
    double *kxyzr;     /* x, y, z, r of ids[k] at k (kx) and k + kd, 2 kd, 3 kd */
    size_t kd;         /* m and a leaf more, in whole 64-byte lines */
} bvh;

static void bvh_free(bvh *t)
{
    free(t->ids);
    free(t->box);
    free(t->rmax);
    free(t->node8);
    free(t->kxyzr);
}

/* The host walk's copies of t's nodes and spheres (vbq_env's node8 and
 * kx .. kr: the same doubles, each node in one 64-byte line, a leaf's
 * spheres side by side instead of scattered by id; zeros past m). */
static int bvh_pack(const vb_sphere_set *s, bvh *t)
{
    size_t nodes = 2 * t->first;
    t->node8 = aligned_alloc(64, nodes * 8 * sizeof *t->node8);
    size_t kd = (t->m + VBQ_LEAF + 7) / 8 * 8;
    t->kd = kd;
    t->kxyzr = aligned_alloc(64, 4 * kd * sizeof *t->kxyzr);
    if (!t->node8 || !t->kxyzr)
        return VB_ENOMEM;
    for (size_t nd = 0; nd < nodes; nd++) {
        memcpy(t->node8 + 8 * nd, t->box + 6 * nd, 6 * sizeof *t->box);
        t->node8[8 * nd + 6] = t->rmax[nd];
        t->node8[8 * nd + 7] = 0.0;
    }
    memset(t->kxyzr, 0, 4 * kd * sizeof *t->kxyzr);
    for (size_t k = 0; k < t->m; k++) {
        uint32_t i = t->ids[k];
        t->kxyzr[k] = s->x[i];
        t->kxyzr[kd + k] = s->y[i];
        t->kxyzr[2 * kd + k] = s->z[i];
        t->kxyzr[3 * kd + k] = s->r[i];
    }
    return VB_OK;
}

typedef struct mkey {
    uint64_t key;
    uint32_t id;
} mkey;

static int cmp_mkey(const void *pa, const void *pb)
{
    const mkey *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return (a->id > b->id) - (a->id < b->id);
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Spreads the low 21 bits of v to every third bit. */
static uint64_t spread3(uint64_t v)
{
    v &= 0x1fffffu;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

static int bvh_build(const vb_sphere_set *s, bvh *t)
{
    memset(t, 0, sizeof *t);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t m = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->contained[i])
            continue;
        const double p[3] = {s->x[i], s->y[i], s->z[i]};
        for (int a = 0; a < 3; a++) {
            lo[a] = p[a] < lo[a] ? p[a] : lo[a];
            hi[a] = p[a] > hi[a] ? p[a] : hi[a];
        }
        if (s->r[i] > t->rmax_all)
            t->rmax_all = s->r[i];
        m++;
    }
    mkey *k = malloc((m ? m : 1) * sizeof *k);
    t->ids = malloc((m ? m : 1) * sizeof *t->ids);
    size_t leaves = (m + VBQ_LEAF - 1) / VBQ_LEAF, first = 1;
    while (first < leaves)
        first *= 2;
    t->first = first;
    t->m = m;
    t->box = malloc(2 * first * 6 * sizeof *t->box);
    t->rmax = calloc(2 * first, sizeof *t->rmax);
    if (!k || !t->ids || !t->box || !t->rmax) {
        free(k);
        return VB_ENOMEM;
    }
    size_t w = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->contained[i])
            continue;
        const double p[3] = {s->x[i], s->y[i], s->z[i]};
        uint64_t key = 0;
        for (int a = 0; a < 3; a++) {
            double ext = hi[a] - lo[a];
            double q = ext > 0.0 ? (p[a] - lo[a]) / ext * 2097151.0 : 0.0;
            uint64_t c = q > 0.0 ? (uint64_t)q : 0u;
            key |= spread3(c > 2097151u ? 2097151u : c) << a;
        }
        k[w].key = key;
        k[w++].id = (uint32_t)i;
    }
    qsort(k, m, sizeof *k, cmp_mkey);
    for (size_t i = 0; i < m; i++)
        t->ids[i] = k[i].id;
    free(k);
    for (size_t nd = 0; nd < 2 * first; nd++) {
        for (int a = 0; a < 3; a++) {
            t->box[6 * nd + a] = INFINITY;
            t->box[6 * nd + 3 + a] = -INFINITY;
        }
    }
    for (size_t l = 0; l < leaves; l++) {
        size_t nd = first + l;
        for (size_t q = l * VBQ_LEAF; q < m && q < (l + 1) * VBQ_LEAF; q++) {
            uint32_t i = t->ids[q];
            const double p[3] = {s->x[i], s->y[i], s->z[i]};
            for (int a = 0; a < 3; a++) {
                if (p[a] < t->box[6 * nd + a])
                    t->box[6 * nd + a] = p[a];
                if (p[a] > t->box[6 * nd + 3 + a])
                    t->box[6 * nd + 3 + a] = p[a];
            }
            if (s->r[i] > t->rmax[nd])
                t->rmax[nd] = s->r[i];
        }
    }
    for (size_t nd = first - 1; nd >= 1; nd--) {
        for (int a = 0; a < 3; a++) {
            double l0 = t->box[6 * (2 * nd) + a], l1 = t->box[6 * (2 * nd + 1) + a];
            double h0 = t->box[6 * (2 * nd) + 3 + a], h1 = t->box[6 * (2 * nd + 1) + 3 + a];
            t->box[6 * nd + a] = l0 < l1 ? l0 : l1;
            t->box[6 * nd + 3 + a] = h0 > h1 ? h0 : h1;
        }
        double r0 = t->rmax[2 * nd], r1 = t->rmax[2 * nd + 1];
        t->rmax[nd] = r0 > r1 ? r0 : r1;
    }
    return VB_OK;
}

/* The largest side of node nd's box. */
static double node_extent(const bvh *t, size_t nd)
{
    double e = 0.0;
    for (int a = 0; a < 3; a++) {
        double w = t->box[6 * nd + 3 + a] - t->box[6 * nd + a];
        e = w > e ? w : e;
    }
    return e;
}

/* The first guess of a near list's radius: a little more than the median
 * extent of the leaves (eight neighbouring centres), which follows the local
 * density of the input wherever most of it is; or half the median extent
 * of the parents of two leaves (sixteen centres) where that is larger: a
 * lattice whose 2 x 2 x 2 blocks fall exactly into leaves (sc 16^3 along
 * the Morton curve) spans one spacing per leaf and three per parent, where
 * sc 14^3 spans three per leaf; its near list held only the six nearest
 * spheres and nearly every patch fetched (sc 4,096 jittered 1e-12: 269,964
 * fetches against the random twin's 73,228). Elsewhere a parent spans less
 * than twice its leaves (random, fcc, proteins, the capsid: the same
 * guess). The vertices do not depend on it, but the count of quadruples
 * proposed (the output's header) does: without memory for it no other guess
 * is taken, the cover fails (-1). */
static int near_radius(const bvh *t, double *out)
{
    size_t leaves = (t->m + VBQ_LEAF - 1) / VBQ_LEAF;
    *out = 1.0;
    if (leaves == 0)
        return 0;
    double *ext = malloc(leaves * sizeof *ext);
    if (!ext)
        return -1;
    for (size_t l = 0; l < leaves; l++)
        ext[l] = node_extent(t, t->first + l);
    qsort(ext, leaves, sizeof *ext, cmp_double);
    double r = 0.6 * ext[leaves / 2];
    /* the parents of two real leaves */
    size_t np = 0;
    for (size_t nd = t->first / 2; nd < t->first; nd++)
        if (2 * nd + 1 < t->first + leaves)
            ext[np++] = node_extent(t, nd);
    if (np) {
        qsort(ext, np, sizeof *ext, cmp_double);
        double rp = 0.3 * ext[np / 2];
        r = rp > r ? rp : r;
    }
    free(ext);
    *out = r > 0.0 ? r : 1.0;
    return 0;
}

struct vb_cover_tree {
    bvh g;
};

int vb_cover_prepare(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                     vb_cover_tree **tree, vbq_env *e)
{
    *tree = NULL;
    vb_cover_options o = opt ? *opt : (vb_cover_options){0};
    memset(e, 0, sizeof *e);
    e->T = o.tiles ? o.tiles : VB_COVER_DEFAULT_TILES;
    e->min_level = o.min_level ? o.min_level : VB_COVER_DEFAULT_MIN_LEVEL;
    e->max_level = o.max_level ? o.max_level : VB_COVER_MAX_LEVEL;
    e->enum_max = o.enum_max ? o.enum_max : 3u;
    if ((e->T & (e->T - 1u)) || e->T > 16u || e->max_level > VB_COVER_MAX_LEVEL ||
        e->enum_max < 3u || e->enum_max > 64u)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "bad cover options");
    if (!set->contained)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "cover needs a validated sphere set");
    if (set->n > UINT32_MAX - 1)
        return vb_error(ctx, VB_EINPUT_TOOLARGE, NULL, 0, "more than 2^32 - 2 spheres");
    vb_cover_tree *t = calloc(1, sizeof *t);
    if (!t || bvh_build(set, &t->g) != VB_OK || bvh_pack(set, &t->g) != VB_OK ||
        near_radius(&t->g, &e->near) != 0) {
        if (t)
            bvh_free(&t->g);
        free(t);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover tree)");
    }
    bvh *g = &t->g;
    e->x = set->x;
    e->y = set->y;
    e->z = set->z;
    e->r = set->r;
    e->box = g->box;
    e->rmax = g->rmax;
    e->ids = g->ids;
    e->first = (uint32_t)g->first;
    e->m = (uint32_t)g->m;
    e->rmax_all = g->rmax_all;
    e->tmax = o.tmax > 0.0 ? o.tmax : (double)INFINITY;
    e->host = set;
    e->node8 = g->node8;
    e->kx = g->kxyzr;
    e->ky = g->kxyzr + g->kd;
    e->kz = g->kxyzr + 2 * g->kd;
    e->kr = g->kxyzr + 3 * g->kd;
    *tree = t;
    return VB_OK;
}

void vb_cover_tree_free(vb_cover_tree *t)
{
    if (t)
        bvh_free(&t->g);
    free(t);
}
