/* Matching across cells (Sec. 5.4), the targeted search for incompletely
 * matched vertices (5.5), the empty-tangent-sphere test, and our additions
 * that only ever add candidates for the exact certifier to judge.
 *
 * Candidates that lie within tol of each other (point and tangent radius)
 * are one vertex; its members are the union of their ids (so a degenerate
 * vertex seen as different quadruples from different cells is one vertex),
 * and it is complete when every member produced a candidate from its own
 * cell. An incomplete vertex whose tangent sphere is cut by another sphere
 * (beyond tol) is spurious and searched no further; for the others, each
 * missing member m shoots the ray from c_m to the vertex, centres a grid
 * cell on it of half the original size, and runs the vertex stage there
 * (Newton, subdivision) with m's coarse culling lists; the cell shrinks by
 * half until the vertex is found or the depth is spent.
 *
 * Then every distinct quadruple gets both of its tangent spheres (Fig. 8)
 * from the double solver, each kept when no sphere cuts it by more than a
 * rounding guard; a sampled quadruple whose own sphere is cut tries the
 * quadruples with the intruder swapped in; and the neighbourhood completion
 * (complete_ring) walks from every kept vertex to its neighbours. */
#include <stdlib.h>
#include <string.h>

#include "vbs_internal.h"

/* Intruder swaps tried from a sampled quadruple whose tangent sphere is not
 * empty (collinear and coplanar corpus cases need two). */
#define VBS_SWAP_DEPTH 2

typedef struct match_ctx {
    const vb_sphere_set *set;
    double tol;
    uint32_t *parent;
    uint32_t *order;      /* candidates sorted by x */
    uint32_t *cl_of;      /* cluster of each candidate */
    uint32_t *cl_start;   /* CSR of candidates per cluster */
    uint32_t *cl_items;
    size_t ncl;
} match_ctx;

static uint32_t find(uint32_t *p, uint32_t a)
{
    while (p[a] != a) {
        p[a] = p[p[a]];
        a = p[a];
    }
    return a;
}

typedef struct xkey {
    double x;
    uint32_t k;
} xkey;

static int cmp_x(const void *pa, const void *pb)
{
    const xkey *a = pa, *b = pb;
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

static void match_free(match_ctx *m)
{
    free(m->parent);
    free(m->order);
    free(m->cl_of);
    free(m->cl_start);
    free(m->cl_items);
    m->parent = m->order = m->cl_of = m->cl_start = m->cl_items = NULL;
    m->ncl = 0;
}

/* Clusters of candidates closer than tol; clusters are numbered in the order
 * of their first candidate, candidates inside a cluster keep their order. */
static int cluster(match_ctx *m, const vb_cand_vec *cv, int nthreads)
{
    size_t n = cv->n;
    match_free(m);
    m->parent = malloc((n + 1) * sizeof *m->parent);
    m->order = malloc((n + 1) * sizeof *m->order);
    m->cl_of = malloc((n + 1) * sizeof *m->cl_of);
    m->cl_start = calloc(n + 2, sizeof *m->cl_start);
    m->cl_items = malloc((n + 1) * sizeof *m->cl_items);
    if (!m->parent || !m->order || !m->cl_of || !m->cl_start || !m->cl_items)
        return VB_ENOMEM;
    xkey *keys = malloc((n + 1) * sizeof *keys);
    if (!keys)
        return VB_ENOMEM;
    for (size_t k = 0; k < n; k++) {
        m->parent[k] = (uint32_t)k;
        keys[k] = (xkey){cv->v[k].x, (uint32_t)k};
    }
    if (vb_psort(keys, n, sizeof *keys, cmp_x, nthreads) != VB_OK) {
        free(keys);
        return VB_ENOMEM;
    }
    for (size_t k = 0; k < n; k++)
        m->order[k] = keys[k].k;
    free(keys);
    double tol = m->tol;
    for (size_t a = 0; a < n; a++) {
        const vbs_cand *ca = cv->v + m->order[a];
        for (size_t b = a + 1; b < n; b++) {
            const vbs_cand *cb = cv->v + m->order[b];
            if (cb->x - ca->x > tol)
                break;
            double dy = cb->y - ca->y, dz = cb->z - ca->z, dt = cb->t - ca->t;
            if (fabs(dy) > tol || fabs(dz) > tol || fabs(dt) > tol)
                continue;
            uint32_t ra = find(m->parent, m->order[a]), rb = find(m->parent, m->order[b]);
            if (ra != rb) {
                if (ra < rb)
                    m->parent[rb] = ra;
                else
                    m->parent[ra] = rb;
            }
        }
    }
    /* Number clusters by first candidate (roots are the smallest index). */
    size_t ncl = 0;
    for (size_t k = 0; k < n; k++) {
        uint32_t r = find(m->parent, (uint32_t)k);
        m->cl_of[k] = r == k ? (uint32_t)ncl++ : m->cl_of[r];
    }
    for (size_t k = 0; k < n; k++)
        m->cl_start[m->cl_of[k] + 1]++;
    for (size_t c = 0; c < ncl; c++)
        m->cl_start[c + 1] += m->cl_start[c];
    uint32_t *fill = m->order; /* reuse */
    memcpy(fill, m->cl_start, ncl * sizeof *fill);
    for (size_t k = 0; k < n; k++)
        m->cl_items[fill[m->cl_of[k]]++] = (uint32_t)k;
    m->ncl = ncl;
    return VB_OK;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Ascending sort of four ids (the same order qsort gives, without its call
 * overhead on the hot paths of the swaps and the completion). */
static void sort4(uint32_t q[4])
{
    for (int a = 1; a < 4; a++) {
        uint32_t x = q[a];
        int b = a;
        while (b > 0 && q[b - 1] > x) {
            q[b] = q[b - 1];
            b--;
        }
        q[b] = x;
    }
}

/* Sorts v and drops repeats; returns the new length. The lists are short
 * (4 ids per candidate of one cluster), so small ones are sorted by
 * insertion rather than through qsort's calls. */
static size_t uniq(uint32_t *v, size_t n)
{
    if (n <= 32) {
        for (size_t a = 1; a < n; a++) {
            uint32_t x = v[a];
            size_t b = a;
            while (b > 0 && v[b - 1] > x) {
                v[b] = v[b - 1];
                b--;
            }
            v[b] = x;
        }
    } else {
        qsort(v, n, sizeof *v, cmp_u32);
    }
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (m == 0 || v[m - 1] != v[k])
            v[m++] = v[k];
    return m;
}

/* Members (union of ids) and finders (bases) of cluster c. */
static size_t cluster_sets(const match_ctx *m, const vb_cand_vec *cv, size_t c, uint32_t *mem,
                           size_t *nmem, uint32_t *found)
{
    size_t nm = 0, nf = 0;
    for (uint32_t q = m->cl_start[c]; q < m->cl_start[c + 1]; q++) {
        const vbs_cand *k = cv->v + m->cl_items[q];
        for (int a = 0; a < 4; a++)
            mem[nm++] = k->ids[a];
        found[nf++] = k->ids[0];
    }
    *nmem = uniq(mem, nm);
    return uniq(found, nf);
}

typedef struct work {
    uint32_t base, cluster;
} work;

static int cmp_work(const void *pa, const void *pb)
{
    const work *a = pa, *b = pb;
    if (a->base != b->base)
        return a->base < b->base ? -1 : 1;
    return (a->cluster > b->cluster) - (a->cluster < b->cluster);
}

/* Base m with its coarse culling lists (vbs_bis_store): sufficient for rays
 * anywhere on the sphere of directions, so the targeted search may place its
 * small cells anywhere. */
typedef struct full_base {
    vbs_base base;
    uint32_t off[6 * VBS_COARSE_T * VBS_COARSE_T + 1];
    const uint32_t *idx;
    unsigned T;
} full_base;

static void full_base_set(full_base *fb, const vb_sphere_set *s, const vbs_bis_store *st,
                          uint32_t m, double clip)
{
    size_t nt = 6u * (size_t)st->T * st->T, first = st->co_off[(size_t)m * nt];
    for (size_t k = 0; k <= nt; k++)
        fb->off[k] = (uint32_t)(st->co_off[(size_t)m * nt + k] - first);
    fb->idx = st->co_idx + first;
    fb->T = st->T;
    vbs_base *b = &fb->base;
    b->cx = s->x[m];
    b->cy = s->y[m];
    b->cz = s->z[m];
    b->r = s->r[m];
    b->scale = vbs_frame_scale(s->r[m]);
    b->clip = clip / b->scale;
    b->id = m;
    b->bis_start = 0;
    b->bis_count = (uint32_t)(st->off[m + 1] - st->off[m]);
    b->tile_start = 0;
}

/* Sec. 5.5 for one (vertex, sphere): returns 1 when found; new candidates
 * (the vertex itself or neighbours revealed by the small cells) go to extra. */
/* The last resort of the targeted search: corners of ever smaller cells
 * around the vertex may never show all three other colours (a face that
 * meets the vertex in a thin wedge keeps its angle at every scale). Solve
 * the vertex's own triple from the ray towards it (d, length n, world
 * units from the base) and accept the point when it is that vertex and the
 * base's lower envelope along its ray reaches it: no other bisector comes
 * first, so the base's cell has the vertex. Returns 1 when found. */
static int targeted_triple(const full_base *fb, const vbs_bisector *bis, const vbs_params *p,
                           const vbs_cand *v, const double d[3], double n, vb_cand_vec *extra,
                           int *err)
{
    uint32_t ids[3];
    int k3 = 0;
    for (int a = 0; a < 4; a++)
        if (v->ids[a] != fb->base.id && k3 < 3)
            ids[k3++] = v->ids[a];
    vbs_bisector tri[3];
    for (int a = 0; a < k3; a++)
        if (!vbs_find_bisector(&fb->base, bis, ids[a], &tri[a]))
            return 0;
    double du[3] = {d[0] / n, d[1] / n, d[2] / n}, P[3], eq_tol = p->tol / fb->base.scale;
    vbs_u32 fl = VBS_CF_TARGETED;
    if (k3 != 3 || !vbs_solve_triple(tri, du, eq_tol, -1.0, p->sing, p->max_iter, P, &fl))
        return 0;
    double np = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]), u, w, dd[3], s;
    const double e[3] = {P[0] / np, P[1] / np, P[2] / np};
    vbs_u32 f = vbs_dir_face(e, &u, &w);
    vbs_envelope_at(&fb->base, bis, fb->off, fb->idx, fb->T, f, u, w, dd, &s);
    if (!(s >= np - eq_tol))
        return 0;
    vbs_cand c;
    vbs_emit em = {&c, 1u, 0u, 0u, 0xffffffffu};
    vbs_emit_point(&fb->base, ids[0], ids[1], ids[2], P, fl, &em);
    double dx = c.x - v->x, dy = c.y - v->y, dz = c.z - v->z;
    if (!(sqrt(dx * dx + dy * dy + dz * dz) <= p->tol))
        return 0;
    if (vb_cand_vec_push(extra, &c)) {
        *err = VB_ENOMEM;
        return 0;
    }
    return 1;
}

static int targeted(const full_base *fb, const vbs_bisector *bis, const vbs_params *p,
                    const vbs_cand *v, unsigned depth, vb_cand_vec *extra, int *err)
{
    double d[3] = {v->x - fb->base.cx, v->y - fb->base.cy, v->z - fb->base.cz};
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(n > 0.0))
        return 0;
    double u, w;
    vbs_u32 f = vbs_dir_face(d, &u, &w);
    vbs_params q = *p;
    q.tiles = fb->T;
    double h = 0.5 * (2.0 / (double)(p->samples - 1u));
    for (unsigned lev = 0; lev < depth; lev++, h *= 0.5) {
        vbs_quad quad;
        quad.u0 = u - 0.5 * h;
        quad.v0 = w - 0.5 * h;
        quad.h = h;
        quad.depth = 0;
        for (int k = 0; k < 4; k++) {
            double dd[3], s;
            quad.col[k] = vbs_envelope_at(&fb->base, bis, fb->off, fb->idx, fb->T, f,
                                          quad.u0 + ((k & 1) ? h : 0.0),
                                          quad.v0 + ((k & 2) ? h : 0.0), dd, &s);
        }
        vbs_cand buf[VBS_MAX_CAND];
        vbs_emit em = {buf, VBS_MAX_CAND, 0u, 0u, 0xffffffffu};
        /* seq is set when the searches' results are merged in order. */
        vbs_process_cell(&fb->base, bis, fb->off, fb->idx, &q, f, &quad, VBS_CF_TARGETED,
                         &em);
        int found = 0;
        for (vbs_u32 k = 0; k < em.n; k++) {
            if (vb_cand_vec_push(extra, buf + k)) {
                *err = VB_ENOMEM;
                return 0;
            }
            double dx = buf[k].x - v->x, dy = buf[k].y - v->y, dz = buf[k].z - v->z;
            if (sqrt(dx * dx + dy * dy + dz * dz) <= p->tol)
                found = 1;
        }
        if (found)
            return 1;
    }
    return targeted_triple(fb, bis, p, v, d, n, extra, err);
}

/* The targeted searches of one run: item w searches vertex wk[w].cluster
 * from sphere wk[w].base; thread t keeps its candidates and their items. */
typedef struct tgt_ctx {
    const vb_sphere_set *set;
    const vbs_culler *cu;
    const vbs_params *params;
    const vb_cand_vec *raw;
    const match_ctx *m;
    const work *wk;
    unsigned depth;
    uint8_t *found;
    vb_cand_vec out[VB_MAX_THREADS];
    size_t *item[VB_MAX_THREADS];
    size_t item_cap[VB_MAX_THREADS];
    int err;
} tgt_ctx;

static void tgt_search(void *arg, size_t w, int tid)
{
    tgt_ctx *c = arg;
    uint32_t mb = c->wk[w].base;
    const vbs_bis_store *st = c->cu->store;
    if (st->off[mb + 1] == st->off[mb])
        return;
    full_base fb;
    full_base_set(&fb, c->set, st, mb, c->cu->clip);
    const vbs_cand *v = c->raw->v + c->m->cl_items[c->m->cl_start[c->wk[w].cluster]];
    size_t before = c->out[tid].n;
    int rc = VB_OK;
    c->found[w] = (uint8_t)targeted(&fb, st->bis + st->off[mb], c->params, v, c->depth,
                                    &c->out[tid], &rc);
    if (c->out[tid].n > c->item_cap[tid]) {
        size_t nc = c->out[tid].cap;
        size_t *p = realloc(c->item[tid], nc * sizeof *p);
        if (!p)
            rc = VB_ENOMEM;
        else {
            c->item[tid] = p;
            c->item_cap[tid] = nc;
        }
    }
    for (size_t k = before; rc == VB_OK && k < c->out[tid].n; k++)
        c->item[tid][k] = w;
    if (rc != VB_OK)
        c->err = rc;
}

/* Empty tangent sphere in double: returns the sphere (outside the four ids)
 * that reaches deepest, by more than tol, into the tangent sphere of
 * candidate k (lowest id on ties), or VBS_INF_COLOUR when there is none. */
static uint32_t tangent_intruder(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4],
                                 double tol, uint32_t **buf, size_t *cap, int *err)
{
    const vb_sphere_set *s = h->set;
    const double p[3] = {k->x, k->y, k->z};
    size_t n = 0;
    double radius = k->t + h->rmax + tol;
    if (radius < 0.0)
        return VBS_INF_COLOUR;
    if (vbs_hash_query(h, p, radius, buf, &n, cap)) {
        *err = VB_ENOMEM;
        return VBS_INF_COLOUR;
    }
    uint32_t worst = VBS_INF_COLOUR;
    double deepest = -tol;
    for (size_t i = 0; i < n; i++) {
        uint32_t j = (*buf)[i];
        if (j == q[0] || j == q[1] || j == q[2] || j == q[3])
            continue;
        if (s->contained && s->contained[j])
            continue;
        double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
        double gap = sqrt(dx * dx + dy * dy + dz * dz) - s->r[j] - k->t;
        if (gap < deepest) {
            deepest = gap;
            worst = j;
        }
    }
    return worst;
}

int vbs_tangent_empty(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4], double tol)
{
    const vb_sphere_set *s = h->set;
    const double p[3] = {k->x, k->y, k->z};
    double radius = k->t + h->rmax + tol;
    if (radius < 0.0)
        return 1;
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        double l = (p[a] - radius - h->lo[a]) / h->h, u = (p[a] + radius - h->lo[a]) / h->h;
        lo[a] = l < 0.0 ? 0 : l >= (double)h->dim[a] ? h->dim[a] : (int)l;
        hi[a] = u < 0.0 ? -1 : u >= (double)h->dim[a] ? h->dim[a] - 1 : (int)u;
    }
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int x = lo[0]; x <= hi[0]; x++) {
                size_t c = ((size_t)z * (size_t)h->dim[1] + (size_t)y) * (size_t)h->dim[0] + (size_t)x;
                for (uint32_t m = h->start[c]; m < h->start[c + 1]; m++) {
                    uint32_t j = h->idx[m];
                    if (j == q[0] || j == q[1] || j == q[2] || j == q[3] ||
                        (s->contained && s->contained[j]))
                        continue;
                    double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
                    if (sqrt(dx * dx + dy * dy + dz * dz) - s->r[j] - k->t < -tol)
                        return 0;
                }
            }
    return 1;
}

/* Set of sorted quadruples already handled: VBS_QPARTS open-addressing
 * tables, a quadruple's table chosen by the top bits of its hash, so that
 * inserts into different tables can run on different threads. */
#define VBS_QPARTS 64
typedef struct qtab {
    uint32_t (*keys)[4];
    size_t cap, n;
} qtab;

typedef struct qset {
    qtab part[VBS_QPARTS];
} qset;

static uint64_t qhash(const uint32_t q[4])
{
    uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < 4; k++)
        h = (h ^ q[k]) * 1099511628211ull;
    return h;
}

/* Table of a quadruple with hash h (the multiply leaves the top bits the
 * best mixed), and its first slot in a table of cap entries. */
static unsigned qpart(uint64_t h)
{
    return (unsigned)(h >> 58);
}

static size_t qslot(uint64_t h, size_t cap)
{
    return (size_t)(h ^ (h >> 29)) & (cap - 1);
}

/* 1 when q is in the set (read-only: safe on several threads while nobody
 * inserts). */
static int qset_has(const qset *s, const uint32_t q[4])
{
    uint64_t hv = qhash(q);
    const qtab *t = &s->part[qpart(hv)];
    if (t->cap == 0)
        return 0;
    for (size_t h = qslot(hv, t->cap); t->keys[h][0] != 0xffffffffu; h = (h + 1) & (t->cap - 1))
        if (memcmp(t->keys[h], q, 4 * sizeof *q) == 0)
            return 1;
    return 0;
}

/* Inserts q, whose hash is hv, into its table t; returns 1 if new, 0 if
 * present, -1 on allocation failure. Touches no other table. */
static int qtab_add(qtab *t, uint64_t hv, const uint32_t q[4])
{
    if (2 * (t->n + 1) > t->cap) {
        size_t nc = t->cap ? 2 * t->cap : 256;
        uint32_t (*k)[4] = malloc(nc * sizeof *k);
        if (!k)
            return -1;
        memset(k, 0xff, nc * sizeof *k);
        for (size_t i = 0; i < t->cap; i++)
            if (t->keys[i][0] != 0xffffffffu) {
                size_t h = qslot(qhash(t->keys[i]), nc);
                while (k[h][0] != 0xffffffffu)
                    h = (h + 1) & (nc - 1);
                memcpy(k[h], t->keys[i], sizeof k[h]);
            }
        free(t->keys);
        t->keys = k;
        t->cap = nc;
    }
    size_t h = qslot(hv, t->cap);
    while (t->keys[h][0] != 0xffffffffu) {
        if (memcmp(t->keys[h], q, 4 * sizeof *q) == 0)
            return 0;
        h = (h + 1) & (t->cap - 1);
    }
    memcpy(t->keys[h], q, 4 * sizeof *q);
    t->n++;
    return 1;
}

static int qset_add(qset *s, const uint32_t q[4])
{
    uint64_t hv = qhash(q);
    return qtab_add(&s->part[qpart(hv)], hv, q);
}

static void qset_free(qset *s)
{
    for (int p = 0; p < VBS_QPARTS; p++)
        free(s->part[p].keys);
    memset(s, 0, sizeof *s);
}


/* Bulk insertion: the items of each table of the set in index order. */
typedef struct qbulk {
    qset *s;
    const uint32_t (*q)[4];
    const uint64_t *hash;
    const size_t *start;     /* VBS_QPARTS + 1 */
    const uint32_t *items;
    uint8_t *fresh;
    int err;
} qbulk;

static void qbulk_table(void *arg, size_t p, int tid)
{
    qbulk *b = arg;
    (void)tid;
    for (size_t j = b->start[p]; j < b->start[p + 1]; j++) {
        uint32_t k = b->items[j];
        int f = qtab_add(&b->s->part[p], b->hash[k], b->q[k]);
        if (f < 0) {
            b->err = VB_ENOMEM;
            return;
        }
        if (b->fresh)
            b->fresh[k] = (uint8_t)f;
    }
}

/* Inserts q[k] for every k < n with !skip[k] (skip may be NULL), the
 * tables of the set in parallel. fresh (may be NULL) gets 1 where q[k]
 * entered the set, else 0: within a table the items go in index order, so
 * set and flags are those of qset_add called for k = 0, 1, ... in turn.
 * Returns VB_OK or VB_ENOMEM. */
static int qset_add_bulk(qset *s, const uint32_t (*q)[4], size_t n, const uint8_t *skip,
                         uint8_t *fresh, int nthreads)
{
    uint64_t *hash = malloc((n + 1) * sizeof *hash);
    uint32_t *items = malloc((n + 1) * sizeof *items);
    size_t start[VBS_QPARTS + 1] = {0}, fill[VBS_QPARTS];
    if (!hash || !items) {
        free(hash);
        free(items);
        return VB_ENOMEM;
    }
    for (size_t k = 0; k < n; k++) {
        if (fresh)
            fresh[k] = 0;
        if (skip && skip[k])
            continue;
        hash[k] = qhash(q[k]);
        start[qpart(hash[k]) + 1]++;
    }
    for (int p = 0; p < VBS_QPARTS; p++)
        start[p + 1] += start[p];
    memcpy(fill, start, sizeof fill);
    for (size_t k = 0; k < n; k++)
        if (!(skip && skip[k]))
            items[fill[qpart(hash[k])]++] = (uint32_t)k;
    qbulk b = {s, q, hash, start, items, fresh, VB_OK};
    vb_parallel_for(qbulk_table, &b, VBS_QPARTS, nthreads);
    free(hash);
    free(items);
    return b.err;
}

/* A candidate with its sorted quadruple; sorted by quadruple, then by the
 * candidate's deterministic order. */
typedef struct qrec {
    uint32_t q[4];
    vbs_cand c;
} qrec;

/* Both tangent spheres of a quadruple (Fig. 8: one quadruple, two vertices),
 * each kept if its tangent sphere is empty; the point p stands in when the
 * double solver cannot separate the roots (the certifier decides). When the
 * root nearest p is not empty, the spheres near a (near-)degenerate vertex
 * are not the ones sampled: each quadruple with one sphere swapped for the
 * intruder is tried too, `depth` swaps deep. */
typedef struct emit_ctx {
    const vb_sphere_set *set;
    const vbs_hash *hash;
    double guard;            /* rounding guard of the tangent test, relative */
    uint32_t *qbuf;
    size_t qcap;
    qset seen;
    vb_sampler_result *res;
} emit_ctx;

/* The tangent spheres of quadruple q and what cuts them: intruder[k] is
 * VBS_INF_COLOUR for an empty sphere, else the deepest intruder for the root
 * nearest proto when want_intruder, else 0. Thread-safe with per-thread buf. */
typedef struct root_eval {
    int n, nearest;
    double roots[2][4];
    uint32_t intruder[2];
} root_eval;

/* Both tangent spheres (centre, radius) of the spheres q[0..3]
 * (vbs_tangent_roots); returns how many. */
static int quad_roots(const vb_sphere_set *s, const uint32_t q[4], double roots[2][4])
{
    double sp[4][4];
    for (int k = 0; k < 4; k++) {
        uint32_t j = q[k];
        sp[k][0] = s->x[j];
        sp[k][1] = s->y[j];
        sp[k][2] = s->z[j];
        sp[k][3] = s->r[j];
    }
    return vbs_tangent_roots(sp, roots);
}

static int eval_roots(const emit_ctx *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int want_intruder, uint32_t **buf, size_t *cap, root_eval *ev)
{
    ev->n = quad_roots(e->set, q, ev->roots);
    if (ev->n == 0 && own) {
        /* Only a Newton point of this very quadruple may stand in. */
        ev->roots[0][0] = proto->x;
        ev->roots[0][1] = proto->y;
        ev->roots[0][2] = proto->z;
        ev->roots[0][3] = proto->t;
        ev->n = 1;
    }
    ev->nearest = 0;
    if (ev->n == 2) {
        double d[2];
        for (int k = 0; k < 2; k++) {
            double dx = ev->roots[k][0] - proto->x, dy = ev->roots[k][1] - proto->y,
                   dz = ev->roots[k][2] - proto->z;
            d[k] = dx * dx + dy * dy + dz * dz;
        }
        ev->nearest = d[1] < d[0];
    }
    for (int k = 0; k < ev->n; k++) {
        vbs_cand c = *proto;
        c.x = ev->roots[k][0];
        c.y = ev->roots[k][1];
        c.z = ev->roots[k][2];
        c.t = ev->roots[k][3];
        /* The roots come from a closed form in double: a guard of 1e-9 of
         * the scale covers their rounding; the certifier decides the rest. */
        double guard = e->guard * (1.0 + fabs(c.t));
        if (k == ev->nearest && want_intruder) {
            int rc = VB_OK;
            ev->intruder[k] = tangent_intruder(e->hash, &c, q, guard, buf, cap, &rc);
            if (rc != VB_OK)
                return rc;
        } else {
            ev->intruder[k] = vbs_tangent_empty(e->hash, &c, q, guard) ? VBS_INF_COLOUR : 0u;
        }
    }
    return VB_OK;
}

static int emit_roots(emit_ctx *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int depth);

/* Keeps the empty tangent spheres of ev; when the one nearest proto is cut,
 * tries the quadruples with its intruder swapped in, `depth` swaps deep. */
static int consume_roots(emit_ctx *e, const uint32_t q[4], const vbs_cand *proto,
                         const root_eval *ev, int depth)
{
    int rc = VB_OK;
    for (int k = 0; k < ev->n && rc == VB_OK; k++) {
        uint32_t j = ev->intruder[k];
        if (j == VBS_INF_COLOUR) {
            if (vb_vertex_list_push(&e->res->candidates, q, 4, ev->roots[k][0], ev->roots[k][1],
                                    ev->roots[k][2], ev->roots[k][3], 0.0, VB_VERTEX_CANDIDATE))
                rc = VB_ENOMEM;
            continue;
        }
        e->res->dropped++;
        if (k != ev->nearest || depth == 0)
            continue;
        vbs_cand c = *proto;
        c.x = ev->roots[k][0];
        c.y = ev->roots[k][1];
        c.z = ev->roots[k][2];
        c.t = ev->roots[k][3];
        for (int a = 0; a < 4 && rc == VB_OK; a++) {
            uint32_t q2[4];
            for (int b = 0; b < 4; b++)
                q2[b] = b == a ? j : q[b];
            sort4(q2);
            int fresh = qset_add(&e->seen, q2);
            if (fresh < 0)
                rc = VB_ENOMEM;
            else if (fresh) {
                e->res->swaps++;
                rc = emit_roots(e, q2, &c, 0, depth - 1);
            }
        }
    }
    return rc;
}

static int emit_roots(emit_ctx *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int depth)
{
    root_eval ev;
    int rc = eval_roots(e, q, proto, own, depth > 0, &e->qbuf, &e->qcap, &ev);
    return rc != VB_OK ? rc : consume_roots(e, q, proto, &ev, depth);
}

/* The sampled quadruples, evaluated in parallel (per-thread buffers). */
typedef struct sampled_ctx {
    const emit_ctx *e;
    const qrec *qs;
    const size_t *which;
    root_eval *ev;
    uint32_t *tbuf[VB_MAX_THREADS];
    size_t tcap[VB_MAX_THREADS];
    int err;
} sampled_ctx;

static void sampled_eval(void *arg, size_t i, int tid)
{
    sampled_ctx *c = arg;
    const qrec *r = c->qs + c->which[i];
    if (eval_roots(c->e, r->q, &r->c, 1, VBS_SWAP_DEPTH > 0, &c->tbuf[tid], &c->tcap[tid],
                   &c->ev[i]))
        c->err = VB_ENOMEM;
}

/* Spheres tried as the fourth of each triple by the neighbourhood completion. */
#define VBS_RING 4

/* Work of the neighbourhood completion. */
typedef struct ring_item {
    uint32_t slot;           /* its quadruple: ring_ctx quad[slot] */
    int n;                   /* roots */
    double roots[2][4];
    int empty[2];            /* tangent sphere k is empty */
} ring_item;

typedef struct ring_ctx {
    emit_ctx *e;
    const vb_vertex_list *v;
    size_t lo;               /* first vertex of the round */
    uint32_t (*best)[VBS_RING];
    int *nb;
    /* Per vertex i, the quadruple of (drop, b) at slot (4 i + drop) VBS_RING
     * + b, sorted, and whether it was seen before the round. */
    uint32_t (*quad)[4];
    uint8_t *old;
    uint8_t *fresh;          /* phase B: the slot's quadruple is new */
    ring_item *items;
    int err;
} ring_ctx;

/* Keeps best[0..*nb) the VBS_RING smallest (gap, id) pairs seen. */
static void ring_insert(uint32_t *best, double *gap, int *nb, uint32_t j, double g)
{
    int at = *nb < VBS_RING ? (*nb)++ : VBS_RING;
    while (at > 0 && (gap[at - 1] > g || (gap[at - 1] == g && best[at - 1] > j))) {
        if (at < VBS_RING) {
            gap[at] = gap[at - 1];
            best[at] = best[at - 1];
        }
        at--;
    }
    if (at < VBS_RING) {
        gap[at] = g;
        best[at] = j;
    }
}

/* Phase A: the VBS_RING spheres with the smallest gaps |p - c_j| - r_j - t
 * (ties: lowest id) among the non-members of vertex lo + i whose centre lies
 * within t + rmax + 4h of p. The grid cells are visited in Chebyshev shells
 * around the cell of p clamped to the grid box; a cell of shell k >= 2 is at
 * least (k - 1) h from that point and so from p (clamping is the projection
 * onto the box), so every sphere of the shell has a gap of at least
 * (k - 1) h - rmax - t. Once VBS_RING spheres are kept and that bound
 * exceeds the largest kept gap, no farther sphere can enter: the result is
 * the one of the plain scan over the whole radius (the (gap, id) order is
 * total), at a fraction of the distance evaluations. */
static void ring_nearest(void *arg, size_t i, int tid)
{
    ring_ctx *r = arg;
    const vb_sphere_set *s = r->e->set;
    const vbs_hash *g = r->e->hash;
    const vb_vertex_list *v = r->v;
    size_t k = r->lo + i;
    const uint32_t *q = v->ids + v->start[k];
    const double p[3] = {v->x[k], v->y[k], v->z[k]};
    double t = v->t[k];
    double radius = t + g->rmax + 4.0 * g->h;
    r->nb[i] = 0;
    memset(r->old + 4 * i * VBS_RING, 1, 4 * VBS_RING);
    (void)tid;
    if (radius < 0.0)
        return;
    int lo[3], hi[3], cc[3], ext = 0;
    for (int a = 0; a < 3; a++) {
        double l = (p[a] - radius - g->lo[a]) / g->h, u = (p[a] + radius - g->lo[a]) / g->h;
        lo[a] = l < 0.0 ? 0 : l >= (double)g->dim[a] ? g->dim[a] : (int)l;
        hi[a] = u < 0.0 ? -1 : u >= (double)g->dim[a] ? g->dim[a] - 1 : (int)u;
        if (lo[a] > hi[a])
            return;
        double c = (p[a] - g->lo[a]) / g->h;
        cc[a] = c < 0.0 ? 0 : c >= (double)g->dim[a] ? g->dim[a] - 1 : (int)c;
        int e = cc[a] - lo[a] > hi[a] - cc[a] ? cc[a] - lo[a] : hi[a] - cc[a];
        if (e > ext)
            ext = e;
    }
    double r2 = radius * radius;
    uint32_t *best = r->best[i];
    double gap[VBS_RING];
    int nb = 0;
    for (int sh = 0; sh <= ext; sh++) {
        if (nb == VBS_RING && sh >= 2 &&
            (double)(sh - 1) * g->h * (1.0 - 1e-9) - g->rmax - t > gap[VBS_RING - 1] + 1e-9 * (1.0 + fabs(gap[VBS_RING - 1])))
            break;
        for (int z = cc[2] - sh; z <= cc[2] + sh; z++) {
            if (z < lo[2] || z > hi[2])
                continue;
            for (int y = cc[1] - sh; y <= cc[1] + sh; y++) {
                if (y < lo[1] || y > hi[1])
                    continue;
                int full = z == cc[2] - sh || z == cc[2] + sh || y == cc[1] - sh || y == cc[1] + sh;
                int step = full || sh == 0 ? 1 : 2 * sh;
                for (int x = cc[0] - sh; x <= cc[0] + sh; x += step) {
                    if (x < lo[0] || x > hi[0])
                        continue;
                    size_t c = ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0] +
                               (size_t)x;
                    for (uint32_t m = g->start[c]; m < g->start[c + 1]; m++) {
                        uint32_t j = g->idx[m];
                        double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
                        if (dx * dx + dy * dy + dz * dz > r2)
                            continue;
                        if (j == q[0] || j == q[1] || j == q[2] || j == q[3] ||
                            (s->contained && s->contained[j]))
                            continue;
                        ring_insert(best, gap, &nb, j,
                                    sqrt(dx * dx + dy * dy + dz * dz) - s->r[j] - t);
                    }
                }
            }
        }
    }
    r->nb[i] = nb;
    for (size_t slot = 4 * i * VBS_RING; slot < 4 * (i + 1) * VBS_RING; slot++)
        r->old[slot] = 1; /* unused unless filled below */
    /* The quadruples phase B will try, and which of them the set already
     * holds (the set is not written during this phase). */
    for (int drop = 0; drop < 4; drop++)
        for (int b = 0; b < nb; b++) {
            size_t slot = (4 * i + (size_t)drop) * VBS_RING + (size_t)b;
            uint32_t *q2 = r->quad[slot];
            for (int a = 0; a < 4; a++)
                q2[a] = a == drop ? best[b] : q[a];
            sort4(q2);
            r->old[slot] = (uint8_t)qset_has(&r->e->seen, q2);
        }
}

/* Phase C: both tangent spheres of item i and whether each is empty. */
static void ring_eval(void *arg, size_t i, int tid)
{
    ring_ctx *r = arg;
    ring_item *it = r->items + i;
    const uint32_t *q = r->quad[it->slot];
    it->n = quad_roots(r->e->set, q, it->roots);
    for (int k = 0; k < it->n; k++) {
        vbs_cand c;
        memset(&c, 0, sizeof c);
        c.x = it->roots[k][0];
        c.y = it->roots[k][1];
        c.z = it->roots[k][2];
        c.t = it->roots[k][3];
        it->empty[k] = vbs_tangent_empty(r->e->hash, &c, q, r->e->guard * (1.0 + fabs(c.t)));
    }
    (void)tid;
}

/* Neighbourhood completion: every vertex found so far tries, for each triple
 * of its spheres, the VBS_RING spheres that come closest to its tangent
 * sphere as the fourth; new vertices take part in the next round. A vertex
 * whose faces are too thin for any ray (symmetric inputs: a face that exists
 * only on a plane of symmetry between samples) is reached this way from a
 * found neighbour across their common edge. Rounds run in parallel phases
 * with sequential bookkeeping between them, so the result does not depend
 * on the number of threads. */
static int complete_ring(emit_ctx *e, int nthreads)
{
    vb_vertex_list *v = &e->res->candidates;
    ring_ctx r;
    memset(&r, 0, sizeof r);
    r.e = e;
    r.v = v;
    size_t cap = 0;
    int rc = VB_OK;
    for (size_t lo = 0; lo < v->n && rc == VB_OK;) {
        size_t hi = v->n, nv = hi - lo;
        r.lo = lo;
        uint32_t(*best)[VBS_RING] = realloc(r.best, nv * sizeof *best);
        int *nb = best ? realloc(r.nb, nv * sizeof *nb) : NULL;
        uint32_t(*quad)[4] = nb ? realloc(r.quad, 4 * VBS_RING * nv * sizeof *quad) : NULL;
        uint8_t *old = quad ? realloc(r.old, 4 * VBS_RING * nv) : NULL;
        uint8_t *fresh = old ? realloc(r.fresh, 4 * VBS_RING * nv) : NULL;
        if (best)
            r.best = best;
        if (nb)
            r.nb = nb;
        if (quad)
            r.quad = quad;
        if (old)
            r.old = old;
        if (fresh)
            r.fresh = fresh;
        if (!fresh) {
            rc = VB_ENOMEM;
            break;
        }
        vb_parallel_for(ring_nearest, &r, nv, nthreads);
        if (r.err) {
            rc = r.err;
            break;
        }
        /* Phase B: the fresh quadruples, in vertex order (those the set
         * held before the round were found in phase A). */
        rc = qset_add_bulk(&e->seen, (const uint32_t(*)[4])r.quad, 4 * VBS_RING * nv, r.old,
                           r.fresh, nthreads);
        if (rc != VB_OK)
            break;
        size_t ni = 0, nslots = 4 * VBS_RING * nv;
        for (size_t k = 0; k < nslots; k++)
            ni += r.fresh[k];
        if (ni > cap) {
            ring_item *p = realloc(r.items, ni * sizeof *p);
            if (!p) {
                rc = VB_ENOMEM;
                break;
            }
            r.items = p;
            cap = ni;
        }
        for (size_t k = 0, at = 0; k < nslots; k++)
            if (r.fresh[k])
                r.items[at++].slot = (uint32_t)k;
        vb_parallel_for(ring_eval, &r, ni, nthreads);
        if (r.err) {
            rc = r.err;
            break;
        }
        /* Phase D: keep the empty tangent spheres, in item order. */
        for (size_t i = 0; i < ni && rc == VB_OK; i++) {
            const ring_item *it = r.items + i;
            e->res->ring_tries++;
            for (int k = 0; k < it->n && rc == VB_OK; k++) {
                if (!it->empty[k]) {
                    e->res->dropped++;
                    continue;
                }
                if (vb_vertex_list_push(v, r.quad[it->slot], 4, it->roots[k][0], it->roots[k][1],
                                        it->roots[k][2], it->roots[k][3], 0.0,
                                        VB_VERTEX_CANDIDATE))
                    rc = VB_ENOMEM;
            }
        }
        lo = hi;
    }
    free(r.best);
    free(r.nb);
    free(r.quad);
    free(r.old);
    free(r.fresh);
    free(r.items);
    return rc;
}

/* The tangent test of every cluster that needs it (incomplete, or seen
 * from sphere 0), in parallel: plaus[c] = 1 when its tangent sphere is
 * empty or it needs no test. */
typedef struct plaus_ctx {
    const match_ctx *m;
    const vb_cand_vec *raw;
    const vbs_hash *hash;
    double tol;
    uint8_t *plaus;
    uint32_t *mem[VB_MAX_THREADS], *found[VB_MAX_THREADS];
    uint32_t *tbuf[VB_MAX_THREADS];
    size_t tcap[VB_MAX_THREADS], mcap[VB_MAX_THREADS];
    int err;
} plaus_ctx;

static void plaus_eval(void *arg, size_t c, int tid)
{
    plaus_ctx *p = arg;
    const match_ctx *m = p->m;
    size_t k = m->cl_start[c + 1] - m->cl_start[c];
    if (p->mcap[tid] < k) {
        size_t nc = 2 * k;
        uint32_t *a = realloc(p->mem[tid], 4 * nc * sizeof *a);
        uint32_t *b = a ? realloc(p->found[tid], nc * sizeof *b) : NULL;
        if (a)
            p->mem[tid] = a;
        if (b)
            p->found[tid] = b;
        if (!b) {
            p->err = VB_ENOMEM;
            return;
        }
        p->mcap[tid] = nc;
    }
    size_t nm, nf = cluster_sets(m, p->raw, c, p->mem[tid], &nm, p->found[tid]);
    p->plaus[c] = 1;
    if (nf < nm || p->found[tid][0] == 0) {
        const vbs_cand *rep = p->raw->v + m->cl_items[m->cl_start[c]];
        uint32_t q4[4];
        memcpy(q4, rep->ids, sizeof q4);
        int rc = VB_OK;
        p->plaus[c] = tangent_intruder(p->hash, rep, q4, p->tol, &p->tbuf[tid], &p->tcap[tid],
                                       &rc) == VBS_INF_COLOUR;
        if (rc != VB_OK)
            p->err = rc;
    }
}

/* Runs plaus_eval over every cluster of m; returns VB_OK or VB_ENOMEM. */
static int tangent_tests(const match_ctx *m, const vb_cand_vec *raw, const vbs_hash *hash,
                         double tol, uint8_t *plaus, int nthreads)
{
    plaus_ctx pc;
    memset(&pc, 0, sizeof pc);
    pc.m = m;
    pc.raw = raw;
    pc.hash = hash;
    pc.tol = tol;
    pc.plaus = plaus;
    vb_parallel_for(plaus_eval, &pc, m->ncl, nthreads);
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        free(pc.mem[t]);
        free(pc.found[t]);
        free(pc.tbuf[t]);
    }
    return pc.err;
}

/* Sort key of a quadruple record: quadruple, base, grid cell, rank, then the
 * record's position, so ties keep the input order as the stable merge sort
 * of qsort did (sorting the 80-byte records spends its time copying). */
typedef struct qkey {
    uint32_t k[7], idx;
} qkey;

static int cmp_qkey(const void *pa, const void *pb)
{
    const qkey *a = pa, *b = pb;
    for (int i = 0; i < 7; i++)
        if (a->k[i] != b->k[i])
            return a->k[i] < b->k[i] ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

int vbs_match(vb_ctx *ctx, const vb_sphere_set *set, const vbs_culler *cu,
              const vbs_params *params, unsigned target_depth, int nthreads,
              vb_cand_vec *raw, vb_sampler_result *res)
{
    match_ctx m = {set, params->tol, NULL, NULL, NULL, NULL, NULL, 0};
    uint32_t *mem = malloc(4 * (raw->n + 1) * sizeof *mem);
    uint32_t *found = malloc((raw->n + 1) * sizeof *found);
    work *wk = NULL;
    size_t nwk = 0, wcap = 0;
    vb_cand_vec extra = {0};
    int rc = (!mem || !found) ? VB_ENOMEM : cluster(&m, raw, nthreads);
    /* A vertex whose tangent sphere is not empty is spurious whichever
     * cells see it: test first, search only for the plausible ones. */
    uint8_t *plaus = rc == VB_OK ? malloc(m.ncl + 1) : NULL;
    if (rc == VB_OK && !plaus)
        rc = VB_ENOMEM;
    if (rc == VB_OK)
        rc = tangent_tests(&m, raw, cu->hash, params->tol, plaus, nthreads);
    /* Pass 1: completeness, the first cell (Fig. 13), work for 5.5. */
    for (size_t c = 0; rc == VB_OK && c < m.ncl; c++) {
        size_t nm, nf = cluster_sets(&m, raw, c, mem, &nm, found);
        size_t fi = 0;
        int complete = 1;
        int plausible = plaus[c];
        for (size_t q = 0; q < nm && plausible; q++) {
            while (fi < nf && found[fi] < mem[q])
                fi++;
            if (fi < nf && found[fi] == mem[q])
                continue;
            complete = 0;
            if (nwk == wcap) {
                wcap = wcap ? 2 * wcap : 256;
                work *p = realloc(wk, wcap * sizeof *p);
                if (!p) {
                    rc = VB_ENOMEM;
                    break;
                }
                wk = p;
            }
            wk[nwk++] = (work){mem[q], (uint32_t)c};
        }
        res->complete_first += (uint64_t)(complete && nf == nm);
        res->first_cell += (uint64_t)(plausible && found[0] == 0);
    }
    /* Sec. 5.5, in parallel; results merged in work order. */
    if (rc == VB_OK && nwk)
        qsort(wk, nwk, sizeof *wk, cmp_work);
    double tt0 = vb_now();
    if (rc == VB_OK && nwk) {
        tgt_ctx tc;
        memset(&tc, 0, sizeof tc);
        tc.set = set;
        tc.cu = cu;
        tc.params = params;
        tc.raw = raw;
        tc.m = &m;
        tc.wk = wk;
        tc.depth = target_depth;
        tc.found = calloc(nwk, 1);
        int nt = nthreads;
        if (!tc.found)
            rc = VB_ENOMEM;
        else
            vb_parallel_for(tgt_search, &tc, nwk, nt);
        if (rc == VB_OK && tc.err)
            rc = tc.err;
        size_t at[VB_MAX_THREADS] = {0};
        for (size_t w = 0; rc == VB_OK && w < nwk; w++) {
            int t = (int)(w % (size_t)(nt < 1 ? 1 : nt > VB_MAX_THREADS ? VB_MAX_THREADS : nt));
            res->targeted_searches++;
            res->targeted_found += tc.found[w];
            while (rc == VB_OK && at[t] < tc.out[t].n && tc.item[t][at[t]] == w) {
                vbs_cand c = tc.out[t].v[at[t]++];
                c.seq = (vbs_u32)extra.n;
                rc = vb_cand_vec_push(&extra, &c);
            }
        }
        for (int t = 0; t < VB_MAX_THREADS; t++) {
            vb_cand_vec_free(&tc.out[t]);
            free(tc.item[t]);
        }
        free(tc.found);
    }
    res->times.targeted += vb_now() - tt0;
    /* Pass 2 on everything found; extra candidates follow the raw ones. */
    for (size_t k = 0; rc == VB_OK && k < extra.n; k++)
        if (vb_cand_vec_push(raw, extra.v + k))
            rc = VB_ENOMEM;
    if (rc == VB_OK && extra.n > 0) {
        free(mem);
        free(found);
        mem = malloc(4 * (raw->n + 1) * sizeof *mem);
        found = malloc((raw->n + 1) * sizeof *found);
        rc = (!mem || !found) ? VB_ENOMEM : cluster(&m, raw, nthreads);
    }
    /* Completeness after 5.5, then every distinct quadruple once. */
    qrec *qs = malloc((raw->n + 1) * sizeof *qs);
    size_t nq = 0;
    if (rc == VB_OK && !qs)
        rc = VB_ENOMEM;
    /* The vertices among the clusters: those found from all of their
     * spheres (but not from sphere 0 alone, as in pass 1) and those with an
     * empty tangent sphere (the spurious ones die there); how many of them
     * sampling and 5.5 did not find from all of their spheres. */
    uint8_t *empty = rc == VB_OK ? malloc(m.ncl + 1) : NULL;
    if (rc == VB_OK && !empty)
        rc = VB_ENOMEM;
    if (rc == VB_OK)
        rc = tangent_tests(&m, raw, cu->hash, params->tol, empty, nthreads);
    for (size_t c = 0; rc == VB_OK && c < m.ncl; c++) {
        size_t nm, nf = cluster_sets(&m, raw, c, mem, &nm, found);
        int complete = nf == nm && memcmp(mem, found, nm * sizeof *mem) == 0;
        res->clusters++;
        res->incomplete += (uint64_t)!complete;
        res->sampled_vertices += empty[c];
        res->vertices_incomplete += (uint64_t)(empty[c] && !complete);
    }
    free(empty);
    for (size_t k = 0; rc == VB_OK && k < raw->n; k++) {
        qs[nq].c = raw->v[k];
        memcpy(qs[nq].q, raw->v[k].ids, sizeof qs[nq].q);
        sort4(qs[nq].q);
        nq++;
    }
    if (rc == VB_OK && nq) {
        qkey *ix = malloc(nq * sizeof *ix);
        qrec *sorted = ix ? malloc(nq * sizeof *sorted) : NULL;
        if (!sorted) {
            free(ix);
            rc = VB_ENOMEM;
        } else {
            for (size_t k = 0; k < nq; k++) {
                const qrec *r = qs + k;
                ix[k] = (qkey){{r->q[0], r->q[1], r->q[2], r->q[3], r->c.ids[0], r->c.cell,
                                r->c.seq}, (uint32_t)k};
            }
            rc = vb_psort(ix, nq, sizeof *ix, cmp_qkey, nthreads);
            for (size_t k = 0; rc == VB_OK && k < nq; k++)
                sorted[k] = qs[ix[k].idx];
            free(ix);
            free(qs);
            qs = sorted;
        }
    }
    /* Sampled quadruples first (all marked seen), then their swaps. */
    double tt1 = vb_now();
    /* 1e-9 of the bounding-box diagonal (the default tol is 1e-5 of it). */
    double diag = 1e5 * vb_sampler_default_tol(set);
    emit_ctx ec = {set, cu->hash, 1e-9 * diag, NULL, 0, {{{NULL, 0, 0}}}, res};
    /* Distinct quadruples (the first, deterministic, candidate of each). */
    size_t *which = malloc((nq + 1) * sizeof *which), nw = 0;
    root_eval *evs = malloc((nq + 1) * sizeof *evs);
    uint32_t (*distinct)[4] = malloc((nq + 1) * sizeof *distinct);
    if (rc == VB_OK && (!which || !evs || !distinct))
        rc = VB_ENOMEM;
    for (size_t k = 0; rc == VB_OK && k < nq; k++)
        if (k == 0 || memcmp(qs[k].q, qs[k - 1].q, sizeof qs[k].q) != 0) {
            memcpy(distinct[nw], qs[k].q, sizeof distinct[nw]);
            which[nw++] = k;
        }
    if (rc == VB_OK)
        rc = qset_add_bulk(&ec.seen, (const uint32_t(*)[4])distinct, nw, NULL, NULL, nthreads);
    free(distinct);
    if (rc == VB_OK) {
        sampled_ctx sc;
        memset(&sc, 0, sizeof sc);
        sc.e = &ec;
        sc.qs = qs;
        sc.which = which;
        sc.ev = evs;
        vb_parallel_for(sampled_eval, &sc, nw, nthreads);
        for (int t = 0; t < VB_MAX_THREADS; t++)
            free(sc.tbuf[t]);
        rc = sc.err;
    }
    for (size_t k = 0; rc == VB_OK && k < nw; k++)
        rc = consume_roots(&ec, qs[which[k]].q, &qs[which[k]].c, &evs[k], VBS_SWAP_DEPTH);
    free(which);
    free(evs);
    res->from_sampling = res->candidates.n;
    double tt2 = vb_now();
    res->times.tangent += tt2 - tt1;
    if (rc == VB_OK)
        rc = complete_ring(&ec, nthreads);
    res->times.completion += vb_now() - tt2;
    free(ec.qbuf);
    qset_free(&ec.seen);
    free(qs);
    free(plaus);
    vb_cand_vec_free(&extra);
    free(wk);
    free(mem);
    free(found);
    match_free(&m);
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "out of memory (matching)");
    return VB_OK;
}

int vb_sampler_swap_candidates(const vb_sphere_set *set, const uint32_t ids[4],
                               uint32_t intruder, const double p[4], vb_vertex_list *out)
{
    for (int a = 0; a < 4; a++) {
        uint32_t q[4];
        double roots[2][4];
        for (int b = 0; b < 4; b++)
            q[b] = b == a ? intruder : ids[b];
        int n = quad_roots(set, q, roots);
        if (n == 0) {
            memcpy(roots[0], p, sizeof roots[0]);
            n = 1;
        }
        for (int k = 0; k < n; k++)
            if (vb_vertex_list_push(out, q, 4, roots[k][0], roots[k][1], roots[k][2],
                                    roots[k][3], 0.0, VB_VERTEX_CANDIDATE))
                return VB_ENOMEM;
    }
    return VB_OK;
}
