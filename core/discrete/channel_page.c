/* Channels on the results page (vbc_page.h). */
#include <stdio.h>
#include <stdlib.h>

#include "vbc_page.h"

static const char *row_kind(int kind)
{
    return kind == VBC_CHANNEL ? "channel" : kind == VBC_PORE ? "pore" : "cavity";
}

static int add_counts(vb_page *p, int k, const vbc_result *res)
{
    size_t count[3] = {0, 0, 0}; /* pores, channels, cavities */
    for (size_t t = 0; t < res->nchannels; t++) {
        int kind = res->channels[t].kind;
        count[kind == VBC_PORE ? 0 : kind == VBC_CHANNEL ? 1 : 2]++;
    }
    static const char *const what[3] = {"pores", "channels", "cavities"};
    char v[32];
    int rc = VB_OK;
    for (int j = 0; j < 3 && rc == VB_OK; j++) {
        snprintf(v, sizeof v, "%zu", count[j]);
        rc = vb_page_fact(p, k, what[j], v);
    }
    return rc;
}

/* The pore's centreline as a profile: axial coordinate (the table's s,
 * along the pore's axis) and radius. */
static int add_profile(vb_page *p, int k, const vbc_result *res, const vbc_channel *c, const char *name)
{
    const vbc_point *pt = res->points + c->first_point;
    double *s = malloc((c->npoints ? c->npoints : 1) * 2 * sizeof *s);
    if (!s)
        return VB_ENOMEM;
    double *r = s + c->npoints;
    const double *u = res->pore.u;
    for (size_t j = 0; j < c->npoints; j++) {
        s[j] = pt[j].x * u[0] + pt[j].y * u[1] + pt[j].z * u[2];
        r[j] = pt[j].r;
    }
    int rc = vb_page_profile(p, k, name, c->npoints, s, r);
    free(s);
    return rc;
}

static int add_row(vb_page *p, int k, const vbc_result *res, size_t t)
{
    const vbc_channel *c = &res->channels[t];
    const vbc_point *pt = res->points + c->first_point;
    char name[48], key[80], v[32];
    snprintf(name, sizeof name, "%s %zu", row_kind(c->kind), t + 1);
    double *xyz = malloc((c->npoints ? c->npoints : 1) * 4 * sizeof *xyz);
    if (!xyz)
        return VB_ENOMEM;
    double *r = xyz + 3 * c->npoints;
    for (size_t j = 0; j < c->npoints; j++) {
        xyz[3 * j] = pt[j].x;
        xyz[3 * j + 1] = pt[j].y;
        xyz[3 * j + 2] = pt[j].z;
        r[j] = pt[j].r;
    }
    int rc = vb_page_path(p, k, name, c->npoints, xyz, r);
    free(xyz);
    snprintf(key, sizeof key, "%s: bottleneck radius (Å)", name);
    snprintf(v, sizeof v, "%.3f", c->bottleneck);
    if (rc == VB_OK)
        rc = vb_page_fact(p, k, key, v);
    snprintf(key, sizeof key, "%s: length (Å)", name);
    snprintf(v, sizeof v, "%.3f", c->length);
    if (rc == VB_OK)
        rc = vb_page_fact(p, k, key, v);
    if (rc == VB_OK && c->kind == VBC_PORE && res->pore.present)
        rc = add_profile(p, k, res, c, name);
    return rc;
}

int vbc_page_add(vb_page *p, const char *label, const vb_sphere_set *s, const vbc_result *res)
{
    int k, rc = vb_page_frame_set(p, label, s, &k);
    if (rc != VB_OK || k < 0)
        return rc;
    rc = add_counts(p, k, res);
    for (size_t t = 0; t < res->nchannels && rc == VB_OK; t++)
        rc = add_row(p, k, res, t);
    return rc;
}
