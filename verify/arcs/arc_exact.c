/* Exact numbers of arc closure: Z[sqrt(d)], signs with two square roots,
 * exact points on a trisector, and the per-thread worker (vbx_arc.h). */
#include <stdlib.h>
#include <string.h>

#include "vbx_arc.h"

void vbx_zs_init(vbx_zs *x)
{
    mpz_init(x->a);
    mpz_init(x->b);
}

void vbx_zs_clear(vbx_zs *x)
{
    mpz_clear(x->a);
    mpz_clear(x->b);
}

void vbx_zs_mul(vbx_zs *r, const vbx_zs *x, const vbx_zs *y, const mpz_t d, mpz_t tmp)
{
    /* (xa + xb s)(ya + yb s) = xa ya + xb yb d + (xa yb + xb ya) s */
    mpz_mul(tmp, x->b, y->b);
    mpz_mul(tmp, tmp, d);
    mpz_mul(r->a, x->a, y->a);
    mpz_add(r->a, r->a, tmp);
    mpz_mul(r->b, x->a, y->b);
    mpz_addmul(r->b, x->b, y->a);
}

void vbx_zs_addmul_z(vbx_zs *r, const vbx_zs *x, const mpz_t z)
{
    mpz_addmul(r->a, x->a, z);
    mpz_addmul(r->b, x->b, z);
}

void vbx_zs_submul_z(vbx_zs *r, const vbx_zs *x, const mpz_t z)
{
    mpz_submul(r->a, x->a, z);
    mpz_submul(r->b, x->b, z);
}

int vbx_zs_sign(const vbx_zs *x, const mpz_t d, mpz_t t1, mpz_t t2)
{
    return vbx_sign_qsqrt(x->a, x->b, d, t1, t2);
}

int vbx_sign_two_sqrt(const mpz_t A, const mpz_t B, const mpz_t d1, const mpz_t C,
                      const mpz_t d2, mpz_t *t)
{
    int s1 = vbx_sign_qsqrt(A, B, d1, t[0], t[1]);
    int s2 = mpz_sgn(d2) ? mpz_sgn(C) : 0;
    if (s2 == 0 || s1 == s2)
        return s1 ? s1 : s2;
    if (s1 == 0)
        return s2;
    /* Opposite signs: |A + B sqrt(d1)| against |C| sqrt(d2), squared:
     * A^2 + B^2 d1 - C^2 d2 + 2 A B sqrt(d1). */
    mpz_mul(t[0], A, A);
    mpz_mul(t[1], B, B);
    mpz_addmul(t[0], t[1], d1);
    mpz_mul(t[1], C, C);
    mpz_submul(t[0], t[1], d2);
    mpz_mul(t[1], A, B);
    mpz_mul_2exp(t[1], t[1], 1);
    int s3 = vbx_sign_qsqrt(t[0], t[1], d1, t[2], t[3]);
    return s1 * s3;
}

void vbx_xpt_init(vbx_xpt *x)
{
    mpz_init(x->d);
    mpz_init(x->den);
    for (int k = 0; k < 4; k++)
        vbx_zs_init(&x->U[k]);
    vbx_zs_init(&x->Gn);
    vbx_zs_init(&x->Sn);
}

void vbx_xpt_clear(vbx_xpt *x)
{
    mpz_clear(x->d);
    mpz_clear(x->den);
    for (int k = 0; k < 4; k++)
        vbx_zs_clear(&x->U[k]);
    vbx_zs_clear(&x->Gn);
    vbx_zs_clear(&x->Sn);
}

int vbx_arcw_init(vbx_arcw *w, vb_ctx *ctx, vb_certifier *c)
{
    memset(w, 0, sizeof *w);
    w->ctx = ctx;
    w->c = c;
    w->set = c->set;
    vbx_solver_init(&w->sv, &c->d);
    vbx_solver_init(&w->sq, &c->d);
    for (int k = 0; k < 16; k++)
        mpz_init(w->z[k]);
    for (int k = 0; k < 8; k++)
        vbx_zs_init(&w->zs[k]);
    vbx_xpt_init(&w->yx[0]);
    vbx_xpt_init(&w->yx[1]);
    w->mark = calloc(c->set->n ? c->set->n : 1, 1);
    return w->mark ? VB_OK : VB_ENOMEM;
}

void vbx_arcw_free(vbx_arcw *w)
{
    if (!w->c)
        return;
    vbx_solver_free(&w->sv);
    vbx_solver_free(&w->sq);
    for (int k = 0; k < 16; k++)
        mpz_clear(w->z[k]);
    for (int k = 0; k < 8; k++)
        vbx_zs_clear(&w->zs[k]);
    vbx_xpt_clear(&w->yx[0]);
    vbx_xpt_clear(&w->yx[1]);
    free(w->mark);
    free(w->cand);
    memset(w, 0, sizeof *w);
}

void vbx_box_of_rounded(const double xyzt[4], vbx_ia box[4])
{
    /* A correctly rounded double is within half an ulp of the exact value,
     * so one step each way encloses it (vbx_ia.h). */
    for (int k = 0; k < 4; k++) {
        box[k].lo = vbx_pred(xyzt[k]);
        box[k].hi = vbx_succ(xyzt[k]);
    }
}
