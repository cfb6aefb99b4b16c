/* The apex of a bounded arc found in u (vbx_apex_point, arc_region.c)
 * against the one drawn in the plane's frame (vbx_apex_box, mapped to u by
 * u = O + S ES + G EG): on every pair of golden vertices v before w of an
 * open triple of crambin_fragment, jittered_fcc and coplanar_centres, both
 * boxes enclose the exact apex, so they must meet on every coordinate;
 * the point's box lies on the plane (m_b . A - W_b / 2 and m_c . A -
 * W_c / 2 enclose 0), and the point's region clears a sphere only where
 * the plane apex's box does not prove L_j < 0 (both are enclosures of
 * L_j(A)). Where an end lacks its tangent, the search is left to the plane
 * (vbx_apex_point answers 0). Planted: alpha's numerator with s_v for s_w,
 * or A taken from w's point with v's tangent: both fail the meets. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_vertex_io.h"
#include "vt_case.h"
#include "vb_verify.h"
#include "vbx_closure.h"
#include "vbx_plane.h"
#include "vbx_region.h"

static int meets(vbx_ia a, vbx_ia b)
{
    return a.lo <= b.hi && b.lo <= a.hi;
}

static int has_triple(const uint32_t *m, size_t nm, const uint32_t t[3])
{
    int n = 0;
    for (size_t i = 0; i < nm; i++)
        n += m[i] == t[0] || m[i] == t[1] || m[i] == t[2];
    return n == 3;
}

typedef struct tally {
    size_t pairs, planes, points, no_tau, bad_meet, bad_plane, bad_clear;
} tally;

/* The two apexes of the arc from vertex v to w (boxes bv, bw) of frame f. */
static void one_pair(vbx_arcw *w, vbx_tframe *f, const vbx_ia bv[4], const vbx_ia bw[4],
                     tally *ty)
{
    vbx_key kv, kw;
    vbx_key_of_box(w, f, bv, &kv);
    vbx_key_of_box(w, f, bw, &kw);
    if (vbx_pos_cmp(w, f, &kv, NULL, &kw, NULL) != -1)
        return;
    ty->pairs++;
    vbx_ia tv[4], tw[4];
    vbx_tau_of_box(w, f, bv, tv);
    vbx_tau_of_box(w, f, bw, tw);
    vbx_arc_end e0 = {0}, e1 = {0};
    e0.key = kv;
    e1.key = kw;
    e0.box = bv;
    e1.box = bw;
    e0.tau = tv;
    vbx_region rp;
    vbx_region_clear(&rp);
    /* one end without its tangent: left to the plane */
    ty->no_tau += vbx_apex_point(w, f, &e0, &e1, &rp) == 0;
    e1.tau = tw;
    if (!vbx_apex_point(w, f, &e0, &e1, &rp))
        return;
    ty->points++;
    vbx_part pb;
    if (!vbx_apex_box(f, kv.G, kw.G, &pb))
        return;
    ty->planes++;
    const vbx_ia *A = rp.p[0].u;
    int ok = rp.n == 1 && rp.p[0].kind == VBX_PART_POINT;
    for (int k = 0; k < 4; k++) {
        vbx_ia x[3] = {pb.S, pb.G, vbx_ia_point(1.0)}, y[3] = {f->ES[k], f->EG[k], f->O[k]};
        ok &= meets(A[k], vb_ia_dot(x, y, 3));
    }
    ty->bad_meet += !ok;
    vbx_ia half = vbx_ia_point(0.5);
    vbx_ia rb = vbx_ia_sub(vbx_ia_dot4(f->mb, A), vbx_ia_mul(f->Wb, half));
    vbx_ia rc = vbx_ia_sub(vbx_ia_dot4(f->mc, A), vbx_ia_mul(f->Wc, half));
    ty->bad_plane += !(rb.lo <= 0.0 && rb.hi >= 0.0 && rc.lo <= 0.0 && rc.hi >= 0.0);
    vbx_region rg;
    vbx_region_clear(&rg);
    rg.p[0] = pb;
    rg.n = 1;
    for (uint32_t j = 0; j < w->set->n; j++) {
        if (j == f->t[0] || j == f->t[1] || j == f->t[2])
            continue;
        if (!vbx_clear_of(w, f, &rp, j))
            continue;
        /* cleared at the point: the plane's box must not prove L_j < 0
         * there (L_j affine: its enclosure over the box holds L_j(A)) */
        const vbx_ia *ba = &w->c->d.box[4 * (size_t)f->t[0]], *bj = &w->c->d.box[4 * (size_t)j];
        vbx_ia m[4], x[8], y[8], u[4];
        for (int k = 0; k < 4; k++) {
            vbx_ia xs[3] = {pb.S, pb.G, vbx_ia_point(1.0)}, ys[3] = {f->ES[k], f->EG[k], f->O[k]};
            u[k] = vb_ia_dot(xs, ys, 3);
            m[k] = vbx_ia_sub(bj[k], ba[k]);
        }
        for (int k = 0; k < 4; k++) {
            x[k] = k < 3 ? m[k] : vbx_ia_neg(m[k]);
            y[k] = m[k];
            x[4 + k] = m[k];
            y[4 + k] = vbx_ia_make(-2.0 * u[k].hi, -2.0 * u[k].lo);
        }
        ty->bad_clear += vb_ia_dot(x, y, 8).hi < 0.0;
    }
}

static void apex_case(const char *name, tally *ty)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s;
    vb_vertex_list g;
    CHECK_INT(vt_read_named(ctx, name, &s, &g), VB_OK);
    vb_certifier *c = NULL;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    vbx_arcw w;
    CHECK_INT(vbx_arcw_init(&w, ctx, c), VB_OK);
    vbx_tframe f;
    vbx_tframe_init(&f);
    for (size_t k = 0; k < g.n && k < 150; k++) {
        const uint32_t *m = g.ids + g.start[k];
        size_t nm = g.start[k + 1] - g.start[k];
        double p[4];
        vbx_ia bv[4];
        vbx_vertex_point(&g, k, p);
        vbx_box_of_rounded(p, bv);
        for (size_t a = 0; a < nm; a++)
            for (size_t b = a + 1; b < nm; b++)
                for (size_t d = b + 1; d < nm; d++) {
                    uint32_t t[3] = {m[a], m[b], m[d]};
                    vbx_tframe_reset(&f);
                    CHECK_INT(vbx_tframe_setup(&w, &f, t), VB_OK);
                    if (f.kind != VBX_TRI_OPEN || !f.ok)
                        continue;
                    for (size_t k2 = 0; k2 < g.n; k2++) {
                        if (k2 == k || !has_triple(g.ids + g.start[k2],
                                                   g.start[k2 + 1] - g.start[k2], t))
                            continue;
                        double p2[4];
                        vbx_ia bw[4];
                        vbx_vertex_point(&g, k2, p2);
                        vbx_box_of_rounded(p2, bw);
                        one_pair(&w, &f, bv, bw, ty);
                    }
                }
    }
    vbx_tframe_clear(&f);
    vbx_arcw_free(&w);
    vb_certifier_close(c);
    vb_vertex_list_free(&g);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    tally ty = {0};
    apex_case("crambin_fragment", &ty);
    apex_case("jittered_fcc", &ty);
    apex_case("coplanar_centres", &ty);
    fprintf(stderr,
            "apex: %zu arcs, %zu apexes in u, %zu also in the plane; %zu left to the plane "
            "without a tangent\n",
            ty.pairs, ty.points, ty.planes, ty.no_tau);
    CHECK(ty.planes > 100);
    CHECK(ty.points >= ty.planes);
    CHECK_INT((long long)ty.no_tau, (long long)ty.pairs);
    CHECK_INT((long long)ty.bad_meet, 0);
    CHECK_INT((long long)ty.bad_plane, 0);
    CHECK_INT((long long)ty.bad_clear, 0);
    VB_TEST_END();
}
