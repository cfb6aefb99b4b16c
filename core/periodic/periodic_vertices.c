/* The periodic vertex pipeline: the open pipeline over the box's atoms and
 * their images (images.c proves which suffice), the cover on the atoms'
 * cells alone, and one canonical translate of each vertex kept. */
#include "vb_periodic.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_parallel.h"

void vb_periodic_result_init(vb_periodic_result *r)
{
    memset(r, 0, sizeof *r);
    vb_vertices_result_init(&r->run);
}

void vb_periodic_result_free(vb_periodic_result *r)
{
    vb_periodic_images_free(&r->img);
    vb_vertices_result_free(&r->run);
    vb_periodic_vertices_free(&r->v);
}

int vb_periodic_member_cmp(const vb_periodic_member *a, const vb_periodic_member *b)
{
    if (a->id != b->id)
        return a->id < b->id ? -1 : 1;
    for (int k = 0; k < 3; k++)
        if (a->s[k] != b->s[k])
            return a->s[k] < b->s[k] ? -1 : 1;
    return 0;
}

static int cmp_member_q(const void *a, const void *b)
{
    return vb_periodic_member_cmp(a, b);
}

/* Lexicographic order of two member lists of equal length. */
static int cmp_list(const vb_periodic_member *a, const vb_periodic_member *b, size_t m)
{
    for (size_t k = 0; k < m; k++) {
        int c = vb_periodic_member_cmp(a + k, b + k);
        if (c)
            return c;
    }
    return 0;
}

int vb_periodic_is_canonical(const vb_periodic_member *found, size_t m,
                             vb_periodic_member *scratch)
{
    vb_periodic_member *best = scratch, *cand = scratch + m;
    int have = 0;
    uint32_t low = found[0].id;
    for (size_t j = 0; j < m && found[j].id == low; j++) {
        for (size_t k = 0; k < m; k++) {
            cand[k].id = found[k].id;
            for (int a = 0; a < 3; a++)
                cand[k].s[a] = (int16_t)(found[k].s[a] - found[j].s[a]);
        }
        qsort(cand, m, sizeof *cand, cmp_member_q);
        if (!have || cmp_list(cand, best, m) < 0) {
            memcpy(best, cand, m * sizeof *best);
            have = 1;
        }
    }
    return cmp_list(found, best, m) == 0;
}

/* A row to sort, with its list (qsort has no context argument). */
typedef struct row {
    const vb_periodic_vertices *v;
    size_t k;
} row;

static int cmp_vertex(const void *pa, const void *pb)
{
    const vb_periodic_vertices *v = ((const row *)pa)->v;
    size_t a = ((const row *)pa)->k, b = ((const row *)pb)->k;
    size_t ma = v->start[a + 1] - v->start[a], mb = v->start[b + 1] - v->start[b];
    size_t m = ma < mb ? ma : mb;
    int c = cmp_list(v->m + v->start[a], v->m + v->start[b], m);
    if (c)
        return c;
    if (ma != mb)
        return ma < mb ? -1 : 1;
    const double pa4[4] = {v->x[a], v->y[a], v->z[a], v->t[a]};
    const double pb4[4] = {v->x[b], v->y[b], v->z[b], v->t[b]};
    for (int k = 0; k < 4; k++)
        if (pa4[k] != pb4[k])
            return pa4[k] < pb4[k] ? -1 : 1;
    return 0;
}

/* What became of certified vertex k (keep_canonical). */
enum { ROW_KEPT = 0, ROW_BEYOND = 1, ROW_TRANSLATE = 2 };

typedef struct canon_job {
    const vb_vertex_list *c;
    const vb_periodic_images *img;
    vb_periodic_member *m;       /* c->nids members, vertex k's at c->start[k] */
    vb_periodic_member *scratch; /* 2 * widest per thread */
    size_t widest;
    uint8_t *fate;
} canon_job;

/* Vertex k alone: its members as atom@shift, sorted, and its fate. */
static void canon_one(void *ctx, size_t k, int tid)
{
    const canon_job *jb = ctx;
    const vb_vertex_list *c = jb->c;
    const vb_periodic_images *img = jb->img;
    size_t m = c->start[k + 1] - c->start[k];
    vb_periodic_member *mem = jb->m + c->start[k];
    for (size_t j = 0; j < m; j++) {
        uint32_t e = c->ids[c->start[k] + j];
        mem[j].id = img->atom[e];
        memcpy(mem[j].s, img->shift[e], sizeof mem[j].s);
    }
    qsort(mem, m, sizeof *mem, cmp_member_q);
    /* reach.c: a vertex with t above the bound at its point is no
     * periodic vertex. */
    if (c->t[k] > vb_periodic_bound_at(img, c->x[k], c->y[k], c->z[k]))
        jb->fate[k] = ROW_BEYOND;
    else if (!vb_periodic_is_canonical(mem, m, jb->scratch + 2 * jb->widest * (size_t)tid))
        jb->fate[k] = ROW_TRANSLATE;
    else
        jb->fate[k] = ROW_KEPT;
}

/* Keeps the canonical translates of the run's certified vertices with
 * t at most the bound at their point, sorted. Each vertex is decided on
 * its own (canon_one, on nt threads), then the kept ones are compacted in
 * order and sorted by a total order of their contents (vb_psort): the
 * same rows whatever nt is. */
static int keep_canonical(vb_ctx *ctx, vb_periodic_result *res, int nt)
{
    const vb_vertex_list *c = &res->run.certified;
    const vb_periodic_images *img = &res->img;
    vb_periodic_vertices all;
    memset(&all, 0, sizeof all);
    size_t nmax = c->n ? c->n : 1, idmax = c->nids ? c->nids : 1, widest = 4;
    for (size_t k = 0; k < c->n; k++)
        if (c->start[k + 1] - c->start[k] > widest)
            widest = c->start[k + 1] - c->start[k];
    all.start = malloc((nmax + 1) * sizeof *all.start);
    all.m = malloc(idmax * sizeof *all.m);
    all.x = malloc(nmax * sizeof *all.x);
    all.y = malloc(nmax * sizeof *all.y);
    all.z = malloc(nmax * sizeof *all.z);
    all.t = malloc(nmax * sizeof *all.t);
    vb_periodic_member *scratch = malloc(2 * widest * (size_t)nt * sizeof *scratch);
    vb_periodic_member *mem = malloc(idmax * sizeof *mem);
    uint8_t *fate = malloc(nmax);
    row *order = malloc(nmax * sizeof *order);
    if (!all.start || !all.m || !all.x || !all.y || !all.z || !all.t || !scratch || !mem ||
        !fate || !order) {
        vb_periodic_vertices_free(&all);
        free(scratch);
        free(mem);
        free(fate);
        free(order);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic vertices)");
    }
    canon_job jb = {c, img, mem, scratch, widest, fate};
    vb_parallel_for(canon_one, &jb, c->n, nt);
    all.start[0] = 0;
    size_t w = 0, used = 0;
    for (size_t k = 0; k < c->n; k++) {
        if (fate[k] != ROW_KEPT) {
            res->beyond_rho += fate[k] == ROW_BEYOND;
            res->translates += fate[k] == ROW_TRANSLATE;
            continue;
        }
        size_t m = c->start[k + 1] - c->start[k];
        memcpy(all.m + used, mem + c->start[k], m * sizeof *mem);
        all.x[w] = c->x[k];
        all.y[w] = c->y[k];
        all.z[w] = c->z[k];
        all.t[w] = c->t[k];
        used += m;
        all.start[++w] = used;
    }
    free(mem);
    free(fate);
    all.n = w;
    for (size_t k = 0; k < w; k++)
        order[k] = (row){&all, k};
    int rc = vb_psort(order, w, sizeof *order, cmp_vertex, nt);
    /* The sorted copy. */
    vb_periodic_vertices *v = &res->v;
    v->n = w;
    v->start = malloc((w + 1) * sizeof *v->start);
    v->m = malloc((used ? used : 1) * sizeof *v->m);
    v->x = malloc(nmax * sizeof *v->x);
    v->y = malloc(nmax * sizeof *v->y);
    v->z = malloc(nmax * sizeof *v->z);
    v->t = malloc(nmax * sizeof *v->t);
    if (rc == VB_OK)
        rc = v->start && v->m && v->x && v->y && v->z && v->t ? VB_OK : VB_ENOMEM;
    if (rc == VB_OK) {
        v->start[0] = 0;
        for (size_t k = 0; k < w; k++) {
            size_t a = order[k].k, m = all.start[a + 1] - all.start[a];
            memcpy(v->m + v->start[k], all.m + all.start[a], m * sizeof *v->m);
            v->start[k + 1] = v->start[k] + m;
            v->x[k] = all.x[a];
            v->y[k] = all.y[a];
            v->z[k] = all.z[a];
            v->t[k] = all.t[a];
        }
    }
    vb_periodic_vertices_free(&all);
    free(scratch);
    free(order);
    return rc == VB_OK ? VB_OK : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (periodic vertices)");
}

/* vb_periodic_vertices_run on the backends be, or on the engine e when
 * not NULL. */
static int periodic_run(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                        const vb_vertices_config *cfg, const vb_vertices_backends *be,
                        vb_vertices_engine *e, vb_periodic_result *res)
{
    if (cfg->proposer && strcmp(cfg->proposer, vb_proposer_cover.name) != 0)
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "periodic boxes need the direction cover (not --proposer %s): its "
                        "completeness is what proves the periodic list complete",
                        cfg->proposer);
    const vb_periodic_image_opt opt = {0.0, res->full_layer, 0.0};
    int rc = vb_periodic_images_build_opt(ctx, atoms, box, &opt, &res->img);
    if (rc != VB_OK)
        return rc;
    /* The cover covers the atoms' cells alone (the box's atoms come first,
     * their images after them), within the caller's split if any. */
    vb_cover_options co;
    memset(&co, 0, sizeof co);
    if (cfg->cover)
        co = *cfg->cover;
    co.base_limit = (uint32_t)res->img.n0;
    /* Only vertices with t <= rho can be periodic (images.c): the cover
     * need not find the others (vbq_floor), which spares the ring fetches
     * of cells that open into vacuum. The full layer (a reference) seeks
     * every vertex. */
    co.tmax = res->full_layer ? 0.0 : res->img.rho;
    vb_vertices_config c = *cfg;
    c.proposer = vb_proposer_cover.name;
    c.cover = &co;
    rc = e ? vb_vertices_run_on(ctx, e, res->img.set, &c, &res->run)
           : vb_vertices_run(ctx, res->img.set, &c, be, &res->run);
    if (rc == VB_OK && !res->run.proposal.complete)
        rc = vb_error(ctx, VB_EINTERNAL, NULL, 0, "the cover did not report a complete run");
    return rc == VB_OK ? keep_canonical(ctx, res, vb_threads(cfg->propose.threads)) : rc;
}

int vb_periodic_vertices_run(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                             const vb_vertices_config *cfg, const vb_vertices_backends *be,
                             vb_periodic_result *res)
{
    return periodic_run(ctx, atoms, box, cfg, be, NULL, res);
}

int vb_periodic_vertices_run_on(vb_ctx *ctx, vb_vertices_engine *e, const vb_sphere_set *atoms,
                                const vb_box *box, const vb_vertices_config *cfg,
                                vb_periodic_result *res)
{
    return periodic_run(ctx, atoms, box, cfg, NULL, e, res);
}

void vb_periodic_certificate(const vb_periodic_result *r, const vb_box *box, char *buf,
                             size_t size)
{
    char v[9][48];
    for (int k = 0; k < 9; k++)
        vb_decimal_format(box->ev[k], v[k], sizeof v[k]);
    snprintf(buf, size,
             "periodic: box a = (%s %s %s), b = (%s %s %s), c = (%s %s %s); ids i@(dx,dy,dz) = "
             "atom i moved by dx a + dy b + dz c\n"
             "complete: %zu certified vertices of the periodic diagram, each once (its canonical "
             "translate), every vertex of the diagram (direction cover of the %zu atoms' cells "
             "among %zu atoms and images; every empty sphere has radius <= %.9g, "
             "images within %.9g of the atoms and needed by the per-bin reach)",
             v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], r->v.n, r->img.n0,
             r->img.set ? r->img.set->n : 0, r->img.rho, r->img.reach);
}
