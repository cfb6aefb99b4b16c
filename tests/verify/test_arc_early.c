/* Early tracing (vb_arc_early, vb_arc_close_early) on the corpus: with the
 * golden traced early in overlapping parts (every other vertex, then the
 * first half: the shared vertices traced twice), in one part that is the
 * whole golden, or in a part of a third of it, the closure of the golden
 * gives the report (every count and the added vertices) and the edges of
 * the closure without early events, on 1 and 3 threads; the vertices taken
 * early are those of the parts (all of them, or the third). A golden
 * traced early in full whose final list lacks one vertex (the end of arcs
 * traced early) gets that vertex back as added, as the closure of the cut
 * list without early events does: the proof fails. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_arc.h"
#include "vb_test.h"
#include "vb_verify.h"
#include "vt_case.h"
#include "vt_corpus.h"

/* The vertices k of g with keep(k), in order (sorted as g is). */
static void part_of(const vb_vertex_list *g, vb_vertex_list *out, int every, size_t lo, size_t hi,
                    size_t drop)
{
    vb_vertex_list_init(out);
    for (size_t k = lo; k < hi && k < g->n; k += (size_t)every)
        if (k != drop)
            vb_vertex_list_push(out, g->ids + g->start[k], g->start[k + 1] - g->start[k], g->x[k],
                                g->y[k], g->z[k], g->t[k], 0, VB_VERTEX_CERTIFIED);
}

static int same_report(const vb_arc_report *a, const vb_arc_report *b)
{
    if (a->vertices != b->vertices || a->half_arcs != b->half_arcs || a->closed != b->closed ||
        a->infinite != b->infinite || a->loops != b->loops || a->undecided != b->undecided ||
        a->components != b->components || a->added.n != b->added.n)
        return 0;
    const vb_vertex_list *x = &a->added, *y = &b->added;
    if (!x->n)
        return 1;
    if (x->start[x->n] != y->start[y->n])
        return 0;
    return memcmp(x->ids, y->ids, x->start[x->n] * sizeof *x->ids) == 0 &&
           memcmp(x->x, y->x, x->n * sizeof *x->x) == 0 &&
           memcmp(x->y, y->y, x->n * sizeof *x->y) == 0 &&
           memcmp(x->z, y->z, x->n * sizeof *x->z) == 0 &&
           memcmp(x->t, y->t, x->n * sizeof *x->t) == 0;
}

static int same_edges(const vb_topology_edge *a, size_t na, const vb_topology_edge *b, size_t nb)
{
    if (na != nb)
        return 0;
    for (size_t k = 0; k < na; k++)
        if (a[k].v[0] != b[k].v[0] || a[k].v[1] != b[k].v[1] ||
            memcmp(a[k].spheres, b[k].spheres, sizeof a[k].spheres) != 0)
            return 0;
    return 1;
}

/* The closure of fin with the early events of parts[0 .. np) (traced on
 * 2 threads) against the closure of fin without them, on `threads`;
 * *taken: the vertices taken early. */
static void early_case(vb_ctx *ctx, const vb_sphere_set *s, vb_certifier *c,
                       const vb_vertex_list *fin, vb_vertex_list *parts, int np, unsigned threads,
                       size_t *taken)
{
    vb_arc_report r0, r1;
    vb_topology_edge *e0 = NULL, *e1 = NULL;
    size_t n0 = 0, n1 = 0;
    CHECK_INT(vb_arc_close_edges(ctx, s, c, fin, threads, &r0, &e0, &n0), VB_OK);
    vb_arc_early *early = NULL;
    CHECK_INT(vb_arc_early_open(ctx, s, c, 2, &early), VB_OK);
    for (int p = 0; early && p < np; p++)
        CHECK_INT(vb_arc_early_part(ctx, early, &parts[p]), VB_OK);
    CHECK_INT(vb_arc_close_early(ctx, s, c, early, fin, threads, &r1, &e1, &n1), VB_OK);
    CHECK(same_report(&r0, &r1));
    CHECK(same_edges(e0, n0, e1, n1));
    size_t filled = 0;
    for (int p = 0; p < np; p++)
        filled += parts[p].n > 0;
    CHECK_INT(r1.early_parts, filled);
    CHECK(r1.early_events > 0 || r1.early_vertices == 0);
    *taken = r1.early_vertices;
    vb_arc_early_free(early);
    vb_arc_report_free(&r0);
    vb_arc_report_free(&r1);
    free(e0);
    free(e1);
}

static void one_case(const char *name, const char *in, const char *gold)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s;
    vb_vertex_list g;
    CHECK_INT(vt_read_case(ctx, in, gold, &s, &g), VB_OK);
    vb_certifier *c = NULL;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    if (!c || g.n < 2) {
        vb_certifier_close(c);
        vb_vertex_list_free(&g);
        vb_spheres_free(s);
        vb_close(ctx);
        return;
    }
    vb_vertex_list parts[2];
    size_t taken = 0;
    for (unsigned threads = 1; threads <= 3; threads += 2) {
        /* overlapping parts that cover the golden */
        part_of(&g, &parts[0], 2, 0, g.n, SIZE_MAX);
        part_of(&g, &parts[1], 1, 0, g.n / 2 + 1, SIZE_MAX);
        vb_vertex_list odd;
        part_of(&g, &odd, 2, 1, g.n, SIZE_MAX);
        vb_vertex_list_free(&parts[1]);
        parts[1] = odd;
        vb_vertex_list three[3];
        three[0] = parts[0];
        three[1] = parts[1];
        part_of(&g, &three[2], 1, 0, g.n / 2 + 1, SIZE_MAX);
        early_case(ctx, s, c, &g, three, 3, threads, &taken);
        CHECK_INT(taken, g.n);
        for (int p = 0; p < 3; p++)
            vb_vertex_list_free(&three[p]);
        /* a third of the golden early, the rest after */
        part_of(&g, &parts[0], 1, 0, g.n / 3, SIZE_MAX);
        early_case(ctx, s, c, &g, parts, 1, threads, &taken);
        CHECK_INT(taken, g.n / 3);
        vb_vertex_list_free(&parts[0]);
    }
    /* the whole golden early, a vertex missing from the final list: it is
     * an end of arcs traced early, and the closure adds it back */
    vb_vertex_list cut;
    size_t drop = g.n / 2;
    part_of(&g, &cut, 1, 0, g.n, drop);
    vb_vertex_list whole;
    part_of(&g, &whole, 1, 0, g.n, SIZE_MAX);
    early_case(ctx, s, c, &cut, &whole, 1, 2, &taken);
    CHECK_INT(taken, cut.n);
    vb_arc_early *early = NULL;
    vb_arc_report r;
    CHECK_INT(vb_arc_early_open(ctx, s, c, 2, &early), VB_OK);
    CHECK_INT(vb_arc_early_part(ctx, early, &whole), VB_OK);
    CHECK_INT(vb_arc_close_early(ctx, s, c, early, &cut, 2, &r, NULL, NULL), VB_OK);
    CHECK(!vb_arc_report_complete(&r));
    CHECK_INT(r.added.n, 1);
    if (r.added.n == 1) {
        size_t nm = g.start[drop + 1] - g.start[drop];
        CHECK(r.added.start[1] == nm &&
              memcmp(r.added.ids, g.ids + g.start[drop], nm * sizeof *g.ids) == 0 &&
              r.added.x[0] == g.x[drop] && r.added.t[0] == g.t[drop]);
    }
    fprintf(stderr, "%s: %zu vertices, %zu early events; cut at %zu: %zu added\n", name, g.n,
            r.early_events, drop, r.added.n);
    vb_arc_report_free(&r);
    vb_arc_early_free(early);
    vb_vertex_list_free(&cut);
    vb_vertex_list_free(&whole);
    vb_certifier_close(c);
    vb_vertex_list_free(&g);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    CHECK(vt_each_golden(one_case) >= 15);
    VB_TEST_END();
}
