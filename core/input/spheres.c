/* Validation of a sphere set as Voronoi input: per-sphere sanity, exact
 * duplicates (sort, O(n log n)) and contained spheres (uniform grid, then a
 * filtered exact predicate). */
#include "vb_spheres.h"
#include "vb_decimal_mpz.h"
#include "vb_diag.h"
#include "vbi_input.h"
#include "vb_parallel.h"

#include <float.h>
#include <gmp.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Beyond these the input is a unit mistake or garbage, and the exact
 * arithmetic downstream would pay for digits nobody meant. */
static const vb_decimal coord_limit = {1, 9};  /* |coordinate| <= 1e9 */
static const vb_decimal radius_limit = {1, 6}; /* radius <= 1e6 */
/* How many contained spheres are named one by one before a summary line. */
#define VBI_CONTAINED_SHOWN 10

static vb_decimal dec_abs(vb_decimal d)
{
    if (d.mant < 0)
        d.mant = -d.mant;
    return d;
}

static int check_values(vb_ctx *ctx, const vb_sphere_set *s)
{
    const char *src = s->source ? s->source : "<spheres>";
    for (size_t i = 0; i < s->n; i++) {
        const vb_decimal c[3] = {s->ex[i], s->ey[i], s->ez[i]};
        if (s->er[i].mant < 0 || (s->er[i].mant == 0 && !s->allows_zero_radius))
            return vb_error(ctx, VB_EINPUT_RADIUS, src, s->line[i],
                            "radius %.17g is not positive%s", s->r[i],
                            s->er[i].mant == 0 ? " (--zero-radius point|drop accepts it)" : "");
        for (int k = 0; k < 3; k++)
            if (vb_decimal_cmp(dec_abs(c[k]), coord_limit) > 0)
                return vb_error(ctx, VB_EINPUT_MAGNITUDE, src, s->line[i],
                                "coordinate %.17g exceeds 1e9 in magnitude",
                                k == 0 ? s->x[i] : k == 1 ? s->y[i] : s->z[i]);
        if (vb_decimal_cmp(s->er[i], radius_limit) > 0)
            return vb_error(ctx, VB_EINPUT_MAGNITUDE, src, s->line[i],
                            "radius %.17g exceeds 1e6", s->r[i]);
    }
    return VB_OK;
}

typedef struct {
    vb_decimal v[4];
    size_t idx;
} dup_key;

/* Order of two spheres by the values of x, y, z, r (never by the bytes of
 * vb_decimal: its padding is not set by the readers, and "1.52" and
 * "1.520" are one value). */
static int same_sphere_cmp(const vb_decimal a[4], const vb_decimal b[4])
{
    for (int k = 0; k < 4; k++) {
        int c = vb_decimal_cmp(a[k], b[k]);
        if (c)
            return c;
    }
    return 0;
}

static int dup_key_cmp(const void *pa, const void *pb)
{
    const dup_key *a = pa, *b = pb;
    int c = same_sphere_cmp(a->v, b->v);
    return c ? c : (a->idx > b->idx) - (a->idx < b->idx);
}

static void sphere_values(const vb_sphere_set *s, size_t i, vb_decimal v[4])
{
    v[0] = s->ex[i];
    v[1] = s->ey[i];
    v[2] = s->ez[i];
    v[3] = s->er[i];
}

static int check_duplicates(vb_ctx *ctx, const vb_sphere_set *s)
{
    dup_key *k = malloc(s->n * sizeof *k);
    if (!k)
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    for (size_t i = 0; i < s->n; i++) {
        sphere_values(s, i, k[i].v);
        k[i].idx = i;
    }
    /* A total order (ties by index): one result on any number of threads. */
    if (vb_psort(k, s->n, sizeof *k, dup_key_cmp, vb_threads(0)) != VB_OK) {
        free(k);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    }
    /* Of all identical pairs, name the one met first when reading the file
     * top down: the later sphere with the smallest index. */
    size_t first = SIZE_MAX, second = SIZE_MAX;
    for (size_t i = 1; i < s->n; i++)
        if (same_sphere_cmp(k[i - 1].v, k[i].v) == 0 && k[i].idx < second) {
            first = k[i - 1].idx;
            second = k[i].idx;
        }
    free(k);
    if (second == SIZE_MAX)
        return VB_OK;
    /* Several copies: the earliest copy of the same sphere is the partner. */
    vb_decimal want[4];
    sphere_values(s, second, want);
    for (size_t i = 0; i < first; i++) {
        vb_decimal v[4];
        sphere_values(s, i, v);
        if (same_sphere_cmp(v, want) == 0) {
            first = i;
            break;
        }
    }
    return vb_error(ctx, VB_EINPUT_DUPLICATE, s->source, s->line[second],
                    "sphere %zu is identical to sphere %zu at line %ld", second, first,
                    s->line[first]);
}

/* Exact sign of (Rj - Ri)^2 - |ci - cj|^2 on the decimals. */
static int contained_exact(const vb_sphere_set *s, size_t i, size_t j)
{
    const vb_decimal v[8] = {s->ex[i], s->ey[i], s->ez[i], s->er[i],
                             s->ex[j], s->ey[j], s->ez[j], s->er[j]};
    int32_t emin = v[0].exp10;
    for (int k = 1; k < 8; k++)
        if (v[k].exp10 < emin)
            emin = v[k].exp10;
    mpz_t a, b, t, acc;
    mpz_inits(a, b, t, acc, NULL);
    for (int k = 0; k < 4; k++) {
        vb_decimal_to_mpz(a, v[k], emin, t);
        vb_decimal_to_mpz(b, v[k + 4], emin, t);
        mpz_sub(a, a, b);
        mpz_mul(a, a, a);
        if (k == 3)
            mpz_sub(acc, a, acc);
        else
            mpz_add(acc, acc, a);
    }
    int sign = mpz_sgn(acc);
    mpz_clears(a, b, t, acc, NULL);
    return sign;
}

/* Where sphere i (radius strictly below j's) lies against sphere j:
 * NEST_INSIDE when |ci-cj| + Ri < Rj (its cell is empty), NEST_TANGENT when
 * |ci-cj| + Ri = Rj exactly (internally tangent: its cell is a point, a
 * segment or a ray on the line of the centres, whose end can be a Voronoi
 * vertex, so the sphere stays in the diagram), NEST_APART otherwise.
 *
 * Filter: e = (rj-ri)^2 - (dx^2+dy^2+dz^2) in double. Each input double is
 * within u = 2^-53 relative of its decimal; a difference t = p - q then has
 * |t^ - t| <= (2u + u^2)(|p|+|q|) =: delta, its square is off by at most
 * delta(2T + delta) + u(T + delta)^2 <= 5.1 u T^2 with T = |p|+|q|, and the
 * three sums add at most 3u * S where S = sum of the four T^2. So
 * |e^ - e| <= 8.2 u S (+ underflow, a few 2^-1074); we take 16 u S + 1e-290. */
enum { NEST_APART = 0, NEST_INSIDE = 1, NEST_TANGENT = 2 };

/* The counts of nesting's evaluations (a thread's, added to the stats). */
typedef struct nest_count {
    uint64_t calls, failures;
} nest_count;

static int nesting(nest_count *st, const vb_sphere_set *s, size_t i, size_t j)
{
    st->calls++;
    double dx = s->x[i] - s->x[j], dy = s->y[i] - s->y[j], dz = s->z[i] - s->z[j];
    double dr = s->r[j] - s->r[i];
    double e = dr * dr - (dx * dx + dy * dy + dz * dz);
    double tx = fabs(s->x[i]) + fabs(s->x[j]), ty = fabs(s->y[i]) + fabs(s->y[j]);
    double tz = fabs(s->z[i]) + fabs(s->z[j]), tr = s->r[i] + s->r[j];
    double bound = 16.0 * (DBL_EPSILON / 2) * (tx * tx + ty * ty + tz * tz + tr * tr) + 1e-290;
    if (e > bound)
        return NEST_INSIDE;
    if (e < -bound)
        return NEST_APART;
    st->failures++;
    int sg = contained_exact(s, i, j);
    return sg > 0 ? NEST_INSIDE : sg == 0 ? NEST_TANGENT : NEST_APART;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Uniform grid over the centres, cells in CSR form. */
typedef struct {
    double min[3], h;
    size_t dim[3];
    size_t *start; /* dim0*dim1*dim2 + 1 */
    size_t *items;
} center_grid;

static size_t cell_coord(double v, double min, double h, size_t dim)
{
    double c = floor((v - min) / h);
    if (!(c > 0))
        return 0;
    if (c >= (double)dim)
        return dim - 1;
    return (size_t)c;
}

static int grid_build(center_grid *g, const vb_sphere_set *s)
{
    const double *c[3] = {s->x, s->y, s->z};
    double max[3];
    for (int k = 0; k < 3; k++) {
        g->min[k] = max[k] = c[k][0];
        for (size_t i = 1; i < s->n; i++) {
            if (c[k][i] < g->min[k])
                g->min[k] = c[k][i];
            if (c[k][i] > max[k])
                max[k] = c[k][i];
        }
    }
    /* Cell edge: an atom diameter, so a typical sphere scans 27 cells; grown
     * until the grid has at most ~4 cells per sphere. */
    double *rs = malloc(s->n * sizeof *rs);
    if (!rs)
        return -1;
    memcpy(rs, s->r, s->n * sizeof *rs);
    qsort(rs, s->n, sizeof *rs, cmp_double);
    g->h = 2.0 * rs[s->n / 2];
    free(rs);
    /* Radius-0 points (PQR polar hydrogens) can make the median 0: start
     * from a unit edge, which the loop below grows as needed. */
    if (!(g->h > 0))
        g->h = 1.0;
    size_t limit = 4 * s->n + 64;
    for (;;) {
        double cells = 1;
        for (int k = 0; k < 3; k++)
            cells *= floor((max[k] - g->min[k]) / g->h) + 1;
        if (cells <= (double)limit)
            break;
        g->h *= 2;
    }
    size_t total = 1;
    for (int k = 0; k < 3; k++) {
        g->dim[k] = (size_t)floor((max[k] - g->min[k]) / g->h) + 1;
        total *= g->dim[k];
    }
    g->start = calloc(total + 1, sizeof *g->start);
    g->items = malloc(s->n * sizeof *g->items);
    size_t *cell = malloc(s->n * sizeof *cell);
    if (!g->start || !g->items || !cell) {
        free(cell);
        return -1;
    }
    for (size_t i = 0; i < s->n; i++) {
        size_t cx = cell_coord(s->x[i], g->min[0], g->h, g->dim[0]);
        size_t cy = cell_coord(s->y[i], g->min[1], g->h, g->dim[1]);
        size_t cz = cell_coord(s->z[i], g->min[2], g->h, g->dim[2]);
        cell[i] = (cz * g->dim[1] + cy) * g->dim[0] + cx;
        g->start[cell[i] + 1]++;
    }
    for (size_t k = 0; k < total; k++)
        g->start[k + 1] += g->start[k];
    /* Filling backwards moves start[c + 1] down to the first item of cell c;
     * one shift makes start[c] the first item of cell c again. */
    for (size_t i = s->n; i-- > 0;)
        g->items[--g->start[cell[i] + 1]] = i;
    memmove(g->start, g->start + 1, total * sizeof *g->start);
    g->start[total] = s->n;
    free(cell);
    return 0;
}

static void grid_free(center_grid *g)
{
    free(g->start);
    free(g->items);
}

/* Warns W701/W722 for the first VBI_CONTAINED_SHOWN spheres marked in
 * `by` (the sphere each lies in or touches from inside), then W702/W723
 * with the count. */
static void warn_nested(vb_ctx *ctx, const vb_sphere_set *s, const size_t *by, int tangent)
{
    size_t count = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (by[i] == SIZE_MAX)
            continue;
        if (count++ >= VBI_CONTAINED_SHOWN)
            continue;
        if (tangent)
            vb_warn(ctx, VB_W_TANGENT_INSIDE, s->source, s->line[i],
                    "sphere %zu touches sphere %zu (line %ld) from inside: its cell is a point or "
                    "a segment on the line of their centres, kept in the diagram",
                    i, by[i], s->line[by[i]]);
        else
            vb_warn(ctx, VB_W_CONTAINED, s->source, s->line[i],
                    "sphere %zu lies inside sphere %zu (line %ld): its cell is empty", i, by[i],
                    s->line[by[i]]);
    }
    if (count > VBI_CONTAINED_SHOWN) {
        if (tangent)
            vb_warn(ctx, VB_W_TANGENT_INSIDE_COUNT, s->source, 0,
                    "%zu spheres in all touch a larger sphere from inside", count);
        else
            vb_warn(ctx, VB_W_CONTAINED_COUNT, s->source, 0,
                    "%zu spheres in all lie inside another sphere", count);
    }
}

/* The search of find_contained. Its order is that of a scan over the
 * spheres j (each testing the spheres i in the grid cells within its pad,
 * pad_box) that skips an i once it is found inside: i is tested against
 * the j whose cells hold i's cell, in increasing j, up to the first that
 * holds it. Done per i (contain_cell) it is the same tests in the same
 * order for each i, so the same marks and counts on any number of threads. */
typedef struct contain_job {
    const vb_sphere_set *s;
    const center_grid *g;
    size_t (*box)[6];     /* per sphere j: its cells' lo[3], hi[3] */
    size_t span[3];       /* most cells from a j's own cell to an end of its box */
    size_t *by, *touch;
    struct cand {
        size_t *j, cap;
        int nomem;
    } *cand;              /* per thread: the candidates of its sphere i */
    nest_count *count;    /* per thread */
} contain_job;

/* The cells of sphere j's search: its centre padded by the rounding of
 * the doubles against their decimals, so no centre within Rj is missed;
 * the predicate itself decides exactly. */
static void pad_box(const vb_sphere_set *s, const center_grid *g, size_t j, size_t box[6])
{
    const double c[3] = {s->x[j], s->y[j], s->z[j]};
    for (int k = 0; k < 3; k++) {
        double pad = s->r[j] + 1e-9 * (2 * fabs(c[k]) + 2 * s->r[j]) + 1e-300;
        box[k] = cell_coord(c[k] - pad, g->min[k], g->h, g->dim[k]);
        box[3 + k] = cell_coord(c[k] + pad, g->min[k], g->h, g->dim[k]);
    }
}

/* The spheres i of grid cell `cell` (contain_job): the j whose boxes hold
 * the cell, gathered once and put in increasing order, then each i's
 * tests in that order. */
static void contain_cell(void *ctx, size_t cell, int tid)
{
    const contain_job *jb = ctx;
    const vb_sphere_set *s = jb->s;
    const center_grid *g = jb->g;
    if (g->start[cell] == g->start[cell + 1])
        return;
    const size_t ci[3] = {cell % g->dim[0], cell / g->dim[0] % g->dim[1],
                          cell / (g->dim[0] * g->dim[1])};
    size_t lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = ci[k] > jb->span[k] ? ci[k] - jb->span[k] : 0;
        hi[k] = ci[k] + jb->span[k] < g->dim[k] ? ci[k] + jb->span[k] : g->dim[k] - 1;
    }
    struct cand *cd = jb->cand + tid;
    size_t nc = 0;
    for (size_t cz = lo[2]; cz <= hi[2]; cz++)
        for (size_t cy = lo[1]; cy <= hi[1]; cy++)
            for (size_t cx = lo[0]; cx <= hi[0]; cx++) {
                size_t other = (cz * g->dim[1] + cy) * g->dim[0] + cx;
                for (size_t t = g->start[other]; t < g->start[other + 1]; t++) {
                    size_t j = g->items[t];
                    const size_t *b = jb->box[j];
                    if (!(b[0] <= ci[0] && ci[0] <= b[3] && b[1] <= ci[1] && ci[1] <= b[4] &&
                          b[2] <= ci[2] && ci[2] <= b[5]))
                        continue;
                    if (nc == cd->cap) {
                        size_t cap = cd->cap ? 2 * cd->cap : 256;
                        size_t *p = realloc(cd->j, cap * sizeof *p);
                        if (!p) {
                            cd->nomem = 1;
                            return;
                        }
                        cd->j = p;
                        cd->cap = cap;
                    }
                    /* In increasing order as they come (few per cell). */
                    size_t q = nc++;
                    for (; q > 0 && cd->j[q - 1] > j; q--)
                        cd->j[q] = cd->j[q - 1];
                    cd->j[q] = j;
                }
            }
    for (size_t t = g->start[cell]; t < g->start[cell + 1]; t++) {
        size_t i = g->items[t];
        for (size_t q = 0; q < nc; q++) {
            size_t j = cd->j[q];
            /* Equal radii would need equal centres: a duplicate, refused
             * before we get here. A smaller double radius has a smaller
             * decimal (rounding keeps the order). */
            if (s->r[j] < s->r[i] || vb_decimal_cmp(s->er[i], s->er[j]) >= 0)
                continue;
            int nest = nesting(jb->count + tid, s, i, j);
            if (nest == NEST_INSIDE) {
                jb->by[i] = j;
                break;
            }
            if (nest == NEST_TANGENT && jb->touch[i] == SIZE_MAX)
                jb->touch[i] = j;
        }
    }
}

/* Marks contained spheres (strictly inside another: empty cell) and, when
 * warn, warns W701 (each, up to a limit) and W702 (the total). A sphere that only
 * touches a larger one from inside is not contained: its cell is a point or
 * a segment that can end at a Voronoi vertex (W722, W723). Decided exactly:
 * a sphere strictly inside any sphere is contained, whatever it touches.
 * The cells of the grid are searched on the host threads (contain_cell). */
static int find_contained(vb_ctx *ctx, vb_sphere_set *s, int warn)
{
    center_grid g;
    memset(&g, 0, sizeof g);
    int nt = vb_threads(0);
    contain_job jb;
    memset(&jb, 0, sizeof jb);
    jb.s = s;
    jb.g = &g;
    jb.by = malloc(s->n * sizeof *jb.by);
    jb.touch = malloc(s->n * sizeof *jb.touch);
    jb.box = malloc(s->n * sizeof *jb.box);
    jb.cand = calloc((size_t)nt, sizeof *jb.cand);
    jb.count = calloc((size_t)nt, sizeof *jb.count);
    if (!jb.by || !jb.touch || !jb.box || !jb.cand || !jb.count || grid_build(&g, s) != 0) {
        free(jb.by);
        free(jb.touch);
        free(jb.box);
        free(jb.cand);
        free(jb.count);
        grid_free(&g);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    }
    for (size_t j = 0; j < s->n; j++) {
        jb.by[j] = jb.touch[j] = SIZE_MAX;
        pad_box(s, &g, j, jb.box[j]);
        for (int k = 0; k < 3; k++) {
            size_t cj = cell_coord(k == 0 ? s->x[j] : k == 1 ? s->y[j] : s->z[j], g.min[k], g.h,
                                   g.dim[k]);
            size_t d = cj - jb.box[j][k] > jb.box[j][3 + k] - cj ? cj - jb.box[j][k]
                                                                 : jb.box[j][3 + k] - cj;
            jb.span[k] = d > jb.span[k] ? d : jb.span[k];
        }
    }
    vb_parallel_for(contain_cell, &jb, g.dim[0] * g.dim[1] * g.dim[2], nt);
    int nomem = 0;
    vb_stats *st = vb_ctx_stats(ctx);
    for (int t = 0; t < nt; t++) {
        nomem |= jb.cand[t].nomem;
        free(jb.cand[t].j);
        st->filter_calls += jb.count[t].calls;
        st->filter_failures += jb.count[t].failures;
        st->exact_evals += jb.count[t].failures;
    }
    grid_free(&g);
    size_t *by = jb.by, *touch = jb.touch;
    free(jb.box);
    free(jb.cand);
    free(jb.count);
    if (nomem) {
        free(by);
        free(touch);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    }
    for (size_t i = 0; i < s->n; i++) {
        if (by[i] != SIZE_MAX) {
            s->contained[i] = 1;
            touch[i] = SIZE_MAX;
        }
    }
    if (warn) {
        warn_nested(ctx, s, by, 0);
        warn_nested(ctx, s, touch, 1);
    }
    free(by);
    free(touch);
    return VB_OK;
}

int vb_spheres_validate(vb_ctx *ctx, vb_sphere_set *s, size_t min_count)
{
    return vbi_spheres_validate(ctx, s, min_count, 1);
}

int vbi_spheres_validate(vb_ctx *ctx, vb_sphere_set *s, size_t min_count, int warn_contained)
{
    if (s->n == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, s->source, 0, "no spheres in the input");
    int rc = check_values(ctx, s);
    if (rc != VB_OK)
        return rc;
    if (s->n < min_count)
        return vb_error(ctx, VB_EINPUT_TOOFEW, s->source, 0,
                        "%zu sphere%s, at least %zu needed", s->n, s->n == 1 ? "" : "s",
                        min_count);
    rc = check_duplicates(ctx, s);
    if (rc != VB_OK)
        return rc;
    free(s->contained);
    s->contained = calloc(s->n, sizeof *s->contained);
    if (!s->contained)
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    return find_contained(ctx, s, warn_contained);
}
