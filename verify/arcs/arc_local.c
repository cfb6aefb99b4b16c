/* Exact points on a trisector (of roots and of vertices) and the local test
 * of which arcs of a triple leave a vertex (vbx_arc.h). */
#include <stdlib.h>
#include <string.h>

#include "vbx_plane.h"

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
    vbx_zs_dot_z(&x->Gn, x->U, f->gz, 4);
    vbx_zs_dot_z(&x->Sn, x->U, f->sz, 4);
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
    vbx_zs_dot_z(dot, tau, row, 4);
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
    vbx_z_tau(f->mz, row, tj);
    for (int i = 0; i < 4; i++) {
        int st = vbx_zs_sign(&tau[i], x->d, z[12], z[13]);
        if (st)
            return st * mpz_sgn(tj[i]) > 0 ? 2 : 0;
    }
    return 0;
}

void vbx_tau_of_box(const vbx_arcw *w, const vbx_tframe *f, const vbx_ia box[4], vbx_ia tau[4])
{
    const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]];
    vbx_ia l[4];
    for (int i = 0; i < 3; i++)
        l[i] = vbx_ia_sub(box[i], ba[i]);
    l[3] = vbx_ia_neg(vbx_ia_add(box[3], ba[3]));
    vbx_ia_tau(f->minor, l, tau);
}

int vbx_local_arcs(vbx_arcw *w, vbx_tframe *f, const uint32_t *m, size_t nm,
                   const double xyzt[4], const vbx_ia box[4], const vbx_ia *tau_in, vbx_xpt *x,
                   int *have, int *fwd, int *bwd, uint64_t *extra)
{
    if (extra)
        *extra = 0;
    /* Filter: tau at the box, its orientation, each member's m_j . tau. */
    vbx_ia tau[4];
    if (tau_in)
        memcpy(tau, tau_in, sizeof tau);
    else
        vbx_tau_of_box(w, f, box, tau);
    int sigma = 0;
    w->cnt.filter_calls++;
    if (f->kind == VBX_TRI_OPEN) {
        sigma = vbx_ia_sign(vbx_ia_dot4(f->gf, tau));
    } else {
        vbx_key k;
        vbx_key_of_box(w, f, box, &k);
        int ss = vbx_ia_sign(vbx_ia_dot4(f->sf, tau));
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
        vbx_ia_row(w, f->t[0], m[i], mj);
        w->cnt.filter_calls++;
        int s = vbx_ia_sign(vbx_ia_dot4(mj, tau));
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
    vbx_zs_tau(w, f->mz, lz, tz);
    mpz_t *z = w->z;
    vbx_zs *dot = &w->zs[1];
    int es = 0;
    if (f->kind == VBX_TRI_OPEN) {
        vbx_zs_dot_z(dot, tz, f->gz, 4);
        es = vbx_zs_sign(dot, x->d, z[12], z[13]);
    } else {
        int h = vbx_xpt_half(w, f, x);
        vbx_zs_dot_z(dot, tz, (h == 1 || h == 3) ? f->sz : f->gz, 4);
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
