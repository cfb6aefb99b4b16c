/* The table's side of the pore stage (vbc_pore_frame.h): the pore put at
 * the head of the channels with its lining atoms, and the discrete
 * channels' bottlenecks refined off the voxel centres. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_pore_frame.h"

/* What vbc_refine_bottlenecks' channels share. */
typedef struct {
    vbc_result *res;
    const vbc_cells *cells;
    double h;
} refine_view;

typedef struct {
    int32_t *list;
    size_t n, cap;
    uint8_t *mark;
    int failed;
} lining_set;

static void lining_put(int32_t atom, void *user)
{
    lining_set *L = user;
    if (L->mark[atom])
        return;
    if (VB_ARRAY_FIT(L->list, L->cap, L->n + 1, 64) != VB_OK) {
        L->failed = 1;
        return;
    }
    L->mark[atom] = 1;
    L->list[L->n++] = atom;
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* Length of the polyline through p[0..n), summed from the first point in the
 * order channel_components.c sums a voxel path, so a path no point of which
 * moved keeps its length to the bit. */
static double path_length(const vbc_point *p, size_t n)
{
    double len = 0.0;
    for (size_t k = 1; k < n; k++)
        len += sqrt((p[k].x - p[k - 1].x) * (p[k].x - p[k - 1].x) +
                    (p[k].y - p[k - 1].y) * (p[k].y - p[k - 1].y) +
                    (p[k].z - p[k - 1].z) * (p[k].z - p[k - 1].z));
    return len;
}

int vbc_pore_lining(const vbc_pore *p, const vbc_cells *cells, double lining_tol, int32_t **out,
                    size_t *n)
{
    const vb_sphere_set *s = vbc_cells_spheres(cells);
    *out = NULL;
    *n = 0;
    lining_set L = {NULL, 0, 0, calloc(s->n ? s->n : 1, 1), 0};
    if (!L.mark)
        return VB_ENOMEM;
    for (size_t k = 0; k < p->n && !L.failed; k++) {
        const vbc_pore_point *q = &p->pts[k];
        double c[3] = {q->x, q->y, q->z};
        vbc_cells_within(cells, c, q->r + lining_tol, lining_put, &L);
    }
    free(L.mark);
    if (L.failed) {
        free(L.list);
        return VB_ENOMEM;
    }
    qsort(L.list, L.n, sizeof *L.list, cmp_i32);
    *out = L.list;
    *n = L.n;
    return VB_OK;
}

int vbc_result_add_pore_lined(vb_ctx *ctx, vbc_result *res, const vbc_pore *p, int32_t *lining,
                              size_t nlining)
{
    size_t np = 0, nl = 0;
    for (size_t t = 0; t < res->nchannels; t++) {
        np += res->channels[t].npoints;
        nl += res->channels[t].nlining;
    }
    vbc_channel *ch = malloc((res->nchannels + 1) * sizeof *ch);
    vbc_point *pts = malloc((np + p->n) * sizeof *pts);
    int32_t *lin = malloc((nl + nlining + 1) * sizeof *lin);
    if (!ch || !pts || !lin) {
        free(lining);
        free(ch);
        free(pts);
        free(lin);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "pore of %zu points", p->n);
    }
    for (size_t k = 0; k < p->n; k++) {
        const vbc_pore_point *q = &p->pts[k];
        pts[k] = (vbc_point){q->x, q->y, q->z, q->r, q->atom};
    }
    if (nlining)
        memcpy(lin, lining, nlining * sizeof *lin);
    free(lining);
    if (nl)
        memcpy(lin + nlining, res->lining, nl * sizeof *lin);
    if (np)
        memcpy(pts + p->n, res->points, np * sizeof *pts);
    double len = path_length(pts, p->n);
    int open = p->open_lo && p->open_hi;
    double rmin = p->pts[p->min_at].r;
    ch[0] = (vbc_channel){VBC_PORE,
                          rmin <= 0.0 ? VBC_WHY_PORE_CLOSED : open ? VBC_WHY_PORE : VBC_WHY_PORE_ONE_END,
                          open, 0, (size_t)(p->open_lo + p->open_hi), len, rmin, p->min_at, 0, p->n,
                          0, nlining};
    for (size_t t = 0; t < res->nchannels; t++) {
        ch[t + 1] = res->channels[t];
        ch[t + 1].first_point += p->n;
        ch[t + 1].first_lining += nlining;
    }
    free(res->channels);
    free(res->points);
    free(res->lining);
    res->channels = ch;
    res->points = pts;
    res->lining = lin;
    res->nchannels++;
    vbc_pore_summary *S = &res->pore;
    S->present = 1;
    memcpy(S->u, p->axis.u, sizeof S->u);
    memcpy(S->c, p->axis.c, sizeof S->c);
    S->source = p->axis.source;
    S->chains = p->axis.chains;
    memcpy(S->why, p->axis.why, sizeof S->why);
    S->step = p->n > 1 ? (p->pts[p->n - 1].s - p->pts[0].s) / (double)(p->n - 1) : 0.0;
    S->F = p->F;
    S->g_macro_pS = p->g_macro_pS;
    S->open_lo = p->open_lo;
    S->open_hi = p->open_hi;
    return VB_OK;
}

#define REFINE_PER_THREAD 8

/* One channel of vbc_refine_bottlenecks (vb_for_fn over the channels: each
 * moves only its own points). */
static void refine_channel(void *ctx, size_t t, int tid)
{
    (void)tid;
    const refine_view *R = ctx;
    vbc_result *res = R->res;
    vbc_channel *c = &res->channels[t];
    if (c->kind == VBC_PORE || c->npoints < 2)
        return;
    vbc_point *p = res->points + c->first_point;
    size_t b = c->bottleneck_at;
    size_t lo = b >= 2 ? b - 2 : 0, hi = b + 2 < c->npoints ? b + 2 : c->npoints - 1;
    for (size_t k = lo; k <= hi; k++) {
        const vbc_point *a = &p[k > 0 ? k - 1 : k], *z = &p[k + 1 < c->npoints ? k + 1 : k];
        double u[3] = {z->x - a->x, z->y - a->y, z->z - a->z};
        double n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (!(n > 0.0))
            continue;
        for (int i = 0; i < 3; i++)
            u[i] /= n;
        double q[3] = {p[k].x, p[k].y, p[k].z};
        int32_t atom;
        double r = vbc_plane_maximise(R->cells, u, R->h, q, &atom);
        if (r > p[k].r) {
            p[k] = (vbc_point){q[0], q[1], q[2], r, atom};
        }
    }
    /* length_A is the length of the centreline as written (the moved
     * points' polyline), not the voxel path's: the pruning by
     * --min-length saw the latter. */
    c->length = path_length(p, c->npoints);
    c->bottleneck = INFINITY;
    for (size_t k = 0; k < c->npoints; k++)
        if (p[k].r < c->bottleneck) {
            c->bottleneck = p[k].r;
            c->bottleneck_at = k;
        }
}

void vbc_refine_bottlenecks(vbc_result *res, const vbc_cells *cells, double h)
{
    refine_view R = {res, cells, h};
    int nt = vbc_pore_threads(res->nchannels, REFINE_PER_THREAD);
    if (nt > 1)
        vb_parallel_for(refine_channel, &R, res->nchannels, nt);
    else
        for (size_t t = 0; t < res->nchannels; t++)
            refine_channel(&R, t, 0);
}
