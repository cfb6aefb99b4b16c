/* Test helper: sphere sets built by hand, without the input readers, for
 * tests that give their spheres inline (verify/, cgal/, channels/). */
#ifndef VB_TEST_SPHERES_H
#define VB_TEST_SPHERES_H

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

#endif
