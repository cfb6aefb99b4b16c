/* Per-residue and per-chain sums of the cell measures (vb_measures.h):
 * atoms grouped by key through the library's hash table, groups in the
 * order of their first atom, each sum an interval sum rounded outward. */
#include <stdlib.h>
#include <string.h>

#include "vb_hash.h"
#include "vb_measures.h"
#include "vbx_ia.h"

typedef struct {
    const vb_atom_info *info;
    const vb_cell_group *g; /* the groups so far (g[k].first: an atom of group k) */
    int by_chain;
    size_t atom;            /* the atom whose group is sought */
} group_key;

static int same_group(const void *key, size_t item)
{
    const group_key *k = key;
    const vb_atom_info *a = &k->info[k->atom], *b = &k->info[k->g[item].first];
    if (strcmp(a->chain, b->chain) != 0)
        return 0;
    return k->by_chain || (a->resseq == b->resseq && a->icode == b->icode &&
                           strcmp(a->resname, b->resname) == 0);
}

static uint64_t hash_atom(const vb_atom_info *a, int by_chain)
{
    uint64_t h = 0;
    for (const char *c = a->chain; *c; c++)
        h = vb_hash_mix(h, (unsigned char)*c);
    if (by_chain)
        return h;
    h = vb_hash_mix(h, (uint64_t)(uint32_t)a->resseq);
    h = vb_hash_mix(h, (unsigned char)a->icode);
    for (const char *c = a->resname; *c; c++)
        h = vb_hash_mix(h, (unsigned char)*c);
    return h;
}

static uint64_t hash_group(const void *arg, size_t item)
{
    const group_key *k = arg;
    return hash_atom(&k->info[k->g[item].first], k->by_chain);
}

int vb_cell_measures_groups(vb_ctx *ctx, const vb_sphere_set *set, const vb_cell_measures *m,
                            int by_chain, vb_cell_group **out, size_t *nout)
{
    *out = NULL;
    *nout = 0;
    if (!set->info || m->n == 0)
        return VB_OK;
    vb_cell_group *g = malloc(m->n * sizeof *g);
    vb_hash h = {0};
    if (!g || vb_hash_fit(&h, 16, hash_group, NULL) != VB_OK) {
        free(g);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (residue sums)");
    }
    group_key k = {set->info, g, by_chain, 0};
    size_t n = 0;
    int rc = VB_OK;
    for (size_t i = 0; i < m->n && rc == VB_OK; i++) {
        k.atom = i;
        uint64_t hv = hash_atom(&set->info[i], by_chain);
        size_t *s = vb_hash_slot(&h, hv, same_group, &k);
        if (*s) {
            vb_cell_group *e = &g[*s - 1];
            vbx_ia v = vbx_ia_add((vbx_ia){e->vol_lo, e->vol_hi}, (vbx_ia){m->vol_lo[i], m->vol_hi[i]});
            vbx_ia a = vbx_ia_add((vbx_ia){e->sas_lo, e->sas_hi}, (vbx_ia){m->sas_lo[i], m->sas_hi[i]});
            e->vol_lo = v.lo, e->vol_hi = v.hi, e->sas_lo = a.lo, e->sas_hi = a.hi;
            e->natoms++;
            continue;
        }
        g[n] = (vb_cell_group){i, 1, m->vol_lo[i], m->vol_hi[i], m->sas_lo[i], m->sas_hi[i]};
        rc = vb_hash_put(&h, s, n, hash_group, &k);
        n++;
    }
    vb_hash_free(&h);
    if (rc != VB_OK) {
        free(g);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (residue sums)");
    }
    *out = g;
    *nout = n;
    return VB_OK;
}
