/* The bisector arcs one atom's regions share (vbm_share.h): each found
 * once, for the first of its two regions, and given to the second. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbm_share.h"

#define PI 3.141592653589793
#define TWO_PI 6.283185307179586

void vbm_share_reset(vbm_share *sh)
{
    sh->nkept = 0;
}

void vbm_share_free(vbm_share *sh)
{
    free(sh->kept);
    free(sh->actcap);
    free(sh->known);
    free(sh->given);
    memset(sh, 0, sizeof *sh);
}

/* A cap index of region x as an active neighbour (x for its own cap). */
static uint32_t to_act(const uint32_t *capact, uint32_t c)
{
    return c == VBM_NO_CAP ? VBM_NO_CAP : capact[c];
}

int vbm_share_keep(vbm_share *sh, uint32_t x, const uint32_t *capact, const vbm_arc *arc,
                   size_t narc)
{
    for (size_t i = 0; i < narc; i++) {
        if (arc[i].cap == 0 || capact[arc[i].cap] < x)
            continue; /* x's own circle, or given to x already */
        if (VB_ARRAY_FIT(sh->kept, sh->cap_kept, sh->nkept + 1, 64) != VB_OK)
            return -1;
        vbm_kept *k = &sh->kept[sh->nkept++];
        k->from = x;
        k->to = capact[arc[i].cap];
        k->arc = arc[i];
        k->arc.pcap = to_act(capact, arc[i].pcap);
        k->arc.qcap = to_act(capact, arc[i].qcap);
    }
    return 1;
}

int vbm_share_pending(const vbm_share *sh, uint32_t x)
{
    for (size_t i = 0; i < sh->nkept; i++)
        if (sh->kept[i].to == x)
            return 1;
    return 0;
}

/* An active neighbour as a cap of the region: 0 for `from` (its own cap
 * circle meets the bisector where the region's own does). */
static uint32_t to_cap(const vbm_share *sh, uint32_t from, uint32_t a)
{
    return a == VBM_NO_CAP ? VBM_NO_CAP : a == from ? 0 : sh->actcap[a];
}

int vbm_share_given(vbm_share *sh, uint32_t x, const uint32_t *capact, size_t ncap, size_t na)
{
    if (VB_ARRAY_FIT(sh->actcap, sh->cap_actcap, na + 1, 64) != VB_OK ||
        VB_ARRAY_FIT(sh->known, sh->cap_known, ncap + 1, 64) != VB_OK)
        return -1;
    for (size_t a = 0; a < na; a++)
        sh->actcap[a] = VBM_NO_CAP;
    for (size_t c = 0; c < ncap; c++) {
        sh->actcap[capact[c]] = (uint32_t)c;
        sh->known[c] = c > 0 && capact[c] < x;
    }
    sh->ngiven = 0;
    for (size_t i = 0; i < sh->nkept; i++) {
        const vbm_kept *k = &sh->kept[i];
        if (k->to != x)
            continue;
        uint32_t c = sh->actcap[k->from];
        if (c == VBM_NO_CAP || c == 0)
            return 0;
        if (VB_ARRAY_FIT(sh->given, sh->cap_given, sh->ngiven + 1, 64) != VB_OK)
            return -1;
        vbm_arc *g = &sh->given[sh->ngiven++];
        const vbm_arc *a = &k->arc;
        g->cap = c;
        g->pcap = to_cap(sh, k->from, a->qcap);
        g->qcap = to_cap(sh, k->from, a->pcap);
        g->p[0] = vbx_ia_neg(a->q[0]);
        g->p[1] = a->q[1];
        g->q[0] = vbx_ia_neg(a->p[0]);
        g->q[1] = a->p[1];
        g->tp = PI - a->tq;
        g->tq = PI - a->tp;
        if (g->tp < 0.0) {
            g->tp += TWO_PI;
            g->tq += TWO_PI;
        }
    }
    return 1;
}
