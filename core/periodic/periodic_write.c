/* Writers of periodic vertex files: the open files' layout (vertex_write.c)
 * with members written i@(dx,dy,dz). Numbers with %.17g, so every double
 * reads back bit-exactly. */
#include "vb_periodic.h"

#include <stdlib.h>
#include <string.h>

#include "vb_json.h"
#include "vb_output.h"

static void members(FILE *f, const vb_periodic_vertices *v, size_t k, int quoted)
{
    for (size_t j = v->start[k]; j < v->start[k + 1]; j++) {
        const vb_periodic_member *m = v->m + j;
        fprintf(f, "%s%s%u@(%d,%d,%d)%s", j == v->start[k] ? "" : ",", quoted ? "\"" : "",
                (unsigned)m->id, m->s[0], m->s[1], m->s[2], quoted ? "\"" : "");
    }
}

int vb_periodic_write(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                      const char *comment)
{
    return vb_periodic_write_prov(ctx, f, v, json, NULL, comment);
}

/* Comment text, one '#' line per line of it. */
int vb_periodic_write_prov(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                           const vb_provenance *prov, const char *comment)
{
    if (json) {
        vb_provenance_write_json_head(f, prov, comment);
        fputs("\"vertices\":[", f);
        for (size_t k = 0; k < v->n; k++) {
            fputs(k ? ",\n{\"ids\":[" : "\n{\"ids\":[", f);
            members(f, v, k, 1);
            fprintf(f, "],\"x\":%.17g,\"y\":%.17g,\"z\":%.17g,\"t\":%.17g,\"status\":\"certified\"}",
                    v->x[k], v->y[k], v->z[k], v->t[k]);
        }
        fputs("\n]}\n", f);
    } else {
        fputs("# vorball periodic vertices\n", f);
        if (vb_provenance_write_comments(f, "# ", prov, comment) != VB_OK)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
        fputs("# ids\tx\ty\tz\tt\tstatus\n", f);
        for (size_t k = 0; k < v->n; k++) {
            members(f, v, k, 0);
            fprintf(f, "\t%.17g\t%.17g\t%.17g\t%.17g\tcertified\n", v->x[k], v->y[k], v->z[k],
                    v->t[k]);
        }
    }
    if (ferror(f)) {
        const char *name = f == stdout ? "<stdout>" : vb_output_name(f);
        return vb_error(ctx, VB_EIO, name, 0, "writing periodic vertices failed");
    }
    return VB_OK;
}
