/* Combination dominance's pair search in vector lanes (vbq_combo_pairs4,
 * core/cells/vbq_combo_shared.h: the host, and the work-item kernel on CPU
 * devices) against the pair loop the kernels run, restated here: the same
 * pair, weights and sum for every label, since the cover's lists follow
 * from them. Random champions (two to six, from vbq_champ_make over random
 * records, some of them parallel: D = 0) and labels (some on a champion's
 * ray: a weight clamped to 0; some equal to a champion: ties between
 * pairs). Also the near-tie test of a fetch (vbq_near_tie, vbq_ring_radius,
 * vbq_ring_shared.h) on the values a jittered crystal's face ball meets. */
#include "vb_test.h"

#include "vb_cover.h"

#include <string.h>

#ifndef VBQ_WALK_V4
int main(void)
{
    printf("no vector lanes in this build: nothing to compare\n");
    return 0;
}
#else

static uint64_t rng = 0x2545f4914f6cdd1dull;

static double uni(double lo, double hi)
{
    vb_test_xorshift(&rng);
    return lo + (hi - lo) * (double)(rng >> 11) * 0x1p-53;
}

/* The kernels' pair loop (vbq_combo_beaten without VBQ_WALK_V4). */
static double loop_pairs(const vbq_champ *c, const double p[VBQ_CHAMP], double *bk, double *bl,
                         vbs_u32 *kk, vbs_u32 *kl)
{
    double best = 2.0;
    for (vbs_u32 k = 0u; k < c->n; k++)
        for (vbs_u32 l = k + 1u; l < c->n; l++) {
            double D = vbq_champ_det(c, k, l), fl = 1e-290 * fabs(D);
            if (D == 0.0)
                continue;
            double sl = D > 0.0 ? p[l] : -p[l], sk = D > 0.0 ? -p[k] : p[k];
            double al = fabs(p[l]), ak = fabs(p[k]);
            if ((sl < 0.0 && al > 1e-5 * ak && al > fl) || (sk < 0.0 && ak > 1e-5 * al && ak > fl))
                continue;
            double lk = p[l] / D, ll = -p[k] / D;
            double tol = VBQ_COMBO_CLAMP * (fabs(lk) + fabs(ll));
            lk = lk < 0.0 && lk >= -tol ? 0.0 : lk;
            ll = ll < 0.0 && ll >= -tol ? 0.0 : ll;
            if (lk >= 0.0 && ll >= 0.0 && lk + ll < best) {
                best = lk + ll;
                *bk = lk;
                *bl = ll;
                *kk = k;
                *kl = l;
            }
        }
    return best;
}


/* The lanes on hand-set pairs (only pair t's determinant D non-zero, the
 * others 0: skipped), for the clamp's and the lane order's boundaries. */
static double lanes_on(const double d[16], const double p[VBQ_CHAMP], double best, double *bk,
                       double *bl, vbs_u32 *kk, vbs_u32 *kl)
{
    vbq_champ c;
    memset(&c, 0, sizeof c);
    for (vbs_u32 t = 0u; t < 16u; t++) {
        c.vd[t / 4u][t % 4u] = d[t];
        c.vf[t / 4u][t % 4u] = 1e-290 * fabs(d[t]);
    }
    *bk = *bl = -1.0;
    *kk = *kl = 99u;
    vbq_combo_pairs4(&c, p, &best, bk, bl, kk, kl);
    return best;
}

/* A weight w < 0 exactly at minus the clamp's tolerance beside L > 0:
 * -w == VBQ_COMBO_CLAMP * (-w + L) in doubles (searched near the fixed
 * point). 0 when none is found for this L. */
static double clamp_edge(double L)
{
    double x = VBQ_COMBO_CLAMP * L;
    for (int it = 0; it < 8; it++)
        x = VBQ_COMBO_CLAMP * (x + L);
    for (int k = 0; k < 64; k++)
        x = nextafter(x, 0.0);
    for (int k = 0; k < 128; k++, x = nextafter(x, 1.0))
        if (VBQ_COMBO_CLAMP * (fabs(-x) + fabs(L)) == x)
            return x;
    return 0.0;
}

static void clamp_edges(void)
{
    double d[16] = {0}, bk, bl, best;
    vbs_u32 kk, kl;
    int met = 0;
    for (double L = 0.5; L < 1.0; L += 0.0625) {
        double x = clamp_edge(L);
        if (x == 0.0)
            continue;
        met++;
        /* pair (0, 1) in lane 0, D = 1: lk = p[1], ll = -p[0] */
        memset(d, 0, sizeof d);
        d[0] = 1.0;
        double p[VBQ_CHAMP] = {-L, -x, 0.0, 0.0, 0.0, 0.0};
        best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
        CHECK(best == L && bk == 0.0 && bl == L && kk == 0u && kl == 1u); /* lk clamped */
        double y = nextafter(x, 1.0); /* one step below -tol: kept negative, fails */
        CHECK(y > VBQ_COMBO_CLAMP * (y + L));
        p[1] = -y;
        best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
        CHECK(best == 2.0 && kk == 99u);
        /* the other weight at the edge: ll = -p[0] = -x, lk = L; pair (4, 5), lane 14 */
        memset(d, 0, sizeof d);
        d[14] = 1.0;
        double p2[VBQ_CHAMP] = {0.0, 0.0, 0.0, 0.0, x, L};
        best = lanes_on(d, p2, 2.0, &bk, &bl, &kk, &kl);
        CHECK(best == L && bk == L && bl == 0.0 && kk == 4u && kl == 5u);
        p2[4] = y;
        best = lanes_on(d, p2, 2.0, &bk, &bl, &kk, &kl);
        CHECK(best == 2.0 && kk == 99u);
    }
    CHECK(met > 0);
    /* lane order: equal sums in lanes 3 (0, 4) and 14 (4, 5): the first;
     * a sum equal to the caller's best is no improvement */
    memset(d, 0, sizeof d);
    d[3] = 1.0;
    d[14] = 1.0;
    double p[VBQ_CHAMP] = {-0.25, 0.0, 0.0, 0.0, -0.25, 0.5};
    best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
    /* lane 3: lk = p[4] = -0.25 < 0 fails; lane 14: lk = p[5] = 0.5, ll = -p[4] = 0.25 */
    CHECK(best == 0.75 && kk == 4u && kl == 5u && bk == 0.5 && bl == 0.25);
    p[0] = -0.5;
    p[4] = 0.25;
    p[5] = 0.25;
    /* lane 3: lk = 0.25, ll = 0.5; lane 14: lk = 0.25, ll = -0.25 fails */
    best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
    CHECK(best == 0.75 && kk == 0u && kl == 4u && bk == 0.25 && bl == 0.5);
    best = lanes_on(d, p, 0.75, &bk, &bl, &kk, &kl);
    CHECK(best == 0.75 && kk == 99u);
    d[14] = -1.0; /* lane 14: lk = -0.25 fails... */
    p[4] = -0.5;  /* ...now lk = p[5] / D = -0.25 still; ll = -p[4] / D = -0.5 fails */
    d[9] = 1.0;   /* lane 9 (2, 3): lk = p[3] = 0, ll = -p[2] = 0.75 */
    p[2] = -0.75;
    p[0] = 0.0;
    best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
    /* lane 3: lk = p[4] = -0.5 fails; lane 9 only */
    CHECK(best == 0.75 && kk == 2u && kl == 3u && bk == 0.0 && bl == 0.75);
    /* ties between lanes 0 and 9: the first */
    d[0] = 1.0;
    p[1] = 0.5;
    p[0] = -0.25;
    best = lanes_on(d, p, 2.0, &bk, &bl, &kk, &kl);
    CHECK(best == 0.75 && kk == 0u && kl == 1u && bk == 0.5 && bl == 0.25);
}

int main(void)
{
    clamp_edges();
    vbq_nb nb[16];
    vbs_u32 lab[16];
    size_t found = 0, none = 0;
    for (int t = 0; t < 20000; t++) {
        vbs_u32 keep = 2u + (vbs_u32)(t % 15);
        for (vbs_u32 k = 0; k < keep; k++) {
            double s = uni(0.05, 0.4);
            nb[k] = (vbq_nb){uni(-s, s), uni(-s, s), uni(-1e-9, 1e-9), 0.0, 1e-17, k, 0u};
            if (t % 7 == 0 && k > 0 && k % 3 == 0) { /* parallel to the one before */
                nb[k].ax = 2.0 * nb[k - 1u].ax;
                nb[k].ay = 2.0 * nb[k - 1u].ay;
                nb[k].az = 2.0 * nb[k - 1u].az;
            }
            lab[k] = k;
        }
        double m[3] = {0.0, 0.0, 1.0}, h[3] = {0.1, 0.1, 0.01};
        vbq_champ c;
        c.round = 0u;
        c.n = 0u;
        vbq_champ_make(nb, lab, keep, m, h, &c);
        for (int j = 0; j < 8; j++) {
            vbq_nb r = {uni(-0.2, 0.2), uni(-0.2, 0.2), uni(-1e-9, 1e-9), 0.0, 1e-17, 99u, 0u};
            if (j == 1 && c.n > 0) { /* on a champion's ray, jittered */
                double f = uni(0.1, 0.9);
                r.ax = f * c.rec[0].ax * (1.0 + 1e-12);
                r.ay = f * c.rec[0].ay;
            }
            if (j == 2 && c.n > 1) /* a champion itself: pairs tie */
                r = c.rec[1], r.id = 99u;
            double p[VBQ_CHAMP] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
            for (vbs_u32 q = 0u; q < c.n; q++)
                p[q] = (r.ax * c.w[q][0] + r.ay * c.w[q][1]) + r.az * c.w[q][2];
            double b1 = 2.0, k1 = 0.0, l1 = 0.0, b2, k2 = 0.0, l2 = 0.0;
            vbs_u32 kk1 = 0u, kl1 = 0u, kk2 = 0u, kl2 = 0u;
            vbq_combo_pairs4(&c, p, &b1, &k1, &l1, &kk1, &kl1);
            b2 = loop_pairs(&c, p, &k2, &l2, &kk2, &kl2);
            int same = b1 == b2 && k1 == k2 && l1 == l2 && kk1 == kk2 && kl1 == kl2;
            CHECK(same);
            if (!same) {
                fprintf(stderr, "trial %d/%d n %u: lanes %.17g (%u,%u) loop %.17g (%u,%u)\n", t,
                        j, c.n, b1, kk1, kl1, b2, kk2, kl2);
                VB_TEST_END();
            }
            found += b2 < 2.0;
            none += b2 == 2.0;
        }
    }
    CHECK(found > 10000 && none > 10000); /* both outcomes occur often */
    printf("pairs found %zu, none %zu\n", found, none);

    /* A jittered face ball's normal (LO ~ 1e-10, centres within 80): a
     * near-tie, its ring infinite at once; a reach within 1e3 times the
     * farthest centre, or LO = 0 (an exact crystal's face, a protein's
     * open side), doubles as before. */
    CHECK_INT((int)vbq_near_tie(1.7e-10, 80.0), 1);
    CHECK(vbq_ring_radius(5.8, 1.7e-10, 0.0, 80.0) == (double)INFINITY);
    CHECK_INT((int)vbq_near_tie(1.0 / 79000.0, 80.0), 0);
    CHECK(vbq_ring_radius(5.8, 1.0 / 79000.0, 0.0, 80.0) == 11.6);
    CHECK_INT((int)vbq_near_tie(0.0, 80.0), 0);
    CHECK(vbq_ring_radius(5.8, 0.0, 0.0, 80.0) == 11.6);
    CHECK(vbq_ring_radius(46.4, 0.0, 0.0, 80.0) == (double)INFINITY);
    CHECK(fabs(vbq_ring_radius(5.8, 0.1, 0.0, 80.0) - 10.0) < 1e-6);
    VB_TEST_END();
}
#endif
