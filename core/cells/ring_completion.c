/* Neighbourhood completion (ours): from every vertex found, the quadruples
 * across its edges. A vertex whose faces are too thin for any ray
 * (symmetric inputs: a face that exists only on a plane of symmetry between
 * samples) is reached from a found neighbour across their common edge. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

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
    vbs_roots *e;
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
            vbs_sort4(q2);
            r->old[slot] = (uint8_t)vbs_qset_has(&r->e->seen, q2);
        }
}

/* Phase C: both tangent spheres of item i and whether each is empty. */
static void ring_eval(void *arg, size_t i, int tid)
{
    ring_ctx *r = arg;
    ring_item *it = r->items + i;
    const uint32_t *q = r->quad[it->slot];
    it->n = vbs_quad_roots(r->e->set, q, it->roots);
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
int vbs_complete_ring(vbs_roots *e, int nthreads)
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
        rc = vbs_qset_add_bulk(&e->seen, (const uint32_t(*)[4])r.quad, 4 * VBS_RING * nv, r.old,
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
