/* The cover's label loops in four lanes (core/cells/vbq_lanes_shared.h)
 * against the loops the kernels keep (vbq_cover_cell's scalar forms): a
 * patch's first pass (vbq_lo_lanes: LO and every label's upper end), a
 * fetch's pass over its four parts (vbq_sub_lo_lanes: each part's LO) and
 * the second pass (vbq_keep_kept: the surviving labels, in order, the
 * owned count and the largest upper end) must give the same doubles, bit
 * for bit, and the same lists, since the cover's decisions and so its
 * quadruples follow from them. Random lists of 0 to 40 labels (every tail
 * length of the lanes), each pass also in two pieces (continued where
 * the first stopped, as a fetching patch's next pass is), with the edges
 * the cover meets: records of nested pairs (err infinite), repeated
 * records (equal enclosures, ties of the maxima), a zero floor and a positive one (tmax), boxes with an end
 * exactly 0, and floors above every label (no label raises LO). Also
 * vbq_looks_flat's distance pass in lanes (vbq_flat_far_lanes: the same
 * largest distance at the same first position, repeats making ties). */
#include "vb_test.h"

#include "vb_cover.h"

#ifndef VBQ_LANES
int main(void)
{
    printf("no vector lanes in this build (AVX2 only): nothing to compare\n");
    return 0;
}
#else

static uint64_t rng = 0x2545f4914f6cdd1dull;

#define uni(lo, hi) vb_test_uniform(&rng, (lo), (hi))

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

#define NREC 48u

int main(void)
{
#if defined(__GNUC__) && defined(__x86_64__)
    if (!__builtin_cpu_supports("avx2")) {
        printf("this CPU has no AVX2: the lanes are not run here\n");
        return 0;
    }
#endif
    vbq_nb nb[NREC];
    vbs_u32 lab[4u * NREC];
    double hi_lanes[NREC], hi_loop[NREC];
    vbq_arena ar;
    memset(&ar, 0, sizeof ar);
    ar.nb = nb;
    ar.lab = lab;
    long differ = 0, raised = 0, floor_kept = 0, kept = 0, dropped = 0, far_later = 0;
    for (int t = 0; t < 6000; t++) {
        /* Records of spheres around a base at the origin. */
        for (vbs_u32 j = 0; j < NREC; j++) {
            vbq_nb_make(0.0, 0.0, 0.0, 1.28, uni(-9.0, 9.0), uni(-9.0, 9.0), uni(-9.0, 9.0),
                        t % 3 ? 1.28 : uni(1.0, 1.6), j, &nb[j]);
            if (j % 11 == 4 && t % 2)
                nb[j].err = (double)INFINITY; /* a nested pair */
            if (j % 7 == 3)
                nb[j] = nb[j - 1u]; /* a repeat: equal enclosures */
            nb[j].id = j;
        }
        vbs_u32 len = (vbs_u32)(t % 41), off = (vbs_u32)(t % 5);
        for (vbs_u32 k = 0; k < len; k++)
            lab[off + k] = (vbs_u32)(rng % NREC), vb_test_xorshift(&rng);
        /* A patch and its four parts. */
        double u0 = uni(-1.0, 0.9), v0 = uni(-1.0, 0.9), side = uni(1e-7, 0.5);
        vbs_u32 f = (vbs_u32)(t % 6);
        double m[3], h[3];
        vbq_patch_box(f, u0, u0 + side, v0, v0 + side, m, h);
        if (t % 13 == 5)
            h[1] = m[1]; /* an end exactly 0 */
        vbq_sub sub[4];
        for (vbs_u32 g = 0; g < 4; g++)
            vbq_sub_box(f, u0, u0 + side, v0, v0 + side, g, sub[g].m, sub[g].h);
        double floor = t % 4 == 1 ? uni(0.0, 0.2) : t % 9 == 2 ? 10.0 : 0.0;

        /* The first pass: LO and the upper ends. */
        ar.hi = hi_lanes;
        double LO4 = vbq_lo_lanes(&ar, off, 0, len, m, h, floor);
        double LO = floor;
        for (vbs_u32 k = 0; k < len; k++) {
            double lo, hi;
            vbq_eval(&nb[lab[off + k]], m, h, &lo, &hi);
            LO = lo > LO ? lo : LO;
            hi_loop[k] = hi;
        }
        differ += !same_bits(LO, LO4);
        for (vbs_u32 k = 0; k < len; k++)
            differ += !same_bits(hi_loop[k], hi_lanes[k]);
        raised += LO > floor;
        floor_kept += len > 0 && LO == floor;
        /* The pass continued where an earlier one stopped (a fetching
         * patch popped again with its list lengthened): the same. */
        vbs_u32 k0 = len / 3u + (vbs_u32)(t % 3);
        k0 = k0 > len ? len : k0;
        double part = vbq_lo_lanes(&ar, off, 0, k0, m, h, floor);
        if (k0 < len)
            hi_lanes[k0] = -1.0; /* must be written again */
        differ += !same_bits(LO, vbq_lo_lanes(&ar, off, k0, len, m, h, part));
        for (vbs_u32 k = 0; k < len; k++)
            differ += !same_bits(hi_loop[k], hi_lanes[k]);
        /* Without the arena's upper ends: LO alone, the same. */
        ar.hi = NULL;
        differ += !same_bits(LO, vbq_lo_lanes(&ar, off, 0, len, m, h, floor));

        /* The fetch's pass over the four parts. */
        double lg4[4], fl4[4] = {floor, floor, floor, floor};
        vbq_sub_lo_lanes(&ar, off, 0, len, sub, fl4, lg4);
        double lgk[4], lgc[4];
        vbq_sub_lo_lanes(&ar, off, 0, k0, sub, fl4, lgk);
        vbq_sub_lo_lanes(&ar, off, k0, len, sub, lgk, lgc);
        for (vbs_u32 g = 0; g < 4; g++)
            differ += !same_bits(lg4[g], lgc[g]);
        for (vbs_u32 g = 0; g < 4; g++) {
            double lg = floor;
            for (vbs_u32 k = 0; k < len; k++) {
                double lo, hi;
                vbq_eval(&nb[lab[off + k]], sub[g].m, sub[g].h, &lo, &hi);
                lg = lo > lg ? lo : lg;
            }
            differ += !same_bits(lg, lg4[g]);
        }

        /* The second pass from the kept upper ends, against the loop. */
        ar.hi = hi_lanes;
        vbs_u32 top = off + len, base = (vbs_u32)(t % 17);
        double hm4 = -(double)INFINITY, hm = -(double)INFINITY;
        vbs_u32 owned4 = 0, owned = 0, keep = 0;
        vbs_u32 keep4 = vbq_keep_kept(&ar, off, len, top, base, LO, &hm4, &owned4);
        vbs_u32 got[NREC];
        memcpy(got, lab + top, keep4 * sizeof *got);
        for (vbs_u32 k = 0; k < len; k++) {
            double hi = hi_loop[k];
            hm = hi > hm ? hi : hm;
            if (hi >= LO) {
                differ += keep >= keep4 || got[keep] != lab[off + k];
                keep++;
                owned += nb[lab[off + k]].id > base;
            }
        }
        differ += keep != keep4 || owned != owned4 || !same_bits(hm, hm4);
        kept += keep;
        dropped += len - keep;

        /* vbq_looks_flat's distance pass: the farthest owned point from
         * the plane through p0 (v1, v2; v2 = 0 in its first pass). */
        double p0[4], v1[4], v2[4];
        for (int k = 0; k < 4; k++) {
            p0[k] = t % 5 == 0 && len ? nb[lab[off]].ax : uni(-0.2, 0.2);
            v1[k] = uni(-1.0, 1.0);
            v2[k] = t % 2 ? 0.0 : uni(-1.0, 1.0);
        }
        double far = -1.0, far4;
        vbs_u32 at = len, at4;
        for (vbs_u32 a = 0; a < len; a++) {
            const vbq_nb *r = &nb[lab[off + a]];
            if (r->id <= base)
                continue;
            double w[4] = {r->ax - p0[0], r->ay - p0[1], r->az - p0[2], r->b - p0[3]};
            double c1 = w[0] * v1[0] + w[1] * v1[1] + w[2] * v1[2] + w[3] * v1[3];
            double c2 = w[0] * v2[0] + w[1] * v2[1] + w[2] * v2[2] + w[3] * v2[3];
            double d2 = 0.0;
            for (int k = 0; k < 4; k++) {
                double e = w[k] - c1 * v1[k] - c2 * v2[k];
                d2 += e * e;
            }
            if (d2 > far) {
                far = d2;
                at = a;
            }
        }
        vbq_flat_far_lanes(nb, lab + off, len, base, p0, v1, v2, &far4, &at4);
        differ += !same_bits(far, far4) || at != at4;
        far_later += at != len && at % 4 != 0;
    }
    CHECK_INT(differ, 0);
    /* The cases occur often enough for the comparison to mean something. */
    CHECK(raised > 1000 && floor_kept > 200);
    CHECK(kept > 10000 && dropped > 10000);
    CHECK(far_later > 1000); /* the farthest in a lane other than the first */
    printf("lanes: LO raised %ld, floor kept %ld; labels kept %ld, dropped %ld\n", raised,
           floor_kept, kept, dropped);
    VB_TEST_END();
}
#endif
