/* Arc closure of a judged vertex file (vb_verify_arcs) and the text of the
 * certificate (vb_arc_write_text). */
#include <stdlib.h>

#include "vb_json.h"

#include "vb_verify_file.h"

int vb_verify_arcs(vb_ctx *ctx, const vb_sphere_set *set, const vb_verify_report *judged,
                   unsigned threads, vb_arc_report *out)
{
    vb_vertex_list in;
    vb_vertex_list_init(&in);
    size_t n = judged->vertices.n;
    uint8_t *seen = NULL;
    size_t nkeys = 0;
    for (size_t k = 0; k < n; k++)
        if (judged->judged[k].has_key && judged->judged[k].key >= nkeys)
            nkeys = judged->judged[k].key + 1;
    seen = calloc(nkeys ? nkeys : 1, 1);
    int rc = seen ? VB_OK : VB_ENOMEM;
    for (size_t k = 0; rc == VB_OK && k < n; k++) {
        const vb_verify_line *l = &judged->judged[k];
        if (l->problems || !l->has_key || seen[l->key])
            continue;
        seen[l->key] = 1;
        rc = vb_vertex_list_push(&in, l->members, l->nmembers, l->ex[0], l->ex[1], l->ex[2],
                                 l->ex[3], 0, VB_VERTEX_CERTIFIED);
    }
    free(seen);
    if (rc == VB_OK)
        rc = vb_arc_close_edges(ctx, set, judged->cert_set == set ? judged->cert : NULL, &in,
                                threads, out, NULL, NULL);
    else
        vb_arc_report_free(out);
    vb_vertex_list_free(&in);
    return rc;
}

int vb_arc_write_text(vb_ctx *ctx, FILE *f, const char *name, const vb_arc_report *r)
{
    const vb_vertex_list *a = &r->added;
    for (size_t k = 0; k < a->n; k++) {
        fprintf(f, "%s: missing vertex ", name);
        for (size_t i = a->start[k]; i < a->start[k + 1]; i++)
            fprintf(f, i > a->start[k] ? ",%u" : "%u", (unsigned)a->ids[i]);
        fprintf(f, " at %.17g %.17g %.17g t %.17g (found by arc closure)\n", a->x[k], a->y[k],
                a->z[k], a->t[k]);
    }
    fprintf(f,
            "%s: arcs: %zu vertices traced, %zu half arcs: %zu closed at a vertex, %zu to "
            "infinity, %zu closed loops, %zu undecided; %zu vertices added; %zu components\n",
            name, r->vertices, r->half_arcs, r->closed, r->infinite, r->loops, r->undecided,
            a->n, r->components);
    if (ferror(f))
        return vb_error(ctx, VB_EIO, NULL, 0, "cannot write the arc report");
    return VB_OK;
}

/* The arc report as a JSON object (vb_verify_write_json_arcs). */
static void arcs_json(FILE *f, const void *arg)
{
    const vb_arc_report *r = arg;
    const vb_vertex_list *a = &r->added;
    fprintf(f,
            "{\"vertices\":%zu,\"half_arcs\":%zu,\"closed\":%zu,\"infinite\":%zu,"
            "\"loops\":%zu,\"undecided\":%zu,\"added\":%zu,\"components\":%zu,"
            "\"complete\":%s,\"missing\":[",
            r->vertices, r->half_arcs, r->closed, r->infinite, r->loops, r->undecided, a->n,
            r->components, vb_arc_report_complete(r) ? "true" : "false");
    for (size_t k = 0; k < a->n; k++) {
        fputs(k ? ",\n{\"ids\":[" : "\n{\"ids\":[", f);
        for (size_t i = a->start[k]; i < a->start[k + 1]; i++)
            fprintf(f, i > a->start[k] ? ",%u" : "%u", (unsigned)a->ids[i]);
        fprintf(f, "],\"x\":%.17g,\"y\":%.17g,\"z\":%.17g,\"t\":%.17g}", a->x[k], a->y[k],
                a->z[k], a->t[k]);
    }
    fputs("]}", f);
}

int vb_verify_write_json_arcs(vb_ctx *ctx, FILE *f, const char *spheres_name, const char *name,
                              const vb_sphere_set *set, const vb_verify_report *judged,
                              const vb_arc_report *r)
{
    int rc = vb_verify_write_json_more(ctx, f, spheres_name, name, set, judged, "arcs",
                                       arcs_json, r, vb_arc_report_complete(r));
    if (rc == VB_OK && ferror(f))
        rc = vb_error(ctx, VB_EIO, NULL, 0, "cannot write the arc report");
    return rc;
}
