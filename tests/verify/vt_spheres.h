/* Test helper: a sphere set built from decimal strings, independent of the
 * input readers (so verify/ tests run while core/ input evolves). */
#ifndef VT_SPHERES_H
#define VT_SPHERES_H

#include <stdlib.h>
#include <string.h>

#include "vb_spheres.h"
#include "vb_test_spheres.h"

/* "-1.250" -> mant -125, exp10 -2 (trailing zeros stripped). */
static vb_decimal vt_decimal(const char *s)
{
    vb_decimal d = {0, 0};
    int neg = 0, point = 0;
    if (*s == '-' || *s == '+')
        neg = *s++ == '-';
    for (; *s; s++) {
        if (*s == '.') {
            point = 1;
            continue;
        }
        d.mant = d.mant * 10 + (*s - '0');
        if (point)
            d.exp10--;
    }
    while (d.mant != 0 && d.mant % 10 == 0) {
        d.mant /= 10;
        d.exp10++;
    }
    if (d.mant == 0)
        d.exp10 = 0;
    if (neg)
        d.mant = -d.mant;
    return d;
}

/* n spheres from 4n strings "x", "y", "z", "r". Free with vb_spheres_free. */
static vb_sphere_set *vt_set(size_t n, const char *const *v)
{
    vb_sphere_set *s = vb_test_spheres_alloc(n, 1);
    s->line = calloc(n, sizeof(long));
    s->contained = calloc(n, 1);
    for (size_t i = 0; i < n; i++) {
        s->x[i] = strtod(v[4 * i], NULL);
        s->y[i] = strtod(v[4 * i + 1], NULL);
        s->z[i] = strtod(v[4 * i + 2], NULL);
        s->r[i] = strtod(v[4 * i + 3], NULL);
        s->ex[i] = vt_decimal(v[4 * i]);
        s->ey[i] = vt_decimal(v[4 * i + 1]);
        s->ez[i] = vt_decimal(v[4 * i + 2]);
        s->er[i] = vt_decimal(v[4 * i + 3]);
        s->line[i] = (long)i + 1;
    }
    return s;
}

/* The cubic lattice: spheres at (+-1, +-1, +-1), radius 0.5, id = bits
 * (x, y, z); its one vertex is the centre, of degree 8. */
static inline vb_sphere_set *vt_cube(void)
{
    const char *v[32];
    for (int i = 0; i < 8; i++) {
        v[4 * i] = (i & 1) ? "1" : "-1";
        v[4 * i + 1] = (i & 2) ? "1" : "-1";
        v[4 * i + 2] = (i & 4) ? "1" : "-1";
        v[4 * i + 3] = "0.5";
    }
    return vt_set(8, v);
}

#endif
