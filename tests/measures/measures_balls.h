/* Helpers of the cell-measure tests: a validated sphere set from XYZR
 * text, enclosure checks, and closed forms of balls and their unions. */
#ifndef MEASURES_BALLS_H
#define MEASURES_BALLS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_spheres.h"

#define PI 3.14159265358979323846

/* A test data file's text, NUL-terminated (at most 1 MiB read); NULL when
 * it cannot be opened or memory runs out. The caller frees it. */
static inline char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = malloc(1 << 20);
    size_t n = buf ? fread(buf, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    if (buf)
        buf[n] = '\0';
    return buf;
}

static inline vb_sphere_set *spheres(vb_ctx *ctx, const char *text)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.format = VB_FMT_XYZR;
    vb_sphere_set *s = NULL;
    if (vb_spheres_read_buffer(ctx, "test", text, strlen(text), &ro, &s) != VB_OK)
        return NULL;
    if (vb_spheres_validate(ctx, s, 1) != VB_OK) {
        vb_spheres_free(s);
        return NULL;
    }
    return s;
}

/* The validated spheres of the XYZR file rel under the source tree dir;
 * NULL when it cannot be read or parsed. */
static inline vb_sphere_set *data_spheres(vb_ctx *ctx, const char *dir, const char *rel)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    char *text = slurp(path);
    vb_sphere_set *s = text ? spheres(ctx, text) : NULL;
    free(text);
    return s;
}

/* lo <= x <= hi, with x known to ~1e-13 relative (double closed forms) and
 * a width the tolerance allows */
static inline int encloses(double lo, double hi, double x, double maxw)
{
    double slack = 1e-12 * fabs(x);
    int ok = lo <= x + slack && x - slack <= hi && hi - lo <= maxw;
    if (!ok)
        fprintf(stderr, "  [%.15g, %.15g] vs %.15g (width %g, allowed %g)\n", lo, hi, x,
                hi - lo, maxw);
    return ok;
}

static inline double cap_volume(double r, double h)
{
    return PI * h * h * (3.0 * r - h) / 3.0;
}

/* Union of two balls of radii r1, r2 at distance d (< r1 + r2, no nesting). */
static inline void union2(double r1, double r2, double d, double *vol, double *area)
{
    double x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d); /* radical plane from c1 */
    double h1 = r1 - x, h2 = r2 - (d - x);
    *vol = 4.0 / 3.0 * PI * (r1 * r1 * r1 + r2 * r2 * r2) - cap_volume(r1, h1) -
           cap_volume(r2, h2);
    *area = 4.0 * PI * (r1 * r1 + r2 * r2) - 2.0 * PI * (r1 * h1 + r2 * h2);
}

static inline void sums(const vb_cell_measures *m, double *vlo, double *vhi, double *alo,
                        double *ahi)
{
    *vlo = *vhi = *alo = *ahi = 0.0;
    for (size_t i = 0; i < m->n; i++) {
        *vlo += m->vol_lo[i];
        *vhi += m->vol_hi[i];
        *alo += m->sas_lo[i];
        *ahi += m->sas_hi[i];
    }
    /* the double sums are within n ulps of the exact sums */
    *vlo *= 1.0 - 1e-14;
    *alo *= 1.0 - 1e-14;
    *vhi *= 1.0 + 1e-14;
    *ahi *= 1.0 + 1e-14;
}

#endif
