/* The HOLE-style pore sweep (vbc_pore.h): the largest empty sphere in each
 * plane normal to the axis, found by a deterministic max-min ascent. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_pore.h"

/* Atoms considered active at most (the nearest ones); more only happen on
 * highly symmetric rings, where any 32 of them decide as well. */
#define MAX_ACTIVE 32

typedef struct {
    const vb_sphere_set *s;
    double p[3];
    int32_t id[MAX_ACTIVE];
    int n;
} active_set;

static void active_add(int32_t atom, void *user)
{
    active_set *A = user;
    if (A->n < MAX_ACTIVE)
        A->id[A->n++] = atom;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Two unit vectors completing u to an orthonormal frame. */
static void plane_frame(const double u[3], double e1[3], double e2[3])
{
    double a[3] = {0.0, 0.0, 0.0};
    int k = fabs(u[0]) <= fabs(u[1]) && fabs(u[0]) <= fabs(u[2]) ? 0 : fabs(u[1]) <= fabs(u[2]) ? 1 : 2;
    a[k] = 1.0;
    double d = dot3(a, u);
    for (int i = 0; i < 3; i++)
        e1[i] = a[i] - d * u[i];
    double n = sqrt(dot3(e1, e1));
    for (int i = 0; i < 3; i++)
        e1[i] /= n;
    e2[0] = u[1] * e1[2] - u[2] * e1[1];
    e2[1] = u[2] * e1[0] - u[0] * e1[2];
    e2[2] = u[0] * e1[1] - u[1] * e1[0];
}

/* The point of the convex hull of g[0..n) (2D) nearest the origin, in *m.
 * Returns 0 when the origin lies in the hull (no ascent direction). */
static int min_norm_point(const double (*g)[2], int n, double m[2])
{
    double best = INFINITY;
    for (int i = 0; i < n; i++)
        for (int j = i; j < n; j++) {
            double q[2] = {g[i][0], g[i][1]};
            if (j > i) {
                double d[2] = {g[j][0] - g[i][0], g[j][1] - g[i][1]};
                double dd = d[0] * d[0] + d[1] * d[1];
                if (dd == 0.0)
                    continue;
                double t = -(q[0] * d[0] + q[1] * d[1]) / dd;
                if (t <= 0.0 || t >= 1.0)
                    continue;
                q[0] += t * d[0];
                q[1] += t * d[1];
            }
            double qq = q[0] * q[0] + q[1] * q[1];
            if (qq >= best)
                continue;
            /* q is the hull's nearest point iff every point lies beyond the
             * line through q normal to q. */
            int ok = 1;
            for (int k = 0; k < n && ok; k++)
                ok = g[k][0] * q[0] + g[k][1] * q[1] >= qq * (1.0 - 1e-12) - 1e-15;
            if (ok) {
                best = qq;
                m[0] = q[0];
                m[1] = q[1];
            }
        }
    return best < INFINITY && best > 1e-20;
}

/* True when some atom of A has its surface within `reach` of q. */
static int blocked_by(const vb_sphere_set *s, const active_set *A, const double q[3], double reach)
{
    for (int k = 0; k < A->n; k++) {
        int32_t i = A->id[k];
        double dx = q[0] - s->x[i], dy = q[1] - s->y[i], dz = q[2] - s->z[i];
        if (sqrt(dx * dx + dy * dy + dz * dz) - s->r[i] <= reach)
            return 1;
    }
    return 0;
}

/* The spheres near the ascent's point: vbc_cells_nearest_near's list. */
#define NEAR_CAP 128
typedef struct {
    int32_t id[NEAR_CAP];
    double dist[NEAR_CAP];
    size_t n;
    int ok; /* complete (else vbc_cells_within answers) */
} near_list;

/* The spheres near a point c0 of the ascent, for queries close to it: the
 * near list of c0 for slack LOCAL_SLACK holds, for any q within
 * (LOCAL_SLACK - eps) / 2 of c0, q's nearest sphere and every sphere within
 * its distance + eps of q (vbc_cells_nearest_among), so the ascent's
 * queries, steps of a fraction of an A, mostly need no walk of the cells. */
#define LOCAL_SLACK 1.1
#define LOCAL_CAP 512
typedef struct {
    double c0[3];
    int32_t id[LOCAL_CAP];
    double dist[LOCAL_CAP];
    size_t n;
    int ok;
} local_set;

/* The clearance at q, and its near list for slack eps (eps <= 0.1). */
static double clearance_near(const vbc_cells *c, const double q[3], double eps, int32_t hint,
                             int32_t *atom, near_list *L, local_set *S)
{
    double R, half = 0.5 * (LOCAL_SLACK - eps) - 1e-6;
    double w[3] = {q[0] - S->c0[0], q[1] - S->c0[1], q[2] - S->c0[2]};
    if (!S->ok || w[0] * w[0] + w[1] * w[1] + w[2] * w[2] > half * half) {
        S->ok = vbc_cells_near_set(c, q, LOCAL_SLACK, hint, &R, atom, S->id, S->dist, LOCAL_CAP,
                                   &S->n) == 0;
        memcpy(S->c0, q, sizeof S->c0);
    }
    L->ok = S->ok && vbc_cells_nearest_among(c, S->id, S->n, q, eps, &R, atom, L->id, L->dist,
                                             NEAR_CAP, &L->n) == 0;
    if (!L->ok)
        L->ok = vbc_cells_nearest_near(c, q, eps, hint, &R, atom, L->id, L->dist, NEAR_CAP, &L->n) == 0;
    return L->ok ? R : vbc_cells_clearance_from(c, q, hint, atom);
}

/* vbc_plane_maximise, and in *went the largest squared distance from the
 * start of a point it tried (the one it compares with travel^2): a run
 * with any travel >= sqrt(*went) takes the very same steps. */
static double ascend(const vbc_cells *c, const double u[3], double travel, double p[3],
                     int32_t *atom, double *went)
{
    const vb_sphere_set *s = vbc_cells_spheres(c);
    double e1[3], e2[3], p0[3] = {p[0], p[1], p[2]};
    plane_frame(u, e1, e2);
    int32_t a;
    double eps = 0.1, step = 0.1;
    /* The near list of p (for eps, which only falls while p stays) answers
     * each step's vbc_cells_within(p, R + eps) as that would: the same
     * atoms in the same order, without a second walk of the cells. */
    near_list lists[2], *here = &lists[0], *there = &lists[1];
    local_set S;
    S.ok = 0;
    double R = clearance_near(c, p, eps, -1, &a, here, &S);
    for (int it = 0; it < 400 && eps >= 1e-7; it++) {
        active_set A = {s, {p[0], p[1], p[2]}, {0}, 0};
        if (here->ok) {
            for (size_t k = 0; k < here->n; k++)
                if (here->dist[k] <= R + eps)
                    active_add(here->id[k], &A);
        } else {
            vbc_cells_within(c, p, R + eps, active_add, &A);
        }
        double g[MAX_ACTIVE][2];
        int n = 0;
        for (int k = 0; k < A.n; k++) {
            int32_t i = A.id[k];
            double d[3] = {p[0] - s->x[i], p[1] - s->y[i], p[2] - s->z[i]};
            double len = sqrt(dot3(d, d));
            if (len == 0.0) { /* on a centre: any direction leads out */
                g[n][0] = 1.0;
                g[n++][1] = 0.0;
                continue;
            }
            g[n][0] = dot3(d, e1) / len;
            g[n++][1] = dot3(d, e2) / len;
        }
        double m[2];
        if (n == 0 || !min_norm_point((const double (*)[2])g, n, m)) {
            eps *= 0.25; /* stationary for this eps: look closer */
            continue;
        }
        double mn = sqrt(m[0] * m[0] + m[1] * m[1]);
        double d[3];
        for (int i = 0; i < 3; i++)
            d[i] = (m[0] * e1[i] + m[1] * e2[i]) / mn;
        /* Backtracking along d: an inactive atom cannot catch up within eps/2. */
        int moved = 0;
        for (double t = fmin(step, fmax(eps, 1e-7)); t >= 1e-8; t *= 0.5) {
            double q[3] = {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]};
            double w[3] = {q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]}, ww = dot3(w, w);
            *went = fmax(*went, ww);
            if (travel > 0.0 && ww > travel * travel)
                continue;
            /* The clearance at q is at most any one atom's distance, taken
             * by the very expression vbc_cells_clearance takes the least of:
             * an active atom within R + 1e-13 of q decides "no step" as the
             * full query would, at a fraction of its cost. */
            if (blocked_by(s, &A, q, R + 1e-13))
                continue;
            int32_t b;
            double Rq = clearance_near(c, q, eps, a, &b, there, &S);
            if (Rq > R + 1e-13) {
                memcpy(p, q, sizeof q);
                R = Rq;
                a = b;
                near_list *was = here; /* the lists swap places, not copied */
                here = there;
                there = was;
                step = fmin(2.0 * t, 1.0);
                moved = 1;
                break;
            }
        }
        if (!moved)
            eps *= 0.25;
    }
    *atom = a;
    return R;
}

double vbc_plane_maximise(const vbc_cells *c, const double u[3], double travel, double p[3],
                          int32_t *atom)
{
    double went = 0.0;
    return ascend(c, u, travel, p, atom, &went);
}

/* The lattice search of vbc_plane_widest: moves p to the widest lattice
 * point (p itself when none is wider), returns its clearance with the
 * nearest atom in *atom, and 1 when p moved. */
static int lattice_best(const vbc_cells *c, const double u[3], double reach, vbc_outside_fn outside,
                        void *user, double p[3], double *Rbest, int32_t *atom);

/* The rest of vbc_plane_widest from the lattice's best point p (moved or
 * not by the lattice, its clearance R): the ascent within reach, kept when
 * it stays inside. */
static double widest_ascent(const vbc_cells *c, const double u[3], double reach,
                            vbc_outside_fn outside, void *user, double p[3], double R,
                            int32_t *atom)
{
    int32_t a;
    double q[3] = {p[0], p[1], p[2]}, went = 0.0;
    double Rq = ascend(c, u, reach, q, &a, &went);
    if (!outside || !outside(user, q)) {
        memcpy(p, q, sizeof q);
        R = Rq;
    } else {
        R = vbc_cells_clearance(c, p, &a); /* the ascent left the molecule: the lattice's best */
    }
    *atom = a;
    return R;
}

double vbc_plane_widest(const vbc_cells *c, const double u[3], double reach, vbc_outside_fn outside,
                        void *user, double p[3], int32_t *atom)
{
    double R;
    lattice_best(c, u, reach, outside, user, p, &R, atom);
    return widest_ascent(c, u, reach, outside, user, p, R, atom);
}

/* The spheres near the lattice's centre (lattice_best) in buckets of
 * their distance from it: bucket b holds those at least `lo` +
 * b LATTICE_BUCKET (the last one: the rest), in any order. A counting
 * sort of a few hundred spheres into 16 buckets: the insertion sort by
 * distance it replaces was about a tenth of the sweep (perf, 1chb). */
#define LATTICE_CAP 512
#define LATTICE_BUCKETS 16
#define LATTICE_BUCKET 0.25
typedef struct {
    int32_t id[LATTICE_CAP];
    double dist[LATTICE_CAP];
    size_t n;
    int ok;
    double lo;                          /* the least distance (the clearance at the centre) */
    size_t first[LATTICE_BUCKETS + 1];  /* bucket b: entries first[b] .. first[b + 1] */
} lattice_near;

static void near_buckets(lattice_near *L, double lo)
{
    int32_t id[LATTICE_CAP];
    double dist[LATTICE_CAP];
    uint8_t at[LATTICE_CAP];
    size_t count[LATTICE_BUCKETS + 1] = {0};
    L->lo = lo;
    for (size_t k = 0; k < L->n; k++) {
        double b = (L->dist[k] - lo) / LATTICE_BUCKET;
        at[k] = (uint8_t)(b <= 0.0 ? 0 : b >= LATTICE_BUCKETS - 1 ? LATTICE_BUCKETS - 1 : (int)b);
        count[at[k] + 1]++;
    }
    for (int b = 0; b < LATTICE_BUCKETS; b++)
        count[b + 1] += count[b];
    memcpy(L->first, count, sizeof L->first);
    for (size_t k = 0; k < L->n; k++) {
        size_t t = count[at[k]]++;
        id[t] = L->id[k];
        dist[t] = L->dist[k];
    }
    memcpy(L->id, id, L->n * sizeof *id);
    memcpy(L->dist, dist, L->n * sizeof *dist);
}

/* The clearance at q, off the list of its centre p (|q - p| <= off, to
 * within rounding): the least distance |q - c| - r, then the lower index,
 * over the listed spheres (whatever order they are met in); a sphere
 * whose distance from p exceeds the best so far by more than off (and a
 * margin far above the roundings) is farther from q than it, so a bucket
 * whose least distance does is skipped, with the rest. */
static double near_min(const vb_sphere_set *s, const lattice_near *L, const double q[3], double off,
                       int32_t *atom)
{
    double best = INFINITY;
    int32_t b = -1;
    off += 1e-9;
    for (int k = 0; k < LATTICE_BUCKETS; k++) {
        /* The bucket's spheres are at least this far from p (its bound
         * less a margin for the rounding of their bucket). */
        if (L->lo + k * LATTICE_BUCKET - 1e-9 - off > best)
            break;
        for (size_t t = L->first[k]; t < L->first[k + 1]; t++) {
            int32_t i = L->id[t];
            double dx = q[0] - s->x[i], dy = q[1] - s->y[i], dz = q[2] - s->z[i];
            double d = sqrt(dx * dx + dy * dy + dz * dz) - s->r[i];
            if (b < 0 || d < best || (d == best && i < b)) {
                best = d;
                b = i;
            }
        }
    }
    *atom = b;
    return best;
}

static int lattice_best(const vbc_cells *c, const double u[3], double reach, vbc_outside_fn outside,
                        void *user, double p[3], double *Rbest, int32_t *atom)
{
    double e1[3], e2[3], best[3] = {p[0], p[1], p[2]};
    plane_frame(u, e1, e2);
    const vb_sphere_set *s = vbc_cells_spheres(c);
    int32_t a, best_atom;
    /* The spheres within R + 2 reach + 0.1 of p, nearer first: a lattice
     * point q is within reach of p, so its nearest sphere (and any tied
     * with it) lies within R(q) + |q - p| <= R + 2 reach of p, and a sphere
     * listed farther than R(q) + |q - p| from p is farther than R(q) from
     * q: near_min's answer is vbc_cells_clearance's (the least distance,
     * then index, by the same expression). A list over its cap, or a
     * lattice wider than the planes' (a subunit's start, whose list would
     * fill the cap): the cells answer. */
    lattice_near L;
    double R;
    L.ok = reach <= VBC_PLANE_LOOK &&
           vbc_cells_near_set(c, p, 2.0 * reach + 0.1, -1, &R, &a, L.id, L.dist, LATTICE_CAP,
                              &L.n) == 0;
    if (L.ok)
        near_buckets(&L, R);
    else
        R = vbc_cells_clearance(c, p, &a);
    int moved = 0;
    best_atom = a;
    /* The nearest atom of the last point queried (0.5 A away, mostly): its
     * distance, by the very expression vbc_cells_clearance takes the least
     * of, bounds the clearance at the next point from above, so a point it
     * puts at or below R cannot win (the strict test below) and needs no
     * query. The same points win as with every point queried. */
    active_set hint = {s, {0.0, 0.0, 0.0}, {a}, a >= 0};
    /* The nearest atoms of the last RECENT points queried: each bounds the
     * clearance from above as the last one does. */
    enum { RECENT = 8 };
    int32_t last = a;
    int put = hint.n;
    long n = (long)floor(reach / 0.5);
    for (long i = -n; i <= n; i++)
        for (long j = -n; j <= n; j++) {
            double di = 0.5 * (double)i, dj = 0.5 * (double)j;
            if (di * di + dj * dj > reach * reach)
                continue;
            double q[3];
            for (int k = 0; k < 3; k++)
                q[k] = p[k] + di * e1[k] + dj * e2[k];
            if (outside && outside(user, q))
                continue;
            if (blocked_by(s, &hint, q, R))
                continue;
            double Rq = L.ok ? near_min(s, &L, q, sqrt(di * di + dj * dj), &a)
                             : vbc_cells_clearance_from(c, q, last, &a);
            last = a;
            if (a >= 0) {
                int k = 0;
                while (k < hint.n && hint.id[k] != a)
                    k++;
                if (k == hint.n) { /* a new one takes the oldest place */
                    hint.id[put % RECENT] = a;
                    put++;
                    hint.n = put < RECENT ? put : RECENT;
                }
            }
            if (Rq > R) { /* strict: the first of equals (in scan order) stays */
                R = Rq;
                best_atom = a;
                moved = 1;
                memcpy(best, q, sizeof q);
            }
        }
    memcpy(p, best, sizeof best);
    *Rbest = R;
    *atom = best_atom;
    return moved;
}

void vbc_pore_free(vbc_pore *p)
{
    free(p->pts);
    memset(p, 0, sizeof *p);
}

void vbc_pore_conductance(vbc_pore *p, double rho)
{
    const double pi = 3.14159265358979323846;
    p->F = 0.0;
    p->g_macro_pS = 0.0;
    if (p->n < 2)
        return;
    for (size_t i = 0; i < p->n; i++) {
        double r = p->pts[i].r;
        if (!(r > 0.0)) {
            p->F = INFINITY;
            return;
        }
        double lo = i > 0 ? p->pts[i].s - p->pts[i - 1].s : p->pts[1].s - p->pts[0].s;
        double hi = i + 1 < p->n ? p->pts[i + 1].s - p->pts[i].s : lo;
        if (i == 0)
            lo = hi;
        p->F += 0.5 * (lo + hi) / (pi * r * r);
    }
    p->g_macro_pS = 100.0 / (rho * p->F);
}

/* One plane of the sweep: the local ascent from p, and the ascent from the
 * best point of a lattice around p (VBC_PLANE_LOOK A): the plane can hold
 * several local maxima, and the previous plane's centre may sit below a
 * lower one (HOLE's Monte Carlo search looks around too). The wider wins,
 * the plain ascent on ties. */
static double plane_best(const vbc_cells *c, const double u[3], vbc_outside_fn outside, void *user,
                         double p[3], int32_t *atom)
{
    double q[3] = {p[0], p[1], p[2]}, went = 0.0, rq;
    int32_t b;
    double r = ascend(c, u, 0.0, p, atom, &went);
    /* When no lattice point beats the start and the plain ascent tried no
     * point farther than VBC_PLANE_LOOK from it, the lattice's ascent (from
     * the same start, within that reach) would take the very same steps to
     * the same r: not wider, so the plain ascent stands. */
    if (!lattice_best(c, u, VBC_PLANE_LOOK, outside, user, q, &rq, &b) &&
        went <= VBC_PLANE_LOOK * VBC_PLANE_LOOK)
        return r;
    rq = widest_ascent(c, u, VBC_PLANE_LOOK, outside, user, q, rq, &b);
    if (rq > r + 1e-9 && !(outside && outside(user, q))) {
        memcpy(p, q, sizeof q);
        *atom = b;
        return rq;
    }
    return r;
}

/* Appends a point; returns -1 when out of memory. */
static int push(vbc_pore_point **v, size_t *n, size_t *cap, const vbc_pore_point *q)
{
    if (VB_ARRAY_FIT(*v, *cap, *n + 1, 256) != VB_OK)
        return -1;
    (*v)[(*n)++] = *q;
    return 0;
}

/* One side of the sweep from the start: planes at +-step, +-2 step, ...
 * along u (sign), each from the previous plane's centre. The two sides
 * depend on the start alone, so they run at once (vb_run_jobs); each fills
 * its own points. */
typedef struct {
    const vbc_cells *c;
    const double *u, *start;
    const vbc_pore_options *opt;
    vbc_outside_fn outside;
    void *user;
    double half, sign;
    double floor;           /* give up at a radius at or below this */
    atomic_int *given_up;   /* shared by the two sides */
    vbc_pore_point *pts;
    size_t n, cap;
    int open, failed;
} sweep_side;

static void *sweep_side_run(void *arg)
{
    sweep_side *S = arg;
    const double *u = S->u;
    double p[3] = {S->start[0], S->start[1], S->start[2]};
    int32_t atom;
    S->open = S->outside && S->outside(S->user, p);
    for (long k = 1; !S->open && k * S->opt->step <= S->half; k++) {
        if (atomic_load(S->given_up))
            break;
        for (int i = 0; i < 3; i++)
            p[i] += S->sign * S->opt->step * u[i];
        double r = plane_best(S->c, u, S->outside, S->user, p, &atom);
        if (r <= S->floor) {
            atomic_store(S->given_up, 1);
            break;
        }
        vbc_pore_point q = {dot3(p, u), p[0], p[1], p[2], r, atom};
        if (push(&S->pts, &S->n, &S->cap, &q) != 0) {
            S->failed = 1;
            break;
        }
        if (S->outside && S->outside(S->user, p))
            S->open = 1;
        else if (S->opt->end_radius > 0.0 && r > S->opt->end_radius)
            break;
    }
    return NULL;
}

int vbc_pore_sweep(vb_ctx *ctx, const vbc_cells *c, const vb_sphere_set *s, const vbc_axis *ax,
                   const vbc_pore_options *opt, vbc_outside_fn outside, void *user, vbc_pore *out)
{
    return vbc_pore_sweep_above(ctx, c, s, ax, opt, outside, user, -INFINITY, out);
}

int vbc_pore_sweep_above(vb_ctx *ctx, const vbc_cells *c, const vb_sphere_set *s,
                         const vbc_axis *ax, const vbc_pore_options *opt, vbc_outside_fn outside,
                         void *user, double floor, vbc_pore *out)
{
    memset(out, 0, sizeof *out);
    double un = sqrt(dot3(ax->u, ax->u));
    if (!(un > 0.0) || !isfinite(un) || !(opt->step > 0.0))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "pore sweep: axis of length %g, step %g", un,
                        opt->step);
    out->axis = *ax;
    double u[3] = {ax->u[0] / un, ax->u[1] / un, ax->u[2] / un};
    memcpy(out->axis.u, u, sizeof u);
    double half = opt->max_half;
    if (!(half > 0.0)) {
        /* The molecule's extent along the axis bounds either side. */
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < s->n; i++) {
            double v = s->x[i] * u[0] + s->y[i] * u[1] + s->z[i] * u[2];
            lo = fmin(lo, v - s->r[i]);
            hi = fmax(hi, v + s->r[i]);
        }
        double s0 = dot3(ax->c, u);
        half = fmax(fabs(hi - s0), fabs(s0 - lo)) + 2.0;
    }
    double start[3] = {ax->c[0], ax->c[1], ax->c[2]};
    int32_t atom;
    double r0 = plane_best(c, u, outside, user, start, &atom);
    vbc_pore_point q0 = {dot3(start, u), start[0], start[1], start[2], r0, atom};
    if (r0 <= floor) { /* given up: no wider than floor */
        memset(out, 0, sizeof *out);
        return VB_OK;
    }
    int rc = VB_OK;
    atomic_int given_up;
    atomic_init(&given_up, 0);
    sweep_side side[2];
    for (int dir = 0; dir < 2; dir++)
        side[dir] = (sweep_side){c, u, start, opt, outside, user, half, dir == 0 ? 1.0 : -1.0,
                                 floor, &given_up, NULL, 0, 0, 0, 0};
    if (vb_threads(0) > 1)
        vb_run_jobs(sweep_side_run, side, sizeof *side, 2);
    else
        for (int dir = 0; dir < 2; dir++)
            sweep_side_run(&side[dir]);
    if (side[0].failed || side[1].failed)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "pore profile");
    if (rc == VB_OK && atomic_load(&given_up)) {
        free(side[0].pts);
        free(side[1].pts);
        memset(out, 0, sizeof *out);
        return VB_OK;
    }
    out->open_hi = side[0].open;
    out->open_lo = side[1].open;
    vbc_pore_point *sidep[2] = {side[0].pts, side[1].pts};
    size_t ns[2] = {side[0].n, side[1].n};
    if (rc == VB_OK) {
        out->n = ns[0] + ns[1] + 1;
        out->pts = malloc(out->n * sizeof *out->pts);
        if (!out->pts)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "pore profile");
    }
    if (rc == VB_OK) {
        size_t t = 0;
        for (size_t k = ns[1]; k > 0; k--)
            out->pts[t++] = sidep[1][k - 1];
        out->pts[t++] = q0;
        for (size_t k = 0; k < ns[0]; k++)
            out->pts[t++] = sidep[0][k];
        for (size_t k = 1; k < out->n; k++)
            if (out->pts[k].r < out->pts[out->min_at].r)
                out->min_at = k;
        vbc_pore_conductance(out, VBC_RHO_KCL);
    }
    free(sidep[0]);
    free(sidep[1]);
    if (rc != VB_OK)
        vbc_pore_free(out);
    return rc;
}
