/* Unit tests of the front door's completion stage (lib/vb_complete.h):
 * where the topology comes from, the whole vertex flow in one call on a
 * corpus case whose diagram is known (the 3x3x3 cubic lattice: 8 vertices
 * at the cube centres, each of degree 8), and the warnings it raises,
 * caught through the context's log callback. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_test_spheres.h"
#include "vorball.h"

static void test_plan(void)
{
    vb_vertices_config cfg = {0};
    vb_completion_opts o = {0};
    cfg.propose.threads = 3;
    o.topology = 1;
    vb_completion_plan(&cfg, &o); /* the cover: exact, from arc closure */
    CHECK_INT(o.arcs, 1);
    CHECK_INT(cfg.propose.topology, 0);
    CHECK_INT(o.threads, 3);
    memset(&o, 0, sizeof o);
    cfg.proposer = "sampling";
    o.topology = 1;
    vb_completion_plan(&cfg, &o); /* sampling alone: its evidence */
    CHECK_INT(o.arcs, 0);
    CHECK_INT(cfg.propose.topology, 1);
    o.arcs = 1;
    vb_completion_plan(&cfg, &o); /* sampling with arcs: exact */
    CHECK_INT(o.arcs, 1);
    CHECK_INT(cfg.propose.topology, 0);
    memset(&o, 0, sizeof o);
    cfg.propose.topology = 0;
    vb_completion_plan(&cfg, &o); /* no topology: nothing changes */
    CHECK_INT(o.arcs, 0);
    CHECK_INT(cfg.propose.topology, 0);
}

typedef struct seen {
    int n, number[8];
} seen;

static void keep(void *arg, const vb_diag_record *r)
{
    seen *s = arg;
    if (s->n < 8)
        s->number[s->n++] = r->number;
}

static vb_sphere_set *lattice(vb_ctx *ctx)
{
    vb_sphere_set *set = vb_test_corpus_load(ctx, "cubic_lattice");
    CHECK(set != NULL);
    return set;
}

static void test_lattice_in_one_call(vb_ctx *ctx, vb_sphere_set *set)
{
    vb_vertices_config cfg = {0};
    cfg.device = VB_DEVICE_REF;
    vb_completion_opts o = {0};
    o.topology = 1;
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    vb_completion done;
    CHECK_INT(vb_vertices_run_complete(ctx, set, &cfg, &o, &res, &done), VB_OK);
    CHECK_INT(res.certified.n, 8);
    CHECK_INT(done.traced, 1);
    CHECK_INT(done.arcs.vertices, 8);
    CHECK_INT(done.arcs.half_arcs, 48);
    CHECK_INT(done.arcs.closed, 24);
    CHECK_INT(done.arcs.infinite, 24);
    CHECK_INT(done.arcs.undecided, 0);
    CHECK_INT(done.arcs.added.n, 0);
    CHECK_INT(done.arcs.components, 1);
    CHECK_INT(done.has_topology, 1);
    CHECK_INT(done.topology.exact, 1);
    CHECK_INT(done.topology.nfaces, 54);
    CHECK_INT(done.topology.nedges, 36);
    const char *nl = strchr(done.certificate, '\n');
    CHECK(strncmp(done.certificate, "complete: 8 certified vertices, every vertex", 44) == 0);
    CHECK(nl && strncmp(nl + 1, "arcs: every arc closed exactly: 8 vertices, 48 half arcs", 56) == 0);
    vb_completion_free(&done);
    CHECK_INT(done.traced, 0);
    vb_vertices_result_free(&res);
}

/* The sampling proposer, topology alone: from its evidence, not traced;
 * refused candidates of a proposer without a proof are warned (W763). */
static void test_sampled(vb_ctx *ctx, vb_sphere_set *set)
{
    vb_vertices_config cfg = {0};
    cfg.device = VB_DEVICE_REF;
    cfg.proposer = "sampling";
    vb_completion_opts o = {0};
    o.topology = 1;
    vb_completion_plan(&cfg, &o);
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    CHECK_INT(vb_vertices_run_default(ctx, set, &cfg, &res), VB_OK);
    CHECK_INT(res.proposal.complete, 0);
    seen s = {0};
    int quiet = vb_set_verbosity(ctx, 1); /* the callback gets what verbosity lets through */
    vb_set_log(ctx, keep, &s);
    vb_completion done;
    CHECK_INT(vb_vertices_complete(ctx, set, &res, 2, &o, &done), VB_OK);
    vb_set_log(ctx, NULL, NULL);
    vb_set_verbosity(ctx, quiet);
    CHECK(s.n >= 1); /* then W765 for trisectors the doubles could not pair, if any */
    CHECK_INT(s.number[0], VB_W_CERT_REJECTED);
    for (int k = 1; k < s.n; k++)
        CHECK_INT(s.number[k], VB_W_TOPO_UNPAIRED);
    CHECK_INT(done.traced, 0);
    CHECK_INT(done.has_topology, 1);
    CHECK_INT(done.topology.exact, 0);
    CHECK(done.topology.nfaces > 0);
    CHECK_STR(done.certificate, ""); /* sampling proves nothing about completeness */
    vb_completion_free(&done);
    CHECK_INT(vb_vertices_complete(ctx, NULL, &res, 0, &o, &done), VB_EMISUSE);
    vb_completion_free(&done);
    vb_vertices_result_free(&res);
}

int main(void)
{
    test_plan();
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    vb_sphere_set *set = lattice(ctx);
    if (set) {
        test_lattice_in_one_call(ctx, set);
        test_sampled(ctx, set);
    }
    vb_spheres_free(set);
    vb_close(ctx);
    VB_TEST_END();
}
