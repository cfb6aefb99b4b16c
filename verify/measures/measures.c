/* Cell measures of a sphere set (vb_measures.h): neighbours within reach,
 * one integration per atom (cell_patches.c) on a thread of its own, and the
 * two sides of every contact met. */
#include <gmp.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_decimal_mpz.h"
#include "vb_diag.h"
#include "vb_measures.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"
#include "vbm_cell.h"
#include "vbm_piece.h"

const char *const vb_cell_stage_name[VB_CELL_NSTAGE] = {"neighbours", "caps", "arrangement",
                                                        "integrals", "patches"};

void vb_measure_defaults(vb_measure_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->probe = 1.4;
    opt->tolerance = VB_MEASURES_TOLERANCE;
}

int vb_measure_options_check(vb_ctx *ctx, const vb_measure_options *opt)
{
    if (!(opt->probe >= 0.0) || !isfinite(opt->probe))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--probe %g: must be >= 0", opt->probe);
    if (!(opt->tolerance > 0.0 && opt->tolerance < 1.0))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--tolerance %g: must lie in (0, 1)",
                        opt->tolerance);
    if (opt->max_patches && opt->max_patches < VB_MEASURES_MIN_PATCHES)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--max-patches needs an integer >= %d",
                        VB_MEASURES_MIN_PATCHES);
    if (opt->threads < 0 || opt->threads > VB_MAX_THREADS)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--threads needs 1..%d", VB_MAX_THREADS);
    return VB_OK;
}

void vb_cell_measures_free(vb_cell_measures *m)
{
    free(m->vol_lo);
    free(m->vol_hi);
    free(m->sas_lo);
    free(m->sas_hi);
    free(m->empty);
    free(m->loose);
    free(m->contacts);
    memset(m, 0, sizeof *m);
}

/* The nearest double of an exact decimal is within half an ulp: one step
 * each way encloses it. */
static vbx_ia widen(double x)
{
    vbx_ia r = {vbx_pred(x), vbx_succ(x)};
    return r;
}

/* An enclosure of b - a for exact decimals a, b (their nearest doubles da,
 * db): exactly 0 when they are equal (equal radii make the face a plane and
 * the Voronoi edges of equal triples lines: decided here from the input,
 * not from doubles), else the exact difference rounded to nearest and
 * widened by one step each way when it fits 18 digits, else the difference
 * of the widened doubles. */
static int scale10(int64_t *m, int32_t shift)
{
    for (; shift > 0; shift--) {
        if (*m >= 100000000000000000 || *m <= -100000000000000000)
            return 0; /* |m| stays below 1e18: the difference fits int64 */
        *m *= 10;
    }
    return 1;
}

static vbx_ia exact_diff(vb_decimal a, vb_decimal b, double da, double db)
{
    if (vb_decimal_cmp(a, b) == 0)
        return vbx_ia_point(0.0);
    int32_t e = a.exp10 < b.exp10 ? a.exp10 : b.exp10;
    int64_t ma = a.mant, mb = b.mant;
    if (scale10(&ma, a.exp10 - e) && scale10(&mb, b.exp10 - e)) {
        vb_decimal d = {mb - ma, e};
        return widen(vb_decimal_double(d));
    }
    return vbx_ia_sub(widen(db), widen(da));
}

/* Exact signs of |cj - ci|^2 - (Rj - Ri)^2 (*sn) and of Rj - Ri (return). */
static int exact_signs(const vb_sphere_set *s, size_t i, size_t j, int *sn)
{
    const vb_decimal v[8] = {s->ex[i], s->ey[i], s->ez[i], s->er[i],
                             s->ex[j], s->ey[j], s->ez[j], s->er[j]};
    int32_t emin = v[0].exp10;
    for (int k = 1; k < 8; k++)
        emin = v[k].exp10 < emin ? v[k].exp10 : emin;
    mpz_t a, b, t, acc;
    mpz_inits(a, b, t, acc, NULL);
    int sd = 0;
    for (int k = 0; k < 4; k++) {
        vb_decimal_to_mpz(a, v[k + 4], emin, t);
        vb_decimal_to_mpz(b, v[k], emin, t);
        mpz_sub(a, a, b);
        if (k == 3)
            sd = mpz_sgn(a);
        mpz_mul(a, a, a);
        if (k == 3)
            mpz_sub(acc, acc, a);
        else
            mpz_add(acc, acc, a);
    }
    *sn = mpz_sgn(acc);
    mpz_clears(a, b, t, acc, NULL);
    return sd;
}

/* Centres sorted by a grid cell of side `h` (keys: 21 bits per axis). */
typedef struct grid_slot {
    uint64_t cell;
    uint64_t id;
} grid_slot;

typedef struct grid {
    double x0[3], ih;
    double cmax; /* the largest |coordinate| */
    grid_slot *key; /* sorted by (cell, id) */
    size_t n;
} grid;

static uint64_t cell_key(long cx, long cy, long cz)
{
    return ((uint64_t)cx << 42) | ((uint64_t)cy << 21) | (uint64_t)cz;
}

static long cell_of(const grid *g, int k, double x)
{
    double c = (x - g->x0[k]) * g->ih;
    return c < 0 ? 0 : c > 2097000.0 ? 2097000 : (long)c;
}

static int cmp_u64(const void *a, const void *b)
{
    const grid_slot *x = a, *y = b;
    if (x->cell != y->cell)
        return x->cell < y->cell ? -1 : 1;
    return x->id < y->id ? -1 : x->id > y->id;
}

/* A thread's stage clocks (opt->clock), no cache line shared with
 * another thread's: lap is written at every region's stages (vbm_lap),
 * and rows of five doubles side by side put two threads' laps on one
 * line. The gap after them (more than a line) keeps the next thread's
 * off it wherever the job's block lies (calloc aligns to 16 only). */
typedef struct thread_clock {
    double clock[VB_CELL_NSTAGE]; /* CPU seconds per stage */
    double lap[VB_CELL_NSTAGE];   /* the atom being measured: its wall seconds per stage */
    char gap[72];
} thread_clock;

typedef struct job {
    const vb_sphere_set *set;
    const vb_measure_options *opt;
    const grid *g;
    vbx_ia probe;
    vb_cell_measures *out;
    const vb_measure_images *img; /* NULL: the open run */
    vbm_pair **pairs; /* per atom, j as sphere ids, sorted by id */
    size_t *npairs;
    vbm_scratch sc[VB_MAX_THREADS];
    vbm_nb *nb[VB_MAX_THREADS];
    size_t cap_nb[VB_MAX_THREADS];
    size_t patches[VB_MAX_THREADS];
    size_t stokes[VB_MAX_THREADS]; /* atoms measured by vbm_cell_stokes */
    thread_clock tc[VB_MAX_THREADS]; /* opt->clock: each thread's stage seconds */
    int failed;
    vb_ctx *ctx;               /* where progress goes */
    atomic_size_t atoms_done;  /* atoms finished, every thread (progress) */
} job;

static int cmp_pair(const void *a, const void *b)
{
    uint32_t x = ((const vbm_pair *)a)->j, y = ((const vbm_pair *)b)->j;
    return x < y ? -1 : x > y;
}

static int written_side(const job *jb, size_t i, uint32_t j, vb_contact *c);

/* Whether atom i integrates its contact with sphere j: the side that
 * writes it (written_side), or both sides with contacts_both. */
static uint8_t wants_contact(const job *jb, size_t i, size_t j)
{
    vb_contact c;
    return (uint8_t)(jb->opt->contacts &&
                     (jb->opt->contacts_both || written_side(jb, i, (uint32_t)j, &c)));
}

/* Collects atom i's neighbours within reach. Returns 0 on a full answer,
 * 1 when the cell is empty (a larger sphere touches i from inside), -1 on
 * ENOMEM. */
static int neighbours(job *jb, size_t i, int tid, size_t *nnb)
{
    const vb_sphere_set *s = jb->set;
    const grid *g = jb->g;
    vbx_ia ri = vbx_ia_add(widen(s->r[i]), jb->probe);
    long c[3] = {cell_of(g, 0, s->x[i]), cell_of(g, 1, s->y[i]), cell_of(g, 2, s->z[i])};
    size_t m = 0;
    for (long dx = -1; dx <= 1; dx++)
        for (long dy = -1; dy <= 1; dy++)
            for (long dz = -1; dz <= 1; dz++) {
                long x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
                if (x < 0 || y < 0 || z < 0)
                    continue;
                uint64_t key = cell_key(x, y, z);
                size_t lo = 0, hi = g->n;
                while (lo < hi) {
                    size_t mid = (lo + hi) / 2;
                    if (g->key[mid].cell < key)
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                for (; lo < g->n && g->key[lo].cell == key; lo++) {
                    size_t j = (size_t)g->key[lo].id;
                    if (j == i || s->contained[j])
                        continue;
                    /* most spheres of the 27 cells are out of reach: rejected
                     * on doubles first where that is proven. The doubles'
                     * difference vector is within 8e-16 cmax of the exact
                     * one and R, dd, far within 1e-15 relative, so dd >
                     * far^2 gives |d| > R (1 + 0.9e-9) + 0.99e-12 cmax
                     * exactly, beyond the enclosures' roundings below
                     * (1e-15 of |d|^2 and 1.6e-15 |d| cmax): the same
                     * spheres are skipped there (3pqr, 1 thread: ~80 % of
                     * the candidates, their exact differences each) */
                    double dx = s->x[i] - s->x[j], dy = s->y[i] - s->y[j], dz = s->z[i] - s->z[j];
                    double far = (s->r[i] + s->r[j] + 2.0 * jb->probe.hi) * (1.0 + 1e-9) +
                                 1e-12 * g->cmax + 1e-150;
                    if (dx * dx + dy * dy + dz * dz > far * far)
                        continue;
                    vbm_nb n;
                    vbx_ia Rj = widen(s->r[j]), d2 = vbx_ia_point(0.0);
                    n.d[0] = exact_diff(s->ex[i], s->ex[j], s->x[i], s->x[j]);
                    n.d[1] = exact_diff(s->ey[i], s->ey[j], s->y[i], s->y[j]);
                    n.d[2] = exact_diff(s->ez[i], s->ez[j], s->z[i], s->z[j]);
                    for (int k = 0; k < 3; k++)
                        d2 = vbx_ia_add(d2, vbx_ia_sqr(n.d[k]));
                    vbx_ia reach = vbx_ia_sqr(vbx_ia_add(ri, vbx_ia_add(Rj, jb->probe)));
                    if (d2.lo > reach.hi)
                        continue; /* the expanded balls do not meet */
                    n.delta = exact_diff(s->er[i], s->er[j], s->r[i], s->r[j]);
                    n.N = vbx_ia_sub(d2, vbx_ia_sqr(n.delta));
                    if (!(n.N.lo > 0.0)) {
                        int sn, sd = exact_signs(s, i, j, &sn);
                        if (sn <= 0 && sd > 0)
                            return 1; /* i touches j from inside (contained is marked apart) */
                        if (sn <= 0)
                            continue; /* j inside i, touching: no constraint */
                        n.N.lo = 0.0;
                    }
                    n.k = vbx_ia_sub(vbx_ia_div(n.N, vbx_ia_add(ri, ri)), n.delta);
                    n.id = (uint32_t)j;
                    n.con = wants_contact(jb, i, j);
                    if (m >= jb->cap_nb[tid]) {
                        size_t cap = jb->cap_nb[tid] ? 2 * jb->cap_nb[tid] : 256;
                        vbm_nb *p = realloc(jb->nb[tid], cap * sizeof *p);
                        if (!p)
                            return -1;
                        jb->nb[tid] = p;
                        jb->cap_nb[tid] = cap;
                    }
                    jb->nb[tid][m++] = n;
                }
            }
    *nnb = m;
    return 0;
}

/* One more atom done (or found empty): the progress, from any thread. */
static void atom_done(job *jb)
{
    vb_progress(jb->ctx, "cells", atomic_fetch_add(&jb->atoms_done, 1) + 1, jb->out->n);
}

static void measure_atom(job *jb, size_t i, int tid)
{
    vb_cell_measures *o = jb->out;
    size_t nnb = 0;
    double *clock = jb->opt->clock ? jb->tc[tid].lap : NULL;
    double t0 = clock ? vb_now() : 0.0;
    int e = jb->set->contained[i] ? 1 : neighbours(jb, i, tid, &nnb);
    t0 = vbm_lap(clock, VB_CELL_NEIGHBOURS, t0);
    if (e < 0 || nnb >= 65536) {
        jb->failed = e < 0 ? VB_ENOMEM : VB_EINTERNAL;
        return;
    }
    if (e > 0) {
        o->empty[i] = 1;
        return;
    }
    vbm_atom_in in = {vbx_ia_add(widen(jb->set->r[i]), jb->probe), jb->nb[tid], nnb,
                      jb->opt->tolerance,
                      jb->opt->max_patches ? jb->opt->max_patches : VB_MEASURES_MAX_PATCHES,
                      jb->opt->contacts, clock};
    vbm_atom_out r;
    double timed = 0.0;
    for (int k = 0; clock && k < VB_CELL_NSTAGE; k++)
        timed -= clock[k];
    int st = jb->opt->patches ? 0 : vbm_cell_stokes(&in, &jb->sc[tid], &r);
    if (st < 0) {
        jb->failed = VB_ENOMEM;
        return;
    }
    jb->stokes[tid] += st;
    if (st == 0 && vbm_cell_integrate(&in, &jb->sc[tid], &r) != VB_OK) {
        jb->failed = VB_ENOMEM;
        return;
    }
    if (clock && st == 0) { /* the patches, and the closed forms' work they replaced */
        for (int k = 0; k < VB_CELL_NSTAGE; k++)
            timed += clock[k];
        clock[VB_CELL_PATCHES] += vb_now() - t0 - timed;
    }
    o->vol_lo[i] = vbx_max(r.vol.lo, 0.0);
    o->vol_hi[i] = r.vol.hi;
    o->sas_lo[i] = vbx_max(r.sas.lo, 0.0);
    o->sas_hi[i] = r.sas.hi;
    o->loose[i] = (uint8_t)r.loose;
    jb->patches[tid] += r.patches;
    for (size_t k = 0; k < r.npairs; k++)
        r.pairs[k].j = jb->nb[tid][r.pairs[k].j].id;
    if (r.npairs) /* qsort takes no NULL, even for 0 elements */
        qsort(r.pairs, r.npairs, sizeof *r.pairs, cmp_pair);
    jb->pairs[i] = r.pairs;
    jb->npairs[i] = r.npairs;
}

static void one_atom(void *ctx, size_t i, int tid)
{
    job *jb = ctx;
    if (!jb->opt->clock) {
        measure_atom(jb, i, tid);
    } else {
        /* the stages on the monotonic clock (cheap), scaled to the atom's
         * CPU seconds (a costlier clock, read twice per atom): a thread
         * that waits for a core, on a loaded machine, counts no waiting */
        memset(jb->tc[tid].lap, 0, sizeof jb->tc[tid].lap);
        double c0 = vb_thread_cpu_now(), w0 = vb_now();
        measure_atom(jb, i, tid);
        double w = vb_now() - w0, f = w > 0.0 ? (vb_thread_cpu_now() - c0) / w : 1.0;
        for (int k = 0; k < VB_CELL_NSTAGE; k++)
            jb->tc[tid].clock[k] += f * jb->tc[tid].lap[k];
    }
    /* MPFR's caches (atan's pi) are per thread and die with it unfreed:
     * freed after each thread's last atom (item i goes to thread i mod
     * threads, at most VB_MAX_THREADS), not after every atom, which made
     * every atom's first atan compute pi again */
    if (i + VB_MAX_THREADS >= jb->out->n)
        vbm_ia_release();
    atom_done(jb);
}

/* The area of (i, j) seen from j, [0, 0] when j proved it absent. In a
 * periodic run j may be an image (atom a moved by s): the other side is
 * a's pair with i moved by -s (an image within a's reach too, as the
 * distance is the same). */
static vbx_ia other_side(const job *jb, size_t j, uint32_t i)
{
    const vb_measure_images *im = jb->img;
    if (im && j >= im->n0) {
        size_t a = im->atom[j];
        for (size_t k = 0; k < jb->npairs[a]; k++) {
            size_t e = jb->pairs[a][k].j;
            if (im->atom[e] == i && im->shift[e][0] == -im->shift[j][0] &&
                im->shift[e][1] == -im->shift[j][1] && im->shift[e][2] == -im->shift[j][2])
                return jb->pairs[a][k].area;
        }
        return vbx_ia_point(0.0);
    }
    size_t lo = 0, hi = jb->npairs[j];
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (jb->pairs[j][mid].j < i)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo < jb->npairs[j] && jb->pairs[j][lo].j == i)
        return jb->pairs[j][lo].area;
    return vbx_ia_point(0.0);
}

/* Whether the contact of atom i with sphere j is the one written of its
 * periodic face: i < j's atom, or j an image of i whose shift is
 * lexicographically positive (vb_contact). */
static int written_side(const job *jb, size_t i, uint32_t j, vb_contact *c)
{
    const vb_measure_images *im = jb->img;
    c->i = (uint32_t)i;
    c->j = j;
    memset(c->s, 0, sizeof c->s);
    if (!im || j < im->n0)
        return i < j;
    c->j = im->atom[j];
    memcpy(c->s, im->shift[j], sizeof c->s);
    if (c->j != i)
        return i < c->j;
    int k = c->s[0] ? 0 : c->s[1] ? 1 : 2;
    return c->s[k] > 0;
}

/* Every contact into o->contacts from the side that writes it, met with
 * the other side's with contacts_both (the other side did not integrate it
 * otherwise: its list lacks it). */
static int meet_contacts(vb_ctx *ctx, job *jb)
{
    vb_cell_measures *o = jb->out;
    size_t total = 0;
    for (size_t i = 0; i < o->n; i++)
        total += jb->npairs[i];
    o->contacts = malloc((total ? total : 1) * sizeof *o->contacts);
    if (!o->contacts)
        return VB_ENOMEM;
    for (size_t i = 0; i < o->n; i++)
        for (size_t k = 0; k < jb->npairs[i]; k++) {
            uint32_t j = jb->pairs[i][k].j;
            vbx_ia a = jb->pairs[i][k].area;
            vbx_ia b = jb->opt->contacts_both ? other_side(jb, j, (uint32_t)i) : a;
            double lo = vbx_max(vbx_max(a.lo, b.lo), 0.0), hi = vbx_min(a.hi, b.hi);
            if (lo > hi)
                return vb_error(ctx, VB_EINTERNAL, jb->set->source, 0,
                                "contact %zu-%u: the enclosures from both sides are disjoint "
                                "([%.17g, %.17g] and [%.17g, %.17g])",
                                i, j, a.lo, a.hi, b.lo, b.hi);
            vb_contact c;
            if (written_side(jb, i, j, &c) && hi > 0.0) {
                c.lo = lo;
                c.hi = hi;
                o->contacts[o->ncontacts++] = c;
            }
        }
    return VB_OK;
}

/* W850 names the atoms with empty cells (the first few one by one), W851
 * counts the values left wider than asked. */
static void warn_atoms(vb_ctx *ctx, const vb_sphere_set *set, const vb_cell_measures *o)
{
    size_t named = 0;
    for (size_t i = 0; i < o->n && named < 10; i++)
        if (o->empty[i]) {
            vb_warn(ctx, VB_W_CELL_EMPTY, set->source, set->line ? set->line[i] : 0,
                    "atom %zu: its constrained cell is empty (inside or touching a larger "
                    "sphere from inside): volume and SAS 0",
                    i);
            named++;
        }
    if (o->nempty > named)
        vb_warn(ctx, VB_W_CELL_EMPTY, set->source, 0, "%zu more atoms with empty cells",
                o->nempty - named);
    if (o->nloose)
        vb_warn(ctx, VB_W_CELL_LOOSE, set->source, 0,
                "%zu atoms have a value wider than the tolerance asks (patch budget per atom "
                "spent): their enclosures still hold",
                o->nloose);
}

static int build_grid(grid *g, const vb_sphere_set *s, double probe)
{
    double rmax = 0.0;
    for (int k = 0; k < 3; k++)
        g->x0[k] = INFINITY;
    g->cmax = 0.0;
    for (size_t i = 0; i < s->n; i++) {
        rmax = vbx_max(rmax, s->r[i]);
        g->cmax = vbx_max(g->cmax, vbx_max(fabs(s->x[i]), vbx_max(fabs(s->y[i]), fabs(s->z[i]))));
        g->x0[0] = vbx_min(g->x0[0], s->x[i]);
        g->x0[1] = vbx_min(g->x0[1], s->y[i]);
        g->x0[2] = vbx_min(g->x0[2], s->z[i]);
    }
    /* a cell at least the reach, with a margin for the rounding of the
     * cell index (neighbours are tested on exact enclosures afterwards) */
    double h = (2.0 * (rmax + probe)) * (1.0 + 1e-9) + 1e-9;
    g->ih = 1.0 / h;
    g->n = s->n;
    g->key = malloc((s->n ? s->n : 1) * sizeof *g->key);
    if (!g->key)
        return VB_ENOMEM;
    for (size_t i = 0; i < s->n; i++) {
        g->key[i].cell = cell_key(cell_of(g, 0, s->x[i]), cell_of(g, 1, s->y[i]),
                                  cell_of(g, 2, s->z[i]));
        g->key[i].id = i;
    }
    qsort(g->key, s->n, sizeof *g->key, cmp_u64);
    return VB_OK;
}

int vb_cell_measures_compute(vb_ctx *ctx, const vb_sphere_set *set, const vb_measure_options *opt,
                             vb_cell_measures *out)
{
    return vb_cell_measures_compute_images(ctx, set, opt, NULL, out);
}

int vb_cell_measures_compute_images(vb_ctx *ctx, const vb_sphere_set *set,
                                    const vb_measure_options *opt, const vb_measure_images *img,
                                    vb_cell_measures *out)
{
    memset(out, 0, sizeof *out);
    int bad = vb_measure_options_check(ctx, opt);
    if (bad != VB_OK)
        return bad;
    if (set->n > UINT32_MAX || !set->contained)
        return vb_error(ctx, VB_EMISUSE, set->source, 0, "the sphere set is not validated");
    if (img && (img->n0 > set->n || !img->atom || !img->shift))
        return vb_error(ctx, VB_EMISUSE, set->source, 0, "periodic images without their atoms");
    size_t n = img ? img->n0 : set->n;
    out->n = n;
    out->periodic = img != NULL;
    out->vol_lo = calloc(n + 1, sizeof(double));
    out->vol_hi = calloc(n + 1, sizeof(double));
    out->sas_lo = calloc(n + 1, sizeof(double));
    out->sas_hi = calloc(n + 1, sizeof(double));
    out->empty = calloc(n + 1, 1);
    out->loose = calloc(n + 1, 1);
    job *jb = calloc(1, sizeof *jb);
    grid g = {{0}, 0, 0, NULL, 0};
    int rc = VB_ENOMEM;
    if (!out->vol_lo || !out->vol_hi || !out->sas_lo || !out->sas_hi || !out->empty ||
        !out->loose || !jb)
        goto done;
    jb->pairs = calloc(n + 1, sizeof *jb->pairs);
    jb->npairs = calloc(n + 1, sizeof *jb->npairs);
    if (!jb->pairs || !jb->npairs || build_grid(&g, set, opt->probe) != VB_OK)
        goto done;
    jb->set = set;
    jb->opt = opt;
    jb->g = &g;
    jb->probe = opt->probe == 0.0 ? vbx_ia_point(0.0) : widen(opt->probe);
    jb->out = out;
    jb->img = img;
    jb->ctx = ctx;
    atomic_init(&jb->atoms_done, 0);
    vb_progress(ctx, "cells", 0, n);
    vb_parallel_for(one_atom, jb, n, vb_threads((unsigned)(opt->threads > 0 ? opt->threads : 0)));
    if (jb->failed) {
        rc = jb->failed == VB_ENOMEM
                 ? VB_ENOMEM
                 : vb_error(ctx, VB_EINTERNAL, set->source, 0, "over 65535 neighbours in reach");
        goto done;
    }
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        out->patches += jb->patches[t];
        out->nclosed += jb->stokes[t];
        for (int k = 0; k < VB_CELL_NSTAGE; k++)
            out->stage_s[k] += jb->tc[t].clock[k];
    }
    for (size_t i = 0; i < n; i++) {
        out->nempty += out->empty[i];
        out->nloose += out->loose[i];
    }
    warn_atoms(ctx, set, out);
    rc = opt->contacts ? meet_contacts(ctx, jb) : VB_OK;
done:
    if (jb) {
        for (int t = 0; t < VB_MAX_THREADS; t++) {
            vbm_scratch_free(&jb->sc[t]);
            free(jb->nb[t]);
        }
        if (jb->pairs)
            for (size_t i = 0; i < n; i++)
                free(jb->pairs[i]);
        free(jb->pairs);
        free(jb->npairs);
    }
    free(jb);
    free(g.key);
    if (rc == VB_ENOMEM)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory in the cell measures");
    if (rc != VB_OK)
        vb_cell_measures_free(out);
    return rc;
}
