/* A periodic vertex file judged exactly (vb_periodic_verify.h). */
#include "vb_periodic_verify.h"

#include <stdlib.h>
#include <string.h>

#include "vb_verify_file.h"

void vb_periodic_judgement_free(vb_periodic_judgement *j)
{
    if (!j)
        return;
    free(j->line);
    free(j->flags);
    free(j->problems);
    memset(j, 0, sizeof *j);
}

/* The counts of the judged lines. */
static void tally(vb_periodic_judgement *j)
{
    for (size_t a = 0; a < j->n; a++) {
        int pr = j->problems[a];
        j->not_canonical += (j->flags[a] & VB_PERIODIC_NOT_CANONICAL) != 0;
        j->beyond += (j->flags[a] & VB_PERIODIC_BEYOND) != 0;
        j->not_vertex += (pr & VB_VERIFY_NOT_VERTEX) != 0;
        j->wrong += (pr & VB_VERIFY_WRONG_COORDS) != 0;
        j->missing += (pr & VB_VERIFY_MISSING) != 0;
        j->duplicate += (pr & VB_VERIFY_DUPLICATE) != 0;
        j->certified += pr == 0 && !j->flags[a];
    }
}

int vb_periodic_verify_file(vb_ctx *ctx, const vb_sphere_set *set, const vb_box *box,
                            const char *path, double tol, vb_periodic_judgement *out)
{
    memset(out, 0, sizeof *out);
    vb_periodic_images img;
    memset(&img, 0, sizeof img);
    vb_periodic_vertices v;
    memset(&v, 0, sizeof v);
    int rc = vb_periodic_read(ctx, path, &v, &out->line);
    if (rc == VB_OK) {
        /* The file's points and radii are judged within tol: the images'
         * bounds allow for that (vb_periodic_image_opt). */
        const vb_periodic_image_opt opt = {tol, 0, 0.0};
        rc = vb_periodic_images_build_opt(ctx, set, box, &opt, &img);
    }
    size_t *row = NULL;
    if (rc == VB_OK) {
        out->n = v.n;
        row = malloc((v.n ? v.n : 1) * sizeof *row);
        out->flags = malloc(v.n ? v.n : 1);
        out->problems = calloc(v.n ? v.n : 1, sizeof *out->problems);
        if (!row || !out->flags || !out->problems)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    vb_vertex_list list;
    vb_vertex_list_init(&list);
    vb_verify_report r;
    memset(&r, 0, sizeof r);
    if (rc == VB_OK)
        rc = vb_periodic_to_images(ctx, &img, &v, &list, row, out->flags);
    if (rc == VB_OK && list.n)
        rc = vb_verify_list(ctx, img.set, path, &list, VB_VFMT_TSV, tol, 0, &r);
    if (rc == VB_OK) {
        for (size_t k = 0; k < list.n; k++)
            out->problems[row[k]] = r.judged[k].problems;
        tally(out);
    } else {
        vb_periodic_judgement_free(out);
    }
    vb_verify_report_free(&r);
    vb_vertex_list_free(&list);
    free(row);
    vb_periodic_vertices_free(&v);
    vb_periodic_images_free(&img);
    return rc;
}
