/* Per-frame periodic boxes of trajectories (core/input/frame_box.c): the
 * XTC/TRR box vectors and the DCD unit cell as exact decimal boxes, and
 * vb_frame_source_next setting each frame's box, on the corpus
 * trajectories that carry one (ngl_md_10frames.xtc and .trr: a cubic box
 * that changes every frame, as MDAnalysis reads it in
 * corpus/golden/trajectories/). */
#include <stdio.h>

#include "input_test_util.h"
#include "vb_frames.h"
#include "vb_periodic.h"

static void xdr_boxes(void)
{
    vb_box b;
    /* The float nearest 5.6064 nm is 56.064 A exactly, not its binary tail. */
    const double nm[9] = {(float)5.6064, 0, 0, 0, (float)5.6035, 0, 0, 0, (float)4.0008};
    CHECK_INT(vb_frame_box_xdr(nm, 0, &b), 1);
    CHECK(dec_is(b.ev[0], "56.064") && dec_is(b.ev[4], "56.035") && dec_is(b.ev[8], "40.008"));
    CHECK(dec_is(b.ev[1], "0") && dec_is(b.ev[3], "0") && b.v[0] == 56.064);
    /* A double-precision TRR: its double's shortest decimal. */
    const double dd[9] = {2.5, 0, 0, 0.125, 3, 0, 0, 0, 1.0000001};
    CHECK_INT(vb_frame_box_xdr(dd, 1, &b), 1);
    CHECK(dec_is(b.ev[3], "1.25") && dec_is(b.ev[8], "10.000001"));
    /* No box: zero, or flat. */
    const double zero[9] = {0};
    CHECK_INT(vb_frame_box_xdr(zero, 0, &b), 0);
    const double flat[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0};
    CHECK_INT(vb_frame_box_xdr(flat, 0, &b), 0);
}

static void dcd_cells(void)
{
    vb_box b, c;
    /* A, gamma, B, beta, alpha, C: cosines (newer CHARMM) or degrees. */
    const double cos_cell[6] = {50.5, 0.0, 60, 0.0, 0.0, 70.25};
    CHECK_INT(vb_frame_box_dcd(cos_cell, &b), 1);
    CHECK(dec_is(b.ev[0], "50.5") && dec_is(b.ev[4], "60") && dec_is(b.ev[8], "70.25"));
    CHECK(dec_is(b.ev[3], "0") && dec_is(b.ev[6], "0") && dec_is(b.ev[7], "0"));
    const double deg_cell[6] = {50.5, 90, 60, 90, 90, 70.25};
    CHECK_INT(vb_frame_box_dcd(deg_cell, &c), 1);
    for (int k = 0; k < 9; k++)
        CHECK(vb_decimal_cmp(b.ev[k], c.ev[k]) == 0);
    /* gamma 120 degrees, as degrees and as its cosine -0.5: b = (-5, 8.660254, 0). */
    const double hex_deg[6] = {10, 120, 10, 90, 90, 10};
    const double hex_cos[6] = {10, -0.5, 10, 0, 0, 10};
    CHECK_INT(vb_frame_box_dcd(hex_deg, &b), 1);
    CHECK_INT(vb_frame_box_dcd(hex_cos, &c), 1);
    CHECK(dec_is(b.ev[3], "-5") && dec_is(b.ev[4], "8.660254") && dec_is(b.ev[8], "10"));
    for (int k = 0; k < 9; k++)
        CHECK(vb_decimal_cmp(b.ev[k], c.ev[k]) == 0);
    /* No cell (zeros, as a DCD without one reads): no box. */
    const double none[6] = {0};
    CHECK_INT(vb_frame_box_dcd(none, &b), 0);
}

/* The boxes of MDAnalysis' reading of the same files, nm (first three frames). */
static void frame_source_boxes(vb_ctx *ctx, const char *traj)
{
    static const char *const want[3] = {"56.064", "56.035", "56.068"};
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.keep_water = 1;
    vb_frame_source *F = NULL;
    char topo[4096];
    snprintf(topo, sizeof topo, "%s", corpus_path("data/ngl_md_ascii_trj.pdb"));
    CHECK_INT(vb_frame_source_open(ctx, topo, corpus_path(traj), &o, &F), VB_OK);
    int frames = 0, boxes = 0, model;
    vb_sphere_set *s = NULL;
    while (F && vb_frame_source_next(ctx, F, &s, &model) == VB_OK && s) {
        if (s->box) {
            boxes++;
            if (frames < 3)
                CHECK(dec_is(s->box->ev[0], want[frames]) && dec_is(s->box->ev[4], want[frames]) &&
                      dec_is(s->box->ev[8], want[frames]) && dec_is(s->box->ev[1], "0"));
        }
        frames++;
        vb_spheres_free(s);
    }
    vb_frame_source_close(F);
    CHECK_INT(frames, 10);
    CHECK_INT(boxes, 10);
}

int main(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    xdr_boxes();
    dcd_cells();
    frame_source_boxes(ctx, "data/ngl_md_10frames.xtc");
    frame_source_boxes(ctx, "data/ngl_md_10frames.trr");
    vb_close(ctx);
    VB_TEST_END();
}
