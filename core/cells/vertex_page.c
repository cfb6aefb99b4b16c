/* Certified vertices on the results page (vb_vertex_page.h). */
#include <stdio.h>
#include <stdlib.h>

#include "vb_page.h"
#include "vb_vertex_page.h"

int vb_vertex_page_check(vb_ctx *ctx, const vb_sphere_set *set)
{
    if (set->n <= VB_VERTEX_PAGE_MAX_SPHERES)
        return VB_OK;
    return vb_error(ctx, VB_EINPUT_PAGE_SIZE, set->source, 0,
                    "%zu spheres: a vertices results page (--html) takes at most %u "
                    "(each vertex is drawn); the vertex table has them all",
                    set->n, VB_VERTEX_PAGE_MAX_SPHERES);
}

/* The page's content: one frame with the vertices and the figures. */
static int fill(vb_page *p, const vb_sphere_set *set, const vb_vertex_list *v,
                const char *certificate)
{
    int k, rc = vb_page_frame(p, "structure", NULL, &k);
    if (rc != VB_OK)
        return rc;
    double *xyz = malloc((v->n ? v->n : 1) * 3 * sizeof *xyz);
    if (!xyz)
        return VB_ENOMEM;
    for (size_t i = 0; i < v->n; i++) {
        xyz[3 * i] = v->x[i];
        xyz[3 * i + 1] = v->y[i];
        xyz[3 * i + 2] = v->z[i];
    }
    rc = vb_page_points(p, k, "vertices", v->n, xyz, v->t);
    free(xyz);
    if (rc == VB_OK)
        rc = vb_page_fact_count(p, k, "spheres", set->n);
    if (rc == VB_OK)
        rc = vb_page_fact_count(p, k, "vertices", v->n);
    if (rc == VB_OK && certificate && certificate[0])
        rc = vb_page_fact(p, k, "certificate", certificate);
    return rc;
}

int vb_vertex_page_write(vb_ctx *ctx, const char *path, const char *title,
                         const vb_sphere_set *set, const vb_vertex_list *v,
                         const char *certificate)
{
    int rc = vb_vertex_page_check(ctx, set);
    if (rc != VB_OK)
        return rc;
    vb_page *p = vb_page_new(ctx, title, set);
    if (!p)
        return vb_errcode(ctx);
    rc = fill(p, set, v, certificate);
    if (rc == VB_ENOMEM)
        rc = vb_error(ctx, rc, NULL, 0, "out of memory for the results page");
    if (rc == VB_OK)
        rc = vb_page_write(p, path);
    vb_page_free(p);
    return rc;
}
