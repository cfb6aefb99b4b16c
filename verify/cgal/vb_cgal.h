/* CGAL as an independent witness for the equal-radius case.
 *
 * When all radii are equal the Voronoi diagram of spheres is the ordinary
 * Voronoi diagram of the centres (and the power diagram with equal weights).
 * CGAL builds its Delaunay triangulation with an exact-constructions kernel
 * from the exact input rationals; every finite cell gives a Voronoi vertex at
 * its circumcentre, and cells with the same circumsphere (co-spherical
 * centres) are merged into one vertex holding all their spheres.
 *
 * This is the only C++ in vorball (CGAL Triangulation_3 is GPL-3+, and the
 * component is optional: VORBALL_WITH_CGAL). Every function catches every
 * exception and returns a status; nothing is thrown across this interface. */
#ifndef VB_CGAL_H
#define VB_CGAL_H

#include <stdio.h>

#include "vb.h"
#include "vb_spheres.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which diagram CGAL computes. */
enum vb_cgal_mode {
    VB_CGAL_VORONOI = 0, /* Delaunay_triangulation_3 of the centres; all radii must be equal */
    VB_CGAL_POWER = 1    /* Regular_triangulation_3 with weights R^2 (any radii) */
};

/* CGAL's vertex set with exact coordinates. Opaque. */
typedef struct vb_cgal_diagram vb_cgal_diagram;

/* Outcome of a comparison, by category. The sets are identical exactly when
 * every count but `cgal`, `theirs` and `matched` is zero (vb_cgal_identical). */
typedef struct vb_cgal_diff {
    size_t cgal;        /* CGAL's vertices */
    size_t theirs;      /* vorball's vertices after merging lines of one exact point */
    size_t matched;     /* same exact point, same ids, correctly rounded doubles */
    size_t missing;     /* CGAL vertex whose exact point no vorball line has */
    size_t extra;       /* vorball vertex at an exact point CGAL lacks */
    size_t membership;  /* same exact point, different id sets */
    size_t rounding;    /* same point and ids, but printed x, y, z or t is not the
                         * exact value rounded to nearest */
    size_t split;       /* one exact point written as several lines (not allowed
                         * unless VB_CGAL_ALLOW_SPLIT) */
    size_t invalid;     /* vorball ids that define no point: fewer than four
                         * affinely independent centres, not all at one power
                         * distance, or an id out of range */
} vb_cgal_diff;

/* Flags of vb_cgal_compare. */
enum {
    VB_CGAL_ALLOW_SPLIT = 1 /* Voronota files: a vertex of degree > 4 is several
                             * quadruple lines, some of which need not determine
                             * the point alone (four coplanar cube corners) */
};

/* The CGAL version string (e.g. "5.5.1"); static. */
const char *vb_cgal_version(void);

/* Builds CGAL's vertex set of a validated sphere set (at least one sphere;
 * identical spheres must have been refused by vb_spheres_validate).
 * VB_CGAL_VORONOI refuses unequal radii (compared exactly on the decimals)
 * with VB_EINPUT naming both lines. Centres that span less than 3D give an
 * empty set and warning W791. In power mode a sphere may own no power cell
 * (hidden by its neighbours): it is in no vertex, and warning W792 counts them.
 * Returns VB_OK with *out allocated (free with vb_cgal_free), VB_EINPUT,
 * VB_ENOMEM or VB_EINTERNAL (a CGAL failure, with its message). */
int vb_cgal_build(vb_ctx *ctx, const vb_sphere_set *set, int mode, vb_cgal_diagram **out);

/* Frees a diagram; NULL is allowed. */
void vb_cgal_free(vb_cgal_diagram *d);

/* Number of vertices (canonical: one per exact point). */
size_t vb_cgal_size(const vb_cgal_diagram *d);

/* Appends CGAL's vertices to `out` in canonical order (sorted by ids): x, y, z
 * are the exact circumcentre rounded to nearest; t = |p - c| - R of the
 * lowest-numbered member, rounded to nearest (the tangent radius when radii
 * are equal); dist 0; status CERTIFIED. Returns VB_OK or VB_ENOMEM. */
int vb_cgal_to_list(vb_ctx *ctx, const vb_cgal_diagram *d, vb_vertex_list *out);

/* Writes vertex k's exact coordinates as canonical rationals "p/q" (or "p")
 * into three malloc'd strings the caller frees. Returns VB_OK, VB_ENOMEM or
 * VB_EMISUSE for k out of range. */
int vb_cgal_exact_point(vb_ctx *ctx, const vb_cgal_diagram *d, size_t k, char **x, char **y,
                        char **z);

/* Compares CGAL's set with vorball's vertex list `theirs` exactly.
 *
 * Each vorball line is taken by its ids alone: its exact point is recomputed
 * in GMP integers from the member centres (the power vertex of four affinely
 * independent members, which for equal radii is the circumcentre) and every
 * member must lie at that one power distance. With VB_CGAL_ALLOW_SPLIT the
 * lines of one exact point are one vertex, and a line whose ids fix no point
 * joins the vertex printed at the same coordinates if its spheres are exactly
 * at one power distance from that vertex's point. Vertices are paired by exact
 * point (rational equality with CGAL's exact circumcentre); paired vertices
 * must have equal id sets, and when radii are equal the printed x, y, z, t
 * must be the exact values rounded to nearest. `set` is the sphere set the
 * diagram was built from; `lines` (may be NULL) gives each vorball vertex's
 * source line for the report. Every difference is written to `report` (may
 * be NULL) as one tab-separated line starting with its category; the counts
 * go to *diff. Returns VB_OK (whatever the differences), VB_ENOMEM or
 * VB_EINTERNAL. */
int vb_cgal_compare(vb_ctx *ctx, const vb_cgal_diagram *d, const vb_sphere_set *set,
                    const vb_vertex_list *theirs, const long *lines, unsigned flags,
                    FILE *report, vb_cgal_diff *diff);

/* 1 when a comparison found no difference of any category, else 0. */
int vb_cgal_identical(const vb_cgal_diff *diff);

#ifdef __cplusplus
}
#endif
#endif
