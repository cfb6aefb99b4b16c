/* Writers of vertex files: tsv (default), json and Voronota's vertex lines.
 * Numbers are printed as %.17g (vb_format_g17, printf's bytes without printf)
 * so that every double reads back bit-exactly;
 * large lists are formatted on threads, written in order (the same bytes);
 * goldens in corpus/ are compared byte for byte, so the layout is fixed. */
#include "vb_vertex_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_build.h"
#include "vb_json.h"
#include "vb_numtext.h"
#include "vb_output.h"
#include "vb_write_lines.h"

int vb_vertex_format_parse(vb_ctx *ctx, const char *name, vb_vertex_format *out)
{
    if (strcmp(name, "tsv") == 0)
        *out = VB_VFMT_TSV;
    else if (strcmp(name, "json") == 0)
        *out = VB_VFMT_JSON;
    else if (strcmp(name, "voronota") == 0)
        *out = VB_VFMT_VORONOTA;
    else if (strcmp(name, "npz") == 0)
        *out = VB_VFMT_NPZ;
    else
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "unknown vertex format '%s' (expected tsv, json, voronota or npz)", name);
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

/* One vertex as a line of each format (json: the array's element, with the
 * separator before it), appended to a text (vb_write_lines). */
typedef void (*line_fn)(vb_text *t, const vb_vertex_list *v, size_t k);

static void ids_csv(vb_text *t, const vb_vertex_list *v, size_t k)
{
    for (size_t i = v->start[k]; i < v->start[k + 1]; i++)
        vb_text_u32(t, i != v->start[k] ? ',' : 0, v->ids[i]);
}

static void put_status(vb_text *t, char sep, int status, char end)
{
    const char *name = vb_vertex_status_name(status);
    size_t n = strlen(name);
    char *d = vb_text_room(t, n + 2);
    if (!d)
        return;
    d[0] = sep;
    memcpy(d + 1, name, n);
    d[n + 1] = end;
    t->n += n + 2;
}

static void tsv_line(vb_text *t, const vb_vertex_list *v, size_t k)
{
    ids_csv(t, v, k);
    vb_text_g17(t, '\t', v->x[k]);
    vb_text_g17(t, '\t', v->y[k]);
    vb_text_g17(t, '\t', v->z[k]);
    vb_text_g17(t, '\t', v->t[k]);
    put_status(t, '\t', v->status[k], '\n');
}

/* JSON has no NaN or Inf: a non-finite value (only possible in a candidate
 * list) is written as null, which the reader refuses with a line number.
 * key is the text before the value (",\"x\":"). */
static void json_number(vb_text *t, const char *key, double d)
{
    vb_text_put(t, key, strlen(key));
    if (isfinite(d))
        vb_text_g17(t, 0, d);
    else
        vb_text_put(t, "null", 4);
}

static void json_item(vb_text *t, const vb_vertex_list *v, size_t k)
{
    if (k)
        vb_text_put(t, ",\n{\"ids\":[", 10);
    else
        vb_text_put(t, "\n{\"ids\":[", 9);
    ids_csv(t, v, k);
    vb_text_put(t, "]", 1);
    json_number(t, ",\"x\":", v->x[k]);
    json_number(t, ",\"y\":", v->y[k]);
    json_number(t, ",\"z\":", v->z[k]);
    json_number(t, ",\"t\":", v->t[k]);
    vb_text_put(t, ",\"status\":", 10);
    put_status(t, '"', v->status[k], '"');
    vb_text_put(t, "}", 1);
}

/* Voronota lists one tangent sphere per quadruple. A vertex with k > 4
 * members is written as the k - 3 quadruples made of its three smallest ids
 * and each further id: together they name every member, and at least one of
 * them determines the point on its own (see vb_vertex_io.h). */
static void voronota_lines(vb_text *t, const vb_vertex_list *v, size_t k)
{
    const uint32_t *id = v->ids + v->start[k];
    size_t m = v->start[k + 1] - v->start[k];
    for (size_t j = 3; j < m; j++) {
        const uint32_t four[4] = {id[0], id[1], id[2], id[j]};
        for (int a = 0; a < 4; a++)
            vb_text_u32(t, a ? ' ' : 0, four[a]);
        vb_text_g17(t, ' ', v->x[k]);
        vb_text_g17(t, ' ', v->y[k]);
        vb_text_g17(t, ' ', v->z[k]);
        vb_text_g17(t, ' ', v->t[k]);
        vb_text_put(t, "\n", 1);
    }
}

/* A line_fn and its list, for vb_write_lines (blocks formatted on the
 * threads, written in order). */
typedef struct list_lines {
    const vb_vertex_list *v;
    line_fn fn;
} list_lines;

static void list_line(vb_text *t, const void *arg, size_t k)
{
    const list_lines *l = arg;
    l->fn(t, l->v, k);
}

static int write_lines(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, line_fn fn)
{
    const list_lines l = {v, fn};
    int rc = vb_write_lines(f, v->n, list_line, &l);
    if (rc == VB_EIO) {
        const char *name = f == stdout ? "<stdout>" : vb_output_name(f);
        return vb_error(ctx, VB_EIO, name, 0, "writing vertices failed");
    }
    return rc == VB_OK ? VB_OK
                       : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
}

/* The provenance lines, then the comment, as one text (malloc'd; NULL when
 * both are absent or memory is short, *nomem says which). */
static char *header_text(const vb_provenance *prov, const char *comment, int *nomem)
{
    *nomem = 0;
    if (!prov && !comment)
        return NULL;
    size_t np = prov ? vb_provenance_text(prov, NULL, 0) : 0;
    size_t nc = comment ? strlen(comment) : 0;
    char *t = malloc(np + nc + 1);
    if (!t) {
        *nomem = 1;
        return NULL;
    }
    if (prov)
        vb_provenance_text(prov, t, np + 1);
    memcpy(t + np, comment ? comment : "", nc + 1);
    return t;
}

static int write_tsv(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, const vb_provenance *prov,
                     const char *comment)
{
    fputs("# vorball vertices\n", f);
    if (vb_provenance_write_comments(f, "# ", prov, comment) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
    fputs("# ids\tx\ty\tz\tt\tstatus\n", f);
    return write_lines(ctx, f, v, tsv_line);
}

static int write_json(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, const vb_provenance *prov,
                      const char *comment)
{
    vb_provenance_write_json_head(f, prov, comment);
    fputs("\"vertices\":[", f);
    int rc = write_lines(ctx, f, v, json_item);
    fputs("\n]}\n", f);
    return rc;
}

static int write_voronota(vb_ctx *ctx, FILE *f, const vb_vertex_list *v)
{
    for (size_t k = 0; k < v->n; k++) {
        size_t m = v->start[k + 1] - v->start[k];
        if (m < 4)
            return vb_error(ctx, VB_EMISUSE, NULL, 0,
                            "vertex %zu has %zu ids: voronota lines need 4", k, m);
    }
    return write_lines(ctx, f, v, voronota_lines);
}

int vb_vertex_write(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                    const char *comment)
{
    return vb_vertex_write_prov(ctx, f, v, fmt, NULL, comment);
}

int vb_vertex_write_prov(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, vb_vertex_format fmt,
                         const vb_provenance *prov, const char *comment)
{
    int rc = VB_OK, nomem = 0;
    char *text = NULL;
    switch (fmt) {
    case VB_VFMT_TSV: rc = write_tsv(ctx, f, v, prov, comment); break;
    case VB_VFMT_JSON: rc = write_json(ctx, f, v, prov, comment); break;
    case VB_VFMT_VORONOTA: rc = write_voronota(ctx, f, v); break;
    case VB_VFMT_NPZ:
        text = header_text(prov, comment, &nomem);
        rc = nomem ? vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)")
                   : vb_vertex_write_npz(ctx, f, v, text);
        free(text);
        break;
    default: return vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown vertex format %d", (int)fmt);
    }
    if (rc != VB_OK)
        return rc;
    if (ferror(f)) {
        const char *name = f == stdout ? "<stdout>" : vb_output_name(f);
        return vb_error(ctx, VB_EIO, name, 0, "writing vertices failed");
    }
    return VB_OK;
}
