/* The exact decision of a tie cluster (vbq_host_cluster, vb_cover_shared.h):
 * a leaf of the direction cover whose owned labels never separated, because
 * they tie exactly (the outer layers of a crystal tie at infinity, the
 * spheres of a cospherical cluster at its centre). Enumerating such a leaf
 * writes C(k, 3) quadruples that all solve to the same one or two points;
 * this decides from the exact input which of them can hold a vertex.
 *
 * Why it is complete. Seen from c_i a label j is the affine function
 * f_j(u) = p_j . (u, 1) of the direction u, with p_j = (d_j, delta_j) / N_j
 * in R^4 (vb_cover_shared.h). Let the owned labels' points p_j lie in an
 * affine plane P (affine rank <= 2). A vertex w of cell i whose smallest
 * member is i has its other members M among the leaf's owned labels (the
 * cover's argument), tied at the largest value of f over them at w, and w is
 * an isolated point of that tie. For fixed u, f_j(u) is an affine function of
 * p_j restricted to P, so the labels that tie at its maximum form a face of
 * the polygon conv{p_j}: a vertex (one label), an edge, or all of them when
 * the function is constant on P. The directions where an edge's labels tie
 * at the top form a curve (one linear condition and an inequality), along
 * which no owned label and no label outside the owned ones can make an
 * isolated point (the latter would be tied at w, so a member smaller than
 * i, or the label of infinity, where the common value is 0 and w no vertex).
 * So M is every owned label and w lies where f is constant on P: u with
 * (u, 1) orthogonal to P's two directions, a line that meets the unit
 * sphere in at most two points, which are exactly the roots of the
 * quadruple of i and any three owned labels spanning P. One such quadruple
 * therefore holds every vertex the leaf can have (the certifier finds all
 * its members); with affine rank <= 1 the ties run along a curve and the
 * leaf has no vertex at all. Any other rank is left to the enumeration.
 *
 * The test is exact: p_j lifted to (p_j, 1) is a multiple of the integer
 * vector V_j = (D_j, Delta_j, N_j) of the decimals scaled to a common
 * exponent, so the affine rank of the points is the linear rank of the V_j
 * minus one, found exactly: in checked 128-bit integers where the numbers
 * fit (cluster_small.c), else by fraction-free elimination in GMP integers
 * (below), unless rank 4 modulo a prime already proves the answer
 * (cluster_modp.c: a jittered crystal's lists that look flat). Both find
 * the same rank and the same first independent labels. */
#include <gmp.h>
#include <stdlib.h>

#include "vb_cover_shared.h"
#include "vb_decimal_mpz.h"
#include "vbq_cluster.h"

/* Rows of at most 4 integer 5-vectors in echelon form (fraction-free):
 * row r has its first non-zero entry in column piv[r], zero below it in
 * earlier rows' pivot columns. */
typedef struct echelon {
    mpz_t row[4][5];
    int piv[4];
    vbs_u32 id[4];
    int n;
    mpz_t t, vp;
} echelon;

static void ech_init(echelon *E)
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 5; c++)
            mpz_init(E->row[r][c]);
    mpz_init(E->t);
    mpz_init(E->vp);
    E->n = 0;
}

static void ech_clear(echelon *E)
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 5; c++)
            mpz_clear(E->row[r][c]);
    mpz_clear(E->t);
    mpz_clear(E->vp);
}

/* Reduces v (overwritten) against the rows; appends it when it is not in
 * their span (and there is room). Returns 1 when v was independent. */
static int ech_add(echelon *E, mpz_t v[5], vbs_u32 id)
{
    for (int r = 0; r < E->n; r++) {
        int p = E->piv[r];
        if (!mpz_sgn(v[p]))
            continue;
        /* v <- row[p] v - v[p] row: v[p] becomes 0, exactly (v[p] is
         * kept aside, since the loop overwrites it). */
        mpz_set(E->vp, v[p]);
        for (int c = 0; c < 5; c++) {
            mpz_mul(E->t, E->row[r][p], v[c]);
            mpz_submul(E->t, E->vp, E->row[r][c]);
            mpz_swap(v[c], E->t);
        }
        /* keep the numbers small: divide by the content */
        mpz_set_ui(E->t, 0);
        for (int c = 0; c < 5; c++)
            mpz_gcd(E->t, E->t, v[c]);
        if (mpz_cmp_ui(E->t, 1) > 0)
            for (int c = 0; c < 5; c++)
                mpz_divexact(v[c], v[c], E->t);
    }
    int p = 0;
    while (p < 5 && !mpz_sgn(v[p]))
        p++;
    if (p == 5)
        return 0;
    if (E->n < 4) {
        for (int c = 0; c < 5; c++)
            mpz_set(E->row[E->n][c], v[c]);
        E->piv[E->n] = p;
        E->id[E->n] = id;
        E->n++;
    }
    return 1;
}

int32_t vbq_cluster_emin(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n)
{
    int32_t emin = s->ex[i].exp10;
    const vb_decimal *col[4] = {s->ex, s->ey, s->ez, s->er};
    for (uint32_t k = 0; k <= n; k++) {
        uint32_t j = k < n ? ids[k] : i;
        for (int a = 0; a < 4; a++)
            if (col[a][j].exp10 < emin)
                emin = col[a][j].exp10;
    }
    return emin;
}

void vbq_cluster_gmp(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin, vbq_cluster_ans *ans)
{
    const vb_decimal *col[4] = {s->ex, s->ey, s->ez, s->er};
    echelon E;
    ech_init(&E);
    mpz_t v[5], ci[4], t;
    for (int c = 0; c < 5; c++)
        mpz_init(v[c]);
    for (int a = 0; a < 4; a++)
        mpz_init(ci[a]);
    mpz_init(t);
    for (int a = 0; a < 4; a++)
        vb_decimal_to_mpz(ci[a], col[a][i], emin, t);
    int decided = 1;
    for (uint32_t k = 0; k < n && decided; k++) {
        uint32_t j = ids[k];
        for (int a = 0; a < 4; a++) {
            vb_decimal_to_mpz(v[a], col[a][j], emin, t);
            mpz_sub(v[a], v[a], ci[a]);
        }
        mpz_mul(v[4], v[0], v[0]);
        mpz_addmul(v[4], v[1], v[1]);
        mpz_addmul(v[4], v[2], v[2]);
        mpz_submul(v[4], v[3], v[3]);
        /* N_j = 0: j touches i from inside, f_j is not an affine function */
        if (mpz_sgn(v[4]) <= 0) {
            decided = 0;
            break;
        }
        if (ech_add(&E, v, j) && E.n > 3)
            decided = 0; /* affine rank >= 3 */
    }
    ans->decided = decided;
    ans->nbasis = E.n < 3 ? E.n : 3;
    for (int r = 0; r < ans->nbasis; r++)
        ans->id[r] = E.id[r];
    for (int c = 0; c < 5; c++)
        mpz_clear(v[c]);
    for (int a = 0; a < 4; a++)
        mpz_clear(ci[a]);
    mpz_clear(t);
    ech_clear(&E);
}

/* ids[0 .. n) ascending, by insertion: a cluster has few owned labels
 * (more than VBQ_CLUSTER_OWNED; 77 at most on 78 cospherical balls), and
 * its exact rank costs far more. */
static void ids_sort(uint32_t *ids, uint32_t n)
{
    for (uint32_t k = 1; k < n; k++) {
        uint32_t v = ids[k], j = k;
        for (; j > 0 && ids[j - 1] > v; j--)
            ids[j] = ids[j - 1];
        ids[j] = v;
    }
}

int vbq_host_cluster(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                     vbs_u32 *ids, vbs_u32 n)
{
    const vb_sphere_set *s = e->host;
    if (!s || !s->ex || n < 3)
        return 0;
    /* The first independent labels and the hull's triples follow the
     * labels' order: the set's own order makes the answer the same for any
     * list the cover has (vbq_cell_shared.h). */
    ids_sort(ids, n);
    vbq_cluster_ans a;
    const uint32_t *tri = NULL;
    uint32_t *own = NULL;
    size_t nt = 0, cap = 0;
    if (!ar->cmemo || !vbq_cluster_memo_get(ar->cmemo, s, i, ids, n, &a, &tri, &nt)) {
        int32_t emin = vbq_cluster_emin(s, i, ids, n);
        int fit = vbq_cluster_small(s, i, ids, n, emin, &a);
        if (!fit && vbq_cluster_modp(s, i, ids, n, emin))
            a = (vbq_cluster_ans){0, 0, {0, 0, 0}}; /* rank >= 4: GMP's decided = 0 */
        else if (!fit)
            vbq_cluster_gmp(s, i, ids, n, emin, &a);
        if (!a.decided) {
            /* affine rank 3 (cluster_hull.c); out of memory: enumerated */
            a.decided = vbq_cluster_hull(s, i, ids, n, emin, &own, &cap, &nt) == 1;
            a.nbasis = 0;
            tri = own;
        }
        if (ar->cmemo)
            vbq_cluster_memo_put(ar->cmemo, s, i, ids, n, &a, tri, nt);
    }
    int rc = a.decided;
    if (a.decided && a.nbasis == 3 && !vbq_add_quad(ar, o, i, a.id[0], a.id[1], a.id[2]))
        rc = -1;
    for (size_t t = 0; t < nt && rc == 1; t++)
        if (!vbq_add_quad(ar, o, i, tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]))
            rc = -1;
    free(own);
    return rc;
}
