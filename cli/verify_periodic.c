/* `vorball verify --periodic SPHERES VERTICES`: a periodic vertex file
 * (i@(dx,dy,dz) members) judged exactly. The library reads it and names
 * its members by the images (core/periodic/), the exact verifier judges
 * them (vb_verify_list); this file reports. */
#include "verify_periodic.h"

#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "vb_verify_file.h"

typedef struct tally {
    size_t lines, certified, not_canonical, beyond, not_vertex, wrong, missing, duplicate;
} tally;

static void report_line(FILE *f, const char *name, long line, const char *what)
{
    fprintf(f, "%s:%ld: %s\n", name, line, what);
}

int vb_cli_verify_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                           const char *path, double tol, int json, FILE *out, int *mismatch)
{
    vb_box box;
    int rc = vb_cli_periodic_box(ctx, set, p, &box);
    vb_periodic_images img;
    memset(&img, 0, sizeof img);
    vb_periodic_vertices v;
    memset(&v, 0, sizeof v);
    long *lines = NULL;
    if (rc == VB_OK)
        rc = vb_periodic_read(ctx, path, &v, &lines);
    if (rc == VB_OK)
        rc = vb_periodic_images_build(ctx, set, &box, &img);
    size_t *row = rc == VB_OK ? malloc(v.n * sizeof *row) : NULL;
    uint8_t *flags = rc == VB_OK ? malloc(v.n) : NULL;
    if (rc == VB_OK && (!row || !flags))
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    vb_vertex_list list;
    vb_vertex_list_init(&list);
    vb_verify_report r;
    memset(&r, 0, sizeof r);
    if (rc == VB_OK)
        rc = vb_periodic_to_images(ctx, &img, &v, &list, row, flags);
    if (rc == VB_OK && list.n)
        rc = vb_verify_list(ctx, img.set, path, &list, VB_VFMT_TSV, tol, 0, &r);
    tally t = {0};
    if (rc == VB_OK) {
        t.lines = v.n;
        for (size_t a = 0; a < v.n; a++) {
            if ((flags[a] & VB_PERIODIC_NOT_CANONICAL) && !json)
                report_line(out, path, lines[a], "not canonical: not the vertex's canonical "
                                                 "translate (README, Periodic boxes)");
            if ((flags[a] & VB_PERIODIC_BEYOND) && !json)
                report_line(out, path, lines[a], "not a vertex: a member beyond the images' "
                                                 "reach, or t above the bound of every empty "
                                                 "sphere");
            t.not_canonical += (flags[a] & VB_PERIODIC_NOT_CANONICAL) != 0;
            t.beyond += (flags[a] & VB_PERIODIC_BEYOND) != 0;
        }
        for (size_t k = 0; k < list.n; k++) {
            int pr = r.judged[k].problems;
            long ln = lines[row[k]];
            t.not_vertex += (pr & VB_VERIFY_NOT_VERTEX) != 0;
            t.wrong += (pr & VB_VERIFY_WRONG_COORDS) != 0;
            t.missing += (pr & VB_VERIFY_MISSING) != 0;
            t.duplicate += (pr & VB_VERIFY_DUPLICATE) != 0;
            t.certified += pr == 0 && !flags[row[k]];
            if (json)
                continue;
            if (pr & VB_VERIFY_NOT_VERTEX)
                report_line(out, path, ln, "not a vertex: a sphere or image cuts the tangent "
                                           "sphere, or the members define none");
            if (pr & VB_VERIFY_WRONG_COORDS)
                report_line(out, path, ln, "wrong coordinates");
            if (pr & VB_VERIFY_MISSING)
                report_line(out, path, ln, "missing members");
            if (pr & VB_VERIFY_DUPLICATE)
                report_line(out, path, ln, "duplicate: an earlier line names the same vertex");
        }
        *mismatch = t.certified != t.lines;
        if (json)
            fprintf(out,
                    "{\"periodic\":true,\"lines\":%zu,\"certified\":%zu,\"not_canonical\":%zu,"
                    "\"beyond_reach\":%zu,\"not_vertex\":%zu,\"wrong_coordinates\":%zu,"
                    "\"missing_members\":%zu,\"duplicate\":%zu,\"ok\":%s}\n",
                    t.lines, t.certified, t.not_canonical, t.beyond, t.not_vertex, t.wrong,
                    t.missing, t.duplicate, *mismatch ? "false" : "true");
        else
            fprintf(out,
                    "%s: %zu periodic vertex lines: %zu certified, %zu not canonical, %zu beyond "
                    "reach, %zu not a vertex, %zu wrong coordinates, %zu missing members, %zu "
                    "duplicate\n",
                    path, t.lines, t.certified, t.not_canonical, t.beyond, t.not_vertex, t.wrong,
                    t.missing, t.duplicate);
    }
    vb_verify_report_free(&r);
    vb_vertex_list_free(&list);
    free(row);
    free(flags);
    free(lines);
    vb_periodic_vertices_free(&v);
    vb_periodic_images_free(&img);
    return rc;
}
