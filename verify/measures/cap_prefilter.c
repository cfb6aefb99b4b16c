/* The caps proven not to touch an intersection of caps (vbm_caps.h,
 * vbm_caps_prefilter): a region of directions is the unit sphere cut by
 * the half-spaces {u : u.n_m >= h_m} of its caps, a convex polyhedron's
 * (issue #31's power-diagram view). The polyhedron is clipped cap by cap
 * in doubles, voro++'s incremental cell, inside a polyhedron around the
 * unit ball's part in cap 0; a cap whose plane leaves every vertex inside
 * is rejected only where a certificate proves it:
 *
 * multipliers lam_i >= 0 (read off the vertex where u.n_m is least:
 * n_m = sum lam_i n_i over its three planes, Cramer's rule in doubles,
 * no proof needed) with, over the caps' enclosures (certify's bounds),
 *   c = sum lam_i h_i - h_m > |v|,  v = n_m - sum lam_i n_i.
 * Then for every unit u in the caps i (u.n_i >= h_i; the start's planes
 * u.f <= rho hold for every unit u in cap 0: start, side_plane)
 *   u.n_m - h_m = sum lam_i (u.n_i - h_i) + u.v + c >= c - |v| > 0:
 * the intersection of the caps kept lies in cap m's interior, away from
 * its circle, so the intersection of all caps is that of the caps kept
 * (each rejected cap holds it) and no rejected circle bounds it. The
 * certificates use the kept caps alone (a rejected one never clips), so
 * there is no circle of reasons. The doubles only choose: a wrong vertex
 * or multiplier fails its certificate and the cap is kept.
 *
 * The whole polyhedron then serves twice more (shape): a cap kept whose
 * face the later caps cut away gets a certificate at the polyhedron's
 * vertex where its u.n - h is least (a second pass), and where a cap
 * leaves nothing of the polyhedron the same certificate for its outside
 * proves the intersection empty. The search over the kept caps takes
 * each circle's neighbours on the polyhedron as the caps to look for its
 * arcs among first (vbm_cap_arcs_near, no trial intersection). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "vb_array.h"
#include "vbm_caps.h"
#include "vbm_dot.h"

#define MAX_VERT 96   /* more vertices: the clip stops, the caps left are kept */
#define NPLANE_BALL 7 /* the cube's faces and a tangent plane */
#define ON_EPS 1e-12  /* a vertex this close to a plane counts as inside (a choice only) */
#define MIN_CAPS 4    /* fewer caps: the search alone */

/* A vertex's planes and neighbours (its coordinates: vbm_poly.x). */
typedef struct pvert {
    uint32_t pl[3]; /* its planes: caps < ncap, the ball's ncap + b */
    uint16_t nb[3]; /* its neighbours: nb[k] along the edge leaving plane pl[k] */
} pvert;

struct vbm_poly {
    pvert v[2 * MAX_VERT];
    double x[3][2 * MAX_VERT]; /* v[i]'s coordinate k is x[k][i] */
    double s[2 * MAX_VERT];
    uint16_t to[2 * MAX_VERT]; /* clip's renumbering */
    double bf[NPLANE_BALL][3], brho[NPLANE_BALL]; /* the ball's planes u.f <= rho */
    size_t nb; /* ball planes */
    uint16_t (*pm)[2]; /* per plane (caps, then the ball's): clip's new vertices on it */
    size_t lo; /* after a clip that cut nothing: the vertex where u.n - h is least */
    size_t nv;
};

/* vbm_cap_arcs' work space (vbm_capwork.pw): the polyhedron, the caps
 * kept in their order and the search over them. */
typedef struct vbm_prework {
    struct vbm_poly poly;
    vbm_capwork sub;
    uint8_t *pre, *known;
    uint32_t *map, *inv;   /* kept cap k is cap map[k]; cap m is kept cap inv[m] */
    uint32_t *seq;         /* the prefilter's caps in their order */
    uint32_t *near_at, *near; /* per kept cap: its neighbours' kept indices (vbm_cap_arcs_near) */
    uint8_t *adj, *face;      /* kept x kept: neighbours; per cap: a face of the polyhedron */
    double *key;
    uint16_t (*pm)[2];        /* the polyhedron's vbm_poly.pm */
    vbm_cap *caps;
    vbm_circle *axes;
    vbm_arc *given;
    size_t cap_near_at, cap_near, cap_adj, cap_face, cap_pm;
    size_t cap_seq, cap_key, cap_pre, cap_known, cap_map, cap_inv, cap_caps, cap_axes, cap_given;
} prework;

/* Plane `id` as u.n >= h in doubles (a cap's midpoints; a ball plane -f,
 * -rho). */
static void plane_of(const vbm_cap *caps, size_t ncap, const struct vbm_poly *P, uint32_t id,
                     double n[3], double *h)
{
    if (id < ncap) {
        for (int k = 0; k < 3; k++)
            n[k] = vbx_ia_mid(caps[id].n[k]);
        *h = vbx_ia_mid(caps[id].h);
    } else {
        for (int k = 0; k < 3; k++)
            n[k] = -P->bf[id - ncap][k];
        *h = -P->brho[id - ncap];
    }
}

/* P->s[i] = ((n0 x0 + n1 x1) + n2 x2) - h in doubles for the vertices x
 * of v[0..nv) (nv >= 1), two at a time where SSE2 is there (the same
 * operations lane by lane); *mn, *mx the least and greatest. Returns 0
 * when some value is not finite. The values only choose; certify proves. */
static int scan(struct vbm_poly *P, size_t nv, const double n[3], double h, double *mn, double *mx)
{
    const double *X = P->x[0], *Y = P->x[1], *Z = P->x[2];
    double *s = P->s;
    size_t i = 0;
    double lo = INFINITY, hi = -INFINITY, fin = 0.0;
#if defined(__SSE2__)
    __m128d a = _mm_set1_pd(n[0]), b = _mm_set1_pd(n[1]), c = _mm_set1_pd(n[2]), hh = _mm_set1_pd(h);
    __m128d vl = _mm_set1_pd(INFINITY), vh = _mm_set1_pd(-INFINITY), vf = _mm_setzero_pd();
    for (; i + 2 <= nv; i += 2) {
        __m128d t = _mm_add_pd(_mm_mul_pd(a, _mm_loadu_pd(X + i)), _mm_mul_pd(b, _mm_loadu_pd(Y + i)));
        t = _mm_sub_pd(_mm_add_pd(t, _mm_mul_pd(c, _mm_loadu_pd(Z + i))), hh);
        _mm_storeu_pd(s + i, t);
        vl = _mm_min_pd(vl, t);
        vh = _mm_max_pd(vh, t);
        vf = _mm_add_pd(vf, _mm_sub_pd(t, t)); /* 0 while finite, else NaN */
    }
    lo = _mm_cvtsd_f64(_mm_min_sd(vl, _mm_unpackhi_pd(vl, vl)));
    hi = _mm_cvtsd_f64(_mm_max_sd(vh, _mm_unpackhi_pd(vh, vh)));
    fin = _mm_cvtsd_f64(_mm_add_sd(vf, _mm_unpackhi_pd(vf, vf)));
#endif
    for (; i < nv; i++) {
        double t = n[0] * X[i] + n[1] * Y[i] + n[2] * Z[i] - h;
        s[i] = t;
        lo = t < lo ? t : lo;
        hi = t > hi ? t : hi;
        fin += t - t;
    }
    *mn = lo;
    *mx = hi;
    return fin == 0.0;
}

/* The first i with s[i] == v (one there: v is scan's least value). */
static size_t first_at(const double *s, double v)
{
    size_t i = 0;
    while (s[i] != v)
        i++;
    return i;
}

/* Clips the polyhedron v[0..*nv) by u.n >= h (plane id): 0 when no
 * vertex lies outside (nothing cut), 1 clipped, -1 every vertex outside,
 * -2 too many vertices or a face the edges do not close (numerically
 * degenerate: the caller stops). voro++'s step: a new vertex on each edge
 * from a vertex inside to one outside, joined around the new face by the
 * planes they share; the vertices left keep their order, moved down in
 * place. */
static int clip(struct vbm_poly *P, size_t *nv, const double n[3], double h, uint32_t id)
{
    pvert *v = P->v;
    double(*x)[2 * MAX_VERT] = P->x;
    size_t n0 = *nv, nn = n0;
    double nrm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), eps = ON_EPS * (nrm + fabs(h));
    double mn, mx;
    if (!scan(P, n0, n, h, &mn, &mx))
        return -2; /* a value not finite (finite caps make none): stop, the rest kept */
    if (!(mn < -eps)) { /* no vertex outside: the first at the least value */
        P->lo = first_at(P->s, mn);
        return 0;
    }
    if (mx < -eps)
        return -1;
    for (size_t b = 0; b < n0; b++) {
        if (!(P->s[b] < -eps))
            continue;
        for (int k = 0; k < 3; k++) {
            size_t a = v[b].nb[k];
            if (P->s[a] < -eps)
                continue;
            if (nn == 2 * MAX_VERT)
                return -2;
            pvert *c = &v[nn];
            double t = P->s[a] / (P->s[a] - P->s[b]);
            for (int d = 0; d < 3; d++)
                x[d][nn] = x[d][a] + t * (x[d][b] - x[d][a]);
            c->pl[0] = v[b].pl[(k + 1) % 3];
            c->pl[1] = v[b].pl[(k + 2) % 3];
            c->pl[2] = id;
            c->nb[2] = (uint16_t)a;
            c->nb[0] = c->nb[1] = UINT16_MAX;
            int ka = 0;
            while (ka < 3 && v[a].nb[ka] != b)
                ka++;
            if (ka == 3)
                return -2;
            v[a].nb[ka] = (uint16_t)nn++;
        }
    }
    /* around the new face: c leaves pl[0] towards the new vertex on pl[1]
     * and id, and pl[1] towards the one on pl[0] and id: the first new d
     * != c with that plane as pl[0] or pl[1], from the first two of each
     * plane (P->pm, all UINT16_MAX between clips; a scan took k^2 steps) */
    uint16_t(*pm)[2] = P->pm;
    for (size_t c = n0; c < nn; c++)
        for (int m = 0; m < 2; m++) {
            uint16_t *f = pm[v[c].pl[m]];
            if (f[0] == UINT16_MAX)
                f[0] = (uint16_t)c;
            else if (f[0] != c && f[1] == UINT16_MAX)
                f[1] = (uint16_t)c;
        }
    for (size_t c = n0; c < nn; c++)
        for (int m = 0; m < 2; m++) {
            const uint16_t *f = pm[v[c].pl[1 - m]];
            v[c].nb[m] = f[0] != c ? f[0] : f[1];
        }
    int open = 0;
    for (size_t c = n0; c < nn; c++) {
        open |= v[c].nb[0] == UINT16_MAX || v[c].nb[1] == UINT16_MAX;
        for (int m = 0; m < 2; m++)
            pm[v[c].pl[m]][0] = pm[v[c].pl[m]][1] = UINT16_MAX;
    }
    if (open)
        return -2;
    size_t no = 0;
    for (size_t i = 0; i < nn; i++)
        P->to[i] = i < n0 && P->s[i] < -eps ? UINT16_MAX : (uint16_t)no++;
    if (no > MAX_VERT)
        return -2;
    for (size_t i = 0; i < nn; i++) {
        size_t j = P->to[i];
        if (j == UINT16_MAX)
            continue;
        if (j != i) {
            v[j] = v[i];
            for (int k = 0; k < 3; k++)
                x[k][j] = x[k][i];
        }
        for (int k = 0; k < 3; k++)
            if ((v[j].nb[k] = P->to[v[j].nb[k]]) == UINT16_MAX)
                return -2;
    }
    *nv = no;
    return 1;
}

static double det3(const double *a, const double *b, const double *c)
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* Plane `id`'s enclosures as bounds: n in [nl, nh], h in [hl, hh] (a
 * ball plane's are points); with `out`, cap id's outside u.(-n) >= -h. */
static void plane_box(const vbm_cap *caps, size_t ncap, const struct vbm_poly *P, uint32_t id,
                      int out, double nl[3], double nh[3], double *hl, double *hh)
{
    if (out) {
        for (int k = 0; k < 3; k++)
            nl[k] = -caps[id].n[k].hi, nh[k] = -caps[id].n[k].lo;
        *hl = -caps[id].h.hi, *hh = -caps[id].h.lo;
    } else if (id < ncap) {
        for (int k = 0; k < 3; k++)
            nl[k] = caps[id].n[k].lo, nh[k] = caps[id].n[k].hi;
        *hl = caps[id].h.lo, *hh = caps[id].h.hi;
    } else {
        for (int k = 0; k < 3; k++)
            nl[k] = nh[k] = -P->bf[id - ncap][k];
        *hl = *hh = -P->brho[id - ncap];
    }
}

/* A lower bound of t0 + sum_i lam[i] y[i] over exact reals (lam[i] >= 0
 * points, so lam y's least corner is lam y.lo, as given): vbm_dotn's low
 * end for these corners, the recursive sum s from t0 and its margin b =
 * fl(fl(S' w) + 2^-1060), w = 5 * 2^-53, S' the sum of the |terms|:
 * s - b <= the exact sum (vbm_dotn's proof for m = 4 terms; t0 is a
 * term whose product is exact). Returns s, *b the margin. */
static inline double dot_lo(double t0, const double lam[3], const double y[3], double *b)
{
    double s = t0, a = fabs(t0);
    for (int i = 0; i < 3; i++) {
        double t = lam[i] * y[i];
        s += t;
        a += fabs(t);
    }
    *b = a * (5.0 * 0x1p-53) + 0x1p-1060;
    return s;
}

/* Whether cap m holds every unit vector in the planes of vertex x's (the
 * certificate above, multipliers from Cramer's rule), in doubles with
 * a-priori bounds instead of interval steps:
 *   c >= sum lam_i h_i.lo - h_m.hi >= sc - bc            (dot_lo)
 *   |v_k| <= max(|vl_k|, |vh_k|) + bl_k + bh_k, v_k in [vl_k - bl_k, vh_k + bh_k]
 * (vl_k from n_mk.lo - sum lam_i n_ik.hi, vh_k from n_mk.hi - sum lam_i
 * n_ik.lo, both dot_lo's form: -x.hi = (-x).lo), and |u.v| <= |v|_1 for
 * |u| <= 1: |v|_1 <= D + A exactly, D and A the sums over k of the
 * maxima and of bl_k + bh_k. Their sums in doubles lose at most a factor
 * (1 - u)^4 (terms >= 0; additions do not underflow), the product by
 * 1 + 2^-20 a factor 1 - u or 2^-1075, the addition of 2^-1058 a factor
 * 1 - u: Vb = fl(fl(fl(D + A)(1 + 2^-20)) + 2^-1058) >= |v|_1. fl(sc -
 * bc) > Vb proves sc - bc > Vb (rounding is monotone, Vb a double), so
 * c > |v|. A NaN or infinity anywhere fails the comparison: kept. */
static int certify(const vbm_cap *caps, size_t ncap, const struct vbm_poly *P, const pvert *x,
                   size_t m, int out)
{
    double mnl[3], mnh[3], mhl, mhh, nl[3][3], nh[3][3], hl[3], hh[3], nm[3], ni[3][3], lam[3];
    plane_box(caps, ncap, P, (uint32_t)m, out, mnl, mnh, &mhl, &mhh);
    for (int i = 0; i < 3; i++)
        plane_box(caps, ncap, P, x->pl[i], 0, nl[i], nh[i], &hl[i], &hh[i]);
    for (int k = 0; k < 3; k++) { /* the multipliers' normals: any near the enclosures */
        nm[k] = 0.5 * mnl[k] + 0.5 * mnh[k];
        for (int i = 0; i < 3; i++)
            ni[i][k] = 0.5 * nl[i][k] + 0.5 * nh[i][k];
    }
    double d = det3(ni[0], ni[1], ni[2]);
    if (!(fabs(d) > 0.0))
        return 0;
    lam[0] = det3(nm, ni[1], ni[2]) / d;
    lam[1] = det3(ni[0], nm, ni[2]) / d;
    lam[2] = det3(ni[0], ni[1], nm) / d;
    for (int i = 0; i < 3; i++)
        lam[i] = lam[i] > 0.0 ? lam[i] : 0.0; /* negative (a degenerate vertex) or NaN: left out */
    double bc, sc = dot_lo(-mhh, lam, hl, &bc), D = 0.0, A = 0.0;
    for (int k = 0; k < 3; k++) {
        double yl[3] = {-nh[0][k], -nh[1][k], -nh[2][k]}, yh[3] = {nl[0][k], nl[1][k], nl[2][k]};
        double bl, bh, vl = dot_lo(mnl[k], lam, yl, &bl), vh = -dot_lo(-mnh[k], lam, yh, &bh);
        vl = fabs(vl), vh = fabs(vh);
        D += vl > vh ? vl : vh; /* a NaN vl comes of a NaN or infinite term: bl is too */
        A += (bl + bh);
    }
    double Vb = (D + A) * (1.0 + 0x1p-20) + 0x1p-1058;
    return sc - bc > Vb;
}

/* Adds the ball's plane u.f <= rho, rho an upper bound of |f|. */
static void ball_plane(struct vbm_poly *P, double x, double y, double z)
{
    double *f = P->bf[P->nb];
    f[0] = x, f[1] = y, f[2] = z;
    vbx_ia ff[3] = {vbx_ia_point(x), vbx_ia_point(y), vbx_ia_point(z)};
    P->brho[P->nb++] = vbx_ia_sqrt(vbm_dot3(ff, ff)).hi;
}

/* The polyhedron's start, cap 0 in it: where cap 0 is smaller than a half
 * sphere, the box around its centre e (doubles) between cap 0's plane and
 * the unit sphere's tangent plane u.e <= rho_e, with the faces u.(+-p) <=
 * rho_p and u.(+-q) <= rho_q, p, q, e nearly orthonormal in doubles (no
 * proof needed: each face holds for every |u| <= 1); else the cube
 * [-1, 1]^3 clipped by cap 0. The box's vertices are near its planes'
 * (they only choose; the certificates take the planes). Was the cube cut
 * by the tangent plane and cap 0 (c1k: 45 M instructions in the two clips
 * and no tighter). (Tangent planes around its rim as well, or a second
 * pass with the caps found to bound the polyhedron first, rejected 5 %
 * more caps on capsid's first 1000 atoms and cost more than they saved.) */
/* Adds the side plane u.f <= r of the unit vectors in cap 0: such a u is
 * a e + w with e the exact axis (in c0->a), c0->c.lo <= a <= 1 and |w| <=
 * sin of cap 0's radius (in c0->s), so u.f <= |e.f| + |w| |f| <= r,
 * rounded up in intervals. Returns r. */
static double side_plane(struct vbm_poly *P, const vbm_circle *c0, double x, double y, double z)
{
    ball_plane(P, x, y, z);
    vbx_ia ff[3] = {vbx_ia_point(x), vbx_ia_point(y), vbx_ia_point(z)}, ef = vbm_dot3(c0->a, ff);
    double r = vbx_ia_add(vbx_ia_point(fmax(-ef.lo, ef.hi)),
                          vbx_ia_mul(c0->s, vbx_ia_point(P->brho[P->nb - 1]))).hi;
    return P->brho[P->nb - 1] = r;
}

static int start(struct vbm_poly *P, const vbm_cap *caps, size_t ncap, const vbm_circle *c0,
                 size_t *nv)
{
    double e[3] = {vbx_ia_mid(c0->a[0]), vbx_ia_mid(c0->a[1]), vbx_ia_mid(c0->a[2])};
    double t0 = vbx_ia_mid(c0->c);
    P->nb = 0;
    *nv = 8;
    if (c0->c.lo > 0.0 && c0->s.lo >= 0.0) {
        int j = fabs(e[0]) <= fabs(e[1]) && fabs(e[0]) <= fabs(e[2]) ? 0 : fabs(e[1]) <= fabs(e[2]) ? 1 : 2;
        double ax[3] = {j == 0, j == 1, j == 2}, p[3], q[3];
        p[0] = e[1] * ax[2] - e[2] * ax[1], p[1] = e[2] * ax[0] - e[0] * ax[2],
        p[2] = e[0] * ax[1] - e[1] * ax[0];
        double np = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (!(np > 0.5)) /* e not near a unit vector */
            return 0;
        for (int k = 0; k < 3; k++)
            p[k] /= np;
        q[0] = e[1] * p[2] - e[2] * p[1], q[1] = e[2] * p[0] - e[0] * p[2],
        q[2] = e[0] * p[1] - e[1] * p[0];
        double r = side_plane(P, c0, p[0], p[1], p[2]);
        side_plane(P, c0, -p[0], -p[1], -p[2]);
        side_plane(P, c0, q[0], q[1], q[2]);
        side_plane(P, c0, -q[0], -q[1], -q[2]);
        ball_plane(P, e[0], e[1], e[2]);
        for (size_t i = 0; i < 8; i++) {
            pvert *x = &P->v[i];
            double sp = i & 1 ? -r : r, sq = i & 2 ? -r : r, se = i & 4 ? t0 : 1.0;
            for (int k = 0; k < 3; k++)
                P->x[k][i] = sp * p[k] + sq * q[k] + se * e[k];
            x->pl[0] = (uint32_t)(ncap + (i & 1));
            x->pl[1] = (uint32_t)(ncap + 2 + ((i >> 1) & 1));
            x->pl[2] = i & 4 ? 0 : (uint32_t)(ncap + 4);
            for (int k = 0; k < 3; k++)
                x->nb[k] = (uint16_t)(i ^ ((size_t)1 << k)); /* flips bit k: leaves plane k */
        }
        return 1;
    }
    for (int k = 0; k < 3; k++)
        for (int s = 0; s < 2; s++)
            ball_plane(P, k == 0 ? (s ? -1.0 : 1.0) : 0.0, k == 1 ? (s ? -1.0 : 1.0) : 0.0,
                       k == 2 ? (s ? -1.0 : 1.0) : 0.0);
    for (size_t i = 0; i < 8; i++) {
        pvert *x = &P->v[i];
        for (int k = 0; k < 3; k++) {
            int neg = (int)(i >> k) & 1;
            P->x[k][i] = neg ? -1.0 : 1.0;
            x->pl[k] = (uint32_t)(ncap + 2 * (size_t)k + (size_t)neg);
            x->nb[k] = (uint16_t)(i ^ ((size_t)1 << k)); /* flips coordinate k: leaves its face */
        }
    }
    double n[3], h;
    plane_of(caps, ncap, P, 0, n, &h);
    return clip(P, nv, n, h, 0) >= 0;
}

static prework *work(vbm_capwork *w)
{
    if (!w->pw)
        w->pw = calloc(1, sizeof *w->pw);
    return w->pw;
}

/* How the clip ended (shape) */
enum { SHAPE_NONE, SHAPE_DONE, SHAPE_EMPTY, SHAPE_STOPPED };

/* The clip over caps[0..ncap) and its certificates (vbm_caps_prefilter),
 * the polyhedron left in pw->poly. Returns how it ended: SHAPE_DONE every
 * cap clipped (then, second pass, a cap kept whose face the later caps
 * cut away is rejected by a certificate at the vertex of the whole
 * polyhedron where its u.n - h is least: its planes are the faces', caps
 * never rejected, so no circle of reasons), SHAPE_EMPTY a cap left
 * nothing (*empty = 1 where a certificate proves the intersection empty:
 * the outside of that cap, u.(-n) >= -h, holds every unit vector in the
 * caps of the vertex where u.n - h is greatest, so no direction lies in
 * them all), SHAPE_STOPPED too many vertices or a face the edges do not
 * close, SHAPE_NONE not started (or ENOMEM). */
static int shape(const vbm_cap *caps, const vbm_circle *circ, size_t ncap, prework *pw,
                 uint8_t *pre, int *empty)
{
    *empty = 0;
    memset(pre, 0, ncap);
    if (VB_ARRAY_FIT(pw->seq, pw->cap_seq, ncap + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->key, pw->cap_key, ncap + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->pm, pw->cap_pm, ncap + NPLANE_BALL, 32) != VB_OK)
        return SHAPE_NONE;
    if (ncap <= 2 || circ[0].kind != VBM_CAP_CIRCLE)
        return SHAPE_NONE;
    memset(pw->pm, 0xff, (ncap + NPLANE_BALL) * sizeof *pw->pm); /* UINT16_MAX: none */
    pw->poly.pm = pw->pm;
    /* the caps cutting deepest into cap 0 first (their circles' axes and
     * cosines: a_m.a_0 - c_m least first), so that few caps clip early
     * that later ones would have bounded away */
    uint32_t *seq = pw->seq;
    double *key = pw->key;
    struct vbm_poly *P = &pw->poly;
    size_t n = 0;
    for (size_t m = 1; m < ncap; m++) {
        if (circ[m].kind != VBM_CAP_CIRCLE)
            continue;
        double x = -vbx_ia_mid(circ[m].c);
        for (int k = 0; k < 3; k++)
            x += vbx_ia_mid(circ[m].a[k]) * vbx_ia_mid(circ[0].a[k]);
        size_t i = n++;
        for (; i > 0 && key[i - 1] > x; i--) {
            key[i] = key[i - 1];
            seq[i] = seq[i - 1];
        }
        key[i] = x;
        seq[i] = (uint32_t)m;
    }
    double nm[3], h;
    if (!start(P, caps, ncap, &circ[0], &P->nv))
        return SHAPE_NONE;
    for (size_t i = 0; i < n; i++) {
        size_t m = seq[i];
        plane_of(caps, ncap, P, (uint32_t)m, nm, &h);
        int e = clip(P, &P->nv, nm, h, (uint32_t)m);
        if (e == -1) { /* every vertex outside cap m */
            size_t hi = 0;
            for (size_t k = 1; k < P->nv; k++)
                hi = P->s[k] > P->s[hi] ? k : hi;
            *empty = P->s[hi] < 0.0 && certify(caps, ncap, P, &P->v[hi], m, 1);
            return SHAPE_EMPTY;
        }
        if (e < 0)
            return SHAPE_STOPPED; /* the rest kept */
        if (e > 0)
            continue;
        /* the vertex where u.n_m is least (the clip's): its planes' multipliers */
        pre[m] = P->s[P->lo] > 0.0 && certify(caps, ncap, P, &P->v[P->lo], m, 0); /* touching: no certificate */
    }
    /* the second pass: caps kept without a face */
    uint8_t *face = pw->face;
    memset(face, 0, ncap);
    const pvert *v = P->v;
    for (size_t i = 0; i < P->nv; i++)
        for (int k = 0; k < 3; k++)
            if (v[i].pl[k] < ncap)
                face[v[i].pl[k]] = 1;
    for (size_t i = 0; i < n; i++) {
        size_t m = seq[i];
        if (pre[m] || face[m])
            continue;
        plane_of(caps, ncap, P, (uint32_t)m, nm, &h);
        double slo, mx;
        if (scan(P, P->nv, nm, h, &slo, &mx) && slo > 0.0) /* else kept */
            pre[m] = certify(caps, ncap, P, &v[first_at(P->s, slo)], m, 0);
    }
    return SHAPE_DONE;
}

size_t vbm_caps_prefilter(const vbm_cap *caps, const vbm_circle *circ, size_t ncap,
                          vbm_capwork *w, uint8_t *pre)
{
    prework *pw = work(w);
    int empty;
    if (!pw || VB_ARRAY_FIT(pw->face, pw->cap_face, ncap + 1, 32) != VB_OK) {
        memset(pre, 0, ncap);
        return 0;
    }
    shape(caps, circ, ncap, pw, pre, &empty);
    size_t nrej = 0;
    for (size_t m = 1; m < ncap; m++)
        nrej += pre[m];
    return nrej;
}

void vbm_prefilter_free(vbm_capwork *w)
{
    prework *pw = w->pw;
    if (!pw)
        return;
    vbm_caps_free(&pw->sub);
    free(pw->pre);
    free(pw->seq);
    free(pw->key);
    free(pw->pm);
    free(pw->near_at);
    free(pw->near);
    free(pw->adj);
    free(pw->face);
    free(pw->known);
    free(pw->map);
    free(pw->inv);
    free(pw->caps);
    free(pw->axes);
    free(pw->given);
    free(pw);
    w->pw = NULL;
}

/* Whether a circle searched (not known) has two arcs or more that are not
 * the halves of one (a split's ends are VBM_NO_CAP): the search lists such
 * a circle's arcs from its widest gap among the ends of the caps it was
 * restricted by, which the rejected caps may have moved. */
static int several_arcs(const vbm_arc *arc, size_t narc, const uint8_t *known)
{
    for (size_t i = 0, run = 0; i < narc; i++) {
        run = i > 0 && arc[i].cap == arc[i - 1].cap ? run : 0;
        run += arc[i].pcap != VBM_NO_CAP;
        if (run >= 2 && !(known && known[arc[i].cap]))
            return 1;
    }
    return 0;
}

/* The kept caps' neighbours on the whole polyhedron (shape's SHAPE_DONE),
 * in kept indices, for vbm_cap_arcs_near: each pair of planes at a vertex
 * shares an edge; a ball plane counts as cap 0 (it holds every unit
 * vector in cap 0, so where it bounds a face cap 0 bounds that circle).
 * A face's circle meets the caps' intersection only where it meets the
 * face, which its neighbours bound; a cap without a face has every kept
 * cap as neighbour. The doubles only choose: the search proves every cap
 * left out. Returns 0 on ENOMEM. */
static int neighbours(prework *pw, size_t ncap, size_t nk)
{
    if (VB_ARRAY_FIT(pw->adj, pw->cap_adj, nk * nk + 1, 256) != VB_OK ||
        VB_ARRAY_FIT(pw->near_at, pw->cap_near_at, nk + 1, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->near, pw->cap_near, nk * nk + 1, 256) != VB_OK)
        return 0;
    uint8_t *adj = pw->adj;
    memset(adj, 0, nk * nk);
    const struct vbm_poly *P = &pw->poly;
    const pvert *v = P->v;
    for (size_t i = 0; i < P->nv; i++)
        for (int a = 0; a < 3; a++) {
            if (v[i].pl[a] >= ncap)
                continue;
            size_t x = pw->inv[v[i].pl[a]];
            for (int b = 1; b < 3; b++) {
                uint32_t y = v[i].pl[(a + b) % 3];
                adj[x * nk + (y < ncap ? pw->inv[y] : 0)] = 1;
            }
        }
    size_t nn = 0;
    for (size_t x = 0; x < nk; x++) {
        pw->near_at[x] = (uint32_t)nn;
        int none = !pw->face[pw->map[x]];
        for (size_t y = 0; y < nk; y++)
            if (y != x && (none || adj[x * nk + y]))
                pw->near[nn++] = (uint32_t)y;
    }
    pw->near_at[nk] = (uint32_t)nn;
    return 1;
}

/* The arrangement (vbm_caps.h) searched over the caps the prefilter keeps,
 * guided by their neighbours on the polyhedron where it was clipped whole
 * (vbm_cap_arcs_near; else vbm_cap_arcs_all's trial), or nothing searched
 * where it proves the intersection empty (no arc given: else the search
 * tells), with the bytes of the search over all caps (vbm_cap_arcs_all): both give
 * the intersection's arcs, the same points from the same restrictions
 * (circle l's frame and cap m's enclosures) with the same angles, in the
 * order of their circles; on a circle with one arc (split the same way)
 * there is no other order, so only a circle with several arcs, whose list
 * starts after the widest gap between the ends of the caps restricting it,
 * can differ: there, and wherever the search over the kept caps is not
 * decided, the search over all caps runs instead. (Where the search over
 * all caps would not have decided and this one does, or an empty one is
 * proven empty, the arcs are those of the same intersection, proven the
 * same way; the atom would have gone to the patches.) */
int vbm_cap_arcs(const vbm_cap *caps, const vbm_circle *axes, size_t ncap, const uint8_t *known,
                 const vbm_arc *given, size_t ngiven, vbm_capwork *w)
{
    prework *pw = ncap >= MIN_CAPS ? work(w) : NULL;
    if (!pw || VB_ARRAY_FIT(w->circ, w->cap_circ, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->pre, pw->cap_pre, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->face, pw->cap_face, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->map, pw->cap_map, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->inv, pw->cap_inv, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->caps, pw->cap_caps, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->axes, pw->cap_axes, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->known, pw->cap_known, ncap, 32) != VB_OK ||
        VB_ARRAY_FIT(pw->given, pw->cap_given, ngiven + 1, 32) != VB_OK)
        return vbm_cap_arcs_all(caps, axes, ncap, known, given, ngiven, w);
    /* the circles as the search makes them (it stops at the first it
     * cannot make or that leaves nothing: so does it again) */
    for (size_t l = 0; l < ncap; l++) {
        if (axes)
            w->circ[l] = axes[l];
        if ((axes ? axes[l].kind == 0 : !vbm_circle_axis(&caps[l], &w->circ[l])) ||
            w->circ[l].kind == VBM_CAP_NONE)
            return vbm_cap_arcs_all(caps, axes, ncap, known, given, ngiven, w);
    }
    uint8_t *pre = pw->pre;
    int empty, how = shape(caps, w->circ, ncap, pw, pre, &empty);
    if (how == SHAPE_EMPTY && empty && ngiven == 0) {
        w->narc = 0; /* proven empty: no arc (with arcs given, the search tells) */
        w->ncirc = ncap;
        return 1;
    }
    size_t nk = 0;
    for (size_t m = 0; m < ncap; m++) {
        pw->inv[m] = VBM_NO_CAP;
        if (pre[m])
            continue;
        pw->map[nk] = (uint32_t)m;
        pw->inv[m] = (uint32_t)nk;
        pw->caps[nk] = caps[m];
        pw->axes[nk] = w->circ[m];
        pw->known[nk++] = known ? known[m] : 0;
    }
    for (size_t i = 0; i < ngiven; i++) { /* a given arc on a rejected circle: all caps */
        vbm_arc *a = &pw->given[i];
        *a = given[i];
        if (pre[a->cap] || (a->pcap != VBM_NO_CAP && pre[a->pcap]) ||
            (a->qcap != VBM_NO_CAP && pre[a->qcap]))
            return vbm_cap_arcs_all(caps, axes, ncap, known, given, ngiven, w);
        a->cap = pw->inv[a->cap];
        a->pcap = a->pcap == VBM_NO_CAP ? a->pcap : pw->inv[a->pcap];
        a->qcap = a->qcap == VBM_NO_CAP ? a->qcap : pw->inv[a->qcap];
    }
    vbm_capwork *sub = &pw->sub;
    if (how != SHAPE_DONE && nk == ncap)
        return vbm_cap_arcs_all(caps, axes, ncap, known, given, ngiven, w);
    int e = how == SHAPE_DONE && neighbours(pw, ncap, nk)
                ? vbm_cap_arcs_near(pw->caps, pw->axes, nk, pw->known, pw->given, ngiven,
                                    pw->near_at, pw->near, sub)
                : vbm_cap_arcs_all(pw->caps, pw->axes, nk, pw->known, pw->given, ngiven, sub);
    if (e != 1 || several_arcs(sub->arc, sub->narc, pw->known) ||
        VB_ARRAY_FIT(w->arc, w->cap_arc, sub->narc + 1, 32) != VB_OK)
        return vbm_cap_arcs_all(caps, axes, ncap, known, given, ngiven, w);
    for (size_t k = 0; k < sub->ncirc; k++)
        w->circ[pw->map[k]] = sub->circ[k];
    for (size_t i = 0; i < sub->narc; i++) {
        vbm_arc *a = &w->arc[i];
        *a = sub->arc[i];
        a->cap = pw->map[a->cap];
        a->pcap = a->pcap == VBM_NO_CAP ? a->pcap : pw->map[a->pcap];
        a->qcap = a->qcap == VBM_NO_CAP ? a->qcap : pw->map[a->qcap];
    }
    w->narc = sub->narc;
    w->ncirc = sub->ncirc == nk ? ncap : 0;
    return 1;
}
