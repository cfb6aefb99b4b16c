/* The trisector of a triple as a conic (vbx_arc.h): its kind, its
 * coordinates G and S, and positions of points on it (the exact points of
 * vertices and roots, and the local test at a vertex: arc_local.c). */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "vbx_plane.h"

/* ---- the frame ------------------------------------------------------------ */

void vbx_tframe_init(vbx_tframe *f)
{
    memset(f, 0, sizeof *f);
    for (int k = 0; k < 4; k++) {
        mpz_init(f->gz[k]);
        mpz_init(f->sz[k]);
        mpz_init(f->ez[k]);
    }
    for (int k = 0; k < 6; k++)
        mpz_init(f->mz[k]);
    for (int k = 0; k < 5; k++) {
        mpz_init(f->rb[k]);
        mpz_init(f->rc[k]);
    }
}

void vbx_tframe_reset(vbx_tframe *f)
{
    memset(f, 0, offsetof(vbx_tframe, gz));
}

void vbx_tframe_clear(vbx_tframe *f)
{
    for (int k = 0; k < 4; k++) {
        mpz_clear(f->gz[k]);
        mpz_clear(f->sz[k]);
        mpz_clear(f->ez[k]);
    }
    for (int k = 0; k < 6; k++)
        mpz_clear(f->mz[k]);
    for (int k = 0; k < 5; k++) {
        mpz_clear(f->rb[k]);
        mpz_clear(f->rc[k]);
    }
}

/* The axis e_k across which e1 = d_b x e_k is taken (collinear centres):
 * the smallest |component| of the exact d_b, the first on ties, so the
 * filter and the exact frame use the same functionals. */
static int circle_axis(mpz_t *db)
{
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (mpz_cmpabs(db[i], db[k]) < 0)
            k = i;
    return k;
}

/* The exact rows and the kind's exact decisions. Returns the kind. */
static int exact_kind(vbx_arcw *w, vbx_tframe *f, int *parabola, int *axis)
{
    mpz_t *z = w->z;
    const vbx_data *d = &w->c->d;
    vbx_row(d, f->t[0], f->t[1], f->rb, z[0]);
    vbx_row(d, f->t[0], f->t[2], f->rc, z[0]);
    mpz_t *n = &z[1]; /* z[1..3] */
    vbx_z_cross(f->rb, f->rc, n);
    *parabola = 0;
    if (mpz_sgn(n[0]) || mpz_sgn(n[1]) || mpz_sgn(n[2])) {
        /* A' = |n|^2 - |r_b d_c - r_c d_b|^2 */
        mpz_t *v = &z[4]; /* z[4..6] */
        for (int k = 0; k < 3; k++) {
            mpz_mul(v[k], f->rb[3], f->rc[k]);
            mpz_submul(v[k], f->rc[3], f->rb[k]);
        }
        vbx_z_dot3(z[7], n, n);
        vbx_z_dot3(z[8], v, v);
        int s = mpz_cmp(z[7], z[8]);
        *parabola = s == 0;
        return s >= 0 ? VBX_TRI_OPEN : VBX_TRI_CLOSED;
    }
    /* Collinear: Delta2 = beta r_c - gamma r_b with beta = d_b . d_b,
     * gamma = d_c . d_b. */
    vbx_z_dot3(z[4], f->rb, f->rb);
    vbx_z_dot3(z[5], f->rc, f->rb);
    mpz_mul(z[6], z[4], f->rc[3]);
    mpz_submul(z[6], z[5], f->rb[3]);
    *axis = circle_axis(f->rb);
    return mpz_sgn(z[6]) ? VBX_TRI_CIRCLE : VBX_TRI_NONE;
}

void vbx_tframe_exact(vbx_arcw *w, vbx_tframe *f)
{
    if (f->exact)
        return;
    mpz_t *z = w->z;
    /* rows were set by exact_kind when the kind needed them; redo them (cheap). */
    const vbx_data *d = &w->c->d;
    vbx_row(d, f->t[0], f->t[1], f->rb, z[0]);
    vbx_row(d, f->t[0], f->t[2], f->rc, z[0]);
    for (int k = 0; k < 6; k++) {
        int p = vbx_minor_cols[k][0], q = vbx_minor_cols[k][1];
        mpz_mul(f->mz[k], f->rb[p], f->rc[q]);
        mpz_submul(f->mz[k], f->rb[q], f->rc[p]);
    }
    for (int k = 0; k < 4; k++) {
        mpz_set_ui(f->gz[k], 0);
        mpz_set_ui(f->sz[k], 0);
        mpz_set_ui(f->ez[k], 0);
    }
    if (f->kind == VBX_TRI_CIRCLE) {
        mpz_t *e = &z[1], *e1 = &z[4];
        int ax = circle_axis(f->rb);
        for (int k = 0; k < 3; k++)
            mpz_set_ui(e[k], k == ax);
        vbx_z_cross(f->rb, e, e1);
        vbx_z_cross(f->rb, e1, f->gz);
        for (int k = 0; k < 3; k++)
            mpz_set(f->sz[k], e1[k]);
    } else {
        vbx_z_cross(f->rb, f->rc, f->gz);
        mpz_set_ui(f->sz[3], 1);
        /* The plane's S direction (up to a positive factor):
         * ([d_b d_c] adj(Gamma) (-r_b, -r_c), |n|^2), adj(Gamma) =
         * [[cc, -bc], [-bc, bb]]. */
        mpz_t *bb = &z[1], *bc = &z[2], *cc = &z[3], *al = &z[4], *be = &z[5];
        vbx_z_dot3(*bb, f->rb, f->rb);
        vbx_z_dot3(*bc, f->rb, f->rc);
        vbx_z_dot3(*cc, f->rc, f->rc);
        mpz_mul(*al, *bc, f->rc[3]);
        mpz_submul(*al, *cc, f->rb[3]);
        mpz_mul(*be, *bc, f->rb[3]);
        mpz_submul(*be, *bb, f->rc[3]);
        for (int k = 0; k < 3; k++) {
            mpz_mul(f->ez[k], *al, f->rb[k]);
            mpz_addmul(f->ez[k], *be, f->rc[k]);
        }
        vbx_z_dot3(f->ez[3], f->gz, f->gz);
    }
    f->exact = 1;
}

/* The filter frame of the plane (O, ES, EG) and the conic's data. */
static void filter_frame(vbx_tframe *f, const vbx_ia n[3])
{
    f->ok = 0;
    const vbx_ia *db = f->mb, *dc = f->mc;
    vbx_ia rb = f->mb[3], rc = f->mc[3];
    vbx_ia half_wb = vbx_ia_scale(f->Wb, 0.5), half_wc = vbx_ia_scale(f->Wc, 0.5);
    vbx_ia one = vbx_ia_point(1.0), zero = vbx_ia_point(0.0);
    if (f->kind == VBX_TRI_CIRCLE) {
        vbx_ia e1[3], e2[3];
        for (int k = 0; k < 3; k++)
            e1[k] = f->sf[k];
        for (int k = 0; k < 3; k++)
            e2[k] = f->gf[k];
        vbx_ia beta = vbx_ia_dot3(db, db), gamma = vbx_ia_dot3(dc, db);
        vbx_ia del2 = vbx_ia_det2(beta, gamma, rb, rc);
        if (!vbx_ia_sign(del2))
            return;
        vbx_ia two_del = vbx_ia_scale(del2, 2.0);
        vbx_ia zq = vbx_ia_div(vbx_ia_det2(f->Wb, rb, f->Wc, rc), two_del);
        vbx_ia os = vbx_ia_div(vbx_ia_det2(beta, gamma, f->Wb, f->Wc),
                               two_del);
        vbx_ia n1 = vbx_ia_dot3(e1, e1), n2 = vbx_ia_dot3(e2, e2);
        for (int k = 0; k < 3; k++) {
            f->O[k] = vbx_ia_mul(zq, db[k]);
            f->ES[k] = vbx_ia_div(e1[k], n1);
            f->EG[k] = vbx_ia_div(e2[k], n2);
        }
        f->O[3] = os;
        f->ES[3] = f->EG[3] = zero;
        vbx_ia f0 = vbx_ia_sub(vbx_ia_dot3(f->O, f->O), vbx_ia_sqr(os));
        vbx_ia rho = vbx_ia_neg(f0);
        if (!(rho.lo > 0.0))
            return;
        f->Sc = zero;
        f->ax = vbx_ia_sqrt(vbx_ia_mul(rho, n1));
        f->bx = vbx_ia_sqrt(vbx_ia_mul(rho, n2));
        f->ok = 1;
        return;
    }
    vbx_ia nn = vbx_ia_dot3(n, n);
    if (!(nn.lo > 0.0))
        return;
    vbx_ia bb = vbx_ia_dot3(db, db), bc = vbx_ia_dot3(db, dc), cc = vbx_ia_dot3(dc, dc);
    /* q = [d_b d_c] adj(Gamma) rhs / |n|^2 for rhs (W_b/2, W_c/2) and (-r_b, -r_c). */
    vbx_ia a0 = vbx_ia_div(vbx_ia_det2(cc, bc, half_wc, half_wb), nn);
    vbx_ia b0 = vbx_ia_div(vbx_ia_det2(bb, bc, half_wb, half_wc), nn);
    vbx_ia a1 = vbx_ia_div(vbx_ia_det2(bc, cc, rb, rc), nn);
    vbx_ia b1 = vbx_ia_div(vbx_ia_det2(bc, bb, rc, rb), nn);
    for (int k = 0; k < 3; k++) {
        f->O[k] = vbx_ia_add(vbx_ia_mul(a0, db[k]), vbx_ia_mul(b0, dc[k]));
        f->ES[k] = vbx_ia_add(vbx_ia_mul(a1, db[k]), vbx_ia_mul(b1, dc[k]));
        f->EG[k] = vbx_ia_div(n[k], nn);
    }
    f->O[3] = zero;
    f->ES[3] = one;
    f->EG[3] = zero;
    /* F(S, G) = Q(u) = |O_q + S ES_q|^2 + G^2 / |n|^2 - S^2 (the three
     * vectors of q are orthogonal to n, exactly). */
    vbx_ia fgg = vbx_ia_div(one, nn);
    vbx_ia fss = vbx_ia_sub(vbx_ia_dot3(f->ES, f->ES), one);
    vbx_ia fs = vbx_ia_scale(vbx_ia_dot3(f->O, f->ES), 2.0);
    vbx_ia f0 = vbx_ia_dot3(f->O, f->O);
    if (f->kind == VBX_TRI_OPEN) {
        if (f->parabola || !(fss.hi < 0.0))
            return;
        vbx_ia mfss = vbx_ia_neg(fss);
        f->Sc = vbx_ia_div(fs, vbx_ia_scale(mfss, 2.0));
        f->k = vbx_ia_sqrt(vbx_ia_div(fgg, mfss));
        f->cp = vbx_ia_div(vbx_ia_add(f0, vbx_ia_mul(mfss, vbx_ia_sqr(f->Sc))), mfss);
        if (!(f->cp.lo > 0.0) || !(f->k.lo > 0.0))
            return;
        f->Smin = vbx_ia_add(f->Sc, vbx_ia_sqrt(f->cp));
        f->mq = mfss;
        f->ok = 1;
        return;
    }
    if (!(fss.lo > 0.0))
        return;
    f->Sc = vbx_ia_neg(vbx_ia_div(fs, vbx_ia_scale(fss, 2.0)));
    vbx_ia rho = vbx_ia_sub(vbx_ia_mul(fss, vbx_ia_sqr(f->Sc)), f0);
    if (!(rho.lo > 0.0))
        return;
    f->ax = vbx_ia_sqrt(vbx_ia_div(rho, fss));
    f->bx = vbx_ia_sqrt(vbx_ia_div(rho, fgg));
    f->ok = 1;
}

/* Internally tangent pairs of a triple (one sphere touches the other from
 * inside: W = |c_x - c_y|^2 - (R_x - R_y)^2 = 0 exactly). The bisector of
 * such a pair is a ray: from the smaller centre, away from the larger one.
 * The tangent spheres of the triple lie on that ray and on the bisector of
 * another pair, a surface that holds no segment of the ray unless that
 * pair's bisector is a ray too, on the same line and overlapping it. So the
 * triple has a curve of tangent spheres (an edge can run along it) only
 * when two such rays overlap in more than a point, which needs collinear
 * centres; otherwise its tangent spheres are a few points, each a vertex
 * only through a fourth sphere whose other triples carry the edges.
 * Returns 1 for "a few points" (no edge along the triple), 0 otherwise.
 * Filter first, exact on doubt. */
static int tangent_pair_points(vbx_arcw *w, const vbx_tframe *f, int collinear_possible)
{
    vbx_ia mbc[4];
    vbx_ia_row(w, f->t[1], f->t[2], mbc);
    vbx_ia Wbc = vbx_ia_lorentz(mbc);
    w->cnt.filter_calls++;
    if (vbx_ia_sign(f->Wb) > 0 && vbx_ia_sign(f->Wc) > 0 && vbx_ia_sign(Wbc) > 0)
        return 0;
    w->cnt.filter_failures++;
    w->cnt.exact_evals++;
    mpz_t *z = w->z;
    const vbx_data *d = &w->c->d;
    static const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    mpz_t row[3][5], dir[3], start[3];
    for (int p = 0; p < 3; p++) {
        for (int k = 0; k < 5; k++)
            mpz_init(row[p][k]);
        mpz_init(dir[p]);
        mpz_init(start[p]);
        vbx_row(d, f->t[pairs[p][0]], f->t[pairs[p][1]], row[p], z[0]);
    }
    int tangent[3], ntangent = 0;
    for (int p = 0; p < 3; p++) {
        tangent[p] = !mpz_sgn(row[p][4]);
        ntangent += tangent[p];
    }
    int points = 0;
    if (ntangent > 0) {
        mpz_t *n = &z[1];
        int collinear = 0;
        if (collinear_possible) {
            vbx_z_cross(row[0], row[1], n);
            collinear = !mpz_sgn(n[0]) && !mpz_sgn(n[1]) && !mpz_sgn(n[2]);
        }
        points = 1;
        if (collinear && ntangent >= 2) {
            /* Positions along the line: D . p with D = c_b - c_a (not zero:
             * the spheres are distinct and a tangent pair has distinct
             * centres). Each ray starts at D . c_small and runs the way of
             * D . (c_small - c_large). */
            const mpz_t *D = row[0];
            for (int p = 0; p < 3; p++) {
                if (!tangent[p])
                    continue;
                uint32_t x = f->t[pairs[p][0]], y = f->t[pairs[p][1]];
                /* row[p] = c_y - c_x with R_y - R_x in slot 3: y is the
                 * larger when that is positive. */
                uint32_t small = mpz_sgn(row[p][3]) > 0 ? x : y;
                mpz_set_ui(start[p], 0);
                for (int k = 0; k < 3; k++)
                    mpz_addmul(start[p], D[k], d->c[4 * (size_t)small + (size_t)k]);
                mpz_set_ui(dir[p], 0);
                for (int k = 0; k < 3; k++)
                    mpz_addmul(dir[p], D[k], row[p][k]);
                /* dir of (c_small - c_large) is -(D . row) when small = x. */
                if (small == x)
                    mpz_neg(dir[p], dir[p]);
            }
            for (int p = 0; p < 3 && points; p++)
                for (int q = p + 1; q < 3 && points; q++) {
                    if (!tangent[p] || !tangent[q])
                        continue;
                    int sp = mpz_sgn(dir[p]), sq = mpz_sgn(dir[q]);
                    int c = mpz_cmp(start[p], start[q]);
                    /* Overlap beyond a point: same way, or facing each
                     * other from distinct starts. */
                    if (sp == sq || (sp > 0 && c < 0) || (sp < 0 && c > 0))
                        points = 0;
                }
        }
    }
    for (int p = 0; p < 3; p++) {
        for (int k = 0; k < 5; k++)
            mpz_clear(row[p][k]);
        mpz_clear(dir[p]);
        mpz_clear(start[p]);
    }
    return points;
}

int vbx_tframe_setup(vbx_arcw *w, vbx_tframe *f, const uint32_t t[3])
{
    int rc = vbx_tframe_setup_local(w, f, t);
    vbx_tframe_plane(f);
    return rc;
}

void vbx_tframe_plane(vbx_tframe *f)
{
    if (f->plane || f->kind == VBX_TRI_NONE)
        return;
    filter_frame(f, f->n);
    f->plane = 1;
}

int vbx_tframe_setup_local(vbx_arcw *w, vbx_tframe *f, const uint32_t t[3])
{
    f->plane = 0;
    f->exact = 0;
    f->ok = 0;
    f->parabola = 0;
    memcpy(f->t, t, sizeof f->t);
    vbx_ia_row(w, t[0], t[1], f->mb);
    vbx_ia_row(w, t[0], t[2], f->mc);
    f->Wb = vbx_ia_lorentz(f->mb);
    f->Wc = vbx_ia_lorentz(f->mc);
    for (int k = 0; k < 6; k++) {
        int p = vbx_minor_cols[k][0], q = vbx_minor_cols[k][1];
        f->minor[k] = vbx_ia_det2(f->mb[p], f->mb[q], f->mc[p], f->mc[q]);
    }
    /* n = d_b x d_c: three of the minors (columns 12, 02, 01), the very
     * operations vbx_ia_cross does (a negated difference is the difference
     * the other way round, bit for bit: pred(z) = -succ(-z)) */
    vbx_ia n[3] = {f->minor[3], vbx_ia_neg(f->minor[1]), f->minor[0]};
    int collinear_possible = !vbx_ia_sign(n[0]) && !vbx_ia_sign(n[1]) && !vbx_ia_sign(n[2]);
    int kind = -1, parabola = 0, axis = 0;
    w->cnt.filter_calls++;
    if (!collinear_possible) {
        vbx_ia v[3];
        for (int k = 0; k < 3; k++)
            v[k] = vbx_ia_det2(f->mb[3], f->mc[3], f->mb[k], f->mc[k]);
        vbx_ia x[6] = {n[0], n[1], n[2], vbx_ia_neg(v[0]), vbx_ia_neg(v[1]), vbx_ia_neg(v[2])};
        vbx_ia y[6] = {n[0], n[1], n[2], v[0], v[1], v[2]};
        int s = vbx_ia_sign(vb_ia_dot(x, y, 6));
        if (s)
            kind = s > 0 ? VBX_TRI_OPEN : VBX_TRI_CLOSED;
    }
    if (kind < 0 || collinear_possible) {
        w->cnt.filter_failures++;
        w->cnt.exact_evals++;
        kind = exact_kind(w, f, &parabola, &axis);
    }
    if (kind != VBX_TRI_NONE && tangent_pair_points(w, f, collinear_possible))
        kind = VBX_TRI_NONE;
    f->kind = kind;
    f->parabola = parabola;
    if (kind == VBX_TRI_NONE)
        return VB_OK;
    vbx_ia zero = vbx_ia_point(0.0);
    if (kind == VBX_TRI_CIRCLE) {
        vbx_ia e[3] = {zero, zero, zero}, e1[3], e2[3];
        e[axis] = vbx_ia_point(1.0);
        vbx_ia_cross(f->mb, e, e1);
        vbx_ia_cross(f->mb, e1, e2);
        for (int k = 0; k < 3; k++) {
            f->sf[k] = e1[k];
            f->gf[k] = e2[k];
        }
        f->sf[3] = f->gf[3] = zero;
    } else {
        for (int k = 0; k < 3; k++) {
            f->gf[k] = n[k];
            f->sf[k] = zero;
        }
        f->gf[3] = zero;
        f->sf[3] = vbx_ia_point(1.0);
    }
    for (int k = 0; k < 3; k++)
        f->n[k] = n[k];
    return VB_OK;
}

/* ---- positions ------------------------------------------------------------ */

void vbx_key_of_box(const vbx_arcw *w, const vbx_tframe *f, const vbx_ia box[4], vbx_key *k)
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_ia u[4];
    for (int i = 0; i < 3; i++)
        u[i] = vbx_ia_sub(box[i], ba[i]);
    u[3] = vbx_ia_add(box[3], ba[3]);
    k->G = vbx_ia_dot4(f->gf, u);
    k->S = vbx_ia_dot4(f->sf, u);
    if (f->kind == VBX_TRI_OPEN) {
        k->half = 0;
        k->val = k->G;
        return;
    }
    int sg = vbx_ia_sign(k->G);
    k->half = sg > 0 ? 1 : sg < 0 ? 3 : -1;
    k->val = sg > 0 ? vbx_ia_neg(k->S) : k->S;
}

/* sign(x - y) for x = Xn / dx, y = Yn / dy in Z[sqrt(d)] over positive dens. */
static int zs_cmp_frac(vbx_arcw *w, const vbx_zs *xn, const mpz_t dx, const mpz_t xd,
                       const vbx_zs *yn, const mpz_t dy, const mpz_t yd)
{
    mpz_t *z = w->z;
    /* xn dy - yn dx = (xa dy - ya dx) + xb dy sqrt(xd) - yb dx sqrt(yd) */
    mpz_mul(z[8], xn->a, dy);
    mpz_submul(z[8], yn->a, dx);
    mpz_mul(z[9], xn->b, dy);
    mpz_mul(z[10], yn->b, dx);
    mpz_neg(z[10], z[10]);
    return vbx_sign_two_sqrt(z[8], z[9], xd, z[10], yd, &z[11]);
}

int vbx_xpt_half(vbx_arcw *w, vbx_tframe *f, const vbx_xpt *x)
{
    mpz_t *z = w->z;
    int sg = vbx_zs_sign(&x->Gn, x->d, z[8], z[9]);
    if (sg)
        return sg > 0 ? 1 : 3;
    int side;
    if (f->kind == VBX_TRI_CIRCLE) {
        side = vbx_zs_sign(&x->Sn, x->d, z[8], z[9]);
    } else {
        /* sign(S - S_c) = sign(l . ES), l = (q, -s): F_S = 2 f_SS (S - S_c). */
        vbx_tframe_exact(w, f);
        vbx_zs *t = &w->zs[0];
        vbx_zs_dot_z(t, x->U, f->ez, 3);
        vbx_zs_submul_z(t, &x->U[3], f->ez[3]);
        side = vbx_zs_sign(t, x->d, z[8], z[9]);
    }
    return side >= 0 ? 0 : 2;
}

static int cmp_exact(vbx_arcw *w, vbx_tframe *f, const vbx_xpt *a, const vbx_xpt *b)
{
    w->cnt.exact_evals++;
    if (f->kind == VBX_TRI_OPEN)
        return zs_cmp_frac(w, &a->Gn, a->den, a->d, &b->Gn, b->den, b->d);
    int ha = vbx_xpt_half(w, f, a), hb = vbx_xpt_half(w, f, b);
    if (ha != hb)
        return ha < hb ? -1 : 1;
    if (ha == 0 || ha == 2)
        return 0;
    int c = zs_cmp_frac(w, &a->Sn, a->den, a->d, &b->Sn, b->den, b->d);
    return ha == 1 ? -c : c;
}

int vbx_pos_cmp(vbx_arcw *w, vbx_tframe *f, const vbx_key *ka, const vbx_xpt *xa,
                const vbx_key *kb, const vbx_xpt *xb)
{
    w->cnt.filter_calls++;
    if (ka->half >= 0 && kb->half >= 0) {
        if (ka->half != kb->half)
            return ka->half < kb->half ? -1 : 1;
        if (ka->val.hi < kb->val.lo)
            return -1;
        if (ka->val.lo > kb->val.hi)
            return 1;
    }
    w->cnt.filter_failures++;
    if (!xa || !xb)
        return 2;
    return cmp_exact(w, f, xa, xb);
}
