/* Random caps for the arrangement's tests (test_cap_bound.c,
 * test_cap_prefilter.c, test_cap_near.c): a seeded generator, unit
 * directions, caps about a direction, a direction's signed distance from
 * a cap, and two comparisons of arc lists. */
#ifndef CAPS_RANDOM_H
#define CAPS_RANDOM_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "vbm_caps.h"

/* A double in [0, 1) from the next step of *s. */
static inline double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* A random unit vector u. */
static inline void unit(uint64_t *s, double *u)
{
    double n;
    do {
        n = 0.0;
        for (int k = 0; k < 3; k++) {
            u[k] = 2.0 * rnd(s) - 1.0;
            n += u[k] * u[k];
        }
    } while (n > 1.0 || n < 1e-6);
    n = sqrt(n);
    for (int k = 0; k < 3; k++)
        u[k] /= n;
}

/* A cap about a direction near v (spread) with cosine of radius c: *cp
 * in point intervals, n and *h its doubles. */
static inline void make_cap(uint64_t *s, const double *v, double spread, double c, vbm_cap *cp,
                            double *n, double *h)
{
    double u[3], nn = 0.0;
    unit(s, u);
    for (int k = 0; k < 3; k++) {
        n[k] = v[k] + spread * u[k];
        nn += n[k] * n[k];
    }
    *h = c * sqrt(nn);
    for (int k = 0; k < 3; k++)
        cp->n[k] = vbx_ia_point(n[k]);
    cp->h = vbx_ia_point(*h);
}

/* Signed distance of u from cap (n, h) in units of |n| (> 0 inside). */
static inline double depth(const double *n, double h, const double *u)
{
    double d = n[0] * u[0] + n[1] * u[1] + n[2] * u[2];
    return (d - h) / sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Random region t (test_cap_prefilter.c, test_cap_near.c): 3-17 caps
 * about a random direction, cap 0 from small to wider than a half sphere
 * (every third t), the others about nearby directions; caps[0..nc) with
 * their doubles n, h. Returns nc (caps, n and h hold 18). */
static inline size_t region_caps(uint64_t *s, int t, vbm_cap *caps, double (*n)[3], double *h)
{
    double v[3];
    size_t nc = 3 + (size_t)(15.0 * rnd(s));
    unit(s, v);
    double c0 = t % 3 == 0 ? 0.95 - 1.8 * rnd(s) : 0.98 - 0.3 * rnd(s);
    make_cap(s, v, 0.0, c0, &caps[0], n[0], &h[0]);
    for (size_t m = 1; m < nc; m++)
        make_cap(s, v, 1.5 * rnd(s), 0.95 - 1.5 * rnd(s), &caps[m], n[m], &h[m]);
    return nc;
}

/* The same list bit for bit. */
static inline int arcs_equal(const vbm_arc *a, size_t na, const vbm_arc *b, size_t nb)
{
    if (na != nb)
        return 0;
    for (size_t i = 0; i < na; i++)
        if (a[i].cap != b[i].cap || a[i].pcap != b[i].pcap || a[i].qcap != b[i].qcap ||
            memcmp(a[i].p, b[i].p, sizeof a[i].p) || memcmp(a[i].q, b[i].q, sizeof a[i].q) ||
            memcmp(&a[i].tp, &b[i].tp, sizeof a[i].tp) || memcmp(&a[i].tq, &b[i].tq, sizeof a[i].tq))
            return 0;
    return 1;
}

/* The same arcs as sets (b's caps through map): fewer caps may start a
 * circle's list at another arc (its widest gap), not change the arcs. */
static inline int arcs_same(const vbm_arc *a, size_t na, const vbm_arc *b, size_t nb, const size_t *map)
{
    if (na != nb)
        return 0;
    for (size_t i = 0; i < na; i++) {
        size_t j = 0;
        while (j < nb && !(map[b[j].cap] == a[i].cap && !memcmp(a[i].p, b[j].p, sizeof a[i].p) &&
                           !memcmp(a[i].q, b[j].q, sizeof a[i].q)))
            j++;
        if (j == nb)
            return 0;
    }
    return 1;
}

#endif
