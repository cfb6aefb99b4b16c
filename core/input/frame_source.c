/* The frames of a molecule: a multi-model reader, or a trajectory (DCD,
 * XTC, TRR) plus its topology (PDB, GRO, mmCIF, PQR, PSF), every frame
 * checked (vb_frames.h). */
#include "vb_frames.h"
#include "vb_select.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_dcd.h"
#include "vb_box.h"
#include "vb_diag.h"
#include "vb_hash.h"
#include "vb_xdr.h"
#include "vbi_input.h"

struct vb_frame_source {
    vb_frame_reader *rd;
    vb_dcd *dcd;
    vb_xdr_traj *xdr;
    char *dcd_path;      /* the trajectory's name */
    vb_sphere_set *topo; /* trajectory: every atom of the topology */
    size_t *keep;        /* trajectory: topology atoms that enter the analysis */
    size_t nkeep;
    double *xyz;         /* one frame: DCD x..., y..., z...; XTC/TRR x0 y0 z0 x1 ... */
    long index;          /* frames read so far */
    long contained_named; /* 1 + the frame whose contained spheres were named (W701) */
    long contained_more;  /* later frames with contained spheres (counted, not named) */
    char contained_src[512]; /* the file they came from, for that count's line */
    char *select;        /* --select of a text frame source (applied per frame), or NULL */
};

void vb_frame_source_close(vb_frame_source *F)
{
    if (!F)
        return;
    vb_frame_reader_close(F->rd);
    vb_dcd_close(F->dcd);
    vb_xdr_close(F->xdr);
    vb_spheres_free(F->topo);
    free(F->dcd_path);
    free(F->keep);
    free(F->xyz);
    free(F->select);
    free(F);
}

/* The topology of a trajectory: a PSF (atoms without coordinates), or any
 * sphere format, read whole (water and hydrogens too) and checked. */
static int read_topology(vb_ctx *ctx, const char *path, const vb_read_options *ro,
                         vb_sphere_set **out)
{
    vb_read_options all = *ro;
    all.keep_water = 1;
    all.keep_virtual_sites = 2;
    all.drop_hydrogens = 0;
    all.select = NULL;
    char *buf;
    size_t len;
    int rc = vbi_slurp(ctx, path, &buf, &len);
    if (rc != VB_OK)
        return rc;
    if (vbi_is_psf(buf, len)) {
        rc = vbi_read_psf(ctx, path, buf, len, &all, out);
    } else {
        rc = vb_spheres_read_buffer(ctx, path, buf, len, &all, out);
        if (rc == VB_OK)
            rc = vbi_spheres_validate(ctx, *out, 1, 0); /* each frame names its contained atoms */
    }
    free(buf);
    return rc;
}

/* Opens the trajectory, known by its magic number; *natoms its atoms. */
static int open_trajectory(vb_ctx *ctx, vb_frame_source *F, const char *traj, size_t *natoms)
{
    unsigned char head[8] = {0};
    FILE *f = vbi_open_input(ctx, traj, NULL);
    if (!f)
        return vb_errcode(ctx);
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    int kind = vbi_trajectory_kind(head, got);
    int rc;
    if (kind == VBI_TRAJ_DCD) {
        if ((rc = vb_dcd_open(ctx, traj, &F->dcd)) == VB_OK)
            *natoms = vb_dcd_atoms(F->dcd);
    } else if (kind == VBI_TRAJ_XTC || kind == VBI_TRAJ_TRR) {
        if ((rc = vb_xdr_open(ctx, traj, &F->xdr)) == VB_OK)
            *natoms = vb_xdr_atoms(F->xdr);
    } else {
        rc = vb_error(ctx, VB_EINPUT_FORMAT, traj, 0,
                      "not a trajectory: no DCD, XTC or TRR magic number");
    }
    return rc;
}

static int open_traj(vb_ctx *ctx, vb_frame_source *F, const char *path, const char *traj,
                     const vb_read_options *ro)
{
    /* The topology must list every atom of the trajectory: read all,
     * select after. */
    size_t na = 0;
    int rc = read_topology(ctx, path, ro, &F->topo);
    if (rc == VB_OK)
        rc = open_trajectory(ctx, F, traj, &na);
    if (rc != VB_OK)
        return rc;
    if (!(F->dcd_path = strdup(traj)))
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    if (na != F->topo->n)
        return vb_error(ctx, VB_EINPUT_TOPOLOGY, traj, 0,
                        "trajectory has %zu atoms per frame, topology %s has %zu", na, path,
                        F->topo->n);
    F->keep = malloc(na * sizeof *F->keep);
    F->xyz = malloc(3 * na * sizeof *F->xyz);
    if (!F->keep || !F->xyz)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "trajectory frame of %zu atoms", na);
    vb_select *sel = NULL;
    if (ro->select && (rc = vb_select_parse(ctx, ro->select, &sel)) != VB_OK)
        return rc;
    size_t sites = 0;
    for (size_t i = 0; i < na; i++) {
        const vb_atom_info *a = F->topo->info ? &F->topo->info[i] : NULL;
        if (a && !ro->keep_water && vbi_is_water(a->resname))
            continue;
        if (a && !ro->keep_virtual_sites && vbi_is_virtual_site(a->resname, a->name)) {
            sites++;
            continue;
        }
        if (a && ro->drop_hydrogens && vbi_is_hydrogen(a->element))
            continue;
        if (sel && !vb_select_match(sel, a))
            continue;
        F->keep[F->nkeep++] = i;
    }
    vb_select_free(sel);
    vbi_dropped dr = {0};
    dr.virtual_sites = sites;
    vbi_report_dropped(ctx, path, &dr); /* W727, as a reader says it */
    vb_select_free(sel);
    if (F->nkeep == 0 && ro->select)
        return vb_error(ctx, VB_EINPUT_SELECT, path, 0, "--select \"%s\" selects none of the %zu atoms",
                        ro->select, na);
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
    int rc = dcd_path ? open_traj(ctx, F, path, dcd_path, ro)
                      : vb_frame_reader_open(ctx, path, ro, &F->rd); /* --model picks one frame */
    if (rc == VB_OK && !dcd_path && ro->select) {
        /* Checked now, so a bad expression stops before the first frame. */
        vb_select *sel = NULL;
        if ((rc = vb_select_parse(ctx, ro->select, &sel)) == VB_OK && !(F->select = strdup(ro->select)))
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
        vb_select_free(sel);
    }
    if (rc != VB_OK) {
        vb_frame_source_close(F);
        return rc;
    }
    *out = F;
    return VB_OK;
}

/* A trajectory frame has no decimals: its coordinates are checked as doubles
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

/* A sphere of the frame as a key of the duplicate check: -0 and 0 are one
 * number (x + 0.0 is +0 for both), as the decimals of a text frame compare;
 * the coordinates are finite (check_frame). */
typedef struct {
    const vb_sphere_set *s;
    double v[4];
} frame_key;

static uint64_t frame_key_hash(const double v[4])
{
    uint64_t h = 0;
    for (int k = 0; k < 4; k++) {
        double x = v[k] + 0.0;
        uint64_t b;
        memcpy(&b, &x, sizeof b);
        h = vb_hash_mix(h, b);
    }
    /* The table takes the low bits: fold the high ones in (a coordinate
     * widened from a float has its low 29 bits zero, which the mixing's
     * product leaves in the low bits of h). */
    return h ^ (h >> 29) ^ (h >> 47);
}

static int frame_key_same(const void *key, size_t item)
{
    const frame_key *K = key;
    const vb_sphere_set *s = K->s;
    return s->x[item] == K->v[0] && s->y[item] == K->v[1] && s->z[item] == K->v[2] &&
           s->r[item] == K->v[3];
}

static uint64_t frame_item_hash(const void *arg, size_t item)
{
    const vb_sphere_set *s = arg;
    const double v[4] = {s->x[item], s->y[item], s->z[item], s->r[item]};
    return frame_key_hash(v);
}

/* E104 when two atoms of a trajectory frame are the same sphere, as
 * vb_spheres_validate says of a text frame (a GRO or PDB model): the pair
 * with the smallest later atom is named, with the earliest copy of it.
 * One pass in atom order through a hash of the spheres seen: the first
 * atom found already there is that later atom, the one there its earliest
 * copy. */
static int check_frame_duplicates(vb_ctx *ctx, const vb_frame_source *F, const vb_sphere_set *s)
{
    vb_hash h = {NULL, 0, 0};
    if (vb_hash_fit(&h, s->n, frame_item_hash, s) != VB_OK)
        return vb_error(ctx, VB_ENOMEM, F->dcd_path, 0, "out of memory");
    size_t first = SIZE_MAX, second = SIZE_MAX;
    for (size_t i = 0; i < s->n; i++) {
        frame_key K = {s, {s->x[i], s->y[i], s->z[i], s->r[i]}};
        size_t *slot = vb_hash_slot(&h, frame_key_hash(K.v), frame_key_same, &K);
        if (*slot) {
            first = *slot - 1;
            second = i;
            break;
        }
        /* Room for s->n items was made: no growth, no failure here. */
        (void)vb_hash_put(&h, slot, i, frame_item_hash, s);
    }
    vb_hash_free(&h);
    if (second == SIZE_MAX)
        return VB_OK;
    size_t a = F->keep[first], b = F->keep[second];
    return vb_error(ctx, VB_EINPUT_DUPLICATE, F->dcd_path, 0,
                    "frame %ld: atom %zu (topology line %ld) is identical to atom %zu (topology "
                    "line %ld)",
                    F->index, b + 1, F->topo->line[b], a + 1, F->topo->line[a]);
}

/* The next trajectory frame, in Angstrom: DCD stores Angstrom; XTC and
 * TRR store nm. A float times 10 is exact in double (24 + 4 bits); a
 * double-precision TRR coordinate times 10 is rounded once. */
static int next_traj(vb_ctx *ctx, vb_frame_source *F, vb_sphere_set **out, int *model)
{
    size_t na = F->topo->n;
    int got, rc;
    const double *cx, *cy, *cz;
    size_t stride;
    vb_box box;
    int has_box = 0;
    if (F->dcd) {
        double cell[6] = {0, 0, 0, 0, 0, 0};
        rc = vb_dcd_next(ctx, F->dcd, F->xyz, F->xyz + na, F->xyz + 2 * na, cell, &got);
        cx = F->xyz, cy = F->xyz + na, cz = F->xyz + 2 * na, stride = 1;
        has_box = rc == VB_OK && got && vb_frame_box_dcd(cell, &box);
    } else {
        vb_xdr_frame fr;
        memset(&fr, 0, sizeof fr);
        rc = vb_xdr_next(ctx, F->xdr, F->xyz, &fr, &got);
        has_box = rc == VB_OK && got && vb_frame_box_xdr(fr.box, fr.is_double, &box);
        for (size_t i = 0; rc == VB_OK && got && i < 3 * na; i++)
            F->xyz[i] *= 10.0;
        cx = F->xyz, cy = F->xyz + 1, cz = F->xyz + 2, stride = 3;
    }
    if (rc != VB_OK || !got)
        return rc;
    vb_sphere_set *s;
    if ((rc = vb_spheres_new(ctx, F->dcd_path, F->nkeep, F->topo->info != NULL, &s)) != VB_OK)
        return rc;
    for (size_t i = 0; i < F->nkeep; i++) {
        size_t k = F->keep[i];
        s->x[i] = cx[stride * k];
        s->y[i] = cy[stride * k];
        s->z[i] = cz[stride * k];
        s->r[i] = F->topo->r[k];
        s->line[i] = F->topo->line[k];
        if (F->topo->info)
            s->info[i] = F->topo->info[k];
    }
    if (has_box && !(s->box = malloc(sizeof *s->box)))
        rc = vb_error(ctx, VB_ENOMEM, F->dcd_path, 0, "out of memory");
    else if (has_box)
        *s->box = box;
    if (rc != VB_OK || (rc = check_frame(ctx, F, s)) != VB_OK ||
        (rc = check_frame_duplicates(ctx, F, s)) != VB_OK) {
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
    int rc = F->rd ? vb_frame_reader_next(ctx, F->rd, out, model) : next_traj(ctx, F, out, model);
    if (rc == VB_OK && *out && F->select) {
        vb_sphere_set *t;
        rc = vb_spheres_select(ctx, *out, F->select, &t);
        vb_spheres_free(*out);
        *out = rc == VB_OK ? t : NULL;
    }
    if (rc == VB_OK && *out && F->rd &&
        (rc = vbi_spheres_validate(ctx, *out, 1, F->contained_named == 0)) != VB_OK) {
        vb_spheres_free(*out);
        *out = NULL;
    }
    if (rc == VB_OK && *out && F->rd) {
        size_t c = 0;
        for (size_t i = 0; i < (*out)->n; i++)
            c += (*out)->contained[i] != 0;
        if (c && F->contained_named == 0) {
            F->contained_named = F->index + 1;
            snprintf(F->contained_src, sizeof F->contained_src, "%s",
                     (*out)->source ? (*out)->source : "");
        }
        else if (c)
            F->contained_more++;
    }
    /* The end: the frames whose contained spheres went unnamed, once. */
    if (rc == VB_OK && !*out && F->contained_more > 0) {
        vb_warn(ctx, VB_W_CONTAINED_COUNT, F->contained_src, 0,
                "spheres inside others in %ld more frame%s (W701 named them for frame %ld "
                "only)",
                F->contained_more, F->contained_more == 1 ? "" : "s", F->contained_named - 1);
        F->contained_more = 0;
    }
    if (rc == VB_OK && *out)
        F->index++;
    return rc;
}
