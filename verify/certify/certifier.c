/* The exact certifier: candidate -> exact tangent sphere -> empty? -> canonical vertex. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"

#include "vbx_cert.h"

/* Solvers and per-candidate scratch (sized by the sphere count); 0 or -1. */
static int open_scratch(vb_certifier *c)
{
    vbx_solver_init(&c->sol, &c->d);
    vbx_solver_init(&c->canon, &c->d);
    size_t n1 = c->set->n ? c->set->n : 1;
    c->cap = n1;
    c->ids = malloc(n1 * sizeof *c->ids);
    c->members = malloc(n1 * sizeof *c->members);
    c->is_def = calloc(n1, 1);
    return c->ids && c->members && c->is_def ? 0 : -1;
}

/* The scaled input as 64-bit integers for the filter of vb_certify_quads:
 * qd.ok only when every value is below 2^62 in magnitude and 10^E is a
 * double. 0, or -1 when out of memory. */
static int open_qdata(vb_certifier *c)
{
    size_t n = c->set->n;
    c->qz = malloc(4 * (n ? n : 1) * sizeof *c->qz);
    if (!c->qz)
        return -1;
    c->qd.z = c->qz;
    c->qd.ok = 0;
    c->qd.ops = vbx_qf_ops_best();
#if LONG_MAX < 0x3fffffffffffffff
    return 0; /* mpz_get_si needs a 64-bit long */
#endif
    double sc = mpz_get_d(c->d.scale);
    if (mpz_cmp_d(c->d.scale, sc) != 0)
        return 0;
    for (size_t i = 0; i < 4 * n; i++) {
        if (mpz_sizeinbase(c->d.c[i], 2) > 61)
            return 0;
        c->qz[i] = (int64_t)mpz_get_si(c->d.c[i]);
    }
    c->qd.scale = sc;
    c->qd.ok = 1;
    return 0;
}

int vb_certifier_open(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier **out)
{
    *out = NULL;
    if (!set)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "vb_certifier_open: no sphere set");
    if (set->n > (size_t)UINT32_MAX)
        return vb_error(ctx, VB_EINPUT_TOOLARGE, set->source, 0,
                        "%zu spheres: the certifier indexes at most 2^32 - 1", set->n);
    vb_certifier *c = calloc(1, sizeof *c);
    if (!c)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certifier)");
    c->set = set;
    int rc = vbx_data_init(ctx, &c->d, set);
    if (rc != VB_OK) {
        free(c);
        return rc;
    }
    if (open_scratch(c) != 0 || vbx_sindex_build(&c->t, c->d.box, c->d.near, set->n) != 0 ||
        open_qdata(c) != 0) {
        vb_certifier_close(c);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certifier)");
    }
    *out = c;
    return VB_OK;
}

vb_certifier *vbx_certifier_worker(const vb_certifier *c)
{
    vb_certifier *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    /* Shallow copies: the parent's GMP integers and index arrays are only
     * read while workers run, which GMP allows from several threads. */
    w->set = c->set;
    w->d = c->d;
    w->t = c->t;
    w->qd = c->qd;
    w->qz = c->qz;
    w->borrowed = 1;
    if (open_scratch(w) != 0) {
        vb_certifier_close(w);
        return NULL;
    }
    return w;
}

void vb_certifier_close(vb_certifier *c)
{
    if (!c)
        return;
    vbx_solver_free(&c->sol);
    vbx_solver_free(&c->canon);
    if (!c->borrowed) {
        vbx_data_free(&c->d);
        vbx_sindex_free(&c->t);
        free(c->qz);
    }
    free(c->ids);
    free(c->members);
    free(c->is_def);
    free(c->keys);
    vb_hash_free(&c->keytab);
    free(c->pool);
    free(c);
}

void vb_certifier_forget_keys(vb_certifier *c)
{
    if (!c)
        return;
    free(c->keys);
    vb_hash_free(&c->keytab);
    free(c->pool);
    c->keys = NULL;
    c->pool = NULL;
    c->nkeys = c->keys_cap = c->npool = c->pool_cap = 0;
}

int vbx_cert_tangent_sign(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, uint32_t j,
                          const vbx_ia box[4])
{
    vb_stats *st = vb_ctx_stats(ctx);
    st->filter_calls++;
    int sg = vbx_ia_sign(vbx_ia_add(box[3], c->d.box[4 * (size_t)j + 3]));
    if (sg)
        return sg;
    st->filter_failures++;
    st->exact_evals++;
    return vbx_sign_tangent(&c->sol, r, j);
}

/* |p - c_j| - R_j - t over the enclosures: its sign if the filter proves it. */
static vbx_ia distance_excess(const vbx_ia cj[4], const vbx_ia box[4])
{
    vbx_ia d2 = vbx_ia_sqr(vbx_ia_sub(box[0], cj[0]));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[1], cj[1])));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[2], cj[2])));
    return vbx_ia_sub(vbx_ia_sub(vbx_ia_sqrt(d2), cj[3]), box[3]);
}

int vbx_cert_round(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, double xyzt[4],
                   vbx_ia box[4])
{
    int rc = vbx_root_coords(&c->sol, r, xyzt, box);
    if (rc != VB_OK)
        return vb_error(ctx, rc, NULL, 0, "cannot round an exact vertex to double");
    return VB_OK;
}

static int is_solved_row(const vbx_solver *s, uint32_t j)
{
    return j == s->base || j == s->rows[0] || j == s->rows[1] || j == s->rows[2];
}

int vbx_cert_defining(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                      size_t ndef, const vbx_ia box[4])
{
    vb_stats *st = vb_ctx_stats(ctx);
    for (size_t i = 0; i < ndef; i++) {
        uint32_t j = def[i];
        if (vbx_cert_tangent_sign(ctx, c, r, j, box) < 0)
            return 0;
        if (is_solved_row(&c->sol, j))
            continue;
        /* A defining sphere beyond the four solved must touch exactly. */
        st->filter_calls++;
        if (vbx_ia_sign(distance_excess(&c->d.box[4 * (size_t)j], box)) != 0)
            return 0;
        st->filter_failures++;
        st->exact_evals++;
        if (vbx_sign_power(&c->sol, r, j) != 0)
            return 0;
    }
    return 1;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The scan of vbx_cert_scan; `first`: stop at the first proven intruder. */
static void scan(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                 size_t ndef, const vbx_ia box[4], int first, int *verdict, uint32_t *intruder)
{
    vb_stats *st = vb_ctx_stats(ctx);
    for (size_t i = 0; i < ndef; i++)
        c->is_def[def[i]] = 1;
    /* Sphere j can reach into the open tangent ball only if
     * |p - c_j| < t + R_j: the walk visits every run of slots the index
     * cannot rule out (vbx_sindex.h), and each sphere there is filtered
     * cheaply (vbx_probe_outside), then by distance_excess, then exactly. */
    const vbx_sindex *t = &c->t;
    vbx_probe pr;
    vbx_probe_init(&pr, t, box);
    vbx_walk w;
    vbx_walk_init(&w, t, box);
    size_t nm = 0, q0, q1;
    int found = 0;
    double depth = 0.0;
    while (vbx_walk_next(&w, &q0, &q1))
        for (size_t q = q0; q < q1; q++) {
            /* The cheap test first (vbx_sindex.h), then the defining ids. */
            const double *cm = &t->mid[4 * q];
            if (vbx_probe_outside(&pr, cm)) {
                st->filter_calls++;
                continue;
            }
            uint32_t j = t->ids[q];
            if (c->is_def[j])
                continue;
            st->filter_calls++;
            const vbx_ia *cj = &t->box[4 * q];
            vbx_ia g = distance_excess(cj, box);
            int sg = vbx_ia_sign(g), exact = sg == 0;
            if (exact) {
                st->filter_failures++;
                st->exact_evals++;
                sg = vbx_sign_distance(&c->sol, r, j);
            }
            if (sg > 0)
                continue;
            if (sg == 0) {
                c->members[ndef + nm++] = j;
                continue;
            }
            /* Report the deepest intruder (exactly decided ones sit at ~0). */
            double dj = exact ? 0.0 : vbx_ia_mid(g);
            if (!found || dj < depth || (dj == depth && j < *intruder)) {
                depth = dj;
                *intruder = j;
            }
            found = 1;
            if (first)
                goto done;
        }
done:
    for (size_t i = 0; i < ndef; i++)
        c->is_def[def[i]] = 0;
    if (found) {
        *verdict = VB_CERT_INTRUDER;
        c->nmembers = 0;
        return;
    }
    memcpy(c->members, def, ndef * sizeof *def);
    c->nmembers = ndef + nm;
    qsort(c->members, c->nmembers, sizeof *c->members, cmp_u32);
    *verdict = VB_CERT_OK;
}

void vbx_cert_scan(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                   size_t ndef, const vbx_ia box[4], int *verdict, uint32_t *intruder)
{
    scan(ctx, c, r, def, ndef, box, 0, verdict, intruder);
}

void vbx_cert_scan_empty(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                         size_t ndef, const vbx_ia box[4], int *verdict)
{
    uint32_t intruder;
    scan(ctx, c, r, def, ndef, box, 1, verdict, &intruder);
}

/* Solves c->canon for the sorted quadruple q; 1 when it is SOLVED with a root. */
static int canon_solves(vb_certifier *c, const uint32_t q[4])
{
    return vbx_solve(&c->canon, q[0], q + 1) == VBX_SOLVED && c->canon.nroots > 0;
}

static int same_quad(const vbx_solver *s, const uint32_t q[4])
{
    return s->base == q[0] && s->rows[0] == q[1] && s->rows[1] == q[2] && s->rows[2] == q[3];
}

int vbx_cert_canonical(vb_certifier *c, int *ours)
{
    const uint32_t *m = c->members;
    size_t n = c->nmembers;
    *ours = 0;
    if (n < 4)
        return 0;
    /* Common case: the four members are the solved quadruple itself. */
    if (n == 4 && same_quad(&c->sol, m) && c->sol.status == VBX_SOLVED) {
        *ours = 1;
        return 1;
    }
    /* The lexicographically first independent quadruple is the greedy one
     * (bases of a matroid); no SOLVED quadruple comes before it. */
    uint32_t q[4] = {m[0], 0, 0, 0};
    if (vbx_pick_rows(&c->canon, m[0], m + 1, n - 1, 4, q + 1) == 3 && canon_solves(c, q)) {
        *ours = same_quad(&c->sol, q);
        return 1;
    }
    /* Otherwise (its line lies on the cone: nested tangent spheres) the
     * first SOLVED quadruple in lexicographic order. */
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
            for (size_t d3 = b + 1; d3 < n; d3++)
                for (size_t e = d3 + 1; e < n; e++) {
                    uint32_t t[4] = {m[a], m[b], m[d3], m[e]};
                    if (canon_solves(c, t)) {
                        *ours = same_quad(&c->sol, t);
                        return 1;
                    }
                }
    return 0;
}

static uint64_t hash_members(const uint32_t *m, size_t n, int sigma)
{
    uint64_t h = 1469598103934665603ull ^ (uint64_t)(sigma + 1);
    for (size_t i = 0; i < n; i++) {
        h ^= m[i];
        h *= 1099511628211ull;
        h ^= h >> 29;
    }
    return h;
}

/* A key sought (vb_hash_same_fn): members m (n of them), root sigma. */
typedef struct key_probe {
    const vb_certifier *c;
    uint64_t hash;
    const uint32_t *m;
    size_t n;
    int sigma;
} key_probe;

static int key_same(const void *key, size_t k)
{
    const key_probe *q = key;
    const vbx_key_entry *e = &q->c->keys[k];
    return e->hash == q->hash && e->n == q->n && e->sigma == q->sigma &&
           memcmp(q->c->pool + e->off, q->m, q->n * sizeof *q->m) == 0;
}

static uint64_t key_hash_of(const void *arg, size_t k)
{
    const vb_certifier *c = arg;
    return c->keys[k].hash;
}

int vbx_cert_identity(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, int *sigma)
{
    int ours;
    if (!vbx_cert_canonical(c, &ours))
        return vb_error(ctx, VB_EINTERNAL, NULL, 0,
                        "a certified vertex has no quadruple of members with a root");
    if (ours) {
        *sigma = r->sigma;
    } else {
        /* The canonical quadruple's line passes through our exact point; its
         * root there is decided exactly (vbx_sigma_in). */
        vb_ctx_stats(ctx)->exact_evals++;
        *sigma = vbx_sigma_in(&c->canon, &c->sol, r);
    }
    return VB_OK;
}

int vbx_cert_key_of(vb_ctx *ctx, vb_certifier *c, const uint32_t *m, size_t n, int sigma,
                    size_t *key)
{
    uint64_t h = hash_members(m, n, sigma);
    key_probe q = {c, h, m, n, sigma};
    if (!c->keytab.cap && vb_hash_fit(&c->keytab, 0, key_hash_of, c) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (vertex keys)");
    size_t *slot = vb_hash_slot(&c->keytab, h, key_same, &q);
    if (*slot) {
        *key = *slot - 1;
        return VB_OK;
    }
    if (VB_ARRAY_FIT(c->pool, c->pool_cap, c->npool + n, 1024) != VB_OK ||
        VB_ARRAY_FIT(c->keys, c->keys_cap, c->nkeys + 1, 64) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (vertex keys)");
    memcpy(c->pool + c->npool, m, n * sizeof *m);
    c->keys[c->nkeys] = (vbx_key_entry){h, c->npool, n, sigma};
    c->npool += n;
    *key = c->nkeys++;
    if (vb_hash_put(&c->keytab, slot, *key, key_hash_of, c) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (vertex keys)");
    return VB_OK;
}

/* Sorted distinct copy of ids into c->ids; returns the count, 0 if an id is
 * out of range. */
static size_t distinct_ids(vb_certifier *c, const uint32_t *ids, size_t nids)
{
    size_t n = c->set->n, m = 0;
    for (size_t i = 0; i < nids; i++)
        if (ids[i] >= n)
            return 0;
    for (size_t i = 0; i < nids; i++)
        c->is_def[ids[i]] = 1;
    for (size_t i = 0; i < nids; i++)
        if (c->is_def[ids[i]]) {
            c->is_def[ids[i]] = 0;
            c->ids[m++] = ids[i];
        }
    qsort(c->ids, m, sizeof *c->ids, cmp_u32);
    return m;
}

int vbx_certify_one(vb_ctx *ctx, vb_certifier *c, const uint32_t *ids, size_t nids,
                    const double p[3], double tol, vb_cert_result *res, int *sigma)
{
    vb_stats *st = vb_ctx_stats(ctx);
    memset(res, 0, sizeof *res);
    st->candidates++;
    st->rejected++; /* undone below when the candidate is certified */
    res->verdict = VB_CERT_BAD_IDS;
    size_t m = nids >= 4 ? distinct_ids(c, ids, nids) : 0;
    if (m < 4)
        return VB_OK;
    uint32_t base = c->ids[0], rows[3];
    int rank = vbx_pick_rows(&c->sol, base, c->ids + 1, m - 1, 4, rows);
    if (rank < 3) {
        /* Rank-deficient: inconsistent rows have no solution; consistent ones
         * leave at least a plane of (q, s), whose points on the cone are not
         * a finite set we can name from these ids. */
        int arank = vbx_pick_rows(&c->sol, base, c->ids + 1, m - 1, 5, rows);
        st->exact_evals++;
        res->verdict = arank > rank ? VB_CERT_NO_SOLUTION : VB_CERT_UNDETERMINED;
        return VB_OK;
    }
    st->exact_evals++;
    int status = vbx_solve(&c->sol, base, rows);
    if (status == VBX_UNDETERMINED) {
        res->verdict = VB_CERT_UNDETERMINED;
        return VB_OK;
    }
    /* Among the roots that solve the unsquared system, the nearest. */
    int best = -1;
    double best_d = 0.0, xyzt[2][4];
    vbx_ia box[2][4];
    for (int r = 0; r < c->sol.nroots; r++) {
        int rc = vbx_cert_round(ctx, c, &c->sol.root[r], xyzt[r], box[r]);
        if (rc != VB_OK)
            return rc;
        if (!vbx_cert_defining(ctx, c, &c->sol.root[r], c->ids, m, box[r]))
            continue;
        double dx = xyzt[r][0] - p[0], dy = xyzt[r][1] - p[1], dz = xyzt[r][2] - p[2];
        double dd = sqrt(dx * dx + dy * dy + dz * dz);
        if (best < 0 || dd < best_d) {
            best = r;
            best_d = dd;
        }
    }
    res->verdict = VB_CERT_NO_SOLUTION;
    if (best < 0)
        return VB_OK;
    res->x = xyzt[best][0];
    res->y = xyzt[best][1];
    res->z = xyzt[best][2];
    res->t = xyzt[best][3];
    res->dist = best_d;
    int verdict;
    vbx_cert_scan(ctx, c, &c->sol.root[best], c->ids, m, box[best], &verdict, &res->intruder);
    res->verdict = verdict;
    if (verdict != VB_CERT_OK)
        return VB_OK;
    if (tol > 0.0 && !(best_d <= tol)) {
        res->verdict = VB_CERT_FAR;
        return VB_OK;
    }
    int rc = vbx_cert_identity(ctx, c, &c->sol.root[best], sigma);
    if (rc != VB_OK)
        return rc;
    res->members = c->members;
    res->nmembers = c->nmembers;
    st->rejected--;
    st->certified++;
    return VB_OK;
}

int vb_certify_candidate(vb_ctx *ctx, vb_certifier *c, const uint32_t *ids, size_t nids,
                         const double p[3], double tol, vb_cert_result *res)
{
    int sigma = 0;
    int rc = vbx_certify_one(ctx, c, ids, nids, p, tol, res, &sigma);
    if (rc != VB_OK || res->verdict != VB_CERT_OK)
        return rc;
    return vbx_cert_key_of(ctx, c, c->members, c->nmembers, sigma, &res->key);
}

/* The MPFR the certifier's exact numbers run on (vb_verify.h). */
const char *vb_verify_mpfr_version(void)
{
    return mpfr_get_version();
}
