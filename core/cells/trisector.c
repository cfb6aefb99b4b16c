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

/* Collinear centres: by the symmetry about their axis the trisector is one
 * circle, at axial position z (from c_a, along the unit axis e) and a
 * fixed t; with z_k the axial positions, subtracting a's condition from
 * b's and c's gives -2 z_k z - 2 (r_k - r_a) t = r_k^2 - r_a^2 - z_k^2,
 * and the radius is rho^2 = (r_a + t)^2 - z^2. Returns 0 when there is
 * no such circle. */
static int circle_init(const double ca[3], const double u[3], const double v[3], double ra,
                       double rb, double rc, vbs_trisector *tr)
{
    double nu = sqrt(dot(u, u)), nv = sqrt(dot(v, v));
    const double *far = nu >= nv ? u : v;
    double nf = nu >= nv ? nu : nv;
    if (!(nf > 0.0))
        return 0;
    double e[3] = {far[0] / nf, far[1] / nf, far[2] / nf};
    double zb = dot(u, e), zc = dot(v, e);
    /* [-2 zb, -2 (rb - ra); -2 zc, -2 (rc - ra)] (z, t) = (fb, fc) */
    double a11 = -2.0 * zb, a12 = -2.0 * (rb - ra), a21 = -2.0 * zc, a22 = -2.0 * (rc - ra);
    double fb = rb * rb - ra * ra - zb * zb, fc = rc * rc - ra * ra - zc * zc;
    double det = a11 * a22 - a12 * a21;
    if (!(fabs(det) > 1e-12 * (fabs(a11 * a22) + fabs(a12 * a21))))
        return 0;
    double z = (fb * a22 - a12 * fc) / det, t = (a11 * fc - fb * a21) / det;
    double rho2 = (ra + t) * (ra + t) - z * z;
    if (!(rho2 > 0.0))
        return 0;
    /* e1, e2: an orthonormal pair across the axis. */
    double h[3] = {1.0, 0.0, 0.0};
    if (fabs(e[0]) > 0.6)
        h[0] = 0.0, h[1] = 1.0;
    double hd = dot(h, e);
    double e1[3] = {h[0] - hd * e[0], h[1] - hd * e[1], h[2] - hd * e[2]};
    double n1 = sqrt(dot(e1, e1));
    for (int k = 0; k < 3; k++) {
        e1[k] /= n1;
        tr->ca[k] = ca[k];
        tr->w0[k] = ca[k] + z * e[k];   /* the circle's centre */
        tr->w1[k] = e1[k];
    }
    tr->n[0] = e[1] * e1[2] - e[2] * e1[1];
    tr->n[1] = e[2] * e1[0] - e[0] * e1[2];
    tr->n[2] = e[0] * e1[1] - e[1] * e1[0];
    tr->A = 0.0;
    tr->B = 0.0;
    tr->C = sqrt(rho2);
    tr->tmin = tr->tmax = t;
    tr->closed = 1;
    tr->circle = 1;
    return 1;
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
    tr->circle = 0;
    if (!(det > 1e-12 * uu * vv) || !(nn > 0.0))
        return circle_init(ca, u, v, ra, rb, rc, tr);
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
    if (tr->circle) {
        const double q[3] = {p[0] - tr->w0[0], p[1] - tr->w0[1], p[2] - tr->w0[2]};
        return atan2(dot(q, tr->n), dot(q, tr->w1));
    }
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
    if (tr->circle) {
        for (int k = 0; k < 3; k++)
            p[k] = tr->w0[k] + tr->C * (cos(s) * tr->w1[k] + sin(s) * tr->n[k]);
        *t = tr->tmin;
        return;
    }
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
