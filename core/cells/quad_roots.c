/* Both tangent spheres of every distinct quadruple (Fig. 8: one quadruple,
 * two vertices) from the double solver, each kept when no sphere cuts it by
 * more than a rounding guard; the point of the sampled candidate stands in
 * when the solver cannot separate the roots (the certifier decides). When
 * the root nearest the candidate is cut, the spheres near a
 * (near-)degenerate vertex are not the ones sampled: the quadruples with
 * one sphere swapped for the intruder are tried too (ours). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbs_match.h"

/* Intruder swaps tried from a sampled quadruple whose tangent sphere is not
 * empty (collinear and coplanar corpus cases need two). */
#define VBS_SWAP_DEPTH 2

/* A candidate with its sorted quadruple; sorted by quadruple, then by the
 * candidate's deterministic order. */
typedef struct qrec {
    uint32_t q[4];
    vbs_cand c;
} qrec;

/* Sort key of a quadruple record: quadruple, base, grid cell, rank, then the
 * record's position, so ties keep the input order as the stable merge sort
 * of qsort did (sorting the 80-byte records spends its time copying). */
typedef struct qkey {
    uint32_t k[7], idx;
} qkey;

static int cmp_qkey(const void *pa, const void *pb)
{
    const qkey *a = pa, *b = pb;
    for (int i = 0; i < 7; i++)
        if (a->k[i] != b->k[i])
            return a->k[i] < b->k[i] ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

/* The tangent spheres of quadruple q and what cuts them: intruder[k] is
 * VBS_INF_COLOUR for an empty sphere, else the deepest intruder for the root
 * nearest proto when want_intruder, else 0. Thread-safe with per-thread buf. */
typedef struct root_eval {
    int n, nearest;
    double roots[2][4];
    uint32_t intruder[2];
} root_eval;

int vbs_quad_roots(const vb_sphere_set *s, const uint32_t q[4], double roots[2][4])
{
    double sp[4][4];
    for (int k = 0; k < 4; k++) {
        uint32_t j = q[k];
        sp[k][0] = s->x[j];
        sp[k][1] = s->y[j];
        sp[k][2] = s->z[j];
        sp[k][3] = s->r[j];
    }
    return vbs_tangent_roots(sp, roots);
}

static int eval_roots(const vbs_roots *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int want_intruder, uint32_t **buf, size_t *cap, root_eval *ev)
{
    ev->n = vbs_quad_roots(e->set, q, ev->roots);
    if (ev->n == 0 && own) {
        /* Only a Newton point of this very quadruple may stand in. */
        ev->roots[0][0] = proto->x;
        ev->roots[0][1] = proto->y;
        ev->roots[0][2] = proto->z;
        ev->roots[0][3] = proto->t;
        ev->n = 1;
    }
    ev->nearest = 0;
    if (ev->n == 2) {
        double d[2];
        for (int k = 0; k < 2; k++) {
            double dx = ev->roots[k][0] - proto->x, dy = ev->roots[k][1] - proto->y,
                   dz = ev->roots[k][2] - proto->z;
            d[k] = dx * dx + dy * dy + dz * dz;
        }
        ev->nearest = d[1] < d[0];
    }
    for (int k = 0; k < ev->n; k++) {
        vbs_cand c = *proto;
        c.x = ev->roots[k][0];
        c.y = ev->roots[k][1];
        c.z = ev->roots[k][2];
        c.t = ev->roots[k][3];
        /* The roots come from a closed form in double: a guard of 1e-9 of
         * the scale covers their rounding; the certifier decides the rest. */
        double guard = e->guard * (1.0 + fabs(c.t));
        if (k == ev->nearest && want_intruder) {
            int rc = VB_OK;
            ev->intruder[k] = vbs_tangent_intruder(e->hash, &c, q, guard, buf, cap, &rc);
            if (rc != VB_OK)
                return rc;
        } else {
            ev->intruder[k] = vbs_tangent_empty(e->hash, &c, q, guard) ? VBS_INF_COLOUR : 0u;
        }
    }
    return VB_OK;
}

static int emit_roots(vbs_roots *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int depth);

/* Keeps the empty tangent spheres of ev; when the one nearest proto is cut,
 * tries the quadruples with its intruder swapped in, `depth` swaps deep. */
static int consume_roots(vbs_roots *e, const uint32_t q[4], const vbs_cand *proto,
                         const root_eval *ev, int depth)
{
    int rc = VB_OK;
    for (int k = 0; k < ev->n && rc == VB_OK; k++) {
        uint32_t j = ev->intruder[k];
        if (j == VBS_INF_COLOUR) {
            if (vb_vertex_list_push(&e->res->candidates, q, 4, ev->roots[k][0], ev->roots[k][1],
                                    ev->roots[k][2], ev->roots[k][3], 0.0, VB_VERTEX_CANDIDATE))
                rc = VB_ENOMEM;
            continue;
        }
        e->res->dropped++;
        if (k != ev->nearest || depth == 0)
            continue;
        vbs_cand c = *proto;
        c.x = ev->roots[k][0];
        c.y = ev->roots[k][1];
        c.z = ev->roots[k][2];
        c.t = ev->roots[k][3];
        for (int a = 0; a < 4 && rc == VB_OK; a++) {
            uint32_t q2[4];
            for (int b = 0; b < 4; b++)
                q2[b] = b == a ? j : q[b];
            vbs_sort4(q2);
            int fresh = vbs_qset_add(&e->seen, q2);
            if (fresh < 0)
                rc = VB_ENOMEM;
            else if (fresh) {
                e->res->swaps++;
                rc = emit_roots(e, q2, &c, 0, depth - 1);
            }
        }
    }
    return rc;
}

static int emit_roots(vbs_roots *e, const uint32_t q[4], const vbs_cand *proto, int own,
                      int depth)
{
    root_eval ev;
    int rc = eval_roots(e, q, proto, own, depth > 0, &e->qbuf, &e->qcap, &ev);
    return rc != VB_OK ? rc : consume_roots(e, q, proto, &ev, depth);
}

/* The sampled quadruples, evaluated in parallel (per-thread buffers). */
typedef struct sampled_ctx {
    const vbs_roots *e;
    const qrec *qs;
    const size_t *which;
    root_eval *ev;
    uint32_t *tbuf[VB_MAX_THREADS];
    size_t tcap[VB_MAX_THREADS];
    int err;
} sampled_ctx;

static void sampled_eval(void *arg, size_t i, int tid)
{
    sampled_ctx *c = arg;
    const qrec *r = c->qs + c->which[i];
    if (eval_roots(c->e, r->q, &r->c, 1, VBS_SWAP_DEPTH > 0, &c->tbuf[tid], &c->tcap[tid],
                   &c->ev[i]))
        c->err = VB_ENOMEM;
}


/* The raw candidates with their sorted quadruples, sorted by quadruple and
 * then by base, grid cell and rank (*qs allocated, *nq of them). */
static int sorted_quads(const vb_cand_vec *raw, int nthreads, qrec **out, size_t *nq)
{
    qrec *qs = malloc((raw->n + 1) * sizeof *qs);
    *out = NULL;
    *nq = 0;
    if (!qs)
        return VB_ENOMEM;
    size_t n = raw->n;
    for (size_t k = 0; k < n; k++) {
        qs[k].c = raw->v[k];
        memcpy(qs[k].q, raw->v[k].ids, sizeof qs[k].q);
        vbs_sort4(qs[k].q);
    }
    int rc = VB_OK;
    if (n) {
        qkey *ix = malloc(n * sizeof *ix);
        qrec *sorted = ix ? malloc(n * sizeof *sorted) : NULL;
        if (!sorted) {
            free(ix);
            rc = VB_ENOMEM;
        } else {
            for (size_t k = 0; k < n; k++) {
                const qrec *r = qs + k;
                ix[k] = (qkey){{r->q[0], r->q[1], r->q[2], r->q[3], r->c.ids[0], r->c.cell,
                                r->c.seq}, (uint32_t)k};
            }
            rc = vb_psort(ix, n, sizeof *ix, cmp_qkey, nthreads);
            for (size_t k = 0; rc == VB_OK && k < n; k++)
                sorted[k] = qs[ix[k].idx];
            free(ix);
            free(qs);
            qs = sorted;
        }
    }
    *out = qs;
    *nq = n;
    return rc;
}

int vbs_tangent_phase(vbs_roots *e, const vb_cand_vec *raw, int nthreads)
{
    qrec *qs;
    size_t nq;
    int rc = sorted_quads(raw, nthreads, &qs, &nq);
    /* Distinct quadruples (the first, deterministic, candidate of each);
     * the sampled ones are all marked seen before any swap is tried. */
    size_t *which = malloc((nq + 1) * sizeof *which), nw = 0;
    root_eval *evs = malloc((nq + 1) * sizeof *evs);
    uint32_t (*distinct)[4] = malloc((nq + 1) * sizeof *distinct);
    if (rc == VB_OK && (!which || !evs || !distinct))
        rc = VB_ENOMEM;
    for (size_t k = 0; rc == VB_OK && k < nq; k++)
        if (k == 0 || memcmp(qs[k].q, qs[k - 1].q, sizeof qs[k].q) != 0) {
            memcpy(distinct[nw], qs[k].q, sizeof distinct[nw]);
            which[nw++] = k;
        }
    if (rc == VB_OK)
        rc = vbs_qset_add_bulk(&e->seen, (const uint32_t(*)[4])distinct, nw, NULL, NULL, nthreads);
    free(distinct);
    if (rc == VB_OK) {
        sampled_ctx sc;
        memset(&sc, 0, sizeof sc);
        sc.e = e;
        sc.qs = qs;
        sc.which = which;
        sc.ev = evs;
        vb_parallel_for(sampled_eval, &sc, nw, nthreads);
        for (int t = 0; t < VB_MAX_THREADS; t++)
            free(sc.tbuf[t]);
        rc = sc.err;
    }
    for (size_t k = 0; rc == VB_OK && k < nw; k++)
        rc = consume_roots(e, qs[which[k]].q, &qs[which[k]].c, &evs[k], VBS_SWAP_DEPTH);
    free(which);
    free(evs);
    free(qs);
    return rc;
}

int vb_sampler_swap_candidates(const vb_sphere_set *set, const uint32_t ids[4],
                               uint32_t intruder, const double p[4], vb_vertex_list *out)
{
    for (int a = 0; a < 4; a++) {
        uint32_t q[4];
        double roots[2][4];
        for (int b = 0; b < 4; b++)
            q[b] = b == a ? intruder : ids[b];
        int n = vbs_quad_roots(set, q, roots);
        if (n == 0) {
            memcpy(roots[0], p, sizeof roots[0]);
            n = 1;
        }
        for (int k = 0; k < n; k++)
            if (vb_vertex_list_push(out, q, 4, roots[k][0], roots[k][1], roots[k][2],
                                    roots[k][3], 0.0, VB_VERTEX_CANDIDATE))
                return VB_ENOMEM;
    }
    return VB_OK;
}
