/* The proposer table (vb_proposer.h): the proposers of the library, the
 * one a name asks for, and the set-up and release of their result. */
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_parallel.h"
#include "vb_proposer.h"

/* The cover first: it proves completeness, and it is the faster of the two
 * on every input measured (papers/gpu-voronoi-cells-of-spheres). */
const vb_proposer *const vb_proposers[] = {&vb_proposer_cover, &vb_proposer_sampling, NULL};

const vb_proposer *vb_proposer_find(const char *name)
{
    for (int i = 0; vb_proposers[i]; i++)
        if (!name || strcmp(vb_proposers[i]->name, name) == 0)
            return vb_proposers[i];
    return NULL;
}

int vb_propose_options_check(vb_ctx *ctx, const vb_propose_options *o)
{
    if (o->samples && (o->samples < VB_SAMPLES_MIN || o->samples > VB_SAMPLES_MAX))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--samples needs an integer in %u..%u",
                        VB_SAMPLES_MIN, VB_SAMPLES_MAX);
    if (o->tiles > VB_TILES_MAX || (o->tiles & (o->tiles - 1u)) != 0)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--tiles needs a power of two in 1..%u",
                        VB_TILES_MAX);
    if (o->threads > VB_MAX_THREADS)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--threads needs an integer in 1..%d",
                        VB_MAX_THREADS);
    if (!(o->tol >= 0.0))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--tol needs a positive number");
    return VB_OK;
}

void vb_proposal_init(vb_proposal *r)
{
    memset(r, 0, sizeof *r);
    vb_vertex_list_init(&r->candidates);
}

void vb_proposal_free(vb_proposal *r)
{
    vb_vertex_list_free(&r->candidates);
    free(r->quads.q);
    free(r->quads.verdict);
    free(r->topo.faces);
    free(r->topo.triples);
    vb_proposal_init(r);
}
