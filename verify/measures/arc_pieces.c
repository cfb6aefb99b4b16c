/* The area's and the volume's pieces along an arc (vbm_arcfun.h): planned
 * halvings from the middle's series, then each piece proven by its own
 * Taylor model (vbm_arc_piece_values, which the contact's march uses too)
 * and halved where it falls short of its share of the widths. */
#include "vbm_arcfun.h"

int vbm_arc_over(const vbx_ia *v, const double *tg)
{
    for (int k = 0; k < NV; k++)
        if (vbm_ia_width(v[k]) > tg[k])
            return 1;
    return 0;
}

static int piece(const vbm_arcfun *f, double x0, double x1, const double *tg, int depth,
                 vbm_sums *out, const vbm_s1 *pre, int rpre, const vbm1_rat *prek);

/* [x0, x1] as two pieces, each to half the widths tg. */
static int halve(const vbm_arcfun *f, double x0, double x1, const double *tg, int depth,
                 vbm_sums *out)
{
    double xc = 0.5 * (x0 + x1), half[NV];
    for (int k = 0; k < NV; k++)
        half[k] = 0.5 * tg[k];
    return piece(f, x0, xc, half, depth + 1, out, NULL, 0, NULL) &&
           piece(f, xc, x1, half, depth + 1, out, NULL, 0, NULL);
}

/* The contact alone over the piece [xc + x] as contact_tm.c's model: the
 * middle's coefficients in c[CON] and its remainder in b[CON].c[K] (the
 * other values 0). Returns 0 when the model cannot be made (then the
 * contact's series over the piece bounds the remainder). */
static int contact_model(const vbm_arcfun *f, double xc, vbx_ia x, vbm_s1 *c, vbm_s1 *b)
{
    vbm_s1 z;
    vbx_ia F0;
    if (!vbm1_rational(&z, f->Pz, 2, vbm_arc_E, 2, vbx_ia_point(xc), 0) ||
        !vbm_owner_fcon(&f->o, z.c[0], &F0))
        return 0;
    for (int k = 0; k < NV; k++) {
        vbm1_const(&c[k], vbx_ia_point(0.0));
        vbm1_const(&b[k], vbx_ia_point(0.0));
    }
    return vbm_contact_tm(&f->cr, &f->o, F0, xc, x, &c[CON], &b[CON].c[VBM1_K]);
}

/* The integrals over the piece [x0, x1] of the values f->want in v[0..NV)
 * (those not wanted: any enclosure); `pre` (NULL: none) the integrand's
 * series at the middle already, rpre what vbm_arcfun_series returned for it, prek
 * its kept polynomials, tg the widths asked (the contact near e_j takes
 * its series in 1 - z only where that remainder leaves room in tg). Returns
 * 0 when an interval cannot bound them or, with `halves` (the piece may
 * still be split), when the contact's model cannot be made. The area's
 * and the volume's remainders over the piece come from the middle's
 * series (vbm1_rational_rest), the contact's from its
 * model (contact_model) or, where that cannot be made, from its series
 * over the piece: only at VBM_ARC_MAX_DEPTH, since elsewhere the piece is halved
 * (the capsid's first 4000 balls, 1crn and 3pqr: the same bytes as trying
 * the series first, which never kept such a piece, and 1.6 % fewer
 * instructions on 1crn). */
int vbm_arc_piece_values(const vbm_arcfun *f, double x0, double x1, const double *tg, int halves,
                         const vbm_s1 *pre, int rpre, const vbm1_rat *prek, vbx_ia *v)
{
    double xc = 0.5 * (x0 + x1);
    vbm_s1 cs[NV], b[NV];
    vbm1_rat kc[2];
    const vbm_s1 *c = pre ? pre : cs;
    const vbm1_rat *kp = pre ? prek : kc;
    vbx_ia box = {x0, x1}, rem = vbx_ia_point(0.0);
    vbx_ia len = vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(x0));
    int near = 0, rc, rb;
    if (f->o.contacts && f->want == 1 << CON) { /* the contact alone: near e_j? */
            vbm_s1 y;
        near = vbm1_rational(&y, f->Emz, 2, vbm_arc_E, 2, box, 0) && y.c[0].hi < VBM_NEAR_Y;
        double yhi = near ? y.c[0].hi : 0.0;
        /* the centre and the box by the same route: both the same function */
        /* and only where the remainder of h's series leaves room: it
         * shrinks with y, not with the piece */
        if (near && vbm_arcfun_near(f, box, VBM1_K, yhi, &b[CON], &rem) &&
            vbm_ia_width(vbx_ia_mul(len, rem)) <= 0.25 * tg[CON] &&
            vbm_arcfun_near(f, vbx_ia_point(xc), VBM1_K - 1, yhi, &cs[CON], NULL)) {
            c = cs;
            for (int k = 0; k < NV; k++)
                if (k != CON) {
                    vbm1_const(&cs[k], vbx_ia_point(0.0));
                    vbm1_const(&b[k], vbx_ia_point(0.0));
                }
        } else
            near = 0;
    }
    vbx_ia mom[VBM1_K + 1];
    vbx_ia x = {vbx_ia_sub(vbx_ia_point(x0), vbx_ia_point(xc)).lo,
                vbx_ia_sub(vbx_ia_point(x1), vbx_ia_point(xc)).hi};
    int model = !near && f->o.contacts && f->want == 1 << CON;
    if (model && contact_model(f, xc, x, cs, b)) {
        c = cs;
        rc = rb = 1;
    } else if (model && halves)
        return 0;
    else if (near)
        rc = rb = 1;
    else {
        int av = f->want & (1 << AREA | 1 << VOL);
        /* the contact's middle to the order K - 1 and its box's order K
         * alone: what vbm1_integrate_m reads of them (the area's and the
         * volume's at the middle keep every order: vbm1_rational_rest) */
        int kc_max = f->want == 1 << CON ? VBM1_K - 1 : VBM1_K;
        rc = pre ? rpre : vbm_arcfun_series(f, f->want, vbx_ia_point(xc), cs, kc_max, 0, kc);
        rb = rc ? vbm_arcfun_series(f, f->want & 1 << CON, box, b, VBM1_K, 1, NULL) : 0;
        for (int k = AREA; rb && av && k <= VOL; k++)
            if (!vbm1_rational_rest(&kp[k - AREA], &c[k], x, &b[k].c[VBM1_K]))
                rb = 0;
    }
    int ok = rc && rb;
    if (ok)
        vbm1_moments(xc, x0, x1, mom);
    for (int k = 0; ok && k < NV; k++) /* the contact's series is 0 without contacts */
        v[k] = k == CON && !f->o.contacts ? vbx_ia_point(0.0)
                                          : vbm1_integrate_m(&c[k], &b[k], mom);
    if (ok && near) /* the remainder of h's series over the piece */
        v[CON] = vbx_ia_add(v[CON], vbx_ia_mul(len, rem));
    if (ok && (rc == 2 || rb == 2)) /* the contact's bound over the box times its length */
        v[CON] = vbx_ia_mul(len, b[CON].c[0]);
    return ok;
}

/* The values integrated alone added to *out: vbm1_integrate_m of a zero
 * series is not exactly 0 (vbm_dotn's margin), and adding it to the others
 * would make the area and volume depend on how many contact pieces there
 * are. */
void vbm_arc_add_piece(const vbm_arcfun *f, const vbx_ia *v, vbm_sums *out)
{
    for (int k = 0; k < NV; k++)
        if (f->want & 1 << k)
            out->v[k] = vbx_ia_add(out->v[k], v[k]);
    out->pieces++;
}

/* The integrals over [x0, x1] to the widths tg (halved where they fall
 * short), added to *out; pre, rpre, prek as piece_values'. */
static int piece(const vbm_arcfun *f, double x0, double x1, const double *tg, int depth,
                 vbm_sums *out, const vbm_s1 *pre, int rpre, const vbm1_rat *prek)
{
    double xc = 0.5 * (x0 + x1);
    int halves = depth < VBM_ARC_MAX_DEPTH && xc > x0 && xc < x1;
    vbx_ia v[NV];
    int ok = vbm_arc_piece_values(f, x0, x1, tg, halves, pre, rpre, prek, v);
    if (!ok && !halves)
        return 0;
    /* a piece whose box an interval cannot bound (the contact's 1 / (1 - z)
     * where the arc passes near e_j) is halved too */
    if ((!ok || vbm_arc_over(v, tg)) && halves)
        return halve(f, x0, x1, tg, depth, out);
    vbm_arc_add_piece(f, v, out);
    return 1;
}

/* [x0, x1] (at depth `depth`) halved d times, each part by piece. */
static int descend(const vbm_arcfun *f, double x0, double x1, const double *tg, int d, int depth,
                   vbm_sums *out)
{
    double xc = 0.5 * (x0 + x1);
    if (d == 0 || !(xc > x0 && xc < x1))
        return piece(f, x0, x1, tg, depth, out, NULL, 0, NULL);
    double half[NV];
    for (int k = 0; k < NV; k++)
        half[k] = 0.5 * tg[k];
    return descend(f, x0, xc, half, d - 1, depth + 1, out) &&
           descend(f, xc, x1, half, d - 1, depth + 1, out);
}

#define PLAN_MAX 3 /* halvings planned before any piece is tried */
/* With the remainder over the piece from the coefficient's recurrence in
 * intervals, 512 (1crn, 1 thread: 54654 pieces). With the area's and the
 * volume's from the middle's series (vbm1_rational_rest), 0.1, 1, 8, 64,
 * 512 gave 31909, 32392, 35228, 40134, 48032 pieces and 2.96, 2.93, 2.98,
 * 3.09, 3.26 G instructions (callgrind; main 3.98 G). */
#define PLAN_FACTOR 1.0

/* Integrates [x0, x1] as piece does, but first halved as often as the
 * middle's series says it will need: each piece's share of tg against
 * PLAN_FACTOR |c_K| 2 h^(K+1) / (K + 1), the size of the remainder term on
 * a piece of half-width h. The halves piece would try anyway, without
 * the wider pieces it would try and drop first. Only where the pieces
 * start is chosen so; each is still proven by its own Taylor model and
 * halved further where it falls short. *est_area: the area's term above at
 * PLAN_FACTOR 1 (-1 where the series cannot be made), for march. */
int vbm_arc_planned(const vbm_arcfun *f, double x0, double x1, const double *tg, vbm_sums *out,
                    double *est_area)
{
    vbm_s1 c[NV];
    vbm1_rat kc[2];
    double xc = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
    int rc = vbm_arcfun_series(f, f->want, vbx_ia_point(xc), c, VBM1_K, 0, kc), d = 0;
    double hk = 2.0 / (VBM1_K + 1) * h;
    for (int n = 0; n < VBM1_K; n++)
        hk *= h;
    *est_area = -1.0;
    for (int k = 0; rc && k < NV; k++) {
        double mag = vbx_max(fabs(c[k].c[VBM1_K].lo), fabs(c[k].c[VBM1_K].hi));
        double est = PLAN_FACTOR * mag * hk;
        if (k == AREA)
            *est_area = mag * hk;
        for (int e = 0; e < PLAN_MAX && est > tg[k]; e++, est *= 1.0 / (1 << VBM1_K))
            d = e + 1 > d ? e + 1 : d;
    }
    if (d == 0)
        return piece(f, x0, x1, tg, 0, out, rc ? c : NULL, rc, kc);
    return descend(f, x0, x1, tg, d, 0, out);
}
