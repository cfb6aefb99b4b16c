/* Internals of vb_certify_quads shared by its files: the merge of the
 * certified roots (certify_merge.c) and the open roots that may be one tie
 * vertex (certify_ties.c). */
#ifndef VBX_QTIES_H
#define VBX_QTIES_H

#include <stddef.h>
#include <stdint.h>

#include "vbx_cert.h"

/* The filter's verdicts on a root; ROOT_UNPLACED: open, and the filter has
 * no enclosure of its point. */
enum { ROOT_REFUSED = 0, ROOT_EMPTY = 1, ROOT_OPEN = 2, ROOT_UNPLACED = 3 };

/* The filter's verdict on root R of line L of vb_certify_quads (R's s set;
 * its point is computed here once the tangency passes): refused (t + R_i < 0
 * for a member, or a sphere inside, proven), empty (every other sphere
 * proven outside), or open. Counts in ctx's stats and *cs. */
int vbx_qfilter_root(vb_ctx *ctx, const vb_certifier *c, vb_cert_quad_stats *cs,
                     const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R);

/* A certified root as the merge sees it: members m[0..nm) (the quadruple
 * itself when nm == 4, so two roots of one quadruple share m), x, y, z, t
 * at xyzt, and the root of its canonical quadruple (the key's sigma). */
typedef struct vbx_vref {
    const uint32_t *m;
    size_t nm;
    const double *xyzt;
    int sigma;
} vbx_vref;

/* Appends the certified roots refs[0..n) (in quadruple order) to out: the
 * vertices with four members in that order (two roots of one quadruple put
 * in vb_vertex_list_sort's order), each vertex of degree > 4 once (its
 * first root, by the certifier's keys; the later ones count in
 * qs->duplicates), merged into vb_vertex_list_sort's order; out is sorted
 * again only when the new vertices interleave with its old ones. Counts
 * qs->vertices and the context's certified. Returns VB_OK or VB_ENOMEM
 * (message in ctx). */
int vbx_quads_merge(vb_ctx *ctx, vb_certifier *c, const vbx_vref *refs, size_t n,
                    vb_vertex_list *out, vb_cert_quad_stats *qs);

/* An open root whose exact path waits: root `root` of quadruple `quad`,
 * left open by the filter while the quadruple's other root was refused or
 * certified by a filter, or the only root of a quadruple with delta = 0
 * (nroots 1). */
typedef struct vbx_qtie {
    double lo[3], hi[3]; /* the filter's enclosure of x, y, z */
    size_t quad;
    size_t leader; /* the tie whose exact vertex this root may be; itself: solved
                      first */
    size_t rec;    /* its record of the exact path in worker wi, SIZE_MAX: none */
    uint32_t wi;
    int8_t root;
    int8_t nroots;   /* the quadruple's exact roots: 2, or 1 (delta = 0) */
    uint8_t skipped; /* proven the leader's vertex: no exact path */
    uint8_t had_rec; /* the filter certified the quadruple's other root */
} vbx_qtie;

/* Groups ties t[0..n) (in quadruple order) by overlapping enclosures: the
 * first tie of a group (t[i].leader = i) is solved exactly, a later one
 * gets the first earlier leader whose enclosure meets its own
 * (t[i].leader < i). A tie whose box is wider than the grid's cells
 * (2^-24 of the input's largest coordinate) leads itself.
 * Only the enclosures decide: the result depends on t alone. Returns VB_OK
 * or VB_ENOMEM (message in ctx). */
int vbx_ties_group(vb_ctx *ctx, const vb_certifier *c, vbx_qtie *t, size_t n);

/* Is the sorted quadruple q a subset of the sorted members m[0..nm)? Then
 * the vertex with members m is exactly a root of q. */
int vbx_quad_within(const uint32_t q[4], const uint32_t *m, size_t nm);

#endif
