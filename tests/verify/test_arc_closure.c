/* Arc closure (verify/arcs/vb_arc.h) on the corpus: every golden is closed (no
 * arc undecided, no vertex added, half arcs accounted for, each finite arc
 * seen from both ends); a golden with one vertex removed gets exactly that
 * vertex back, and one less every third vertex gets all of them back in
 * place; a golden cut down to its first vertex grows back to the whole
 * golden where the vertex-edge graph is connected (the component counts are
 * asserted); the report is the same on 1, 2 and 3 threads, and
 * vb_arc_complete_list restores the removed vertex in place. The traced
 * edges (vb_arc_complete_list_edges): one per finite edge (closed half arcs
 * / 2), one per half arc to infinity, each triple among its ends' members,
 * the same array on 1 and 3 threads (the 3- and a 2-thread run tracing with
 * a certifier lent to the closure, as the pipeline lends its own), and the
 * same edges with their rows in
 * the final list when the closure starts from the golden less a vertex or
 * from its first vertex alone (the vertices added on the way, sorted in).
 * vb_verify_arcs on a judged list traces with the judge's certifier (kept
 * in the report) and reports what vb_arc_close with its own one does. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_arc.h"
#include "vb_test.h"
#include "vb_verify_file.h"
#include "vb_vertex_io.h"
#include "vt_case.h"
#include "vt_corpus.h"

static int same_vertex(const vb_vertex_list *a, size_t i, const vb_vertex_list *b, size_t k)
{
    size_t na = a->start[i + 1] - a->start[i], nb = b->start[k + 1] - b->start[k];
    return na == nb &&
           memcmp(a->ids + a->start[i], b->ids + b->start[k], na * sizeof *a->ids) == 0 &&
           a->x[i] == b->x[k] && a->y[i] == b->y[k] && a->z[i] == b->z[k] && a->t[i] == b->t[k];
}

/* The list without the vertices whose index is not kept. */
static void subset(const vb_vertex_list *g, vb_vertex_list *out, size_t keep_from,
                   size_t keep_to, size_t drop)
{
    vb_vertex_list_init(out);
    for (size_t k = keep_from; k < keep_to; k++)
        if (k != drop)
            vb_vertex_list_push(out, g->ids + g->start[k], g->start[k + 1] - g->start[k], g->x[k],
                                g->y[k], g->z[k], g->t[k], 0, VB_VERTEX_CERTIFIED);
}

/* Edge arrays equal field by field (the struct has padding). */
static int same_edges(const vb_topology_edge *a, const vb_topology_edge *b, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (a[k].v[0] != b[k].v[0] || a[k].v[1] != b[k].v[1] ||
            memcmp(a[k].spheres, b[k].spheres, sizeof a[k].spheres) != 0)
            return 0;
    return 1;
}

/* The list cut judged (vb_verify_list) keeps its certifier for the set s,
 * and the closure of the judged report on 2 threads (tracing with it) is
 * the closure of cut with a certifier of its own, counters and added
 * vertices included. */
static void judged_lends(vb_ctx *ctx, const vb_sphere_set *s, const vb_vertex_list *cut)
{
    vb_verify_report rep;
    vb_arc_report own, lent;
    int rc = vb_verify_list(ctx, s, "cut", cut, VB_VFMT_TSV, 1e-6, 0, &rep);
    CHECK_INT(rc, VB_OK);
    CHECK(rep.cert != NULL && rep.cert_set == s);
    CHECK_INT(rep.counts.certified, cut->n);
    rc = vb_arc_close(ctx, s, cut, 2, &own);
    CHECK_INT(rc, VB_OK);
    rc = vb_verify_arcs(ctx, s, &rep, 2, &lent);
    CHECK_INT(rc, VB_OK);
    CHECK_INT(lent.vertices, own.vertices);
    CHECK_INT(lent.half_arcs, own.half_arcs);
    CHECK_INT(lent.closed, own.closed);
    CHECK_INT(lent.infinite, own.infinite);
    CHECK_INT(lent.components, own.components);
    CHECK_INT(lent.added.n, own.added.n);
    CHECK(lent.filter_calls == own.filter_calls && lent.exact_evals == own.exact_evals);
    CHECK(lent.candidates == own.candidates);
    for (size_t k = 0; k < own.added.n && k < lent.added.n; k++)
        CHECK(same_vertex(&lent.added, k, &own.added, k));
    vb_arc_report_free(&own);
    vb_arc_report_free(&lent);
    vb_verify_report_free(&rep);
    CHECK(rep.cert == NULL);
}

static int has_id(const vb_vertex_list *v, int64_t row, uint32_t id)
{
    for (size_t i = v->start[row]; i < v->start[row + 1]; i++)
        if (v->ids[i] == id)
            return 1;
    return 0;
}

/* The closed list and edges of the golden's vertices [from, to) less drop,
 * on `threads` threads, tracing with cert (NULL: the closure's own): *out
 * the closed list, *e its edges. */
static void closed_edges(vb_ctx *ctx, const vb_sphere_set *s, vb_certifier *cert,
                         const vb_vertex_list *g, size_t from, size_t to, size_t drop,
                         unsigned threads, vb_vertex_list *out, vb_topology_edge **e,
                         size_t *ne, vb_arc_report *r)
{
    subset(g, out, from, to, drop);
    int rc = vb_arc_complete_list_edges(ctx, s, cert, out, threads, r, e, ne);
    CHECK_INT(rc, VB_OK);
}

static void edges_case(vb_ctx *ctx, const vb_sphere_set *s, const vb_vertex_list *g,
                       size_t comps)
{
    vb_vertex_list l1, l3;
    vb_topology_edge *e1 = NULL, *e3 = NULL;
    size_t n1 = 0, n3 = 0;
    vb_arc_report r1, r3;
    /* the 3-thread run borrows a certifier opened here (as the pipeline's
     * is lent): the same counts and edges, and it stays open */
    vb_certifier *cert = NULL;
    CHECK_INT(vb_certifier_open(ctx, s, &cert), VB_OK);
    closed_edges(ctx, s, NULL, g, 0, g->n, (size_t)-1, 1, &l1, &e1, &n1, &r1);
    closed_edges(ctx, s, cert, g, 0, g->n, (size_t)-1, 3, &l3, &e3, &n3, &r3);
    CHECK_INT(n3, n1);
    CHECK(n1 == n3 && same_edges(e1, e3, n1));
    CHECK_INT(r3.half_arcs, r1.half_arcs);
    CHECK_INT(r3.closed, r1.closed);
    CHECK_INT(r3.components, r1.components);
    vb_vertex_list again;
    vb_topology_edge *ea = NULL;
    size_t na = 0;
    vb_arc_report ra;
    closed_edges(ctx, s, cert, g, 0, g->n, (size_t)-1, 2, &again, &ea, &na, &ra);
    CHECK(na == n1 && same_edges(ea, e1, n1));
    free(ea);
    vb_arc_report_free(&ra);
    vb_vertex_list_free(&again);
    vb_certifier_close(cert);
    size_t fin = 0, inf = 0;
    for (size_t k = 0; k < n1; k++) {
        const vb_topology_edge *e = &e1[k];
        CHECK(e->v[0] >= 0 && (size_t)e->v[0] < g->n);
        CHECK(e->v[1] >= -1 && e->v[1] < (int64_t)g->n);
        CHECK(e->spheres[0] < e->spheres[1] && e->spheres[1] < e->spheres[2]);
        if (e->v[1] < 0)
            inf++;
        else
            fin += e->v[1] != e->v[0];
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3 && e->v[i] >= 0; j++)
                CHECK(has_id(g, e->v[i], e->spheres[j]));
    }
    CHECK_INT(2 * fin, r1.closed);
    CHECK_INT(inf, r1.infinite);
    /* Starting from less: the vertices come back, the edges are the same. */
    for (int start = 0; start < 2; start++) {
        if (g->n < 2 || (start == 1 && comps != 1))
            continue;
        vb_vertex_list lc;
        vb_topology_edge *ec = NULL;
        size_t nc = 0;
        vb_arc_report rc;
        if (start == 0)
            closed_edges(ctx, s, NULL, g, 0, g->n, g->n / 2, 2, &lc, &ec, &nc, &rc);
        else
            closed_edges(ctx, s, NULL, g, 0, 1, (size_t)-1, 2, &lc, &ec, &nc, &rc);
        CHECK_INT(lc.n, g->n);
        CHECK(rc.added.n > 0);
        CHECK_INT(nc, n1);
        CHECK(nc == n1 && same_edges(ec, e1, n1));
        free(ec);
        vb_arc_report_free(&rc);
        vb_vertex_list_free(&lc);
    }
    free(e1);
    free(e3);
    vb_arc_report_free(&r1);
    vb_arc_report_free(&r3);
    vb_vertex_list_free(&l1);
    vb_vertex_list_free(&l3);
}

static void one_case(const char *name, const char *in, const char *gold)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s;
    vb_vertex_list g;
    int rc = vt_read_case(ctx, in, gold, &s, &g);
    CHECK_INT(rc, VB_OK);
    vb_arc_report r;
    rc = vb_arc_close(ctx, s, &g, 0, &r);
    CHECK_INT(rc, VB_OK);
    fprintf(stderr, "%s: %zu vertices, %zu half arcs: %zu closed, %zu infinite, %zu loops, "
            "%zu undecided, %zu added, %zu components\n", name, r.vertices, r.half_arcs,
            r.closed, r.infinite, r.loops, r.undecided, r.added.n, r.components);
    CHECK_INT(r.undecided, 0);
    CHECK_INT(r.added.n, 0);
    CHECK(vb_arc_report_complete(&r));
    CHECK_INT(r.vertices, g.n);
    CHECK_INT(r.closed + r.infinite + r.loops, r.half_arcs);
    CHECK_INT(r.closed % 2, 0);
    /* internally_tangent: its one vertex lies on the edge of 1, 2, 3 and
     * nothing else leaves it (two half arcs) */
    CHECK(g.n == 0 || r.half_arcs >= 4 * g.n || r.half_arcs >= 4 ||
          (strcmp(name, "internally_tangent.xyzr") == 0 && r.half_arcs == 2));
    size_t comps = r.components;
    /* coplanar_centres: the lens cell of sphere 8 (vertices 0,7,8,10 above
     * and below the plane, three edges between them, one each to infinity)
     * is a component of its own; every other golden is connected. */
    CHECK_INT(comps, strcmp(name, "coplanar_centres.xyzr") == 0 ? 2 : 1);
    vb_arc_report_free(&r);
    if (g.n >= 2) {
        size_t drop = g.n / 2;
        vb_vertex_list cut;
        subset(&g, &cut, 0, g.n, drop);
        rc = vb_arc_close(ctx, s, &cut, 0, &r);
        CHECK_INT(rc, VB_OK);
        CHECK_INT(r.added.n, 1);
        CHECK(!vb_arc_report_complete(&r));
        if (r.added.n == 1)
            CHECK(same_vertex(&r.added, 0, &g, drop));
        vb_arc_report_free(&r);
        vb_vertex_list_free(&cut);
    }
    if (g.n >= 2) {
        /* Rounds on threads: the golden less its middle vertex closed on 1,
         * 2 and 3 threads gives the same report, counters included, and
         * vb_arc_complete_list puts the vertex back where it was. */
        vb_vertex_list cut;
        subset(&g, &cut, 0, g.n, g.n / 2);
        vb_arc_report rt[3];
        for (unsigned t = 0; t < 3; t++) {
            rc = vb_arc_close(ctx, s, &cut, t + 1, &rt[t]);
            CHECK_INT(rc, VB_OK);
        }
        for (unsigned t = 1; t < 3; t++) {
            CHECK_INT(rt[t].vertices, rt[0].vertices);
            CHECK_INT(rt[t].half_arcs, rt[0].half_arcs);
            CHECK_INT(rt[t].closed, rt[0].closed);
            CHECK_INT(rt[t].infinite, rt[0].infinite);
            CHECK_INT(rt[t].components, rt[0].components);
            CHECK_INT(rt[t].added.n, rt[0].added.n);
            CHECK(rt[t].filter_calls == rt[0].filter_calls);
            CHECK(rt[t].filter_failures == rt[0].filter_failures);
            CHECK(rt[t].exact_evals == rt[0].exact_evals);
            CHECK(rt[t].candidates == rt[0].candidates);
            for (size_t k = 0; k < rt[0].added.n && k < rt[t].added.n; k++)
                CHECK(same_vertex(&rt[t].added, k, &rt[0].added, k));
        }
        for (unsigned t = 0; t < 3; t++)
            vb_arc_report_free(&rt[t]);
        judged_lends(ctx, s, &cut);
        rc = vb_arc_complete_list(ctx, s, &cut, 2, &r);
        CHECK_INT(rc, VB_OK);
        CHECK_INT(r.added.n, 1);
        CHECK_INT(cut.n, g.n);
        for (size_t k = 0; k < g.n && k < cut.n; k++)
            CHECK(same_vertex(&cut, k, &g, k));
        char line[512];
        vb_arc_certificate(&r, line, sizeof line);
        CHECK(strncmp(line, "arcs: every arc closed exactly: ", 32) == 0);
        CHECK(strstr(line, "; 1 vertices added by tracing; ") != NULL);
        vb_arc_report_free(&r);
        vb_vertex_list_free(&cut);
    }
    if (g.n >= 3) {
        /* Every third vertex dropped: forward arcs then end at listed
         * vertices beyond the dropped ones (the bounded searches at the
         * apex of the arc between them must see the sphere that cuts it),
         * and all the dropped vertices come back in place. */
        vb_vertex_list cut;
        vb_vertex_list_init(&cut);
        size_t dropped = 0;
        for (size_t k = 0; k < g.n; k++) {
            if (k % 3 == 1) {
                dropped++;
                continue;
            }
            vb_vertex_list_push(&cut, g.ids + g.start[k], g.start[k + 1] - g.start[k], g.x[k],
                                g.y[k], g.z[k], g.t[k], 0, VB_VERTEX_CERTIFIED);
        }
        rc = vb_arc_complete_list(ctx, s, &cut, 2, &r);
        CHECK_INT(rc, VB_OK);
        CHECK_INT(r.undecided, 0);
        CHECK_INT(r.added.n, dropped);
        CHECK_INT(cut.n, g.n);
        for (size_t k = 0; k < g.n && k < cut.n; k++)
            CHECK(same_vertex(&cut, k, &g, k));
        vb_arc_report_free(&r);
        vb_vertex_list_free(&cut);
    }
    if (g.n >= 2 && comps == 1) {
        vb_vertex_list one;
        subset(&g, &one, 0, 1, (size_t)-1);
        rc = vb_arc_close(ctx, s, &one, 0, &r);
        CHECK_INT(rc, VB_OK);
        CHECK_INT(r.added.n + 1, g.n);
        CHECK_INT(r.vertices, g.n);
        vb_arc_report_free(&r);
        vb_vertex_list_free(&one);
    }
    edges_case(ctx, s, &g, comps);
    vb_vertex_list_free(&g);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    CHECK(vt_each_golden(one_case) >= 15);
    VB_TEST_END();
}
