/* vbx_qf_power_fast (the far roots' static-bound power filter) against
 * the exact power in 128-bit integers: integer (q, s) near a root far out
 * (|q| ~ 2^40 .. 2^50) and sphere offsets m (|m| < 2^20, or up to 2^61,
 * beyond double's integers), the power made
 * to cancel down to a few units, with boxes of several widths around the
 * true q. Every sign the filter gives must be the exact one for every q
 * of its box, and it must decide what its bound covers. */
#include <math.h>

#include "vb_test.h"
#include "vbx_quad.h"

typedef __int128 i128;

static int64_t draw(uint64_t *s, int bits)
{
    uint64_t x = vb_test_xorshift(s);
    int64_t v = (int64_t)(x >> (64 - bits));
    return (x & 1) ? -v : v;
}

/* Exact power W - 2 (q . m_xyz + s m_r) at integer q. */
static int exact_sign(const int64_t q[4], const int64_t m[4])
{
    i128 e = (i128)m[0] * m[0] + (i128)m[1] * m[1] + (i128)m[2] * m[2] - (i128)m[3] * m[3];
    for (int k = 0; k < 4; k++)
        e -= 2 * (i128)q[k] * m[k];
    return e > 0 ? 1 : e < 0 ? -1 : 0;
}

static void test_against_exact(void)
{
    int64_t z[8];
    vbx_qdata qd = {0};
    qd.z = z;
    qd.scale = 1.0;
    vbx_qline L;
    memset(&L, 0, sizeof L);
    L.q[0] = 0;
    uint64_t s = 0x2545f4914f6cdd1du;
    size_t wrong = 0, decided = 0, far_decided = 0, cases = 0;
    for (int it = 0; it < 200000; it++) {
        int64_t q[4], m[4];
        int qb = 40 + (int)(vb_test_xorshift(&s) % 11);
        for (int k = 0; k < 4; k++) {
            q[k] = draw(&s, qb);
            m[k] = draw(&s, (it & 2) ? 61 : 20);
        }
        if (m[0] == 0)
            m[0] = 1;
        /* Cancel: q[0] so that 2 q . m is within a few m[0] of W, then a
         * shift of -3 .. 3. */
        i128 W = (i128)m[0] * m[0] + (i128)m[1] * m[1] + (i128)m[2] * m[2] - (i128)m[3] * m[3];
        i128 rest = 2 * ((i128)q[1] * m[1] + (i128)q[2] * m[2] + (i128)q[3] * m[3]);
        if (it & 1) {
            i128 q0 = (W - rest) / (2 * (i128)m[0]);
            if (q0 >= ((i128)1 << 52) || q0 <= -((i128)1 << 52))
                continue; /* q must stay exact in double */
            q[0] = (int64_t)q0 + (int64_t)(vb_test_xorshift(&s) % 7) - 3;
        }
        for (int k = 0; k < 4; k++) {
            z[k] = 1000;                 /* base */
            z[4 + k] = 1000 + m[k];      /* sphere 1 */
        }
        int ex = exact_sign(q, m);
        /* Boxes: the point, then widths 2^-8 .. 2^8 around it, off-centre. */
        for (int w = -1; w <= 16; w += 1) {
            vbx_ia qs[4];
            for (int k = 0; k < 4; k++) {
                double qk = (double)q[k]; /* exact: |q| < 2^53 */
                double lo = qk, hi = qk;
                if (w >= 0) {
                    double h = ldexp(1.0, w - 8);
                    lo = qk - h * (double)(1 + (vb_test_xorshift(&s) & 3));
                    hi = qk + h;
                }
                qs[k] = vbx_ia_make(lo, hi);
            }
            double mr[8];
            vbx_qf_power_mr(qs, mr);
            int f = vbx_qf_power_fast(&qd, &L, mr, 1);
            cases++;
            if (f) {
                decided++;
                if (f != ex)
                    wrong++;
                if (w == -1 && (it & 1) == 0)
                    far_decided++;
            }
        }
    }
    CHECK_INT((int)wrong, 0);
    /* The uncancelled points (half the draws, w = -1: 100,000) are far from
     * zero against the bound: all decided. */
    CHECK_INT((int)far_decided, 100000);
    CHECK(decided > cases / 2);
}

/* A box whose radius alone spans zero stays open; signs on either side of
 * it are decided. */
static void test_open(void)
{
    int64_t z[8] = {0, 0, 0, 0, 1, 0, 0, 0};
    vbx_qdata qd = {0};
    qd.z = z;
    qd.scale = 1.0;
    vbx_qline L;
    memset(&L, 0, sizeof L);
    /* m = (1, 0, 0, 0): power 1 - 2 q_x; q_x in [0.25, 0.75] spans 0. */
    vbx_ia qs[4] = {vbx_ia_make(0.25, 0.75), vbx_ia_point(0), vbx_ia_point(0), vbx_ia_point(0)};
    double mr[8];
    vbx_qf_power_mr(qs, mr);
    CHECK_INT(vbx_qf_power_fast(&qd, &L, mr, 1), 0);
    qs[0] = vbx_ia_make(0.0, 0.4999);
    vbx_qf_power_mr(qs, mr);
    CHECK_INT(vbx_qf_power_fast(&qd, &L, mr, 1), 1);
    qs[0] = vbx_ia_make(0.5001, 0.9);
    vbx_qf_power_mr(qs, mr);
    CHECK_INT(vbx_qf_power_fast(&qd, &L, mr, 1), -1);
}

int main(void)
{
    test_against_exact();
    test_open();
    VB_TEST_END();
}
