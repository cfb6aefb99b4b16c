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
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vbm_cell.h"
#include "vbm_series.h"

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

/* L = sigma d_w + a d_p + b d_q for series a, b. */
static void ser_linear(vbm_ser *L, const vbm_ser *a, const vbm_ser *b, const vbm_nb *n, int w,
                       int p, int q, double sigma)
{
    vbm_ser t;
    vbm_affine(L, n->d[p], a, vbx_ia_mul(vbx_ia_point(sigma), n->d[w]));
    vbm_affine(&t, n->d[q], b, vbx_ia_point(0.0));
    vbm_add(L, L, &t);
}

/* s = sqrt(1 + a^2 + b^2) and 1 / s^3 as series at (A, B). */
static int ser_s(vbm_ser *s, vbm_ser *inv_s3, vbm_ser *a, vbm_ser *b, vbx_ia A, vbx_ia B)
{
    vbm_ser q, t;
    vbm_var(a, A, 0);
    vbm_var(b, B, 1);
    vbm_mul(&q, a, a);
    vbm_mul(&t, b, b);
    vbm_add(&q, &q, &t);
    q.c[0] = vbx_ia_add(q.c[0], vbx_ia_point(1.0));
    if (!vbm_sqrt(s, &q))
        return 0;
    vbm_mul(&t, &q, s);
    return vbm_recip(inv_s3, &t);
}

/* Taylor-model integrals over patch P: the solid angle (owner < 0) or, for
 * owner j, the integrals of E^-3 and of sqrt(N + 2 delta E / s) E^-3. */
static int taylor(const vbm_atom_in *in, const patch *P, int owner, vbx_ia *i1, vbx_ia *i2)
{
    int w, p, q;
    double sigma;
    face_axes(P->face, &w, &p, &q, &sigma);
    double ac = 0.5 * (P->a0 + P->a1), bc = 0.5 * (P->b0 + P->b1);
    double ha = 0.5 * (P->a1 - P->a0), hb = 0.5 * (P->b1 - P->b0);
    vbm_ser r1[2], r2[2];
    for (int k = 0; k < 2; k++) {
        vbx_ia A = k ? ia(P->a0, P->a1) : vbx_ia_point(ac);
        vbx_ia B = k ? ia(P->b0, P->b1) : vbx_ia_point(bc);
        vbm_ser a, b, s, inv_s3;
        if (!ser_s(&s, &inv_s3, &a, &b, A, B))
            return 0;
        if (owner < 0) {
            r1[k] = inv_s3;
            continue;
        }
        const vbm_nb *n = &in->nb[owner];
        vbm_ser E, t, e1, e2, D, g;
        ser_linear(&E, &a, &b, n, w, p, q, sigma);
        vbm_affine(&t, n->delta, &s, vbx_ia_point(0.0));
        vbm_add(&E, &E, &t);
        if (!vbm_recip(&e1, &E))
            return 0;
        vbm_mul(&e2, &e1, &e1);
        vbm_mul(&r1[k], &e2, &e1);
        if (!i2)
            continue;
        if (!vbm_recip(&t, &s))
            return 0;
        vbm_mul(&D, &E, &t);
        vbm_affine(&t, vbx_ia_add(n->delta, n->delta), &D, n->N);
        if (!vbm_sqrt(&g, &t))
            return 0;
        vbm_mul(&r2[k], &g, &r1[k]);
    }
    *i1 = vbm_integrate(&r1[0], &r1[1], ha, hb);
    if (i2 && owner >= 0)
        *i2 = vbm_integrate(&r2[0], &r2[1], ha, hb);
    return 1;
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

    if (kept == 0) { /* the ball's sphere: no neighbour reaches it here */
        vbx_ia om;
        P->sas = vbx_ia_mul(r2, omega);
        if (taylor(in, P, -1, &om, NULL)) {
            P->vol = ia_meet(P->vol, vbx_ia_div(vbx_ia_mul(ia_cube(r), om), vbx_ia_point(3.0)));
            P->sas = ia_meet(P->sas, vbx_ia_mul(r2, om));
        }
    } else if (kept == 1 && covered) { /* one face, inside the ball */
        const vbm_nb *nb = &in->nb[cb[0].j];
        vbx_ia i1, i2, c = vbx_ia_mul(contact_bound(nb, cb[0].E, s), area);
        if (taylor(in, P, (int)cb[0].j, &i1, in->contacts ? &i2 : NULL)) {
            P->vol = ia_meet(P->vol,
                             vbx_ia_div(vbx_ia_mul(ia_cube(nb->N), i1), vbx_ia_point(24.0)));
            if (in->contacts)
                c = ia_meet(c, vbx_ia_div(vbx_ia_mul(vbx_ia_sqr(nb->N), i2), vbx_ia_point(4.0)));
        }
        if (in->contacts) {
            pair[0].j = cb[0].j;
            pair[0].area = c;
            P->npair = 1;
        }
    } else if (in->contacts) { /* owners change inside: each may own none or all of it */
        for (size_t k = 0; k < kept; k++) {
            pair[k].j = cb[k].j;
            pair[k].area = ia(0.0, vbx_ia_mul(contact_bound(&in->nb[cb[k].j], cb[k].E, s), area).hi);
        }
        P->npair = (uint32_t)kept;
    }
    *npair_used += P->npair;
    return VB_OK;
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
                       double *total, vbm_atom_out *out)
{
    vbx_ia *sum = sc->sum;
    sum_live(in, sc, np, out, sum);
    double r = in->r.hi, fv = FLOOR_FRACTION * 4.18879020478639 * r * r * r,
           fa = FLOOR_FRACTION * 12.566370614359172 * r * r;
    tg->vol = target_of(in->tolerance, out->vol, fv);
    tg->sas = target_of(in->tolerance, out->sas, fa);
    for (size_t j = 0; j < in->nnb; j++)
        tg->pair[j] = target_of(in->tolerance, sum[j], fa);
    patch *pt = sc->patch;
    uint32_t *h = sc->heap;
    size_t nh = 0;
    *total = 0.0;
    for (size_t i = 0; i < np; i++) {
        if (!pt[i].alive)
            continue;
        pt[i].w = pt[i].w == 0.0 && pt[i].a1 - pt[i].a0 < MIN_SIDE ? 0.0 : weight(sc, &pt[i], tg);
        *total += pt[i].w;
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
    double total;
    size_t nh = retarget(in, sc, np, &tg, &total, out);
    size_t next = 2 * nh;
    while (np < in->max_patches) {
        if (total <= 1.0) {
            nh = retarget(in, sc, np, &tg, &total, out);
            next = 2 * nh;
            if (total <= 1.0)
                break;
        }
        if (nh == 0)
            break;
        patch *pt = sc->patch;
        uint32_t *h = sc->heap;
        uint32_t top = h[0];
        if (pt[top].w <= 0.0)
            break;
        total -= pt[top].w;
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
            total += P->w;
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
        cnt += sum[j].hi > 0.0;
    if (cnt) {
        out->pairs = malloc(cnt * sizeof *out->pairs);
        if (!out->pairs)
            return VB_ENOMEM;
        for (size_t j = 0; j < nnb; j++) {
            if (!(sum[j].hi > 0.0))
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
