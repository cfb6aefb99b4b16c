/* The direction-cover proposer on the host (vb_cover.h; the argument is in
 * vb_cover_shared.h). Each cell is covered independently: a near list of
 * neighbours from a uniform grid, then a depth-first subdivision of the
 * cube's faces in which every patch keeps the labels its enclosures cannot
 * exclude. Cells run on worker threads; the quadruples are sorted at the
 * end, so the result does not depend on the thread count. */
#include "vb_cover.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover_shared.h"
#include "vbs_internal.h"

/* ---- uniform grid of the centres ---------------------------------------- */

typedef struct cgrid {
    double lo[3], cell;
    int dim[3];
    uint32_t *start; /* dim0*dim1*dim2 + 1 */
    uint32_t *ids;
    double rmax;
} cgrid;

static void cgrid_free(cgrid *g)
{
    free(g->start);
    free(g->ids);
}

static size_t cgrid_slot(const cgrid *g, int x, int y, int z)
{
    return ((size_t)z * g->dim[1] + (size_t)y) * g->dim[0] + (size_t)x;
}

static int cgrid_coord(const cgrid *g, double v, int a)
{
    double w = (v - g->lo[a]) / g->cell;
    if (!(w > 0.0))
        return 0;
    int k = w >= (double)g->dim[a] ? g->dim[a] - 1 : (int)w;
    return k;
}

static int cgrid_build(const vb_sphere_set *s, cgrid *g)
{
    memset(g, 0, sizeof *g);
    double hi[3];
    size_t m = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->contained[i])
            continue;
        const double p[3] = {s->x[i], s->y[i], s->z[i]};
        for (int a = 0; a < 3; a++) {
            if (m == 0 || p[a] < g->lo[a])
                g->lo[a] = p[a];
            if (m == 0 || p[a] > hi[a])
                hi[a] = p[a];
        }
        if (s->r[i] > g->rmax)
            g->rmax = s->r[i];
        m++;
    }
    double ext = 0.0;
    for (int a = 0; a < 3; a++)
        ext = hi[a] - g->lo[a] > ext ? hi[a] - g->lo[a] : ext;
    /* About two centres per cell in a protein-like density. */
    double vol = 1.0;
    for (int a = 0; a < 3; a++)
        vol *= (hi[a] - g->lo[a]) + 1e-9 * (ext + 1.0);
    g->cell = cbrt(2.0 * vol / (double)(m ? m : 1));
    if (!(g->cell > 0.0))
        g->cell = 1.0;
    size_t cells = 1;
    for (int a = 0; a < 3; a++) {
        double d = (hi[a] - g->lo[a]) / g->cell;
        g->dim[a] = d >= 1023.0 ? 1024 : (int)d + 1;
        cells *= (size_t)g->dim[a];
    }
    /* Cap the cell count at a few per sphere. */
    while (cells > 8 * (m + 1)) {
        g->cell *= 1.26;
        cells = 1;
        for (int a = 0; a < 3; a++) {
            double d = (hi[a] - g->lo[a]) / g->cell;
            g->dim[a] = d >= 1023.0 ? 1024 : (int)d + 1;
            cells *= (size_t)g->dim[a];
        }
    }
    g->start = calloc(cells + 1, sizeof *g->start);
    g->ids = malloc((m ? m : 1) * sizeof *g->ids);
    if (!g->start || !g->ids)
        return VB_ENOMEM;
    for (size_t i = 0; i < s->n; i++)
        if (!s->contained[i])
            g->start[cgrid_slot(g, cgrid_coord(g, s->x[i], 0), cgrid_coord(g, s->y[i], 1),
                                cgrid_coord(g, s->z[i], 2)) + 1]++;
    for (size_t c = 0; c < cells; c++)
        g->start[c + 1] += g->start[c];
    uint32_t *fill = malloc(cells * sizeof *fill);
    if (!fill)
        return VB_ENOMEM;
    memcpy(fill, g->start, cells * sizeof *fill);
    for (size_t i = 0; i < s->n; i++)
        if (!s->contained[i])
            g->ids[fill[cgrid_slot(g, cgrid_coord(g, s->x[i], 0), cgrid_coord(g, s->y[i], 1),
                                   cgrid_coord(g, s->z[i], 2))]++] = (uint32_t)i;
    free(fill);
    return VB_OK;
}

/* ---- per-thread scratch -------------------------------------------------- */

typedef struct frame {
    vbs_u32 f, level, iu, iv;
    size_t off, len;   /* labels in lab[off .. off + len) */
    double ecert;      /* every sphere with e_j <= ecert is in the list (or INFINITY) */
    vbs_u32 stall;     /* consecutive levels that excluded no label */
} frame;

typedef struct scratch {
    vbq_nb *nb;        /* neighbour records of the current cell */
    size_t nnb, nb_cap;
    uint32_t *nbidx;   /* per sphere: its record in nb, or UINT32_MAX */
    uint32_t *stamp;   /* per sphere: token of the list it was last seen in */
    uint32_t token;
    uint32_t *lab;     /* stacked label lists (indices into nb) */
    size_t lab_cap;
    frame *st;
    size_t st_cap;
    double *lo, *hi;
    size_t lo_cap, hi_cap;
    uint32_t *own;
    size_t own_cap;
    uint32_t (*q)[4];  /* quadruples of this thread */
    size_t nq, q_cap;
    vb_cover_stats stats;
} scratch;

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t nc = *cap ? *cap : 256;
    while (nc < need)
        nc *= 2;
    void *q = realloc(*p, nc * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = nc;
    return 0;
}

typedef struct job {
    const vb_sphere_set *set;
    const cgrid *g;
    vbs_u32 T, min_level, max_level, enum_max;
    atomic_size_t next;
    atomic_int failed;
} job;

/* The record of neighbour j of base i, made once per cell; its index. */
static int nb_of(scratch *sc, const vb_sphere_set *s, uint32_t i, uint32_t j, uint32_t *idx)
{
    if (sc->nbidx[j] != UINT32_MAX) {
        *idx = sc->nbidx[j];
        return 0;
    }
    if (grow((void **)&sc->nb, &sc->nb_cap, sc->nnb + 1, sizeof *sc->nb))
        return -1;
    vbq_nb_make(s->x[i], s->y[i], s->z[i], s->r[i], s->x[j], s->y[j], s->z[j], s->r[j], j,
                &sc->nb[sc->nnb]);
    sc->nbidx[j] = (uint32_t)sc->nnb;
    *idx = (uint32_t)sc->nnb++;
    sc->stats.neighbours++;
    return 0;
}

static int lab_push(scratch *sc, size_t at, uint32_t v)
{
    if (grow((void **)&sc->lab, &sc->lab_cap, at + 1, sizeof *sc->lab))
        return -1;
    sc->lab[at] = v;
    return 0;
}

/* Neighbours of i whose centre lies within rq of c_i, appended to the
 * label list at lab[off + *len ...]. */
static int gather_ball(scratch *sc, const job *jb, uint32_t i, double rq, size_t off, size_t *len)
{
    const vb_sphere_set *s = jb->set;
    const cgrid *g = jb->g;
    int lo[3], hi[3];
    const double c[3] = {s->x[i], s->y[i], s->z[i]};
    for (int a = 0; a < 3; a++) {
        lo[a] = cgrid_coord(g, c[a] - rq, a);
        hi[a] = cgrid_coord(g, c[a] + rq, a);
    }
    double rq2 = rq * rq;
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int x = lo[0]; x <= hi[0]; x++) {
                size_t sl = cgrid_slot(g, x, y, z);
                for (uint32_t k = g->start[sl]; k < g->start[sl + 1]; k++) {
                    uint32_t j = g->ids[k], idx;
                    if (j == i)
                        continue;
                    double dx = s->x[j] - c[0], dy = s->y[j] - c[1], dz = s->z[j] - c[2];
                    if (dx * dx + dy * dy + dz * dz > rq2)
                        continue;
                    if (nb_of(sc, s, i, j, &idx) || lab_push(sc, off + *len, idx))
                        return -1;
                    (*len)++;
                }
            }
    return 0;
}

/* Every sphere not in the list lab[off .. off + *len) that can be a label in
 * the patch (m, h) with lower envelope LO, appended to it: f_j(u) >= LO >= 0
 * somewhere needs u.d + delta >= 0 (N > 0), and when LO > 0 also e_j <= 1/LO
 * (|a_j| + b_j = 1/e_j, e_j = |c_i - c_j| - R_j + R_i). A grid cell is skipped
 * when the interval bound of max u.(c - c_i) over the patch box and the
 * cell's box, plus R_max - R_i, is negative, or when the cell lies beyond
 * 1/LO + R_max - R_i (both with a relative margin far above the rounding
 * errors); each remaining sphere is kept when its enclosure reaches LO. */
static int gather_far(scratch *sc, const job *jb, uint32_t i, const double m[3],
                      const double h[3], double LO, size_t off, size_t *len)
{
    const vb_sphere_set *s = jb->set;
    const cgrid *g = jb->g;
    const double c[3] = {s->x[i], s->y[i], s->z[i]};
    double slack = g->rmax - s->r[i];
    double reach = LO > 0.0 ? (1.0 / LO) * (1.0 + 1e-9) + slack + 1e-9 * g->cell : INFINITY;
    uint32_t tok = ++sc->token;
    for (size_t k = 0; k < *len; k++)
        sc->stamp[sc->nb[sc->lab[off + k]].id] = tok;
    sc->stamp[i] = tok;
    for (int z = 0; z < g->dim[2]; z++)
        for (int y = 0; y < g->dim[1]; y++)
            for (int x = 0; x < g->dim[0]; x++) {
                size_t sl = cgrid_slot(g, x, y, z);
                if (g->start[sl] == g->start[sl + 1])
                    continue;
                const int xyz[3] = {x, y, z};
                double best = 0.0, near2 = 0.0;
                for (int a = 0; a < 3; a++) {
                    /* Centres of the cell lie in [b0, b1]; the outer cells
                     * take everything beyond the grid (cgrid_coord clamps). */
                    double b0 = g->lo[a] + g->cell * xyz[a] - c[a];
                    double b1 = xyz[a] + 1 == g->dim[a] ? INFINITY : b0 + g->cell;
                    if (xyz[a] == 0)
                        b0 = -INFINITY;
                    double u0 = m[a] - h[a], u1 = m[a] + h[a];
                    double p[4] = {u0 * b0, u0 * b1, u1 * b0, u1 * b1};
                    double mx = -INFINITY;
                    for (int q = 0; q < 4; q++)
                        if (p[q] == p[q] && p[q] > mx)
                            mx = p[q];
                        else if (p[q] != p[q])
                            mx = INFINITY; /* 0 * inf: cannot tell */
                    best += mx;
                    double dn = b0 > 0.0 ? b0 : (b1 < 0.0 ? -b1 : 0.0);
                    near2 += dn * dn;
                }
                if (best + slack < -1e-9 * (fabs(best) + fabs(slack) + g->cell))
                    continue;
                if (near2 > reach * reach)
                    continue;
                for (uint32_t k = g->start[sl]; k < g->start[sl + 1]; k++) {
                    uint32_t j = g->ids[k], idx;
                    if (sc->stamp[j] == tok)
                        continue;
                    sc->stamp[j] = tok;
                    if (nb_of(sc, s, i, j, &idx))
                        return -1;
                    double l, hh;
                    vbq_eval(&sc->nb[idx], m, h, &l, &hh);
                    if (!(hh >= LO))
                        continue;
                    if (lab_push(sc, off + *len, idx))
                        return -1;
                    (*len)++;
                    sc->stats.far_neighbours++;
                }
            }
    return 0;
}

static int push_quad(scratch *sc, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    uint32_t v[4] = {a, b, c, d};
    for (int x = 1; x < 4; x++)
        for (int y = x; y > 0 && v[y - 1] > v[y]; y--) {
            uint32_t t = v[y];
            v[y] = v[y - 1];
            v[y - 1] = t;
        }
    if (grow((void **)&sc->q, &sc->q_cap, sc->nq + 1, sizeof *sc->q))
        return -1;
    memcpy(sc->q[sc->nq++], v, sizeof v);
    return 0;
}

static int cmp_quad(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    for (int k = 0; k < 4; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

/* Sorts q[from ..] and drops repeats. */
static void unique_tail(uint32_t (*q)[4], size_t from, size_t *n)
{
    if (*n - from < 2)
        return;
    qsort(q + from, *n - from, sizeof *q, cmp_quad);
    size_t w = from + 1;
    for (size_t k = from + 1; k < *n; k++)
        if (cmp_quad(q[k], q[w - 1]) != 0)
            memcpy(q[w++], q[k], sizeof *q);
    *n = w;
}

/* The first level at which a patch that is not closed fetches its far
 * spheres instead of subdividing further. */
#define VBQ_FETCH_LEVEL 2u
/* Levels without an exclusion before a patch enumerates (when it has at
 * most VBQ_STALL_ENUM owned labels: 364 quadruples). */
#define VBQ_STALL 4u
#define VBQ_STALL_ENUM 14u

/* Covers the cell of sphere i: quadruples {i < j < k < l} appended to sc->q. */
static int cover_cell(scratch *sc, const job *jb, uint32_t i)
{
    const vb_sphere_set *s = jb->set;
    const cgrid *g = jb->g;
    size_t qfrom = sc->nq;
    /* Near list: every sphere whose centre is within rq of c_i, so every
     * sphere with e_j <= rq - (R_max - R_i) is in it. */
    double rq = 2.0 * g->cell + 2.0 * g->rmax;
    size_t len0 = 0;
    int rc = VB_ENOMEM;
    if (gather_ball(sc, jb, i, rq, 0, &len0))
        goto done;
    double ecert0 = (rq - (g->rmax - s->r[i])) * (1.0 - 1e-9);

    vbs_u32 T = jb->T;
    size_t nst = 0;
    for (vbs_u32 f = 0; f < 6; f++)
        for (vbs_u32 iv = 0; iv < T; iv++)
            for (vbs_u32 iu = 0; iu < T; iu++) {
                if (grow((void **)&sc->st, &sc->st_cap, nst + 1, sizeof *sc->st))
                    goto done;
                sc->st[nst++] = (frame){f, 0u, iu, iv, 0, len0, ecert0, 0u};
            }
    /* The roots share lab[0 .. len0); lists of deeper frames are stacked
     * above top. A frame's list lies below the lists of every frame pushed
     * after it, so popping a frame frees everything above its list. */
    size_t top = len0;
    while (nst > 0) {
        frame fr = sc->st[--nst];
        if (fr.off + fr.len < top)
            top = fr.off + fr.len > len0 ? fr.off + fr.len : len0;
        double u0, u1, v0, v1, m[3], h[3];
        vbq_patch_square(T, fr.level, fr.iu, fr.iv, &u0, &u1, &v0, &v1);
        vbq_patch_box(fr.f, u0, u1, v0, v1, m, h);
        sc->stats.patches++;
        if (grow((void **)&sc->lo, &sc->lo_cap, fr.len + 1, sizeof *sc->lo) ||
            grow((void **)&sc->hi, &sc->hi_cap, fr.len + 1, sizeof *sc->hi))
            goto done;
        /* LO: the envelope is at least max(0, lo_k) everywhere in P (0 is
         * "infinity", the envelope's floor). */
        double LO = 0.0;
        for (size_t k = 0; k < fr.len; k++) {
            vbq_eval(&sc->nb[sc->lab[fr.off + k]], m, h, &sc->lo[k], &sc->hi[k]);
            if (sc->lo[k] > LO)
                LO = sc->lo[k];
        }
        sc->stats.evals += fr.len;
        /* Closed: no sphere outside the list can reach LO, because each has
         * e_j > ecert and so f_j <= 1/e_j < 1/ecert <= LO. */
        int closed = fr.ecert == INFINITY || (LO > 0.0 && 1.0 / fr.ecert < LO * (1.0 - 1e-9));
        if (!closed && fr.level >= VBQ_FETCH_LEVEL) {
            size_t nlen = fr.len;
            if (grow((void **)&sc->lab, &sc->lab_cap, top + fr.len + 1, sizeof *sc->lab))
                goto done;
            memcpy(sc->lab + top, sc->lab + fr.off, fr.len * sizeof *sc->lab);
            if (gather_far(sc, jb, i, m, h, LO, top, &nlen))
                goto done;
            fr.off = top;
            fr.ecert = INFINITY;
            top += nlen;
            if (nlen > fr.len) {
                /* Evaluate again with the far labels. */
                fr.len = nlen;
                sc->st[nst++] = fr;
                sc->stats.patches--;
                continue;
            }
            closed = 1;
        }
        /* The surviving labels, copied above top. */
        if (grow((void **)&sc->lab, &sc->lab_cap, top + fr.len + 1, sizeof *sc->lab))
            goto done;
        size_t keep = 0, owned = 0;
        for (size_t k = 0; k < fr.len; k++)
            if (sc->hi[k] >= LO) {
                uint32_t li = sc->lab[fr.off + k];
                sc->lab[top + keep++] = li;
                if (sc->nb[li].id > i)
                    owned++;
            }
        /* Fewer than three owned labels: no vertex of this cell whose
         * smallest member is i lies in P (once the list is known whole). */
        if (closed && owned < 3)
            continue;
        /* Labels that tie exactly along a curve (equal spheres on a circle,
         * lattices) survive every subdivision there: once VBQ_STALL levels
         * in a row excluded nothing, more levels would only multiply the
         * patches, so the patch enumerates (a larger patch only adds
         * quadruples whose roots the certifier refutes). */
        int stalled = keep == fr.len ? fr.stall + 1u >= VBQ_STALL : 0;
        int deep = fr.level + 1u >= jb->max_level || (stalled && owned <= VBQ_STALL_ENUM);
        if (closed && (deep || (fr.level >= jb->min_level && owned <= jb->enum_max))) {
            sc->stats.leaves++;
            if (deep)
                sc->stats.max_level_leaves++;
            if (fr.level > sc->stats.max_level_seen)
                sc->stats.max_level_seen = fr.level;
            if (grow((void **)&sc->own, &sc->own_cap, owned + 1, sizeof *sc->own))
                goto done;
            size_t no = 0;
            for (size_t k = 0; k < keep; k++) {
                uint32_t id = sc->nb[sc->lab[top + k]].id;
                if (id > i)
                    sc->own[no++] = id;
            }
            for (size_t a = 0; a < no; a++)
                for (size_t b = a + 1; b < no; b++)
                    for (size_t c = b + 1; c < no; c++)
                        if (push_quad(sc, i, sc->own[a], sc->own[b], sc->own[c]))
                            goto done;
            continue;
        }
        /* Subdivide: the four children share the surviving list. */
        size_t off = top;
        top += keep;
        if (grow((void **)&sc->st, &sc->st_cap, nst + 4, sizeof *sc->st))
            goto done;
        for (vbs_u32 c = 0; c < 4; c++)
            sc->st[nst++] = (frame){fr.f, fr.level + 1u, 2u * fr.iu + (c & 1u),
                                    2u * fr.iv + (c >> 1), off, keep, fr.ecert,
                                    keep == fr.len ? fr.stall + 1u : 0u};
    }
    rc = VB_OK;
done:
    for (size_t k = 0; k < sc->nnb; k++)
        sc->nbidx[sc->nb[k].id] = UINT32_MAX;
    sc->nnb = 0;
    if (rc == VB_OK) {
        unique_tail(sc->q, qfrom, &sc->nq);
        sc->stats.cells++;
    }
    return rc;
}

typedef struct worker {
    job *jb;
    scratch sc;
    int rc;
} worker;

static void *work(void *arg)
{
    worker *w = arg;
    job *jb = w->jb;
    const vb_sphere_set *s = jb->set;
    w->sc.nbidx = malloc(s->n * sizeof *w->sc.nbidx);
    w->sc.stamp = calloc(s->n, sizeof *w->sc.stamp);
    if (w->sc.nbidx)
        memset(w->sc.nbidx, 0xff, s->n * sizeof *w->sc.nbidx);
    if (!w->sc.nbidx || !w->sc.stamp) {
        w->rc = VB_ENOMEM;
        atomic_store(&jb->failed, 1);
        return NULL;
    }
    for (;;) {
        size_t i = atomic_fetch_add(&jb->next, 1);
        if (i >= s->n || atomic_load(&jb->failed))
            break;
        if (s->contained[i])
            continue;
        int rc = cover_cell(&w->sc, jb, (uint32_t)i);
        if (rc != VB_OK) {
            w->rc = rc;
            atomic_store(&jb->failed, 1);
            break;
        }
    }
    return NULL;
}

static void scratch_free(scratch *sc)
{
    free(sc->nb);
    free(sc->nbidx);
    free(sc->stamp);
    free(sc->own);
    free(sc->lab);
    free(sc->st);
    free(sc->lo);
    free(sc->hi);
    free(sc->q);
}

void vb_quad_list_free(vb_quad_list *l)
{
    free(l->q);
    memset(l, 0, sizeof *l);
}

int vb_cover_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                 vb_quad_list *out, vb_cover_stats *stats)
{
    vb_cover_options o = opt ? *opt : (vb_cover_options){0};
    job jb;
    memset(&jb, 0, sizeof jb);
    jb.set = set;
    jb.T = o.tiles ? o.tiles : VB_COVER_DEFAULT_TILES;
    jb.min_level = o.min_level ? o.min_level : VB_COVER_DEFAULT_MIN_LEVEL;
    jb.max_level = o.max_level ? o.max_level : VB_COVER_MAX_LEVEL;
    jb.enum_max = o.enum_max ? o.enum_max : 3u;
    if ((jb.T & (jb.T - 1u)) || jb.T > 16u || jb.max_level > VB_COVER_MAX_LEVEL ||
        jb.enum_max < 3u || jb.enum_max > 64u)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "bad cover options");
    if (!set->contained)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "cover needs a validated sphere set");
    cgrid g;
    if (cgrid_build(set, &g) != VB_OK) {
        cgrid_free(&g);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover grid)");
    }
    jb.g = &g;
    int nt = vb_threads(o.threads);
    worker *w = calloc((size_t)nt, sizeof *w);
    int rc = w ? VB_OK : VB_ENOMEM;
    for (int t = 0; rc == VB_OK && t < nt; t++)
        w[t].jb = &jb;
    if (rc == VB_OK) {
        vb_run_jobs(work, w, sizeof *w, nt);
        for (int t = 0; t < nt; t++)
            if (w[t].rc != VB_OK && rc == VB_OK)
                rc = w[t].rc;
    }
    size_t total = 0;
    for (int t = 0; rc == VB_OK && t < nt; t++)
        total += w[t].sc.nq;
    if (rc == VB_OK && total + out->n > out->cap) {
        void *p = realloc(out->q, (total + out->n) * sizeof *out->q);
        if (!p)
            rc = VB_ENOMEM;
        else {
            out->q = p;
            out->cap = total + out->n;
        }
    }
    vb_cover_stats st;
    memset(&st, 0, sizeof st);
    for (int t = 0; w && t < nt; t++) {
        if (rc == VB_OK && w[t].sc.nq) {
            memcpy(out->q + out->n, w[t].sc.q, w[t].sc.nq * sizeof *out->q);
            out->n += w[t].sc.nq;
        }
        const vb_cover_stats *ws = &w[t].sc.stats;
        st.cells += ws->cells;
        st.neighbours += ws->neighbours;
        st.far_neighbours += ws->far_neighbours;
        st.patches += ws->patches;
        st.evals += ws->evals;
        st.leaves += ws->leaves;
        st.max_level_leaves += ws->max_level_leaves;
        if (ws->max_level_seen > st.max_level_seen)
            st.max_level_seen = ws->max_level_seen;
        scratch_free(&w[t].sc);
    }
    free(w);
    cgrid_free(&g);
    if (rc == VB_OK && out->n > 1) {
        qsort(out->q, out->n, sizeof *out->q, cmp_quad);
        size_t k = 1;
        for (size_t a = 1; a < out->n; a++)
            if (cmp_quad(out->q[a], out->q[k - 1]) != 0)
                memcpy(out->q[k++], out->q[a], sizeof *out->q);
        out->n = k;
    }
    st.quads = out->n;
    if (stats)
        *stats = st;
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    return rc;
}
