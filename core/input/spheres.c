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
        /* The doubles filter: each is the decimal rounded once (to nearest),
         * so one well inside a limit has its decimal inside it too. */
        const double d[3] = {s->x[i], s->y[i], s->z[i]};
        for (int k = 0; k < 3; k++)
            if (!(fabs(d[k]) < 0.999e9) && vb_decimal_cmp(dec_abs(c[k]), coord_limit) > 0)
                return vb_error(ctx, VB_EINPUT_MAGNITUDE, src, s->line[i],
                                "coordinate %.17g exceeds 1e9 in magnitude",
                                k == 0 ? s->x[i] : k == 1 ? s->y[i] : s->z[i]);
        if (!(s->r[i] < 0.999e6) && vb_decimal_cmp(s->er[i], radius_limit) > 0)
            return vb_error(ctx, VB_EINPUT_MAGNITUDE, src, s->line[i],
                            "radius %.17g exceeds 1e6", s->r[i]);
    }
    return VB_OK;
}

/* A sphere by its doubles: identical decimals round to identical doubles,
 * so identical spheres sit in one run of equal keys once sorted. */
typedef struct {
    double v[4];
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
    for (int k = 0; k < 4; k++)
        if (a->v[k] != b->v[k])
            return (a->v[k] > b->v[k]) - (a->v[k] < b->v[k]);
    return (a->idx > b->idx) - (a->idx < b->idx);
}

static int same_key(const dup_key *a, const dup_key *b)
{
    return a->v[0] == b->v[0] && a->v[1] == b->v[1] && a->v[2] == b->v[2] && a->v[3] == b->v[3];
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
        k[i] = (dup_key){{s->x[i], s->y[i], s->z[i], s->r[i]}, i};
    }
    /* A total order (ties by index): one result on any number of threads. */
    if (vb_psort(k, s->n, sizeof *k, dup_key_cmp, vb_threads(0)) != VB_OK) {
        free(k);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    }
    /* Of all identical pairs, name the one met first when reading the file
     * top down: the later sphere with the smallest index. A run of equal
     * doubles (by index) is compared on the decimals; runs are short. */
    size_t first = SIZE_MAX, second = SIZE_MAX;
    for (size_t r0 = 0, r1; r0 < s->n; r0 = r1) {
        for (r1 = r0 + 1; r1 < s->n && same_key(&k[r0], &k[r1]); r1++)
            ;
        for (size_t j = r0 + 1; j < r1; j++) {
            vb_decimal vj[4];
            sphere_values(s, k[j].idx, vj);
            for (size_t i = r0; i < j && k[j].idx < second; i++) {
                vb_decimal vi[4];
                sphere_values(s, k[i].idx, vi);
                if (same_sphere_cmp(vi, vj) == 0) {
                    first = k[i].idx;
                    second = k[j].idx;
                }
            }
        }
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
 * order for each i, so the same marks and counts on any number of threads.
 * The j of a cell are listed once beforehand (contain_all), each j entered
 * into the cells of its box in increasing j. */
typedef struct contain_job {
    const vb_sphere_set *s;
    const center_grid *g;
    size_t *cstart;       /* per grid cell c: its j are entries cstart[c] .. cstart[c + 1] */
    size_t *cj, base, c0; /* the entries of the cells of a run from c0 on, the first
                             (cstart[c0]) at cj[0] */
    size_t *fill;         /* per cell: the next entry to fill */
    size_t *by, *touch;
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

/* The spheres i of grid cell `cell` (contain_job), each tested against the
 * cell's j in increasing order. */
static void contain_cell(void *ctx, size_t k, int tid)
{
    const contain_job *jb = ctx;
    const vb_sphere_set *s = jb->s;
    const center_grid *g = jb->g;
    size_t cell = jb->c0 + k;
    const size_t *cj = jb->cj + (jb->cstart[cell] - jb->base);
    size_t nc = jb->cstart[cell + 1] - jb->cstart[cell];
    for (size_t t = g->start[cell]; t < g->start[cell + 1]; t++) {
        size_t i = g->items[t];
        for (size_t q = 0; q < nc; q++) {
            size_t j = cj[q];
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

/* Most candidate entries listed at a time (32 MB): more cells are done in
 * runs of consecutive cells, each listed by its own pass over the boxes. */
#define CAND_CHUNK ((size_t)4 << 20)

/* Calls fn(jb, j, c) for every sphere j, in increasing j, and every cell c
 * in [c0, c1) of j's box that holds a sphere. */
static void each_box_cell(contain_job *jb, size_t (*box)[6], size_t c0, size_t c1,
                          void (*fn)(contain_job *, size_t, size_t))
{
    const center_grid *g = jb->g;
    for (size_t j = 0; j < jb->s->n; j++) {
        const size_t *b = box[j];
        for (size_t cz = b[2]; cz <= b[5]; cz++)
            for (size_t cy = b[1]; cy <= b[4]; cy++) {
                size_t r = (cz * g->dim[1] + cy) * g->dim[0];
                if (r + b[3] < c0 || r + b[0] >= c1)
                    continue;
                for (size_t cx = b[0]; cx <= b[3]; cx++) {
                    size_t c = r + cx;
                    if (c >= c0 && c < c1 && g->start[c] != g->start[c + 1])
                        fn(jb, j, c);
                }
            }
    }
}

static void count_j(contain_job *jb, size_t j, size_t c)
{
    (void)j;
    jb->cstart[c + 1]++;
}

static void fill_j(contain_job *jb, size_t j, size_t c)
{
    jb->cj[jb->fill[c]++] = j;
}

/* Every cell's spheres against the j whose box holds the cell, listed in
 * increasing j (jb->cstart counts, then jb->cj filled in j order), in runs
 * of cells of at most CAND_CHUNK entries (a cell alone may exceed it).
 * 0, or -1 when out of memory. */
static int contain_all(contain_job *jb, int nt)
{
    const vb_sphere_set *s = jb->s;
    const center_grid *g = jb->g;
    size_t total = g->dim[0] * g->dim[1] * g->dim[2];
    size_t (*box)[6] = malloc(s->n * sizeof *box);
    jb->cstart = calloc(total + 1, sizeof *jb->cstart);
    jb->fill = malloc((total + 1) * sizeof *jb->fill);
    int rc = box && jb->cstart && jb->fill ? 0 : -1;
    for (size_t j = 0; rc == 0 && j < s->n; j++)
        pad_box(s, g, j, box[j]);
    if (rc == 0)
        each_box_cell(jb, box, 0, total, count_j);
    for (size_t c = 0; rc == 0 && c < total; c++)
        jb->cstart[c + 1] += jb->cstart[c];
    for (size_t c0 = 0, c1; rc == 0 && c0 < total; c0 = c1) {
        for (c1 = c0 + 1; c1 < total && jb->cstart[c1 + 1] - jb->cstart[c0] <= CAND_CHUNK; c1++)
            ;
        free(jb->cj);
        if (!(jb->cj = malloc((jb->cstart[c1] - jb->cstart[c0] + 1) * sizeof *jb->cj))) {
            rc = -1;
            break;
        }
        /* cj holds the run's entries from cstart[c0] on. */
        jb->base = jb->cstart[c0];
        for (size_t c = c0; c < c1; c++)
            jb->fill[c] = jb->cstart[c] - jb->base;
        each_box_cell(jb, box, c0, c1, fill_j);
        jb->c0 = c0;
        vb_parallel_for(contain_cell, jb, c1 - c0, nt);
    }
    free(box);
    free(jb->cstart);
    free(jb->fill);
    free(jb->cj);
    return rc;
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
    jb.count = calloc((size_t)nt, sizeof *jb.count);
    for (size_t j = 0; jb.by && jb.touch && j < s->n; j++)
        jb.by[j] = jb.touch[j] = SIZE_MAX;
    if (!jb.by || !jb.touch || !jb.count || grid_build(&g, s) != 0 || contain_all(&jb, nt) != 0) {
        free(jb.by);
        free(jb.touch);
        free(jb.count);
        grid_free(&g);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    }
    vb_stats *st = vb_ctx_stats(ctx);
    for (int t = 0; t < nt; t++) {
        st->filter_calls += jb.count[t].calls;
        st->filter_failures += jb.count[t].failures;
        st->exact_evals += jb.count[t].failures;
    }
    grid_free(&g);
    size_t *by = jb.by, *touch = jb.touch;
    free(jb.count);
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
