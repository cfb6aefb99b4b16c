/* Burial bounds: which pairs of spheres can share a vertex at all.
 *
 * Claim. Let T >= 0 and suppose every point of the sphere
 * S_a(T) = { c_a + (T + R_a) w : |w| = 1 } lies strictly inside some ball
 * B(c_j, T + R_j), j != a ("a is buried at scale T"). Then every vertex that
 * sphere a touches has t < T.
 * Proof. A vertex ball B(p, t) touching a has p = c_a + (t + R_a) w for a
 * unit w; write x = c_a + R_a w (the touching point). The balls
 * B(x + tau w, tau), tau >= 0, are nested and grow with tau (all touch a at
 * x from outside). If t >= T, B(p, t) contains B(x + T w, T), whose centre
 * lies in S_a(T), hence within T + R_j of some c_j: that open ball meets the
 * open ball of sphere j, so j cuts into B(p, t), which is then not empty.
 * Consequence. If a vertex touches a and b, |c_a - c_b| <= |c_a - p| +
 * |p - c_b| = 2t + R_a + R_b < 2 T_a + R_a + R_b: a pair farther apart than
 * that shares no vertex (if a is buried at T_a), and no quadruple containing
 * it need be solved.
 *
 * The covering is tested on direction patches of a cube map, each enclosed
 * in interval arithmetic (vbx_ia.h): a patch is covered when the interval
 * box of its points at radius T + R_a lies, as a box, strictly within
 * T + R_j of one c_j. Patches that no single ball covers are split; a patch
 * still uncovered at the finest level means "not shown buried at T". The
 * test is only sufficient, which is all the claim needs. */
#include <stdlib.h>

#include "vbx_burial.h"

#define VBX_PATCH_DEPTH 5      /* finest patch: 1/32 of a cube face side */
#define VBX_PATCH_BUDGET 6000  /* patches tested per (sphere, T) before giving up */

typedef struct burial_ctx {
    const vbx_data *d;
    uint32_t a;
    double T;
    vbx_ia rho;            /* T + R_a */
    const uint32_t *cand;  /* spheres whose balls may reach S_a(T) */
    size_t ncand;
    int budget;
} burial_ctx;

/* Is the patch (face f, [u0,u1] x [v0,v1] of the face square) covered? */
static int patch_covered(burial_ctx *b, int f, double u0, double u1, double v0, double v1,
                         int depth)
{
    if (--b->budget < 0)
        return 0;
    /* Face f: axis f/2 carries +-1, the other two axes carry u and v. */
    int ax = f / 2;
    vbx_ia comp[3];
    comp[ax] = vbx_ia_point((f & 1) ? -1.0 : 1.0);
    vbx_ia U = {u0, u1}, V = {v0, v1};
    comp[(ax + 1) % 3] = U;
    comp[(ax + 2) % 3] = V;
    vbx_ia n2 = vbx_ia_add(vbx_ia_add(vbx_ia_point(1.0), vbx_ia_sqr(U)), vbx_ia_sqr(V));
    vbx_ia norm = vbx_ia_sqrt(n2);
    const vbx_ia *ca = &b->d->box[4 * (size_t)b->a];
    vbx_ia p[3];
    for (int k = 0; k < 3; k++)
        p[k] = vbx_ia_add(ca[k], vbx_ia_mul(b->rho, vbx_ia_div(comp[k], norm)));
    vbx_ia T = vbx_ia_point(b->T);
    for (size_t i = 0; i < b->ncand; i++) {
        const vbx_ia *cj = &b->d->box[4 * (size_t)b->cand[i]];
        vbx_ia d2 = vbx_ia_sqr(vbx_ia_sub(p[0], cj[0]));
        d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(p[1], cj[1])));
        d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(p[2], cj[2])));
        vbx_ia reach = vbx_ia_add(T, cj[3]);
        if (vbx_ia_sqrt(d2).hi < reach.lo)
            return 1;
    }
    if (depth >= VBX_PATCH_DEPTH)
        return 0;
    double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    return patch_covered(b, f, u0, um, v0, vm, depth + 1) &&
           patch_covered(b, f, um, u1, v0, vm, depth + 1) &&
           patch_covered(b, f, u0, um, vm, v1, depth + 1) &&
           patch_covered(b, f, um, u1, vm, v1, depth + 1);
}

static int buried_at(burial_ctx *b, double T, uint32_t *scratch)
{
    const vbx_data *d = b->d;
    b->T = T;
    b->rho = vbx_ia_add(vbx_ia_point(T), d->box[4 * (size_t)b->a + 3]);
    /* Candidates: balls B(c_j, T + R_j) that can reach S_a(T) at all. The
     * choice only affects how often the test succeeds, never its truth. */
    const double *nr = d->near;
    size_t m = 0;
    for (size_t j = 0; j < d->n; j++) {
        if (j == b->a)
            continue;
        double dx = nr[4 * j] - nr[4 * (size_t)b->a], dy = nr[4 * j + 1] - nr[4 * (size_t)b->a + 1],
               dz = nr[4 * j + 2] - nr[4 * (size_t)b->a + 2];
        double reach = 2.0 * T + nr[4 * j + 3] + nr[4 * (size_t)b->a + 3];
        if (dx * dx + dy * dy + dz * dz < 1.0001 * reach * reach)
            scratch[m++] = (uint32_t)j;
    }
    b->cand = scratch;
    b->ncand = m;
    b->budget = VBX_PATCH_BUDGET;
    for (int f = 0; f < 6; f++)
        if (!patch_covered(b, f, -1.0, 1.0, -1.0, 1.0, 0))
            return 0;
    return 1;
}

int vbx_burial_bounds(const vbx_data *d, double *T)
{
    size_t n = d->n;
    uint32_t *scratch = malloc((n ? n : 1) * sizeof *scratch);
    if (!scratch)
        return VB_ENOMEM;
    /* Scale of the set: the largest side of the box of centres. */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = vbx_min(lo[k], d->near[4 * i + k]);
            hi[k] = vbx_max(hi[k], d->near[4 * i + k]);
        }
    double ext = 0.0;
    for (int k = 0; k < 3; k++)
        ext = vbx_max(ext, hi[k] - lo[k]);
    double cap = 2.0 * ext + 4.0 * d->rmax;
    for (size_t a = 0; a < n; a++) {
        burial_ctx b = {d, (uint32_t)a, 0.0, {0.0, 0.0}, NULL, 0, 0};
        /* Start near the spacing of the set, double until buried (or give
         * up at the cap: a sphere on the hull is never buried), then bisect. */
        double t = vbx_max(ext / cbrt((double)n), d->rmax) * 0.5;
        double good = INFINITY, bad = 0.0;
        while (t <= cap) {
            if (buried_at(&b, t, scratch)) {
                good = t;
                break;
            }
            bad = t;
            t *= 2.0;
        }
        for (int it = 0; it < 4 && good < INFINITY; it++) {
            double mid = 0.5 * (good + bad);
            if (buried_at(&b, mid, scratch))
                good = mid;
            else
                bad = mid;
        }
        T[a] = good;
    }
    free(scratch);
    return VB_OK;
}
