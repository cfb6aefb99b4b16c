/* A neighbour's constants along its arcs (vbm_arc.h, vbm_arcfun.h): the
 * constants made once per region (vbm_owner_make) and the functions of z
 * they give: the volume's and the contact's F at a constant z (the own
 * circle's closed form, the contact model's middle) and phi's series in
 * y = 1 - z (the contact near e_j). */
#include <string.h>

#include "vbm_arcfun.h"
#include "vbm_piece.h"

int vbm_owner_make(const vbm_atom_in *in, size_t j, vbx_ia D, vbm_owner *o)
{
    const vbm_nb *n = &in->nb[j];
    int contacts = in->contacts && n->con; /* else the face's other atom integrates it */
    memset(o, 0, sizeof *o);
    o->D = D;
    o->delta = n->delta;
    o->N = n->N;
    vbx_ia N3 = vbx_ia_mul(vbx_ia_sqr(n->N), n->N);
    o->K = vbx_ia_div(N3, vbx_ia_mul(vbx_ia_point(48.0), vbx_ia_sqr(vbx_ia_add(D, n->delta))));
    o->contacts = contacts;
    if (!contacts)
        return 1;
    o->rN = vbx_ia_sqrt(n->N);
    o->hN = vbx_ia_div(vbx_ia_point(0.5), n->N);
    o->kL = vbx_ia_mul(vbx_ia_sqr(n->delta), vbx_ia_div(o->hN, o->rN));
    if (!vbm_ia_is_zero(n->delta)) {
        vbx_ia ad = n->delta.lo > 0.0 ? n->delta : vbx_ia_neg(n->delta);
        if (!(ad.lo > 0.0))
            return 0;
        o->lnd = vbm_ia_log(vbx_ia_add(ad, ad));
    }
    o->C = vbx_ia_div(vbx_ia_sqr(n->N), vbx_ia_mul(vbx_ia_point(4.0), D));
    if (!vbm_contact_g(o, vbx_ia_add(D, n->delta), &o->G1))
        return 0;
    return 1;
}

/* phi(y) = f(1 - y) with f(z) = N^2 sqrt(N + 2 delta q) / (4 q^3),
 * q = D z + delta: the contact's integrand per solid angle (F = int_z^1 f)
 * as a function of y = 1 - z; its series at `at` (a point, or an interval
 * of y holding 0, where q(0) = D + delta > 0, so that q proven non-zero is
 * proven > 0). Returns 0 when q or S = N + 2 delta q is not proven so. */
int vbm_owner_phi(const vbm_owner *o, vbx_ia at, vbm_s1 *phi)
{
    vbm_s1 y, q, S, r, q2, q3, iq3;
    vbm1_var(&y, at);
    vbm1_affine(&q, vbx_ia_neg(o->D), &y, vbx_ia_add(o->D, o->delta));
    vbm1_affine(&S, vbx_ia_add(o->delta, o->delta), &q, o->N);
    if (!vbm1_sqrt(&r, &S))
        return 0;
    vbm1_mul(&q2, &q, &q);
    vbm1_mul(&q3, &q2, &q);
    if (!vbm1_recip(&iq3, &q3))
        return 0;
    vbm1_mul(phi, &r, &iq3);
    vbm1_affine(phi, vbx_ia_div(vbx_ia_sqr(o->N), vbx_ia_point(4.0)), phi, vbx_ia_point(0.0));
    return 1;
}

/* F_vol(z) / (1 - z) = K (D (1 + z) + 2 delta) / (D z + delta)^2 */
vbx_ia vbm_owner_fvol_over(const vbm_owner *o, vbx_ia z)
{
    vbx_ia q = vbx_ia_add(vbx_ia_mul(o->D, z), o->delta);
    vbx_ia t = vbx_ia_add(vbx_ia_mul(o->D, vbx_ia_add(vbx_ia_point(1.0), z)),
                          vbx_ia_add(o->delta, o->delta));
    return vbx_ia_div(vbx_ia_mul(o->K, t), vbx_ia_sqr(q));
}

/* F_con(z) = C (G(D + delta) - G(D z + delta)) at a constant z. */
int vbm_owner_fcon(const vbm_owner *o, vbx_ia z, vbx_ia *F)
{
    vbx_ia G;
    if (!vbm_contact_g(o, vbx_ia_add(vbx_ia_mul(o->D, z), o->delta), &G))
        return 0;
    *F = vbx_ia_mul(o->C, vbx_ia_sub(o->G1, G));
    return 1;
}
