/* The arrangement guided by each circle's neighbours (verify/measures/
 * cap_search.c, vbm_cap_arcs_near) and the prefilter's proof of an empty
 * intersection (cap_prefilter.c). The neighbours only choose where a
 * circle's arcs are looked for first; every cap left out must still be
 * proven to hold them. So on 4000 random intersections of 3-17 caps, with
 * hints that are wrong on purpose (no neighbours at all, a random third of
 * the caps) and with every cap, the guided search must give the arcs of the
 * search over all caps (vbm_cap_arcs_all): the same set, and the same list
 * bit for bit where no circle has several arcs (whose list may start at
 * another arc). Then an intersection of caps parallel to cap 0 that the
 * midpoints make empty by 5e-10: proven empty as points (vbm_cap_arcs
 * answers 1 and no arc, as the full search does), not proven where the
 * enclosure of h holds values that make it a band (vbm_cap_arcs answers as
 * the full search does, never 1 without arcs).
 * Planted and caught: vbm_cap_arcs_near trusting its hint (the arcs found
 * among the neighbours taken without vbm_arcs_inside: with no neighbours
 * every circle comes back whole); the empty proof skipped (empty where
 * the clip in doubles says so: the wide band answered 1 without arcs). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vbm_caps.h"
#include "caps_random.h"
#include "vb_test.h"

#define NCAP 17

/* Circle l's hint: none (mode 0), a random third of the caps (1), all (2). */
static size_t hint(uint64_t *seed, int mode, size_t nc, uint32_t *at, uint32_t *near)
{
    size_t nn = 0;
    for (size_t l = 0; l < nc; l++) {
        at[l] = (uint32_t)nn;
        for (size_t m = 0; m < nc && mode > 0; m++)
            if (m != l && (mode == 2 || rnd(seed) < 1.0 / 3.0))
                near[nn++] = (uint32_t)m;
    }
    at[nc] = (uint32_t)nn;
    return nn;
}

/* Whether a circle of the list has two arcs or more (not the halves of
 * one). */
static int several(const vbm_arc *a, size_t na)
{
    for (size_t i = 1; i < na; i++)
        if (a[i].cap == a[i - 1].cap && a[i].pcap != VBM_NO_CAP)
            return 1;
    return 0;
}

int main(void)
{
    uint64_t seed = 54;
    vbm_capwork w = {0}, wn = {0};
    size_t cases = 0, same_set = 0, same_bytes = 0, set_differ = 0, bytes_differ = 0,
           undecided = 0, with_arcs = 0, multi = 0;
    size_t map[NCAP + 1];
    for (size_t m = 0; m <= NCAP; m++)
        map[m] = m;
    for (int t = 0; t < 4000; t++) {
        vbm_cap caps[NCAP + 1];
        double n[NCAP + 1][3], h[NCAP + 1];
        size_t nc = region_caps(&seed, t, caps, n, h);
        if (vbm_cap_arcs_all(caps, NULL, nc, NULL, NULL, 0, &w) != 1)
            continue;
        cases++;
        with_arcs += w.narc > 0;
        int sev = several(w.arc, w.narc);
        multi += sev;
        for (int mode = 0; mode < 3; mode++) {
            uint32_t at[NCAP + 2], near[NCAP * NCAP + 1];
            hint(&seed, mode, nc, at, near);
            int e = vbm_cap_arcs_near(caps, NULL, nc, NULL, NULL, 0, at, near, &wn);
            if (e != 1) {
                undecided++;
                continue;
            }
            int s = arcs_same(w.arc, w.narc, wn.arc, wn.narc, map);
            same_set += s;
            set_differ += !s;
            if (!sev) {
                int b = arcs_equal(w.arc, w.narc, wn.arc, wn.narc);
                same_bytes += b;
                bytes_differ += !b;
            }
        }
    }
    CHECK_INT((long long)set_differ, 0);
    CHECK_INT((long long)bytes_differ, 0);
    CHECK(undecided * 100 < 3 * cases);
    /* not vacuous: many intersections with arcs, some with several on a circle */
    CHECK(cases > 3500);
    CHECK(with_arcs * 2 > cases);
    CHECK(multi > 20);
    CHECK(same_bytes > 8000);

    /* Cap 0 about z (cos radius 0.6) and the directions below it by
     * 5e-10, u.(0, 0, -1) >= -0.6 + 5e-10, with two caps that hold every
     * direction near z: empty, and vbm_cap_arcs says so (1, no arc) as the
     * full search does. With that h widened to [-0.6 - 5e-10, -0.6 +
     * 1.5e-9] (the same midpoint) some caps in the enclosures leave a band
     * around z: the prefilter must not call it empty, and vbm_cap_arcs
     * answers as the full search does. */
    {
        vbm_cap c[4];
        double z[3] = {0, 0, 1}, mz[3] = {0, 0, -1}, a[3] = {0.1, 0, 1}, b[3] = {0, 0.1, 1};
        double hz;
        for (int k = 0; k < 3; k++) {
            c[0].n[k] = vbx_ia_point(z[k]);
            c[1].n[k] = vbx_ia_point(mz[k]);
            c[2].n[k] = vbx_ia_point(a[k]);
            c[3].n[k] = vbx_ia_point(b[k]);
        }
        c[0].h = vbx_ia_point(0.6);
        hz = -0.6 + 5e-10;
        c[1].h = vbx_ia_point(hz);
        c[2].h = vbx_ia_point(-0.5);
        c[3].h = vbx_ia_point(-0.5);
        int ea = vbm_cap_arcs_all(c, NULL, 4, NULL, NULL, 0, &w);
        int eb = vbm_cap_arcs(c, NULL, 4, NULL, NULL, 0, &wn);
        CHECK(ea == 1 && w.narc == 0);
        CHECK(eb == 1 && wn.narc == 0);
        c[1].h = vbx_ia_make(-0.6 - 5e-10, -0.6 + 1.5e-9);
        ea = vbm_cap_arcs_all(c, NULL, 4, NULL, NULL, 0, &w);
        eb = vbm_cap_arcs(c, NULL, 4, NULL, NULL, 0, &wn);
        CHECK_INT(eb, ea);
        CHECK(!(eb == 1 && wn.narc == 0) || (ea == 1 && w.narc == 0));
        /* a true band of width 1e-6: arcs on both circles, as the full search */
        c[1].h = vbx_ia_point(-0.6 - 1e-6);
        ea = vbm_cap_arcs_all(c, NULL, 4, NULL, NULL, 0, &w);
        eb = vbm_cap_arcs(c, NULL, 4, NULL, NULL, 0, &wn);
        CHECK(ea == 1 && w.narc > 0);
        CHECK(eb == 1 && arcs_equal(w.arc, w.narc, wn.arc, wn.narc));
    }
    vbm_caps_free(&w);
    vbm_caps_free(&wn);
    printf("cases %zu with arcs %zu several on a circle %zu; guided: same arcs %zu, same bytes %zu, "
           "undecided %zu\n",
           cases, with_arcs, multi, same_set, same_bytes, undecided);
    VB_TEST_END();
}
