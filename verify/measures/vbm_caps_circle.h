/* One circle's arcs inside a set of caps (cap_arcs.c), the step the
 * searches over an intersection's circles take (cap_search.c): the
 * states of the caps they share and the two calls. Internal to the
 * arrangement's files. */
#ifndef VBM_CAPS_CIRCLE_H
#define VBM_CAPS_CIRCLE_H

#include <stddef.h>
#include <stdint.h>

#include "vbm_caps.h"

/* vbm_capwork.state, per cap: its circle done, on the boundary, queued,
 * likely on it (the trial's), near the circle now searched (its subset in
 * vbm_cap_arcs_near), BAD: not proven to hold the arcs of the circle now
 * searched (vbm_arcs_inside), held away from the intersection. */
enum { DONE = 1, ON_BOUNDARY = 2, QUEUED = 4, LIKELY = 8, NEAR = 16, BAD = 32, HELD = 64 };

/* The arcs of circle l inside the caps sel[0..nsel) (l itself skipped)
 * and, with keep > 0, inside the caps of the last call on circle l too:
 * its first `keep` restrictions and their ends (w->rix; w->nres says how
 * many it made) are taken as they are. The arcs are pushed to w->arc
 * (w->narc). With `test`, nothing is pushed: returns 2 when some arc
 * exists. Returns 1 (done, or no arc), 0 undecided, -1 ENOMEM. */
int vbm_circle_arcs(const vbm_cap *caps, const uint32_t *sel, size_t nsel, vbm_capwork *w,
                    size_t l, int test, size_t keep);

/* Whether every cap m in 1..ncap - 1 other than l (cap 0 is in every
 * subset the searches make), not VBM_CAP_ALL and with no
 * bit of `skip` in w->state[m], holds the arcs w->arc[first..narc) of
 * circle l: each cap not proven to is marked BAD. Returns how many were
 * (a restriction it cannot make for ENOMEM counts as one). */
size_t vbm_arcs_inside(const vbm_cap *caps, size_t ncap, vbm_capwork *w, size_t l,
                       size_t first, uint8_t skip);

#endif
