/* Topology of the cells (Sec. 4): faces from the colours a cell's rays see,
 * Voronoi edges from two-colour neighbourhoods, joined to certified vertices.
 *
 * A face (i, j) exists where a ray of i meets the bisector of j first. An
 * edge of cell i lies where two faces a, b meet: grid cells whose corners
 * carry exactly the two colours a, b show that the trisector of {i, a, b}
 * carries a Voronoi edge. The edges along a trisector are decided on the
 * curve itself (trisector.c): the certified vertices whose members contain
 * the triple, in their order along it, and between and beyond them one
 * point each whose tangent sphere must be empty for that part to be an
 * edge. Every triple of every vertex is tried so; the two-colour evidence
 * is counted against the result (vb_topology.sampled). */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_topology.h"
#include "vbs_internal.h"

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static int push(uint32_t **v, size_t *n, size_t *cap, const uint32_t *x, size_t k)
{
    if (VB_ARRAY_FIT(*v, *cap, *n + k, 1024) != VB_OK)
        return VB_ENOMEM;
    if (k)
        memcpy(*v + *n, x, k * sizeof *x);
    *n += k;
    return VB_OK;
}

static void sort3(uint32_t t[3])
{
    qsort(t, 3, sizeof *t, cmp_u32);
}

/* Colour of a ray only where it is unambiguous: the runner-up bisector is
 * hit more than 1e-9 (relative) farther. On symmetric inputs many rays pass
 * exactly through edges, where a rounding decides the colour; such rays
 * say nothing about which faces exist. Returns VBS_INF_COLOUR - 1 for them. */
#define AMBIGUOUS (VBS_INF_COLOUR - 1u)

static uint32_t robust_colour(const vbs_base *b, const vbs_bisector *bis, const uint32_t *off,
                              const uint32_t *idx, unsigned T, unsigned f, double u, double v)
{
    double d[3];
    vbs_face_dir(f, u, v, d);
    unsigned tile = b->tile_start + f * T * T + vbs_tile_of(v, T) * T + vbs_tile_of(u, T);
    double best = b->clip, second = b->clip;
    uint32_t colour = VBS_INF_COLOUR;
    for (uint32_t q = off[tile]; q < off[tile + 1]; q++) {
        const vbs_bisector *e = bis + idx[q];
        double h = vbs_ray_hit(e->ex, e->ey, e->ez, e->delta, e->num, d);
        if (h < 0.0)
            continue;
        if (h < best) {
            second = best;
            best = h;
            colour = e->id;
        } else if (h < second) {
            second = h;
        }
    }
    return second - best > 1e-9 * best ? colour : AMBIGUOUS;
}

/* Two-colour test of one grid cell: q holds the colours of its nq corner
 * rays. Ambiguous corners say nothing either way and are skipped. Writes
 * the sorted triple {base, a, b} and returns 1 when exactly two finite
 * colours a, b remain; 0 otherwise. */
static int cell_triple(const uint32_t *q, int nq, uint32_t base, uint32_t t[3])
{
    uint32_t a = VBS_INF_COLOUR, c2 = VBS_INF_COLOUR;
    for (int m = 0; m < nq; m++) {
        if (q[m] >= AMBIGUOUS || q[m] == a || q[m] == c2)
            continue;
        if (a == VBS_INF_COLOUR)
            a = q[m];
        else if (c2 == VBS_INF_COLOUR)
            c2 = q[m];
        else
            return 0;
    }
    if (c2 == VBS_INF_COLOUR)
        return 0;
    t[0] = base;
    t[1] = a;
    t[2] = c2;
    sort3(t);
    return 1;
}

/* Edge triples of one base, buffered in buf (cap entries of 3) and flushed
 * into the accumulator when full. */
typedef struct triple_buf {
    vbs_topo_acc *acc;
    uint32_t *buf;
    size_t n, cap;
} triple_buf;

static int emit_cell(triple_buf *tb, const uint32_t *q, int nq, uint32_t base)
{
    uint32_t *t = tb->buf + 3 * tb->n;
    if (!cell_triple(q, nq, base, t))
        return VB_OK;
    /* Neighbouring cells repeat the same triple: skip runs. */
    if (tb->n > 0 && memcmp(t, t - 3, 3 * sizeof *t) == 0)
        return VB_OK;
    if (++tb->n < tb->cap)
        return VB_OK;
    tb->n = 0;
    return push(&tb->acc->triples, &tb->acc->ntriples, &tb->acc->triples_cap, tb->buf,
                3 * tb->cap);
}

/* Index of the grid row next to a face boundary: sign > 0 is the row before
 * coordinate +1 (k = S-2), sign < 0 the row after -1 (k = 1); with
 * edge_row, the face cells along that boundary. */
static unsigned inner_row(int sign, unsigned S)
{
    return sign > 0 ? S - 2u : 1u;
}

/* Index of the boundary row itself (coordinate +1 or -1). */
static unsigned edge_row(int sign, unsigned S)
{
    return sign > 0 ? S - 1u : 0u;
}

int vbs_topo_collect(vbs_topo_acc *acc, const vb_sampler_batch *bt, size_t k)
{
    unsigned S = bt->params.samples, T = bt->params.tiles;
    const vbs_base *b = bt->bases + k;
    uint32_t base = b->id;
    size_t rays = 6u * (size_t)S * S;
    uint32_t *colours = malloc(2 * rays * sizeof *colours);
    if (!colours)
        return VB_ENOMEM;
    uint32_t *tmp = colours + rays;
    for (unsigned f = 0; f < 6; f++)
        for (unsigned iv = 0; iv < S; iv++)
            for (unsigned iu = 0; iu < S; iu++)
                colours[((size_t)f * S + iv) * S + iu] =
                    robust_colour(b, bt->bis, bt->tile_off, bt->tile_idx, T, f,
                                  vbs_sample_coord(iu, S), vbs_sample_coord(iv, S));
    /* Faces: distinct unambiguous colours of this base. */
    size_t n = 0;
    for (size_t q = 0; q < rays; q++)
        if (colours[q] < AMBIGUOUS)
            tmp[n++] = colours[q];
    if (n)
        qsort(tmp, n, sizeof *tmp, cmp_u32);
    int rc = VB_OK;
    for (size_t q = 0; q < n && rc == VB_OK; q++) {
        if (q > 0 && tmp[q] == tmp[q - 1])
            continue;
        uint32_t f[2] = {base < tmp[q] ? base : tmp[q], base < tmp[q] ? tmp[q] : base};
        rc = push(&acc->faces, &acc->nfaces, &acc->faces_cap, f, 2);
    }
    /* Edges: grid cells with exactly two finite colours. */
    triple_buf tb = {acc, tmp, 0, rays / 3};
#define COL(f, iu, iv) colours[((size_t)(f) * S + (iv)) * S + (iu)]
    for (unsigned f = 0; f < 6 && rc == VB_OK; f++)
        for (unsigned iv = 0; iv + 1 < S && rc == VB_OK; iv++)
            for (unsigned iu = 0; iu + 1 < S && rc == VB_OK; iu++) {
                uint32_t q[4] = {COL(f, iu, iv), COL(f, iu + 1, iv), COL(f, iu, iv + 1),
                                 COL(f, iu + 1, iv + 1)};
                rc = emit_cell(&tb, q, 4, base);
            }
    /* Cells across the cube's seams and corners. A face's grid cells end at
     * the seam rays; an edge running along a seam (directions of an
     * axis-aligned input) puts exactly those rays on the trisector, where
     * they are ambiguous, so no face cell sees its two colours. A seam cell
     * is the union of the two face cells that meet at the seam (rows next to
     * the seam and the seam rays of both faces); a corner cell the union of
     * the three face cells at the corner. Ray spacing stays the grid's, so
     * they say no more than a face cell would.
     * Face f (axis a, sign s) at u = sg borders face g (axis a+1, sign sg):
     * there g's u runs along the seam as f's v does, and g's v = s. */
    for (unsigned f = 0; f < 6 && rc == VB_OK; f++) {
        unsigned a = f / 2u;
        int s = (f & 1u) ? -1 : 1;
        for (int sg = -1; sg <= 1 && rc == VB_OK; sg += 2) {
            unsigned g = 2u * ((a + 1u) % 3u) + (sg > 0 ? 0u : 1u);
            unsigned fu = inner_row(sg, S), fs = edge_row(sg, S);
            unsigned gv = inner_row(s, S), gs = edge_row(s, S);
            for (unsigned t = 0; t + 1 < S && rc == VB_OK; t++) {
                uint32_t q[8] = {COL(f, fu, t), COL(f, fu, t + 1), COL(f, fs, t),
                                 COL(f, fs, t + 1), COL(g, t, gv), COL(g, t + 1, gv),
                                 COL(g, t, gs), COL(g, t + 1, gs)};
                rc = emit_cell(&tb, q, 8, base);
            }
        }
    }
    /* Corner (sx, sy, sz): on the face of axis a the corner is at
     * u = s[a+1], v = s[a+2]. */
    for (unsigned c = 0; c < 8 && rc == VB_OK; c++) {
        int sgn[3] = {(c & 1u) ? -1 : 1, (c & 2u) ? -1 : 1, (c & 4u) ? -1 : 1};
        uint32_t q[12];
        for (unsigned a = 0; a < 3; a++) {
            unsigned f = 2u * a + (sgn[a] > 0 ? 0u : 1u);
            int su = sgn[(a + 1u) % 3u], sv = sgn[(a + 2u) % 3u];
            unsigned iu = inner_row(su, S), eu = edge_row(su, S);
            unsigned iv = inner_row(sv, S), ev = edge_row(sv, S);
            q[4 * a] = COL(f, iu, iv);
            q[4 * a + 1] = COL(f, eu, iv);
            q[4 * a + 2] = COL(f, iu, ev);
            q[4 * a + 3] = COL(f, eu, ev);
        }
        rc = emit_cell(&tb, q, 12, base);
    }
#undef COL
    if (rc == VB_OK)
        rc = push(&acc->triples, &acc->ntriples, &acc->triples_cap, tmp, 3 * tb.n);
    free(colours);
    return rc;
}

static int cmp_pair(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    if (a[0] != b[0])
        return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

static int cmp_triple(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

static size_t dedupe(uint32_t *v, size_t n, size_t w, int (*cmp)(const void *, const void *))
{
    if (n)
        qsort(v, n, w * sizeof *v, cmp);
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (m == 0 || memcmp(v + w * (m - 1), v + w * k, w * sizeof *v) != 0)
            memmove(v + w * m++, v + w * k, w * sizeof *v);
    return m;
}

int vbs_topo_finish(vbs_topo_acc *acc, vb_topology_evidence *ev)
{
    acc->nfaces = 2 * dedupe(acc->faces, acc->nfaces / 2, 2, cmp_pair);
    acc->ntriples = 3 * dedupe(acc->triples, acc->ntriples / 3, 3, cmp_triple);
    ev->faces = acc->faces;
    ev->nfaces = acc->nfaces / 2;
    ev->triples = acc->triples;
    ev->ntriples = acc->ntriples / 3;
    acc->faces = acc->triples = NULL;
    acc->nfaces = acc->ntriples = 0;
    return VB_OK;
}

void vb_topology_init(vb_topology *t)
{
    memset(t, 0, sizeof *t);
}

void vb_topology_free(vb_topology *t)
{
    free(t->faces);
    free(t->edges);
    vb_topology_init(t);
}

/* (triple, vertex) record for the join. */
typedef struct tv {
    uint32_t t[3];
    uint32_t v;
} tv;

static int cmp_tv(const void *pa, const void *pb)
{
    const tv *a = pa, *b = pb;
    int c = cmp_triple(a->t, b->t);
    return c ? c : (a->v > b->v) - (a->v < b->v);
}

/* Appends an edge; a finite one lists its lower row first. */
static int add_edge(vb_topology *out, int64_t v0, int64_t v1, const uint32_t t[3])
{
    if (v1 >= 0 && v1 < v0) {
        int64_t w = v0;
        v0 = v1;
        v1 = w;
    }
    if (VB_ARRAY_FIT(out->edges, out->edges_cap, out->nedges + 1, 256) != VB_OK)
        return VB_ENOMEM;
    vb_topology_edge *ed = out->edges + out->nedges++;
    ed->v[0] = v0;
    ed->v[1] = v1;
    memcpy(ed->spheres, t, sizeof ed->spheres);
    return VB_OK;
}

/* A vertex on a trisector: its branch parameter and row. */
typedef struct on_curve {
    double s;
    uint32_t v;
} on_curve;

static int cmp_on_curve(const void *pa, const void *pb)
{
    const on_curve *a = pa, *b = pb;
    if (a->s != b->s)
        return a->s < b->s ? -1 : 1;
    return (a->v > b->v) - (a->v < b->v);
}

/* Whether the trisector's point at branch parameter s is on a Voronoi edge
 * of its three spheres: its tangent sphere holds no other sphere. A sphere
 * within `band` of touching it is beyond what doubles decide: for equal
 * radii the point is then decided in rationals (an exact lattice touches,
 * a jittered one may cut by 1e-18); otherwise touching counts as on it. */
static int on_edge(const vbs_hash *h, const vbs_trisector *tr, const uint32_t t[3], double s,
                   double guard, uint32_t **near, size_t *near_cap)
{
    vbs_cand c;
    memset(&c, 0, sizeof c);
    double p[3];
    vbs_trisector_point(tr, s, p, &c.t);
    c.x = p[0];
    c.y = p[1];
    c.z = p[2];
    const uint32_t q[4] = {t[0], t[1], t[2], t[2]};
    double band = guard * (1.0 + fabs(c.t));
    if (!vbs_tangent_empty(h, &c, q, band))
        return 0; /* cut by more than the band */
    c.t += 2.0 * band;
    int clear = vbs_tangent_empty(h, &c, q, band);
    c.t -= 2.0 * band;
    if (clear || !vbs_trisector_equal_radii(h->set, t))
        return 1;
    size_t nn = 0;
    if (vbs_hash_query(h, p, c.t + h->rmax + 2.0 * band, near, &nn, near_cap) != VB_OK)
        return -1;
    return vbs_trisector_exact_on_edge(h->set, t, p, *near, nn);
}

/* Buffers reused across triples: the vertices on a curve, the spheres
 * near a test point. */
typedef struct edge_scratch {
    on_curve *oc;
    uint32_t *near;
    size_t near_cap;
} edge_scratch;

/* on_edge at s, with an allocation failure as VB_ENOMEM in *rc. */
static int part_on_edge(const vbs_hash *h, const vbs_trisector *tr, const uint32_t t[3],
                        double s, double guard, edge_scratch *sc, int *rc)
{
    int on = on_edge(h, tr, t, s, guard, &sc->near, &sc->near_cap);
    if (on < 0)
        *rc = VB_ENOMEM;
    return on > 0;
}

/* The edges along the trisector of t through the vertices rows[0..nv):
 * sorted along the branch, consecutive vertices are joined where the curve
 * between them is on the diagram, and the ends run to infinity (open
 * branch) or join around (closed curve) where that part is. Membership can
 * change only at a vertex, so one point per part decides it. Where doubles
 * find no trisector curve the plain join is kept: one vertex runs to
 * infinity, two are joined, more are counted unresolved. */
static int trisector_edges(const vb_sphere_set *set, const vbs_hash *h, double guard,
                           const vb_vertex_list *vx, const uint32_t t[3], const tv *rows,
                           size_t nv, edge_scratch *sc, vb_topology *out)
{
    on_curve *oc = sc->oc;
    vbs_trisector tr;
    if (!vbs_trisector_init(set, t[0], t[1], t[2], &tr)) {
        if (nv > 2) {
            out->unresolved++;
            return VB_OK;
        }
        return add_edge(out, rows[0].v, nv == 2 ? (int64_t)rows[1].v : -1, t);
    }
    for (size_t k = 0; k < nv; k++) {
        uint32_t v = rows[k].v;
        const double p[3] = {vx->x[v], vx->y[v], vx->z[v]};
        oc[k] = (on_curve){vbs_trisector_param(&tr, p, vx->t[v]), v};
    }
    if (nv > 1)
        qsort(oc, nv, sizeof *oc, cmp_on_curve);
    int rc = VB_OK;
    for (size_t k = 0; k + 1 < nv && rc == VB_OK; k++)
        if (part_on_edge(h, &tr, t, 0.5 * (oc[k].s + oc[k + 1].s), guard, sc, &rc))
            rc = add_edge(out, oc[k].v, oc[k + 1].v, t);
    double first = oc[0].s, last = oc[nv - 1].s;
    if (rc == VB_OK && !tr.closed) {
        if (part_on_edge(h, &tr, t, first - (1.0 + fabs(first)), guard, sc, &rc))
            rc = add_edge(out, oc[0].v, -1, t);
        if (rc == VB_OK && part_on_edge(h, &tr, t, last + (1.0 + fabs(last)), guard, sc, &rc))
            rc = add_edge(out, oc[nv - 1].v, -1, t);
    } else if (rc == VB_OK) {
        /* Around through s = +-pi. */
        const double L = 3.14159265358979323846;
        double mid = L - last > first + L ? 0.5 * (last + L) : 0.5 * (first - L);
        if (part_on_edge(h, &tr, t, mid, guard, sc, &rc)) {
            if (nv == 1)
                out->unresolved++; /* a closed edge through one vertex */
            else
                rc = add_edge(out, oc[nv - 1].v, oc[0].v, t);
        }
    }
    return rc;
}

int vb_topology_build(vb_ctx *ctx, const vb_sphere_set *set, const vb_topology_evidence *ev,
                      const vb_vertex_list *vx, vb_topology *out)
{
    vb_topology_init(out);
    size_t ntv = 0, cap = 0;
    tv *recs = NULL;
    uint32_t *faces = NULL, *trip = NULL;
    edge_scratch sc = {NULL, NULL, 0};
    size_t nf = 0, fcap = 0, ntr = 0, tcap = 0;
    vbs_hash hash;
    memset(&hash, 0, sizeof hash);
    int rc = vbs_hash_build(ctx, set, &hash);
    if (rc != VB_OK)
        return rc;
    rc = push(&faces, &nf, &fcap, ev->faces, 2 * ev->nfaces);
    for (size_t k = 0; k < vx->n && rc == VB_OK; k++) {
        const uint32_t *m = vx->ids + vx->start[k];
        size_t nm = vx->start[k + 1] - vx->start[k];
        for (size_t a = 0; a < nm && rc == VB_OK; a++)
            for (size_t b = a + 1; b < nm && rc == VB_OK; b++) {
                if (nm == 4) {
                    uint32_t f[2] = {m[a], m[b]};
                    rc = push(&faces, &nf, &fcap, f, 2);
                }
                for (size_t c = b + 1; c < nm && rc == VB_OK; c++) {
                    if (VB_ARRAY_FIT(recs, cap, ntv + 1, 1024) != VB_OK) {
                        rc = VB_ENOMEM;
                        break;
                    }
                    recs[ntv++] = (tv){{m[a], m[b], m[c]}, (uint32_t)k};
                    uint32_t t[3] = {m[a], m[b], m[c]};
                    rc = push(&trip, &ntr, &tcap, t, 3);
                }
            }
    }
    if (rc == VB_OK && !(sc.oc = malloc((ntv + 1) * sizeof *sc.oc)))
        rc = VB_ENOMEM;
    if (rc == VB_OK) {
        if (ntv)
            qsort(recs, ntv, sizeof *recs, cmp_tv);
        nf = 2 * dedupe(faces, nf / 2, 2, cmp_pair);
        ntr = 3 * dedupe(trip, ntr / 3, 3, cmp_triple);
        out->faces = faces;
        out->nfaces = nf / 2;
        faces = NULL;
        /* Rounding guard of the emptiness tests: 1e-9 of the bounding-box
         * diagonal (as the matching's; the default tol is 1e-5 of it). */
        double guard = 1e-4 * vb_sampler_default_tol(set);
        /* Join each triple with the vertices that contain it. */
        size_t r = 0;
        for (size_t k = 0; k < ntr / 3 && rc == VB_OK; k++) {
            const uint32_t *t = trip + 3 * k;
            while (r < ntv && cmp_triple(recs[r].t, t) < 0)
                r++;
            size_t e = r;
            while (e < ntv && cmp_triple(recs[e].t, t) == 0)
                e++;
            rc = trisector_edges(set, &hash, guard, vx, t, recs + r, e - r, &sc, out);
        }
        /* How many edge lines the two-colour sampling saw (Sec. 4). */
        for (size_t k = 0; rc == VB_OK && ev->ntriples && k < out->nedges; k++)
            out->sampled += bsearch(out->edges[k].spheres, ev->triples, ev->ntriples,
                                    3 * sizeof *ev->triples, cmp_triple) != NULL;
    }
    free(sc.oc);
    free(sc.near);
    free(recs);
    free(faces);
    free(trip);
    vbs_hash_free(&hash);
    if (rc != VB_OK) {
        vb_topology_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (topology)");
    }
    return VB_OK;
}

int vb_topology_write(vb_ctx *ctx, FILE *f, const vb_topology *t)
{
    fputs("# vorball topology\n# face\ti\tj\t(spheres sharing a Voronoi face)\n"
          "# edge\tv1\tv2\ti,j,k\t(0-based vertex rows of the vertex output; -1: the edge "
          "runs to infinity)\n",
          f);
    if (t->exact) {
        size_t fin = 0, inf = 0, loops = 0;
        for (size_t k = 0; k < t->nedges; k++) {
            const vb_topology_edge *e = t->edges + k;
            fin += e->v[1] >= 0 && e->v[1] != e->v[0];
            inf += e->v[1] < 0;
            loops += e->v[1] == e->v[0];
        }
        fprintf(f,
                "# edges exact (from arc closure): every Voronoi edge at the vertices traced "
                "to its ends, once each (more spheres on one edge: the triple of its three "
                "smallest ids; v1 = v2: a closed loop); faces decided exactly at the vertices\n"
                "# %zu faces, %zu edges: %zu between vertices, %zu to infinity, %zu closed "
                "loops; %zu half arcs undecided, %zu vertices with undecided faces\n",
                t->nfaces, t->nedges, fin, inf, loops, t->undecided, t->unresolved);
    } else {
        fprintf(f, "# %zu faces, %zu edge lines (%zu of them seen by two-colour sampling)\n",
                t->nfaces, t->nedges, t->sampled);
    }
    for (size_t k = 0; k < t->nfaces; k++)
        fprintf(f, "face\t%u\t%u\n", (unsigned)t->faces[2 * k], (unsigned)t->faces[2 * k + 1]);
    for (size_t k = 0; k < t->nedges; k++) {
        const vb_topology_edge *e = t->edges + k;
        fprintf(f, "edge\t%lld\t%lld\t%u,%u,%u\n", (long long)e->v[0], (long long)e->v[1],
                (unsigned)e->spheres[0], (unsigned)e->spheres[1], (unsigned)e->spheres[2]);
    }
    if (ferror(f))
        return vb_error(ctx, VB_EIO, NULL, 0, "write failed (topology)");
    return VB_OK;
}
