/* Bivariate Taylor models in interval arithmetic (vbm_series.h). */
#include "vbm_series.h"

void vbm_const(vbm_ser *f, vbx_ia v)
{
    for (int k = 0; k < VBM_NC; k++)
        f->c[k] = vbx_ia_point(0.0);
    f->c[0] = v;
}

void vbm_var(vbm_ser *f, vbx_ia at, int which)
{
    vbm_const(f, at);
    f->c[which ? VBM_IDX(0, 1) : VBM_IDX(1, 0)] = vbx_ia_point(1.0);
}

void vbm_add(vbm_ser *r, const vbm_ser *f, const vbm_ser *g)
{
    for (int k = 0; k < VBM_NC; k++)
        r->c[k] = vbx_ia_add(f->c[k], g->c[k]);
}

void vbm_sub(vbm_ser *r, const vbm_ser *f, const vbm_ser *g)
{
    for (int k = 0; k < VBM_NC; k++)
        r->c[k] = vbx_ia_sub(f->c[k], g->c[k]);
}

void vbm_affine(vbm_ser *r, vbx_ia v, const vbm_ser *f, vbx_ia w)
{
    for (int k = 0; k < VBM_NC; k++)
        r->c[k] = f->c[k].lo == 0.0 && f->c[k].hi == 0.0 ? f->c[k] : vbx_ia_mul(v, f->c[k]);
    r->c[0] = vbx_ia_add(r->c[0], w);
}

/* sum over (k, l) <= (i, j), (k, l) not in {skip1, skip2}, of f_kl g_(i-k)(j-l) */
static vbx_ia conv(const vbm_ser *f, const vbm_ser *g, int i, int j, int skip_lo, int skip_hi)
{
    vbx_ia s = vbx_ia_point(0.0);
    for (int k = 0; k <= i; k++)
        for (int l = 0; l <= j; l++) {
            int kl = VBM_IDX(k, l);
            if (kl == skip_lo || kl == skip_hi)
                continue;
            vbx_ia x = f->c[kl], y = g->c[VBM_IDX(i - k, j - l)];
            /* exact zeros (a variable's, a function of one variable's) add nothing */
            if ((x.lo == 0.0 && x.hi == 0.0) || (y.lo == 0.0 && y.hi == 0.0))
                continue;
            s = vbx_ia_add(s, vbx_ia_mul(x, y));
        }
    return s;
}

void vbm_mul(vbm_ser *r, const vbm_ser *f, const vbm_ser *g)
{
    for (int d = 0; d <= VBM_ORDER; d++)
        for (int j = 0; j <= d; j++)
            r->c[VBM_IDX(d - j, j)] = conv(f, g, d - j, j, -1, -1);
}

/* sum over (k, l) <= (i, j) of f_kl f_(i-k)(j-l), each pair of mirrored
 * terms computed once and doubled (exact), the middle one (2k = i, 2l = j)
 * once; skip_end leaves out the pair {(0, 0), (i, j)} (the square root's
 * unknown). Half the products of conv(f, f, ...). */
static vbx_ia conv_sym(const vbm_ser *f, int i, int j, int skip_end)
{
    vbx_ia s = vbx_ia_point(0.0), mid = vbx_ia_point(0.0);
    for (int k = 0; 2 * k <= i; k++)
        for (int l = 0; l <= j; l++) {
            int k2 = i - k, l2 = j - l;
            if (k == k2 && l > l2)
                break; /* the mirror of a pair already counted */
            if (skip_end && k == 0 && l == 0)
                continue;
            vbx_ia x = f->c[VBM_IDX(k, l)], y = f->c[VBM_IDX(k2, l2)];
            if ((x.lo == 0.0 && x.hi == 0.0) || (y.lo == 0.0 && y.hi == 0.0))
                continue;
            if (k == k2 && l == l2)
                mid = vbx_ia_sqr(x);
            else
                s = vbx_ia_add(s, vbx_ia_mul(x, y));
        }
    s.lo *= 2.0; /* exact: a power-of-two scaling */
    s.hi *= 2.0;
    return vbx_ia_add(s, mid);
}

void vbm_square(vbm_ser *r, const vbm_ser *f)
{
    for (int d = 0; d <= VBM_ORDER; d++)
        for (int j = 0; j <= d; j++)
            r->c[VBM_IDX(d - j, j)] = conv_sym(f, d - j, j, 0);
    r->c[0] = vbx_ia_sqr(f->c[0]);
}

int vbm_recip(vbm_ser *r, const vbm_ser *f)
{
    if (!(f->c[0].lo > 0.0 || f->c[0].hi < 0.0))
        return 0;
    vbx_ia one = vbx_ia_point(1.0);
    r->c[0] = vbx_ia_div(one, f->c[0]);
    /* f r = 1: sum_{(k,l)} f_kl r_(i-k)(j-l) = 0 for (i, j) != 0, solved for
     * r_ij by increasing total degree (the terms use lower degrees only). */
    for (int d = 1; d <= VBM_ORDER; d++)
        for (int j = 0; j <= d; j++) {
            int i = d - j;
            /* f_00 r_ij is the term left out (k = l = 0) */
            vbx_ia s = conv(f, r, i, j, 0, -1);
            r->c[VBM_IDX(i, j)] = vbx_ia_div(vbx_ia_neg(s), f->c[0]);
        }
    return 1;
}

int vbm_sqrt(vbm_ser *r, const vbm_ser *f)
{
    if (!(f->c[0].lo > 0.0))
        return 0;
    r->c[0] = vbx_ia_sqrt(f->c[0]);
    vbx_ia two_r0 = vbx_ia_add(r->c[0], r->c[0]);
    /* r r = f: 2 r_00 r_ij = f_ij - sum of the other products (those of
     * lower degree), by increasing total degree. */
    for (int d = 1; d <= VBM_ORDER; d++)
        for (int j = 0; j <= d; j++) {
            int i = d - j;
            int ij = VBM_IDX(i, j);
            vbx_ia s = conv_sym(r, i, j, 1);
            r->c[ij] = vbx_ia_div(vbx_ia_sub(f->c[ij], s), two_r0);
        }
    return 1;
}

/* The integral of x^i over [-h, h]: 2 h^(i+1) / (i + 1) for even i, 0 for odd
 * i; `abs` gives that of |x|^i instead (2 h^(i+1) / (i + 1) for every i). */
static vbx_ia moment(double h, int i, int abs)
{
    if (!abs && (i & 1))
        return vbx_ia_point(0.0);
    vbx_ia p = vbx_ia_point(2.0 * h); /* exact: a power-of-two scaling */
    for (int k = 0; k < i; k++)
        p = vbx_ia_mul(p, vbx_ia_point(h));
    return vbx_ia_div(p, vbx_ia_point((double)(i + 1)));
}

vbx_ia vbm_integrate(const vbm_ser *centre, const vbm_ser *box, double ha, double hb)
{
    vbx_ia s = vbx_ia_point(0.0);
    for (int d = 0; d < VBM_ORDER; d++)
        for (int j = 0; j <= d; j++) {
            int i = d - j;
            if ((i & 1) || (j & 1))
                continue;
            vbx_ia m = vbx_ia_mul(moment(ha, i, 0), moment(hb, j, 0));
            s = vbx_ia_add(s, vbx_ia_mul(centre->c[VBM_IDX(i, j)], m));
        }
    /* Remainder: c(xi(x, y)) x^i y^j with c in C = box coefficient. Where
     * x^i y^j >= 0 on the whole box (i and j even) the integral is in C M;
     * otherwise the monomial is positive on half the box by measure and
     * negative on the other half with the same mass P = |M| / 2, so the
     * integral is in C P - C P = [-(C.hi - C.lo) P, (C.hi - C.lo) P]. */
    for (int j = 0; j <= VBM_ORDER; j++) {
        int i = VBM_ORDER - j;
        vbx_ia c = box->c[VBM_IDX(i, j)];
        vbx_ia m = vbx_ia_mul(moment(ha, i, 1), moment(hb, j, 1));
        if (!(i & 1) && !(j & 1)) {
            s = vbx_ia_add(s, vbx_ia_mul(c, m));
        } else {
            vbx_ia p = vbx_ia_mul(m, vbx_ia_point(0.5));
            s = vbx_ia_add(s, vbx_ia_sub(vbx_ia_mul(c, p), vbx_ia_mul(c, p)));
        }
    }
    return s;
}
