/* Writers of vertex files: tsv (default), json and Voronota's vertex lines.
 * Numbers are printed with %.17g so that every double reads back bit-exactly;
 * goldens in corpus/ are compared byte for byte, so the layout is fixed. */
#include "vb_vertex_io.h"

#include <math.h>
#include <string.h>

#include "vb_json.h"

int vb_vertex_format_parse(vb_ctx *ctx, const char *name, vb_vertex_format *out)
{
    if (strcmp(name, "tsv") == 0)
        *out = VB_VFMT_TSV;
    else if (strcmp(name, "json") == 0)
        *out = VB_VFMT_JSON;
    else if (strcmp(name, "voronota") == 0)
        *out = VB_VFMT_VORONOTA;
    else
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "unknown vertex format '%s' (expected tsv, json or voronota)", name);
    return VB_OK;
}

const char *vb_vertex_status_name(int status)
{
    switch (status) {
    case VB_VERTEX_CANDIDATE: return "candidate";
    case VB_VERTEX_CERTIFIED: return "certified";
    case VB_VERTEX_REJECTED: return "rejected";
    default: return "unknown";
    }
}

/* Comment text may span lines; each becomes its own '#' line so that the
 * reader's "skip lines starting with #" rule holds. */
static void write_comment_lines(FILE *f, const char *comment)
{
    const char *p = comment;
    while (*p) {
        size_t len = strcspn(p, "\n");
        fprintf(f, "# %.*s\n", (int)len, p);
        p += len;
        if (*p == '\n')
            p++;
    }
}

static void write_tsv(FILE *f, const vb_vertex_list *v, const char *comment)
{
    fputs("# vorball vertices\n", f);
    if (comment)
        write_comment_lines(f, comment);
    fputs("# ids\tx\ty\tz\tt\tstatus\n", f);
    for (size_t k = 0; k < v->n; k++) {
        for (size_t i = v->start[k]; i < v->start[k + 1]; i++)
            fprintf(f, i == v->start[k] ? "%u" : ",%u", (unsigned)v->ids[i]);
        fprintf(f, "\t%.17g\t%.17g\t%.17g\t%.17g\t%s\n", v->x[k], v->y[k], v->z[k], v->t[k],
                vb_vertex_status_name(v->status[k]));
    }
}

/* JSON has no NaN or Inf: a non-finite value (only possible in a candidate
 * list) is written as null, which the reader refuses with a line number. */
static void json_number(FILE *f, const char *key, double d)
{
    if (isfinite(d))
        fprintf(f, ",\"%s\":%.17g", key, d);
    else
        fprintf(f, ",\"%s\":null", key);
}

static void write_json(FILE *f, const vb_vertex_list *v, const char *comment)
{
    fputs("{", f);
    if (comment) {
        fputs("\"comment\":", f);
        vb_json_write_string(f, comment);
        fputs(",", f);
    }
    fputs("\"vertices\":[", f);
    for (size_t k = 0; k < v->n; k++) {
        fputs(k ? ",\n{\"ids\":[" : "\n{\"ids\":[", f);
        for (size_t i = v->start[k]; i < v->start[k + 1]; i++)
            fprintf(f, i == v->start[k] ? "%u" : ",%u", (unsigned)v->ids[i]);
        fputs("]", f);
        json_number(f, "x", v->x[k]);
        json_number(f, "y", v->y[k]);
        json_number(f, "z", v->z[k]);
        json_number(f, "t", v->t[k]);
        fprintf(f, ",\"status\":\"%s\"}", vb_vertex_status_name(v->status[k]));
    }
    fputs("\n]}\n", f);
}

/* Voronota lists one tangent sphere per quadruple. A vertex with k > 4
 * members is written as the k - 3 quadruples made of its three smallest ids
 * and each further id: together they name every member, and at least one of
 * them determines the point on its own (see vb_vertex_io.h). */
static int write_voronota(vb_ctx *ctx, FILE *f, const vb_vertex_list *v)
{
    for (size_t k = 0; k < v->n; k++) {
        const uint32_t *id = v->ids + v->start[k];
        size_t m = v->start[k + 1] - v->start[k];
        if (m < 4)
            return vb_error(ctx, VB_EMISUSE, NULL, 0,
                            "vertex %zu has %zu ids: voronota lines need 4", k, m);
        for (size_t j = 3; j < m; j++)
            fprintf(f, "%u %u %u %u %.17g %.17g %.17g %.17g\n", (unsigned)id[0], (unsigned)id[1],
                    (unsigned)id[2], (unsigned)id[j], v->x[k], v->y[k], v->z[k], v->t[k]);
    }
    return VB_OK;
}

int vb_vertex_write(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                    const char *comment)
{
    int rc = VB_OK;
    switch (fmt) {
    case VB_VFMT_TSV: write_tsv(f, v, comment); break;
    case VB_VFMT_JSON: write_json(f, v, comment); break;
    case VB_VFMT_VORONOTA: rc = write_voronota(ctx, f, v); break;
    default: return vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown vertex format %d", (int)fmt);
    }
    if (rc != VB_OK)
        return rc;
    if (ferror(f))
        return vb_error(ctx, VB_EIO, NULL, 0, "writing vertices failed");
    return VB_OK;
}
