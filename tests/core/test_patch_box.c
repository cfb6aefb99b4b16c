/* The patch's box of directions (vbq_patch_box, core/cells/vb_cover_shared.h)
 * on known squares of every cube face: it must hold every direction of the
 * square (a 41 x 41 grid of them, vbs_face_dir) and be tight, its ends
 * within 1e-12 of the exact extremes, which lie among the nine points
 * (corners, the clamped zeros on the edges, the clamped centre): the root
 * halves, squares straddling an axis (the face axis extreme inside), dyadic
 * squares of the cover's levels and thin ones. A swapped extreme (a min
 * kept as a max, lo and hi exchanged, a clamp at the wrong end) fails here
 * at once instead of stalling the cover. */
#include "vb_test.h"

#include "vb_cover.h"

static long n_squares, n_points;

static void check_square(vbs_u32 f, double u0, double u1, double v0, double v1)
{
    double m[3], h[3];
    vbq_patch_box(f, u0, u1, v0, v1, m, h);
    /* the exact extremes: the nine points */
    double uc = u0 > 0.0 ? u0 : (u1 < 0.0 ? u1 : 0.0), vc = v0 > 0.0 ? v0 : (v1 < 0.0 ? v1 : 0.0);
    double us[3] = {u0, u1, uc}, vs[3] = {v0, v1, vc}, lo[3] = {2, 2, 2}, hi[3] = {-2, -2, -2};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double d[3];
            vbs_face_dir(f, us[a], vs[b], d);
            for (int k = 0; k < 3; k++) {
                lo[k] = d[k] < lo[k] ? d[k] : lo[k];
                hi[k] = d[k] > hi[k] ? d[k] : hi[k];
            }
        }
    int bad = 0;
    for (int k = 0; k < 3; k++) {
        CHECK(h[k] >= 0.0);
        /* holds the extremes, and no wider than 1e-12 past them */
        bad += !(m[k] - h[k] <= lo[k] && m[k] + h[k] >= hi[k]);
        bad += !(m[k] - h[k] >= lo[k] - 1e-12 && m[k] + h[k] <= hi[k] + 1e-12);
    }
    /* every direction of the square inside (and none past the nine's extremes) */
    for (int i = 0; i <= 40; i++)
        for (int j = 0; j <= 40; j++) {
            double u = u0 + (u1 - u0) * (double)i / 40.0, v = v0 + (v1 - v0) * (double)j / 40.0;
            double d[3];
            vbs_face_dir(f, u, v, d);
            for (int k = 0; k < 3; k++) {
                bad += !(fabs(d[k] - m[k]) <= h[k]);
                bad += !(d[k] >= lo[k] - 1e-15 && d[k] <= hi[k] + 1e-15);
            }
            n_points++;
        }
    CHECK_INT(bad, 0);
    if (bad)
        fprintf(stderr, "  face %u [%g, %g] x [%g, %g]: m (%g %g %g) h (%g %g %g), want [%g %g %g] .. "
                        "[%g %g %g]\n",
                f, u0, u1, v0, v1, m[0], m[1], m[2], h[0], h[1], h[2], lo[0], lo[1], lo[2], hi[0],
                hi[1], hi[2]);
    n_squares++;
}

int main(void)
{
    /* the face's box is known in closed form at the whole face: the face
     * axis in [1/sqrt(3), 1] (sign by face), the others in [-1/sqrt(2),
     * 1/sqrt(2)] (at the edge centres) */
    for (vbs_u32 f = 0u; f < 6u; f++) {
        double m[3], h[3];
        vbq_patch_box(f, -1.0, 1.0, -1.0, 1.0, m, h);
        vbs_u32 ax = f / 2u;
        double sgn = (f & 1u) ? -1.0 : 1.0;
        for (vbs_u32 k = 0u; k < 3u; k++) {
            double lo = k == ax ? (sgn > 0 ? 1.0 / sqrt(3.0) : -1.0) : -sqrt(0.5);
            double hi = k == ax ? (sgn > 0 ? 1.0 : -1.0 / sqrt(3.0)) : sqrt(0.5);
            CHECK(fabs((m[k] - h[k]) - lo) < 1e-12 && fabs((m[k] + h[k]) - hi) < 1e-12);
        }
        check_square(f, -1.0, 1.0, -1.0, 1.0);
        /* the root halves (T = 2, level 0) and the cover's dyadic levels */
        for (vbs_u32 level = 0u; level < 4u; level++) {
            vbs_u64 side = (vbs_u64)2 << level;
            for (vbs_u64 iu = 0u; iu < side; iu++)
                for (vbs_u64 iv = 0u; iv < side; iv++) {
                    double u0, u1, v0, v1;
                    vbq_patch_square(2u, level, iu, iv, &u0, &u1, &v0, &v1);
                    check_square(f, u0, u1, v0, v1);
                }
        }
        /* straddling an axis (a clamped zero inside an edge), off-centre */
        check_square(f, -0.3, 0.5, 0.2, 0.7);
        check_square(f, 0.2, 0.7, -0.6, 0.1);
        check_square(f, -0.9, -0.4, -0.25, 0.75);
        check_square(f, -0.5, -0.1, -0.9, -0.3);
        check_square(f, -0.125, 0.375, -0.875, 0.0625);
        /* thin: one edge long, one 2^-30 */
        check_square(f, 0.5, 0.5 + 0x1p-30, -1.0, 1.0);
        check_square(f, -1.0, 1.0, -0.25 - 0x1p-30, -0.25);
    }
    printf("%ld squares, %ld directions\n", n_squares, n_points);
    CHECK(n_squares == 6 * (1 + 4 + 16 + 64 + 256 + 7));
    VB_TEST_END();
}
