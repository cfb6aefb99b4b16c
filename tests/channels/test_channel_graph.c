/* The channel analysis's voxel graph (core/discrete/channel_voxels.c,
 * channel_graph.c, channel_radix.c) against definitions written plainly
 * here: the 26-connected CSR adjacency against every neighbour looked up
 * by binary search (order, step codes, degrees; 1 and 3 threads, grids
 * one voxel thin), the radix heap's sweep against an O(m^2) Dijkstra that
 * settles in (distance, position) order (distance bits and predecessors,
 * tied clearances everywhere, and a clearance so large that steps vanish:
 * the binary heap's fallback; stopped at a target: its path), the radix sort against qsort,
 * given component labels (the device's) against the union-find's groups: accepted when
 * right, refused when one label covers two pieces, the support atoms against a scan of
 * every atom in index order, and the openings of a component against a plain union-find of
 * its mouth voxels. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_paths_math.h"
#include "synth.h"
#include "vb_test.h"
#include "vbc_radix.h"
#include "vbc_voxels.h"

/* A random voxel set of g (each voxel present with probability p), loaded
 * and linked into W. */
static void random_graph(uint64_t *seed, const vbc_grid *g, double p, analysis *W)
{
    size_t nv = vbc_grid_voxels(g), n = 0;
    uint32_t *vox = malloc((nv ? nv : 1) * sizeof *vox);
    for (size_t v = nv; v-- > 0;) /* descending: the load sorts */
        if (synth_uniform(seed) < p)
            vox[n++] = (uint32_t)v;
    memset(W, 0, sizeof *W);
    W->A.g = W->g = g;
    W->nvox = n;
    CHECK(vbc_analysis_alloc(W) == 0 && vbc_voxels_load(W, vox, NULL, NULL) == 0 &&
          vbc_voxels_link(W) == 0);
    free(vox);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Edges of W that differ from the neighbours found by binary search. */
static size_t csr_mismatches(const analysis *W)
{
    const vbc_grid *g = W->g;
    size_t bad = 0;
    for (size_t t = 0; t < W->nvox; t++) {
        uint32_t v = W->sorted[t];
        int i = (int)(v % (uint32_t)g->nx), j = (int)(v / (uint32_t)g->nx % (uint32_t)g->ny);
        int k = (int)(v / ((uint32_t)g->nx * (uint32_t)g->ny));
        size_t e = W->A.adj_start[t];
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    if (!(dx | dy | dz) || i + dx < 0 || i + dx >= g->nx || j + dy < 0 ||
                        j + dy >= g->ny || k + dz < 0 || k + dz >= g->nz)
                        continue;
                    uint32_t w = (uint32_t)((i + dx) + g->nx * ((j + dy) + g->ny * (k + dz)));
                    const uint32_t *at = bsearch(&w, W->sorted, W->nvox, sizeof w, cmp_u32);
                    if (!at)
                        continue;
                    bad += e >= W->A.adj_start[t + 1] || W->A.adj[e] != (uint32_t)(at - W->sorted) ||
                           W->A.adj_len[e] != abs(dx) + abs(dy) + abs(dz);
                    e++;
                }
        bad += e != W->A.adj_start[t + 1];
    }
    return bad;
}

/* Dijkstra by definition over component mem[0..m): settle the unsettled
 * member of least (distance, position), relax its neighbours strictly. */
static void plain_dijkstra(const analysis *W, const uint32_t *mem, size_t m, uint32_t src, int weighted,
                           double *dist, uint32_t *pred, uint8_t *done)
{
    for (size_t t = 0; t < m; t++) {
        dist[mem[t]] = INFINITY;
        pred[mem[t]] = UINT32_MAX;
        done[mem[t]] = 0;
    }
    dist[src] = 0.0;
    for (;;) {
        uint32_t u = UINT32_MAX;
        for (size_t t = 0; t < m; t++)
            if (!done[mem[t]] && dist[mem[t]] < INFINITY &&
                (u == UINT32_MAX || vbc_path_pred_before(dist[mem[t]], mem[t], dist[u], u)))
                u = mem[t];
        if (u == UINT32_MAX)
            return;
        done[u] = 1;
        for (size_t e = W->A.adj_start[u]; e < W->A.adj_start[u + 1]; e++) {
            uint32_t q = W->A.adj[e];
            double nd = dist[u] + vbc_path_step(W->A.adj_len[e], W->clear[u], W->clear[q], weighted);
            if (!done[q] && nd < dist[q]) {
                dist[q] = nd;
                pred[q] = u;
            }
        }
    }
}

/* Sweeps of every component of a random set from a random member, plain
 * and weighted, against plain_dijkstra. Clearances: `levels` values (ties),
 * or uniform doubles when levels is 0; huge puts 1e30 on one voxel. */
static void sweep_case(uint64_t *seed, int n, double p, int levels, int huge)
{
    static const double lv[4] = {1.0, 0.5, 0.05, 0.02};
    vbc_grid g = {n, n - 2, n - 4, 3, {0.0, 0.0, 0.0}, 1.0};
    analysis W;
    random_graph(seed, &g, p, &W);
    vbc_components_group(&W);
    for (size_t t = 0; t < W.nvox; t++)
        W.clear[t] = levels ? lv[(int)(synth_uniform(seed) * levels) % levels]
                            : 0.01 + 3.0 * synth_uniform(seed);
    if (huge && W.nvox)
        W.clear[W.nvox / 2] = 1e30;
    double *dist = malloc((W.nvox + 1) * sizeof *dist);
    uint32_t *pred = malloc((W.nvox + 1) * sizeof *pred);
    uint8_t *done = malloc(W.nvox + 1);
    size_t bad = 0, paths = 0;
    for (int weighted = 0; weighted <= 1; weighted++)
        for (size_t c = 0; c < W.ncomp; c++) {
            size_t m = W.cstart[c + 1] - W.cstart[c];
            const uint32_t *mem = W.order + W.cstart[c];
            uint32_t src = mem[(size_t)(synth_uniform(seed) * (double)m) % m];
            vbc_sweep(&W.A, mem, m, src, weighted);
            plain_dijkstra(&W, mem, m, src, weighted, dist, pred, done);
            for (size_t t = 0; t < m; t++)
                bad += memcmp(&dist[mem[t]], &W.A.dist[mem[t]], sizeof(double)) != 0 ||
                       pred[mem[t]] != W.A.pred[mem[t]];
            /* Stopped at a target: its path back to src is the same. */
            uint32_t to = mem[(size_t)(synth_uniform(seed) * (double)m) % m];
            vbc_sweep_to(&W.A, mem, m, src, weighted, to);
            for (uint32_t q = to; q != UINT32_MAX; q = pred[q]) {
                bad += memcmp(&dist[q], &W.A.dist[q], sizeof(double)) != 0 || pred[q] != W.A.pred[q];
                paths++;
            }
        }
    CHECK_INT(bad, 0);
    CHECK(paths > 2 * W.ncomp); /* two sweeps a component: some paths leave their source */
    free(dist);
    free(pred);
    free(done);
    vbc_analysis_free(&W);
}

/* The openings of vbc_channel_openings against their definition: mouth
 * voxels joined across every edge (a plain union-find here, each edge
 * from both ends), each opening's widest voxel (ties to the first
 * member), and with two or more openings and an atom far wider than the
 * grid (no pair is through) the farthest pair of those voxels, listed by
 * their openings' smallest members (ties to the first pair). Mouths of
 * random sets with probability pm, clearances with ties. */
static void openings_case(uint64_t *seed, int n, double p, double pm)
{
    vbc_grid g = {n, n - 1, n - 2, 3, {0.0, 0.0, 0.0}, 1.0};
    analysis W;
    random_graph(seed, &g, p, &W);
    vbc_components_group(&W);
    double x = 0.0, y = 0.0, z = 0.0, r = 1e6;
    vb_sphere_set s;
    memset(&s, 0, sizeof s);
    s.n = 1;
    s.x = &x;
    s.y = &y;
    s.z = &z;
    s.r = &r;
    W.A.s = &s;
    for (size_t t = 0; t < W.nvox; t++) {
        W.mouth[t] = synth_uniform(seed) < pm;
        W.clear[t] = 0.5 * (double)(int)(4.0 * synth_uniform(seed));
    }
    uint32_t *P = malloc((W.nvox + 1) * sizeof *P), *rep = malloc((W.nvox + 1) * sizeof *rep);
    uint32_t *reps = malloc((W.nvox + 1) * sizeof *reps);
    vb_uf uf = {P, W.nvox, 0};
    size_t bad = 0, multi = 0;
    for (size_t c = 0; c < W.ncomp; c++) {
        size_t m = W.cstart[c + 1] - W.cstart[c], k = 0;
        const uint32_t *mem = W.order + W.cstart[c];
        for (size_t t = 0; t < m; t++)
            P[mem[t]] = mem[t];
        for (size_t t = 0; t < m; t++)
            for (size_t e = W.A.adj_start[mem[t]]; e < W.A.adj_start[mem[t] + 1]; e++)
                if (W.mouth[mem[t]] && W.mouth[W.A.adj[e]])
                    vb_uf_join(&uf, mem[t], W.A.adj[e]);
        for (size_t t = 0; t < m; t++) {
            uint32_t u = mem[t], ru = vb_uf_root(&uf, u);
            if (!W.mouth[u])
                continue;
            if (ru == u)
                rep[ru] = u;
            else if (W.clear[u] > W.clear[rep[ru]])
                rep[ru] = u;
        }
        for (size_t t = 0; t < m; t++)
            if (W.mouth[mem[t]] && P[mem[t]] == mem[t])
                reps[k++] = rep[mem[t]];
        uint32_t wa = k ? reps[0] : mem[0], wb = UINT32_MAX;
        double best = -1.0;
        for (size_t i = 0; k >= 2 && i < k; i++)
            for (size_t j = i + 1; j < k; j++) {
                double pi[3], pj[3];
                vbc_voxel_centre(&g, W.sorted[reps[i]], pi);
                vbc_voxel_centre(&g, W.sorted[reps[j]], pj);
                double d = (pi[0] - pj[0]) * (pi[0] - pj[0]) + (pi[1] - pj[1]) * (pi[1] - pj[1]) +
                           (pi[2] - pj[2]) * (pi[2] - pj[2]);
                if (d > best) {
                    best = d;
                    wa = reps[i];
                    wb = reps[j];
                }
            }
        multi += k >= 2;
        uint32_t a = 0, b = 0;
        int through = 1;
        CHECK_INT(vbc_channel_openings(&W.A, &W.uf, mem, m, &a, &b, &through), 0);
        bad += a != wa || b != wb || through != 0;
    }
    CHECK_INT(bad, 0);
    CHECK(multi >= 1); /* a component with several openings */
    free(P);
    free(rep);
    free(reps);
    vbc_analysis_free(&W);
}

typedef struct {
    double c;
    uint32_t pos;
} by_clear;

static int cmp_by_clear(const void *x, const void *y)
{
    const by_clear *a = x, *b = y;
    if (a->c != b->c)
        return a->c < b->c ? 1 : -1;
    return (a->pos > b->pos) - (a->pos < b->pos);
}

/* vbc_radix_desc keys sorted with positions (ascending on entry) against
 * qsort by (value descending, position ascending). */
static void radix_case(uint64_t *seed, size_t n)
{
    static const double odd[6] = {0.0, -0.0, 1.5, -2.25, 1e-300, INFINITY};
    uint64_t *key = malloc(2 * n * sizeof *key);
    uint32_t *val = malloc(2 * n * sizeof *val);
    by_clear *S = malloc(n * sizeof *S);
    for (size_t t = 0; t < n; t++) {
        double u = synth_uniform(seed);
        S[t].c = u < 0.3 ? odd[(size_t)(u * 20.0) % 6] : u < 0.6 ? (double)(float)(u * 7.0 - 3.0) : u;
        S[t].pos = (uint32_t)(3 * t + 1);
        key[t] = vbc_radix_desc(S[t].c);
        val[t] = S[t].pos;
    }
    vbc_radix_sort(key, val, key + n, val + n, n, 0);
    qsort(S, n, sizeof *S, cmp_by_clear);
    size_t bad = 0;
    for (size_t t = 0; t < n; t++)
        bad += val[t] != S[t].pos;
    CHECK_INT(bad, 0);
    free(key);
    free(val);
    free(S);
}

/* Labels as the device gives them (each voxel's smallest voxel index in its
 * component) on a random set: accepted, the union-find's groups. Then
 * refused, with the union-find's groups used, when (1) the members of one
 * component carry another's label whose smallest voxel is smaller (every
 * check of a voxel and of an edge passes, only the groups' connectivity
 * fails), or (2) one voxel with a smaller neighbour does (the edge check
 * fails; the descent to smaller neighbours alone would see a connected
 * group). Returns the components. */
static size_t labels_case(uint64_t *seed, int n, double p)
{
    vbc_grid g = {n, n - 1, n - 2, 3, {0.0, 0.0, 0.0}, 1.0};
    analysis H;
    random_graph(seed, &g, p, &H);
    vbc_components_group(&H);
    uint32_t *lab = malloc((H.nvox ? H.nvox : 1) * sizeof *lab);
    for (size_t c = 0; c < H.ncomp; c++)
        for (size_t t = H.cstart[c]; t < H.cstart[c + 1]; t++)
            lab[H.order[t]] = H.sorted[H.order[H.cstart[c]]];
    for (int spoil = 0; spoil <= 2 && H.ncomp >= 2; spoil++) {
        /* A later component (with a member past its first, for case 2). */
        size_t cb = H.ncomp, ca = 0, from = 0;
        for (int tries = 0; tries < 100 && cb == H.ncomp; tries++) {
            cb = 1 + (size_t)(synth_uniform(seed) * (double)(H.ncomp - 1)) % (H.ncomp - 1);
            if (H.cstart[cb + 1] - H.cstart[cb] < 2)
                cb = H.ncomp;
        }
        CHECK(cb < H.ncomp);
        if (cb == H.ncomp)
            break;
        ca = (size_t)(synth_uniform(seed) * (double)cb) % cb;
        from = spoil == 1 ? H.cstart[cb] : H.cstart[cb + 1] - 1;
        for (size_t t = from; spoil && t < H.cstart[cb + 1]; t++)
            lab[H.order[t]] = H.sorted[H.order[H.cstart[ca]]];
        analysis W;
        memset(&W, 0, sizeof W);
        W.A.g = W.g = &g;
        W.nvox = H.nvox;
        CHECK(vbc_analysis_alloc(&W) == 0 && vbc_voxels_load(&W, H.sorted, NULL, lab) == 0 &&
              vbc_voxels_link(&W) == 0);
        vbc_components_given(&W);
        CHECK_INT(W.comp_bad, spoil != 0);
        CHECK_INT(W.ncomp, H.ncomp);
        size_t bad = 0;
        for (size_t t = 0; t < H.nvox && W.ncomp == H.ncomp; t++)
            bad += W.order[t] != H.order[t];
        for (size_t c = 0; c <= H.ncomp && W.ncomp == H.ncomp; c++)
            bad += W.cstart[c] != H.cstart[c];
        CHECK_INT(bad, 0);
        vbc_analysis_free(&W);
        for (size_t t = from; spoil && t < H.cstart[cb + 1]; t++)
            lab[H.order[t]] = H.sorted[H.order[H.cstart[cb]]];
    }
    size_t ncomp = H.ncomp;
    free(lab);
    vbc_analysis_free(&H);
    return ncomp;
}

/* The support atoms of vbc_graph_support against their definition: per
 * direction of the same Fibonacci sphere, the first atom in index order of
 * least c - r and of greatest c + r. Spheres: shape 0 a ball, 1 a rod, 2
 * a lattice of equal radii (ties everywhere), 3 a ball with each atom
 * written twice (ties of equal atoms), 4 far from the origin. */
static void support_case(uint64_t *seed, size_t n, int shape)
{
    vb_sphere_set s;
    memset(&s, 0, sizeof s);
    s.n = shape == 3 ? 2 * n : n;
    s.x = malloc((s.n + 1) * sizeof *s.x);
    s.y = malloc((s.n + 1) * sizeof *s.y);
    s.z = malloc((s.n + 1) * sizeof *s.z);
    s.r = malloc((s.n + 1) * sizeof *s.r);
    for (size_t i = 0; i < n; i++) {
        double x = synth_uniform(seed) - 0.5, y = synth_uniform(seed) - 0.5, z = synth_uniform(seed) - 0.5;
        if (shape == 2) {
            x = (double)(i % 7);
            y = (double)(i / 7 % 7);
            z = (double)(i / 49);
        }
        s.x[i] = 30.0 * x * (shape == 1 ? 8.0 : 1.0) + (shape == 4 ? 5e3 : 0.0);
        s.y[i] = 30.0 * y;
        s.z[i] = 30.0 * z - (shape == 4 ? 7e3 : 0.0);
        s.r[i] = shape == 2 ? 1.5 : 1.2 + 0.6 * synth_uniform(seed);
        if (shape == 3) {
            s.x[n + i] = s.x[i];
            s.y[n + i] = s.y[i];
            s.z[n + i] = s.z[i];
            s.r[n + i] = s.r[i];
        }
    }
    vbc_graph A;
    memset(&A, 0, sizeof A);
    A.s = &s;
    CHECK_INT(vbc_graph_support(&A), 0);
    CHECK_INT(A.nsupport, 128);
    size_t bad = 0;
    for (int d = 0; d < 64 && A.support; d++) {
        double z = 1.0 - (2.0 * d + 1.0) / 64, r = sqrt(1.0 - z * z);
        double u[3] = {r * cos(2.39996322972865332 * d), r * sin(2.39996322972865332 * d), z};
        int32_t lo = 0, hi = 0;
        double vlo = INFINITY, vhi = -INFINITY;
        for (size_t i = 0; i < s.n; i++) {
            double c = s.x[i] * u[0] + s.y[i] * u[1] + s.z[i] * u[2];
            if (c - s.r[i] < vlo) {
                vlo = c - s.r[i];
                lo = (int32_t)i;
            }
            if (c + s.r[i] > vhi) {
                vhi = c + s.r[i];
                hi = (int32_t)i;
            }
        }
        bad += A.support[2 * d] != lo || A.support[2 * d + 1] != hi;
    }
    CHECK_INT(bad, 0);
    free(A.support);
    free(s.x);
    free(s.y);
    free(s.z);
    free(s.r);
}

int main(void)
{
    uint64_t seed = 20261206;
    static const int dims[5][3] = {{9, 7, 5}, {1, 6, 6}, {6, 1, 6}, {6, 6, 1}, {17, 13, 11}};
    for (int threads = 1; threads <= 3; threads += 2) {
        setenv("VORBALL_THREADS", threads == 1 ? "1" : "3", 1);
        for (int d = 0; d < 5; d++)
            for (int r = 0; r < 3; r++) {
                vbc_grid g = {dims[d][0], dims[d][1], dims[d][2], 3, {0.0, 0.0, 0.0}, 1.0};
                analysis W;
                random_graph(&seed, &g, 0.2 + 0.3 * r, &W);
                CHECK_INT(csr_mismatches(&W), 0);
                vbc_analysis_free(&W);
            }
    }
    /* Big enough for several link slices (4096 voxels each) on 3 threads. */
    vbc_grid big = {48, 40, 36, 3, {0.0, 0.0, 0.0}, 1.0};
    analysis W;
    random_graph(&seed, &big, 0.5, &W);
    CHECK(W.nvox > 3 * 4096);
    CHECK_INT(csr_mismatches(&W), 0);
    vbc_analysis_free(&W);
    for (int r = 0; r < 4; r++) {
        sweep_case(&seed, 14, 0.45, 4, 0);
        sweep_case(&seed, 14, 0.55, 2, 0);
        sweep_case(&seed, 12, 0.5, 0, 0);
        sweep_case(&seed, 12, 0.6, 4, 1);
    }
    /* Sparse sets (many small components), dense ones (large components
     * shaped with dips, which the breadth-first walk checks). */
    static const double dens[6] = {0.03, 0.05, 0.08, 0.12, 0.2, 0.25};
    size_t comps = 0;
    for (int r = 0; r < 6; r++) {
        size_t c = labels_case(&seed, 14, dens[r]);
        CHECK(c >= 2);
        comps += c;
    }
    CHECK(comps > 100);
    static const size_t sizes[4] = {0, 1, 343, 4000};
    for (int shape = 0; shape < 5; shape++)
        for (int k = 0; k < 4; k++)
            support_case(&seed, sizes[k], shape);
    radix_case(&seed, 1);
    radix_case(&seed, 5000);
    for (int r = 0; r < 4; r++) {
        openings_case(&seed, 14, 0.5, 0.3);
        openings_case(&seed, 16, 0.35, 0.6);
    }
    VB_TEST_END();
}
