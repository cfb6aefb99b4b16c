/* The order of the channel table and the reason of each row (vbc_rank). */
#include <math.h>
#include <stdlib.h>

#include "vbc_pore_frame.h"

const char *vbc_why_text(int why)
{
    switch (why) {
    case VBC_WHY_PORE: return "pore along the axis, open at both ends";
    case VBC_WHY_PORE_CLOSED: return "pore along the axis, closed (radius <= 0)";
    case VBC_WHY_PORE_ONE_END: return "pore along the axis, one end inside the molecule";
    case VBC_WHY_THROUGH: return "through: openings on opposite faces";
    case VBC_WHY_PORE_BRANCH: return "branch of the pore (vestibule or side way)";
    case VBC_WHY_TUNNEL: return "tunnel: reaches the surface, not through";
    default: return "cavity: closed inside";
    }
}

/* Group of a reason in the table order. */
static int group(int why)
{
    switch (why) {
    case VBC_WHY_PORE: case VBC_WHY_PORE_CLOSED: case VBC_WHY_PORE_ONE_END: return 0;
    case VBC_WHY_THROUGH: return 1;
    case VBC_WHY_PORE_BRANCH: return 2;
    case VBC_WHY_TUNNEL: return 3;
    default: return 4;
    }
}

static int cmp_rank(const void *a, const void *b)
{
    const vbc_channel *x = a, *y = b;
    int gx = group(x->why), gy = group(y->why);
    if (gx != gy)
        return gx < gy ? -1 : 1;
    if (gx == 1 && x->bottleneck != y->bottleneck)
        return x->bottleneck > y->bottleneck ? -1 : 1;
    if (x->length != y->length)
        return x->length > y->length ? -1 : 1;
    return (x->first_point > y->first_point) - (x->first_point < y->first_point);
}

/* A third or more of c's points lie inside a pore sphere grown by 1 A. */
static int runs_along(const vbc_result *res, const vbc_channel *pore, const vbc_channel *c)
{
    const vbc_point *P = res->points + pore->first_point, *Q = res->points + c->first_point;
    size_t near = 0;
    for (size_t k = 0; k < c->npoints; k++)
        for (size_t j = 0; j < pore->npoints; j++) {
            double dx = Q[k].x - P[j].x, dy = Q[k].y - P[j].y, dz = Q[k].z - P[j].z;
            double reach = fmax(P[j].r, 0.0) + 1.0;
            if (dx * dx + dy * dy + dz * dz <= reach * reach) {
                near++;
                break;
            }
        }
    return 3 * near >= c->npoints;
}

void vbc_rank(vbc_result *res)
{
    const vbc_channel *pore = res->nchannels && res->channels[0].kind == VBC_PORE ? &res->channels[0] : NULL;
    for (size_t t = 0; t < res->nchannels; t++) {
        vbc_channel *c = &res->channels[t];
        if (c->kind == VBC_PORE)
            continue;
        c->why = c->kind == VBC_CAVITY ? VBC_WHY_CAVITY : c->through ? VBC_WHY_THROUGH : VBC_WHY_TUNNEL;
        if (pore && c->kind == VBC_CHANNEL && runs_along(res, pore, c))
            c->why = VBC_WHY_PORE_BRANCH;
    }
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_rank);
}
