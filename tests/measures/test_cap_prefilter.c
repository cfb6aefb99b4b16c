/* The caps rejected before a region's arrangement (verify/measures/
 * cap_prefilter.c, vbm_caps_prefilter): each rejected cap must hold, in
 * its interior, every direction inside the caps kept. On 6000 random
 * intersections of 3-17 caps (cap 0 from small to wider than a half
 * sphere, the others about nearby directions): 4000 directions spread
 * over cap 0 each, every one inside all kept caps (by a margin, in
 * doubles) must lie inside every rejected cap; the search over all caps
 * (vbm_cap_arcs_all) must have no arc on a rejected circle and none
 * ending on one; the search over the kept caps alone must give the same
 * arcs (the kept caps define the intersection); and vbm_cap_arcs (the
 * kept caps' search, the full one where a circle has several arcs) must
 * give the full search's list bit for bit, order included. Then a cap
 * whose plane passes through a vertex of the intersection (touching it at
 * one point) must be kept, a cap cutting a corner off must be kept, and
 * the prefilter must reject caps on most intersections (no vacuous pass).
 * Planted and caught: the certificate skipped with vertices within 1e-3
 * of a plane counted inside (the touching cap rejected); the tangent
 * plane at 0.995 (the same); vbm_cap_arcs' fallback only for three arcs
 * on a circle (a list in another order); the certificate on the
 * midpoints (the caps' enclosures left out: the wide h or n_z rejected);
 * |v| left out of the certificate (the wide n_z rejected). The clip's
 * decisions are pinned to main 91d4a11's (24,917 caps, a hash of every
 * case's): planted and caught, the vertex after the least one taken, a
 * new vertex joined to itself or along the wrong plane, the new face's
 * plane map not cleared between clips. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vbm_caps.h"
#include "caps_random.h"
#include "vb_test.h"

#define NCAP 17

/* The cap {u : u.n >= h} in point intervals. */
static void set_cap(const double *n, double h, vbm_cap *cp)
{
    for (int k = 0; k < 3; k++)
        cp->n[k] = vbx_ia_point(n[k]);
    cp->h = vbx_ia_point(h);
}

/* The prefilter over caps[0..nc) (their circles made here); pre has
 * the rejected ones. Returns how many, or -1 when a circle cannot be made. */
static long prefilter(const vbm_cap *caps, size_t nc, vbm_capwork *w, uint8_t *pre)
{
    vbm_circle circ[NCAP + 1];
    for (size_t m = 0; m < nc; m++)
        if (!vbm_circle_axis(&caps[m], &circ[m]) || circ[m].kind == VBM_CAP_NONE)
            return -1;
    return (long)vbm_caps_prefilter(caps, circ, nc, w, pre);
}

int main(void)
{
    uint64_t seed = 52;
    vbm_capwork w = {0}, w2 = {0}, wp = {0};
    vbm_arc arcs[512];
    uint8_t pre[NCAP + 1];
    size_t cases = 0, with_rej = 0, rejected = 0, tested = 0, pts = 0, wrong = 0,
           arc_on_rej = 0, compared = 0, differ = 0, both = 0, bytes_differ = 0, ret_differ = 0,
           several = 0;
    uint64_t pre_hash = 14695981039346656037u;
    for (int t = 0; t < 6000; t++) {
        vbm_cap caps[NCAP + 1], kept[NCAP + 1];
        double n[NCAP + 1][3], h[NCAP + 1];
        size_t nc = region_caps(&seed, t, caps, n, h);
        long nr = prefilter(caps, nc, &wp, pre);
        if (nr < 0)
            continue;
        cases++;
        for (size_t m = 0; m < nc; m++) /* FNV-1a over every case's decisions */
            pre_hash = (pre_hash ^ pre[m]) * 1099511628211u;
        with_rej += nr > 0;
        rejected += (size_t)nr;
        if (nr == 0)
            continue;
        /* directions over cap 0 (uniform in its area) */
        double e[3], f[3], g[3], en = sqrt(n[0][0] * n[0][0] + n[0][1] * n[0][1] + n[0][2] * n[0][2]);
        for (int k = 0; k < 3; k++)
            e[k] = n[0][k] / en;
        int ax = fabs(e[0]) < 0.6 ? 0 : 1;
        double a[3] = {ax == 0, ax == 1, 0.0};
        f[0] = e[1] * a[2] - e[2] * a[1], f[1] = e[2] * a[0] - e[0] * a[2], f[2] = e[0] * a[1] - e[1] * a[0];
        double fn = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (int k = 0; k < 3; k++)
            f[k] /= fn;
        g[0] = e[1] * f[2] - e[2] * f[1], g[1] = e[2] * f[0] - e[0] * f[2], g[2] = e[0] * f[1] - e[1] * f[0];
        double ca = h[0] / en;
        for (int p = 0; p < 4000; p++) {
            double z = ca + (1.0 - ca) * rnd(&seed), ph = 6.283185307179586 * rnd(&seed);
            double r = sqrt(fmax(0.0, 1.0 - z * z)), u[3];
            for (int k = 0; k < 3; k++)
                u[k] = z * e[k] + r * (cos(ph) * f[k] + sin(ph) * g[k]);
            int in = 1;
            for (size_t m = 0; m < nc && in; m++)
                in = pre[m] || depth(n[m], h[m], u) > 1e-9;
            if (!in)
                continue;
            pts++;
            for (size_t m = 1; m < nc; m++)
                wrong += pre[m] && depth(n[m], h[m], u) < 1e-12;
        }
        tested++;
        /* the arrangement over all caps: nothing on a rejected circle; and
         * over the kept caps alone: the same arcs */
        int ea = vbm_cap_arcs_all(caps, NULL, nc, NULL, NULL, 0, &w);
        if (ea != 1 || w.narc > 512)
            continue;
        /* vbm_cap_arcs (the search over the kept caps) gives the search
         * over all caps' bytes where both decide */
        int eb = vbm_cap_arcs(caps, NULL, nc, NULL, NULL, 0, &w2);
        ret_differ += eb != 1;
        both += eb == 1;
        bytes_differ += eb == 1 && !arcs_equal(w.arc, w.narc, w2.arc, w2.narc);
        for (size_t i = 1; i < w.narc; i++)
            several += w.arc[i].cap == w.arc[i - 1].cap && w.arc[i].pcap != VBM_NO_CAP;
        for (size_t i = 0; i < w.narc; i++) {
            const vbm_arc *x = &w.arc[i];
            arc_on_rej += pre[x->cap] || (x->pcap != VBM_NO_CAP && pre[x->pcap]) ||
                          (x->qcap != VBM_NO_CAP && pre[x->qcap]);
        }
        size_t nk = 0, map[NCAP + 1];
        for (size_t m = 0; m < nc; m++)
            if (!pre[m]) {
                map[nk] = m;
                kept[nk++] = caps[m];
            }
        memcpy(arcs, w.arc, w.narc * sizeof *arcs);
        size_t na = w.narc;
        if (vbm_cap_arcs_all(kept, NULL, nk, NULL, NULL, 0, &w2) != 1)
            continue;
        compared++;
        differ += !arcs_same(arcs, na, w2.arc, w2.narc, map);
    }
    CHECK_INT((long long)wrong, 0);
    CHECK_INT((long long)arc_on_rej, 0);
    CHECK_INT((long long)differ, 0);
    CHECK_INT((long long)bytes_differ, 0);
    CHECK(ret_differ * 100 < both);
    CHECK(several > 100); /* circles with several arcs, whose order is at stake */
    /* not vacuous: caps rejected on many intersections, points tested */
    CHECK(cases > 5000);
    /* the decisions themselves, pinned: main 91d4a11's clip (before the
     * coordinates by arrays, scan, and the new face's plane map) rejects
     * the same 24,917 caps, case by case; the clip only chooses, so a
     * plant there (the wrong vertex at the least value, a new vertex
     * joined to the wrong neighbour) shows here as fewer or other
     * rejections, not as a wrong one */
    CHECK_INT((long long)rejected, 24917);
    CHECK(pre_hash == 0xe8cbb60803c57216u);
    CHECK(with_rej * 4 > cases);
    CHECK(rejected > cases);
    CHECK(pts > 100000);
    CHECK(compared * 2 > tested);

    /* Cap 0 about z (cos radius 0.6) cut by x >= 0 and y >= 0: a corner of
     * directions with the vertex (0, 0, 1) on both planes. The cap
     * u.(1, 1, -4) >= -4 holds the rest but passes through that vertex
     * (x + y - 4 z = -4 only there): kept. u.(1, 1, 0) >= 0.05 cuts the
     * corner off: kept, and then the cap through the vertex holds what is
     * left, away from its circle: rejected. u.(1, 1, 0) >= -0.05 holds
     * the corner with room: rejected, the touching one kept. */
    {
        vbm_cap c[5];
        double z[3] = {0, 0, 1}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
        double touch[3] = {1, 1, -4}, cut[3] = {1, 1, 0};
        set_cap(z, 0.6, &c[0]);
        set_cap(x, 0.0, &c[1]);
        set_cap(y, 0.0, &c[2]);
        set_cap(touch, -4.0, &c[3]);
        CHECK(prefilter(c, 4, &wp, pre) == 0);
        set_cap(cut, 0.05, &c[3]);
        CHECK(prefilter(c, 4, &wp, pre) == 0);
        set_cap(touch, -4.0, &c[3]);
        set_cap(cut, 0.05, &c[4]);
        CHECK(prefilter(c, 5, &wp, pre) == 1);
        CHECK(pre[3] && !pre[4] && !pre[1] && !pre[2]);
        set_cap(cut, -0.05, &c[4]);
        CHECK(prefilter(c, 5, &wp, pre) == 1);
        CHECK(pre[4] && !pre[3] && !pre[1] && !pre[2]);

        /* The certificate's bounds over the enclosures: u.(1, 1, -4) >=
         * -4 - 5e-10 holds the corner by 5e-10 at (0, 0, 1): rejected as
         * points. With h in [-4 - 2.5e-9, -4 + 1.5e-9] (mid the same) or
         * n_z in [-4 - 1e-9, -4 + 1e-9] some cap in the enclosures cuts
         * the vertex (0, 0, 1) away: kept, though the midpoints hold it. */
        set_cap(touch, -4.0 - 5e-10, &c[3]);
        CHECK(prefilter(c, 4, &wp, pre) == 1 && pre[3]);
        c[3].h = vbx_ia_make(-4.0 - 2.5e-9, -4.0 + 1.5e-9);
        CHECK(prefilter(c, 4, &wp, pre) == 0);
        c[3].h = vbx_ia_point(-4.0 - 5e-10);
        c[3].n[2] = vbx_ia_make(-4.0 - 1e-9, -4.0 + 1e-9);
        CHECK(prefilter(c, 4, &wp, pre) == 0);
    }
    vbm_caps_free(&w);
    vbm_caps_free(&w2);
    vbm_caps_free(&wp);
    printf("cases %zu with rejections %zu rejected %zu points %zu compared %zu decided by both %zu "
           "(the kept caps' search undecided %zu) several arcs %zu\n",
           cases, with_rej, rejected, pts, compared, both, ret_differ, several);
    VB_TEST_END();
}
