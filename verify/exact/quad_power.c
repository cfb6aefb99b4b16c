/* The power of a sphere at a filter root in double intervals (the
 * emptiness scan's second stage before double-double, vbx_quad.h): the
 * root's (q, s) enclosures made once, then one affine form per sphere. */
#include <stdint.h>

#include "vbx_quad.h"

/* An enclosure of the int64 x (|x| < 2^62): exact below 2^53, else the
 * two doubles around its rounding to nearest. */
static vbx_ia ia_of_i64(int64_t x)
{
    double d = (double)x;
    if ((int64_t)d == x)
        return vbx_ia_point(d);
    vbx_ia r = {vbx_pred(d), vbx_succ(d)};
    return r;
}

void vbx_qf_power_qs(const vbx_qdata *qd, const vbx_qline *L, const vbx_qroot *R, vbx_ia qs[4])
{
    const int64_t *cb = &qd->z[4 * (size_t)L->q[0]];
    vbx_ia sc = vbx_ia_point(qd->scale);
    for (int k = 0; k < 3; k++)
        qs[k] = vbx_ia_sub(vbx_ia_mul(R->p[k], sc), ia_of_i64(cb[k]));
    qs[3] = R->s;
}

/* In scaled units, with q = p - c_a and s = t + R_a for the base a = q[0],
 * m = (c_j - c_a, R_j - R_a) and W = |c_j - c_a|^2 - (R_j - R_a)^2:
 *   |q - m_xyz|^2 - (s + m_r)^2 = (|q|^2 - s^2) + W - 2 (q . m_xyz + s m_r),
 * and |q| = s exactly at the root (the vertex touches a), so the power is
 * the affine W - 2 (q . m_xyz + s m_r). Evaluated over the enclosures of q
 * (R->p times the exact 10^E, minus c_a) and s (R->s), it encloses the
 * exact power. Far roots (a jittered crystal's face: t ~ 10^10 against an
 * excess ~ 10^-8) leave the distance's box open, while this affine form
 * has no such cancellation and decides them without double-double. */
int vbx_qf_power_ia(const vbx_qdata *qd, const vbx_qline *L, const vbx_ia qs[4], uint32_t j)
{
    const int64_t *cb = &qd->z[4 * (size_t)L->q[0]], *cj = &qd->z[4 * (size_t)j];
    vbx_ia W = vbx_ia_point(0.0), mq = vbx_ia_point(0.0);
    for (int k = 0; k < 4; k++) {
        vbx_ia m = ia_of_i64(cj[k] - cb[k]);
        vbx_ia m2 = vbx_ia_sqr(m);
        W = k < 3 ? vbx_ia_add(W, m2) : vbx_ia_sub(W, m2);
        mq = vbx_ia_add(mq, vbx_ia_mul(qs[k], m));
    }
    return vbx_ia_sign(vbx_ia_sub(W, vbx_ia_add(mq, mq)));
}
