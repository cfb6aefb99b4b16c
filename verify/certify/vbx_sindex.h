/* The spatial index of sphere centres for the emptiness scans of verify/:
 * a uniform grid whose cell side comes from the local density of the
 * centres (not from the bounding box: a shell-like input such as a capsid
 * protomer has few centres in a large box), for the common small tangent
 * balls, and a bounding volume hierarchy over the same slots for the large
 * ones (far hull vertices), whose cost follows the ball's surface rather
 * than its volume.
 *
 * Slots: the spheres sorted by grid cell in row-major order (x fastest,
 * then by id), so a run of cells along x is one run of slots; the
 * hierarchy's leaves are the occupied cells, ordered along a Morton curve
 * of their coordinates and split where the codes' highest differing bit
 * changes (an LBVH over cells).
 *
 * Conservative, in both parts:
 *  - grid: a sphere sits in the cell of the nearest double of its exact
 *    centre, and a cell index is floor((x - x0) * (1 / h)) clamped, in
 *    round-to-nearest. Every step is monotone non-decreasing in x, and so is
 *    rounding an exact value to nearest. Hence when an exact centre lies in a
 *    box [L, H] with double ends, its nearest double does too (RN(L) = L),
 *    and its cell lies between the cells of L and H: visiting those cells
 *    sees every sphere whose exact centre is in the box.
 *  - hierarchy: a node's box is the union of the enclosures of its spheres'
 *    exact centres (vbx_data.box) and its rmax the largest upper bound of
 *    their radii; a node is skipped only when vbx_outside_box proves every
 *    such sphere outside the tangent ball of every point of the query.
 * The density estimate, the cell boxes used to skip rows (see
 * vbx_walk_next) and the choice between the two parts decide only the
 * cost, never which sphere is seen. */
#ifndef VBX_SINDEX_H
#define VBX_SINDEX_H

#include <stddef.h>
#include <stdint.h>

#include "vbx_ia.h"

/* A query spanning more cells than this on an axis walks the hierarchy. */
#define VBX_SINDEX_GRID_SPAN 8
/* Depth bound of the hierarchy: distinct 63-bit Morton codes split at
 * most 63 times. */
#define VBX_SINDEX_STACK 66

typedef struct vbx_bvh_node {
    double lo[3], hi[3]; /* every exact centre of the node's spheres lies in [lo, hi] */
    double rmax;         /* >= every exact radius of the node's spheres */
    uint32_t first;      /* leaf: first slot; internal: index of the right child */
    uint32_t count;      /* leaf: spheres in slots [first, first + count); 0: internal
                          * (the left child is the next node) */
} vbx_bvh_node;

typedef struct vbx_sindex {
    size_t n, nnodes;
    uint32_t *ids;      /* slot -> sphere id */
    vbx_ia *box;        /* 4 per slot: enclosures of x, y, z, R of ids[slot], input units */
    double *mid;        /* 4 per slot: the nearest doubles of x, y, z and the upper
                         * bound of R (the probes' compact copy) */
    double wc;          /* >= the width of every centre enclosure (any axis) */
    vbx_bvh_node *node; /* node 0 is the root (none when n == 0) */
    double x0[3], h, ih;/* grid: cell of x along axis k is floor((x - x0[k]) ih), clamped;
                         * ih = fl(1 / h) */
    double eps[3];      /* margin of a cell's box (vbx_walk_next) */
    int nc[3];          /* cells per axis */
    uint32_t *cell;     /* ncells + 1, row-major (x fastest): cell c holds slots
                         * [cell[c], cell[c + 1]) */
    double rmax;        /* >= every exact radius */
    double rmin;        /* <= every exact radius (NaN: an enclosure was NaN) */
} vbx_sindex;

/* Builds the index over n spheres from their enclosures (box[4*i + k],
 * k = x, y, z, R) and the nearest doubles of their centres (near[4*i + k],
 * k < 3). Returns 0, or -1 when out of memory or n >= 2^31 (t is then
 * empty). */
int vbx_sindex_build(vbx_sindex *t, const vbx_ia *box, const double *near, size_t n);
void vbx_sindex_free(vbx_sindex *t);

/* 1 when every sphere with centre in [clo, chi] and radius <= rhi is proven
 * outside the tangent ball of every (x, y, z, t) in p: |q - c| - R - t > 0;
 * 0 when it cannot tell. d2 = the sum of the squared axis gaps fl(p_lo -
 * c_hi) or fl(c_lo - p_hi) where positive (vbx_gap2). Plain round-to-nearest with one
 * relative margin instead of a step outward per operation (u = 2^-53;
 * normal range, checked below):
 *  - g~ = fl(p_lo - c_hi) (or fl(c_lo - p_hi)) has the sign of the exact
 *    difference, which is a lower bound of |q_k - c_k| for every point of
 *    the boxes; when g~ > 0 the exact one is >= g~ / (1 + u). Axes with
 *    g~ <= 0 add 0, which only lowers the bound.
 *  - d~ = fl(fl(g0~^2) + fl(g1~^2) + fl(g2~^2)): at most 3 more roundings per
 *    term (square, two sums), so |q - c|^2 >= d~ / (1 + u)^5. Terms that
 *    underflow lose at most 2^-1074 each, negligible when d~ >= 2^-900.
 *  - r~ = fl(t_hi + rhi) >= (t + R) / (1 + u) when positive, so
 *    (t + R)^2 <= fl(r~^2) (1 + u)^3.
 * Hence d~ > fl(r~^2) (1 + u)^8 proves the claim, and fl(fl(r~^2) (1 + 2^-40))
 * exceeds that by far ((1 + u)^8 < 1 + 2^-49). When r~ < 0, t + R < 0 <=
 * |q - c| (fl keeps the sign of a sum). Infinite or NaN bounds make the
 * comparisons fail: "cannot tell". */
static inline int vbx_outside_box(double d2, double rhi, const vbx_ia p[4])
{
    double r = p[3].hi + rhi;
    /* Non-short-circuit: comparisons are cheaper than branches here. */
    return (r < 0.0) | ((d2 >= 0x1p-900) & (d2 <= DBL_MAX) & (d2 > (r * r) * (1.0 + 0x1p-40)));
}

/* max(m, 0) without a branch (a compare-and-branch on the sign of a gap is
 * unpredictable in the scans): 0.5 (m + |m|) is m for m >= 0 and 0 for
 * m < 0, exactly (2m and the halving are exact below DBL_MAX / 2; above,
 * +inf makes the test answer "cannot tell"; NaN stays NaN). */
static inline double vbx_pos(double m)
{
    return 0.5 * (m + fabs(m));
}

static inline double vbx_gap2(const double clo[3], const double chi[3], const vbx_ia p[4])
{
    double g0 = vbx_pos(vbx_max(p[0].lo - chi[0], clo[0] - p[0].hi));
    double g1 = vbx_pos(vbx_max(p[1].lo - chi[1], clo[1] - p[1].hi));
    double g2 = vbx_pos(vbx_max(p[2].lo - chi[2], clo[2] - p[2].hi));
    return (g0 * g0 + g1 * g1) + g2 * g2;
}

/* The same test for one sphere: cj = its enclosures (x, y, z, R). */
static inline int vbx_outside_sphere(const vbx_ia cj[4], const vbx_ia p[4])
{
    double g0 = vbx_pos(vbx_max(p[0].lo - cj[0].hi, cj[0].lo - p[0].hi));
    double g1 = vbx_pos(vbx_max(p[1].lo - cj[1].hi, cj[1].lo - p[1].hi));
    double g2 = vbx_pos(vbx_max(p[2].lo - cj[2].hi, cj[2].lo - p[2].hi));
    return vbx_outside_box((g0 * g0 + g1 * g1) + g2 * g2, cj[3].hi, p);
}

/* The per-sphere tests of a scan, cheaper than enclosing |q - c| - R - t
 * in intervals: the query box p is replaced by one of its corners m
 * (m_k = p_k.lo, |q_k - m_k| <= the box's width) and each exact centre c by
 * its nearest double c~ (|c_k - c~_k| <= wc), so for every q in the box
 * |q - c| = |m - c~| +- W with W >= sqrt(sum_k (width_k + wc)^2). */
typedef struct vbx_probe {
    double m[3];
    double thw;  /* fl(t_hi + W), rounded up */
    double tlw;  /* fl(t_lo - W), rounded down */
} vbx_probe;

static inline void vbx_probe_init(vbx_probe *pr, const vbx_sindex *t, const vbx_ia p[4])
{
    double a2 = 0.0;
    for (int k = 0; k < 3; k++) {
        pr->m[k] = p[k].lo;
        double a = vbx_succ(vbx_succ(p[k].hi - p[k].lo) + t->wc);
        a2 += a * a;
    }
    /* The sum of squares and the root: 5 roundings, (1 + u)^5 < 1 + 2^-48. */
    double W = sqrt(a2) * (1.0 + 0x1p-48);
    pr->thw = vbx_succ(p[3].hi + W);
    pr->tlw = vbx_pred(p[3].lo - W);
}

/* 1 when sphere c (c = mid of its slot: c~ and R_hi) is proven outside the
 * tangent ball of every point of the box: |q - c| - R - t > 0. With
 * D~ = fl(sum fl(fl(m_k - c~_k)^2)) >= ... |m - c~|^2 >= D~ / (1 + u)^5, and
 * rho~ = fl(thw + R_hi) >= (t + R + W) / (1 + u) when positive, so
 * (t + R + W)^2 <= fl(rho~^2) (1 + u)^3: D~ > fl(rho~^2) (1 + 2^-40) proves
 * |m - c~| > t + R + W, hence |q - c| > t + R. rho~ < 0: t + R < -W <= 0.
 * D~ >= 2^-900 keeps underflow out of the argument. */
static inline int vbx_probe_outside(const vbx_probe *pr, const double c[4])
{
    double dx = pr->m[0] - c[0], dy = pr->m[1] - c[1], dz = pr->m[2] - c[2];
    double D = (dx * dx + dy * dy) + dz * dz, rho = pr->thw + c[3];
    return (rho < 0.0) | (D > vbx_max((rho * rho) * (1.0 + 0x1p-40), 0x1p-900));
}

/* 1 when sphere c, of radius at least rlo, is proven inside the tangent
 * ball of every point of the box: |q - c| < t + R. sigma~ =
 * fl(fl(tlw + rlo) (1 - 2^-52)) <= t + R - W when positive (the sum is
 * within u of its value, and the product with (1 - 2^-52), rounded, stays
 * below (1 - u) times it); when sigma~ >= 2^-400 and
 * fl(D~ (1 + 2^-40)) >= D~ (1 + u)^5 >= |m - c~|^2 is below
 * fl(fl(sigma~^2) (1 - 2^-40)) <= sigma~^2: |q - c| <= |m - c~| + W <
 * sigma~ + W <= t + R. The bound on sigma~ keeps underflow (absolute errors
 * near 2^-1074) far below the margin. */
static inline int vbx_probe_inside(const vbx_probe *pr, const double c[4], double rlo)
{
    double dx = pr->m[0] - c[0], dy = pr->m[1] - c[1], dz = pr->m[2] - c[2];
    double D = (dx * dx + dy * dy) + dz * dz, sg = (pr->tlw + rlo) * (1.0 - 0x1p-52);
    return sg >= 0x1p-400 && D * (1.0 + 0x1p-40) < (sg * sg) * (1.0 - 0x1p-40);
}

/* A walk over the runs of slots that may hold a sphere reaching into the
 * tangent ball of some point of p (x, y, z, t): the grid's cells around p
 * for a small ball, else the hierarchy's leaves that vbx_outside_box cannot
 * skip, nearest child first. */
typedef struct vbx_walk {
    const vbx_sindex *t;
    const vbx_ia *p;
    int grid;                  /* 1: grid rows, 0: hierarchy */
    int lo[3], hi[3], at[3];   /* grid: cell range and the next row (at[1], at[2]) */
    double r2;                 /* grid: bound of (t + R)^2 (vbx_walk_next) */
    double g2[2][VBX_SINDEX_GRID_SPAN]; /* grid: fl(g~^2) of the gap from p to each
                                         * row's y (0) and z (1) range, lo first */
    uint32_t sp;
    uint32_t stack[VBX_SINDEX_STACK];
    /* hierarchy: a second test that may skip a node from its box and rmax
     * (1: every sphere of the node is proven outside), or NULL
     * (vbx_walk_skip) */
    int (*skip)(const void *arg, const double lo[3], const double hi[3], double rmax);
    const void *skip_arg;
} vbx_walk;

/* Cell of x along axis k, clamped (monotone in x; NaN clamps low, and the
 * range below treats NaN bounds as the whole axis). */
static inline int vbx_sindex_axis(const vbx_sindex *t, int k, double x)
{
    /* Monotone: a subtraction and a multiplication by ih > 0 in
     * round-to-nearest, then truncation, which is floor for f >= 0. */
    double f = (x - t->x0[k]) * t->ih;
    if (!(f >= 0.0))
        return 0;
    if (f >= (double)(t->nc[k] - 1))
        return t->nc[k] - 1;
    return (int)f;
}

/* Bounds of the centres in the cells i along axis k: a centre whose
 * nearest double falls in cell i lies in [x0 + i h, x0 + (i + 1) h] up to
 * the roundings of (near - x0) ih (two, relative u each, on values below
 * |x0| + nc h), of ih against 1 / h and of near itself (u each), and of
 * these bounds (two): t->eps = 2^-45 (|x0| + nc h) + 2^-1000 covers them by
 * far. The cells at the ends of an axis also hold everything beyond. */
static inline double vbx_sindex_lo(const vbx_sindex *t, int k, int i)
{
    return i == 0 ? -INFINITY : t->x0[k] + (double)i * t->h - t->eps[k];
}

static inline double vbx_sindex_hi(const vbx_sindex *t, int k, int i)
{
    return i == t->nc[k] - 1 ? INFINITY : t->x0[k] + (double)(i + 1) * t->h + t->eps[k];
}

static inline int vbx_bvh_skip(const vbx_bvh_node *nd, const vbx_ia p[4], double *d2)
{
    *d2 = vbx_gap2(nd->lo, nd->hi, p);
    return vbx_outside_box(*d2, nd->rmax, p);
}

static inline void vbx_walk_init(vbx_walk *w, const vbx_sindex *t, const vbx_ia p[4])
{
    w->t = t;
    w->p = p;
    w->sp = 0;
    w->grid = 0;
    w->skip = NULL;
    w->skip_arg = NULL;
    for (int k = 0; k < 3; k++)
        w->lo[k] = w->hi[k] = w->at[k] = 0;
    if (!t->n)
        return;
    /* Sphere j can reach into the open tangent ball only if |q - c_j| <
     * t + R_j <= t + Rmax: the grid visits the cells of the centres within
     * t + Rmax of the box (bounds pushed outward, see vbx_ia.h). */
    double rad = vbx_succ(p[3].hi + t->rmax);
    int span_ok = rad < INFINITY;
    for (int k = 0; k < 3 && span_ok; k++) {
        double blo = vbx_pred(p[k].lo - rad), bhi = vbx_succ(p[k].hi + rad);
        if (blo != blo || bhi != bhi) {
            span_ok = 0;
            break;
        }
        w->lo[k] = vbx_sindex_axis(t, k, blo);
        w->hi[k] = vbx_sindex_axis(t, k, bhi);
        span_ok = w->hi[k] - w->lo[k] < VBX_SINDEX_GRID_SPAN;
    }
    if (span_ok) {
        /* r2 >= fl(r~^2) (1 + u)^3 with r~ = fl(t_hi + Rmax) (see
         * vbx_outside_box); a negative r~ reaches nothing. */
        double r = p[3].hi + t->rmax;
        w->grid = 1;
        w->at[1] = w->lo[1];
        w->at[2] = r < 0.0 ? w->hi[2] + 1 : w->lo[2];
        w->r2 = (r * r) * (1.0 + 0x1p-40);
        /* The rows' gaps along y and z, once per cell instead of once per
         * row (vbx_walk_next combines them: the same operations). */
        for (int a = 0; a < 2; a++)
            for (int i = w->lo[a + 1]; i <= w->hi[a + 1]; i++) {
                double lo = vbx_sindex_lo(t, a + 1, i), hi = vbx_sindex_hi(t, a + 1, i);
                double g = vbx_pos(vbx_max(p[a + 1].lo - hi, lo - p[a + 1].hi));
                w->g2[a][i - w->lo[a + 1]] = g * g;
            }
        return;
    }
    double d2;
    if (!vbx_bvh_skip(&t->node[0], p, &d2))
        w->stack[w->sp++] = 0;
}

/* A walk of the hierarchy (not the grid) that also skips a node where
 * skip(arg, lo, hi, rmax) of its box proves every sphere of it outside the
 * tangent ball of the query's exact point (a far root's power bound,
 * vbx_qf_group_outside). Set after vbx_walk_init; the root node is not
 * asked. Speed only: the nodes left are visited in the same order. */
static inline void vbx_walk_skip(vbx_walk *w,
                                 int (*skip)(const void *, const double *, const double *, double),
                                 const void *arg)
{
    w->skip = skip;
    w->skip_arg = arg;
}

/* Next run of slots [*first, *end); 0 when the walk is over. */
static inline int vbx_walk_next(vbx_walk *w, size_t *first, size_t *end)
{
    const vbx_sindex *t = w->t;
    if (w->grid) {
        const vbx_ia *p = w->p;
        while (w->at[2] <= w->hi[2]) {
            int y = w->at[1], z = w->at[2];
            if (++w->at[1] > w->hi[1]) {
                w->at[1] = w->lo[1];
                w->at[2]++;
            }
            /* The centres of row (y, z) that may reach: with gy~, gz~ the
             * computed gaps from the box to the row (lower bounds of the
             * exact gaps over (1 + u)) and d~ = fl(gy~^2 + gz~^2) (exact
             * gap^2 >= d~ / (1 + u)^4), a centre reaches only if
             * (c_x - q_x)^2 < (t + R)^2 - gap^2 <= r2 - d~ / (1 + u)^4 <=
             * W = fl(fl(r2 - fl(d~ (1 - 2^-40))) (1 + 2^-50)) (the
             * subtraction's rounding, u, is within the factor). W <= 0:
             * none does (fl keeps the sign of a difference). Else the
             * half-width fl(fl(sqrt(W)) (1 + 2^-50)) >= sqrt(W), and the x
             * range pushed out by a step holds them all. NaN: whole row. */
            double W = (w->r2 - (w->g2[0][y - w->lo[1]] + w->g2[1][z - w->lo[2]]) * (1.0 - 0x1p-40)) *
                       (1.0 + 0x1p-50);
            if (W <= 0.0)
                continue;
            int x0 = w->lo[0], x1 = w->hi[0];
            double hw = sqrt(W) * (1.0 + 0x1p-50);
            /* Outward by t->eps instead of a step: inside the grid's range
             * the roundings of p.lo - hw and of the subtraction of eps are
             * below u (|x0| + nc h), far below eps; outside it the cell
             * clamps to the end cell either way (both roundings are
             * monotone). */
            double bl = (p[0].lo - hw) - t->eps[0], bh = (p[0].hi + hw) + t->eps[0];
            if (bl == bl && bh == bh) {
                int a0 = vbx_sindex_axis(t, 0, bl), a1 = vbx_sindex_axis(t, 0, bh);
                x0 = a0 > x0 ? a0 : x0;
                x1 = a1 < x1 ? a1 : x1;
                if (x0 > x1)
                    continue;
            }
            size_t row = ((size_t)z * (size_t)t->nc[1] + (size_t)y) * (size_t)t->nc[0];
            size_t a = t->cell[row + (size_t)x0], b = t->cell[row + (size_t)x1 + 1];
            if (a == b)
                continue;
            *first = a;
            *end = b;
            return 1;
        }
        return 0;
    }
    const vbx_bvh_node *node = t->node;
    while (w->sp) {
        uint32_t i = w->stack[--w->sp];
        const vbx_bvh_node *nd = &node[i];
        if (nd->count) {
            *first = nd->first;
            *end = (size_t)nd->first + nd->count;
            return 1;
        }
        uint32_t a = i + 1, b = nd->first;
        double da, db;
        int sa = vbx_bvh_skip(&node[a], w->p, &da), sb = vbx_bvh_skip(&node[b], w->p, &db);
        if (w->skip) {
            sa = sa || w->skip(w->skip_arg, node[a].lo, node[a].hi, node[a].rmax);
            sb = sb || w->skip(w->skip_arg, node[b].lo, node[b].hi, node[b].rmax);
        }
        /* Nearer child on top of the stack. */
        if (da > db) {
            uint32_t tmp = a;
            a = b;
            b = tmp;
            int ts = sa;
            sa = sb;
            sb = ts;
        }
        if (!sb)
            w->stack[w->sp++] = b;
        if (!sa)
            w->stack[w->sp++] = a;
    }
    return 0;
}

#endif
