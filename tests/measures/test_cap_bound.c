/* The bounding caps that reject a region's caps (verify/measures/cap_geom.c,
 * used by cap_arcs.c's bound_prune): vbm_arcs_cap's cap B = {u : u.M >= cr}
 * built from an intersection's boundary arcs must hold the whole
 * intersection (not only its arcs: the proof goes through a point outside
 * it), and vbm_cap_holds must say a cap holds B only when it does. Here, on
 * 3000 random intersections of 2-13 caps (cap 0's cosine of radius from 0.9
 * to -0.95, the others' up to wider than a hemisphere: holes and several
 * pieces): 4000 random directions each, every one inside all caps (by a
 * margin, in doubles) must lie in B, and every one in B must lie in each
 * cap said to hold B. The bound must also be proven on
 * most non-empty intersections and reject caps (no vacuous pass). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "vbm_caps.h"
#include "caps_random.h"
#include "vb_test.h"

#define NCAP 14

int main(void)
{
    uint64_t seed = 44;
    vbm_capwork w = {0};
    vbx_ia tmp[4 * 256];
    size_t nonempty = 0, bounded = 0, inside = 0, missed = 0, held = 0, held_pts = 0,
           held_wrong = 0, tries = 0;
    for (int t = 0; t < 3000; t++) {
        vbm_cap caps[NCAP + 4];
        double n[NCAP + 4][3], h[NCAP + 4], v[3];
        size_t nc = 2 + (size_t)(12.0 * rnd(&seed));
        unit(&seed, v);
        /* cap 0 of angular radius up to ~162 degrees; the others about
         * directions near it, from small caps to ones wider than a
         * hemisphere */
        make_cap(&seed, v, 0.0, 0.9 - 1.85 * rnd(&seed), &caps[0], n[0], &h[0]);
        for (size_t m = 1; m < nc + 4; m++)
            make_cap(&seed, v, 1.5 * rnd(&seed), 0.95 - 1.5 * rnd(&seed), &caps[m], n[m],
                     &h[m]);
        if (vbm_cap_arcs(caps, NULL, nc, NULL, NULL, 0, &w) != 1 || w.narc == 0 || w.narc > 256 ||
            w.circ[0].kind != VBM_CAP_CIRCLE)
            continue;
        nonempty++;
        vbx_ia M[3], P[3];
        double cr;
        for (int k = 0; k < 3; k++)
            P[k] = vbx_ia_neg(w.circ[0].a[k]);
        if (!vbm_arcs_cap(w.circ, w.arc, w.narc, P, tmp, M, &cr))
            continue;
        bounded++;
        /* the four extra caps (not in the intersection) and the others:
         * which hold B */
        vbm_circle extra[NCAP + 4];
        int holds[NCAP + 4];
        for (size_t m = 0; m < nc + 4; m++) {
            holds[m] = 0;
            if (vbm_circle_of(&caps[m], &extra[m]) && extra[m].kind == VBM_CAP_CIRCLE)
                holds[m] = vbm_cap_holds(&extra[m], M, cr, vbm_cap_sine(cr));
            held += (size_t)holds[m];
            tries++;
        }
        double Mm[3] = {vbx_ia_mid(M[0]), vbx_ia_mid(M[1]), vbx_ia_mid(M[2])};
        for (int p = 0; p < 4000; p++) {
            double u[3];
            unit(&seed, u);
            double um = u[0] * Mm[0] + u[1] * Mm[1] + u[2] * Mm[2];
            int in = 1;
            for (size_t m = 0; m < nc && in; m++)
                in = depth(n[m], h[m], u) > 1e-9;
            if (in) {
                inside++;
                missed += um < cr - 1e-9;
            }
            if (um > cr + 1e-9)
                for (size_t m = 0; m < nc + 4; m++)
                    if (holds[m]) {
                        held_pts++;
                        held_wrong += depth(n[m], h[m], u) < -1e-9;
                    }
        }
    }
    vbm_caps_free(&w);
    CHECK_INT((long long)missed, 0);
    CHECK_INT((long long)held_wrong, 0);
    /* not vacuous: the bound proven on most intersections, points tested,
     * caps rejected */
    CHECK(nonempty > 1000);
    CHECK(bounded * 10 > nonempty * 9);
    CHECK(inside > 100000);
    CHECK(held * 10 > tries);
    CHECK(held_pts > 100000);
    VB_TEST_END();
}
