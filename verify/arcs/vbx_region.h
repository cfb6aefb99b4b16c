/* The regions of arc closure's search (arc_region.c): convex parts of the
 * (S, G) plane of a triple that hold an arc of its trisector, and the
 * spheres that may touch inside them (why these are complete: the top of
 * arc_region.c). */
#ifndef VBX_REGION_H
#define VBX_REGION_H

#include "vbx_arc.h"

enum { VBX_PART_BOX = 0, VBX_PART_STRIP = 1, VBX_PART_POINT = 2 };

typedef struct vbx_part {
    int kind;
    vbx_ia S, G;   /* box; strip: its segment (G a point interval) */
    vbx_ia D[2];   /* strip: recession direction (dS, dG) */
    vbx_ia u[4];   /* point: enclosures of u = (q, s) itself (no plane frame) */
} vbx_part;

typedef struct vbx_region {
    int brute;
    int n;
    vbx_part p[40];
} vbx_region;

/* Makes rg an empty region (no parts, not brute). Only the header is
 * cleared: whoever appends a part writes it whole (kind, S, G, and D for a
 * strip; kind and u for a point), and nothing reads a part at or beyond n,
 * nor a box's D, nor a point's S and G (the
 * memset of all 40 parts this replaces was 2 % of the closure's
 * instructions: 2.9 KB per region, one region per traced arc). */
static inline void vbx_region_clear(vbx_region *rg)
{
    rg->brute = 0;
    rg->n = 0;
}

/* Boxes of one piece of a tail searched outwards (arc_search.c). */
enum { VBX_PIECE_PARTS = 4 };

/* S on the open branch at |G| = g (g an interval >= 0). */
vbx_ia vbx_branch_S(const vbx_tframe *f, vbx_ia g);

/* The boxes of the open branch over mirrored positions g in [ga, gb] (G =
 * sgn g), `parts` of them appended to rg: each from breakpoint g_i
 * to g_i+1 (shared by neighbours, so they cover [ga, gb]), its S from the
 * branch's at g_i (Sa at ga: the start vertex's enclosure) to the
 * branch's at g_i+1, and Smin when G = 0 lies between (S depends on |G|
 * alone and grows with it). Thin boxes keep Q small over each, so the
 * tangent-ball queries stay close to the arc. */
void vbx_piece_parts(const vbx_tframe *f, vbx_ia Sa, double ga, double gb, double sgn,
                     int parts, vbx_region *rg);

/* The tail of the open branch beyond mirrored position g (a double; sgn
 * +1 forward, -1 backward): from g < 0 a box up to the branch's vertex
 * (g = 0), then the half-strip from max(g, 0) along the asymptote. */
void vbx_tail_from(const vbx_tframe *f, double g, double sgn, vbx_region *rg);

/* The box of the apex A of the arc of the open branch between positions
 * G0 < G1 (enclosures g0, g1 of the exact ends): where the tangents at the
 * two ends meet. The arc lies in the triangle of its ends and A (S is a
 * strictly convex function of G), so an affine L_j that is >= 0 at both
 * ends and > 0 at A is > 0 on the open arc. 1 when *p is set, 0 when the
 * enclosures cannot order the ends or separate their slopes. */
int vbx_apex_box(const vbx_tframe *f, vbx_ia g0, vbx_ia g1, vbx_part *p);

/* The bounded arc of an open branch from e0 to e1 (both vertices with
 * their box and tau): its region as the one point where the tangents at
 * the ends meet, computed in u (arc_region.c says why). 1 when set, 0 when
 * an end lacks them, the curve is not open, or the enclosures cannot
 * separate the tangents (the caller takes vbx_region_of). Needs no plane
 * frame. */
int vbx_apex_point(const vbx_arcw *w, const vbx_tframe *f, const vbx_arc_end *e0,
                   const vbx_arc_end *e1, vbx_region *rg);

/* The region of the arc from e0 to e1 (arc_region.c says which); f's
 * plane frame must be set (vbx_tframe_plane). */
void vbx_region_of(const vbx_tframe *f, const vbx_arc_end *e0, const vbx_arc_end *e1,
                   vbx_region *rg);

/* Candidates of the region: VB_OK, VB_ENOMEM; sets rg->brute when a query
 * cannot be bounded. */
int vbx_gather(vbx_arcw *w, const vbx_tframe *f, vbx_region *rg);

/* Candidates of a tail region when there are at most cap of them: 1 when
 * gathered (then w->cand holds them, as vbx_gather would), 0 when over the cap
 * or unbounded (nothing held), -1 out of memory. */
int vbx_gather_capped(vbx_arcw *w, const vbx_tframe *f, const vbx_region *rg, size_t cap);

/* 1 when L_j > 0 is proven over the whole region. */
int vbx_clear_of(const vbx_arcw *w, const vbx_tframe *f, const vbx_region *rg, uint32_t j);

/* Empties the worker's candidates (and their marks). */
void vbx_clear_cands(vbx_arcw *w);

#endif
