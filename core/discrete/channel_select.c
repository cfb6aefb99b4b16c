/* Atoms left out of the channel analysis by residue name (--ignore, as
 * HOLE's ignore card: ligands, sugars, ions, waters; --membrane: membrane
 * dummy atoms, lipids and detergents). */
#include <string.h>
#include <strings.h>

#include "vbc_channel.h"

/* The index of resname in names (case-insensitive), or -1. */
static long listed_at(const char *resname, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (strcasecmp(resname, names[k]) == 0)
            return (long)k;
    return -1;
}

static int listed(const char *resname, const char *const *names, size_t n)
{
    return listed_at(resname, names, n) >= 0;
}

int vbc_spheres_without(vb_ctx *ctx, const vb_sphere_set *s, const char *const *resnames, size_t n,
                        size_t *counts, vb_sphere_set **out, size_t *dropped)
{
    *out = NULL;
    *dropped = 0;
    size_t keep = 0;
    for (size_t i = 0; i < s->n; i++) {
        long at = s->info ? listed_at(s->info[i].resname, resnames, n) : -1;
        keep += at < 0;
        if (at >= 0 && counts)
            counts[at]++;
    }
    if (keep == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, s->source, 0,
                        "--ignore and --membrane leave no atom");
    vb_sphere_set *t;
    int rc = vb_spheres_new(ctx, s->source, keep, s->info != NULL, &t);
    if (rc != VB_OK)
        return rc;
    size_t k = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->info && listed(s->info[i].resname, resnames, n))
            continue;
        t->x[k] = s->x[i];
        t->y[k] = s->y[i];
        t->z[k] = s->z[i];
        t->r[k] = s->r[i];
        t->line[k] = s->line ? s->line[i] : 0;
        if (s->info)
            t->info[k] = s->info[i];
        k++;
    }
    *dropped = s->n - keep;
    *out = t;
    return VB_OK;
}
