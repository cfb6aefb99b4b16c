/* The cover walk's two ways of asking the four parts of a fetch
 * (core/cells/vbq_gather_shared.h): one part after the other
 * (vbq_walk_node1, vbq_walk_parts1: the kernels' loops) and the four side
 * by side (vbq_walk_node4, vbq_walk_parts4: the host, and the work-item
 * kernel on CPU devices) must give the same answer for every node and
 * every record, since the cover's lists, and so its quadruples, follow
 * from those answers. Random walks and nodes, with the edges the cover
 * meets: parts whose LO is 0 (no reach), a ring unbounded outside (rq1
 * infinite), empty node boxes (lo +inf, hi -inf), parts whose box end is
 * exactly 0 (0 * inf is NaN), offsets straddling the base, and values
 * near the decision's threshold. Both answers occur often (counted).
 * Also the ring test of a leaf at once (vbq_walk_ring8) against the one
 * by sphere id. */
#include "vb_test.h"

#include "vb_cover.h"

#ifndef VBQ_WALK_V4
int main(void)
{
    printf("no vector lanes in this build: nothing to compare\n");
    return 0;
}
#else

static uint64_t rng = 0x9e3779b97f4a7c15ull;

/* Uniform in [lo, hi). */
static double uni(double lo, double hi)
{
    vb_test_xorshift(&rng);
    return lo + (hi - lo) * (double)(rng >> 11) * 0x1p-53;
}

/* Four parts of a random patch; kind picks the edges. */
static void make_parts(vbq_sub sub[4], int kind)
{
    double u0 = uni(-1.0, 0.9), v0 = uni(-1.0, 0.9), side = uni(1e-6, 0.1);
    for (vbs_u32 g = 0; g < 4; g++) {
        vbq_sub_box((vbs_u32)(kind % 6), u0, u0 + side, v0, v0 + side, g, sub[g].m, sub[g].h);
        if (kind % 5 == 1 && g == 1)
            sub[g].h[0] = sub[g].m[0]; /* an end exactly 0 */
        double lo = kind % 3 == 0 && g % 2 ? 0.0 : uni(0.0, 0.4);
        vbq_sub_set_lo(&sub[g], lo);
    }
}

int main(void)
{
    vbq_env e;
    memset(&e, 0, sizeof e);
    double xs[1] = {0.0}, rs[1] = {1.6};
    e.x = e.y = e.z = xs;
    e.r = rs;
    long pass_node = 0, fail_node = 0, pass_rec = 0, fail_rec = 0, differ = 0;
    for (int t = 0; t < 4000; t++) {
        vbq_sub sub[4];
        make_parts(sub, t);
        double rq0 = t % 4 == 0 ? -1.0 : uni(0.0, 6.0);
        double rq1 = t % 7 == 0 ? (double)INFINITY : rq0 + uni(0.5, 12.0);
        vbq_walk w;
        vbq_walk_make(&e, 0u, rq0, rq1, sub, VBQ_NSUB, &w);
        for (int k = 0; k < 60; k++) {
            double b0[3], b1[3], mag = 0.0;
            double reach = uni(0.5, 3.0) * (k % 3 ? 4.0 : 1.0);
            for (int a = 0; a < 3; a++) {
                if (k % 17 == 5) {
                    b0[a] = (double)INFINITY; /* an empty node */
                    b1[a] = -(double)INFINITY;
                } else {
                    double c = uni(-reach, reach), half = uni(0.0, reach * 0.5);
                    b0[a] = c - half;
                    b1[a] = c + half;
                }
                mag += fabs(b0[a]) + fabs(b1[a]);
            }
            double slack = k % 11 == 0 ? 0.0 : uni(-0.6, 0.6);
            int n1 = vbq_walk_node1(&w, b0, b1, slack, mag);
            int n4 = vbq_walk_node4(&w, b0, b1, slack, mag);
            differ += n1 != n4;
            pass_node += n1 != 0;
            fail_node += n1 == 0;

            vbq_nb rec;
            vbq_nb_make(0.0, 0.0, 0.0, 1.6, uni(-6.0, 6.0), uni(-6.0, 6.0), uni(-6.0, 6.0),
                        uni(1.2, 2.0), 1u, &rec);
            if (k % 13 == 7)
                rec.err = (double)INFINITY; /* a nested pair: kept everywhere */
            int r1 = vbq_walk_parts1(&w, &rec), r4 = vbq_walk_parts4(&w, &rec);
            differ += r1 != r4;
            pass_rec += r1 != 0;
            fail_rec += r1 == 0;
        }
    }
    /* The ring test of a leaf's eight positions at once (vbq_walk_ring8,
     * from the tree-ordered copies) against vbq_walk_ring by sphere id. */
    long in_ring = 0, out_ring = 0;
    for (int t = 0; t < 20000; t++) {
        double x[9], y[9], z[9], r[9], kx[8], ky[8], kz[8], kr[8];
        vbs_u32 ids[8];
        x[8] = y[8] = z[8] = 0.0; /* the base: sphere 8 */
        r[8] = 1.6;
        for (int k = 0; k < 8; k++) {
            ids[k] = (vbs_u32)(7 - k); /* tree order differs from id order */
            x[7 - k] = kx[k] = t % 9 == 0 && k == 3 ? 2.0 : uni(-9.0, 9.0);
            y[7 - k] = ky[k] = t % 9 == 0 && k == 3 ? 0.0 : uni(-9.0, 9.0);
            z[7 - k] = kz[k] = t % 9 == 0 && k == 3 ? 0.0 : uni(-9.0, 9.0);
            r[7 - k] = kr[k] = 1.5;
        }
        vbq_env by_id;
        memset(&by_id, 0, sizeof by_id);
        by_id.x = x;
        by_id.y = y;
        by_id.z = z;
        by_id.r = r;
        by_id.ids = ids;
        vbq_env tree = by_id;
        tree.kx = kx;
        tree.ky = ky;
        tree.kz = kz;
        tree.kr = kr;
        /* t % 9 == 0: a sphere exactly on the inner bound rq0 = 2. */
        double rq0 = t % 9 == 0 ? 2.0 : t % 4 == 0 ? -1.0 : uni(0.0, 6.0);
        double rq1 = t % 7 == 0 ? (double)INFINITY : rq0 + uni(0.5, 9.0);
        vbq_walk w;
        vbq_walk_make(&by_id, 8u, rq0, rq1, NULL, 0u, &w);
        unsigned bits = vbq_walk_ring8(&tree, &w, 0u);
        for (vbs_u32 k = 0; k < 8; k++) {
            vbs_u32 j;
            int one = vbq_walk_ring(&by_id, &w, k, &j);
            differ += one != (int)((bits >> k) & 1u);
            in_ring += one;
            out_ring += !one;
        }
    }
    CHECK(in_ring > 20000 && out_ring > 20000);
    CHECK_INT(differ, 0);
    /* Both answers are common, so the comparison means something. */
    CHECK(pass_node > 20000 && fail_node > 20000);
    CHECK(pass_rec > 20000 && fail_rec > 20000);
    printf("nodes %ld pass %ld fail, records %ld kept %ld dropped\n", pass_node, fail_node,
           pass_rec, fail_rec);
    VB_TEST_END();
}
#endif
