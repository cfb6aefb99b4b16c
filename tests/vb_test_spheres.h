/* Test helper: sphere sets built by hand, without the input readers, for
 * tests that give their spheres inline (verify/, cgal/, channels/), and a
 * corpus case read from the source tree. */
#ifndef VB_TEST_SPHERES_H
#define VB_TEST_SPHERES_H

#include <stdio.h>
#include <stdlib.h>

#include "vb_spheres.h"

/* A set of n spheres, all zero: the double columns, and with `exact` the
 * decimal columns too (atom records, lines and flags stay NULL). Free with
 * vb_spheres_free. */
static inline vb_sphere_set *vb_test_spheres_alloc(size_t n, int exact)
{
    vb_sphere_set *s = calloc(1, sizeof *s);
    s->n = n;
    s->x = calloc(n, sizeof(double));
    s->y = calloc(n, sizeof(double));
    s->z = calloc(n, sizeof(double));
    s->r = calloc(n, sizeof(double));
    if (exact) {
        s->ex = calloc(n, sizeof(vb_decimal));
        s->ey = calloc(n, sizeof(vb_decimal));
        s->ez = calloc(n, sizeof(vb_decimal));
        s->er = calloc(n, sizeof(vb_decimal));
    }
    return s;
}

/* corpus/inputs/<name>.xyzr of the source tree (VORBALL_SOURCE_DIR, else
 * the working directory), read by the library; NULL (message in ctx) when
 * it cannot be read. */
static inline vb_sphere_set *vb_test_corpus_load(vb_ctx *ctx, const char *name)
{
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/corpus/inputs/%s.xyzr", src ? src : ".", name);
    vb_read_options ro = {0};
    ro.format = VB_FMT_XYZR;
    vb_sphere_set *set = NULL;
    return vb_spheres_load(ctx, path, &ro, NULL, 4, &set) == VB_OK ? set : NULL;
}

#endif
