/* `vorball verify SPHERES VERTICES`: judges every line of a vertex file (ours
 * or Voronota's) exactly against the spheres, and with --complete also lists
 * the vertices the file misses. The certifier decides; this file only groups
 * its verdicts into the report classes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "input_options.h"
#include "vb_json.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"

static const char *const usage_text =
    "usage: vorball verify SPHERES VERTICES [--tol T] [--complete] [--json] [-o FILE]\n"
    "                      [input options]\n"
    "\n"
    "Checks every line of VERTICES (tsv, json or Voronota's 'q1 q2 q3 q4 x y z r',\n"
    "detected by content; '-' reads stdin) exactly against SPHERES. Each line is\n"
    "  certified          its ids are tangent to one empty sphere at its point\n"
    "  not a vertex       a sphere cuts the tangent sphere, no tangent sphere exists,\n"
    "                     or the ids do not determine a point\n"
    "  wrong coordinates  the exact vertex is farther than T from the line's x y z\n"
    "                     (or its t differs by more than T), in input units\n"
    "  missing members    the line's ids are a strict subset of the vertex's spheres\n"
    "  duplicate          an earlier line names the same exact vertex\n"
    "Voronota lists a vertex of degree > 4 as several quadruple lines: its lines\n"
    "are grouped by exact vertex and membership is judged on the group's union.\n"
    "\n"
    "  --tol T      distance tolerance, > 0 (default 1e-6)\n"
    "  --complete   also compute all vertices exactly (vorball reference) and list\n"
    "               those the file misses (brute force: small inputs)\n"
    "  --json       report as JSON with counts per class\n"
    "  -o FILE      write the report to FILE (default stdout)\n";

static const char *const usage_tail =
    "\n"
    "Exit status: 0 when every line is certified (and, with --complete, nothing\n"
    "is missed), 1 when a problem was found, other codes as for every command.\n";

enum problem {
    P_NOT_VERTEX = 1 << 0,
    P_WRONG_COORDS = 1 << 1,
    P_MISSING = 1 << 2,
    P_DUPLICATE = 1 << 3
};

/* The judgement of one line of the vertex file. */
typedef struct {
    int problems;       /* enum problem bits */
    int verdict;        /* certifier verdict behind P_NOT_VERTEX */
    uint32_t intruder;
    double dist, dt;    /* distance to the exact point, |t - exact t| */
    double ex[4];       /* exact vertex (x y z t) rounded, when known */
    int has_key;        /* the exact vertex is identified */
    size_t key;
    uint32_t *members;  /* all spheres of the exact vertex (owned) */
    size_t nmembers;
    long dup_of;        /* P_DUPLICATE: source line of the first line of the vertex */
    int group_missing;  /* Voronota: members was cut down to those no line of the group names */
} judgement;

typedef struct {
    const char *spheres_path, *vertices_path, *out_path;
    double tol;
    int complete, json;
    vb_cli_input_opts in;
} options;

/* Copies the certifier's member list into the judgement. */
static int keep_members(judgement *j, const vb_cert_result *res)
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
                      const vb_vertex_list *v, size_t k, double tol, judgement *j)
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
            j->problems |= P_NOT_VERTEX;
            j->verdict = res.verdict;
            j->intruder = res.intruder;
        } else if ((rc = keep_members(j, &res)) == VB_OK) {
            j->dist = res.dist;
            j->dt = fabs(p[3] - res.t);
            if (j->dist > tol || j->dt > tol)
                j->problems |= P_WRONG_COORDS;
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
static int judge_groups(const vb_vertex_list *v, const long *lines, judgement *j,
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
        judgement *first = &j[e[a].line];
        if (!voronota) {
            for (size_t i = a + 1; i < b; i++) {
                j[e[i].line].problems |= P_DUPLICATE;
                j[e[i].line].dup_of = lines[e[a].line];
            }
            for (size_t i = a; i < b; i++) {
                size_t k = e[i].line;
                if (j[k].nmembers > v->start[k + 1] - v->start[k])
                    j[k].problems |= P_MISSING;
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
                    j[k].problems |= P_DUPLICATE;
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
            first->problems |= P_MISSING;
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

/* ---- reports ---- */

static const char *not_vertex_reason(int verdict)
{
    switch (verdict) {
    case VB_CERT_INTRUDER: return "intruder";
    case VB_CERT_NO_SOLUTION: return "no_solution";
    case VB_CERT_UNDETERMINED: return "undetermined";
    case VB_CERT_BAD_IDS: return "bad_ids";
    default: return "unknown";
    }
}

static void print_ids(FILE *f, const uint32_t *ids, size_t n)
{
    for (size_t i = 0; i < n; i++)
        fprintf(f, i ? ",%u" : "%u", (unsigned)ids[i]);
}

/* The member ids a line (or a Voronota group) does not list. */
static size_t missing_ids(const vb_vertex_list *v, size_t k, const judgement *j, uint32_t *out)
{
    if (j->group_missing) {
        memcpy(out, j->members, j->nmembers * sizeof *out);
        return j->nmembers;
    }
    size_t n = 0;
    const uint32_t *ids = v->ids + v->start[k];
    size_t nids = v->start[k + 1] - v->start[k];
    for (size_t m = 0; m < j->nmembers; m++)
        if (!contains(ids, nids, j->members[m]))
            out[n++] = j->members[m];
    return n;
}

typedef struct {
    size_t lines, certified, not_vertex, wrong, missing, duplicate, missed, groups;
} counts;

static void print_human(FILE *f, const options *o, const vb_sphere_set *set,
                        const vb_vertex_list *v, const long *lines, const judgement *j,
                        const vb_vertex_list *missed, const counts *n, uint32_t *scratch,
                        vb_vertex_format fmt)
{
    const char *name = o->vertices_path;
    for (size_t k = 0; k < v->n; k++) {
        const judgement *jk = &j[k];
        if (jk->problems & P_NOT_VERTEX) {
            fprintf(f, "%s:%ld: not a vertex: ", name, lines[k]);
            switch (jk->verdict) {
            case VB_CERT_INTRUDER:
                fprintf(f, "sphere %u (%s:%ld) cuts the tangent sphere\n",
                        (unsigned)jk->intruder, set->source,
                        jk->intruder < set->n ? set->line[jk->intruder] : 0L);
                break;
            case VB_CERT_NO_SOLUTION:
                fputs("the spheres have no common tangent sphere\n", f);
                break;
            case VB_CERT_UNDETERMINED:
                fputs("the ids do not determine a point\n", f);
                break;
            default:
                fputs("fewer than 4 distinct ids, or an id out of range\n", f);
                break;
            }
        }
        if (jk->problems & P_WRONG_COORDS)
            fprintf(f,
                    "%s:%ld: wrong coordinates: %.3g from the exact vertex (t off by %.3g), "
                    "tol %g; exact %.17g %.17g %.17g t %.17g\n",
                    name, lines[k], jk->dist, jk->dt, o->tol, jk->ex[0], jk->ex[1], jk->ex[2],
                    jk->ex[3]);
        if (jk->problems & P_MISSING) {
            size_t m = missing_ids(v, k, jk, scratch);
            fprintf(f, "%s:%ld: missing members: the exact vertex also touches ", name,
                    lines[k]);
            print_ids(f, scratch, m);
            fputc('\n', f);
        }
        if (jk->problems & P_DUPLICATE)
            fprintf(f, "%s:%ld: duplicate: same vertex as line %ld\n", name, lines[k],
                    jk->dup_of);
    }
    for (size_t k = 0; k < missed->n; k++) {
        fprintf(f, "%s: missed vertex ", name);
        print_ids(f, missed->ids + missed->start[k], missed->start[k + 1] - missed->start[k]);
        fprintf(f, " at %.17g %.17g %.17g t %.17g\n", missed->x[k], missed->y[k], missed->z[k],
                missed->t[k]);
    }
    fprintf(f,
            "verify: %zu lines (%s", n->lines,
            fmt == VB_VFMT_VORONOTA ? "voronota" : fmt == VB_VFMT_JSON ? "json" : "tsv");
    if (fmt == VB_VFMT_VORONOTA)
        fprintf(f, ", %zu vertices", n->groups);
    fprintf(f,
            "): %zu certified, %zu not a vertex, %zu wrong coordinates, %zu missing members, "
            "%zu duplicate",
            n->certified, n->not_vertex, n->wrong, n->missing, n->duplicate);
    if (o->complete)
        fprintf(f, ", %zu missed", n->missed);
    fputc('\n', f);
}

static void json_ids(FILE *f, const uint32_t *ids, size_t n)
{
    fputc('[', f);
    print_ids(f, ids, n);
    fputc(']', f);
}

static void print_json(FILE *f, const options *o, const vb_vertex_list *v, const long *lines,
                       const judgement *j, const vb_vertex_list *missed, const counts *n,
                       uint32_t *scratch, vb_vertex_format fmt)
{
    fputs("{\"spheres\":", f);
    vb_json_write_string(f, o->spheres_path);
    fputs(",\"vertices\":", f);
    vb_json_write_string(f, o->vertices_path);
    fprintf(f, ",\"format\":\"%s\",\"tol\":%.17g,\"complete\":%s,\"lines\":%zu",
            fmt == VB_VFMT_VORONOTA ? "voronota" : fmt == VB_VFMT_JSON ? "json" : "tsv", o->tol,
            o->complete ? "true" : "false", n->lines);
    if (fmt == VB_VFMT_VORONOTA)
        fprintf(f, ",\"groups\":%zu", n->groups);
    fprintf(f,
            ",\"counts\":{\"certified\":%zu,\"not_a_vertex\":%zu,\"wrong_coordinates\":%zu,"
            "\"missing_members\":%zu,\"duplicate\":%zu",
            n->certified, n->not_vertex, n->wrong, n->missing, n->duplicate);
    if (o->complete)
        fprintf(f, ",\"missed\":%zu", n->missed);
    fputs("},\"problems\":[", f);
    int any = 0;
    for (size_t k = 0; k < v->n; k++) {
        const judgement *jk = &j[k];
        if (jk->problems & P_NOT_VERTEX) {
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"not_a_vertex\",\"reason\":\"%s\"",
                    any++ ? "," : "", lines[k], not_vertex_reason(jk->verdict));
            if (jk->verdict == VB_CERT_INTRUDER)
                fprintf(f, ",\"sphere\":%u", (unsigned)jk->intruder);
            fputc('}', f);
        }
        if (jk->problems & P_WRONG_COORDS)
            fprintf(f,
                    "%s\n{\"line\":%ld,\"class\":\"wrong_coordinates\",\"distance\":%.17g,"
                    "\"t_difference\":%.17g,\"exact\":[%.17g,%.17g,%.17g,%.17g]}",
                    any++ ? "," : "", lines[k], jk->dist, jk->dt, jk->ex[0], jk->ex[1],
                    jk->ex[2], jk->ex[3]);
        if (jk->problems & P_MISSING) {
            size_t m = missing_ids(v, k, jk, scratch);
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"missing_members\",\"missing\":",
                    any++ ? "," : "", lines[k]);
            json_ids(f, scratch, m);
            fputc('}', f);
        }
        if (jk->problems & P_DUPLICATE)
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"duplicate\",\"of_line\":%ld}",
                    any++ ? "," : "", lines[k], jk->dup_of);
    }
    for (size_t k = 0; k < missed->n; k++) {
        fprintf(f, "%s\n{\"class\":\"missed\",\"ids\":", any++ ? "," : "");
        json_ids(f, missed->ids + missed->start[k], missed->start[k + 1] - missed->start[k]);
        fprintf(f, ",\"x\":%.17g,\"y\":%.17g,\"z\":%.17g,\"t\":%.17g}", missed->x[k],
                missed->y[k], missed->z[k], missed->t[k]);
    }
    int ok = n->certified == n->lines && n->missed == 0;
    fprintf(f, "\n],\"ok\":%s}\n", ok ? "true" : "false");
}

/* ---- command ---- */

static int parse_args(int argc, char **argv, options *o)
{
    const char *pos[2];
    int npos = 0;
    o->tol = 1e-6;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int used = vb_cli_input_option(&o->in, argc, argv, &i);
        if (used < 0)
            return VB_EXIT_USAGE;
        if (used > 0)
            continue;
        if (strcmp(a, "--tol") == 0) {
            if (i + 1 >= argc || vb_cli_parse_double(argv[++i], &o->tol) || !(o->tol > 0) ||
                !isfinite(o->tol))
                return vb_cli_usage_error("verify", "--tol needs a positive number");
        } else if (strcmp(a, "--complete") == 0) {
            o->complete = 1;
        } else if (strcmp(a, "--json") == 0) {
            o->json = 1;
        } else if (strcmp(a, "-o") == 0) {
            if (i + 1 >= argc)
                return vb_cli_usage_error("verify", "-o needs a file name");
            o->out_path = argv[++i];
        } else if (a[0] == '-' && a[1] != '\0') {
            return vb_cli_usage_error("verify", "unknown option '%s'", a);
        } else if (npos < 2) {
            pos[npos++] = a;
        } else {
            return vb_cli_usage_error("verify", "too many arguments ('%s')", a);
        }
    }
    if (npos != 2)
        return vb_cli_usage_error("verify", "needs SPHERES and VERTICES");
    if (strcmp(pos[0], "-") == 0 && strcmp(pos[1], "-") == 0)
        return vb_cli_usage_error("verify", "only one of SPHERES and VERTICES can be '-'");
    o->spheres_path = pos[0];
    o->vertices_path = pos[1];
    return VB_EXIT_OK;
}

static void tally(const vb_vertex_list *v, const judgement *j, size_t nmissed,
                  const key_entry *sorted, size_t nsorted, counts *n)
{
    memset(n, 0, sizeof *n);
    n->lines = v->n;
    n->missed = nmissed;
    for (size_t k = 0; k < v->n; k++) {
        int p = j[k].problems;
        n->certified += p == 0;
        n->not_vertex += (p & P_NOT_VERTEX) != 0;
        n->wrong += (p & P_WRONG_COORDS) != 0;
        n->missing += (p & P_MISSING) != 0;
        n->duplicate += (p & P_DUPLICATE) != 0;
    }
    for (size_t i = 0; i < nsorted; i++)
        n->groups += i == 0 || sorted[i].key != sorted[i - 1].key;
}

static int run(vb_ctx *ctx, const options *o, int *mismatch)
{
    vb_sphere_set *set = NULL;
    vb_certifier *cert = NULL;
    vb_vertex_list v, missed;
    vb_vertex_list_init(&v);
    vb_vertex_list_init(&missed);
    long *lines = NULL;
    judgement *j = NULL;
    key_entry *sorted = NULL;
    size_t nsorted = 0;
    uint32_t *scratch = NULL;
    vb_vertex_format fmt = VB_VFMT_TSV;
    FILE *out = NULL;
    int rc = vb_cli_load_spheres(ctx, o->spheres_path, &o->in, 4, &set);
    if (rc == VB_OK)
        rc = vb_vertex_read_file(ctx, o->vertices_path, &v, &fmt, &lines);
    if (rc == VB_OK && v.n == 0)
        vb_warn(ctx, 740, o->vertices_path, 0, "no vertex lines: nothing to verify");
    if (rc == VB_OK)
        rc = vb_certifier_open(ctx, set, &cert);
    if (rc == VB_OK && !(j = calloc(v.n ? v.n : 1, sizeof *j)))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    for (size_t k = 0; rc == VB_OK && k < v.n; k++)
        if ((rc = judge_line(ctx, cert, set, &v, k, o->tol, &j[k])) == VB_ENOMEM)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (rc == VB_OK &&
        judge_groups(&v, lines, j, fmt == VB_VFMT_VORONOTA, &sorted, &nsorted) != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (rc == VB_OK && o->complete)
        rc = find_missed(ctx, cert, set, sorted, nsorted, &missed);
    if (rc == VB_OK && !(scratch = malloc((set->n ? set->n : 1) * sizeof *scratch)))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (rc == VB_OK && !(out = vb_cli_open_output(ctx, o->out_path)))
        rc = VB_EIO;
    if (rc == VB_OK) {
        counts n;
        tally(&v, j, missed.n, sorted, nsorted, &n);
        if (o->json)
            print_json(out, o, &v, lines, j, &missed, &n, scratch, fmt);
        else
            print_human(out, o, set, &v, lines, j, &missed, &n, scratch, fmt);
        *mismatch = !(n.certified == n.lines && n.missed == 0);
        rc = vb_cli_close_output(ctx, out, o->out_path);
    }
    for (size_t k = 0; j && k < v.n; k++)
        free(j[k].members);
    free(j);
    free(sorted);
    free(scratch);
    free(lines);
    vb_vertex_list_free(&v);
    vb_vertex_list_free(&missed);
    vb_certifier_close(cert);
    vb_spheres_free(set);
    return rc;
}

int vb_cmd_verify(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (vb_cli_is_help(argv[i])) {
            fputs(usage_text, stdout);
            vb_cli_input_help(stdout);
            fputs(usage_tail, stdout);
            return VB_EXIT_OK;
        }
    options o;
    memset(&o, 0, sizeof o);
    vb_cli_input_defaults(&o.in);
    int ex = parse_args(argc, argv, &o);
    if (ex != VB_EXIT_OK)
        return ex;
    vb_ctx *ctx;
    vb_config cfg = {.verbosity = 1};
    if (vb_open(&ctx, &cfg) != VB_OK) {
        fprintf(stderr, "vorball: out of memory\n");
        return VB_EXIT_NOMEM;
    }
    int mismatch = 0;
    int rc = run(ctx, &o, &mismatch);
    ex = rc == VB_OK ? (mismatch ? VB_EXIT_MISMATCH : VB_EXIT_OK) : vb_cli_fail(ctx, rc);
    vb_close(ctx);
    return ex;
}
