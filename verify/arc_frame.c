/* The trisector of a triple as a conic (vbx_arc.h): its kind, its
 * coordinates G and S, positions of points on it, exact points of vertices
 * and roots, and the local test of which arcs leave a vertex. */
#include <stdlib.h>
#include <string.h>

#include "vbx_arc.h"

/* Columns of the six 2x2 minors, and for each column i the three others. */
static const int minor_cols[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
static const int other_cols[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

static int minor_at(int p, int q)
{
    for (int k = 0; k < 6; k++)
        if (minor_cols[k][0] == p && minor_cols[k][1] == q)
            return k;
    return -1;
}

/* ---- interval helpers ----------------------------------------------------- */

static vbx_ia ia_dot3(const vbx_ia *a, const vbx_ia *b)
{
    vbx_ia r = vbx_ia_mul(a[0], b[0]);
    r = vbx_ia_add(r, vbx_ia_mul(a[1], b[1]));
    return vbx_ia_add(r, vbx_ia_mul(a[2], b[2]));
}

static vbx_ia ia_dot4(const vbx_ia *a, const vbx_ia *b)
{
    return vbx_ia_add(ia_dot3(a, b), vbx_ia_mul(a[3], b[3]));
}

static void ia_cross(const vbx_ia *a, const vbx_ia *b, vbx_ia *r)
{
    r[0] = vbx_ia_sub(vbx_ia_mul(a[1], b[2]), vbx_ia_mul(a[2], b[1]));
    r[1] = vbx_ia_sub(vbx_ia_mul(a[2], b[0]), vbx_ia_mul(a[0], b[2]));
    r[2] = vbx_ia_sub(vbx_ia_mul(a[0], b[1]), vbx_ia_mul(a[1], b[0]));
}

static vbx_ia ia_scale(vbx_ia a, double s)
{
    return vbx_ia_mul(a, vbx_ia_point(s));
}

/* The generalised cross product tau of the rows m_b, m_c (through their
 * minors) and l: x . tau = det[x; m_b; m_c; l] for every x (Laplace along
 * the first row; the third row of each 3x3 minor is l). */
static void ia_tau(const vbx_ia minor[6], const vbx_ia l[4], vbx_ia tau[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = other_cols[i];
        vbx_ia t = vbx_ia_mul(l[c[0]], minor[minor_at(c[1], c[2])]);
        t = vbx_ia_sub(t, vbx_ia_mul(l[c[1]], minor[minor_at(c[0], c[2])]));
        t = vbx_ia_add(t, vbx_ia_mul(l[c[2]], minor[minor_at(c[0], c[1])]));
        tau[i] = (i & 1) ? vbx_ia_neg(t) : t;
    }
}

/* Row m_j = (c_j - c_a, R_j - R_a) over the enclosures, input units. */
static void ia_row(const vbx_arcw *w, uint32_t a, uint32_t j, vbx_ia m[4])
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)a], *bj = &w->c->d.box[4 * (size_t)j];
    for (int k = 0; k < 4; k++)
        m[k] = vbx_ia_sub(bj[k], ba[k]);
}

/* ---- exact helpers -------------------------------------------------------- */

/* tau from exact minors and l in Z[sqrt(d)]^4 (same formula as ia_tau). */
static void zs_tau(vbx_arcw *w, mpz_t minor[6], const vbx_zs l[4], vbx_zs tau[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = other_cols[i];
        mpz_set_ui(tau[i].a, 0);
        mpz_set_ui(tau[i].b, 0);
        vbx_zs_addmul_z(&tau[i], &l[c[0]], minor[minor_at(c[1], c[2])]);
        vbx_zs_submul_z(&tau[i], &l[c[1]], minor[minor_at(c[0], c[2])]);
        vbx_zs_addmul_z(&tau[i], &l[c[2]], minor[minor_at(c[0], c[1])]);
        if (i & 1) {
            mpz_neg(tau[i].a, tau[i].a);
            mpz_neg(tau[i].b, tau[i].b);
        }
    }
    (void)w;
}

/* tau for an integer third row x (the direction of {x . u = const} in the
 * plane): out[i] integers. */
static void z_tau(mpz_t minor[6], mpz_t *x, mpz_t out[4])
{
    for (int i = 0; i < 4; i++) {
        const int *c = other_cols[i];
        mpz_mul(out[i], x[c[0]], minor[minor_at(c[1], c[2])]);
        mpz_submul(out[i], x[c[1]], minor[minor_at(c[0], c[2])]);
        mpz_addmul(out[i], x[c[2]], minor[minor_at(c[0], c[1])]);
        if (i & 1)
            mpz_neg(out[i], out[i]);
    }
}

/* r = sum_k z[k] x[k] over k < n. */
static void zs_dot_z(vbx_zs *r, const vbx_zs *x, mpz_t *z, int n)
{
    mpz_set_ui(r->a, 0);
    mpz_set_ui(r->b, 0);
    for (int k = 0; k < n; k++)
        vbx_zs_addmul_z(r, &x[k], z[k]);
}

static void z_cross(mpz_t *a, mpz_t *b, mpz_t *r)
{
    mpz_mul(r[0], a[1], b[2]);
    mpz_submul(r[0], a[2], b[1]);
    mpz_mul(r[1], a[2], b[0]);
    mpz_submul(r[1], a[0], b[2]);
    mpz_mul(r[2], a[0], b[1]);
    mpz_submul(r[2], a[1], b[0]);
}

static void z_dot3(mpz_t r, mpz_t *a, mpz_t *b)
{
    mpz_mul(r, a[0], b[0]);
    mpz_addmul(r, a[1], b[1]);
    mpz_addmul(r, a[2], b[2]);
}

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
    z_cross(f->rb, f->rc, n);
    *parabola = 0;
    if (mpz_sgn(n[0]) || mpz_sgn(n[1]) || mpz_sgn(n[2])) {
        /* A' = |n|^2 - |r_b d_c - r_c d_b|^2 */
        mpz_t *v = &z[4]; /* z[4..6] */
        for (int k = 0; k < 3; k++) {
            mpz_mul(v[k], f->rb[3], f->rc[k]);
            mpz_submul(v[k], f->rc[3], f->rb[k]);
        }
        z_dot3(z[7], n, n);
        z_dot3(z[8], v, v);
        int s = mpz_cmp(z[7], z[8]);
        *parabola = s == 0;
        return s >= 0 ? VBX_TRI_OPEN : VBX_TRI_CLOSED;
    }
    /* Collinear: Delta2 = beta r_c - gamma r_b with beta = d_b . d_b,
     * gamma = d_c . d_b. */
    z_dot3(z[4], f->rb, f->rb);
    z_dot3(z[5], f->rc, f->rb);
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
        int p = minor_cols[k][0], q = minor_cols[k][1];
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
        z_cross(f->rb, e, e1);
        z_cross(f->rb, e1, f->gz);
        for (int k = 0; k < 3; k++)
            mpz_set(f->sz[k], e1[k]);
    } else {
        z_cross(f->rb, f->rc, f->gz);
        mpz_set_ui(f->sz[3], 1);
        /* The plane's S direction (up to a positive factor):
         * ([d_b d_c] adj(Gamma) (-r_b, -r_c), |n|^2), adj(Gamma) =
         * [[cc, -bc], [-bc, bb]]. */
        mpz_t *bb = &z[1], *bc = &z[2], *cc = &z[3], *al = &z[4], *be = &z[5];
        z_dot3(*bb, f->rb, f->rb);
        z_dot3(*bc, f->rb, f->rc);
        z_dot3(*cc, f->rc, f->rc);
        mpz_mul(*al, *bc, f->rc[3]);
        mpz_submul(*al, *cc, f->rb[3]);
        mpz_mul(*be, *bc, f->rb[3]);
        mpz_submul(*be, *bb, f->rc[3]);
        for (int k = 0; k < 3; k++) {
            mpz_mul(f->ez[k], *al, f->rb[k]);
            mpz_addmul(f->ez[k], *be, f->rc[k]);
        }
        z_dot3(f->ez[3], f->gz, f->gz);
    }
    f->exact = 1;
}

/* The filter frame of the plane (O, ES, EG) and the conic's data. */
static void filter_frame(vbx_tframe *f, const vbx_ia n[3])
{
    f->ok = 0;
    const vbx_ia *db = f->mb, *dc = f->mc;
    vbx_ia rb = f->mb[3], rc = f->mc[3];
    vbx_ia half_wb = ia_scale(f->Wb, 0.5), half_wc = ia_scale(f->Wc, 0.5);
    vbx_ia one = vbx_ia_point(1.0), zero = vbx_ia_point(0.0);
    if (f->kind == VBX_TRI_CIRCLE) {
        vbx_ia e1[3], e2[3];
        for (int k = 0; k < 3; k++)
            e1[k] = f->sf[k];
        for (int k = 0; k < 3; k++)
            e2[k] = f->gf[k];
        vbx_ia beta = ia_dot3(db, db), gamma = ia_dot3(dc, db);
        vbx_ia del2 = vbx_ia_sub(vbx_ia_mul(beta, rc), vbx_ia_mul(gamma, rb));
        if (!vbx_ia_sign(del2))
            return;
        vbx_ia two_del = ia_scale(del2, 2.0);
        vbx_ia zq = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(f->Wb, rc), vbx_ia_mul(rb, f->Wc)), two_del);
        vbx_ia os = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(beta, f->Wc), vbx_ia_mul(gamma, f->Wb)),
                               two_del);
        vbx_ia n1 = ia_dot3(e1, e1), n2 = ia_dot3(e2, e2);
        for (int k = 0; k < 3; k++) {
            f->O[k] = vbx_ia_mul(zq, db[k]);
            f->ES[k] = vbx_ia_div(e1[k], n1);
            f->EG[k] = vbx_ia_div(e2[k], n2);
        }
        f->O[3] = os;
        f->ES[3] = f->EG[3] = zero;
        vbx_ia f0 = vbx_ia_sub(ia_dot3(f->O, f->O), vbx_ia_sqr(os));
        vbx_ia rho = vbx_ia_neg(f0);
        if (!(rho.lo > 0.0))
            return;
        f->Sc = zero;
        f->ax = vbx_ia_sqrt(vbx_ia_mul(rho, n1));
        f->bx = vbx_ia_sqrt(vbx_ia_mul(rho, n2));
        f->ok = 1;
        return;
    }
    vbx_ia nn = ia_dot3(n, n);
    if (!(nn.lo > 0.0))
        return;
    vbx_ia bb = ia_dot3(db, db), bc = ia_dot3(db, dc), cc = ia_dot3(dc, dc);
    /* q = [d_b d_c] adj(Gamma) rhs / |n|^2 for rhs (W_b/2, W_c/2) and (-r_b, -r_c). */
    vbx_ia a0 = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(cc, half_wb), vbx_ia_mul(bc, half_wc)), nn);
    vbx_ia b0 = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(bb, half_wc), vbx_ia_mul(bc, half_wb)), nn);
    vbx_ia a1 = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(bc, rc), vbx_ia_mul(cc, rb)), nn);
    vbx_ia b1 = vbx_ia_div(vbx_ia_sub(vbx_ia_mul(bc, rb), vbx_ia_mul(bb, rc)), nn);
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
    vbx_ia fss = vbx_ia_sub(ia_dot3(f->ES, f->ES), one);
    vbx_ia fs = ia_scale(ia_dot3(f->O, f->ES), 2.0);
    vbx_ia f0 = ia_dot3(f->O, f->O);
    if (f->kind == VBX_TRI_OPEN) {
        if (f->parabola || !(fss.hi < 0.0))
            return;
        vbx_ia mfss = vbx_ia_neg(fss);
        f->Sc = vbx_ia_div(fs, ia_scale(mfss, 2.0));
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
    f->Sc = vbx_ia_neg(vbx_ia_div(fs, ia_scale(fss, 2.0)));
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
    ia_row(w, f->t[1], f->t[2], mbc);
    vbx_ia Wbc = vbx_ia_sub(ia_dot3(mbc, mbc), vbx_ia_sqr(mbc[3]));
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
            z_cross(row[0], row[1], n);
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
    f->exact = 0;
    f->ok = 0;
    f->parabola = 0;
    memcpy(f->t, t, sizeof f->t);
    ia_row(w, t[0], t[1], f->mb);
    ia_row(w, t[0], t[2], f->mc);
    f->Wb = vbx_ia_sub(ia_dot3(f->mb, f->mb), vbx_ia_sqr(f->mb[3]));
    f->Wc = vbx_ia_sub(ia_dot3(f->mc, f->mc), vbx_ia_sqr(f->mc[3]));
    for (int k = 0; k < 6; k++) {
        int p = minor_cols[k][0], q = minor_cols[k][1];
        f->minor[k] = vbx_ia_sub(vbx_ia_mul(f->mb[p], f->mc[q]), vbx_ia_mul(f->mb[q], f->mc[p]));
    }
    vbx_ia n[3];
    ia_cross(f->mb, f->mc, n);
    int collinear_possible = !vbx_ia_sign(n[0]) && !vbx_ia_sign(n[1]) && !vbx_ia_sign(n[2]);
    int kind = -1, parabola = 0, axis = 0;
    w->cnt.filter_calls++;
    if (!collinear_possible) {
        vbx_ia v[3];
        for (int k = 0; k < 3; k++)
            v[k] = vbx_ia_sub(vbx_ia_mul(f->mb[3], f->mc[k]), vbx_ia_mul(f->mc[3], f->mb[k]));
        int s = vbx_ia_sign(vbx_ia_sub(ia_dot3(n, n), ia_dot3(v, v)));
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
        ia_cross(f->mb, e, e1);
        ia_cross(f->mb, e1, e2);
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
    filter_frame(f, n);
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
    k->G = ia_dot4(f->gf, u);
    k->S = ia_dot4(f->sf, u);
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
        zs_dot_z(t, x->U, f->ez, 3);
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

/* ---- exact points --------------------------------------------------------- */

void vbx_xpt_of_root(vbx_arcw *w, vbx_tframe *f, const vbx_solver *s, const vbx_root *r,
                     vbx_xpt *x)
{
    vbx_tframe_exact(w, f);
    const vbx_data *d = &w->c->d;
    uint32_t a = f->t[0], base = s->base;
    mpz_set(x->d, s->delta);
    mpz_set(x->den, r->den);
    mpz_t *z = w->z;
    for (int k = 0; k < 4; k++) {
        mpz_set(x->U[k].a, r->a[k]);
        mpz_set(x->U[k].b, r->b[k]);
    }
    if (base != a) {
        /* q_a = q_base + (c_base - c_a), s_a = s_base + R_a - R_base. */
        for (int k = 0; k < 3; k++) {
            mpz_sub(z[0], d->c[4 * (size_t)base + k], d->c[4 * (size_t)a + k]);
            mpz_addmul(x->U[k].a, z[0], r->den);
        }
        mpz_sub(z[0], d->c[4 * (size_t)a + 3], d->c[4 * (size_t)base + 3]);
        mpz_addmul(x->U[3].a, z[0], r->den);
    }
    zs_dot_z(&x->Gn, x->U, f->gz, 4);
    zs_dot_z(&x->Sn, x->U, f->sz, 4);
}

static void sort4(uint32_t q[4])
{
    for (int i = 1; i < 4; i++)
        for (int k = i; k > 0 && q[k - 1] > q[k]; k--) {
            uint32_t t = q[k];
            q[k] = q[k - 1];
            q[k - 1] = t;
        }
}

static int in_triple(const uint32_t t[3], uint32_t j)
{
    return j == t[0] || j == t[1] || j == t[2];
}

int vbx_xpt_of_vertex(vbx_arcw *w, vbx_tframe *f, const uint32_t *m, size_t nm,
                      const double xyzt[4], vbx_xpt *x)
{
    w->cnt.exact_evals++;
    for (size_t i = 0; i < nm; i++) {
        if (in_triple(f->t, m[i]))
            continue;
        uint32_t q[4] = {f->t[0], f->t[1], f->t[2], m[i]};
        sort4(q);
        if (vbx_solve(&w->sv, q[0], q + 1) != VBX_SOLVED || w->sv.nroots == 0)
            continue;
        int hit = -1, hits = 0;
        for (int r = 0; r < w->sv.nroots; r++) {
            double out[4];
            vbx_ia box[4];
            if (vbx_root_coords(&w->sv, &w->sv.root[r], out, box) != VB_OK)
                continue;
            if (out[0] == xyzt[0] && out[1] == xyzt[1] && out[2] == xyzt[2] &&
                out[3] == xyzt[3]) {
                hit = r;
                hits++;
            }
        }
        if (hits == 1) {
            vbx_xpt_of_root(w, f, &w->sv, &w->sv.root[hit], x);
            return 1;
        }
        if (hits > 1)
            return 0; /* two exact points round alike: cannot tell which */
    }
    return 0;
}

/* ---- the local test ------------------------------------------------------- */

/* Exact local test of member j (row mj, exact): +1 when j is outside just
 * forward of the vertex, -1 just backward, 2 both ways (identically zero on
 * the plane: *ident set; or touching tangentially from outside), 0 neither.
 * tau is the exact tangent at the vertex, sigma its orientation. */
static int exact_member(vbx_arcw *w, vbx_tframe *f, const vbx_xpt *x, const vbx_zs tau[4],
                        int sigma, uint32_t j, int *ident)
{
    mpz_t *z = w->z;
    mpz_t *row = &z[0]; /* z[0..4] */
    vbx_row(&w->c->d, f->t[0], j, row, z[5]);
    vbx_zs *dot = &w->zs[1];
    zs_dot_z(dot, tau, row, 4);
    int s = vbx_zs_sign(dot, x->d, z[6], z[7]);
    *ident = 0;
    if (s)
        return sigma * s < 0 ? 1 : -1;
    /* L_j's line is tangent to the conic here, or L_j vanishes on the plane:
     * the 3x3 minors of the augmented rows (b, c, j) over 5 columns. */
    int zero = 1;
    for (int a = 0; a < 5 && zero; a++)
        for (int b = a + 1; b < 5 && zero; b++)
            for (int c = b + 1; c < 5 && zero; c++) {
                mpz_t *r1 = f->rb, *r2 = f->rc;
                mpz_mul(z[6], r1[b], r2[c]);
                mpz_submul(z[6], r1[c], r2[b]);
                mpz_mul(z[7], row[a], z[6]);
                mpz_mul(z[6], r1[a], r2[c]);
                mpz_submul(z[6], r1[c], r2[a]);
                mpz_submul(z[7], row[b], z[6]);
                mpz_mul(z[6], r1[a], r2[b]);
                mpz_submul(z[6], r1[b], r2[a]);
                mpz_addmul(z[7], row[c], z[6]);
                zero = mpz_sgn(z[7]) == 0;
            }
    if (zero) {
        *ident = 1;
        return 2;
    }
    /* Tangent: near the vertex L_j has the sign of mu where m_j = mu l on
     * the plane's directions, i.e. tau_j = mu tau for tau_j = cross(m_b,
     * m_c, m_j) (vbx_arc.h: the curve bends into K = {Q < 0}). */
    mpz_t *tj = &z[8]; /* z[8..11] */
    z_tau(f->mz, row, tj);
    for (int i = 0; i < 4; i++) {
        int st = vbx_zs_sign(&tau[i], x->d, z[12], z[13]);
        if (st)
            return st * mpz_sgn(tj[i]) > 0 ? 2 : 0;
    }
    return 0;
}

int vbx_local_arcs(vbx_arcw *w, vbx_tframe *f, const uint32_t *m, size_t nm,
                   const double xyzt[4], const vbx_ia box[4], vbx_xpt *x, int *have, int *fwd,
                   int *bwd, uint64_t *extra)
{
    if (extra)
        *extra = 0;
    /* Filter: tau at the box, its orientation, each member's m_j . tau. */
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_ia l[4], tau[4];
    for (int i = 0; i < 3; i++)
        l[i] = vbx_ia_sub(box[i], ba[i]);
    l[3] = vbx_ia_neg(vbx_ia_add(box[3], ba[3]));
    ia_tau(f->minor, l, tau);
    int sigma = 0;
    w->cnt.filter_calls++;
    if (f->kind == VBX_TRI_OPEN) {
        sigma = vbx_ia_sign(ia_dot4(f->gf, tau));
    } else {
        vbx_key k;
        vbx_key_of_box(w, f, box, &k);
        int ss = vbx_ia_sign(ia_dot4(f->sf, tau));
        if (k.half == 1)
            sigma = -ss;
        else if (k.half == 3)
            sigma = ss;
    }
    int f_ok = 1, b_ok = 1, need_exact = sigma == 0;
    uint64_t open_bits = 0;
    size_t nx = 0;
    for (size_t i = 0; i < nm && !need_exact; i++) {
        if (in_triple(f->t, m[i]))
            continue;
        vbx_ia mj[4];
        ia_row(w, f->t[0], m[i], mj);
        w->cnt.filter_calls++;
        int s = vbx_ia_sign(ia_dot4(mj, tau));
        if (s == 0) {
            w->cnt.filter_failures++;
            if (nx < 64)
                open_bits |= 1ull << nx;
            else
                need_exact = 1;
        } else if (sigma * s < 0) {
            b_ok = 0;
        } else {
            f_ok = 0;
        }
        nx++;
    }
    if (!need_exact && open_bits == 0) {
        *fwd = f_ok;
        *bwd = b_ok;
        return VB_OK;
    }
    if (!need_exact && !f_ok && !b_ok) {
        /* Both ways cut by members the filter decided: nothing else matters. */
        *fwd = *bwd = 0;
        return VB_OK;
    }
    if (sigma == 0)
        w->cnt.filter_failures++;
    /* Exact: the point, tau, sigma, then every member again (simple, rare). */
    if (!*have) {
        if (!vbx_xpt_of_vertex(w, f, m, nm, xyzt, x))
            return VB_EDEGENERATE;
        *have = 1;
    }
    vbx_tframe_exact(w, f);
    w->cnt.exact_evals++;
    vbx_zs *lz = &w->zs[4]; /* zs[4..7] as l */
    for (int i = 0; i < 3; i++) {
        mpz_set(lz[i].a, x->U[i].a);
        mpz_set(lz[i].b, x->U[i].b);
    }
    mpz_neg(lz[3].a, x->U[3].a);
    mpz_neg(lz[3].b, x->U[3].b);
    vbx_zs tz[4];
    for (int i = 0; i < 4; i++)
        vbx_zs_init(&tz[i]);
    zs_tau(w, f->mz, lz, tz);
    mpz_t *z = w->z;
    vbx_zs *dot = &w->zs[1];
    int es = 0;
    if (f->kind == VBX_TRI_OPEN) {
        zs_dot_z(dot, tz, f->gz, 4);
        es = vbx_zs_sign(dot, x->d, z[12], z[13]);
    } else {
        int h = vbx_xpt_half(w, f, x);
        zs_dot_z(dot, tz, (h == 1 || h == 3) ? f->sz : f->gz, 4);
        int s = vbx_zs_sign(dot, x->d, z[12], z[13]);
        es = h == 1 ? -s : h == 3 ? s : h == 0 ? s : -s;
    }
    int rc = VB_OK;
    if (es == 0) {
        rc = VB_EDEGENERATE; /* the conic's tangent vanishes: a singular point */
    } else {
        f_ok = b_ok = 1;
        size_t ix = 0;
        for (size_t i = 0; i < nm && (f_ok || b_ok); i++) {
            if (in_triple(f->t, m[i]))
                continue;
            int ident;
            int s = exact_member(w, f, x, tz, es, m[i], &ident);
            if (ident && extra && ix < 64)
                *extra |= 1ull << ix;
            if (s == 1)
                b_ok = 0;
            else if (s == -1)
                f_ok = 0;
            else if (s == 0)
                f_ok = b_ok = 0;
            ix++;
        }
        *fwd = f_ok;
        *bwd = b_ok;
    }
    for (int i = 0; i < 4; i++)
        vbx_zs_clear(&tz[i]);
    return rc;
}
