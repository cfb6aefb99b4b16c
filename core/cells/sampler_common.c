/* Small pieces every part of the sampling pipeline uses (the driver, the
 * backends, matching): the growable candidate array and the batch-size
 * policy. */
#include <stdlib.h>

#include "vb_array.h"
#include "vb_sampler.h"

int vb_cand_vec_push(vb_cand_vec *cv, const vbs_cand *c)
{
    if (VB_ARRAY_FIT(cv->v, cv->cap, cv->n + 1, 1024) != VB_OK)
        return VB_ENOMEM;
    cv->v[cv->n++] = *c;
    return VB_OK;
}

void vb_cand_vec_free(vb_cand_vec *cv)
{
    free(cv->v);
    cv->v = NULL;
    cv->n = cv->cap = 0;
}

unsigned vb_sampler_batch_rays(int gpu)
{
    return gpu ? 1u << 25 : 1u << 22;
}
