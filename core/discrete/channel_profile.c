/* Radius profiles of the channels (CSV, one row per point) and the
 * occupancy of the voxels over the frames of a trajectory. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_json.h"
#include "vbc_channel.h"

/* "A:GLY12:CA", or "#<index>" without atom records. */
static void atom_label(const vb_sphere_set *s, int32_t atom, char *buf, size_t len)
{
    if (atom < 0) {
        snprintf(buf, len, "-");
        return;
    }
    if (!s->info) {
        snprintf(buf, len, "#%d", (int)atom);
        return;
    }
    const vb_atom_info *a = &s->info[atom];
    if (a->icode != ' ' && a->icode != '\0')
        snprintf(buf, len, "%s:%s%d%c:%s", a->chain, a->resname, (int)a->resseq, a->icode, a->name);
    else
        snprintf(buf, len, "%s:%s%d:%s", a->chain, a->resname, (int)a->resseq, a->name);
}

void vbc_write_profile_header(FILE *f)
{
    fprintf(f, "frame,model,channel,kind,point,s_A,arc_A,x,y,z,radius_A,nearest_atom,touching_atoms\n");
}

/* Touching atoms: surfaces within this of the sphere (the atoms that bound it). */
#define TOUCH_A 0.05

void vbc_write_profile_rows(FILE *f, const vbc_frame_info *fi, const vb_sphere_set *s,
                            const vbc_result *res)
{
    const vbc_pore_summary *P = &res->pore;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        const vbc_point *p = res->points + c->first_point;
        double arc = 0.0;
        for (size_t u = 0; u < c->npoints; u++) {
            if (u > 0)
                arc += sqrt((p[u].x - p[u - 1].x) * (p[u].x - p[u - 1].x) +
                            (p[u].y - p[u - 1].y) * (p[u].y - p[u - 1].y) +
                            (p[u].z - p[u - 1].z) * (p[u].z - p[u - 1].z));
            char label[96];
            fprintf(f, "%ld,%d,%zu,%s,%zu,", fi->frame, fi->model, t + 1,
                    c->kind == VBC_PORE ? "pore" : c->kind == VBC_CHANNEL ? "channel" : "cavity", u);
            if (P->present)
                fprintf(f, "%.3f", p[u].x * P->u[0] + p[u].y * P->u[1] + p[u].z * P->u[2]);
            fprintf(f, ",%.3f,%.3f,%.3f,%.3f,%.4f,", arc, p[u].x, p[u].y, p[u].z, p[u].r);
            atom_label(s, p[u].atom, label, sizeof label);
            vb_csv_write_field(f, label);
            fputc(',', f);
            /* The atoms that bound this sphere, by a scan with a cheap box test. */
            char *field = NULL;
            size_t len = 0;
            FILE *m = open_memstream(&field, &len);
            if (m) {
                double reach = p[u].r + TOUCH_A;
                int any = 0;
                for (size_t i = 0; i < s->n; i++) {
                    double lim = reach + s->r[i];
                    double dx = p[u].x - s->x[i], dy = p[u].y - s->y[i], dz = p[u].z - s->z[i];
                    if (fabs(dx) > lim || fabs(dy) > lim || fabs(dz) > lim)
                        continue;
                    if (sqrt(dx * dx + dy * dy + dz * dz) - s->r[i] > reach)
                        continue;
                    atom_label(s, (int32_t)i, label, sizeof label);
                    fprintf(m, "%s%s", any ? ";" : "", label);
                    any = 1;
                }
                fclose(m);
            }
            vb_csv_write_field(f, field ? field : "");
            free(field);
            fputc('\n', f);
        }
    }
}

int vbc_occupancy_add(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_result *res,
                      float *count)
{
    size_t nv = vbc_grid_voxels(g);
    uint8_t *hit = calloc(nv, 1);
    if (!hit)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "occupancy of %zu voxels", nv);
    for (size_t v = 0; flags && v < nv; v++)
        hit[v] = (flags[v] & VBC_F_CHANNEL) != 0;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        if (c->kind != VBC_PORE)
            continue;
        const vbc_point *p = res->points + c->first_point;
        for (size_t u = 0; u < c->npoints; u++) {
            if (!(p[u].r > 0.0))
                continue;
            double q[3] = {p[u].x, p[u].y, p[u].z};
            int lo[3], hi[3], n[3] = {g->nx, g->ny, g->nz};
            for (int a = 0; a < 3; a++) {
                double f0 = floor((q[a] - p[u].r - g->origin[a]) / g->h - 0.5);
                double f1 = ceil((q[a] + p[u].r - g->origin[a]) / g->h - 0.5);
                lo[a] = f0 < 0 ? 0 : f0 >= n[a] ? n[a] : (int)f0;
                hi[a] = f1 < 0 ? -1 : f1 >= n[a] ? n[a] - 1 : (int)f1;
            }
            for (int k = lo[2]; k <= hi[2]; k++)
                for (int j = lo[1]; j <= hi[1]; j++)
                    for (int i = lo[0]; i <= hi[0]; i++) {
                        double dx = g->origin[0] + (i + 0.5) * g->h - q[0];
                        double dy = g->origin[1] + (j + 0.5) * g->h - q[1];
                        double dz = g->origin[2] + (k + 0.5) * g->h - q[2];
                        if (dx * dx + dy * dy + dz * dz <= p[u].r * p[u].r)
                            hit[(size_t)i + (size_t)g->nx * ((size_t)j + (size_t)g->ny * (size_t)k)] = 1;
                    }
        }
    }
    for (size_t v = 0; v < nv; v++)
        count[v] += hit[v];
    free(hit);
    return VB_OK;
}
