/* The JSON writer of the cell measures (vb_measures.h): per-atom rows as
 * the TSV prints them, then per-residue and per-chain sums. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_build.h"
#include "vb_json.h"
#include "vb_measures.h"
#include "vbm_text.h"

/* "name": value, "name_lo": lo, "name_hi": hi with the TSV's digits. */
static void put_value(FILE *f, const char *name, double lo, double hi)
{
    fprintf(f, ", \"%s\": %.12g, \"%s_lo\": %.12g, \"%s_hi\": %.12g", name, vbm_text_mid(lo, hi),
            name, vbm_text_lo(lo), name, vbm_text_hi(hi));
}

static void put_string(FILE *f, const char *key, const char *s)
{
    fprintf(f, ", \"%s\": ", key);
    vb_json_write_string(f, s);
}

/* The fields naming atom a's residue (by_chain: its chain alone). */
static void put_names(FILE *f, const vb_atom_info *a, int by_chain)
{
    put_string(f, "chain", a->chain);
    if (by_chain)
        return;
    put_string(f, "resname", a->resname);
    fprintf(f, ", \"resseq\": %d", (int)a->resseq);
    char icode[2] = {a->icode == ' ' ? '\0' : a->icode, '\0'};
    put_string(f, "icode", icode);
}

static void put_groups(FILE *f, const char *key, const vb_sphere_set *set, const vb_cell_group *g,
                       size_t n, int by_chain)
{
    fprintf(f, ",\n  \"%s\": [", key);
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "%s\n    {\"atoms\": %zu", k ? "," : "", g[k].natoms);
        put_names(f, &set->info[g[k].first], by_chain);
        put_value(f, "volume", g[k].vol_lo, g[k].vol_hi);
        put_value(f, "sas", g[k].sas_lo, g[k].sas_hi);
        fputc('}', f);
    }
    fputs(n ? "\n  ]" : "]", f);
}

int vb_cell_measures_write_json(vb_ctx *ctx, FILE *f, const vb_sphere_set *set,
                                const vb_cell_measures *m, long frame, int model)
{
    return vb_cell_measures_write_json_prov(ctx, f, set, m, frame, model, NULL);
}

int vb_cell_measures_write_json_prov(vb_ctx *ctx, FILE *f, const vb_sphere_set *set,
                                     const vb_cell_measures *m, long frame, int model,
                                     const vb_provenance *prov)
{
    vb_cell_group *res = NULL, *ch = NULL;
    size_t nres = 0, nch = 0;
    int rc = vb_cell_measures_groups(ctx, set, m, 0, &res, &nres);
    if (rc == VB_OK)
        rc = vb_cell_measures_groups(ctx, set, m, 1, &ch, &nch);
    if (rc != VB_OK) {
        free(res);
        return rc;
    }
    fputs("{", f);
    if (prov)
        vb_provenance_write_json(f, prov);
    if (frame >= 0)
        fprintf(f, "\"frame\": %ld, \"model\": %d, ", frame, model);
    fprintf(f, "\"atoms\": [");
    for (size_t i = 0; i < m->n; i++) {
        fprintf(f, "%s\n    {\"id\": %zu", i ? "," : "", i);
        if (set->info) {
            put_names(f, &set->info[i], 0);
            put_string(f, "atom", set->info[i].name);
        }
        put_value(f, "volume", m->vol_lo[i], m->vol_hi[i]);
        put_value(f, "sas", m->sas_lo[i], m->sas_hi[i]);
        fprintf(f, ", \"empty\": %s, \"loose\": %s}", m->empty[i] ? "true" : "false",
                m->loose[i] ? "true" : "false");
    }
    fputs(m->n ? "\n  ]" : "]", f);
    if (set->info) {
        put_groups(f, "residues", set, res, nres, 0);
        put_groups(f, "chains", set, ch, nch, 1);
    }
    fputs("}", f);
    free(res);
    free(ch);
    return VB_OK;
}
