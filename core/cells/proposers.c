/* The proposer table (vb_proposer.h): the proposers of the library, the
 * one a name asks for, and the set-up and release of their result. */
#include <stdlib.h>
#include <string.h>

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

void vb_proposal_init(vb_proposal *r)
{
    memset(r, 0, sizeof *r);
    vb_vertex_list_init(&r->candidates);
}

void vb_proposal_free(vb_proposal *r)
{
    vb_vertex_list_free(&r->candidates);
    free(r->quads.q);
    free(r->topo.faces);
    free(r->topo.triples);
    vb_proposal_init(r);
}
