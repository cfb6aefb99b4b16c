/* The empty-tangent-sphere test in double (a vertex is a point whose
 * tangent sphere no other sphere enters): the deepest intruder, for the
 * swaps and the plausibility of clusters, and the yes/no test of the
 * roots, the completion and the topology. Candidates only: the exact
 * certifier decides. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

uint32_t vbs_tangent_intruder(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4],
                                 double tol, uint32_t **buf, size_t *cap, int *err)
{
    const vb_sphere_set *s = h->set;
    const double p[3] = {k->x, k->y, k->z};
    size_t n = 0;
    double radius = k->t + h->rmax + tol;
    if (radius < 0.0)
        return VBS_INF_COLOUR;
    if (vbs_hash_query(h, p, radius, buf, &n, cap)) {
        *err = VB_ENOMEM;
        return VBS_INF_COLOUR;
    }
    uint32_t worst = VBS_INF_COLOUR;
    double deepest = -tol;
    for (size_t i = 0; i < n; i++) {
        uint32_t j = (*buf)[i];
        if (j == q[0] || j == q[1] || j == q[2] || j == q[3])
            continue;
        if (s->contained && s->contained[j])
            continue;
        double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
        double gap = sqrt(dx * dx + dy * dy + dz * dz) - s->r[j] - k->t;
        if (gap < deepest) {
            deepest = gap;
            worst = j;
        }
    }
    return worst;
}

int vbs_tangent_empty(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4], double tol)
{
    const vb_sphere_set *s = h->set;
    const double p[3] = {k->x, k->y, k->z};
    double radius = k->t + h->rmax + tol;
    if (radius < 0.0)
        return 1;
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        double l = (p[a] - radius - h->lo[a]) / h->h, u = (p[a] + radius - h->lo[a]) / h->h;
        lo[a] = l < 0.0 ? 0 : l >= (double)h->dim[a] ? h->dim[a] : (int)l;
        hi[a] = u < 0.0 ? -1 : u >= (double)h->dim[a] ? h->dim[a] - 1 : (int)u;
    }
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int x = lo[0]; x <= hi[0]; x++) {
                size_t c = ((size_t)z * (size_t)h->dim[1] + (size_t)y) * (size_t)h->dim[0] + (size_t)x;
                for (uint32_t m = h->start[c]; m < h->start[c + 1]; m++) {
                    uint32_t j = h->idx[m];
                    if (j == q[0] || j == q[1] || j == q[2] || j == q[3] ||
                        (s->contained && s->contained[j]))
                        continue;
                    double dx = s->x[j] - p[0], dy = s->y[j] - p[1], dz = s->z[j] - p[2];
                    if (sqrt(dx * dx + dy * dy + dz * dz) - s->r[j] - k->t < -tol)
                        return 0;
                }
            }
    return 1;
}
