/* The bisector circles one atom's regions share (share_arcs.c): the arcs
 * found on circle (j, k) while bounding neighbour j's region of directions,
 * given back reversed when neighbour k's region is bounded (stokes_cell.c). */
#ifndef VBM_SHARE_H
#define VBM_SHARE_H

#include <stddef.h>
#include <stdint.h>

#include "vbm_caps.h"

/* An arc of region `from` on its circle with region `to`; pcap and qcap
 * are active-neighbour indices (`from` for from's own cap circle) or
 * VBM_NO_CAP. */
typedef struct vbm_kept {
    uint32_t from, to;
    vbm_arc arc;
} vbm_kept;

/* Work space (zero-initialise; free with vbm_share_free). */
typedef struct vbm_share {
    vbm_kept *kept;
    uint32_t *actcap; /* per active neighbour: its cap in the region now bounded */
    uint8_t *known;   /* per cap of that region: its circle's arcs are given */
    vbm_arc *given;
    size_t nkept, ngiven, cap_kept, cap_actcap, cap_known, cap_given;
} vbm_share;

/* Forgets the arcs of the previous atom. */
void vbm_share_reset(vbm_share *sh);

/* Keeps region x's arcs arc[0..narc) (caps indexed as in its cap list,
 * capact[c] the active neighbour of cap c, capact[0] = x) that lie on a
 * bisector circle with a region y > x, bounded later. Returns 1, -1 on
 * ENOMEM. */
int vbm_share_keep(vbm_share *sh, uint32_t x, const uint32_t *capact, const vbm_arc *arc,
                   size_t narc);

/* For region x (ncap caps, capact as above, na active neighbours, every
 * region y < x bounded and kept): sh->known and sh->given as vbm_cap_arcs
 * takes them. Region y's arcs on circle (y, x) are region x's arcs on
 * circle (x, y), reversed: on that circle t_x = t_y, so x's ball cap holds
 * a point of it exactly when y's does, and so does every bisector cap
 * (x, l) exactly when (y, l) does; their set is the same. The cap of
 * (x, y) is the complement of (y, x) (n and h negated exactly in
 * intervals), whose circle has the frame (-e1, e2): a point (cx, cy) of
 * y's frame is (-cx, cy) in x's, and the angle t becomes pi - t. Returns 1,
 * 0 when a given arc's circle is missing from x's caps (region_caps proved
 * it away: a contradiction the caller leaves to the patches), -1 on
 * ENOMEM. */
int vbm_share_given(vbm_share *sh, uint32_t x, const uint32_t *capact, size_t ncap, size_t na);

/* Whether some region bounded before kept an arc for region x. */
int vbm_share_pending(const vbm_share *sh, uint32_t x);

void vbm_share_free(vbm_share *sh);

#endif
