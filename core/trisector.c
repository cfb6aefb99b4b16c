/* The trisector of three spheres as a parametrised curve (topology's edge
 * pairing). With q = p - c_a, u = c_b - c_a, v = c_c - c_a, the tangency
 * conditions |q| = r_a + t, |q - u| = r_b + t, |q - v| = r_c + t give two
 * linear equations for the in-plane part of q, linear in t:
 *   2 q.u = |u|^2 + (r_a + t)^2 - (r_b + t)^2, the same with v and r_c,
 * and the normal part g from |q|^2: g^2 = (r_a + t)^2 - |w0 + t w1|^2.
 * g^2 <= 0 at t = -r_a (and likewise at -r_b, -r_c), so with A > 0 the
 * branch t >= tmin (the larger root) is where every radius r_x + t >= 0. */
#include <math.h>

#include "vbs_internal.h"

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int vbs_trisector_init(const vb_sphere_set *s, uint32_t a, uint32_t b, uint32_t c,
                       vbs_trisector *tr)
{
    const double ca[3] = {s->x[a], s->y[a], s->z[a]};
    const double u[3] = {s->x[b] - ca[0], s->y[b] - ca[1], s->z[b] - ca[2]};
    const double v[3] = {s->x[c] - ca[0], s->y[c] - ca[1], s->z[c] - ca[2]};
    double ra = s->r[a], rb = s->r[b], rc = s->r[c];
    double uu = dot(u, u), vv = dot(v, v), uv = dot(u, v), det = uu * vv - uv * uv;
    double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2],
           nz = u[0] * v[1] - u[1] * v[0], nn = sqrt(nx * nx + ny * ny + nz * nz);
    if (!(det > 1e-12 * uu * vv) || !(nn > 0.0))
        return 0;
    double eu0 = 0.5 * (uu + ra * ra - rb * rb), eu1 = ra - rb;
    double ev0 = 0.5 * (vv + ra * ra - rc * rc), ev1 = ra - rc;
    double al0 = (vv * eu0 - uv * ev0) / det, be0 = (uu * ev0 - uv * eu0) / det;
    double al1 = (vv * eu1 - uv * ev1) / det, be1 = (uu * ev1 - uv * eu1) / det;
    for (int k = 0; k < 3; k++) {
        tr->ca[k] = ca[k];
        tr->w0[k] = al0 * u[k] + be0 * v[k];
        tr->w1[k] = al1 * u[k] + be1 * v[k];
    }
    tr->n[0] = nx / nn;
    tr->n[1] = ny / nn;
    tr->n[2] = nz / nn;
    tr->A = 1.0 - dot(tr->w1, tr->w1);
    tr->B = 2.0 * (ra - dot(tr->w0, tr->w1));
    tr->C = ra * ra - dot(tr->w0, tr->w0);
    tr->closed = 0;
    if (fabs(tr->A) <= 1e-12) { /* parabola: g^2 = B t + C */
        if (!(tr->B > 0.0))
            return 0;
        tr->tmin = -tr->C / tr->B;
        tr->tmax = INFINITY;
        return 1;
    }
    double disc = tr->B * tr->B - 4.0 * tr->A * tr->C;
    if (!(disc > 0.0))
        return 0;
    double sq = sqrt(disc), t1 = (-tr->B - sq) / (2.0 * tr->A), t2 = (-tr->B + sq) / (2.0 * tr->A);
    if (tr->A > 0.0) {
        tr->tmin = t1 > t2 ? t1 : t2;
        tr->tmax = INFINITY;
    } else {
        tr->closed = 1;
        tr->tmin = t1 < t2 ? t1 : t2;
        tr->tmax = t1 < t2 ? t2 : t1;
    }
    return 1;
}

double vbs_trisector_param(const vbs_trisector *tr, const double p[3], double t)
{
    const double q[3] = {p[0] - tr->ca[0], p[1] - tr->ca[1], p[2] - tr->ca[2]};
    double g = dot(q, tr->n);
    if (!tr->closed)
        return g;
    double tc = 0.5 * (tr->tmin + tr->tmax);
    return atan2(g, sqrt(-tr->A) * (t - tc));
}

void vbs_trisector_point(const vbs_trisector *tr, double s, double p[3], double *t)
{
    double g, tt;
    if (tr->closed) {
        double tc = 0.5 * (tr->tmin + tr->tmax), g2 = (tr->A * tc + tr->B) * tc + tr->C;
        double R = g2 > 0.0 ? sqrt(g2) : 0.0;
        g = R * sin(s);
        tt = tc + R * cos(s) / sqrt(-tr->A);
    } else if (fabs(tr->A) <= 1e-12) {
        g = s;
        tt = (s * s - tr->C) / tr->B;
    } else {
        double disc = tr->B * tr->B - 4.0 * tr->A * (tr->C - s * s);
        g = s;
        tt = (-tr->B + sqrt(disc > 0.0 ? disc : 0.0)) / (2.0 * tr->A);
    }
    for (int k = 0; k < 3; k++)
        p[k] = tr->ca[k] + tr->w0[k] + tt * tr->w1[k] + g * tr->n[k];
    *t = tt;
}
