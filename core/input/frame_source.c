/* The frames of a molecule: a multi-model reader, or a DCD plus its
 * topology, every frame checked (vb_frames.h). */
#include "vb_frames.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_dcd.h"
#include "vbi_input.h"

struct vb_frame_source {
    vb_frame_reader *rd;
    vb_dcd *dcd;
    char *dcd_path;
    vb_sphere_set *topo; /* DCD: every atom of the topology */
    size_t *keep;        /* DCD: topology atoms that enter the analysis */
    size_t nkeep;
    double *xyz;         /* DCD: one frame, 3 * natoms */
    long index;          /* frames read so far */
};

void vb_frame_source_close(vb_frame_source *F)
{
    if (!F)
        return;
    vb_frame_reader_close(F->rd);
    vb_dcd_close(F->dcd);
    vb_spheres_free(F->topo);
    free(F->dcd_path);
    free(F->keep);
    free(F->xyz);
    free(F);
}

static int open_dcd(vb_ctx *ctx, vb_frame_source *F, const char *path, const char *dcd_path,
                    const vb_read_options *ro)
{
    /* The topology must list every atom of the DCD: read all, select after. */
    vb_read_options all = *ro;
    all.keep_water = 1;
    all.drop_hydrogens = 0;
    int rc = vb_spheres_read_file(ctx, path, &all, &F->topo);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, F->topo, 1);
    if (rc == VB_OK)
        rc = vb_dcd_open(ctx, dcd_path, &F->dcd);
    if (rc != VB_OK)
        return rc;
    if (!(F->dcd_path = strdup(dcd_path)))
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    size_t na = vb_dcd_atoms(F->dcd);
    if (na != F->topo->n)
        return vb_error(ctx, VB_EINPUT_MODEL, dcd_path, 0,
                        "DCD has %zu atoms per frame, topology %s has %zu", na, path, F->topo->n);
    F->keep = malloc(na * sizeof *F->keep);
    F->xyz = malloc(3 * na * sizeof *F->xyz);
    if (!F->keep || !F->xyz)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD frame of %zu atoms", na);
    for (size_t i = 0; i < na; i++) {
        const vb_atom_info *a = F->topo->info ? &F->topo->info[i] : NULL;
        if (a && !ro->keep_water && vbi_is_water(a->resname))
            continue;
        if (a && ro->drop_hydrogens && vbi_is_hydrogen(a->element))
            continue;
        F->keep[F->nkeep++] = i;
    }
    if (F->nkeep == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, path, 0, "no atoms left after dropping water");
    return VB_OK;
}

int vb_frame_source_open(vb_ctx *ctx, const char *path, const char *dcd_path,
                         const vb_read_options *ro, vb_frame_source **out)
{
    *out = NULL;
    vb_frame_source *F = calloc(1, sizeof *F);
    if (!F)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    int rc = dcd_path ? open_dcd(ctx, F, path, dcd_path, ro)
                      : vb_frame_reader_open(ctx, path, ro, &F->rd); /* --model picks one frame */
    if (rc != VB_OK) {
        vb_frame_source_close(F);
        return rc;
    }
    *out = F;
    return VB_OK;
}

/* A DCD frame has no decimals: its coordinates are checked as doubles
 * against the limits vb_spheres_validate applies to decimals. */
static int check_frame(vb_ctx *ctx, const vb_frame_source *F, const vb_sphere_set *s)
{
    const double *c[3] = {s->x, s->y, s->z};
    for (size_t i = 0; i < s->n; i++)
        for (int a = 0; a < 3; a++) {
            double v = c[a][i];
            size_t atom = F->keep[i];
            if (!isfinite(v))
                return vb_error(ctx, VB_EINPUT_NONFINITE, F->dcd_path, 0,
                                "frame %ld: atom %zu (topology line %ld) has coordinate %g",
                                F->index, atom + 1, F->topo->line[atom], v);
            if (fabs(v) > 1e9)
                return vb_error(ctx, VB_EINPUT_MAGNITUDE, F->dcd_path, 0,
                                "frame %ld: atom %zu (topology line %ld): coordinate %.17g "
                                "exceeds 1e9 in magnitude",
                                F->index, atom + 1, F->topo->line[atom], v);
        }
    return VB_OK;
}

static int next_dcd(vb_ctx *ctx, vb_frame_source *F, vb_sphere_set **out, int *model)
{
    size_t na = F->topo->n;
    int got;
    int rc = vb_dcd_next(ctx, F->dcd, F->xyz, F->xyz + na, F->xyz + 2 * na, NULL, &got);
    if (rc != VB_OK || !got)
        return rc;
    vb_sphere_set *s;
    if ((rc = vb_spheres_new(ctx, F->dcd_path, F->nkeep, F->topo->info != NULL, &s)) != VB_OK)
        return rc;
    for (size_t i = 0; i < F->nkeep; i++) {
        size_t k = F->keep[i];
        s->x[i] = F->xyz[k];
        s->y[i] = F->xyz[na + k];
        s->z[i] = F->xyz[2 * na + k];
        s->r[i] = F->topo->r[k];
        s->line[i] = F->topo->line[k];
        if (F->topo->info)
            s->info[i] = F->topo->info[k];
    }
    if ((rc = check_frame(ctx, F, s)) != VB_OK) {
        vb_spheres_free(s);
        return rc;
    }
    *out = s;
    *model = (int)(F->index + 1);
    return VB_OK;
}

int vb_frame_source_next(vb_ctx *ctx, vb_frame_source *F, vb_sphere_set **out, int *model)
{
    *out = NULL;
    int rc = F->rd ? vb_frame_reader_next(ctx, F->rd, out, model) : next_dcd(ctx, F, out, model);
    if (rc == VB_OK && *out && F->rd && (rc = vb_spheres_validate(ctx, *out, 1)) != VB_OK) {
        vb_spheres_free(*out);
        *out = NULL;
    }
    if (rc == VB_OK && *out)
        F->index++;
    return rc;
}
