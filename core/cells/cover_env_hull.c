/* The envelope decision from a convex hull (vbq_env_hull,
 * core/cells/vbq_env_exact.h): the vertices of the envelope max(0,
 * max_j a_j . u) on a patch, found without testing every owned triple.
 *
 * Why it is the same set. Testing triples (core/cells/cover_envelope.c)
 * writes owned (j, k, l) exactly when a_j, a_k, a_l are affinely
 * independent, W = sigma (a_k - a_j) x (a_l - a_j) is in the patch's closed
 * cone with n . W > 0, a_j . W > 0, and no label's point is above their
 * plane in direction W. That plane passes through three affinely
 * independent points of P = {0} u {a_m} and has every point of P on its
 * side: it is the plane of a 2-face of conv(P), W its outward normal, and
 * 0 is strictly below it (so 0 is no vertex of that face). Conversely
 * every such face gives exactly its owned affinely independent triples.
 * So: build conv(P) as triangles (every sign exact: each triangle's
 * cofactors in doubles from the exact rows first, vbq_env_sign_rows, then
 * vbq_env_sign_exact), keep the triangles whose
 * outward normal passes the patch's tests, collect the points on each
 * kept triangle's plane (exact zero signs: an exact crystal's cocircular
 * neighbours make faces of more than three points) and write their owned
 * triples that are affinely independent (a non-zero sign against 0).
 *
 * The hull: beneath-beyond, the points in their list order. A point sees
 * a triangle when it is strictly above its plane; the triangles it sees
 * are replaced by the cone from it to their horizon. With strict tests a
 * point on a triangle's plane outside the hull still sees some other
 * triangle (the hull is the intersection of its triangles' half-spaces),
 * coplanar neighbours may remain (faces come as several triangles), and a
 * point inside or on the hull is no vertex. If P lies in one plane (0
 * included), every plane through three of its points holds 0: no vertex,
 * nothing is written.
 *
 * The seen triangles: the live ones are tested newest first until one is
 * seen, then the search spreads from it across edges to the neighbours
 * that are seen too. That finds them all: the triangles a point outside a
 * convex polytope strictly sees form one disk of its boundary (the part
 * of the boundary that the segments from the point cross first), so they
 * are connected through edges. They are then replaced in ascending order,
 * so the triangles made are those of testing every live triangle
 * (tests/core/test_env_hull_vertices.c compares the seen sets). Cost:
 * the signs until a first seen triangle (every live one for a point
 * inside), then the seen ones' neighbours, and the faces' n each; most
 * decided by the filter, against C(owned, 3) triples times n beaters. */
#include <stdlib.h>
#include <string.h>

#include "vbq_env_exact.h"

/* A triangle of the hull: v counter-clockwise seen from outside; the
 * cofactors' doubles of its three rows (vbq_env_cofactors): a point's side
 * is one dot product away. */
typedef struct hull_tri {
    vbs_u32 v[3];
    vbs_u32 dead, seen, tested; /* seen, tested: the round of the last insertion */
    int tri_i;         /* its 128-bit cofactors: 0 not made, 1 made, -1 too large */
    double f[4], fe[4];
    vbq_i128 ci[4];
} hull_tri;

typedef struct hull {
    vbq_env_ctx *c;
    vbs_u32 np;       /* points: the labels 0 .. n-1, then n (the origin) */
    hull_tri *t;
    vbs_u32 nt, cap;
    vbs_u32 *edge;    /* edge[a * np + b]: the triangle with directed edge a -> b */
    vbs_u32 cur;      /* the triangle whose exact cofactors the context holds (or none) */
    vbs_u32 round;
    vbs_u32 *vis;     /* the triangles a point sees (cap of them) */
} hull;

#define HULL_NONE 0xffffffffu

/* Triangle (a, b, c) appended with its filter data; its edges recorded. */
static int hull_add(hull *h, vbs_u32 a, vbs_u32 b, vbs_u32 c)
{
    if (h->nt == h->cap) {
        vbs_u32 cap = h->cap ? 2u * h->cap : 64u;
        hull_tri *t = realloc(h->t, (size_t)cap * sizeof *t);
        if (t)
            h->t = t;
        vbs_u32 *vis = t ? realloc(h->vis, (size_t)cap * sizeof *vis) : NULL;
        if (!vis)
            return 0;
        h->vis = vis;
        h->cap = cap;
    }
    hull_tri *t = &h->t[h->nt];
    t->v[0] = a;
    t->v[1] = b;
    t->v[2] = c;
    t->dead = 0u;
    t->seen = 0u;
    t->tested = 0u;
    t->tri_i = 0;
    vbq_env_cofactors(h->c, a, b, c, t->f, t->fe);
    h->edge[a * h->np + b] = h->nt;
    h->edge[b * h->np + c] = h->nt;
    h->edge[c * h->np + a] = h->nt;
    h->nt++;
    return 1;
}

/* The exact sign of the triple product of triangle t's Y = (a_v1 - a_v0)
 * x (a_v2 - a_v0) with X = a_m - a_v0 (q NULL) or X = q: its cofactors'
 * doubles first, then vbq_env_sign_exact. 2: no memory. */
static int hull_sign(hull *h, vbs_u32 t, const double *q, vbs_u32 m)
{
    const hull_tri *r = &h->t[t];
    double r0[4];
    const double *row = r0;
    if (q) {
        r0[0] = 0.0;
        for (int a = 0; a < 3; a++)
            r0[a + 1] = q[a];
    } else {
        if (m == r->v[0] || m == r->v[1] || m == r->v[2])
            return 0;
        row = h->c->X.rd[m];
    }
    int v = vbq_env_sign_rows(row, r->f, r->fe);
    if (v)
        return v;
    /* the context takes the triangle's cofactors (its doubles, and its
     * 128-bit ones once made), and gives those back */
    vbq_env_ctx *c = h->c;
    if (h->cur != t) {
        if (h->cur != HULL_NONE && c->tri_i) {
            h->t[h->cur].tri_i = c->tri_i;
            memcpy(h->t[h->cur].ci, c->ci, sizeof c->ci);
        }
        memcpy(c->f, r->f, sizeof c->f);
        memcpy(c->fe, r->fe, sizeof c->fe);
        memcpy(c->ci, r->ci, sizeof c->ci);
        c->tri_i = r->tri_i;
        c->fast_made = 1;
        c->tri_made = 0;
        h->cur = t;
    }
    return vbq_env_sign_exact(c, q, m, r->v[0], r->v[1], r->v[2]);
}

/* The first tetrahedron: the origin, label 0 and the first pair (x, y)
 * off a common plane with them, as four outward triangles. 0 when every
 * point lies in one plane (see the top), -1 no memory. */
static int hull_start(hull *h, vbs_u32 *used)
{
    vbs_u32 A = h->np - 1u, B = 0u;
    for (vbs_u32 x = 1u; x + 1u < h->np; x++) {
        h->nt = 0u;
        h->cur = HULL_NONE; /* triangle 0 is made again */
        if (!hull_add(h, A, B, x))
            return -1;
        for (vbs_u32 y = x + 1u; y + 1u < h->np; y++) {
            int s = hull_sign(h, 0u, NULL, y);
            if (s == 2)
                return -1;
            if (s == 0)
                continue;
            /* orient so that y is below (A, b, c) */
            vbs_u32 b = s > 0 ? x : B, c = s > 0 ? B : x;
            h->nt = 0u;
            h->cur = HULL_NONE;
            if (!hull_add(h, A, b, c) || !hull_add(h, A, y, b) || !hull_add(h, b, y, c) ||
                !hull_add(h, A, c, y))
                return -1;
            used[0] = x;
            used[1] = y;
            return 1;
        }
    }
    return 0;
}

/* Live triangle t tested against point m this round: marked tested, and
 * seen (appended to vis) when m is strictly above it. 1, -1 no memory. */
static int hull_test(hull *h, vbs_u32 t, vbs_u32 m, vbs_u32 *nv)
{
    int s = hull_sign(h, t, NULL, m);
    if (s == 2)
        return -1;
    h->t[t].tested = h->round;
    if (s > 0) {
        h->t[t].seen = h->round;
        h->vis[(*nv)++] = t;
    }
    return 1;
}

/* Point m added: the triangles it sees (found as the top says) replaced,
 * in ascending order, by the cone from m to their horizon. 1 done (or m
 * inside), -1 no memory. */
static int hull_insert(hull *h, vbs_u32 m)
{
    h->round++;
    vbs_u32 nt = h->nt, nv = 0u;
    for (vbs_u32 t = nt; nv == 0u && t-- > 0u;)
        if (!h->t[t].dead && hull_test(h, t, m, &nv) < 0)
            return -1;
    for (vbs_u32 k = 0u; k < nv; k++)
        for (int e = 0; e < 3; e++) {
            vbs_u32 t = h->vis[k], a = h->t[t].v[e], b = h->t[t].v[(e + 1) % 3];
            vbs_u32 tw = h->edge[b * h->np + a];
            if (h->t[tw].tested != h->round && hull_test(h, tw, m, &nv) < 0)
                return -1;
        }
    for (vbs_u32 k = 1u; k < nv; k++) {
        vbs_u32 t = h->vis[k], j = k;
        for (; j > 0u && h->vis[j - 1u] > t; j--)
            h->vis[j] = h->vis[j - 1u];
        h->vis[j] = t;
    }
    for (vbs_u32 k = 0u; k < nv; k++) {
        vbs_u32 t = h->vis[k];
        h->t[t].dead = 1u;
        for (int e = 0; e < 3; e++) {
            vbs_u32 a = h->t[t].v[e], b = h->t[t].v[(e + 1) % 3];
            vbs_u32 tw = h->edge[b * h->np + a];
            if (h->t[tw].seen != h->round && !hull_add(h, a, b, m))
                return -1;
        }
    }
    return 1;
}

/* Does triangle t's outward normal pass the patch's tests (cone, square,
 * positive value)? 1 yes, 0 no, 2 no memory. */
static int hull_face_due(hull *h, vbs_u32 t, double qs[5][3])
{
    const hull_tri *r = &h->t[t];
    vbs_u32 o = h->np - 1u;
    if (r->v[0] == o || r->v[1] == o || r->v[2] == o)
        return 0; /* the origin on the face: value 0 */
    int v = hull_sign(h, t, qs[0], 0u);
    if (v != 1)
        return v == 2 ? 2 : 0;
    for (int e = 1; e < 5; e++) {
        v = hull_sign(h, t, qs[e], 0u);
        if (v == 2 || v < 0)
            return v == 2 ? 2 : 0;
    }
    v = hull_sign(h, t, NULL, o);
    return v == 2 ? 2 : v < 0;
}

/* The owned, affinely independent triples of the points on triangle t's
 * plane added (t passed hull_face_due); every live triangle on that plane
 * marked (seen = HULL_NONE) so the face is written once. 1, 0 no memory
 * (or a point above the plane: not a hull), -1 q full. */
static int hull_face_write(hull *h, vbs_u32 t, const vbq_arena *ar, vbq_cell_out *o,
                           vbs_u32 *on)
{
    vbq_env_ctx *c = h->c;
    vbs_u32 k = 0u;
    for (vbs_u32 m = 0u; m + 1u < h->np; m++) {
        int s = hull_sign(h, t, NULL, m);
        if (s != 0 && s != -1)
            return 0;
        if (s == 0)
            on[k++] = m;
    }
    vbs_u32 o0 = h->np - 1u;
    for (vbs_u32 a = 0u; a < k; a++) {
        if (c->L[on[a]].id <= c->i)
            continue;
        for (vbs_u32 b = a + 1u; b < k; b++) {
            if (c->L[on[b]].id <= c->i)
                continue;
            for (vbs_u32 d = b + 1u; d < k; d++) {
                if (c->L[on[d]].id <= c->i)
                    continue;
                if (k > 3u) {
                    /* collinear on the face: no vertex (0 is off the plane) */
                    c->tri_made = c->fast_made = c->tri_i = 0;
                    h->cur = HULL_NONE;
                    int s = vbq_env_sign_exact(c, NULL, o0, on[a], on[b], on[d]);
                    if (s == 2)
                        return 0;
                    if (s == 0)
                        continue;
                }
                if (!vbq_add_quad(ar, o, c->i, c->L[on[a]].id, c->L[on[b]].id,
                                  c->L[on[d]].id))
                    return -1;
            }
        }
    }
    if (k > 3u)
        for (vbs_u32 u = 0u; u < h->nt; u++) {
            const hull_tri *r = &h->t[u];
            int in = 0;
            for (vbs_u32 a = 0u; a < k; a++)
                in += on[a] == r->v[0] || on[a] == r->v[1] || on[a] == r->v[2];
            if (!r->dead && in == 3)
                h->t[u].seen = HULL_NONE;
        }
    else
        h->t[t].seen = HULL_NONE;
    return 1;
}

int vbq_env_hull(vbq_env_ctx *c, const vbq_arena *ar, vbq_cell_out *o, double qs[5][3])
{
    hull h;
    memset(&h, 0, sizeof h);
    h.c = c;
    h.np = c->n + 1u;
    h.cur = HULL_NONE;
    h.edge = malloc((size_t)h.np * h.np * sizeof *h.edge);
    vbs_u32 *on = malloc((size_t)h.np * sizeof *on);
    int rc = h.edge && on && vbq_env_rows_made(c) ? 1 : 0;
    vbs_u32 used[2] = {0u, 0u};
    int st = rc == 1 && c->n >= 3u ? hull_start(&h, used) : 0;
    if (st < 0)
        rc = 0;
    for (vbs_u32 m = 1u; rc == 1 && st == 1 && m < c->n; m++)
        if (m != used[0] && m != used[1] && hull_insert(&h, m) < 0)
            rc = 0;
    /* the faces; every live triangle's mark is now below the round count */
    for (vbs_u32 t = 0u; rc == 1 && st == 1 && t < h.nt; t++) {
        if (h.t[t].dead || h.t[t].seen == HULL_NONE)
            continue;
        int d = hull_face_due(&h, t, qs);
        if (d == 2)
            rc = 0;
        else if (d == 1)
            rc = hull_face_write(&h, t, ar, o, on);
    }
    free(h.edge);
    free(h.t);
    free(h.vis);
    free(on);
    return rc;
}
