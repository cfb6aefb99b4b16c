/* Writers of periodic vertex files: the open files' layout (vertex_write.c)
 * with members written i@(dx,dy,dz). Numbers as %.17g (vb_text_g17: printf's
 * bytes, faster), so every double reads back bit-exactly. */
#include "vb_periodic.h"

#include <stdlib.h>
#include <string.h>

#include "vb_json.h"
#include "vb_numtext.h"
#include "vb_output.h"
#include "vb_write_lines.h"

static void members(vb_text *t, const vb_periodic_vertices *v, size_t k, int quoted)
{
    for (size_t j = v->start[k]; j < v->start[k + 1]; j++) {
        const vb_periodic_member *m = v->m + j;
        char *b = vb_text_room(t, 64);
        if (!b)
            return;
        size_t n = 0;
        if (j != v->start[k])
            b[n++] = ',';
        if (quoted)
            b[n++] = '"';
        n += vb_format_u32(m->id, b + n);
        b[n++] = '@';
        for (int a = 0; a < 3; a++) {
            b[n++] = a ? ',' : '(';
            n += vb_format_i32(m->s[a], b + n);
        }
        b[n++] = ')';
        if (quoted)
            b[n++] = '"';
        t->n += n;
    }
}

int vb_periodic_write(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                      const char *comment)
{
    return vb_periodic_write_prov(ctx, f, v, json, NULL, comment);
}

static void put(vb_text *t, const char *s)
{
    vb_text_put(t, s, strlen(s));
}

/* Vertex k as a JSON item (after a comma unless it is the first). */
static void json_item(vb_text *t, const void *arg, size_t k)
{
    const vb_periodic_vertices *v = arg;
    put(t, k ? ",\n{\"ids\":[" : "\n{\"ids\":[");
    members(t, v, k, 1);
    put(t, "],\"x\":");
    vb_text_g17(t, 0, v->x[k]);
    put(t, ",\"y\":");
    vb_text_g17(t, 0, v->y[k]);
    put(t, ",\"z\":");
    vb_text_g17(t, 0, v->z[k]);
    put(t, ",\"t\":");
    vb_text_g17(t, 0, v->t[k]);
    put(t, ",\"status\":\"certified\"}");
}

/* Vertex k as a TSV line. */
static void tsv_line(vb_text *t, const void *arg, size_t k)
{
    const vb_periodic_vertices *v = arg;
    members(t, v, k, 0);
    vb_text_g17(t, '\t', v->x[k]);
    vb_text_g17(t, '\t', v->y[k]);
    vb_text_g17(t, '\t', v->z[k]);
    vb_text_g17(t, '\t', v->t[k]);
    put(t, "\tcertified\n");
}

/* Comment text, one '#' line per line of it. The rows are formatted on
 * the threads (vb_write_lines), written in order. */
int vb_periodic_write_prov(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                           const vb_provenance *prov, const char *comment)
{
    int rc;
    if (json) {
        vb_provenance_write_json_head(f, prov, comment);
        fputs("\"vertices\":[", f);
        rc = vb_write_lines(f, v->n, json_item, v);
        fputs("\n]}\n", f);
    } else {
        fputs("# vorball periodic vertices\n", f);
        if (vb_provenance_write_comments(f, "# ", prov, comment) != VB_OK)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
        fputs("# ids\tx\ty\tz\tt\tstatus\n", f);
        rc = vb_write_lines(f, v->n, tsv_line, v);
    }
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
    if (rc != VB_OK || ferror(f)) {
        const char *name = f == stdout ? "<stdout>" : vb_output_name(f);
        return vb_error(ctx, VB_EIO, name, 0, "writing periodic vertices failed");
    }
    return VB_OK;
}
