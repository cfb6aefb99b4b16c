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
 * Two degenerate quadruples need no GMP solve either (vbx_quad.h): rows of
 * rank < 3 proven in integers (VBX_QL_FLAT: the squares of an exact
 * crystal) have no root, as the exact solver would find; and where delta
 * is exactly 0 (GMP integers decide it from the line's exact v and U), the
 * one root mu = -B / A goes through the same filter as any root, with the
 * exact solver's sigma 0.
 *
 * Why a root certified by the filter has exactly the four members: every
 * other sphere was proven strictly outside, so the tangent sphere touches
 * only q. Its exact point can come from no other quadruple (one would be a
 * subset of the members), and the roots of q are distinct points (delta > 0,
 * or one root), so such vertices need no key: only vertices of degree > 4,
 * which always take the exact path (their extra members touch exactly,
 * which no enclosure proves), are deduplicated through the certifier's keys.
 *
 * A vertex of degree > 4 is open in each quadruple of its members: an open
 * root whose quadruple's other root a filter refused or certified, or that
 * is its quadruple's only root, is a tie (certify_ties.c). The ties wait
 * until every quadruple is judged; then, in quadruple order, the first of
 * each group of meeting enclosures is solved exactly, and a later one whose
 * quadruple lies within the members of its leader's vertex is that vertex
 * (a duplicate: no exact path); the others are solved as before. The
 * grouping depends on the ties alone, and a tie's record is merged after
 * its quadruple's other root, where judge_quad would have pushed it, so the
 * merge keeps the same first root of each vertex.
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
#include "vbx_qties.h"

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
    size_t *chunk_tfirst; /* per chunk: its first tie, and the end */
    size_t *chunk_tend;
    vbx_qtie *ties;     /* the exact paths of ties: all ties, */
    const size_t *todo; /* ... those to solve, */
    size_t ntodo;
    atomic_size_t *tnext; /* ... the next of todo to take */
    uint16_t index;
    qrec *rec;
    size_t nrec, rec_cap;
    uint32_t *pool;
    size_t npool, pool_cap;
    vbx_qtie *tie; /* the ties this worker met, in chunk order */
    size_t ntie, tie_cap;
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

/* What the exact path still has to do for a root. */
enum { NEED_NOTHING = 0, NEED_ROUND = 1, NEED_ALL = 2 };

/* The exact path for quadruple k: need[r] per root of the exact solver
 * (root r is the filter's root r, of the filter's nroots), or NULL to judge
 * every root. */
static int exact_quad(qworker *w, size_t k, const int *need, int nroots)
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
    if (need && c->sol.nroots != nroots)
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

static int push_tie(qworker *w, size_t k, int r, int nroots, const vbx_ia p[4], int had_rec)
{
    if (VB_ARRAY_FIT(w->tie, w->tie_cap, w->ntie + 1, 256) != VB_OK)
        return vb_error(w->ctx, VB_ENOMEM, NULL, 0, "out of memory (tie vertices)");
    vbx_qtie *t = &w->tie[w->ntie++];
    for (int a = 0; a < 3; a++) {
        t->lo[a] = p[a].lo;
        t->hi[a] = p[a].hi;
    }
    t->quad = k;
    t->leader = SIZE_MAX;
    t->rec = SIZE_MAX;
    t->wi = 0;
    t->root = (int8_t)r;
    t->nroots = (int8_t)nroots;
    t->skipped = 0;
    t->had_rec = (uint8_t)had_rec;
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
    int ls = ops->line(&c->qd, q, &L);
    if (ls == VBX_QL_LINE) {
        fs = ops->prep(&L, &P);
        w->st.delta_exact += P.delta_exact;
        st->exact_evals += P.delta_exact;
    }
    if (fs != VBX_QF_TWO && (v[0] != VBD_OPEN || v[1] != VBD_OPEN)) {
        /* The verdicts proved two distinct roots (D, A != 0, delta > 0). */
        if (fs == VBX_QF_NONE || fs == VBX_QF_ONE || ls == VBX_QL_FLAT)
            return vb_error(w->ctx, VB_EINTERNAL, NULL, 0,
                            "the certification filter and the certifier's filter disagree on "
                            "quadruple %u %u %u %u",
                            q[0], q[1], q[2], q[3]);
        st->filter_failures++;
        w->st.quads_exact++;
        int need[2] = {need_of(v[0]), need_of(v[1])};
        rc = exact_quad(w, k, need, 2);
    } else if (ls == VBX_QL_FLAT) {
        w->st.flat++;
    } else if (fs == VBX_QF_NONE) {
        w->st.no_root++;
    } else if (fs == VBX_QF_EXACT) {
        st->filter_failures++;
        w->st.quads_exact++;
        rc = exact_quad(w, k, NULL, 0);
    } else {
        /* Two roots, or the one root of delta = 0 (the exact solver's
         * sigma 0). */
        int nr = fs == VBX_QF_ONE ? 1 : 2;
        w->st.one_root += nr == 1;
        int need[2] = {NEED_NOTHING, NEED_NOTHING}, placed[2] = {0, 0};
        vbx_qroot R[2];
        for (int r = 0; r < nr && rc == VB_OK; r++) {
            if (v[r] == VBD_NOT)
                continue;
            if (v[r] == VBD_VERTEX) {
                rc = judged_root(w, k, &L, &P, r, &need[r]);
                continue;
            }
            ops->root(&P, r, &R[r]);
            int fv = vbx_qfilter_root(w->ctx, c, &w->st, &L, &P, &R[r]);
            if (fv == ROOT_OPEN || fv == ROOT_UNPLACED) {
                need[r] = NEED_ALL;
                placed[r] = fv == ROOT_OPEN;
            } else if (fv == ROOT_EMPTY) {
                double xyzt[4];
                if (ops->round(&R[r], xyzt)) {
                    w->st.roots_fast++;
                    rc = push_rec(w, k, xyzt, q, 4, nr == 1 ? 0 : r ? -1 : 1);
                } else {
                    need[r] = NEED_ROUND;
                }
            }
        }
        /* One open root, the other refused or certified by a filter (or
         * none): a tie whose exact path waits (certify_ties.c); the
         * quadruple's counts wait with it. */
        for (int r = 0; r < nr && rc == VB_OK; r++)
            if (need[r] == NEED_ALL && placed[r] && need[1 - r] == NEED_NOTHING)
                return push_tie(w, k, r, nr, R[r].p, w->nrec != nrec0);
        if (rc == VB_OK && (need[0] || need[1]))
            rc = exact_quad(w, k, need, nr);
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
        w->chunk_tfirst[ch] = w->ntie;
        for (size_t k = k0; k < k1; k++) {
            int rc = judge_quad(w, k);
            if (rc != VB_OK) {
                w->rc = rc;
                w->fail_at = k;
                w->chunk_end[ch] = w->nrec;
                w->chunk_tend[ch] = w->ntie;
                return NULL;
            }
        }
        w->chunk_end[ch] = w->nrec;
        w->chunk_tend[ch] = w->ntie;
        vb_progress(w->ctx, "certify", atomic_fetch_add(w->judged, k1 - k0) + (k1 - k0), w->n);
    }
    return NULL;
}

/* The exact paths of the ties w->todo names, a few at a time. */
static void *work_ties(void *arg)
{
    qworker *w = arg;
    for (;;) {
        size_t i0 = atomic_fetch_add(w->tnext, 16);
        if (i0 >= w->ntodo)
            break;
        size_t i1 = i0 + 16 < w->ntodo ? i0 + 16 : w->ntodo;
        for (size_t i = i0; i < i1; i++) {
            vbx_qtie *t = &w->ties[w->todo[i]];
            int need[2] = {NEED_NOTHING, NEED_NOTHING};
            need[t->root] = NEED_ALL;
            size_t nrec0 = w->nrec;
            int rc = exact_quad(w, t->quad, need, t->nroots);
            if (rc != VB_OK) {
                w->rc = rc;
                w->fail_at = t->quad;
                return NULL;
            }
            if (w->nrec > nrec0) {
                t->rec = nrec0;
                t->wi = w->index;
            }
        }
    }
    return NULL;
}

/* Runs the exact paths of ties todo[0..n) on the workers; VB_OK or the
 * first error (as one thread taking the quadruples in order meets it). */
static int run_ties(vb_ctx *ctx, qworker *ws, unsigned nt, vbx_qtie *ties, const size_t *todo,
                    size_t n)
{
    atomic_size_t tnext;
    atomic_init(&tnext, 0);
    for (unsigned i = 0; i < nt; i++) {
        ws[i].ties = ties;
        ws[i].todo = todo;
        ws[i].ntodo = n;
        ws[i].tnext = &tnext;
    }
    unsigned nrun = n / 16 + 1 < nt ? (unsigned)(n / 16 + 1) : nt;
    vb_run_jobs(work_ties, ws, sizeof *ws, (int)nrun);
    int bad = vb_jobs_first_error(ws, sizeof *ws, (int)nrun, offsetof(qworker, rc),
                                  offsetof(qworker, fail_at));
    if (bad > 0)
        return vb_error(ctx, ws[bad].rc, NULL, 0, "%s", vb_errmsg(ws[bad].ctx));
    return bad == 0 ? ws[0].rc : VB_OK;
}

/* The ties of every chunk in quadruple order, grouped; the first of each
 * group solved, then each later one that its leader's vertex does not
 * prove skipped (certify_ties.c). Sets *out (caller frees) and *nout. */
static int settle_ties(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4], size_t n,
                       qworker *ws, unsigned nt, vbx_qtie **out, size_t *nout)
{
    size_t nch = (n + QCHUNK - 1) / QCHUNK, nties = 0;
    const uint32_t *cw = ws[0].chunk_worker;
    for (size_t ch = 0; ch < nch; ch++)
        nties += ws[0].chunk_tend[ch] - ws[0].chunk_tfirst[ch];
    *nout = nties;
    *out = NULL;
    if (!nties)
        return VB_OK;
    vbx_qtie *t = malloc(nties * sizeof *t);
    size_t *todo = malloc(nties * sizeof *todo), ntodo = 0, m = 0;
    if (!t || !todo) {
        free(t);
        free(todo);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (tie vertices)");
    }
    *out = t;
    for (size_t ch = 0; ch < nch; ch++)
        for (size_t i = ws[0].chunk_tfirst[ch]; i < ws[0].chunk_tend[ch]; i++)
            t[m++] = ws[cw[ch]].tie[i];
    int rc = vbx_ties_group(ctx, c, t, nties);
    for (size_t i = 0; i < nties; i++)
        if (t[i].leader == i)
            todo[ntodo++] = i;
    if (rc == VB_OK)
        rc = run_ties(ctx, ws, nt, t, todo, ntodo);
    ntodo = 0;
    for (size_t i = 0; i < nties && rc == VB_OK; i++) {
        if (t[i].leader == i)
            continue;
        const vbx_qtie *l = &t[t[i].leader];
        const qrec *r = l->rec != SIZE_MAX ? &ws[l->wi].rec[l->rec] : NULL;
        const uint32_t *mm = r && r->nm > 4 ? ws[l->wi].pool + r->moff : NULL;
        if (mm && vbx_quad_within(quads[t[i].quad], mm, r->nm))
            t[i].skipped = 1;
        else
            todo[ntodo++] = i;
    }
    if (rc == VB_OK)
        rc = run_ties(ctx, ws, nt, t, todo, ntodo);
    free(todo);
    return rc;
}

static vbx_vref ref_of(const qworker *ws, const uint32_t (*quads)[4], uint32_t wi, size_t i)
{
    const qrec *r = &ws[wi].rec[i];
    vbx_vref v = {r->nm == 4 ? quads[r->quad] : ws[wi].pool + r->moff, r->nm, r->xyzt,
                  r->sigma};
    return v;
}

/* Ties t[*j ..) of quadruples before `before`: their records to refs (at
 * *m), their counts. */
static void tie_refs(const qworker *ws, const uint32_t (*quads)[4], const vbx_qtie *t,
                     size_t nties, size_t before, size_t *j, vbx_vref *refs, size_t *m,
                     vb_stats *st, vb_cert_quad_stats *qs)
{
    for (; *j < nties && t[*j].quad < before; (*j)++) {
        const vbx_qtie *tj = &t[*j];
        /* A skipped root is a certified root of a vertex already found. */
        qs->roots_tied += tj->skipped;
        qs->duplicates += tj->skipped;
        if (tj->rec != SIZE_MAX)
            refs[(*m)++] = ref_of(ws, quads, tj->wi, tj->rec);
        else if (!tj->skipped && !tj->had_rec)
            st->rejected++;
    }
}

/* The certified roots of every chunk and tie in quadruple order (a tie's
 * after its quadruple's other root, as judge_quad pushed them) merged into
 * out; the counts the ties' quadruples waited for. */
static int gather(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4], size_t n,
                  const qworker *ws, const vbx_qtie *t, size_t nties, vb_vertex_list *out,
                  vb_cert_quad_stats *qs)
{
    size_t nch = (n + QCHUNK - 1) / QCHUNK, total = nties, m = 0, j = 0;
    const uint32_t *cw = ws[0].chunk_worker;
    for (size_t ch = 0; ch < nch; ch++)
        total += ws[0].chunk_end[ch] - ws[0].chunk_first[ch];
    vbx_vref *refs = malloc((total ? total : 1) * sizeof *refs);
    if (!refs)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certified vertices)");
    vb_stats *st = vb_ctx_stats(ctx);
    for (size_t ch = 0; ch < nch; ch++)
        for (size_t i = ws[0].chunk_first[ch]; i < ws[0].chunk_end[ch]; i++) {
            tie_refs(ws, quads, t, nties, ws[cw[ch]].rec[i].quad, &j, refs, &m, st, qs);
            refs[m++] = ref_of(ws, quads, cw[ch], i);
        }
    tie_refs(ws, quads, t, nties, SIZE_MAX, &j, refs, &m, st, qs);
    int rc = vbx_quads_merge(ctx, c, refs, m, out, qs);
    free(refs);
    return rc;
}

static void add_qstats(vb_cert_quad_stats *to, const vb_cert_quad_stats *from)
{
    to->quads += from->quads;
    to->no_root += from->no_root;
    to->flat += from->flat;
    to->delta_exact += from->delta_exact;
    to->one_root += from->one_root;
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
    size_t *chunk_ties = malloc(2 * nch1 * sizeof *chunk_ties);
    if (!ws || !chunk_worker || !chunk_first || !chunk_end || !chunk_ties) {
        free(ws);
        free(chunk_worker);
        free(chunk_first);
        free(chunk_end);
        free(chunk_ties);
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
        ws[i].chunk_tfirst = chunk_ties;
        ws[i].chunk_tend = chunk_ties + nch1;
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
    int rc_ws = VB_OK;
    vbx_qtie *ties = NULL;
    size_t nties = 0;
    if (rc == VB_OK) {
        int bad = vb_jobs_first_error(ws, sizeof *ws, (int)nt, offsetof(qworker, rc),
                                      offsetof(qworker, fail_at));
        if (bad > 0)
            rc_ws = vb_error(ctx, ws[bad].rc, NULL, 0, "%s", vb_errmsg(ws[bad].ctx));
        else
            rc_ws = ws[0].rc;
        if (rc_ws == VB_OK)
            rc_ws = settle_ties(ctx, c, quads, n, ws, nt, &ties, &nties);
    }
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
    if (rc != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certifier threads)");
    else
        rc = rc_ws;
    if (rc == VB_OK)
        rc = gather(ctx, c, quads, n, ws, ties, nties, out, &qs);
    free(ties);
    for (unsigned i = 0; i < nt; i++) {
        free(ws[i].rec);
        free(ws[i].pool);
        free(ws[i].tie);
        if (i > 0) {
            vb_certifier_close(ws[i].c);
            vb_close(ws[i].ctx);
        }
    }
    free(ws);
    free(chunk_worker);
    free(chunk_first);
    free(chunk_end);
    free(chunk_ties);
    if (stats)
        *stats = qs;
    return rc;
}
