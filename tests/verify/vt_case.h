/* Test helper: one corpus case read as the arc tests use it, its spheres
 * validated (as the CLI does) and its golden vertex list. */
#ifndef VT_CASE_H
#define VT_CASE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_spheres.h"
#include "vb_vertex_io.h"

/* Reads spheres in (into *s, validated) and golden list gold (into g,
 * initialised here). Returns VB_OK or the first failure's status; free
 * with vb_spheres_free and vb_vertex_list_free either way. */
static inline int vt_read_case(vb_ctx *ctx, const char *in, const char *gold, vb_sphere_set **s,
                               vb_vertex_list *g)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    *s = NULL;
    vb_vertex_list_init(g);
    int rc = vb_spheres_read_file(ctx, in, &ro, s);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, *s, 4);
    if (rc == VB_OK)
        rc = vb_vertex_read_file(ctx, gold, g, NULL, NULL);
    return rc;
}

/* vt_read_case on the corpus case `name`: corpus/inputs/NAME.xyzr and
 * corpus/golden/NAME.tsv under $VORBALL_SOURCE_DIR, else ".". */
static inline int vt_read_named(vb_ctx *ctx, const char *name, vb_sphere_set **s,
                                vb_vertex_list *g)
{
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char in[1024], gold[1024];
    snprintf(in, sizeof in, "%s/corpus/inputs/%s.xyzr", src ? src : ".", name);
    snprintf(gold, sizeof gold, "%s/corpus/golden/%s.tsv", src ? src : ".", name);
    return vt_read_case(ctx, in, gold, s, g);
}

#endif
