/* Where a channel's centreline starts and ends: its openings, the widest
 * pair of them through the molecule, or the fallbacks. */
#include <math.h>
#include <stdlib.h>

#include "vbc_graph.h"
#include "vbc_radix.h"

/* A pair of openings counts as "through" the molecule when they are at
 * least this fraction of the molecule's width apart along the line joining
 * them: two mouths of a pore on opposite faces, not two openings of one
 * vestibule or of one groove. */
#define THROUGH_RATIO 0.6

/* How many voxels ahead the Kruskal scan fetches adjacency. */
#define KRUSKAL_AHEAD 8

/* Whether the molecule is wider along unit vector u than d / THROUGH_RATIO,
 * i.e. whether THROUGH_RATIO * width > d for its width from the support
 * atoms. The width only grows atom by atom (and the product with it), so
 * the walk stops at the first atom that settles it: the same answer as
 * the whole width's, at a fraction of the atoms for most pairs. */
static int wider_than(const vbc_graph *A, const double u[3], double d)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t t = 0; t < A->nsupport; t++) {
        int32_t i = A->support[t];
        double c = A->s->x[i] * u[0] + A->s->y[i] * u[1] + A->s->z[i] * u[2];
        /* fmin/fmax on finite values, without their libm calls. */
        lo = c - A->s->r[i] < lo ? c - A->s->r[i] : lo;
        hi = c + A->s->r[i] > hi ? c + A->s->r[i] : hi;
        if (THROUGH_RATIO * (hi - lo) > d)
            return 1;
    }
    return 0;
}

static int through_pair(const vbc_graph *A, uint32_t ra, uint32_t rb)
{
    double pa[3], pb[3], u[3];
    vbc_voxel_centre(A->g, A->v[ra], pa);
    vbc_voxel_centre(A->g, A->v[rb], pb);
    double d = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                    (pa[2] - pb[2]) * (pa[2] - pb[2]));
    if (d == 0.0)
        return 0;
    for (int k = 0; k < 3; k++)
        u[k] = (pb[k] - pa[k]) / d;
    return !wider_than(A, u, d);
}

/* The members in Kruskal's order, (clearance descending, position
 * ascending), into order[0..m): a radix sort on the clearance's bits over
 * members (ascending positions), so ties keep their positions' order.
 * key holds 2 m keys and order 2 m positions (the second halves scratch).
 * Clearances are never NaN (distances to atoms; given ones are finite
 * floats). */
static void kruskal_order(const vbc_graph *A, const uint32_t *members, size_t m, uint64_t *key,
                          uint32_t *order)
{
    for (size_t t = 0; t < m; t++) {
        key[t] = vbc_radix_desc(A->clear[members[t]]);
        order[t] = members[t];
    }
    vbc_radix_sort(key, order, key + m, order + m, m, 0);
}

/* The widest pair of openings that lies through the molecule: voxels enter by
 * decreasing clearance (a maximum spanning forest, as in Kruskal); the first
 * union that joins two openings forming a through pair decides, and the
 * clearance at that moment is the best bottleneck any path between them can
 * have. Returns 1 with *a, *b set, 0 when no pair is through, -1 on ENOMEM. */
static int widest_through(vbc_graph *A, vb_uf *uf, const uint32_t *members, size_t m,
                          const uint32_t *reps, size_t k, uint32_t *a, uint32_t *b)
{
    uint64_t *key = malloc(2 * m * sizeof *key);
    uint32_t *S = malloc(2 * m * sizeof *S);
    uint32_t *head = malloc(m * sizeof *head), *tail = malloc(m * sizeof *tail);
    uint32_t *next = malloc(k * sizeof *next);
    int found = 0;
    if (!key || !S || !head || !tail || !next) {
        found = -1;
        goto out;
    }
    /* Positions are global; index the scratch by order in `members` via pred. */
    for (size_t t = 0; t < m; t++) {
        A->pred[members[t]] = (uint32_t)t;   /* local index */
        A->hpos[members[t]] = 0;             /* not yet added */
        head[t] = tail[t] = UINT32_MAX;
    }
    for (size_t r = 0; r < k; r++) {
        uint32_t l = A->pred[reps[r]];
        head[l] = tail[l] = (uint32_t)r;
        next[r] = UINT32_MAX;
    }
    /* A total order (ties by position): the same on any number of threads. */
    kruskal_order(A, members, m, key, S);
    /* The voxels come in clearance order, scattered over the graph: their
     * adjacency is fetched ahead (perf: the scan waited on the loads of
     * adj_start and adj; the order is known, so the loads can start
     * KRUSKAL_AHEAD voxels early, the adjacency's once its start is in). */
    const size_t *adj_start = A->adj_start;
    const uint32_t *adj = A->adj;
    uint32_t *added = A->hpos;
    for (size_t t = 0; t < m && !found; t++) {
        if (t + 2 * KRUSKAL_AHEAD < m)
            __builtin_prefetch(&adj_start[S[t + 2 * KRUSKAL_AHEAD]]);
        if (t + KRUSKAL_AHEAD < m)
            __builtin_prefetch(&adj[adj_start[S[t + KRUSKAL_AHEAD]]]);
        uint32_t u = S[t], ru = u; /* u's root, kept through its unions */
        added[u] = 1;
        uf->p[u] = u;
        for (size_t e = adj_start[u], end = adj_start[u + 1]; e < end && !found; e++) {
            uint32_t q = adj[e];
            if (!added[q])
                continue;
            uint32_t rq = vb_uf_root(uf, (uint32_t)q);
            if (ru == rq)
                continue;
            uint32_t lu = A->pred[ru], lq = A->pred[rq];
            for (uint32_t x = head[lu]; x != UINT32_MAX && !found; x = next[x])
                for (uint32_t y = head[lq]; y != UINT32_MAX && !found; y = next[y])
                    if (through_pair(A, reps[x], reps[y])) {
                        *a = reps[x < y ? x : y];
                        *b = reps[x < y ? y : x];
                        found = 1;
                    }
            uint32_t root = vb_uf_join(uf, ru, rq), lr = A->pred[root], lo = root == ru ? lq : lu;
            ru = root;
            /* Concatenate the opening lists into the surviving root's. */
            if (head[lo] != UINT32_MAX) {
                if (head[lr] == UINT32_MAX) {
                    head[lr] = head[lo];
                } else {
                    next[tail[lr]] = head[lo];
                }
                tail[lr] = tail[lo];
                head[lo] = tail[lo] = UINT32_MAX;
            }
        }
    }
out:
    free(key);
    free(S);
    free(head);
    free(tail);
    free(next);
    return found;
}

/* Atoms extreme along any of SUPPORT_DIRS directions (Fibonacci sphere):
 * the width of the molecule along a direction is then measured over these
 * few atoms instead of all. Per direction the atom of least c - r and the
 * one of greatest c + r (c = p . u; ties to the lowest index, as a scan in
 * index order keeps its first). *out is malloc'ed.
 *
 * The atoms are visited by decreasing reach rho = |p - C| + r from their
 * centroid C, not in index order: c + r <= C . u + rho and c - r >=
 * C . u - rho, so once C . u + rho (less the margin) falls below the
 * greatest c + r found, and C . u - rho (plus it) above the least c - r,
 * no atom left can reach either, not even tie it. The margin, 1e-9 of the
 * coordinates' scale, dwarfs the rounding of these sums (about 1e-15 of
 * it). A globular molecule's outer shell decides, a few per cent of its
 * atoms a direction (1chb: 0.4 ms of a frame's serial analysis before). */
#define SUPPORT_DIRS 64

static int support_atoms(const vb_sphere_set *s, int32_t **out, size_t *count)
{
    int32_t *list = malloc(2 * SUPPORT_DIRS * sizeof *list);
    /* Reaches as descending radix keys, with their atoms (second halves:
     * the sort's scratch). */
    uint64_t *key = malloc(2 * (s->n ? s->n : 1) * sizeof *key);
    uint32_t *at = malloc(2 * (s->n ? s->n : 1) * sizeof *at);
    double *rho = malloc((s->n ? s->n : 1) * sizeof *rho);
    if (!list || !key || !at || !rho) {
        free(list);
        free(key);
        free(at);
        free(rho);
        return -1;
    }
    double C[3] = {0.0, 0.0, 0.0}, scale = 1.0;
    for (size_t i = 0; i < s->n; i++) {
        C[0] += s->x[i];
        C[1] += s->y[i];
        C[2] += s->z[i];
        double m = fabs(s->x[i]) + fabs(s->y[i]) + fabs(s->z[i]) + fabs(s->r[i]);
        scale = m > scale ? m : scale;
    }
    for (int k = 0; k < 3 && s->n; k++)
        C[k] /= (double)s->n;
    for (size_t i = 0; i < s->n; i++) {
        double dx = s->x[i] - C[0], dy = s->y[i] - C[1], dz = s->z[i] - C[2];
        rho[i] = sqrt(dx * dx + dy * dy + dz * dz) + s->r[i];
        key[i] = vbc_radix_desc(rho[i]);
        at[i] = (uint32_t)i;
    }
    vbc_radix_sort(key, at, key + s->n, at + s->n, s->n, 0);
    double margin = 1e-9 * scale;
    size_t n = 0;
    for (int d = 0; d < SUPPORT_DIRS; d++) {
        double z = 1.0 - (2.0 * d + 1.0) / SUPPORT_DIRS, r = sqrt(1.0 - z * z);
        double u[3] = {r * cos(2.39996322972865332 * d), r * sin(2.39996322972865332 * d), z};
        double cu = C[0] * u[0] + C[1] * u[1] + C[2] * u[2];
        int32_t lo = 0, hi = 0;
        double vlo = INFINITY, vhi = -INFINITY;
        for (size_t k = 0; k < s->n; k++) {
            int32_t i = (int32_t)at[k];
            if (cu + rho[i] + margin < vhi && cu - rho[i] - margin > vlo)
                break;
            double c = s->x[i] * u[0] + s->y[i] * u[1] + s->z[i] * u[2];
            double a = c - s->r[i], b = c + s->r[i];
            if (a < vlo || (a == vlo && i < lo)) {
                vlo = a;
                lo = i;
            }
            if (b > vhi || (b == vhi && i < hi)) {
                vhi = b;
                hi = i;
            }
        }
        list[n++] = lo;
        list[n++] = hi;
    }
    free(key);
    free(at);
    free(rho);
    *out = list;
    *count = n;
    return 0;
}

int vbc_graph_support(vbc_graph *A)
{
    return A->support ? 0 : support_atoms(A->s, &A->support, &A->nsupport);
}

/* vbc_channel_ends without its sweep: *b is UINT32_MAX when the member
 * farthest from *a along the voxels (plain lengths) ends the line.
 * Returns 0, or -1 when out of memory. */
int vbc_channel_openings(vbc_graph *A, vb_uf *uf, const uint32_t *members, size_t m, uint32_t *a,
                         uint32_t *b, int *through)
{
    *through = 0;
    for (size_t t = 0; t < m; t++) {
        uf->p[members[t]] = members[t];
        A->rep[members[t]] = UINT32_MAX;
    }
    /* The openings: mouth voxels joined across their edges, each edge once,
     * from its smaller end. The sets, each named by its smallest voxel, do
     * not depend on the order of the joins. */
    const uint8_t *mouth = A->mouth;
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (!mouth[u])
            continue;
        for (size_t e = A->adj_start[u], end = A->adj_start[u + 1]; e < end; e++) {
            uint32_t q = A->adj[e];
            if (q > u && mouth[q])
                vb_uf_join(uf, u, q);
        }
    }
    /* The widest voxel of each opening, kept at the opening's root. */
    size_t k = 0;
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (!A->mouth[u])
            continue;
        uint32_t r = vb_uf_root(uf, u);
        if (A->rep[r] == UINT32_MAX) {
            k++;
            A->rep[r] = u;
        } else if (A->clear[u] > A->clear[A->rep[r]]) {
            A->rep[r] = u;
        }
    }
    if (k == 0) {
        /* No mouth: callers send cavities elsewhere; span the component anyway. */
        *a = members[0];
        *b = UINT32_MAX;
        return 0;
    }
    uint32_t *reps = malloc(k * sizeof *reps);
    if (!reps)
        return -1;
    k = 0;
    for (size_t t = 0; t < m; t++) {
        uint32_t u = members[t];
        if (A->mouth[u] && uf->p[u] == u)
            reps[k++] = A->rep[u];
    }
    if (k >= 2 && vbc_graph_support(A) != 0) {
        free(reps);
        return -1;
    }
    int w = k >= 2 ? widest_through(A, uf, members, m, reps, k, a, b) : 0;
    if (w < 0) {
        free(reps);
        return -1;
    }
    if (w == 1) {
        *through = 1;
        free(reps);
        return 0;
    }
    /* No through pair: the farthest pair of openings (ties to the lowest). */
    uint32_t ba = reps[0], bb = UINT32_MAX;
    double best = -1.0;
    for (size_t x = 0; x < k; x++) {
        double px[3];
        vbc_voxel_centre(A->g, A->v[reps[x]], px);
        for (size_t y = x + 1; y < k; y++) {
            double py[3];
            vbc_voxel_centre(A->g, A->v[reps[y]], py);
            double d = (px[0] - py[0]) * (px[0] - py[0]) + (px[1] - py[1]) * (px[1] - py[1]) +
                       (px[2] - py[2]) * (px[2] - py[2]);
            if (d > best) {
                best = d;
                ba = reps[x];
                bb = reps[y];
            }
        }
    }
    free(reps);
    *a = ba;
    *b = bb;
    return 0;
}

/* Ends of the centreline of a component with mouths. Mouth voxels that touch
 * each other form one opening, represented by its widest voxel. The line
 * joins the widest pair of openings through the molecule (a pore: its two
 * mouths; *through = 1); failing that the two openings farthest apart, or,
 * with a single opening, the opening and the member farthest along the
 * voxels (a dead-end tunnel). Returns 0, or -1 when out of memory. */
int vbc_channel_ends(vbc_graph *A, vb_uf *uf, const uint32_t *members, size_t m, uint32_t *a,
                     uint32_t *b, int *through)
{
    if (vbc_channel_openings(A, uf, members, m, a, b, through) != 0)
        return -1;
    if (*b == UINT32_MAX) {
        vbc_sweep(A, members, m, *a, 0);
        *b = vbc_farthest(A, members, m);
    }
    return 0;
}
