/* `vorball verify --periodic SPHERES VERTICES`: a periodic vertex file
 * (i@(dx,dy,dz) members) judged exactly by the library
 * (vb_periodic_verify_file); this file reports. */
#include "verify_periodic.h"

#include <string.h>

#include "cli_common.h"
#include "vb_periodic_verify.h"
#include "vb_verify_file.h"

static void report_line(FILE *f, const char *name, long line, const char *what)
{
    fprintf(f, "%s:%ld: %s\n", name, line, what);
}

/* The problems, FILE:LINE: class: first the lines the periodic wing
 * flagged, then those the exact verifier found, in file order. */
static void report_lines(FILE *out, const char *path, const vb_periodic_judgement *j)
{
    for (size_t a = 0; a < j->n; a++) {
        if (j->flags[a] & VB_PERIODIC_NOT_CANONICAL)
            report_line(out, path, j->line[a], "not canonical: not the vertex's canonical "
                                               "translate (README, Periodic boxes)");
        if (j->flags[a] & VB_PERIODIC_BEYOND)
            report_line(out, path, j->line[a], "not a vertex: a member beyond the images' "
                                               "reach, or t above the bound of every empty "
                                               "sphere");
    }
    for (size_t a = 0; a < j->n; a++) {
        int pr = j->problems[a];
        long ln = j->line[a];
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
}

int vb_cli_verify_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                           const char *path, double tol, int json, FILE *out, int *mismatch)
{
    vb_box box;
    vb_periodic_judgement j;
    memset(&j, 0, sizeof j);
    int rc = vb_cli_periodic_box(ctx, set, p, &box);
    if (rc == VB_OK)
        rc = vb_periodic_verify_file(ctx, set, &box, path, tol, &j);
    if (rc == VB_OK) {
        if (!json)
            report_lines(out, path, &j);
        *mismatch = j.certified != j.n;
        if (json)
            fprintf(out,
                    "{\"periodic\":true,\"lines\":%zu,\"certified\":%zu,\"not_canonical\":%zu,"
                    "\"beyond_reach\":%zu,\"not_vertex\":%zu,\"wrong_coordinates\":%zu,"
                    "\"missing_members\":%zu,\"duplicate\":%zu,\"ok\":%s}\n",
                    j.n, j.certified, j.not_canonical, j.beyond, j.not_vertex, j.wrong,
                    j.missing, j.duplicate, *mismatch ? "false" : "true");
        else
            fprintf(out,
                    "%s: %zu periodic vertex lines: %zu certified, %zu not canonical, %zu beyond "
                    "reach, %zu not a vertex, %zu wrong coordinates, %zu missing members, %zu "
                    "duplicate\n",
                    path, j.n, j.certified, j.not_canonical, j.beyond, j.not_vertex, j.wrong,
                    j.missing, j.duplicate);
    }
    vb_periodic_judgement_free(&j);
    return rc;
}
