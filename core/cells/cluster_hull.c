/* A tie cluster of affine rank 3 (vbq_cluster.h): the owned labels' points
 * p_j in R^4 (cover_cluster.c) lie on an affine 3-space P but on no plane,
 * as spheres tangent to one sphere with unequal radii do (cospherical-78-
 * unequal: 77 labels of one cell, whose C(77, 3) quadruples all solve to
 * the one vertex of degree 78).
 *
 * Why the facets suffice. As in cover_cluster.c, the members M of a vertex
 * w of cell i with smallest member i are the owned labels tied at the
 * largest value of f at w, and for fixed u the labels that maximise the
 * affine function p -> p . (u, 1) on P form a face of the polytope
 * conv{p_j}: a vertex, an edge, a facet or all of it. Where a vertex's or
 * an edge's labels tie at the top, (u, 1) is orthogonal to at most one
 * direction of P, a set of directions without isolated points, so no
 * vertex of the cell lies there. So M is a facet or all of P, and w is a
 * root of the quadruple of i and any three affinely independent labels of
 * a facet (with M all of P, of any facet: every label ties at w). Writing
 * the quadruple of every triple that spans a supporting plane of the
 * points in P (all the points on one side of it, ties allowed) therefore
 * writes a root of every vertex the leaf can have; the certifier finds
 * all its members and refutes the rest.
 *
 * The tests, exact in checked 128-bit integers (0, "not decided", on any
 * overflow: the leaf is enumerated as before). V_j = (D_j, Delta_j, N_j) is
 * a positive multiple of (p_j, 1). Rank exactly 4: a normal h != 0 with
 * h . V_j = 0 for every label (h the generalised cross product of four
 * independent V's). Dropping a column g with h_g != 0 is injective on h's
 * orthogonal complement, so with W_j the other four columns the sign of
 * det[W_a; W_b; W_c; W_m] = W_m . K (K the cofactors of W_a, W_b, W_c) is
 * the side of p_m of the plane through p_a, p_b, p_c in P (the positive
 * multiples keep the sign), and K != 0 iff the three are independent. */
#include <stdlib.h>

#include "vb_array.h"
#include "vbq_cluster.h"

/* The 3x3 determinant of rows r[0..3) on columns c[0..3); 0 on overflow. */
static int det3(const vbq_i128 *const r[3], const int c[3], vbq_i128 *out)
{
    vbq_i128 m[3], t, u, acc = 0;
    /* the 2x2 minors of rows 1, 2 on the column pairs (1,2), (0,2), (0,1) */
    const int p[3][2] = {{1, 2}, {0, 2}, {0, 1}};
    for (int a = 0; a < 3; a++)
        if (!vbq_cmul(r[1][c[p[a][0]]], r[2][c[p[a][1]]], &t) ||
            !vbq_cmul(r[1][c[p[a][1]]], r[2][c[p[a][0]]], &u) || !vbq_csub(t, u, &m[a]))
            return 0;
    for (int a = 0; a < 3; a++) {
        if (!vbq_cmul(r[0][c[a]], m[a], &t))
            return 0;
        if (!(a == 1 ? vbq_csub(acc, t, &acc) : vbq_cadd(acc, t, &acc)))
            return 0;
    }
    *out = acc;
    return 1;
}

/* The cofactors K of rows a, b, c on the four columns c4: det[w; a; b; c]
 * = sum_x w[c4[x]] K[x]. 0 on overflow. */
static int cof3(const vbq_i128 *a, const vbq_i128 *b, const vbq_i128 *c, const int c4[4],
                vbq_i128 K[4])
{
    const vbq_i128 *const r[3] = {a, b, c};
    for (int x = 0; x < 4; x++) {
        int cc[3], m = 0;
        for (int y = 0; y < 4; y++)
            if (y != x)
                cc[m++] = c4[y];
        vbq_i128 d;
        if (!det3(r, cc, &d))
            return 0;
        K[x] = x & 1 ? -d : d;
    }
    return 1;
}

/* w . K over the columns c4 (nc of them); 0 on overflow. */
static int dotc(const vbq_i128 *w, const vbq_i128 *K, const int *c4, int nc, vbq_i128 *out)
{
    vbq_i128 acc = 0, t;
    for (int x = 0; x < nc; x++)
        if (!vbq_cmul(w[c4[x]], K[x], &t) || !vbq_cadd(acc, t, &acc))
            return 0;
    *out = acc;
    return 1;
}

/* The normal h of the span of four rows (h_g = (-1)^g det4 without column
 * g); 0 on overflow. */
static int normal4(const vbq_i128 *b0, const vbq_i128 *b1, const vbq_i128 *b2,
                   const vbq_i128 *v, vbq_i128 h[5])
{
    for (int g = 0; g < 5; g++) {
        int c4[4], m = 0;
        for (int y = 0; y < 5; y++)
            if (y != g)
                c4[m++] = y;
        vbq_i128 K[4], d;
        if (!cof3(b0, b1, b2, c4, K) || !dotc(v, K, c4, 4, &d))
            return 0;
        h[g] = g & 1 ? -d : d;
    }
    return 1;
}

/* Is v independent of rows b[0 .. nb) (nb <= 2)? Some 2x2 / 3x3 minor of
 * the rows and v non-zero. -1 on overflow. */
static int indep(const vbq_i128 *const b[2], int nb, const vbq_i128 *v)
{
    for (int a = 0; a < 5; a++)
        for (int c = a + 1; c < 5; c++) {
            if (nb == 0)
                return 1;
            if (nb == 1) {
                vbq_i128 t, u, d;
                if (!vbq_cmul(b[0][a], v[c], &t) || !vbq_cmul(b[0][c], v[a], &u) ||
                    !vbq_csub(t, u, &d))
                    return -1;
                if (d)
                    return 1;
                continue;
            }
            for (int e = c + 1; e < 5; e++) {
                const vbq_i128 *const r[3] = {b[0], b[1], v};
                const int cc[3] = {a, c, e};
                vbq_i128 d;
                if (!det3(r, cc, &d))
                    return -1;
                if (d)
                    return 1;
            }
        }
    return 0;
}

int vbq_cluster_hull(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin, uint32_t **tri, size_t *cap, size_t *nt)
{
    *nt = 0;
    int64_t ci[4];
    if (n < 4 || !vbq_cluster_scaled4(s, i, emin, ci))
        return 0;
    vbq_i128(*V)[5] = malloc((size_t)n * sizeof *V);
    if (!V)
        return -1;
    int rc = 0;
    const vbq_i128 *b[3];
    int nb = 0;
    vbq_i128 h[5] = {0, 0, 0, 0, 0};
    int have_h = 0;
    for (uint32_t k = 0; k < n; k++) {
        if (!vbq_cluster_vector(s, ids[k], emin, ci, V[k]) || V[k][4] <= 0)
            goto done;
        if (have_h)
            continue;
        if (nb < 3) {
            int d = indep(b, nb, V[k]);
            if (d < 0)
                goto done;
            if (d)
                b[nb++] = V[k];
            continue;
        }
        if (!normal4(b[0], b[1], b[2], V[k], h))
            goto done;
        for (int g = 0; g < 5; g++)
            have_h |= h[g] != 0;
    }
    if (!have_h)
        goto done; /* rank <= 3: the rank test's case */
    int all[5] = {0, 1, 2, 3, 4}, g = 0, c4[4], m = 0;
    for (uint32_t k = 0; k < n; k++) {
        vbq_i128 d;
        if (!dotc(V[k], h, all, 5, &d) || d != 0)
            goto done; /* rank 5, or too large */
    }
    while (h[g] == 0)
        g++;
    for (int y = 0; y < 5; y++)
        if (y != g)
            c4[m++] = y;
    uint32_t last = 0;
    for (uint32_t a = 0; a < n; a++)
        for (uint32_t bb = a + 1; bb < n; bb++)
            for (uint32_t c = bb + 1; c < n; c++) {
                vbq_i128 K[4];
                if (!cof3(V[a], V[bb], V[c], c4, K))
                    goto done;
                if (!K[0] && !K[1] && !K[2] && !K[3])
                    continue; /* dependent: no plane */
                int pos = 0, neg = 0;
                for (uint32_t t = 0; t <= n && !(pos && neg); t++) {
                    uint32_t q = t == 0 ? last : t - 1u;
                    if ((t > 0 && q == last) || q >= n || q == a || q == bb || q == c)
                        continue;
                    vbq_i128 d;
                    if (!dotc(V[q], K, c4, 4, &d))
                        goto done;
                    pos |= d > 0;
                    neg |= d < 0;
                    if (pos && neg)
                        last = q;
                }
                if (pos && neg)
                    continue;
                if (VB_ARRAY_FIT(*tri, *cap, 3 * (*nt + 1), 64) != VB_OK) {
                    rc = -1;
                    goto done;
                }
                (*tri)[3 * *nt] = ids[a];
                (*tri)[3 * *nt + 1] = ids[bb];
                (*tri)[3 * *nt + 2] = ids[c];
                (*nt)++;
            }
    rc = 1;
done:
    if (rc != 1)
        *nt = 0;
    free(V);
    return rc;
}
