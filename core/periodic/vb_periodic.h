/* Periodic boxes: the Voronoi diagram of spheres repeated by a lattice.
 *
 * The box is a property of the sphere set (vb_sphere_set.box, from the
 * file) or given apart (--box); its three edge vectors are exact decimals,
 * so every image translation c + dx a + dy b + dz c is an exact decimal too.
 *
 * The periodic diagram is computed as the open diagram of the box's atoms
 * and a layer of their images, lazily: only images within a proven reach
 * of the atoms (images.c states the argument), with the direction cover run
 * on the atoms' cells alone (the images are neighbours, never cells).
 *
 * Notation: a member of a periodic vertex is `i@(dx,dy,dz)`, atom i (its
 * 0-based index in the input, as in open vertex files) translated by
 * dx a + dy b + dz c. A periodic vertex stands for all its translates; it
 * is written once, as its canonical translate: among the translates in
 * which a member with the smallest atom id has shift (0,0,0), the one whose
 * member list, sorted by (id, dx, dy, dz), is lexicographically smallest.
 * Its point is that translate's point. */
#ifndef VB_PERIODIC_H
#define VB_PERIODIC_H

#include <stdio.h>

#include "vb_box.h"
#include "vb_build.h"
#include "vb_spheres.h"
#include "vb_vertices.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- boxes: vb_box.h (core/input/box.c) ---------------------------------- */

/* ---- images (images.c) --------------------------------------------------- */

struct vbp_bins;

/* The box's atoms and the images that the periodic diagram needs. */
typedef struct vb_periodic_images {
    vb_sphere_set *set;     /* the atoms first (ids 0 .. n0), then the images; validated */
    size_t n0;              /* atoms of the box */
    uint32_t *atom;         /* per sphere of set: the atom it is an image of */
    int16_t (*shift)[3];    /* per sphere of set: its translation (dx, dy, dz) */
    double rho;             /* proven upper bound of every periodic vertex's radius t */
    double reach;           /* images are kept within this distance of an atom (at least) */
    int layers[3];          /* images span shifts -layers[k] .. layers[k] along edge k */
    size_t layer_spheres;   /* atoms and images of the one global layer (within reach) */
    double slack;           /* the build's slack (vb_periodic_image_opt) */
    struct vbp_bins *bins;  /* per-bin bounds (reach.c), NULL for the full layer */
} vb_periodic_images;

/* How images are built: slack, a distance by which a reader's points and
 * radii may be off (a verifier's tolerance; 0 for the pipeline); full, 1
 * to keep the one global layer of images (every image within `reach` of
 * the atoms) instead of the per-bin reach (reach.c); both give the same
 * periodic vertices, the full layer only more spheres; reach, a distance
 * fixed by the caller. */
typedef struct vb_periodic_image_opt {
    double slack;
    int full;
    double reach; /* > 0: every image within this distance of an atom instead (the cell
                   * measures' 2 (Rmax + probe)); no bound rho then (rho 0, no bins) */
} vb_periodic_image_opt;

/* Builds the atoms' images for the periodic diagram of `atoms` in `box`
 * (the atoms must have exact decimals; they need not lie in the box), and
 * validates the result (vb_spheres_validate: two atoms that coincide
 * modulo the box are VB_EINPUT_DUPLICATE). Returns VB_OK, VB_EINPUT_BOX_SMALL
 * (the reach exceeds 4 heights of the box: an atom's cell would meet
 * images more than 4 layers away), VB_EINPUT_MAGNITUDE (an image
 * coordinate beyond 18 digits), VB_ENOMEM. Free with
 * vb_periodic_images_free. */
int vb_periodic_images_build(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                             vb_periodic_images *out);

/* As vb_periodic_images_build with options (opt NULL: slack 0, per-bin
 * reach). The images kept are those within the global layer that the
 * per-bin reach needs (reach.c proves both). */
int vb_periodic_images_build_opt(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                                 const vb_periodic_image_opt *opt, vb_periodic_images *out);

/* A proven upper bound, plus 2 slack, of the radius of every empty sphere
 * of the periodic set centred at (x, y, z) or within the bins' growth of
 * it (the bound of its bin, reach.c; rho without bins). A vertex found
 * with these images is a periodic vertex exactly when it is certified,
 * has a member at shift 0, and its radius is at most this bound at its
 * point (minus the slack for a point read from a file). */
double vb_periodic_bound_at(const vb_periodic_images *img, double x, double y, double z);

void vb_periodic_images_free(vb_periodic_images *img);

/* ---- the periodic vertex pipeline (periodic_vertices.c) ----------------- */

typedef struct vb_periodic_member {
    uint32_t id;
    int16_t s[3];
} vb_periodic_member;

/* Orders members by (id, dx, dy, dz): -1, 0, +1. */
int vb_periodic_member_cmp(const vb_periodic_member *a, const vb_periodic_member *b);

/* Periodic vertices, canonical translates (see above), sorted by member
 * list then point. Vertex k owns m[start[k] .. start[k + 1]). */
typedef struct vb_periodic_vertices {
    size_t n;
    size_t *start;
    vb_periodic_member *m;
    double *x, *y, *z, *t;
} vb_periodic_vertices;

typedef struct vb_periodic_result {
    vb_periodic_images img;
    vb_vertices_result run;      /* the open run on img.set, cells of the atoms only */
    vb_periodic_vertices v;
    int full_layer;              /* input: 1 builds the full layer (vb_periodic_image_opt)
                                  * and has the cover seek every vertex, not only those
                                  * with t <= rho (vb_cover_options.tmax): a reference */
    size_t translates;           /* certified vertices of the run that are not canonical */
    size_t beyond_rho;           /* certified vertices of the run with t > rho: not periodic */
} vb_periodic_result;

void vb_periodic_result_init(vb_periodic_result *r);
void vb_periodic_result_free(vb_periodic_result *r);

/* The periodic diagram of the validated set `atoms` in `box`: builds the
 * images (vb_periodic_images_build), runs the vertex pipeline on them with
 * the direction cover on the atoms' cells (cfg's proposer must be the
 * cover: VB_EMISUSE otherwise), and keeps each certified vertex's
 * canonical translate once. Every vertex kept is certified exactly by
 * the pipeline's certifier against atoms and images, and no sphere of the
 * infinite periodic set can enter its tangent sphere (images.c); every
 * vertex of the periodic diagram is kept (the cover's completeness). The
 * bytes do not depend on the device or the thread count. Returns VB_OK or
 * the errors of vb_periodic_images_build and vb_vertices_run. */
int vb_periodic_vertices_run(vb_ctx *ctx, const vb_sphere_set *atoms, const vb_box *box,
                             const vb_vertices_config *cfg, const vb_vertices_backends *be,
                             vb_periodic_result *res);

/* vb_periodic_vertices_run on an engine opened once (vb_vertices_open: the
 * Python Engine over a trajectory's frames): the same vertices, bytes and
 * errors; the engine's device replaces cfg->device (vb_vertices_run_on). */
int vb_periodic_vertices_run_on(vb_ctx *ctx, vb_vertices_engine *e, const vb_sphere_set *atoms,
                                const vb_box *box, const vb_vertices_config *cfg,
                                vb_periodic_result *res);

/* Whether the sorted member list found[0 .. m) is its vertex's canonical
 * translate (see above): among the translates that put a member of the
 * smallest id at shift 0, the lexicographically smallest list. scratch
 * holds 2 m members. 1 or 0. */
int vb_periodic_is_canonical(const vb_periodic_member *found, size_t m,
                             vb_periodic_member *scratch);

void vb_periodic_vertices_free(vb_periodic_vertices *v);

/* ---- periodic vertex files read back (periodic_read.c) ------------------- */

/* Reads a periodic vertex file (tsv as vb_periodic_write writes it; '#'
 * lines skipped) into *out, and *lines (malloc'd) the source line of each
 * vertex. VB_OK, VB_EINPUT_MALFORMED (file:line), VB_EINPUT_EMPTY (no
 * vertex line), VB_EIO, VB_ENOMEM; on failure *out is empty. */
int vb_periodic_read(vb_ctx *ctx, const char *path, vb_periodic_vertices *out, long **lines);

enum {
    VB_PERIODIC_NOT_CANONICAL = 1, /* members not sorted, or not the canonical translate */
    VB_PERIODIC_BEYOND = 2         /* a member beyond the images' reach, or t > rho: not a
                                    * vertex of the periodic diagram (images.c) */
};

/* The vertices of v named by the spheres of img (the images' set), for the
 * exact verifier: each vertex a without VB_PERIODIC_BEYOND in flags[a] is
 * appended to out (status candidate), row[k] = a for out's vertex k (row
 * and flags hold v->n entries). VB_OK or VB_ENOMEM. */
int vb_periodic_to_images(vb_ctx *ctx, const vb_periodic_images *img,
                          const vb_periodic_vertices *v, vb_vertex_list *out, size_t *row,
                          uint8_t *flags);

/* What a periodic result proves, one or more lines for a file's header. */
void vb_periodic_certificate(const vb_periodic_result *r, const vb_box *box, char *buf,
                             size_t size);

/* Writes the vertices: tsv (the default; ids column `i@(dx,dy,dz)` joined
 * by ',') or json ("ids": ["i@(dx,dy,dz)", ...]); comment lines as the
 * open writer's. VB_OK, VB_EMISUSE (voronota: it has no images), VB_EIO. */
int vb_periodic_write(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                      const char *comment);

/* As vb_periodic_write with the provenance (may be NULL, vb_build.h) first
 * in the header: tsv '#' lines, json keys. VB_ENOMEM too. */
int vb_periodic_write_prov(vb_ctx *ctx, FILE *f, const vb_periodic_vertices *v, int json,
                           const vb_provenance *prov, const char *comment);

#ifdef __cplusplus
}
#endif
#endif
