/* The exact reference: every vertex of the diagram, from all quadruples.
 *
 * Correctness argument. A vertex with member set S (rank 3, see below) is a
 * root of the squared system of its canonical quadruple Q(S), the
 * lexicographically first 4-subset of S whose line meets the cone in at
 * most two points (vbx_cert_canonical): that line passes through the
 * vertex. We enumerate every sorted quadruple a<b<c<d with base a and rows
 * (b, c, d), which includes Q(S), except those containing a pair that
 * provably shares no vertex (burial.c). A quadruple is skipped only when the
 * interval filter PROVES, for each root of its squared system, that the root
 * is not an outer tangent sphere (s < 0 or s + r_i < 0) or that a sphere j
 * outside the quadruple intrudes (|p - c_j| < t + R_j); neither holds at a
 * vertex, so the canonical quadruple of every vertex survives. Survivors go
 * to the exact path (vbx_solve, vbx_cert_defining, vbx_cert_scan), and a
 * certified root is emitted only by its canonical quadruple, so each exact
 * vertex appears once with all its members.
 *
 * Not covered: a vertex whose members' rows have rank < 3 (centres and radii
 * in a degenerate family: such a set has a positive-dimensional family of
 * tangent spheres in general and an isolated point only when a conic
 * degenerates, which needs nested spheres that touch), or none of whose
 * 4-subsets has finitely many tangent spheres. */
#include <stdlib.h>
#include <string.h>

#include "vbx_burial.h"
#include "vbx_cert.h"
#include "vb_diag.h"

/* Neighbours tried first as intruders: the nearest few of the base sphere. */
#define VBX_NEAR_K 12

typedef struct ref_state {
    vb_ctx *ctx;
    vb_certifier *c;
    size_t n;
    vbx_ia *m;           /* n x 5 rows relative to the current base: dx, dy, dz, r, W/2 */
    double *mid;         /* n x 5 midpoints of m (approximate search only) */
    uint32_t *near;      /* n x VBX_NEAR_K nearest spheres (by centre distance) */
    uint32_t cache[2];   /* last intruder that proved a root, per root side */
    uint64_t *pairs;     /* n x n bits: 1 = the pair may share a vertex */
    vb_vertex_list *out;
} ref_state;

/* Rows relative to base a, as intervals. */
static void base_rows(ref_state *rs, uint32_t a)
{
    const vbx_ia *box = rs->c->d.box;
    const vbx_ia half = vbx_ia_point(0.5);
    for (size_t j = 0; j < rs->n; j++) {
        vbx_ia *m = &rs->m[5 * j];
        for (int k = 0; k < 4; k++)
            m[k] = vbx_ia_sub(box[4 * j + k], box[4 * (size_t)a + k]);
        vbx_ia w = vbx_ia_add(vbx_ia_sqr(m[0]), vbx_ia_sqr(m[1]));
        w = vbx_ia_add(w, vbx_ia_sqr(m[2]));
        w = vbx_ia_sub(w, vbx_ia_sqr(m[3]));
        m[4] = vbx_ia_mul(w, half);
        for (int k = 0; k < 5; k++)
            rs->mid[5 * j + k] = vbx_ia_mid(m[k]);
    }
}

/* The line of quadruple (a, b, c, d) as u = (U + mu v) / D in u = (q, s),
 * s = t + R_a (as in tangent_solver.c, with the right-hand side W/2): v is
 * the kernel of the rows, D = +-v_k its non-zero entry, U solves the rows
 * with u_k = 0. Roots mu of A mu^2 + 2 B mu + C = 0, A = Q(v), B = Q(U, v),
 * C = Q(U), and the enclosure of s at each root. */
typedef struct quad_line {
    vbx_ia D, U[4], v[4];
    vbx_ia mu[2], s[2];
    int nroots; /* 0: proven no root; 2: two enclosures (may coincide) */
} quad_line;

/* 3x3 minor of rows (b, c, d) over columns i < j < k, expanded along row d
 * with the 2x2 minors pbc[ij] of rows (b, c). */
static inline vbx_ia minor3(const vbx_ia *md, const vbx_ia pbc[5][5], int i, int j, int k)
{
    vbx_ia r = vbx_ia_mul(md[i], pbc[j][k]);
    r = vbx_ia_sub(r, vbx_ia_mul(md[j], pbc[i][k]));
    return vbx_ia_add(r, vbx_ia_mul(md[k], pbc[i][j]));
}

static inline vbx_ia lorentz(const vbx_ia x[4], const vbx_ia y[4])
{
    vbx_ia r = vbx_ia_add(vbx_ia_mul(x[0], y[0]), vbx_ia_mul(x[1], y[1]));
    r = vbx_ia_add(r, vbx_ia_mul(x[2], y[2]));
    return vbx_ia_sub(r, vbx_ia_mul(x[3], y[3]));
}

/* Returns 0 when the filter cannot set the line up (no minor or A provably
 * non-zero): the quadruple then goes to the exact path. */
static int quad_setup(const vbx_ia *md, const vbx_ia pbc[5][5], quad_line *L)
{
    static const int cols[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    /* Kernel v_k = (-1)^k D_k; the free unknown is s (k = 3) when its minor
     * is provably non-zero, else the first coordinate whose minor is. */
    int k = -1;
    for (int i = 3; i >= 0; i--) {
        vbx_ia Dk = minor3(md, pbc, cols[i][0], cols[i][1], cols[i][2]);
        L->v[i] = (i & 1) ? vbx_ia_neg(Dk) : Dk;
        if (k < 0 && vbx_ia_sign(Dk) != 0) {
            k = i;
            L->D = Dk;
        }
    }
    if (k < 0)
        return 0;
    /* Cramer with u_k = 0: column c_p of the minor replaced by W/2 (column 4)
     * and moved last, (2 - p) transpositions. */
    L->U[k] = vbx_ia_point(0.0);
    for (int p = 0; p < 3; p++) {
        int rest[2], r = 0;
        for (int q = 0; q < 3; q++)
            if (q != p)
                rest[r++] = cols[k][q];
        vbx_ia m = minor3(md, pbc, rest[0], rest[1], 4);
        L->U[cols[k][p]] = (p & 1) ? vbx_ia_neg(m) : m;
    }
    vbx_ia A = lorentz(L->v, L->v);
    if (vbx_ia_sign(A) == 0)
        return 0;
    vbx_ia B = lorentz(L->U, L->v), C = lorentz(L->U, L->U);
    vbx_ia delta = vbx_ia_sub(vbx_ia_sqr(B), vbx_ia_mul(A, C));
    if (delta.hi < 0.0) {
        L->nroots = 0;
        return 1;
    }
    /* sqrt of [max(lo, 0), hi] encloses sqrt(delta) whenever delta >= 0. */
    vbx_ia sq = vbx_ia_sqrt(delta);
    vbx_ia nb = vbx_ia_neg(B);
    L->mu[0] = vbx_ia_div(vbx_ia_add(nb, sq), A);
    L->mu[1] = vbx_ia_div(vbx_ia_sub(nb, sq), A);
    for (int r = 0; r < 2; r++)
        L->s[r] = vbx_ia_div(vbx_ia_add(L->U[3], vbx_ia_mul(L->mu[r], L->v[3])), L->D);
    L->nroots = 2;
    return 1;
}

/* Does sphere j provably intrude the tangent sphere at root r of L?
 * On the cone F_j = |p - c_j|^2 - (t + R_j)^2 = 2 (W_j/2 - m_j . u), and
 * D (W_j/2 - m_j . u) = G_j = (W_j/2) D - m_j . U - mu (m_j . v);
 * intrusion needs F_j < 0 and t + R_j = s + r_j > 0. */
static int proves_intrusion(const ref_state *rs, const quad_line *L, int r, uint32_t j)
{
    const vbx_ia *mj = &rs->m[5 * (size_t)j];
    if (!(vbx_ia_add(L->s[r], mj[3]).lo > 0.0))
        return 0;
    vbx_ia mu = vbx_ia_add(vbx_ia_mul(mj[0], L->U[0]), vbx_ia_mul(mj[1], L->U[1]));
    mu = vbx_ia_add(mu, vbx_ia_add(vbx_ia_mul(mj[2], L->U[2]), vbx_ia_mul(mj[3], L->U[3])));
    vbx_ia mv = vbx_ia_add(vbx_ia_mul(mj[0], L->v[0]), vbx_ia_mul(mj[1], L->v[1]));
    mv = vbx_ia_add(mv, vbx_ia_add(vbx_ia_mul(mj[2], L->v[2]), vbx_ia_mul(mj[3], L->v[3])));
    vbx_ia G = vbx_ia_sub(vbx_ia_sub(vbx_ia_mul(mj[4], L->D), mu), vbx_ia_mul(L->mu[r], mv));
    return vbx_ia_sign(G) * vbx_ia_sign(L->D) < 0;
}

/* Cheap guess in double: is j likely inside the tangent sphere at (q, s)? */
static int looks_inside(const ref_state *rs, const double q[3], double s, uint32_t j)
{
    const double *mj = &rs->mid[5 * (size_t)j];
    double sr = s + mj[3];
    if (!(sr > 0.0))
        return 0;
    double f = mj[4] - (mj[0] * q[0] + mj[1] * q[1] + mj[2] * q[2]) - mj[3] * s;
    return f < 0.0;
}

/* Tries to prove that root k of L is no vertex. */
static int root_refuted(ref_state *rs, const quad_line *L, int k, const uint32_t quad[4])
{
    vbx_ia S = L->s[k];
    vb_stats *st = vb_ctx_stats(rs->ctx);
    st->filter_calls++;
    /* Not an outer tangent sphere: s = t + R_a < 0 or s + r_i < 0. */
    if (S.hi < 0.0)
        return 1;
    for (int i = 1; i < 4; i++)
        if (vbx_ia_add(S, rs->m[5 * (size_t)quad[i] + 3]).hi < 0.0)
            return 1;
    double s = vbx_ia_mid(S), D = vbx_ia_mid(L->D), mu = vbx_ia_mid(L->mu[k]), q[3];
    for (int i = 0; i < 3; i++)
        q[i] = (vbx_ia_mid(L->U[i]) + mu * vbx_ia_mid(L->v[i])) / D;
    uint32_t j = rs->cache[k];
    if (j != quad[0] && j != quad[1] && j != quad[2] && j != quad[3] && j < rs->n &&
        proves_intrusion(rs, L, k, j))
        return 1;
    for (int w = 0; w < 4; w += 3) {
        const uint32_t *nb = &rs->near[VBX_NEAR_K * (size_t)quad[w]];
        for (int i = 0; i < VBX_NEAR_K; i++) {
            j = nb[i];
            if (j == UINT32_MAX)
                break;
            if (j == quad[0] || j == quad[1] || j == quad[2] || j == quad[3])
                continue;
            if (looks_inside(rs, q, s, j) && proves_intrusion(rs, L, k, j)) {
                rs->cache[k] = j;
                return 1;
            }
        }
    }
    /* Last resort: every sphere, cheap guess first. */
    for (j = 0; j < rs->n; j++) {
        if (j == quad[0] || j == quad[1] || j == quad[2] || j == quad[3])
            continue;
        if (looks_inside(rs, q, s, j) && proves_intrusion(rs, L, k, j)) {
            rs->cache[k] = j;
            return 1;
        }
    }
    st->filter_failures++;
    return 0;
}

/* Exact path for one quadruple: emit the certified roots it owns. */
static int quad_exact(ref_state *rs, const uint32_t quad[4])
{
    vb_certifier *c = rs->c;
    vb_ctx *ctx = rs->ctx;
    vb_stats *st = vb_ctx_stats(ctx);
    st->exact_evals++;
    if (vbx_solve(&c->sol, quad[0], quad + 1) != VBX_SOLVED)
        return VB_OK; /* never canonical (singular, or a line of solutions) */
    for (int r = 0; r < c->sol.nroots; r++) {
        const vbx_root *root = &c->sol.root[r];
        double xyzt[4];
        vbx_ia box[4];
        int rc = vbx_cert_round(ctx, c, root, xyzt, box);
        if (rc != VB_OK)
            return rc;
        if (!vbx_cert_defining(ctx, c, root, quad, 4, box))
            continue;
        int verdict;
        uint32_t intruder;
        vbx_cert_scan(ctx, c, root, quad, 4, box, &verdict, &intruder);
        if (verdict != VB_CERT_OK)
            continue;
        int ours;
        if (!vbx_cert_canonical(c, &ours) || !ours)
            continue; /* found again, and emitted, by its canonical quadruple */
        st->certified++;
        rc = vb_vertex_list_push(rs->out, c->members, c->nmembers, xyzt[0], xyzt[1], xyzt[2],
                                 xyzt[3], 0.0, VB_VERTEX_CERTIFIED);
        if (rc != VB_OK)
            return vb_error(ctx, rc, NULL, 0, "out of memory (reference vertices)");
    }
    return VB_OK;
}

/* K nearest spheres of each sphere by centre distance (a heuristic order for
 * the intruder search; correctness never depends on it). */
static void nearest_lists(ref_state *rs)
{
    const double *nr = rs->c->d.near;
    double best[VBX_NEAR_K];
    for (size_t i = 0; i < rs->n; i++) {
        uint32_t *nb = &rs->near[VBX_NEAR_K * i];
        int cnt = 0;
        for (size_t j = 0; j < rs->n; j++) {
            if (j == i)
                continue;
            double dx = nr[4 * j] - nr[4 * i], dy = nr[4 * j + 1] - nr[4 * i + 1],
                   dz = nr[4 * j + 2] - nr[4 * i + 2];
            double d = dx * dx + dy * dy + dz * dz;
            if (cnt == VBX_NEAR_K && !(d < best[cnt - 1]))
                continue;
            int p = cnt < VBX_NEAR_K ? cnt++ : cnt - 1;
            while (p > 0 && best[p - 1] > d) {
                best[p] = best[p - 1];
                nb[p] = nb[p - 1];
                p--;
            }
            best[p] = d;
            nb[p] = (uint32_t)j;
        }
        for (int k = cnt; k < VBX_NEAR_K; k++)
            nb[k] = UINT32_MAX;
    }
}

static inline int pair_ok(const ref_state *rs, uint32_t x, uint32_t y)
{
    size_t k = (size_t)x * rs->n + y;
    return (int)((rs->pairs[k >> 6] >> (k & 63)) & 1u);
}

/* Marks the pairs that may share a vertex: for each sphere buried at T_x,
 * only those with |c_x - c_y| < 2 T_x + R_x + R_y (burial.c); a pair is
 * dropped only when interval arithmetic proves it too far apart. */
static int pair_table(ref_state *rs)
{
    size_t n = rs->n, words = (n * n + 63) / 64;
    double *T = malloc((n ? n : 1) * sizeof *T);
    rs->pairs = malloc((words ? words : 1) * sizeof *rs->pairs);
    if (!T || !rs->pairs) {
        free(T);
        return VB_ENOMEM;
    }
    int rc = vbx_burial_bounds(&rs->c->d, T);
    if (rc != VB_OK) {
        free(T);
        return rc;
    }
    const vbx_ia *box = rs->c->d.box;
    for (size_t w = 0; w < words; w++)
        rs->pairs[w] = 0;
    for (size_t x = 0; x < n; x++)
        for (size_t y = 0; y < n; y++) {
            int ok = 1;
            if (T[x] < INFINITY) {
                vbx_ia d2 = vbx_ia_sqr(vbx_ia_sub(box[4 * x], box[4 * y]));
                d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[4 * x + 1], box[4 * y + 1])));
                d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[4 * x + 2], box[4 * y + 2])));
                vbx_ia lim = vbx_ia_add(vbx_ia_mul(vbx_ia_point(2.0), vbx_ia_point(T[x])),
                                        vbx_ia_add(box[4 * x + 3], box[4 * y + 3]));
                ok = !(vbx_ia_sqrt(d2).lo >= lim.hi);
            }
            if (ok)
                continue;
            /* Either sphere's bound excludes the pair: clear both orders. */
            size_t k1 = x * n + y, k2 = y * n + x;
            rs->pairs[k1 >> 6] |= (uint64_t)1 << (k1 & 63);
            rs->pairs[k2 >> 6] |= (uint64_t)1 << (k2 & 63);
        }
    /* Bits set so far mark excluded pairs; flip to "may share". */
    for (size_t w = 0; w < words; w++)
        rs->pairs[w] = ~rs->pairs[w];
    free(T);
    return VB_OK;
}

static int run(ref_state *rs)
{
    size_t n = rs->n;
    vb_stats *st = vb_ctx_stats(rs->ctx);
    vbx_ia pbc[5][5];
    /* Progress in quadruples: those with first index a number C(n-a-1, 3). */
    uint64_t quads = n >= 4 ? (uint64_t)n * (n - 1) / 2 * (n - 2) / 3 * (n - 3) / 4 : 0, done = 0;
    vb_progress(rs->ctx, "reference", 0, quads);
    for (uint32_t a = 0; a + 3 < n; a++) {
        if (a > 0) {
            uint64_t r = n - a;   /* C(r, 3) quadruples began at a - 1 */
            done += r * (r - 1) / 2 * (r - 2) / 3;
            vb_progress(rs->ctx, "reference", done, quads);
        }
        base_rows(rs, a);
        for (uint32_t b = a + 1; b + 2 < n; b++) {
            if (!pair_ok(rs, a, b))
                continue;
            const vbx_ia *mb = &rs->m[5 * (size_t)b];
            for (uint32_t c = b + 1; c + 1 < n; c++) {
                if (!pair_ok(rs, a, c) || !pair_ok(rs, b, c))
                    continue;
                const vbx_ia *mc = &rs->m[5 * (size_t)c];
                for (int i = 0; i < 5; i++)
                    for (int j = i + 1; j < 5; j++)
                        pbc[i][j] = vbx_ia_sub(vbx_ia_mul(mb[i], mc[j]), vbx_ia_mul(mb[j], mc[i]));
                for (uint32_t d = c + 1; d < n; d++) {
                    if (!pair_ok(rs, a, d) || !pair_ok(rs, b, d) || !pair_ok(rs, c, d))
                        continue;
                    uint32_t quad[4] = {a, b, c, d};
                    st->candidates++;
                    quad_line L;
                    int refuted = 0;
                    if (quad_setup(&rs->m[5 * (size_t)d], pbc, &L)) {
                        refuted = 1;
                        for (int k = 0; k < L.nroots && refuted; k++)
                            refuted = root_refuted(rs, &L, k, quad);
                    } else {
                        st->filter_calls++;
                        st->filter_failures++;
                    }
                    if (refuted) {
                        st->rejected++;
                        continue;
                    }
                    int rc = quad_exact(rs, quad);
                    if (rc != VB_OK)
                        return rc;
                }
            }
        }
    }
    vb_progress(rs->ctx, "reference", quads, quads);
    return VB_OK;
}

int vb_reference(vb_ctx *ctx, const vb_sphere_set *set, vb_vertex_list *out)
{
    vb_certifier *c;
    int rc = vb_certifier_open(ctx, set, &c);
    if (rc != VB_OK)
        return rc;
    ref_state rs = {ctx, c, set->n, NULL, NULL, NULL, {UINT32_MAX, UINT32_MAX}, NULL, out};
    if (set->n > VB_REFERENCE_MAX_SPHERES)
        vb_warn(ctx, VB_W_REFERENCE_SLOW, set->source, 0,
                "exact reference on %zu spheres: the enumeration grows as n^4 and may "
                "take very long",
                set->n);
    size_t n1 = set->n ? set->n : 1;
    rs.m = malloc(5 * n1 * sizeof *rs.m);
    rs.mid = malloc(5 * n1 * sizeof *rs.mid);
    rs.near = malloc(VBX_NEAR_K * n1 * sizeof *rs.near);
    if (!rs.m || !rs.mid || !rs.near) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (reference)");
    } else if ((rc = pair_table(&rs)) != VB_OK) {
        rc = vb_error(ctx, rc, NULL, 0, "out of memory (reference pair table)");
    } else {
        nearest_lists(&rs);
        rc = run(&rs);
    }
    if (rc == VB_OK && vb_vertex_list_sort(out) != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (sorting vertices)");
    free(rs.m);
    free(rs.mid);
    free(rs.near);
    free(rs.pairs);
    vb_certifier_close(c);
    return rc;
}

int vb_reference_run(vb_ctx *ctx, const vb_sphere_set *set, int force, const char *name,
                     vb_vertex_list *out)
{
    if (set->n > VB_REFERENCE_MAX_SPHERES && !force)
        return vb_error(ctx, VB_EINPUT_REFERENCE_SIZE, name, 0,
                        "%zu spheres: the exact reference takes at most %d without --force (its "
                        "time grows as n^2.7 to n^4; `vorball vertices` is the pipeline for "
                        "large inputs)",
                        set->n, VB_REFERENCE_MAX_SPHERES);
    return vb_reference(ctx, set, out);
}
