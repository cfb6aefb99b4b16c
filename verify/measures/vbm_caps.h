/* The boundary of an intersection of spherical caps on the unit sphere, as
 * circle arcs (cap_arcs.c): the regions of directions a neighbour owns in a
 * constrained cell are such intersections (stokes_cell.c). */
#ifndef VBM_CAPS_H
#define VBM_CAPS_H

#include <stddef.h>
#include <stdint.h>

#include "vbx_ia.h"

/* The cap {u in S^2 : u.n >= h} (n any non-zero vector). */
typedef struct vbm_cap {
    vbx_ia n[3], h;
} vbm_cap;

/* A cap's boundary circle u(t) = c a + s (cos t e1 + sin t e2): a = n / |n|,
 * e1, e2 a frame with e1 x e2 = a (the cap lies to the left as t grows),
 * c and s the cosine and sine of its angular radius. The intervals enclose
 * the exact values of one exact frame. */
typedef struct vbm_circle {
    vbx_ia a[3], e1[3], e2[3], c, s;
    int kind; /* VBM_CAP_CIRCLE, _ALL (h < -|n|: every direction), _NONE (h > |n|) */
    int framed; /* e1 and e2 made (vbm_circle_frame) */
} vbm_circle;

enum { VBM_CAP_CIRCLE = 1, VBM_CAP_ALL = 2, VBM_CAP_NONE = 3 };

/* An arc of circle `cap` from p to q counterclockwise (points of the unit
 * circle in its frame, as intervals), tp < tq <= tp + 2.6 their angles
 * (nearest doubles: the arcs' frames only). */
typedef struct vbm_arc {
    uint32_t cap;
    uint32_t pcap, qcap; /* the caps whose circles end the arc at p and q
                          * (VBM_NO_CAP: a split of a longer arc, or none) */
    vbx_ia p[2], q[2];
    double tp, tq;
} vbm_arc;

#define VBM_NO_CAP UINT32_MAX

/* Work space of vbm_cap_arcs (zero-initialise; free with vbm_caps_free). */
typedef struct vbm_capwork {
    vbm_circle *circ;
    struct vbm_endpt **ord; /* the ends in the order of their angles (cap_arcs.c's) */
    vbm_arc *arc, *sorted;
    uint32_t *sel, *queue;  /* caps restricting a circle; circles to do next */
    uint8_t *state;         /* per cap: done, on the boundary, queued */
    vbx_ia *bnd;            /* bound_prune's arc caps */
    struct vbm_rcache *rc;  /* the restrictions made (cap_arcs.c's) */
    uint32_t *rslot, *rix;  /* per circle and cap: its restriction; per restriction of a circle */
    size_t nrc, nslot, cap_rc, cap_rslot, cap_rix;
    size_t nres; /* restrictions made by the last circle_arcs */
    size_t ncirc; /* circ[0..ncirc) are the last vbm_cap_arcs call's circles */
    size_t cap_circ, cap_ord, cap_arc, narc, cap_sorted, cap_sel, cap_queue, cap_state, cap_bnd;
    struct vbm_prework *pw; /* vbm_cap_arcs' prefilter and compacted caps (cap_prefilter.c's) */
} vbm_capwork;

/* The circle of a cap: kind VBM_CAP_CIRCLE with the frame, _ALL or _NONE;
 * 0 when the intervals cannot tell (|h| close to |n|). (cap_geom.c, as
 * the rest up to vbm_caps_free) */
int vbm_circle_of(const vbm_cap *cp, vbm_circle *c);

/* vbm_circle_of without the frame (kind, a, c and s; framed 0). */
int vbm_circle_axis(const vbm_cap *cp, vbm_circle *c);

/* vbm_circle_axis with n2 = vbm_dot3(cp->n, cp->n) given (the caller has
 * it: stokes_cell.c's pair caps), bit for bit the same circle. */
int vbm_circle_axis_nn(const vbm_cap *cp, vbx_ia n2, vbm_circle *c);

/* The frame e1, e2 of a circle whose axis is set (framed 1). Returns 0
 * when the intervals cannot normalise it. */
int vbm_circle_frame(vbm_circle *c);

/* A cap around arc a of circle C: its centre M (enclosing an exact unit
 * vector) and a lower bound *cr of the cosine of its angular radius.
 * Returns 0 when *cr is not proven > -1. */
int vbm_arc_bound(const vbm_circle *C, const vbm_arc *a, vbx_ia *M, double *cr);

/* The sines of the angular radii rho with cos rho in [cr, 1]. */
vbx_ia vbm_cap_sine(double cr);

/* Whether the cap of circle cm holds the cap {u : u.M >= cr} in its
 * interior (M enclosing an exact unit vector; sinr = vbm_cap_sine(cr)). */
int vbm_cap_holds(const vbm_circle *cm, const vbx_ia *M, double cr, vbx_ia sinr);

/* A cap {u : u.M >= *cr} (M enclosing an exact unit vector) holding the
 * arcs arc[0..n) (circles circ) and not the unit vector `out`: it holds
 * every closed set of directions whose boundary lies on those arcs and
 * which misses `out`. tmp: 4 n intervals of work space. Returns 0 when it
 * cannot be proven. */
int vbm_arcs_cap(const vbm_circle *circ, const vbm_arc *arc, size_t n, const vbx_ia *out,
                 vbx_ia *tmp, vbx_ia *M, double *cr);

/* The boundary of the intersection of caps[0..ncap) as arcs in w->arc
 * (w->narc; none when the intersection is empty or the whole sphere: the
 * caller tells them apart). Each arc is a piece of one cap's circle lying
 * in every other cap, oriented with the intersection on its left, so that
 * Stokes' theorem integrates over the intersection along them. Circles
 * already solved are given: known[m] != 0 (known may be NULL) says circle
 * m's arcs are exactly those of given[0..ngiven) with cap m (none when no
 * such arc; their pcap and qcap indices into caps too, or VBM_NO_CAP), and
 * only the other circles are searched, the given arcs bounding their
 * search as found ones do. Cap 0 is never known. Returns 1, 0 when an
 * interval cannot decide a step (tangent or coincident circles, an arc end
 * on a third circle), -1 on ENOMEM. axes (may be NULL) gives each cap's
 * circle as vbm_circle_axis makes it (kind 0: it could not), with its frame
 * where framed, when the caller has them already; w->circ[l] has circle
 * l afterwards, framed where the search made the frame. The search runs
 * over the caps vbm_caps_prefilter keeps, and over all of them where that
 * could not give the same bytes (cap_prefilter.c). */
int vbm_cap_arcs(const vbm_cap *caps, const vbm_circle *axes, size_t ncap, const uint8_t *known,
                 const vbm_arc *given, size_t ngiven, vbm_capwork *w);

/* vbm_cap_arcs' search over every cap given (cap_arcs.c): vbm_cap_arcs
 * runs it on the caps vbm_caps_prefilter keeps, and on all of them where
 * that cannot give its bytes. Same arguments and returns. */
int vbm_cap_arcs_all(const vbm_cap *caps, const vbm_circle *axes, size_t ncap,
                     const uint8_t *known, const vbm_arc *given, size_t ngiven, vbm_capwork *w);

/* vbm_cap_arcs_all guided by each circle's neighbours (cap_arcs.c): the
 * arcs of circle l are found inside the caps near[near_at[l] ..
 * near_at[l + 1]) first, every other cap then proven to hold them (or
 * added); no trial. The same arcs as vbm_cap_arcs_all; a circle's list
 * may start at another of its arcs when it has several. Same arguments
 * and returns as vbm_cap_arcs_all, near_at with ncap + 1 entries. */
int vbm_cap_arcs_near(const vbm_cap *caps, const vbm_circle *axes, size_t ncap,
                      const uint8_t *known, const vbm_arc *given, size_t ngiven,
                      const uint32_t *near_at, const uint32_t *near, vbm_capwork *w);

/* The caps 1..ncap - 1 of the intersection of caps[0..ncap) proven to hold
 * in their interior every unit vector inside the caps not rejected (a
 * polyhedron clip and a second pass over the caps left without a face,
 * cap_prefilter.c): pre[m]
 * = 1 for each (0 elsewhere; pre has ncap bytes). Their circles touch no
 * point of the intersection, which the caps kept define alone. circ: each
 * cap's circle (vbm_circle_axis, no frame needed). w: its work space only.
 * Returns how many, 0 also on ENOMEM (none rejected). (cap_prefilter.c) */
size_t vbm_caps_prefilter(const vbm_cap *caps, const vbm_circle *circ, size_t ncap,
                          vbm_capwork *w, uint8_t *pre);

void vbm_caps_free(vbm_capwork *w);

/* Frees vbm_capwork.pw (cap_prefilter.c; vbm_caps_free calls it). */
void vbm_prefilter_free(vbm_capwork *w);

/* An exact unit vector (x, y) at about the angle t: (cos t, sin t) in
 * doubles, normalised in intervals. */
void vbm_unit_at(double t, vbx_ia *x, vbx_ia *y);

/* t = tan(angle / 2) of the unit vector (x, y) rotated by -mid, (cm, sm)
 * enclosing (cos mid, sin mid): an enclosure. */
vbx_ia vbm_half_tan(vbx_ia x, vbx_ia y, vbx_ia cm, vbx_ia sm);

/* An enclosure of 2 (atan t1 - atan t0), the angle of an arc from t0 to t1
 * (t = tan(angle / 2) about its middle). */
vbx_ia vbm_arc_angle(vbx_ia t0, vbx_ia t1);

#endif
