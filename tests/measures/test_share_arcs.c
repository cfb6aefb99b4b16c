/* The bisector arcs one atom's regions share (verify/measures/share_arcs.c):
 * the proof that region y may take region x's arcs on their common circle,
 * reversed, rests on the complementary cap (-n, -h) having the frame
 * (-a, -e1, e2) with c negated and s the same, exactly in intervals. Here:
 * that frame on 2000 random caps, the same points of the sphere from both
 * frames ((x, y) in one is (-x, y) in the other), and vbm_share's
 * bookkeeping (which circles are known, the given arc's ends, angles and
 * end caps) on a three-region example. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "vbm_caps.h"
#include "vbm_share.h"
#include "vb_test.h"

#define PI 3.141592653589793

static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static int same(vbx_ia a, vbx_ia b)
{
    return a.lo == b.lo && a.hi == b.hi;
}

static int meets(vbx_ia a, vbx_ia b)
{
    return a.lo <= b.hi && b.lo <= a.hi;
}

/* The point c a + s (x e1 + y e2) of a circle, per coordinate. */
static void point(const vbm_circle *C, vbx_ia x, vbx_ia y, vbx_ia *u)
{
    for (int k = 0; k < 3; k++)
        u[k] = vbx_ia_add(vbx_ia_mul(C->c, C->a[k]),
                          vbx_ia_mul(C->s, vbx_ia_add(vbx_ia_mul(x, C->e1[k]),
                                                      vbx_ia_mul(y, C->e2[k]))));
}

static void test_frames(void)
{
    uint64_t seed = 31;
    int frames = 0, points = 0;
    for (int i = 0; i < 2000; i++) {
        vbm_cap A, B;
        double nn = 0.0, v[3];
        for (int k = 0; k < 3; k++) {
            v[k] = 20.0 * rnd(&seed) - 10.0;
            nn += v[k] * v[k];
        }
        double h = (1.8 * rnd(&seed) - 0.9) * sqrt(nn);
        for (int k = 0; k < 3; k++) {
            A.n[k] = (vbx_ia){vbx_pred(v[k]), vbx_succ(v[k])};
            B.n[k] = vbx_ia_neg(A.n[k]);
        }
        A.h = (vbx_ia){vbx_pred(h), vbx_succ(h)};
        B.h = vbx_ia_neg(A.h);
        vbm_circle ca, cb;
        if (!vbm_circle_of(&A, &ca) || !vbm_circle_of(&B, &cb) || ca.kind != VBM_CAP_CIRCLE ||
            cb.kind != VBM_CAP_CIRCLE)
            continue;
        int ok = same(cb.c, vbx_ia_neg(ca.c)) && same(cb.s, ca.s);
        for (int k = 0; k < 3; k++)
            ok = ok && same(cb.a[k], vbx_ia_neg(ca.a[k])) &&
                 same(cb.e1[k], vbx_ia_neg(ca.e1[k])) && same(cb.e2[k], ca.e2[k]);
        frames += ok;
        vbx_ia x, y, u[3], w[3];
        vbm_unit_at(2.0 * PI * rnd(&seed), &x, &y);
        point(&ca, x, y, u);
        point(&cb, vbx_ia_neg(x), y, w);
        points += meets(u[0], w[0]) && meets(u[1], w[1]) && meets(u[2], w[2]);
    }
    CHECK_INT(frames, 2000);
    CHECK_INT(points, 2000);
}

static vbm_arc arc_on(uint32_t cap, double a, double b, uint32_t pcap, uint32_t qcap)
{
    vbm_arc r;
    r.cap = cap;
    r.pcap = pcap;
    r.qcap = qcap;
    vbm_unit_at(a, &r.p[0], &r.p[1]);
    vbm_unit_at(b, &r.q[0], &r.q[1]);
    r.tp = a;
    r.tq = b;
    return r;
}

/* Regions 0, 1, 2 (active neighbours). Region 0's caps: its own, then
 * neighbours 1 and 2; an arc on its circle with 1 from 0.5 to 1.5 rad,
 * ended by circle (0, 2) and by 0's own; one on its circle with 2. Region
 * 1's caps: its own, neighbour 2, neighbour 0. */
static void test_bookkeeping(void)
{
    vbm_share sh = {0};
    const uint32_t capact0[3] = {0, 1, 2}, capact1[3] = {1, 2, 0};
    vbm_arc arcs0[3] = {arc_on(0, 0.1, 0.4, 1, 2), arc_on(1, 0.5, 1.5, 2, 0),
                        arc_on(2, 4.0, 5.0, 0, VBM_NO_CAP)};
    vbm_share_reset(&sh);
    CHECK_INT(vbm_share_keep(&sh, 0, capact0, arcs0, 3), 1);
    CHECK_INT(sh.nkept, 2); /* not the arc on 0's own circle */
    CHECK_INT(vbm_share_pending(&sh, 1), 1);
    CHECK_INT(vbm_share_pending(&sh, 2), 1);
    CHECK_INT(vbm_share_pending(&sh, 0), 0);
    CHECK_INT(vbm_share_given(&sh, 1, capact1, 3, 3), 1);
    CHECK_INT(sh.known[0], 0);
    CHECK_INT(sh.known[1], 0); /* neighbour 2: bounded after 1 */
    CHECK_INT(sh.known[2], 1); /* neighbour 0: bounded before */
    CHECK_INT(sh.ngiven, 1);
    if (sh.ngiven == 1) {
        const vbm_arc *g = &sh.given[0];
        CHECK_INT(g->cap, 2);
        CHECK_INT(g->pcap, 0);  /* 0's own circle ends it: 1's own does too */
        CHECK_INT(g->qcap, 1);  /* circle (0, 2) ends it: circle (1, 2) does too */
        CHECK_NEAR(g->tp, PI - 1.5, 1e-15);
        CHECK_NEAR(g->tq, PI - 0.5, 1e-15);
        CHECK(same(g->p[0], vbx_ia_neg(arcs0[1].q[0])) && same(g->p[1], arcs0[1].q[1]));
        CHECK(same(g->q[0], vbx_ia_neg(arcs0[1].p[0])) && same(g->q[1], arcs0[1].p[1]));
    }
    /* region 1 bounded: its arc on circle (1, 2) kept for 2, which then has
     * both circles known */
    vbm_arc arcs1[1] = {arc_on(1, 3.0, 4.0, 0, 2)};
    CHECK_INT(vbm_share_keep(&sh, 1, capact1, arcs1, 1), 1);
    const uint32_t capact2[3] = {2, 0, 1};
    CHECK_INT(vbm_share_given(&sh, 2, capact2, 3, 3), 1);
    CHECK_INT(sh.known[1] + sh.known[2], 2);
    CHECK_INT(sh.ngiven, 2);
    /* a region whose cap list lacks a circle holding given arcs: undecided */
    const uint32_t capact2b[2] = {2, 1};
    CHECK_INT(vbm_share_given(&sh, 2, capact2b, 2, 3), 0);
    vbm_share_free(&sh);
}

int main(void)
{
    test_frames();
    test_bookkeeping();
    VB_TEST_END();
}
