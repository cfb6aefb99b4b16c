/* The integrands along an arc as series in t = tan(angle / 2) about a
 * point or over an interval (vbm_arcfun.h): the area's and the volume's
 * quotients of polynomials, the contact's root and logs of such quotients
 * (Taylor coefficients by linear recurrences, vbm1_rational), and the
 * contact's plain interval bound where its series cannot be made. */
#include "vbm_arcfun.h"
#include "vbm_piece.h"

const vbx_ia vbm_arc_E[3] = {{1.0, 1.0}, {0.0, 0.0}, {1.0, 1.0}};

/* With E = 1 + t^2, cos = (1 - t^2) / E and sin = 2 t / E, so
 *   z = Pz / E, 1 + z = Po / E, q = D z + delta = Pq / E,
 *   e.(u x du/dt) = 2 Pn / E^2 (Pz, Po, Pq, Pn quadratics in t), and
 *   area integrand   (1 - z) dphi/dt = 2 Pn / (E Po),
 *   volume integrand K (D (1 + z) + 2 delta) / q^2 times that
 *                    = 2 K Pn (D Po + 2 delta E) / (Pq^2 Po). */
static void rational_of(vbm_arcfun *f)
{
    const vbm_owner *o = &f->o;
    vbx_ia sA1 = vbx_ia_mul(f->s, f->A1), sA2 = vbx_ia_mul(f->s, f->A2);
    vbx_ia mA1 = vbx_ia_mul(f->mcs, f->A1), mA2 = vbx_ia_mul(f->mcs, f->A2);
    vbx_ia one = vbx_ia_point(1.0), two = vbx_ia_point(2.0), dd = vbx_ia_add(o->delta, o->delta);
    vbx_ia E[3] = {one, vbx_ia_point(0.0), one};
    vbx_ia Pz[3] = {vbx_ia_add(sA1, f->cA0), vbx_ia_mul(two, sA2), vbx_ia_sub(f->cA0, sA1)};
    vbx_ia Pn[3] = {vbx_ia_add(mA1, f->sA0s), vbx_ia_mul(two, mA2), vbx_ia_sub(f->sA0s, mA1)};
    vbx_ia Po[3], Pq[3], Pv[3], Pq2[5], t[5];
    for (int k = 0; k < 3; k++) {
        Po[k] = vbx_ia_add(E[k], Pz[k]);
        Pq[k] = vbx_ia_add(vbx_ia_mul(o->D, Pz[k]), vbx_ia_mul(o->delta, E[k]));
        Pv[k] = vbx_ia_add(vbx_ia_mul(o->D, Po[k]), vbx_ia_mul(dd, E[k]));
        f->an[k] = vbx_ia_mul(two, Pn[k]);
        f->Pz[k] = Pz[k];
        f->Pq[k] = Pq[k];
    }
    vbm1_poly_mul(f->ad, E, 2, Po, 2);
    vbm1_poly_mul(t, Pn, 2, Pv, 2);
    vbx_ia k2 = vbx_ia_mul(two, o->K);
    for (int k = 0; k < 5; k++)
        f->vn[k] = vbx_ia_mul(k2, t[k]);
    vbm1_poly_mul(Pq2, Pq, 2, Pq, 2);
    vbm1_poly_mul(f->vd, Pq2, 4, Po, 2);
    if (!o->contacts)
        return;
    /* 1 / (1 - z) = E / (E - Pz), so the area's integrand over 1 - z is
     * 2 Pn / (Po (E - Pz)) */
    vbx_ia Emz[3];
    for (int k = 0; k < 3; k++) {
        Emz[k] = vbx_ia_sub(E[k], Pz[k]);
        f->Emz[k] = Emz[k];
    }
    vbm1_poly_mul(f->cd, Po, 2, Emz, 2);
    /* q' / q^3 = (Pq' E - Pq E') E / Pq^3, Pq' E - Pq E' = p1 + 2 (p2 - p0) t
     * - p1 t^2 (the t^3 terms cancel: contact_tm.c); S = (N E + 2 delta Pq)
     * / E */
    vbx_ia dq[3] = {Pq[1], vbx_ia_mul(two, vbx_ia_sub(Pq[2], Pq[0])), vbx_ia_neg(Pq[1])}, Pq3[7];
    vbm1_poly_mul(f->cr.rn, dq, 2, E, 2);
    vbm1_poly_mul(Pq3, Pq2, 4, Pq, 2);
    for (int k = 0; k < 7; k++)
        f->cr.rd[k] = Pq3[k];
    for (int k = 0; k < 5; k++)
        f->cr.cd[k] = f->cd[k];
    for (int k = 0; k < 3; k++) {
        f->cr.po[k] = Po[k];
        f->cr.sd[k] = E[k];
        f->cr.an[k] = f->an[k];
        f->cr.yn[k] = Emz[k];
    }
}

void vbm_arcfun_make(vbm_arcfun *f, const vbm_owner *o, const vbm_arcrec *a, vbx_ia cm,
                     vbx_ia sm, vbm_phic *pc)
{
    f->o = *o;
    f->pc = pc;
    f->want = 0;
    f->cA0 = vbx_ia_mul(a->c, a->A0);
    f->s = a->s;
    f->sA0s = vbx_ia_mul(vbx_ia_sqr(a->s), a->A0);
    f->mcs = vbx_ia_neg(vbx_ia_mul(a->c, a->s));
    f->A1 = vbx_ia_add(vbx_ia_mul(a->A1, cm), vbx_ia_mul(a->A2, sm));
    f->A2 = vbx_ia_sub(vbx_ia_mul(a->A2, cm), vbx_ia_mul(a->A1, sm));
    rational_of(f);
}

/* S = N + 2 delta q = (N E + 2 delta Pq) / E; the algebraic part of G(q),
 * -S^(3/2) / (2 N q^2) + delta sqrt(S) / (2 N q), is sqrt(S) times
 * (delta q - S) / (2 N q^2) = -(N E + delta Pq) E / (2 N Pq^2) = Rn / Rd.
 * Made where contact_of reads them (its fallback), not for every arc
 * (c1k --contacts: 25,761 arcs, far fewer fallback series). */
static void alg_of(const vbm_arcfun *f, vbx_ia *Rn, vbx_ia *Rd)
{
    const vbm_owner *o = &f->o;
    vbx_ia W[3], Pq2[5];
    for (int k = 0; k < 3; k++)
        W[k] = vbx_ia_neg(
            vbx_ia_add(vbx_ia_mul(o->N, vbm_arc_E[k]), vbx_ia_mul(o->delta, f->Pq[k])));
    vbm1_poly_mul(Rn, W, 2, vbm_arc_E, 2);
    vbm1_poly_mul(Pq2, f->Pq, 2, f->Pq, 2);
    vbx_ia twoN = vbx_ia_add(o->N, o->N);
    for (int k = 0; k < 5; k++)
        Rd[k] = vbx_ia_mul(twoN, Pq2[k]);
}

/* The contact's integrand C (G1 - G(q)) / (1 - z) times the area's, G as
 * vbm_contact_g's but its algebraic part one root times a rational function, to
 * the order kmax; with `last`, of *con the order kmax alone (the others
 * 0: over a piece only the remainder's order is read). Returns 0 when a
 * series cannot be bounded (the caller bounds it near e_j). */
static int contact_of(const vbm_arcfun *f, vbx_ia at, int kmax, int last, vbm_s1 *con)
{
    const vbm_owner *o = &f->o;
    vbm_s1 S, r, R, G, u, a, q;
    /* S = N + 2 delta q from q's series (one affine map where SN / E took a
     * second rational recurrence; S = N exactly for delta = 0) */
    int dz = vbm_ia_is_zero(o->delta);
    if (dz)
        vbm1_const(&S, o->N);
    else if (vbm1_rational(&q, f->Pq, 2, vbm_arc_E, 2, at, kmax))
        vbm1_affine(&S, vbx_ia_add(o->delta, o->delta), &q, o->N);
    else
        return 0;
    vbx_ia Rn[5], Rd[5];
    alg_of(f, Rn, Rd);
    if (!vbm1_sqrt_to(&r, &S, kmax) || !vbm1_rational(&R, Rn, 4, Rd, 4, at, kmax) ||
        !vbm1_rational(&a, f->an, 2, f->cd, 4, at, kmax))
        return 0;
    vbm1_mul_to(&G, &r, &R, kmax);
    if (!dz) { /* - delta^2 / (2 N sqrt N) log(2 |delta| q / (sqrt S + sqrt N)^2) */
        vbm_s1 lq, ls;
        vbm1_affine(&u, vbx_ia_point(1.0), &r, o->rN);
        if (!vbm1_log_to(&lq, &q, kmax) || !vbm1_log_to(&ls, &u, kmax))
            return 0;
        vbm1_affine(&u, vbx_ia_point(-2.0), &ls, o->lnd);
        vbm1_add(&u, &u, &lq);
        vbm1_affine(&u, vbx_ia_neg(o->kL), &u, vbx_ia_point(0.0));
        vbm1_add(&G, &G, &u);
    }
    vbm1_affine(&G, vbx_ia_neg(o->C), &G, vbx_ia_mul(o->C, o->G1));
    if (last) {
        vbm1_const(con, vbx_ia_point(0.0));
        con->c[kmax] = vbm1_mul_coef(&G, &a, kmax);
    } else
        vbm1_mul_to(con, &G, &a, kmax);
    return 1;
}

int vbm_arcfun_series(const vbm_arcfun *f, int want, vbx_ia at, vbm_s1 *v, int kmax, int last,
                      vbm1_rat *keep)
{
    int av = want & (1 << AREA | 1 << VOL);
    if (av && keep &&
        (!vbm1_rational_keep(&v[AREA], f->an, 2, f->ad, 4, at, &keep[0]) ||
         !vbm1_rational_keep(&v[VOL], f->vn, 4, f->vd, 6, at, &keep[1])))
        return 0;
    if (av && !keep && (!vbm1_rational(&v[AREA], f->an, 2, f->ad, 4, at, kmax) ||
                        !vbm1_rational(&v[VOL], f->vn, 4, f->vd, 6, at, kmax)))
        return 0;
    if (!av) {
        vbm1_const(&v[AREA], vbx_ia_point(0.0));
        vbm1_const(&v[VOL], vbx_ia_point(0.0));
    }
    vbm1_const(&v[CON], vbx_ia_point(0.0));
    if (!f->o.contacts || !(want & 1 << CON))
        return 1;
    if (contact_of(f, at, kmax, last, &v[CON]))
        return 1;
    vbx_ia b;
    if (!vbm_arcfun_contact_bound(f, at, &b))
        return 0;
    vbm1_const(&v[CON], b);
    return 2;
}

int vbm_arcfun_contact_bound(const vbm_arcfun *f, vbx_ia at, vbx_ia *b)
{
    vbm_s1 z;
    if (!vbm1_rational(&z, f->Pz, 2, vbm_arc_E, 2, at, 0))
        return 0;
    vbx_ia Z = {z.c[0].lo, 1.0};
    vbx_ia qz = vbx_ia_add(vbx_ia_mul(f->o.D, Z), f->o.delta);
    vbx_ia S = vbx_ia_add(f->o.N, vbx_ia_mul(vbx_ia_add(f->o.delta, f->o.delta), qz));
    vbx_ia fa = vbx_ia_div(vbx_ia_mul(vbx_ia_sqr(f->o.N), vbx_ia_sqrt(S)),
                           vbx_ia_mul(vbx_ia_point(4.0), vbx_ia_mul(vbx_ia_sqr(qz), qz)));
    vbm_s1 area; /* the area's integrand here, whether wanted or not */
    if (!vbm1_rational(&area, f->an, 2, f->ad, 4, at, 0))
        return 0;
    *b = vbx_ia_mul(fa, area.c[0]);
    return 1;
}
