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

int main(void)
{
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
