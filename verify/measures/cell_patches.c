/* One atom's constrained cell, measured over its sphere of directions.
 *
 * The additively weighted cell of atom i is star-shaped from its centre ci,
 * so with r = Ri + probe and rho(u) the distance from ci along the unit
 * direction u to the cell boundary (rho = min over neighbours j of
 * t_j(u) = N_j / (2 (u.d_j + delta_j)), infinite where u.d_j + delta_j <= 0):
 *   volume  = (1/3) integral over S^2 of min(r, rho(u))^3 domega,
 *   SAS     = r^2 |{u : rho(u) >= r}|,
 *   contact = integral over {u : j owns u, t_j(u) < r} of t^2 / cos(angle
 *             between u and the face normal) domega.
 * Directions are mapped from the six faces of the cube, u ~ (a, b, 1) in
 * each face's axes, domega = da db / s^3 with s = sqrt(1 + a^2 + b^2); with
 * E = s (u.d + delta) = L + delta s, L = a d_p + b d_q + sigma d_w, the
 * integrands per da db are closed forms in (a, b):
 *   ball (rho >= r):  volume r^3 / (3 s^3),  SAS r^2 / s^3,
 *   owner j:          volume N^3 / (24 E^3), contact N^2 sqrt(N + 2 delta E/s) / (4 E^3)
 * (the face's area element: grad of |x-cj| - |x-ci| makes cos^2 = (u.d +
 * delta) / (2 (t + delta)) with u, giving t^2 sqrt(2 (t + delta) / (u.d +
 * delta)) per domega).
 *
 * A patch (a box of one face) is classified by interval bounds of every
 * neighbour still possible in its parent: j drops out where its ball
 * provably does not cover (t_j > r) or another bound is provably nearer.
 * A patch with one owner (the ball, or one j covering it all) is integrated
 * by a Taylor model (vbm_series.h: error O(h^8) on a patch of side h,
 * remainder proven); a patch where the owner changes (a Voronoi edge or the
 * SAS circle crosses it) gets the bounds min..max of the integrand times
 * its solid angle. Those patches are the cost: their enclosure shrinks as
 * h^3 for the volume but as h^2 for the SAS and contact areas (the
 * indicator jumps across the curve), so the curved SAS boundary is handled
 * by refinement, not by an exact treatment of its circle arcs. Patches are
 * split (into four) widest-first, the width weighed against each value's
 * target, until every value is within its target or the patch budget is
 * spent. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vbm_cell.h"
#include "vbm_piece.h"

#define GRID0 4              /* patches per face side at the start */
#define MIN_SIDE 0x1p-40     /* a patch this small is not split further */
#define FLOOR_FRACTION 1e-3  /* tolerance floor: this fraction of the ball's measure */

typedef struct patch {
    double a0, a1, b0, b1;
    uint32_t cand_off, ncand, pair_off, npair;
    vbx_ia vol, sas;
    double w;
    uint8_t face, alive;
} patch;

/* A neighbour's bounds over one patch. */
typedef struct cand_box {
    uint32_t j;
    vbx_ia t, C, E;
} cand_box;

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

void vbm_scratch_free(vbm_scratch *sc)
{
    free(sc->patch);
    free(sc->heap);
    free(sc->cand);
    free(sc->pair);
    free(sc->tmp);
    free(sc->sum);
    vbm_stokes_free(sc->stokes);
    memset(sc, 0, sizeof *sc);
}

/* Face f: the direction sigma e_w + a e_p + b e_q. */
static void face_axes(int f, int *w, int *p, int *q, double *sigma)
{
    *w = f >> 1;
    *p = (*w + 1) % 3;
    *q = (*w + 2) % 3;
    *sigma = (f & 1) ? -1.0 : 1.0;
}

static vbx_ia ia(double lo, double hi)
{
    vbx_ia r = {lo, hi};
    return r;
}

static vbx_ia ia_meet(vbx_ia a, vbx_ia b)
{
    return ia(vbx_max(a.lo, b.lo), vbx_min(a.hi, b.hi));
}

static vbx_ia ia_cube(vbx_ia a)
{
    return vbx_ia_mul(vbx_ia_sqr(a), a);
}

/* Taylor-model integrals over patch P owned by `owner` alone (-1: the
 * ball): volume, SAS and contact area (vbm_box_integrate). */
static int taylor(const vbm_atom_in *in, const patch *P, int owner, vbx_ia *vol, vbx_ia *sas,
                  vbx_ia *con)
{
    vbm_axes ax;
    face_axes(P->face, &ax.w, &ax.p, &ax.q, &ax.sigma);
    return vbm_box_integrate(in, owner, &ax, P->a0, P->a1, P->b0, P->b1, vol, sas, con);
}

static vbx_ia curve_at(const vbm_curve *cv, vbx_ia A, vbx_ia B, vbx_ia s)
{
    return vbx_ia_sub(vbx_ia_add(cv->l0, vbx_ia_add(vbx_ia_mul(cv->la, A), vbx_ia_mul(cv->lb, B))),
                      vbx_ia_mul(cv->kappa, s));
}

static int sign_of(vbx_ia x)
{
    return x.lo > 0.0 ? 1 : x.hi < 0.0 ? -1 : 0;
}

int vbm_curve_sign(const vbm_curve *cv, vbx_ia A, vbx_ia B, vbx_ia s)
{
    int sg = sign_of(curve_at(cv, A, B, s));
    if (sg)
        return sg;
    /* near the curve the box's interval is too wide: where F is monotone
     * in a and in b over the box (dF/da = la - kappa a / s, dF/db = lb -
     * kappa b / s, each of one sign), its extremes are at the corners,
     * evaluated at points */
    if (!sign_of(vbx_ia_sub(cv->la, vbx_ia_mul(cv->kappa, vbx_ia_div(A, s)))) ||
        !sign_of(vbx_ia_sub(cv->lb, vbx_ia_mul(cv->kappa, vbx_ia_div(B, s)))))
        return 0;
    for (int c = 0; c < 4; c++) {
        vbx_ia a = vbx_ia_point(c & 1 ? A.hi : A.lo), b = vbx_ia_point(c & 2 ? B.hi : B.lo);
        vbx_ia sc =
            vbx_ia_sqrt(vbx_ia_add(vbx_ia_point(1.0), vbx_ia_add(vbx_ia_sqr(a), vbx_ia_sqr(b))));
        int k = sign_of(curve_at(cv, a, b, sc));
        if (!k || (c && k != sg))
            return 0;
        sg = k;
    }
    return sg;
}

/* The contact integrand per da db over the box: N^2 sqrt(N + 2 delta D) /
 * (4 E^3), D = E / s (unbounded unless E > 0). */
static vbx_ia contact_bound(const vbm_nb *n, vbx_ia E, vbx_ia s)
{
    if (!(E.lo > 0.0))
        return ia(0.0, INFINITY);
    vbx_ia D = vbx_ia_div(E, s);
    vbx_ia g = vbx_ia_sqrt(vbx_ia_add(n->N, vbx_ia_mul(vbx_ia_add(n->delta, n->delta), D)));
    vbx_ia v = vbx_ia_div(vbx_ia_mul(vbx_ia_sqr(n->N), g), vbx_ia_mul(vbx_ia_point(4.0), ia_cube(E)));
    v.lo = vbx_max(v.lo, 0.0);
    return v;
}

/* The Voronoi edge of neighbours j and k on face (w, p, q, sigma):
 * F = N_k E_j - N_j E_k > 0 where t_j < t_k (E = L + delta s > 0). */
static void pair_curve(const vbm_atom_in *in, uint32_t j, uint32_t k, int w, int p, int q,
                       double sigma, vbm_curve *cv)
{
    const vbm_nb *nj = &in->nb[j], *nk = &in->nb[k];
    vbx_ia lj[3], lk[3];
    for (int x = 0; x < 3; x++) {
        lj[x] = vbx_ia_mul(nk->N, nj->d[x]);
        lk[x] = vbx_ia_mul(nj->N, nk->d[x]);
    }
    cv->l0 = vbx_ia_mul(vbx_ia_point(sigma), vbx_ia_sub(lj[w], lk[w]));
    cv->la = vbx_ia_sub(lj[p], lk[p]);
    cv->lb = vbx_ia_sub(lj[q], lk[q]);
    /* equal radii (delta exactly 0 for both): kappa exactly 0, the edge's
     * curve linear (an interval product would widen 0 by a subnormal) */
    cv->kappa = vbm_ia_is_zero(nj->delta) && vbm_ia_is_zero(nk->delta)
                    ? vbx_ia_point(0.0)
                    : vbx_ia_sub(vbx_ia_mul(nj->N, nk->delta), vbx_ia_mul(nk->N, nj->delta));
    cv->pos = (int)j;
    cv->neg = (int)k;
}

/* Classifies patch `pi` against the candidates [off, off + n) of the
 * arena, appends its own candidates and pairs, and sets its values. */
static int classify(const vbm_atom_in *in, vbm_scratch *sc, size_t *ncand_used,
                    size_t *npair_used, uint32_t pi, uint32_t off, uint32_t n)
{
    patch *P = (patch *)sc->patch + pi;
    int w, p, q;
    double sigma;
    face_axes(P->face, &w, &p, &q, &sigma);
    vbx_ia A = ia(P->a0, P->a1), B = ia(P->b0, P->b1);
    vbx_ia qq = vbx_ia_add(vbx_ia_point(1.0), vbx_ia_add(vbx_ia_sqr(A), vbx_ia_sqr(B)));
    vbx_ia s = vbx_ia_sqrt(qq);
    vbx_ia area = vbx_ia_mul(vbx_ia_point(P->a1 - P->a0), vbx_ia_point(P->b1 - P->b0));
    vbx_ia omega = vbx_ia_div(area, vbx_ia_mul(qq, s)); /* crude solid angle */
    vbx_ia r = in->r;

    if (!grow(&sc->tmp, &sc->cap_tmp, n, sizeof(cand_box)))
        return VB_ENOMEM;
    cand_box *cb = sc->tmp;
    const uint32_t *parent = (const uint32_t *)sc->cand + off;
    size_t m = 0;
    double tmin = r.hi;
    for (uint32_t k = 0; k < n; k++) {
        const vbm_nb *nb = &in->nb[parent[k]];
        vbx_ia L = vbx_ia_add(vbx_ia_mul(vbx_ia_point(sigma), nb->d[w]),
                              vbx_ia_add(vbx_ia_mul(A, nb->d[p]), vbx_ia_mul(B, nb->d[q])));
        vbx_ia C = vbx_ia_sub(L, vbx_ia_mul(nb->k, s));
        if (C.hi < 0.0)
            continue; /* t_j > r over the whole patch */
        vbx_ia E = vbx_ia_add(L, vbx_ia_mul(nb->delta, s));
        vbx_ia t;
        if (E.lo > 0.0) {
            t = vbx_ia_div(vbx_ia_mul(nb->N, s), vbx_ia_add(E, E));
        } else {
            t.hi = INFINITY;
            t.lo = E.hi > 0.0 ? vbx_ia_div(vbx_ia_mul(nb->N, s), vbx_ia_point(2.0 * E.hi)).lo : 0.0;
        }
        t.lo = vbx_max(t.lo, 0.0);
        cb[m].j = parent[k];
        cb[m].t = t;
        cb[m].C = C;
        cb[m].E = E;
        m++;
        tmin = vbx_min(tmin, t.hi);
    }
    /* j owns no direction where its bound is provably beyond another's */
    size_t kept = 0;
    double tlo = r.lo;
    int covered = 0;
    for (size_t k = 0; k < m; k++) {
        if (cb[k].t.lo > tmin)
            continue;
        cb[kept++] = cb[k];
        tlo = vbx_min(tlo, cb[k].t.lo);
        covered |= cb[k].C.lo > 0.0;
    }
    /* two neighbours compared directly: t_j > t_k wherever F_jk < 0
     * (vbm_curve of the pair: linear in a and b but for kappa s, so its
     * interval is far tighter than the two t intervals apart) */
    if (kept >= 2 && kept <= 12) {
        uint8_t drop[12] = {0};
        for (size_t x = 0; x < kept; x++)
            for (size_t y = 0; y < kept; y++) {
                if (x == y || drop[y])
                    continue;
                vbm_curve cv;
                pair_curve(in, cb[x].j, cb[y].j, w, p, q, sigma, &cv);
                if (vbm_curve_sign(&cv, A, B, s) < 0) {
                    drop[x] = 1;
                    break;
                }
            }
        /* `covered` stays: a dropped neighbour that covers the patch proves
         * that the one nearer than it does too */
        size_t k2 = 0;
        for (size_t x = 0; x < kept; x++)
            if (!drop[x])
                cb[k2++] = cb[x];
        kept = k2;
    }
    if (!grow(&sc->cand, &sc->cap_cand, *ncand_used + kept, sizeof(uint32_t)) ||
        !grow(&sc->pair, &sc->cap_pair, *npair_used + kept, sizeof(vbm_pair)))
        return VB_ENOMEM;
    P = (patch *)sc->patch + pi;
    uint32_t *own = (uint32_t *)sc->cand + *ncand_used;
    vbm_pair *pair = (vbm_pair *)sc->pair + *npair_used;
    for (size_t k = 0; k < kept; k++)
        own[k] = cb[k].j;
    P->cand_off = (uint32_t)*ncand_used;
    P->ncand = (uint32_t)kept;
    P->pair_off = (uint32_t)*npair_used;
    P->npair = 0;
    *ncand_used += kept;

    /* the crude enclosure: min..max of the integrand times the solid angle */
    vbx_ia f = ia(vbx_min(r.lo, tlo), tmin);
    P->vol = vbx_ia_div(vbx_ia_mul(omega, ia_cube(f)), vbx_ia_point(3.0));
    vbx_ia r2 = vbx_ia_sqr(r);
    P->sas = covered ? vbx_ia_point(0.0) : ia(0.0, vbx_ia_mul(r2, omega).hi);

    vbx_ia tv, ts, tc, tc2;
    if (kept == 0) { /* the ball's sphere: no neighbour reaches it here */
        vbx_ia om = ia_meet(omega, vbm_solid_angle(P->a0, P->a1, P->b0, P->b1));
        P->sas = vbx_ia_mul(r2, om);
        P->vol = vbx_ia_div(vbx_ia_mul(ia_cube(r), om), vbx_ia_point(3.0));
    } else if (kept == 1 && covered) { /* one face, inside the ball */
        const vbm_nb *nb = &in->nb[cb[0].j];
        vbx_ia c = vbx_ia_mul(contact_bound(nb, cb[0].E, s), area);
        if (taylor(in, P, (int)cb[0].j, &tv, &ts, &tc)) {
            P->vol = ia_meet(P->vol, tv);
            c = ia_meet(c, tc);
        }
        if (in->contacts) {
            pair[0].j = cb[0].j;
            pair[0].area = c;
            P->npair = 1;
        }
    } else {
        /* owners change inside: each may own none or all of it */
        for (size_t k = 0; in->contacts && k < kept; k++) {
            pair[k].j = cb[k].j;
            pair[k].area = ia(0.0, vbx_ia_mul(contact_bound(&in->nb[cb[k].j], cb[k].E, s), area).hi);
        }
        P->npair = in->contacts ? (uint32_t)kept : 0;
        /* one curve across: the SAS circle of one neighbour, or the
         * Voronoi edge of two that both cover the patch */
        vbm_curve cv;
        int cut = 0;
        const vbm_nb *nj = &in->nb[cb[0].j];
        if (kept == 1) {
            cv.l0 = vbx_ia_mul(vbx_ia_point(sigma), nj->d[w]);
            cv.la = nj->d[p];
            cv.lb = nj->d[q];
            cv.kappa = nj->k;
            cv.pos = (int)cb[0].j;
            cv.neg = -1;
            cut = 1;
        } else if (kept == 2 && covered) { /* the ball owns nothing here */
            pair_curve(in, cb[0].j, cb[1].j, w, p, q, sigma, &cv);
            cut = 1;
        }
        vbm_axes ax = {w, p, q, sigma};
        if (cut && vbm_cut_integrate(in, &ax, &cv, P->a0, P->a1, P->b0, P->b1, &tv, &ts, &tc,
                                     &tc2)) {
            P->vol = ia_meet(P->vol, tv);
            P->sas = ia_meet(P->sas, ts);
            for (uint32_t k = 0; k < P->npair; k++)
                pair[k].area = ia_meet(pair[k].area, (int)pair[k].j == cv.pos ? tc : tc2);
        }
    }
    *npair_used += P->npair;
    return VB_OK;
}

/* The sum of the live weights: the finite ones added, the infinite ones
 * counted (an unbounded patch must not turn the sum into inf - inf). */
typedef struct load {
    double finite;
    size_t ninf;
} load;

static void load_add(load *l, double w, int sign)
{
    if (w < INFINITY)
        l->finite += sign * w;
    else
        l->ninf += (size_t)(ptrdiff_t)sign;
}

static int load_done(const load *l)
{
    return l->ninf == 0 && l->finite <= 1.0;
}

/* Targets of the values: tolerance * max(|midpoint|, floor). */
typedef struct targets {
    double vol, sas, *pair; /* pair: one per neighbour */
} targets;

static double width(vbx_ia a)
{
    double d = a.hi - a.lo;
    return d == d ? d : INFINITY;
}

static double weight(const vbm_scratch *sc, const patch *P, const targets *tg)
{
    double w = vbx_max(width(P->vol) / tg->vol, width(P->sas) / tg->sas);
    const vbm_pair *pr = (const vbm_pair *)sc->pair + P->pair_off;
    for (uint32_t k = 0; k < P->npair; k++)
        w = vbx_max(w, width(pr[k].area) / tg->pair[pr[k].j]);
    return w == w ? w : INFINITY;
}

/* Heap of patch indices by weight (largest first; ties by index). */
static int heap_less(const patch *pt, uint32_t x, uint32_t y)
{
    return pt[x].w < pt[y].w || (pt[x].w == pt[y].w && x > y);
}

static void heap_down(const patch *pt, uint32_t *h, size_t n, size_t i)
{
    for (;;) {
        size_t l = 2 * i + 1, b = i;
        if (l < n && heap_less(pt, h[b], h[l]))
            b = l;
        if (l + 1 < n && heap_less(pt, h[b], h[l + 1]))
            b = l + 1;
        if (b == i)
            return;
        uint32_t t = h[i];
        h[i] = h[b];
        h[b] = t;
        i = b;
    }
}

static void heap_up(const patch *pt, uint32_t *h, size_t i)
{
    while (i > 0 && heap_less(pt, h[(i - 1) / 2], h[i])) {
        uint32_t t = h[i];
        h[i] = h[(i - 1) / 2];
        h[(i - 1) / 2] = t;
        i = (i - 1) / 2;
    }
}

/* Sums the live patches into out (vol, sas) and sum[j] (contacts). */
static void sum_live(const vbm_atom_in *in, const vbm_scratch *sc, size_t np, vbm_atom_out *out,
                     vbx_ia *sum)
{
    const patch *pt = sc->patch;
    out->vol = out->sas = vbx_ia_point(0.0);
    for (size_t j = 0; j < in->nnb; j++)
        sum[j] = vbx_ia_point(0.0);
    for (size_t i = 0; i < np; i++) {
        if (!pt[i].alive)
            continue;
        out->vol = vbx_ia_add(out->vol, pt[i].vol);
        out->sas = vbx_ia_add(out->sas, pt[i].sas);
        const vbm_pair *pr = (const vbm_pair *)sc->pair + pt[i].pair_off;
        for (uint32_t k = 0; k < pt[i].npair; k++)
            sum[pr[k].j] = vbx_ia_add(sum[pr[k].j], pr[k].area);
    }
}

static double target_of(double tol, vbx_ia v, double floor)
{
    double m = fabs(vbx_ia_mid(v));
    return tol * (m < INFINITY ? vbx_max(m, floor) : floor);
}

/* Recomputes the targets from the current sums, every live weight, the heap
 * and the total weight. Returns the number of live patches. */
static size_t retarget(const vbm_atom_in *in, vbm_scratch *sc, size_t np, targets *tg,
                       load *total, vbm_atom_out *out)
{
    vbx_ia *sum = sc->sum;
    sum_live(in, sc, np, out, sum);
    double r = in->r.hi, fv = FLOOR_FRACTION * 4.18879020478639 * r * r * r,
           fa = FLOOR_FRACTION * 12.566370614359172 * r * r;
    tg->vol = target_of(in->tolerance, out->vol, fv);
    tg->sas = target_of(in->tolerance, out->sas, fa);
    /* every contact drives the refinement, the ones the other atom of the
     * face integrates too (only the output leaves them out): the patches
     * around those faces narrow the volume as well, and on a budget
     * (test_cells_periodic's one atom) leaving them out widened it 5x */
    for (size_t j = 0; j < in->nnb; j++)
        tg->pair[j] = target_of(in->tolerance, sum[j], fa);
    patch *pt = sc->patch;
    uint32_t *h = sc->heap;
    size_t nh = 0;
    total->finite = 0.0;
    total->ninf = 0;
    for (size_t i = 0; i < np; i++) {
        if (!pt[i].alive)
            continue;
        pt[i].w = pt[i].w == 0.0 && pt[i].a1 - pt[i].a0 < MIN_SIDE ? 0.0 : weight(sc, &pt[i], tg);
        load_add(total, pt[i].w, 1);
        h[nh++] = (uint32_t)i;
    }
    for (size_t i = nh / 2; i-- > 0;)
        heap_down(pt, h, nh, i);
    return nh;
}

int vbm_cell_integrate(const vbm_atom_in *in, vbm_scratch *sc, vbm_atom_out *out)
{
    memset(out, 0, sizeof *out);
    size_t nnb = in->nnb, ncand = 0, npair = 0, np = 0;
    size_t first = 6 * GRID0 * GRID0;
    if (!grow(&sc->cand, &sc->cap_cand, nnb, sizeof(uint32_t)) ||
        !grow(&sc->patch, &sc->cap_patch, first, sizeof(patch)) ||
        !grow(&sc->heap, &sc->cap_heap, first, sizeof(uint32_t)) ||
        !grow(&sc->sum, &sc->cap_sum, 2 * nnb + 1, sizeof(vbx_ia)))
        return VB_ENOMEM;
    for (size_t j = 0; j < nnb; j++)
        ((uint32_t *)sc->cand)[j] = (uint32_t)j;
    ncand = nnb;
    targets tg;
    tg.pair = (double *)((vbx_ia *)sc->sum + nnb); /* nnb doubles fit in nnb + 1 intervals */
    for (int f = 0; f < 6; f++)
        for (int ia_ = 0; ia_ < GRID0; ia_++)
            for (int ib = 0; ib < GRID0; ib++) {
                patch *P = (patch *)sc->patch + np;
                P->face = (uint8_t)f;
                P->alive = 1;
                P->w = 1.0;
                P->a0 = -1.0 + 2.0 * ia_ / GRID0;
                P->a1 = -1.0 + 2.0 * (ia_ + 1) / GRID0;
                P->b0 = -1.0 + 2.0 * ib / GRID0;
                P->b1 = -1.0 + 2.0 * (ib + 1) / GRID0;
                if (classify(in, sc, &ncand, &npair, (uint32_t)np, 0, (uint32_t)nnb) != VB_OK)
                    return VB_ENOMEM;
                np++;
            }
    load total;
    size_t nh = retarget(in, sc, np, &tg, &total, out);
    size_t next = 2 * nh, recheck = 0;
    while (np < in->max_patches) {
        /* done by the targets of the last sums: new sums, new targets; not
         * done by those, refine on (the next such check after 1/8 more
         * patches, so that checking stays linear in all) */
        if (load_done(&total) && np >= recheck) {
            nh = retarget(in, sc, np, &tg, &total, out);
            next = 2 * nh;
            recheck = np + np / 8;
            if (load_done(&total))
                break;
        }
        if (nh == 0)
            break;
        patch *pt = sc->patch;
        uint32_t *h = sc->heap;
        uint32_t top = h[0];
        if (pt[top].w <= 0.0)
            break;
        load_add(&total, pt[top].w, -1);
        h[0] = h[--nh];
        heap_down(pt, h, nh, 0);
        if (pt[top].a1 - pt[top].a0 < MIN_SIDE) {
            pt[top].w = 0.0; /* kept as it is, counted as loose below */
            out->loose = 1;
            continue;
        }
        if (!grow(&sc->patch, &sc->cap_patch, np + 4, sizeof(patch)) ||
            !grow(&sc->heap, &sc->cap_heap, nh + 4, sizeof(uint32_t)))
            return VB_ENOMEM;
        pt = sc->patch;
        h = sc->heap;
        pt[top].alive = 0;
        patch parent = pt[top];
        double am = 0.5 * (parent.a0 + parent.a1), bm = 0.5 * (parent.b0 + parent.b1);
        for (int c = 0; c < 4; c++) {
            patch *P = (patch *)sc->patch + np;
            *P = parent;
            P->alive = 1;
            if (c & 1)
                P->a0 = am;
            else
                P->a1 = am;
            if (c & 2)
                P->b0 = bm;
            else
                P->b1 = bm;
            if (classify(in, sc, &ncand, &npair, (uint32_t)np, parent.cand_off, parent.ncand) !=
                VB_OK)
                return VB_ENOMEM;
            P = (patch *)sc->patch + np;
            P->w = weight(sc, P, &tg);
            load_add(&total, P->w, 1);
            h[nh] = (uint32_t)np;
            heap_up(sc->patch, h, nh);
            nh++;
            np++;
        }
        if (nh >= next) {
            nh = retarget(in, sc, np, &tg, &total, out);
            next = 2 * nh;
        }
    }
    vbx_ia *sum = sc->sum;
    sum_live(in, sc, np, out, sum);
    out->patches = np;
    double r = in->r.hi, fv = FLOOR_FRACTION * 4.18879020478639 * r * r * r,
           fa = FLOOR_FRACTION * 12.566370614359172 * r * r;
    if (width(out->vol) > target_of(in->tolerance, out->vol, fv) ||
        width(out->sas) > target_of(in->tolerance, out->sas, fa))
        out->loose = 1;
    size_t cnt = 0;
    for (size_t j = 0; j < nnb; j++)
        cnt += in->nb[j].con && sum[j].hi > 0.0;
    if (cnt) {
        out->pairs = malloc(cnt * sizeof *out->pairs);
        if (!out->pairs)
            return VB_ENOMEM;
        for (size_t j = 0; j < nnb; j++) {
            if (!(in->nb[j].con && sum[j].hi > 0.0))
                continue;
            if (width(sum[j]) > target_of(in->tolerance, sum[j], fa))
                out->loose = 1;
            out->pairs[out->npairs].j = (uint32_t)j;
            out->pairs[out->npairs].area = sum[j];
            out->npairs++;
        }
    }
    return VB_OK;
}
