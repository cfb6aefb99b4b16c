/* The targeted search (Sec. 5.5) for incompletely matched vertices: each
 * missing member m shoots the ray from c_m to the vertex, centres a grid
 * cell on it of half the original size, and runs the vertex stage there
 * (Newton, subdivision) with m's coarse culling lists; the cell shrinks by
 * half until the vertex is found or the depth is spent. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbs_match.h"

static int cmp_work(const void *pa, const void *pb)
{
    const vbs_work *a = pa, *b = pb;
    if (a->base != b->base)
        return a->base < b->base ? -1 : 1;
    return (a->cluster > b->cluster) - (a->cluster < b->cluster);
}

/* Base m with its coarse culling lists (vbs_bis_store): sufficient for rays
 * anywhere on the sphere of directions, so the targeted search may place its
 * small cells anywhere. */
typedef struct full_base {
    vbs_base base;
    uint32_t off[6 * VBS_COARSE_T * VBS_COARSE_T + 1];
    const uint32_t *idx;
    unsigned T;
} full_base;

static void full_base_set(full_base *fb, const vb_sphere_set *s, const vbs_bis_store *st,
                          uint32_t m, double clip)
{
    size_t nt = 6u * (size_t)st->T * st->T, first = st->co_off[(size_t)m * nt];
    for (size_t k = 0; k <= nt; k++)
        fb->off[k] = (uint32_t)(st->co_off[(size_t)m * nt + k] - first);
    fb->idx = st->co_idx + first;
    fb->T = st->T;
    vbs_base *b = &fb->base;
    b->cx = s->x[m];
    b->cy = s->y[m];
    b->cz = s->z[m];
    b->r = s->r[m];
    b->scale = vbs_frame_scale(s->r[m]);
    b->clip = clip / b->scale;
    b->id = m;
    b->bis_start = 0;
    b->bis_count = (uint32_t)(st->off[m + 1] - st->off[m]);
    b->tile_start = 0;
}

/* The last resort of the targeted search: corners of ever smaller cells
 * around the vertex may never show all three other colours (a face that
 * meets the vertex in a thin wedge keeps its angle at every scale). Solve
 * the vertex's own triple from the ray towards it (d, length n, world
 * units from the base) and accept the point when it is that vertex and the
 * base's lower envelope along its ray reaches it: no other bisector comes
 * first, so the base's cell has the vertex. Returns 1 when found. */
static int targeted_triple(const full_base *fb, const vbs_bisector *bis, const vbs_params *p,
                           const vbs_cand *v, const double d[3], double n, vb_cand_vec *extra,
                           int *err)
{
    uint32_t ids[3];
    int k3 = 0;
    for (int a = 0; a < 4; a++)
        if (v->ids[a] != fb->base.id && k3 < 3)
            ids[k3++] = v->ids[a];
    vbs_bisector tri[3];
    for (int a = 0; a < k3; a++)
        if (!vbs_find_bisector(&fb->base, bis, ids[a], &tri[a]))
            return 0;
    double du[3] = {d[0] / n, d[1] / n, d[2] / n}, P[3], eq_tol = p->tol / fb->base.scale;
    vbs_u32 fl = VBS_CF_TARGETED;
    if (k3 != 3 || !vbs_solve_triple(tri, du, eq_tol, -1.0, p->sing, p->max_iter, P, &fl))
        return 0;
    double np = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]), u, w, dd[3], s;
    const double e[3] = {P[0] / np, P[1] / np, P[2] / np};
    vbs_u32 f = vbs_dir_face(e, &u, &w);
    vbs_envelope_at(&fb->base, bis, fb->off, fb->idx, fb->T, f, u, w, dd, &s);
    if (!(s >= np - eq_tol))
        return 0;
    vbs_cand c;
    vbs_emit em = {&c, 1u, 0u, 0u, 0xffffffffu};
    vbs_emit_point(&fb->base, ids[0], ids[1], ids[2], P, fl, &em);
    double dx = c.x - v->x, dy = c.y - v->y, dz = c.z - v->z;
    if (!(sqrt(dx * dx + dy * dy + dz * dz) <= p->tol))
        return 0;
    if (vb_cand_vec_push(extra, &c)) {
        *err = VB_ENOMEM;
        return 0;
    }
    return 1;
}

/* Sec. 5.5 for one (vertex, sphere): returns 1 when found; new candidates
 * (the vertex itself or neighbours revealed by the small cells) go to extra. */
static int targeted(const full_base *fb, const vbs_bisector *bis, const vbs_params *p,
                    const vbs_cand *v, unsigned depth, vb_cand_vec *extra, int *err)
{
    double d[3] = {v->x - fb->base.cx, v->y - fb->base.cy, v->z - fb->base.cz};
    double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(n > 0.0))
        return 0;
    double u, w;
    vbs_u32 f = vbs_dir_face(d, &u, &w);
    vbs_params q = *p;
    q.tiles = fb->T;
    double h = 0.5 * (2.0 / (double)(p->samples - 1u));
    for (unsigned lev = 0; lev < depth; lev++, h *= 0.5) {
        vbs_quad quad;
        quad.u0 = u - 0.5 * h;
        quad.v0 = w - 0.5 * h;
        quad.h = h;
        quad.depth = 0;
        for (int k = 0; k < 4; k++) {
            double dd[3], s;
            quad.col[k] = vbs_envelope_at(&fb->base, bis, fb->off, fb->idx, fb->T, f,
                                          quad.u0 + ((k & 1) ? h : 0.0),
                                          quad.v0 + ((k & 2) ? h : 0.0), dd, &s);
        }
        vbs_cand buf[VBS_MAX_CAND];
        vbs_emit em = {buf, VBS_MAX_CAND, 0u, 0u, 0xffffffffu};
        /* seq is set when the searches' results are merged in order. */
        vbs_process_cell(&fb->base, bis, fb->off, fb->idx, &q, f, &quad, VBS_CF_TARGETED,
                         &em);
        int found = 0;
        for (vbs_u32 k = 0; k < em.n; k++) {
            if (vb_cand_vec_push(extra, buf + k)) {
                *err = VB_ENOMEM;
                return 0;
            }
            double dx = buf[k].x - v->x, dy = buf[k].y - v->y, dz = buf[k].z - v->z;
            if (sqrt(dx * dx + dy * dy + dz * dz) <= p->tol)
                found = 1;
        }
        if (found)
            return 1;
    }
    return targeted_triple(fb, bis, p, v, d, n, extra, err);
}

/* The targeted searches of one run: item w searches vertex wk[w].cluster
 * from sphere wk[w].base; thread t keeps its candidates and their items. */
typedef struct tgt_ctx {
    const vb_sphere_set *set;
    const vbs_culler *cu;
    const vbs_params *params;
    const vb_cand_vec *raw;
    const vbs_clusters *m;
    const vbs_work *wk;
    unsigned depth;
    uint8_t *found;
    vb_cand_vec out[VB_MAX_THREADS];
    size_t *item[VB_MAX_THREADS];
    size_t item_cap[VB_MAX_THREADS];
    int err;
} tgt_ctx;

static void tgt_search(void *arg, size_t w, int tid)
{
    tgt_ctx *c = arg;
    uint32_t mb = c->wk[w].base;
    const vbs_bis_store *st = c->cu->store;
    if (st->off[mb + 1] == st->off[mb])
        return;
    full_base fb;
    full_base_set(&fb, c->set, st, mb, c->cu->clip);
    const vbs_cand *v = c->raw->v + c->m->cl_items[c->m->cl_start[c->wk[w].cluster]];
    size_t before = c->out[tid].n;
    int rc = VB_OK;
    c->found[w] = (uint8_t)targeted(&fb, st->bis + st->off[mb], c->params, v, c->depth,
                                    &c->out[tid], &rc);
    if (c->out[tid].n > c->item_cap[tid]) {
        size_t nc = c->out[tid].cap;
        size_t *p = realloc(c->item[tid], nc * sizeof *p);
        if (!p)
            rc = VB_ENOMEM;
        else {
            c->item[tid] = p;
            c->item_cap[tid] = nc;
        }
    }
    for (size_t k = before; rc == VB_OK && k < c->out[tid].n; k++)
        c->item[tid][k] = w;
    if (rc != VB_OK)
        c->err = rc;
}


int vbs_targeted_work(const vbs_clusters *m, const vb_cand_vec *raw, const uint8_t *plaus,
                      vbs_work **wk, size_t *nwk, size_t *wcap, vb_proposal *res)
{
    uint32_t *mem = malloc(4 * (raw->n + 1) * sizeof *mem);
    uint32_t *found = malloc((raw->n + 1) * sizeof *found);
    int rc = (!mem || !found) ? VB_ENOMEM : VB_OK;
    for (size_t c = 0; rc == VB_OK && c < m->ncl; c++) {
        size_t nm, nf = vbs_cluster_sets(m, raw, c, mem, &nm, found);
        size_t fi = 0;
        int complete = 1;
        int plausible = plaus[c];
        for (size_t q = 0; q < nm && plausible; q++) {
            while (fi < nf && found[fi] < mem[q])
                fi++;
            if (fi < nf && found[fi] == mem[q])
                continue;
            complete = 0;
            if (VB_ARRAY_FIT(*wk, *wcap, *nwk + 1, 256) != VB_OK) {
                rc = VB_ENOMEM;
                break;
            }
            (*wk)[(*nwk)++] = (vbs_work){mem[q], (uint32_t)c};
        }
        res->complete_first += (uint64_t)(complete && nf == nm);
        res->first_cell += (uint64_t)(plausible && found[0] == 0);
    }
    free(mem);
    free(found);
    return rc;
}

int vbs_targeted_search(const vb_sphere_set *set, const vbs_culler *cu, const vbs_params *params,
                        unsigned depth, int nthreads, const vb_cand_vec *raw,
                        const vbs_clusters *m, vbs_work *wk, size_t nwk, vb_cand_vec *extra,
                        vb_proposal *res)
{
    if (nwk == 0)
        return VB_OK;
    qsort(wk, nwk, sizeof *wk, cmp_work);
    tgt_ctx tc;
    memset(&tc, 0, sizeof tc);
    tc.set = set;
    tc.cu = cu;
    tc.params = params;
    tc.raw = raw;
    tc.m = m;
    tc.wk = wk;
    tc.depth = depth;
    tc.found = calloc(nwk, 1);
    int nt = nthreads, rc = VB_OK;
    if (!tc.found)
        rc = VB_ENOMEM;
    else
        vb_parallel_for(tgt_search, &tc, nwk, nt);
    if (rc == VB_OK && tc.err)
        rc = tc.err;
    /* Item w ran on thread w mod nt (vb_parallel_for): merge in work order. */
    size_t at[VB_MAX_THREADS] = {0};
    for (size_t w = 0; rc == VB_OK && w < nwk; w++) {
        int t = (int)(w % (size_t)(nt < 1 ? 1 : nt > VB_MAX_THREADS ? VB_MAX_THREADS : nt));
        res->targeted_searches++;
        res->targeted_found += tc.found[w];
        while (rc == VB_OK && at[t] < tc.out[t].n && tc.item[t][at[t]] == w) {
            vbs_cand c = tc.out[t].v[at[t]++];
            c.seq = (vbs_u32)extra->n;
            rc = vb_cand_vec_push(extra, &c);
        }
    }
    for (int t = 0; t < VB_MAX_THREADS; t++) {
        vb_cand_vec_free(&tc.out[t]);
        free(tc.item[t]);
    }
    free(tc.found);
    return rc;
}
