/* vb_verify_file: every line of a vertex file judged exactly (see
 * vb_verify_file.h). The certifier decides; this file groups its verdicts. */
#include "vb_verify_file.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Copies the certifier's member list into the vb_verify_line. */
static int keep_members(vb_verify_line *j, const vb_cert_result *res)
{
    j->members = malloc((res->nmembers ? res->nmembers : 1) * sizeof *j->members);
    if (!j->members)
        return VB_ENOMEM;
    memcpy(j->members, res->members, res->nmembers * sizeof *j->members);
    j->nmembers = res->nmembers;
    j->has_key = 1;
    j->key = res->key;
    j->ex[0] = res->x;
    j->ex[1] = res->y;
    j->ex[2] = res->z;
    j->ex[3] = res->t;
    return VB_OK;
}

static int contains(const uint32_t *ids, size_t n, uint32_t id)
{
    for (size_t i = 0; i < n; i++)
        if (ids[i] == id)
            return 1;
    return 0;
}

/* Ids that do not determine a point (e.g. four coplanar corners of a cube)
 * may still name part of a real vertex: returns in *wide (malloc'd) the ids
 * plus every sphere whose distance from the line's point is within tol of the
 * line's t, and their count in *nwide (0 when no sphere was added). */
static int widen(const vb_sphere_set *set, const uint32_t *ids, size_t nids, const double p[4],
                 double tol, uint32_t **wide, size_t *nwide)
{
    *nwide = 0;
    if (!(*wide = malloc((set->n + nids) * sizeof **wide)))
        return VB_ENOMEM;
    memcpy(*wide, ids, nids * sizeof *ids);
    size_t n = nids;
    for (size_t s = 0; s < set->n; s++) {
        double dx = p[0] - set->x[s], dy = p[1] - set->y[s], dz = p[2] - set->z[s];
        double d = sqrt(dx * dx + dy * dy + dz * dz) - set->r[s] - p[3];
        if (fabs(d) <= tol && !contains(ids, nids, (uint32_t)s))
            (*wide)[n++] = (uint32_t)s;
    }
    if (n > nids)
        *nwide = n;
    return VB_OK;
}

/* Judges one line on its own: certification, coordinates, membership. */
static int judge_line(vb_ctx *ctx, vb_certifier *c, const vb_sphere_set *set,
                      const vb_vertex_list *v, size_t k, double tol, vb_verify_line *j)
{
    const uint32_t *ids = v->ids + v->start[k];
    size_t nids = v->start[k + 1] - v->start[k];
    double p[4] = {v->x[k], v->y[k], v->z[k], v->t[k]};
    uint32_t *wide = NULL;
    size_t nwide = 0;
    vb_cert_result res;
    int rc = vb_certify_candidate(ctx, c, ids, nids, p, tol, &res);
    if (rc == VB_OK && res.verdict == VB_CERT_UNDETERMINED &&
        (rc = widen(set, ids, nids, p, tol, &wide, &nwide)) == VB_OK && nwide > 0) {
        vb_cert_result w;
        rc = vb_certify_candidate(ctx, c, wide, nwide, p, tol, &w);
        /* Only a widened set that certifies at the line's own point says
         * what the line meant; otherwise the line stays undetermined. */
        if (rc == VB_OK && w.verdict == VB_CERT_OK) {
            res = w;
            ids = wide;
            nids = nwide;
        }
    }
    /* A far vertex is still identified (tol 0 skips the distance check) so
     * that it is reported once, as wrong coordinates, and not also as missed. */
    if (rc == VB_OK && res.verdict == VB_CERT_FAR)
        rc = vb_certify_candidate(ctx, c, ids, nids, p, 0.0, &res);
    if (rc == VB_OK) {
        if (res.verdict != VB_CERT_OK) {
            j->problems |= VB_VERIFY_NOT_VERTEX;
            j->verdict = res.verdict;
            j->intruder = res.intruder;
        } else if ((rc = keep_members(j, &res)) == VB_OK) {
            j->dist = res.dist;
            j->dt = fabs(p[3] - res.t);
            if (j->dist > tol || j->dt > tol)
                j->problems |= VB_VERIFY_WRONG_COORDS;
        }
    }
    free(wide);
    return rc;
}

/* Lines sorted by key bring the lines of one exact vertex together. */
typedef struct {
    size_t key, line;
} key_entry;

static int cmp_key_entry(const void *a, const void *b)
{
    const key_entry *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->line > y->line) - (x->line < y->line);
}

static int same_ids(const vb_vertex_list *v, size_t a, size_t b)
{
    size_t na = v->start[a + 1] - v->start[a], nb = v->start[b + 1] - v->start[b];
    return na == nb &&
           memcmp(v->ids + v->start[a], v->ids + v->start[b], na * sizeof *v->ids) == 0;
}

/* Groups the identified lines by exact vertex. Ours: a second line of a
 * vertex is a duplicate, and each line must list every member. Voronota:
 * a repeated quadruple is a duplicate, and the group's union of ids must
 * list every member (reported on the group's first line). */
static int judge_groups(const vb_vertex_list *v, const long *lines, vb_verify_line *j,
                        int voronota, key_entry **sorted, size_t *nsorted)
{
    key_entry *e = malloc((v->n ? v->n : 1) * sizeof *e);
    uint8_t *seen = NULL;
    if (!e)
        return VB_ENOMEM;
    size_t n = 0;
    for (size_t k = 0; k < v->n; k++)
        if (j[k].has_key)
            e[n++] = (key_entry){j[k].key, k};
    qsort(e, n, sizeof *e, cmp_key_entry);
    for (size_t a = 0, b; a < n; a = b) {
        for (b = a + 1; b < n && e[b].key == e[a].key; b++)
            ;
        vb_verify_line *first = &j[e[a].line];
        if (!voronota) {
            for (size_t i = a + 1; i < b; i++) {
                j[e[i].line].problems |= VB_VERIFY_DUPLICATE;
                j[e[i].line].dup_of = lines[e[a].line];
            }
            for (size_t i = a; i < b; i++) {
                size_t k = e[i].line;
                if (j[k].nmembers > v->start[k + 1] - v->start[k])
                    j[k].problems |= VB_VERIFY_MISSING;
            }
            continue;
        }
        free(seen);
        seen = calloc(first->nmembers ? first->nmembers : 1, 1);
        if (!seen) {
            free(e);
            return VB_ENOMEM;
        }
        for (size_t i = a; i < b; i++) {
            size_t k = e[i].line;
            for (size_t h = a; h < i; h++)
                if (same_ids(v, k, e[h].line)) {
                    j[k].problems |= VB_VERIFY_DUPLICATE;
                    j[k].dup_of = lines[e[h].line];
                    break;
                }
            for (size_t q = v->start[k]; q < v->start[k + 1]; q++)
                for (size_t m = 0; m < first->nmembers; m++)
                    if (first->members[m] == v->ids[q])
                        seen[m] = 1;
        }
        size_t covered = 0;
        for (size_t m = 0; m < first->nmembers; m++)
            covered += seen[m];
        if (covered < first->nmembers) {
            first->problems |= VB_VERIFY_MISSING;
            /* Keep only the members no line of the group names. */
            size_t w = 0;
            for (size_t m = 0; m < first->nmembers; m++)
                if (!seen[m])
                    first->members[w++] = first->members[m];
            first->nmembers = w;
            first->group_missing = 1;
        }
    }
    free(seen);
    *sorted = e;
    *nsorted = n;
    return VB_OK;
}

/* Runs the exact reference and collects in `missed` its vertices whose key
 * no line of the file has. */
static int find_missed(vb_ctx *ctx, vb_certifier *c, const vb_sphere_set *set,
                       const key_entry *sorted, size_t nsorted, vb_vertex_list *missed)
{
    vb_vertex_list ref;
    vb_vertex_list_init(&ref);
    int rc = vb_reference(ctx, set, &ref);
    for (size_t k = 0; rc == VB_OK && k < ref.n; k++) {
        const uint32_t *ids = ref.ids + ref.start[k];
        size_t nids = ref.start[k + 1] - ref.start[k];
        double p[3] = {ref.x[k], ref.y[k], ref.z[k]};
        vb_cert_result res;
        if ((rc = vb_certify_candidate(ctx, c, ids, nids, p, 0.0, &res)))
            break;
        if (res.verdict != VB_CERT_OK) {
            rc = vb_error(ctx, VB_EINTERNAL, NULL, 0,
                          "the certifier refuses reference vertex %zu (verdict %d)", k,
                          res.verdict);
            break;
        }
        key_entry probe = {res.key, 0};
        size_t lo = 0, hi = nsorted;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (sorted[mid].key < probe.key)
                lo = mid + 1;
            else
                hi = mid;
        }
        if (lo < nsorted && sorted[lo].key == probe.key)
            continue;
        rc = vb_vertex_list_push(missed, ids, nids, ref.x[k], ref.y[k], ref.z[k], ref.t[k], 0,
                                 VB_VERTEX_CERTIFIED);
        if (rc)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    vb_vertex_list_free(&ref);
    return rc;
}

static void tally(const vb_vertex_list *v, const vb_verify_line *j, size_t nmissed,
                  const key_entry *sorted, size_t nsorted, vb_verify_counts *n)
{
    memset(n, 0, sizeof *n);
    n->lines = v->n;
    n->missed = nmissed;
    for (size_t k = 0; k < v->n; k++) {
        int p = j[k].problems;
        n->certified += p == 0;
        n->not_vertex += (p & VB_VERIFY_NOT_VERTEX) != 0;
        n->wrong += (p & VB_VERIFY_WRONG_COORDS) != 0;
        n->missing += (p & VB_VERIFY_MISSING) != 0;
        n->duplicate += (p & VB_VERIFY_DUPLICATE) != 0;
    }
    for (size_t i = 0; i < nsorted; i++)
        n->groups += i == 0 || sorted[i].key != sorted[i - 1].key;
}

static void report_init(vb_verify_report *out, double tol, int complete)
{
    memset(out, 0, sizeof *out);
    vb_vertex_list_init(&out->vertices);
    vb_vertex_list_init(&out->missed);
    out->tol = tol;
    out->complete = complete;
    out->format = VB_VFMT_TSV;
}

/* Judges the lines in out->vertices (source lines in out->lines); name is
 * the vertex file in messages. */
static int judge_report(vb_ctx *ctx, const vb_sphere_set *set, const char *name,
                        vb_verify_report *out)
{
    vb_certifier *cert = NULL;
    key_entry *sorted = NULL;
    size_t nsorted = 0;
    const vb_vertex_list *v = &out->vertices;
    int rc = VB_OK;
    if (v->n == 0)
        rc = vb_error(ctx, VB_EINPUT_EMPTY, name, 0, "no vertex lines: nothing to verify");
    if (rc == VB_OK)
        rc = vb_certifier_open(ctx, set, &cert);
    if (rc == VB_OK && !(out->judged = calloc(v->n, sizeof *out->judged)))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    for (size_t k = 0; rc == VB_OK && k < v->n; k++)
        if ((rc = judge_line(ctx, cert, set, v, k, out->tol, &out->judged[k])) == VB_ENOMEM)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (rc == VB_OK && judge_groups(v, out->lines, out->judged, out->format == VB_VFMT_VORONOTA,
                                    &sorted, &nsorted) != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (rc == VB_OK && out->complete)
        rc = find_missed(ctx, cert, set, sorted, nsorted, &out->missed);
    if (rc == VB_OK)
        tally(v, out->judged, out->missed.n, sorted, nsorted, &out->counts);
    free(sorted);
    /* Kept for vb_verify_arcs (closed by vb_verify_report_free); the keys
     * have been used by now (judge_groups, find_missed). */
    vb_certifier_forget_keys(cert);
    out->cert = cert;
    out->cert_set = cert ? set : NULL;
    return rc;
}

int vb_verify_file(vb_ctx *ctx, const vb_sphere_set *set, const char *path, double tol,
                   int complete, vb_verify_report *out)
{
    report_init(out, tol, complete);
    int rc = vb_vertex_read_file(ctx, path, &out->vertices, &out->format, &out->lines);
    return rc == VB_OK ? judge_report(ctx, set, path, out) : rc;
}

int vb_verify_list(vb_ctx *ctx, const vb_sphere_set *set, const char *name,
                   const vb_vertex_list *v, vb_vertex_format format, double tol, int complete,
                   vb_verify_report *out)
{
    report_init(out, tol, complete);
    out->format = format;
    if (v->n && !(out->lines = malloc(v->n * sizeof *out->lines)))
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    for (size_t k = 0; k < v->n; k++) {
        out->lines[k] = (long)k + 1;
        if (vb_vertex_list_push(&out->vertices, v->ids + v->start[k], v->start[k + 1] - v->start[k],
                                v->x[k], v->y[k], v->z[k], v->t[k], v->dist[k],
                                v->status[k]) != VB_OK)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    return judge_report(ctx, set, name, out);
}

int vb_verify_report_ok(const vb_verify_report *r)
{
    return r->counts.certified == r->counts.lines && r->counts.missed == 0;
}

void vb_verify_report_free(vb_verify_report *r)
{
    for (size_t k = 0; r->judged && k < r->vertices.n; k++)
        free(r->judged[k].members);
    free(r->judged);
    free(r->lines);
    vb_vertex_list_free(&r->vertices);
    vb_vertex_list_free(&r->missed);
    vb_certifier_close(r->cert);
    memset(r, 0, sizeof *r);
}
