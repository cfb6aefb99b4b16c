/* vb_certify_quads: every exact root of every proposed quadruple, judged.
 *
 * Per quadruple, filter first (vbx_quad.h): the exact line in 128-bit
 * integers, the roots enclosed in double intervals. A root is refused when
 * the enclosures prove t + R_i < 0 for a member or a sphere inside its
 * tangent ball (the walk visits the nearest leaves first, so an intruder
 * usually comes early); it is certified when they prove t + R_i > 0 for
 * every member and every sphere the hierarchy cannot skip outside, and its
 * coordinates are then rounded from long double intervals. Only what the
 * enclosures cannot decide goes to GMP: the exact solve, then the exact
 * signs (vbx_cert_defining, the scan) of the roots left open, or just
 * vbx_root_coords for a certified root whose rounding was a near tie.
 *
 * Why a root certified by the filter has exactly the four members: every
 * other sphere was proven strictly outside, so the tangent sphere touches
 * only q. Its exact point can come from no other quadruple (one would be a
 * subset of the members), and the two roots of q are distinct points
 * (delta > 0), so such vertices need no key: only vertices of degree > 4,
 * which always take the exact path (their extra members touch exactly,
 * which no enclosure proves), are deduplicated through the certifier's keys.
 *
 * Threads as in vb_certify_list: workers take chunks of quadruples in
 * order and keep their vertices in chunk order; the merge walks the chunks
 * in order. Nothing a worker computes for a quadruple depends on the other
 * quadruples it judged, so the output and every counter are the same for
 * any thread count. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbd_cert_shared.h"
#include "vbx_cert.h"

#define QCHUNK 64
#define MIN_PER_THREAD 256

/* A certified root of one quadruple. */
typedef struct qrec {
    double xyzt[4];
    size_t quad;      /* index in the input */
    size_t moff;      /* nm > 4: members in the worker's pool */
    uint32_t nm;      /* 4: the members are the quadruple */
    int8_t sigma;     /* canonical root (keys) */
} qrec;

typedef struct qworker {
    vb_certifier *c;
    vb_ctx *ctx;
    const uint32_t (*quads)[4];
    const uint8_t *verdict;  /* NULL, or the certification filter's verdicts */
    size_t n;
    atomic_size_t *next;
    atomic_size_t *judged;   /* quadruples judged by every worker (progress) */
    uint32_t *chunk_worker;  /* per chunk: who judged it */
    size_t *chunk_first;     /* per chunk: its first record, and (next entry) the end */
    size_t *chunk_end;
    uint16_t index;
    qrec *rec;
    size_t nrec, rec_cap;
    uint32_t *pool;
    size_t npool, pool_cap;
    vb_cert_quad_stats st;
    int rc;
    size_t fail_at;
} qworker;

static int push_rec(qworker *w, size_t k, const double xyzt[4], const uint32_t *m, size_t nm,
                    int sigma)
{
    if (VB_ARRAY_FIT(w->rec, w->rec_cap, w->nrec + 1, 1024) != VB_OK)
        return vb_error(w->ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    qrec *r = &w->rec[w->nrec++];
    memcpy(r->xyzt, xyzt, sizeof r->xyzt);
    r->quad = k;
    r->nm = (uint32_t)nm;
    r->sigma = (int8_t)sigma;
    r->moff = 0;
    if (nm == 4)
        return VB_OK;
    if (VB_ARRAY_FIT(w->pool, w->pool_cap, w->npool + nm, 1024) != VB_OK)
        return vb_error(w->ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    memcpy(w->pool + w->npool, m, nm * sizeof *m);
    r->moff = w->npool;
    w->npool += nm;
    return VB_OK;
}

/* |p - c_j| - R_j - t over the enclosures (as in certifier.c). */
static vbx_ia distance_excess(const vbx_ia cj[4], const vbx_ia box[4])
{
    vbx_ia d2 = vbx_ia_sqr(vbx_ia_sub(box[0], cj[0]));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[1], cj[1])));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[2], cj[2])));
    return vbx_ia_sub(vbx_ia_sub(vbx_ia_sqrt(d2), cj[3]), box[3]);
}

enum { ROOT_REFUSED = 0, ROOT_EMPTY = 1, ROOT_OPEN = 2 };

/* The scan's second stage for sphere j, which root R's double box cannot
 * place: outside when t + R_j < 0 is proven (the distance exceeds t + R_j),
 * else, once t + R_j > 0 is proven, the sign of the power, which is the
 * distance's there: in doubles with a static bound first (vbx_qf_power_fast),
 * then in double intervals (vbx_qf_power_ia), then in
 * double-double (vbx_qf_power_sign). 0: still open. The radius difference
 * is exact in double below 2^53 and a sum rounded to nearest keeps its sign
 * (as in vbx_qf_tangent_sign). */
static int second_stage(qworker *w, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R,
                        const vbx_ia qs[4], const double mr[8], uint32_t j)
{
    const vbx_qdata *qd = &w->c->qd;
    int64_t rj = qd->z[4 * (size_t)j + 3] - qd->z[4 * (size_t)L->q[0] + 3];
    if (rj >= ((int64_t)1 << 53) || rj <= -((int64_t)1 << 53))
        return 0;
    double r = (double)rj;
    if (R->s.hi + r < 0.0)
        return 1;
    if (!(R->s.lo + r > 0.0))
        return 0;
    int sg = vbx_qf_power_fast(qd, L, mr, j);
    if (!sg)
        sg = vbx_qf_power_ia(qd, L, qs, j);
    if (!sg) {
        sg = qd->ops->power(qd, L, P, R, j);
        if (sg)
            w->st.power_signs_dd++;
    }
    if (sg)
        w->st.power_signs++;
    return sg;
}

/* The filter's verdict on root R of line L (R's s set; its point is
 * computed here once the tangency passes). */
static int filter_root(qworker *w, const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R)
{
    vb_stats *st = vb_ctx_stats(w->ctx);
    const vb_certifier *c = w->c;
    int open = 0;
    for (int i = 0; i < 4; i++) {
        st->filter_calls++;
        int sg = vbx_qf_tangent_sign(L, R->s, i);
        if (sg < 0) {
            w->st.refused_tangent++;
            return ROOT_REFUSED;
        }
        if (sg == 0) {
            st->filter_failures++;
            open = 1;
        }
    }
    if (!c->qd.ops->point(&c->qd, L, P, R)) {
        st->filter_failures++;
        return ROOT_OPEN;
    }
    const vbx_ia *p = R->p;
    const uint32_t *q = L->q;
    const vbx_sindex *t = &c->t;
    vbx_probe pr;
    vbx_probe_init(&pr, t, p);
    vbx_walk walk;
    vbx_walk_init(&walk, t, p);
    vbx_ia qs[4];
    double mr[8];
    int have_qs = 0;
    /* A far root (t ~ 10^10 on a jittered face): the distance's double box
     * cannot place what the probes leave open, the power mostly can, so it
     * goes first. Each gives the exact sign or none: speed only. */
    int far = p[3].lo > 1e6;
    /* ... and there the scan would meet every sphere of the face layer (the
     * distance's bound skips no node the ball's flat side touches): the
     * power bound of a node clears whole groups off the vertex's own
     * neighbours (speed only: the spheres it clears are outside). */
    vbx_qf_group fg = {&c->qd, L, mr, t->rmin};
    if (far) {
        vbx_qf_power_qs(&c->qd, L, R, qs);
        vbx_qf_power_mr(qs, mr);
        have_qs = 1;
        vbx_walk_skip(&walk, vbx_qf_group_outside, &fg);
    }
    size_t s0, s1;
    uint64_t calls = 0, failures = 0;
    int verdict = ROOT_EMPTY;
    while (verdict == ROOT_EMPTY && vbx_walk_next(&walk, &s0, &s1))
        for (size_t s = s0; s < s1; s++) {
            calls++;
            const double *cm = &t->mid[4 * s];
            if (vbx_probe_outside(&pr, cm))
                continue;
            uint32_t j = t->ids[s];
            if (j == q[0] || j == q[1] || j == q[2] || j == q[3]) {
                calls--;
                continue;
            }
            const vbx_ia *cj = &t->box[4 * s];
            int sg = vbx_probe_inside(&pr, cm, cj[3].lo) ? -1
                     : far                               ? 0
                                                         : vbx_ia_sign(distance_excess(cj, p));
            if (sg == 0) {
                if (!have_qs) {
                    vbx_qf_power_qs(&c->qd, L, R, qs);
                    vbx_qf_power_mr(qs, mr);
                }
                have_qs = 1;
                sg = second_stage(w, L, P, R, qs, mr, j);
            }
            if (sg == 0 && far)
                sg = vbx_ia_sign(distance_excess(cj, p));
            if (sg > 0)
                continue;
            if (sg < 0) {
                verdict = ROOT_REFUSED;
                break;
            }
            failures++;
            open = 1;
        }
    st->filter_calls += calls;
    st->filter_failures += failures;
    if (verdict == ROOT_REFUSED) {
        w->st.refused_intruder++;
        return ROOT_REFUSED;
    }
    return open ? ROOT_OPEN : ROOT_EMPTY;
}

/* What the exact path still has to do for a root. */
enum { NEED_NOTHING = 0, NEED_ROUND = 1, NEED_ALL = 2 };

/* The exact path for quadruple k: need[r] per root of the exact solver
 * (root r is the filter's root r), or NULL to judge every root. */
static int exact_quad(qworker *w, size_t k, const int *need)
{
    vb_certifier *c = w->c;
    vb_ctx *ctx = w->ctx;
    vb_stats *st = vb_ctx_stats(ctx);
    const uint32_t *q = w->quads[k];
    st->exact_evals++;
    w->st.exact_solves++;
    /* SINGULAR: the rows have rank < 3 (vbx_certify_one's NO_SOLUTION or
     * UNDETERMINED); UNDETERMINED: a line of tangent spheres. Neither names
     * a vertex. */
    if (vbx_solve(&c->sol, q[0], q + 1) != VBX_SOLVED)
        return VB_OK;
    if (need && c->sol.nroots != 2)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0,
                        "the filter and the exact solver disagree on quadruple %u %u %u %u",
                        q[0], q[1], q[2], q[3]);
    for (int r = 0; r < c->sol.nroots; r++) {
        int mode = need ? need[r] : NEED_ALL;
        if (mode == NEED_NOTHING)
            continue;
        const vbx_root *root = &c->sol.root[r];
        double xyzt[4];
        vbx_ia box[4];
        int rc = vbx_cert_round(ctx, c, root, xyzt, box);
        if (rc != VB_OK)
            return rc;
        if (mode == NEED_ROUND) {
            w->st.roots_round_exact++;
            rc = push_rec(w, k, xyzt, q, 4, root->sigma);
            if (rc != VB_OK)
                return rc;
            continue;
        }
        w->st.roots_exact++;
        if (!vbx_cert_defining(ctx, c, root, q, 4, box))
            continue;
        int verdict;
        vbx_cert_scan_empty(ctx, c, root, q, 4, box, &verdict);
        if (verdict != VB_CERT_OK)
            continue;
        int sigma;
        rc = vbx_cert_identity(ctx, c, root, &sigma);
        if (rc == VB_OK)
            rc = push_rec(w, k, xyzt, c->members, c->nmembers, sigma);
        if (rc != VB_OK)
            return rc;
    }
    return VB_OK;
}

/* Root r of a prepared line proven a vertex by the certification filter:
 * only its coordinates, rounded (NEED_ROUND when double-double cannot). */
static int judged_root(qworker *w, size_t k, const vbx_qline *L, const vbx_qprep *P, int r,
                       int *need)
{
    const vbx_qf_ops *ops = w->c->qd.ops;
    vbx_qroot R;
    ops->root(P, r, &R);
    double xyzt[4];
    if (ops->point(&w->c->qd, L, P, &R) && ops->round(&R, xyzt)) {
        w->st.roots_fast++;
        return push_rec(w, k, xyzt, w->quads[k], 4, r ? -1 : 1);
    }
    *need = NEED_ROUND;
    return VB_OK;
}

/* What the exact path does for a root with verdict v. */
static int need_of(unsigned v)
{
    return v == VBD_VERTEX ? NEED_ROUND : v == VBD_NOT ? NEED_NOTHING : NEED_ALL;
}

static int judge_quad(qworker *w, size_t k)
{
    vb_certifier *c = w->c;
    vb_stats *st = vb_ctx_stats(w->ctx);
    const uint32_t *q = w->quads[k];
    size_t nrec0 = w->nrec;
    uint64_t solves0 = w->st.exact_solves;
    st->candidates++;
    w->st.quads++;
    unsigned v[2] = {VBD_OPEN, VBD_OPEN};
    if (w->verdict) {
        v[0] = VBD_ROOT(w->verdict[k], 0);
        v[1] = VBD_ROOT(w->verdict[k], 1);
        for (int r = 0; r < 2; r++) {
            w->st.judged_vertex += v[r] == VBD_VERTEX;
            w->st.judged_not += v[r] == VBD_NOT;
            w->st.judged_open += v[r] == VBD_OPEN;
        }
    }
    vbx_qline L;
    vbx_qprep P;
    int fs = VBX_QF_EXACT, rc = VB_OK;
    if (v[0] == VBD_NOT && v[1] == VBD_NOT) {
        st->rejected++;
        w->st.rejected_fast++;
        return VB_OK;
    }
    st->filter_calls++;
    const vbx_qf_ops *ops = c->qd.ops;
    if (ops->line(&c->qd, q, &L))
        fs = ops->prep(&L, &P);
    if (fs != VBX_QF_TWO && (v[0] != VBD_OPEN || v[1] != VBD_OPEN)) {
        /* The verdicts proved two distinct roots (D, A != 0, delta > 0). */
        if (fs == VBX_QF_NONE)
            return vb_error(w->ctx, VB_EINTERNAL, NULL, 0,
                            "the certification filter and the certifier's filter disagree on "
                            "quadruple %u %u %u %u",
                            q[0], q[1], q[2], q[3]);
        st->filter_failures++;
        w->st.quads_exact++;
        int need[2] = {need_of(v[0]), need_of(v[1])};
        rc = exact_quad(w, k, need);
    } else if (fs == VBX_QF_NONE) {
        w->st.no_root++;
    } else if (fs == VBX_QF_EXACT) {
        st->filter_failures++;
        w->st.quads_exact++;
        rc = exact_quad(w, k, NULL);
    } else {
        int need[2] = {NEED_NOTHING, NEED_NOTHING};
        for (int r = 0; r < 2 && rc == VB_OK; r++) {
            if (v[r] == VBD_NOT)
                continue;
            if (v[r] == VBD_VERTEX) {
                rc = judged_root(w, k, &L, &P, r, &need[r]);
                continue;
            }
            vbx_qroot R;
            ops->root(&P, r, &R);
            int fv = filter_root(w, &L, &P, &R);
            if (fv == ROOT_OPEN) {
                need[r] = NEED_ALL;
            } else if (fv == ROOT_EMPTY) {
                double xyzt[4];
                if (ops->round(&R, xyzt)) {
                    w->st.roots_fast++;
                    rc = push_rec(w, k, xyzt, q, 4, r ? -1 : 1);
                } else {
                    need[r] = NEED_ROUND;
                }
            }
        }
        if (rc == VB_OK && (need[0] || need[1]))
            rc = exact_quad(w, k, need);
    }
    if (w->nrec == nrec0) {
        st->rejected++;
        if (w->st.exact_solves == solves0)
            w->st.rejected_fast++;
    }
    return rc;
}

static void *work(void *arg)
{
    qworker *w = arg;
    for (;;) {
        size_t k0 = atomic_fetch_add(w->next, QCHUNK);
        if (k0 >= w->n)
            break;
        size_t k1 = k0 + QCHUNK < w->n ? k0 + QCHUNK : w->n, ch = k0 / QCHUNK;
        w->chunk_worker[ch] = w->index;
        w->chunk_first[ch] = w->nrec;
        for (size_t k = k0; k < k1; k++) {
            int rc = judge_quad(w, k);
            if (rc != VB_OK) {
                w->rc = rc;
                w->fail_at = k;
                w->chunk_end[ch] = w->nrec;
                return NULL;
            }
        }
        w->chunk_end[ch] = w->nrec;
        vb_progress(w->ctx, "certify", atomic_fetch_add(w->judged, k1 - k0) + (k1 - k0), w->n);
    }
    return NULL;
}

static void add_qstats(vb_cert_quad_stats *to, const vb_cert_quad_stats *from)
{
    to->quads += from->quads;
    to->no_root += from->no_root;
    to->refused_tangent += from->refused_tangent;
    to->refused_intruder += from->refused_intruder;
    to->rejected_fast += from->rejected_fast;
    to->roots_fast += from->roots_fast;
    to->roots_round_exact += from->roots_round_exact;
    to->roots_exact += from->roots_exact;
    to->quads_exact += from->quads_exact;
    to->exact_solves += from->exact_solves;
    to->mpfr_rounds += from->mpfr_rounds;
    to->power_signs += from->power_signs;
    to->power_signs_dd += from->power_signs_dd;
    to->judged_vertex += from->judged_vertex;
    to->judged_not += from->judged_not;
    to->judged_open += from->judged_open;
}

/* ---- the merge ------------------------------------------------------------ */

typedef struct vref {
    const uint32_t *m;
    size_t nm;
    const double *xyzt;
} vref;

static int cmp_double(double a, double b)
{
    return (a > b) - (a < b);
}

/* The order of vb_vertex_list_sort: ids lexicographically (a prefix first),
 * then x, y, z, t. */
static int cmp_vref(const vref *a, const vref *b)
{
    size_t m = a->nm < b->nm ? a->nm : b->nm;
    for (size_t i = 0; i < m; i++)
        if (a->m[i] != b->m[i])
            return a->m[i] < b->m[i] ? -1 : 1;
    if (a->nm != b->nm)
        return a->nm < b->nm ? -1 : 1;
    for (int k = 0; k < 4; k++) {
        int c = cmp_double(a->xyzt[k], b->xyzt[k]);
        if (c)
            return c;
    }
    return 0;
}

static int cmp_vref_q(const void *pa, const void *pb)
{
    return cmp_vref(pa, pb);
}

static vref ref_of(const qworker *ws, const uint32_t (*quads)[4], uint32_t wi, const qrec *r)
{
    vref v = {r->nm == 4 ? quads[r->quad] : ws[wi].pool + r->moff, r->nm, r->xyzt};
    return v;
}

static int push_ref(vb_vertex_list *out, const vref *v)
{
    return vb_vertex_list_push(out, v->m, v->nm, v->xyzt[0], v->xyzt[1], v->xyzt[2],
                               v->xyzt[3], 0.0, VB_VERTEX_CERTIFIED);
}

/* Vertex k of a list as a reference (its t and x, y, z are not adjacent:
 * copied into buf). */
static vref ref_list(const vb_vertex_list *v, size_t k, double buf[4])
{
    buf[0] = v->x[k];
    buf[1] = v->y[k];
    buf[2] = v->z[k];
    buf[3] = v->t[k];
    vref r = {v->ids + v->start[k], v->start[k + 1] - v->start[k], buf};
    return r;
}

static int merge(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4], size_t n,
                 qworker *ws, const uint32_t *chunk_worker, const size_t *chunk_first,
                 const size_t *chunk_end, vb_vertex_list *out, vb_cert_quad_stats *qs)
{
    size_t nch = (n + QCHUNK - 1) / QCHUNK, total = 0;
    for (size_t ch = 0; ch < nch; ch++)
        total += chunk_end[ch] - chunk_first[ch];
    vref *four = malloc((total ? total : 1) * sizeof *four);
    vref *more = malloc((total ? total : 1) * sizeof *more);
    size_t nfour = 0, nmore = 0;
    size_t *where = NULL, nwhere = 0; /* key -> 1 when written in this call, else SIZE_MAX */
    int rc = four && more ? VB_OK : VB_ENOMEM;
    for (size_t ch = 0; ch < nch && rc == VB_OK; ch++) {
        uint32_t wi = chunk_worker[ch];
        for (size_t i = chunk_first[ch]; i < chunk_end[ch] && rc == VB_OK; i++) {
            vref v = ref_of(ws, quads, wi, &ws[wi].rec[i]);
            if (v.nm == 4) {
                /* Quadruples are sorted, so these come in order but for the
                 * two roots of one quadruple. */
                if (nfour && v.m == four[nfour - 1].m && cmp_vref(&v, &four[nfour - 1]) < 0) {
                    four[nfour] = four[nfour - 1];
                    four[nfour - 1] = v;
                } else {
                    four[nfour] = v;
                }
                nfour++;
                continue;
            }
            size_t key;
            rc = vbx_cert_key_of(ctx, c, v.m, v.nm, ws[wi].rec[i].sigma, &key);
            if (rc != VB_OK)
                break;
            rc = vbx_where_fit(&where, &nwhere, key);
            if (rc != VB_OK)
                break;
            if (where[key] != SIZE_MAX) {
                qs->duplicates++;
                continue;
            }
            where[key] = 1;
            more[nmore++] = v;
        }
    }
    free(where);
    if (rc == VB_OK)
        qsort(more, nmore, sizeof *more, cmp_vref_q);
    size_t old = out->n, a = 0, b = 0;
    while (rc == VB_OK && (a < nfour || b < nmore)) {
        if (b == nmore || (a < nfour && cmp_vref(&four[a], &more[b]) <= 0))
            rc = push_ref(out, &four[a++]);
        else
            rc = push_ref(out, &more[b++]);
    }
    free(four);
    free(more);
    if (rc == VB_OK) {
        qs->vertices += out->n - old;
        vb_ctx_stats(ctx)->certified += out->n - old;
    }
    /* Appended after earlier vertices: sort only when they interleave. */
    if (rc == VB_OK && old > 0 && out->n > old) {
        double b1[4], b2[4];
        vref last = ref_list(out, old - 1, b1), first = ref_list(out, old, b2);
        if (cmp_vref(&last, &first) > 0)
            rc = vb_vertex_list_sort(out);
    }
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    return rc;
}

/* Sorted ids in range, quadruples strictly increasing. */
static int check_quads(vb_ctx *ctx, const vb_certifier *c, const uint32_t (*quads)[4], size_t n)
{
    for (size_t k = 0; k < n; k++) {
        const uint32_t *q = quads[k];
        int bad = !(q[0] < q[1] && q[1] < q[2] && q[2] < q[3]) || q[3] >= c->set->n;
        if (!bad && k > 0) {
            const uint32_t *p = quads[k - 1];
            int i = 0;
            while (i < 4 && p[i] == q[i])
                i++;
            bad = i == 4 || p[i] > q[i];
        }
        if (bad)
            return vb_error(ctx, VB_EMISUSE, NULL, 0,
                            "vb_certify_quads: quadruple %zu (%u %u %u %u) is not sorted, "
                            "distinct and after the one before it",
                            k, q[0], q[1], q[2], q[3]);
    }
    return VB_OK;
}

int vb_certify_quads(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4], size_t n,
                     vb_vertex_list *out, vb_cert_quad_stats *stats)
{
    return vb_certify_quads_judged(ctx, c, quads, NULL, n, out, stats);
}

int vb_certify_quads_judged(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4],
                            const uint8_t *verdict, size_t n, vb_vertex_list *out,
                            vb_cert_quad_stats *stats)
{
    vb_cert_quad_stats qs;
    memset(&qs, 0, sizeof qs);
    int rc = check_quads(ctx, c, quads, n);
    if (rc != VB_OK)
        return rc;
    unsigned nt = (unsigned)vb_threads(c->threads);
    size_t most = n / MIN_PER_THREAD;
    if (most < 1)
        most = 1;
    if (nt > most)
        nt = (unsigned)most;
    size_t nch = (n + QCHUNK - 1) / QCHUNK, nch1 = nch ? nch : 1;
    qworker *ws = calloc(nt, sizeof *ws);
    uint32_t *chunk_worker = malloc(nch1 * sizeof *chunk_worker);
    size_t *chunk_first = malloc(nch1 * sizeof *chunk_first);
    size_t *chunk_end = malloc(nch1 * sizeof *chunk_end);
    if (!ws || !chunk_worker || !chunk_first || !chunk_end) {
        free(ws);
        free(chunk_worker);
        free(chunk_first);
        free(chunk_end);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certifier)");
    }
    atomic_size_t next, judged;
    atomic_init(&next, 0);
    atomic_init(&judged, 0);
    vb_progress(ctx, "certify", 0, n);
    uint64_t slow0 = c->sol.slow_rounds;
    for (unsigned i = 0; i < nt; i++) {
        ws[i].quads = quads;
        ws[i].verdict = verdict;
        ws[i].n = n;
        ws[i].next = &next;
        ws[i].judged = &judged;
        ws[i].chunk_worker = chunk_worker;
        ws[i].chunk_first = chunk_first;
        ws[i].chunk_end = chunk_end;
        ws[i].index = (uint16_t)i;
        ws[i].fail_at = SIZE_MAX;
        ws[i].rc = VB_OK;
    }
    ws[0].c = c;
    ws[0].ctx = ctx;
    for (unsigned i = 1; i < nt && rc == VB_OK; i++) {
        ws[i].c = vbx_certifier_worker(c);
        if (!ws[i].c || vb_open_worker(&ws[i].ctx, ctx) != VB_OK)
            rc = VB_ENOMEM;
    }
    /* A thread that cannot start has its share run by the caller. */
    if (rc == VB_OK)
        vb_run_jobs(work, ws, sizeof *ws, (int)nt);
    qs.mpfr_rounds += c->sol.slow_rounds - slow0;
    add_qstats(&qs, &ws[0].st);
    for (unsigned i = 1; i < nt; i++) {
        if (ws[i].ctx)
            vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(ws[i].ctx));
        if (ws[i].c) {
            qs.mpfr_rounds += ws[i].c->sol.slow_rounds;
            c->slow_rounds += ws[i].c->sol.slow_rounds;
        }
        add_qstats(&qs, &ws[i].st);
    }
    vb_stats *cst = vb_ctx_stats(ctx);
    cst->judged_vertex += qs.judged_vertex;
    cst->judged_not += qs.judged_not;
    cst->judged_open += qs.judged_open;
    if (rc != VB_OK) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certifier threads)");
    } else {
        int bad = vb_jobs_first_error(ws, sizeof *ws, (int)nt, offsetof(qworker, rc),
                                      offsetof(qworker, fail_at));
        if (bad > 0)
            rc = vb_error(ctx, ws[bad].rc, NULL, 0, "%s", vb_errmsg(ws[bad].ctx));
        else
            rc = ws[0].rc;
    }
    if (rc == VB_OK)
        rc = merge(ctx, c, quads, n, ws, chunk_worker, chunk_first, chunk_end, out, &qs);
    for (unsigned i = 0; i < nt; i++) {
        free(ws[i].rec);
        free(ws[i].pool);
        if (i > 0) {
            vb_certifier_close(ws[i].c);
            vb_close(ws[i].ctx);
        }
    }
    free(ws);
    free(chunk_worker);
    free(chunk_first);
    free(chunk_end);
    if (stats)
        *stats = qs;
    return rc;
}
