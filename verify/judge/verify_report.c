/* The report of vb_verify_file, as text and as JSON. */
#include <stdlib.h>
#include <string.h>

#include "vb_json.h"
#include "vb_verify_file.h"

static int contains(const uint32_t *ids, size_t n, uint32_t id)
{
    for (size_t i = 0; i < n; i++)
        if (ids[i] == id)
            return 1;
    return 0;
}

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

static const char *format_name(vb_vertex_format fmt)
{
    return fmt == VB_VFMT_VORONOTA ? "voronota" : fmt == VB_VFMT_JSON ? "json" : "tsv";
}

static void print_ids(FILE *f, const uint32_t *ids, size_t n)
{
    for (size_t i = 0; i < n; i++)
        fprintf(f, i ? ",%u" : "%u", (unsigned)ids[i]);
}

/* The member ids a line (or a Voronota group) does not list. */
static size_t missing_ids(const vb_vertex_list *v, size_t k, const vb_verify_line *j, uint32_t *out)
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

static void print_human(FILE *f, const char *name, const vb_sphere_set *set,
                        const vb_verify_report *r, uint32_t *scratch)
{
    const vb_vertex_list *v = &r->vertices, *missed = &r->missed;
    const long *lines = r->lines;
    const vb_verify_line *j = r->judged;
    const vb_verify_counts *n = &r->counts;
    vb_vertex_format fmt = r->format;
    for (size_t k = 0; k < v->n; k++) {
        const vb_verify_line *jk = &j[k];
        if (jk->problems & VB_VERIFY_NOT_VERTEX) {
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
        if (jk->problems & VB_VERIFY_WRONG_COORDS)
            fprintf(f,
                    "%s:%ld: wrong coordinates: %.3g from the exact vertex (t off by %.3g), "
                    "tol %g; exact %.17g %.17g %.17g t %.17g\n",
                    name, lines[k], jk->dist, jk->dt, r->tol, jk->ex[0], jk->ex[1], jk->ex[2],
                    jk->ex[3]);
        if (jk->problems & VB_VERIFY_MISSING) {
            size_t m = missing_ids(v, k, jk, scratch);
            fprintf(f, "%s:%ld: missing members: the exact vertex also touches ", name,
                    lines[k]);
            print_ids(f, scratch, m);
            fputc('\n', f);
        }
        if (jk->problems & VB_VERIFY_DUPLICATE)
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
            format_name(fmt));
    if (fmt == VB_VFMT_VORONOTA)
        fprintf(f, ", %zu vertices", n->groups);
    fprintf(f,
            "): %zu certified, %zu not a vertex, %zu wrong coordinates, %zu missing members, "
            "%zu duplicate",
            n->certified, n->not_vertex, n->wrong, n->missing, n->duplicate);
    if (r->complete)
        fprintf(f, ", %zu missed", n->missed);
    fputc('\n', f);
}

static void json_ids(FILE *f, const uint32_t *ids, size_t n)
{
    fputc('[', f);
    print_ids(f, ids, n);
    fputc(']', f);
}

static void print_json(FILE *f, const char *spheres_name, const char *name,
                       const vb_verify_report *r, uint32_t *scratch, const char *key,
                       void (*more)(FILE *, const void *), const void *arg, int more_ok)
{
    const vb_vertex_list *v = &r->vertices, *missed = &r->missed;
    const long *lines = r->lines;
    const vb_verify_line *j = r->judged;
    const vb_verify_counts *n = &r->counts;
    vb_vertex_format fmt = r->format;
    fputs("{\"spheres\":", f);
    vb_json_write_string(f, spheres_name);
    fputs(",\"vertices\":", f);
    vb_json_write_string(f, name);
    fprintf(f, ",\"format\":\"%s\",\"tol\":%.17g,\"complete\":%s,\"lines\":%zu",
            format_name(fmt), r->tol,
            r->complete ? "true" : "false", n->lines);
    if (fmt == VB_VFMT_VORONOTA)
        fprintf(f, ",\"groups\":%zu", n->groups);
    fprintf(f,
            ",\"counts\":{\"certified\":%zu,\"not_a_vertex\":%zu,\"wrong_coordinates\":%zu,"
            "\"missing_members\":%zu,\"duplicate\":%zu",
            n->certified, n->not_vertex, n->wrong, n->missing, n->duplicate);
    if (r->complete)
        fprintf(f, ",\"missed\":%zu", n->missed);
    fputs("},\"problems\":[", f);
    int any = 0;
    for (size_t k = 0; k < v->n; k++) {
        const vb_verify_line *jk = &j[k];
        if (jk->problems & VB_VERIFY_NOT_VERTEX) {
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"not_a_vertex\",\"reason\":\"%s\"",
                    any++ ? "," : "", lines[k], not_vertex_reason(jk->verdict));
            if (jk->verdict == VB_CERT_INTRUDER)
                fprintf(f, ",\"sphere\":%u", (unsigned)jk->intruder);
            fputc('}', f);
        }
        if (jk->problems & VB_VERIFY_WRONG_COORDS)
            fprintf(f,
                    "%s\n{\"line\":%ld,\"class\":\"wrong_coordinates\",\"distance\":%.17g,"
                    "\"t_difference\":%.17g,\"exact\":[%.17g,%.17g,%.17g,%.17g]}",
                    any++ ? "," : "", lines[k], jk->dist, jk->dt, jk->ex[0], jk->ex[1],
                    jk->ex[2], jk->ex[3]);
        if (jk->problems & VB_VERIFY_MISSING) {
            size_t m = missing_ids(v, k, jk, scratch);
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"missing_members\",\"missing\":",
                    any++ ? "," : "", lines[k]);
            json_ids(f, scratch, m);
            fputc('}', f);
        }
        if (jk->problems & VB_VERIFY_DUPLICATE)
            fprintf(f, "%s\n{\"line\":%ld,\"class\":\"duplicate\",\"of_line\":%ld}",
                    any++ ? "," : "", lines[k], jk->dup_of);
    }
    for (size_t k = 0; k < missed->n; k++) {
        fprintf(f, "%s\n{\"class\":\"missed\",\"ids\":", any++ ? "," : "");
        json_ids(f, missed->ids + missed->start[k], missed->start[k + 1] - missed->start[k]);
        fprintf(f, ",\"x\":%.17g,\"y\":%.17g,\"z\":%.17g,\"t\":%.17g}", missed->x[k],
                missed->y[k], missed->z[k], missed->t[k]);
    }
    int ok = n->certified == n->lines && n->missed == 0 && (!more || more_ok);
    fputs("\n]", f);
    if (more) {
        fprintf(f, ",\"%s\":", key);
        more(f, arg);
    }
    fprintf(f, ",\"ok\":%s}\n", ok ? "true" : "false");
}

/* Scratch for the member lists of the report: one id per sphere. */
static uint32_t *scratch_for(vb_ctx *ctx, const vb_sphere_set *set)
{
    uint32_t *s = malloc((set->n ? set->n : 1) * sizeof *s);
    if (!s)
        vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    return s;
}

int vb_verify_write_text(vb_ctx *ctx, FILE *f, const char *name, const vb_sphere_set *set,
                         const vb_verify_report *r)
{
    uint32_t *scratch = scratch_for(ctx, set);
    if (!scratch)
        return VB_ENOMEM;
    print_human(f, name, set, r, scratch);
    free(scratch);
    return VB_OK;
}

int vb_verify_write_json_more(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                              const vb_sphere_set *set, const vb_verify_report *r,
                              const char *key, void (*more)(FILE *, const void *),
                              const void *arg, int more_ok)
{
    uint32_t *scratch = scratch_for(ctx, set);
    if (!scratch)
        return VB_ENOMEM;
    print_json(f, spheres_name, name, r, scratch, key, more, arg, more_ok);
    free(scratch);
    return VB_OK;
}

int vb_verify_write_json(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                         const vb_sphere_set *set, const vb_verify_report *r)
{
    return vb_verify_write_json_more(ctx, f, spheres_name, name, set, r, NULL, NULL, NULL, 1);
}
