/* A program outside the tree, compiled against the installed headers and
 * libvorball (tests/pipeline/install.sh): reads an XYZR file given as its
 * argument, runs the vertex flow with its completion (arc closure and the
 * exact topology) in one call on the reference backend, verifies its own
 * certified vertices in memory (vb_verify_list) and prints "<certified>
 * <verified>" on stdout. Exit 0, or 1 with a message (also when an arc
 * stayed undecided, tracing added a vertex the cover missed, or no
 * topology came back). It includes the one public header alone. */
#include <stdio.h>
#include <stdlib.h>

#include "vorball.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: install_client FILE.xyzr\n");
        return 1;
    }
    vb_config cfg = {0, NULL}; /* quiet */
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    vb_read_options ro = {0};
    ro.format = VB_FMT_XYZR;
    vb_sphere_set *set = NULL;
    vb_vertices_config vc = {0};
    vc.device = VB_DEVICE_REF;
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    vb_verify_report rep = {0};
    vb_completion_opts co = {0};
    co.topology = 1; /* exact: implies arc closure */
    vb_completion done;
    vb_completion_init(&done);
    int rc = vb_spheres_load(ctx, argv[1], &ro, NULL, 4, &set);
    if (rc == VB_OK)
        rc = vb_vertices_run_complete(ctx, set, &vc, &co, &res, &done);
    if (rc == VB_OK && (!done.traced || done.arcs.undecided || done.arcs.added.n ||
                        !done.has_topology || !done.topology.exact || !done.topology.nfaces)) {
        fprintf(stderr, "install_client: completion: traced %d, %zu undecided, %zu added, "
                "topology %d (%zu faces)\n", done.traced, done.arcs.undecided,
                done.arcs.added.n, done.has_topology, done.topology.nfaces);
        rc = VB_EINTERNAL;
    }
    if (rc == VB_OK)
        rc = vb_verify_list(ctx, set, "in memory", &res.certified, VB_VFMT_TSV, 1e-6, 0, &rep);
    if (rc == VB_OK)
        printf("%zu %zu\n", res.certified.n, rep.counts.certified);
    else
        fprintf(stderr, "install_client: E%d: %s\n", vb_diag_number(rc), vb_errmsg(ctx));
    vb_verify_report_free(&rep);
    vb_completion_free(&done);
    vb_vertices_result_free(&res);
    vb_spheres_free(set);
    vb_close(ctx);
    return rc == VB_OK ? 0 : 1;
}
