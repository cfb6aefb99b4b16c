/* The power of a sphere at a filter root in double intervals (the
 * emptiness scan's second stage before double-double, vbx_quad.h): the
 * root's (q, s) enclosures made once, then one affine form per sphere. */
#include <math.h>
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

void vbx_qf_power_mr(const vbx_ia qs[4], double mr[8])
{
    for (int k = 0; k < 4; k++) {
        double m = 0.5 * qs[k].lo + 0.5 * qs[k].hi;
        mr[k] = m;
        mr[4 + k] = vbx_succ(vbx_max(qs[k].hi - m, m - qs[k].lo));
    }
}

/* The affine form of vbx_qf_power_ia in plain doubles, q in [mr_k - rad_k,
 * mr_k + rad_k] (rad_k = mr[4 + k]), u = 2^-53. The offsets m_k (|m_k| <
 * 2^63) are rounded to nearest: m_k = md_k (1 + d), |d| <= u. With
 * E0 = sum_{k<3} md_k^2 - md_3^2 - 2 sum_k mr_k md_k, the exact power
 * differs from E0 by at most 2 SR (SR = sum_k rad_k |md_k|, the box) plus
 * 2.01 u sum_k md_k^2 + 2 u sum_k (|mr_k| + rad_k) |md_k| (the rounded
 * offsets), and the double e of E0 (8 rounded terms) from E0 by at most
 * gamma_9 A, A = sum_k md_k^2 + 2 sum_k |mr_k md_k|, gamma_9 < 9.1 u: in
 * all at most 2 SR + 2 u SR + 11.2 u A. B = 2 sr + 2^-48 (a + 2 sr) + 2^-1000
 * (sr, a: the doubles of SR and A, within 5 u and 10 u relative; 2^-48 =
 * 32 u) exceeds it after B's own four roundings; the constant covers
 * underflow in the products (at most 2^-1074 each). An overflow gives inf
 * or NaN, and neither comparison then holds. */
int vbx_qf_power_fast(const vbx_qdata *qd, const vbx_qline *L, const double mr[8], uint32_t j)
{
    const int64_t *cb = &qd->z[4 * (size_t)L->q[0]], *cj = &qd->z[4 * (size_t)j];
    double W = 0.0, d = 0.0, a = 0.0, sr = 0.0;
    for (int k = 0; k < 4; k++) {
        double m = (double)(cj[k] - cb[k]), m2 = m * m, qm = mr[k] * m;
        W = k < 3 ? W + m2 : W - m2;
        d += qm;
        a += m2 + 2.0 * fabs(qm);
        sr += mr[4 + k] * fabs(m);
    }
    double e = W - 2.0 * d;
    double B = 2.0 * sr + 0x1p-48 * (a + 2.0 * sr) + 0x1p-1000;
    return e > B ? 1 : e < -B ? -1 : 0;
}

/* The power of every sphere of a group at once: the affine form of
 * vbx_qf_power_ia is a sum of one term per coordinate,
 *   power = sum_{k<3} (m_k^2 - 2 q_k m_k) - (m_r^2 + 2 s m_r),
 * so over a box of offsets m (the group's centres and radii, minus the
 * base's) and the root's boxes of (q, s) it is at least
 *   sum_{k<3} g_k(x_k) - max(h(m_r lo), h(m_r hi)) - 2 (sum_k rad_k |m_k|max),
 * with g_k(m) = m (m - 2 mr_k) convex, least at x_k = mr_k clamped to the
 * box (an exact double), h(m) = m (m + 2 mr_3) convex, largest at an end of
 * the box, and |q_k - mr_k| <= rad_k (the rest of the affine form). In
 * doubles: 2 mr_k is exact, each g or h rounds twice (2.01 u |x| (|x| +
 * 2 |mr_k|), summed in a), the four terms add with gamma_3 of their
 * magnitudes (< a (1 + 3u)); the radius sum S~ rounds 5 times (gamma_5 S).
 * In all the exact lower bound is above fl(e - S~) (1 - u) - 5.2 u a -
 * 5.1 u S~, and B = 2^-45 (a + S~) + 2^-1000 (2^-45 = 256 u; the constant
 * covers underflow) exceeds that error by far. The box: the group's
 * centres' enclosures [lo, hi] and radius bounds [rlo, rhi] in input units,
 * times the exact 10^E and minus the base's scaled values, rounded outward.
 * An overflow gives inf or NaN, and the comparison then fails. */
int vbx_qf_power_box(const vbx_qdata *qd, const vbx_qline *L, const double mr[8],
                     const double lo[3], const double hi[3], double rlo, double rhi)
{
    const int64_t *cb = &qd->z[4 * (size_t)L->q[0]];
    vbx_ia sc = vbx_ia_point(qd->scale);
    double e = 0.0, a = 0.0, S = 0.0;
    for (int k = 0; k < 4; k++) {
        vbx_ia g = {k < 3 ? lo[k] : rlo, k < 3 ? hi[k] : rhi};
        if (!(g.lo <= g.hi))
            return 0; /* NaN */
        vbx_ia m = vbx_ia_sub(vbx_ia_mul(g, sc), ia_of_i64(cb[k]));
        double q = mr[k], tq = 2.0 * q, al = fabs(m.lo), ah = fabs(m.hi);
        S += mr[4 + k] * vbx_max(al, ah);
        if (k < 3) {
            double x = q < m.lo ? m.lo : (q > m.hi ? m.hi : q);
            e += x * (x - tq);
            a += fabs(x) * (fabs(x) + fabs(tq));
        } else {
            e -= vbx_max(m.lo * (m.lo + tq), m.hi * (m.hi + tq));
            a += vbx_max(al * (al + fabs(tq)), ah * (ah + fabs(tq)));
        }
    }
    S = 2.0 * S;
    double B = 0x1p-45 * (a + S) + 0x1p-1000;
    return e - S > B;
}

int vbx_qf_group_outside(const void *group, const double lo[3], const double hi[3], double rmax)
{
    const vbx_qf_group *g = group;
    return vbx_qf_power_box(g->z, g->L, g->mr, lo, hi, g->rmin, rmax);
}
