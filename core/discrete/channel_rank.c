/* The order of the channel table and the reason of each row (vbc_rank). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

/* The pore's points ordered along a line through the pore (its first to
 * last point), so that a channel point asks only those whose projection
 * lies within the widest sphere's reach of its own: a point farther along
 * the line is farther in space (the projection moves no faster), so it
 * holds no sphere the point is in, and the answer is the full scan's. */
typedef struct pore_index {
    const vbc_point *P;
    size_t n;
    double u[3];   /* unit direction of the line */
    double reach;  /* the largest sphere's reach, with a margin */
    double *t;     /* sorted projections, n */
    double *r;     /* the reach of each (reach_of) */
    uint32_t *at;  /* the point of each */
} pore_index;

/* The margin of the window, A: far above the rounding of a projection and
 * of a squared distance (coordinates below 1e4 A: 1e-12 A), far below
 * any distance that matters. */
#define WINDOW_MARGIN 1e-6

/* A pore sphere grown by 1 A: its radius (0 when it is closed). */
static double reach_of(const vbc_point *q)
{
    return fmax(q->r, 0.0) + 1.0;
}

static int cmp_proj(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

static void pore_index_free(pore_index *X)
{
    free(X->t);
    free(X->r);
    free(X->at);
    X->t = X->r = NULL;
    X->at = NULL;
}

/* Fills X for pore's points; 0, or -1 (no line, or out of memory: the
 * caller scans every point). */
static int pore_index_make(const vbc_result *res, const vbc_channel *pore, pore_index *X)
{
    memset(X, 0, sizeof *X);
    X->P = res->points + pore->first_point;
    X->n = pore->npoints;
    if (X->n < 2 || X->n > UINT32_MAX)
        return -1;
    const vbc_point *a = X->P, *b = X->P + X->n - 1;
    double d[3] = {b->x - a->x, b->y - a->y, b->z - a->z};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 1e-3))
        return -1;
    for (int k = 0; k < 3; k++)
        X->u[k] = d[k] / len;
    double *pair = malloc(2 * X->n * sizeof *pair);
    X->t = malloc(X->n * sizeof *X->t);
    X->r = malloc(X->n * sizeof *X->r);
    X->at = malloc(X->n * sizeof *X->at);
    if (!pair || !X->t || !X->r || !X->at) {
        free(pair);
        pore_index_free(X);
        return -1;
    }
    for (size_t j = 0; j < X->n; j++) {
        const vbc_point *q = &X->P[j];
        pair[2 * j] = q->x * X->u[0] + q->y * X->u[1] + q->z * X->u[2];
        pair[2 * j + 1] = (double)j;
        X->reach = fmax(X->reach, reach_of(q));
    }
    qsort(pair, X->n, 2 * sizeof *pair, cmp_proj);
    for (size_t j = 0; j < X->n; j++) {
        X->t[j] = pair[2 * j];
        X->at[j] = (uint32_t)pair[2 * j + 1];
        X->r[j] = reach_of(&X->P[X->at[j]]);
    }
    free(pair);
    X->reach += WINDOW_MARGIN;
    return 0;
}

/* Whether Q lies in the sphere at P grown to `reach` (reach_of(P)). */
static int in_grown(const vbc_point *P, double reach, const vbc_point *Q)
{
    double dx = Q->x - P->x, dy = Q->y - P->y, dz = Q->z - P->z;
    return dx * dx + dy * dy + dz * dz <= reach * reach;
}

/* Whether Q lies in some pore sphere grown by 1 A: of the points in the
 * window of X when X has them (X->t), else of all. */
static int near_pore(const pore_index *X, const vbc_point *Q)
{
    if (!X->t) {
        for (size_t j = 0; j < X->n; j++)
            if (in_grown(&X->P[j], reach_of(&X->P[j]), Q))
                return 1;
        return 0;
    }
    double tq = Q->x * X->u[0] + Q->y * X->u[1] + Q->z * X->u[2];
    size_t lo = 0, hi = X->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (X->t[mid] < tq - X->reach)
            lo = mid + 1;
        else
            hi = mid;
    }
    /* Within the window, a sphere whose own reach (and the margin) the
     * projections already part holds no Q either. */
    for (size_t j = lo; j < X->n && X->t[j] <= tq + X->reach; j++)
        if (fabs(X->t[j] - tq) <= X->r[j] + WINDOW_MARGIN && in_grown(&X->P[X->at[j]], X->r[j], Q))
            return 1;
    return 0;
}

/* A third or more of c's points lie inside a pore sphere grown by 1 A. */
static int runs_along(const vbc_result *res, const pore_index *X, const vbc_channel *c)
{
    const vbc_point *Q = res->points + c->first_point;
    size_t near = 0;
    for (size_t k = 0; k < c->npoints; k++)
        near += (size_t)near_pore(X, &Q[k]);
    return 3 * near >= c->npoints;
}

void vbc_rank(vbc_result *res)
{
    const vbc_channel *pore = res->nchannels && res->channels[0].kind == VBC_PORE ? &res->channels[0] : NULL;
    pore_index X;
    if (pore)
        (void)pore_index_make(res, pore, &X); /* when it fails: X.t NULL, every point asked */
    for (size_t t = 0; t < res->nchannels; t++) {
        vbc_channel *c = &res->channels[t];
        if (c->kind == VBC_PORE)
            continue;
        c->why = c->kind == VBC_CAVITY ? VBC_WHY_CAVITY : c->through ? VBC_WHY_THROUGH : VBC_WHY_TUNNEL;
        if (pore && c->kind == VBC_CHANNEL && runs_along(res, &X, c))
            c->why = VBC_WHY_PORE_BRANCH;
    }
    if (pore)
        pore_index_free(&X);
    if (res->nchannels > 1)
        qsort(res->channels, res->nchannels, sizeof *res->channels, cmp_rank);
}
