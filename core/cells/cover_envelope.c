/* The exact decision of a stalled near-tie chain (vbq_host_envelope,
 * vb_cover_shared.h): a closed patch of cell i whose surviving labels stopped
 * separating (a jittered crystal's face ball: ~30 labels tie with infinity
 * at its outward normal to 1e-10 and would separate only ~22 levels down).
 * Instead of subdividing, the patch's vertices are decided from the exact
 * input, and the chain ends.
 *
 * What it covers: every label of the patch has the base's radius (the
 * decimals are compared; b = 0 in every record) and every vertex is sought
 * (no tangent-radius floor). Anything else returns 0 and the patch is
 * subdivided as before.
 *
 * Why it is exact and complete. With equal radii f_j(u) = a_j . u, a_j =
 * d_j / |d_j|^2 (vb_cover_shared.h). The patch is closed: every sphere
 * outside its list L, and every label its ancestors dropped, is strictly
 * below the envelope at every direction of the patch, so there the
 * envelope is max(0, max_{j in L} a_j . u) and it is attained only by
 * labels of L or by 0 ("infinity"). A vertex of cell i with smallest member
 * i in a direction W of the patch is a point where labels of L tie at the
 * largest value, which is > 0; the tied labels' points a_t span an affine
 * plane at least (else they tie along a great circle and W is no isolated
 * point), so three of them, j, k, l, all owned (ids > i), are affinely
 * independent, and W is parallel to Y = (a_k - a_j) x (a_l - a_j) != 0;
 * the quadruple (i, j, k, l) solves to W and the certifier finds every
 * other member. So it suffices to write, for every owned triple, the
 * quadruple exactly when its tie direction on the patch's face is a vertex
 * of the envelope there:
 *   W = sigma Y with sigma = sign(n . Y) != 0 (n the face's axis; the face
 *       is w = n + s e_u + t e_v, so W is on the face's cone iff n . W > 0),
 *   (s, t) = (e_u . Y, e_v . Y) / (n . Y) in [u0, u1] x [v0, v1]:
 *       sigma Q . Y >= 0 for Q = e_u - u0 n, u1 n - e_u, e_v - v0 n,
 *       v1 n - e_v,
 *   a_j . W > 0 (the value is positive: not a vertex at infinity), and
 *   no label m of L beats them: sigma (a_m - a_j) . Y <= 0.
 * Every test is the sign of a triple product det[X; a_k - a_j; a_l - a_j]
 * with X a dyadic vector Q or a difference a_m - a_j (a_j itself for the
 * value). Dropping every triple that fails a test drops only triples whose
 * tie point is off the patch or under the envelope; a triple that passes
 * is a vertex of the envelope in the patch, and may also be written by the
 * patch next to it (the cell's list is unique). What subdivision would have
 * written on the way down is a superset of these (its leaves keep every
 * label that may be largest in them); the certifier refutes the others,
 * so the vertices written are the same, and fewer quadruples reach it.
 *
 * The signs: a filter first (vbq_env_triple, core/cells/vbq_envelope_shared.h,
 * shared with the kernels; a triple it leaves undecided is decided here with
 * every sign exact). The records hold a~ with |a~ - a|_1 <= err
 * (vbq_nb_make). A row X~ = fl(a~_m - a~_j) is within eX = err_m + err_j +
 * 1.01 u |X~|_1 of X in L1 (each component rounds once, relative u); a Q
 * row is exact (components 0, +-1, +-u0: dyadic). For |det(A, B, C)| <=
 * |A|_1 |B|_1 |C|_1, multilinearity gives |det(X, Y, Z) - det(X~, Y~, Z~)|
 * <= (nX + eX)(nY + eY)(nZ + eZ) - nX nY nZ (n the L1 norms of the
 * computed rows), and computing det(X~, Y~, Z~) as X~ . (Y~ x Z~) errs by
 * at most 5.01 u sum |x y z| <= 5.01 u nX nY nZ (cross product gamma_2,
 * dot gamma_3). The bound below takes 8 u and a factor 1 + 1e-12 for its
 * own roundings (a dozen, of non-negative terms). A sign is taken when
 * |det~| exceeds the bound; otherwise the exact sign: det[X; a_k - a_j;
 * a_l - a_j] = -det4[(x0, X'); (1, a_j); (1, a_k); (1, a_l)] with X = X'
 * (x0 = 0) or X = a_m - a_j (x0 = 1, X' = a_m), and scaling rows and
 * columns by positive numbers keeps the sign: a label's row is (N_j, D_j)
 * with D_j the integer differences of the decimals scaled to a common
 * exponent and N_j = |D_j|^2 > 0, infinity's is (1, 0, 0, 0) and a Q row is
 * (0, 2^p Q), integers in GMP. */
#include <math.h>

#include "vb_cover_shared.h"
#include "vbq_env_exact.h"

/* Is owned triple (j, k, l) a vertex of the envelope on the patch, every
 * sign exact (the triples vbq_env_triple's doubles could not decide)? 1
 * yes, 0 no, 2 undecided (out of memory). *last: the label that beat the
 * last triple (tried first). */
static int env_triple(vbq_env_ctx *c, vbs_u32 j, vbs_u32 k, vbs_u32 l, double qs[5][3], vbs_u32 *last)
{
    c->tri_made = c->fast_made = c->tri_i = 0;
    /* sigma: the face's side of Y (qs[0] is n) */
    int sg = vbq_env_sign_exact(c, qs[0], 0u, j, k, l);
    if (sg == 2 || sg == 0)
        return sg;
    /* the square: sigma Q . Y >= 0 for its four sides */
    for (int e = 1; e < 5; e++) {
        int v = vbq_env_sign_exact(c, qs[e], 0u, j, k, l);
        if (v == 2)
            return 2;
        if (sg * v < 0)
            return 0;
    }
    /* positive value: sigma a_j . Y > 0 (det[-a_j; ..] from infinity's row) */
    int v = vbq_env_sign_exact(c, 0, c->n, j, k, l);
    if (v == 2)
        return 2;
    if (-sg * v <= 0)
        return 0;
    /* no label beats them: sigma (a_m - a_j) . Y <= 0, the last beater first */
    for (vbs_u32 t = 0; t <= c->n; t++) {
        vbs_u32 m = t == 0 ? *last : t - 1u;
        if ((t > 0 && m == *last) || m >= c->n || m == j || m == k || m == l)
            continue;
        v = vbq_env_sign_exact(c, 0, m, j, k, l);
        if (v == 2)
            return 2;
        if (sg * v > 0) {
            *last = m;
            return 0;
        }
    }
    return 1;
}

/* The corner rays of the patch's cone: w = n + s e_u + t e_v for (s, t)
 * the square's corners (vbq_env_sides' face and square; exact doubles). */
static void env_corners(vbs_u32 T, const vbq_frame *fr, double w[4][3])
{
    double u[2], v[2];
    vbq_patch_square(T, fr->level, fr->iu, fr->iv, &u[0], &u[1], &v[0], &v[1]);
    vbs_u32 ax = fr->f / 2u, au = (ax + 1u) % 3u, av = (ax + 2u) % 3u;
    for (int c = 0; c < 4; c++) {
        w[c][ax] = (fr->f & 1u) ? -1.0 : 1.0;
        w[c][au] = u[c & 1];
        w[c][av] = v[c >> 1];
    }
}

/* 1 when labels j and k are proven to tie nowhere in the patch's closed
 * cone: (a_k - a_j) . w has one strict sign at its four corner rays w, so
 * (linear in w) on the whole cone but 0; no triple holding both has its
 * tie direction there, and its side tests (env_triple) would drop it. With
 * X~ = fl(a~_k - a~_j): |X~ - X|_1 <= eX = err_j + err_k + 1.01 u |X~|_1
 * (the top), a corner's components are at most M = max |w_a| in size and
 * exact, so |X . w - X~ . w| <= eX M and the computed dot errs by at most
 * 3.01 u |X~|_1 M: the bound takes eX M + 4.02 u |X~|_1 M, times 1 + 1e-12
 * for its own roundings. 0: it cannot tell (NaN and infinity included). */
static int env_pair_apart(const vbq_nb *rj, const vbq_nb *rk, const double w[4][3])
{
    double X[3] = {rk->ax - rj->ax, rk->ay - rj->ay, rk->az - rj->az};
    double n1 = fabs(X[0]) + fabs(X[1]) + fabs(X[2]), M = 0.0;
    for (int c = 0; c < 4; c++)
        for (int a = 0; a < 3; a++)
            M = fmax(M, fabs(w[c][a]));
    double b = ((rj->err + rk->err + 1.01 * VBQ_U * n1) * M + 4.02 * VBQ_U * n1 * M) *
                   (1.0 + 1e-12) + VBQ_TINY;
    if (!isfinite(b))
        return 0;
    int pos = 0, neg = 0;
    for (int c = 0; c < 4; c++) {
        double d = X[0] * w[c][0] + X[1] * w[c][1] + X[2] * w[c][2];
        pos += d > b;
        neg += d < -b;
    }
    return pos == 4 || neg == 4;
}

/* Equal decimals (values, whatever their exponents). */
static int env_dec_equal(vb_decimal p, vb_decimal q)
{
    if (p.mant == q.mant && p.exp10 == q.exp10)
        return 1;
    while (p.mant != 0 && p.mant % 10 == 0) {
        p.mant /= 10;
        p.exp10++;
    }
    while (q.mant != 0 && q.mant % 10 == 0) {
        q.mant /= 10;
        q.exp10++;
    }
    return p.mant == q.mant && (p.mant == 0 || p.exp10 == q.exp10);
}

/* Every owned triple of the patch tested (env_triple's argument, the
 * top): own[0 .. no) the owned labels' indices into c->L. Returns as
 * vbq_envelope_decide. */
static int env_triples(vbq_env_ctx *c, const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o,
                       const vbq_frame *fr, vbs_u32 top, const vbs_u32 *own, vbs_u32 no,
                       double qs[5][3])
{
    /* The pairs whose tie circle may meet the patch: a triple is tested
     * only when its three pairs are (env_pair_apart: speed only). */
    double w[4][3];
    env_corners(e->T, fr, w);
    vbs_u64 meets[VBQ_ENV_TRIPLES_MAX][2] = {{0}};
    if (no > VBQ_ENV_TRIPLES_MAX)
        return 0;
    const vbq_nb *nb = ar->nb;
    const vbs_u32 *lab = ar->lab + top;
    for (vbs_u32 a = 0; a < no; a++)
        for (vbs_u32 b = a + 1; b < no; b++)
            if (!env_pair_apart(&nb[lab[own[a]]], &nb[lab[own[b]]], w)) {
                meets[a][b >> 6] |= (vbs_u64)1 << (b & 63u);
                meets[b][a >> 6] |= (vbs_u64)1 << (a & 63u);
            }
    int rc = 1;
    vbs_u32 last = 0;
    for (vbs_u32 a = 0; a < no && rc == 1; a++)
        for (vbs_u32 b = a + 1; b < no && rc == 1; b++) {
            if (!(meets[a][b >> 6] >> (b & 63u) & 1u))
                continue;
            for (vbs_u32 d = b + 1; d < no && rc == 1; d++) {
                if (!(meets[a][d >> 6] >> (d & 63u) & 1u) || !(meets[b][d >> 6] >> (d & 63u) & 1u))
                    continue;
                int v = vbq_env_triple(ar->nb, lab, c->n, own[a], own[b], own[d], qs, &last);
                if (v == 2)
                    v = env_triple(c, own[a], own[b], own[d], qs, &last);
                if (v == 2)
                    rc = 0;
                else if (v == 1 && !vbq_add_quad(ar, o, c->i, c->L[own[a]].id, c->L[own[b]].id,
                                                 c->L[own[d]].id))
                    rc = -1;
            }
        }
    return rc;
}

int vbq_envelope_decide(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                        const vbq_frame *fr, vbs_u32 top, vbs_u32 keep, int way,
                        vbs_u32 *exact_calls)
{
    const vb_sphere_set *s = e->host;
    if (!s || !s->ex || keep > VBQ_ENV_KEEP)
        return 0;
    vbq_env_lab L[VBQ_ENV_KEEP];
    vbs_u32 own[VBQ_ENV_KEEP], no = 0;
    for (vbs_u32 k = 0; k < keep; k++) {
        vbq_nb r = ar->nb[ar->lab[top + k]];
        if (!env_dec_equal(s->er[r.id], s->er[i]) || r.b != 0.0 || !(r.err < (double)INFINITY))
            return 0;
        L[k].id = r.id;
        if (r.id > i)
            own[no++] = k;
    }
    double qs[5][3];
    vbq_env_sides(e->T, fr, qs);
    vbq_env_ctx c = {.s = s, .i = i, .n = keep, .L = L};
    if (way == VBQ_ENV_AUTO)
        way = no > VBQ_ENV_HULL_OWNED ? VBQ_ENV_HULL : VBQ_ENV_TRIPLES;
    int rc = way == VBQ_ENV_HULL ? vbq_env_hull(&c, ar, o, qs)
                                 : env_triples(&c, e, ar, o, fr, top, own, no, qs);
    if (exact_calls)
        *exact_calls = c.exact_calls;
    vbq_env_ctx_free(&c);
    return rc;
}

int vbq_host_envelope(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                      const vbq_frame *fr, vbs_u32 top, vbs_u32 keep, vbs_u32 owned, int act,
                      int closed)
{
    if (!vbq_envelope_due(e, fr, ar->nb, ar->lab + top, keep, owned, act, closed) ||
        (owned <= VBQ_CLUSTER_OWNED && !vbq_envelope_sure(e, ar, i, fr, top, keep)))
        return 0;
    return vbq_envelope_decide(e, ar, o, i, fr, top, keep, VBQ_ENV_AUTO, NULL);
}
