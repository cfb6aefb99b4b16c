/* Atoms left out of the channel analysis by residue name (--ignore, as
 * HOLE's ignore card: ligands, sugars, ions, waters; --membrane: membrane
 * dummy atoms, lipids and detergents). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vb_select.h"
#include "vbc_channel.h"

/* The index of resname in names (case-insensitive), or -1. */
static long listed_at(const char *resname, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (strcasecmp(resname, names[k]) == 0)
            return (long)k;
    return -1;
}

int vbc_spheres_without(vb_ctx *ctx, const vb_sphere_set *s, const char *const *resnames, size_t n,
                        size_t *counts, vb_sphere_set **out, size_t *dropped)
{
    *out = NULL;
    *dropped = 0;
    uint8_t *keep = malloc(s->n ? s->n : 1);
    if (!keep)
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    size_t kept = 0;
    for (size_t i = 0; i < s->n; i++) {
        long at = s->info ? listed_at(s->info[i].resname, resnames, n) : -1;
        kept += keep[i] = at < 0;
        if (at >= 0 && counts)
            counts[at]++;
    }
    int rc = kept == 0 ? vb_error(ctx, VB_EINPUT_EMPTY, s->source, 0,
                                  "--ignore and --membrane leave no atom")
                       : vb_spheres_subset(ctx, s, keep, out);
    free(keep);
    if (rc == VB_OK)
        *dropped = s->n - kept;
    return rc;
}
