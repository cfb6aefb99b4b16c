/* Atoms left out of the channel analysis by residue name (--ignore, as
 * HOLE's ignore card: ligands, sugars, ions, waters; --membrane: membrane
 * dummy atoms, lipids and detergents) and the ligands (HETATM residues that
 * are no polymer residue, unless --keep-ligands). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vb_select.h"
#include "vbc_channel.h"
#include "vbc_channels_config.h"

/* The index of resname in names (case-insensitive), or -1. */
static long listed_at(const char *resname, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (strcasecmp(resname, names[k]) == 0)
            return (long)k;
    return -1;
}

/* HETATM residue names that are part of a polymer chain: modified amino
 * acids, D-amino acids (gramicidin's), terminal caps, modified nucleotides.
 * Sorted for bsearch. */
static const char *const polymer_hetatm[] = {
    "0AF", "1MA", "2MG", "5MC", "5MU", "7MG", "ABA", "ACE", "AIB", "ALY", "ASX", "CGU", "CME",
    "CSD", "CSO", "CSS", "CSX", "DAL", "DAR", "DAS", "DCY", "DGL", "DGN", "DHI", "DIL", "DLE",
    "DLY", "DPN", "DPR", "DSG", "DSN", "DTH", "DTR", "DTY", "DVA", "ETA", "FME", "FOR", "FVA",
    "GLX", "H2U", "HIC", "HYP", "KCX", "LLP", "M2G", "M3L", "MED", "MLY", "MLZ", "MSE", "MVA",
    "NH2", "NHE", "NLE", "NME", "OMC", "OMG", "ORN", "PCA", "PSU", "PTR", "PYL", "SAR", "SEC",
    "SEP", "TPO", "TYS", "UNK"};

static int cmp_name(const void *a, const void *b)
{
    return strcasecmp(*(const char *const *)a, *(const char *const *)b);
}

int vbc_is_ligand(const vb_atom_info *a)
{
    const char *key = a->resname;
    if (!a->hetatm || bsearch(&key, polymer_hetatm, sizeof polymer_hetatm / sizeof polymer_hetatm[0],
                              sizeof polymer_hetatm[0], cmp_name))
        return 0;
    /* The membrane's residues are --membrane's to leave out or keep. */
    char word[sizeof a->resname + 2];
    snprintf(word, sizeof word, ",%s,", a->resname);
    return strstr("," VBC_MEMBRANE_DEFAULT ",", word) == NULL;
}

static void ligand_count(vbc_ligands *L, const char *resname)
{
    L->atoms++;
    for (size_t k = 0; k < L->n; k++)
        if (strcmp(L->name[k], resname) == 0) {
            L->count[k]++;
            return;
        }
    if (L->n == VBC_LIGAND_NAMES)
        return;
    snprintf(L->name[L->n], sizeof L->name[L->n], "%s", resname);
    L->count[L->n++] = 1;
}

int vbc_spheres_without(vb_ctx *ctx, const vb_sphere_set *s, const char *const *resnames, size_t n,
                        size_t *counts, vbc_ligands *lig, vb_sphere_set **out, size_t *dropped)
{
    *out = NULL;
    *dropped = 0;
    uint8_t *keep = malloc(s->n ? s->n : 1);
    if (!keep)
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory");
    size_t kept = 0;
    /* The atoms of a residue follow each other: the verdict on the last
     * (residue name, HETATM) pair is reused while it repeats. */
    const vb_atom_info *last = NULL;
    long at = -1;
    int ligand = 0;
    for (size_t i = 0; i < s->n; i++) {
        const vb_atom_info *a = s->info ? &s->info[i] : NULL;
        if (a && !(last && last->hetatm == a->hetatm &&
                   strncmp(last->resname, a->resname, sizeof a->resname) == 0)) {
            at = listed_at(a->resname, resnames, n);
            ligand = at < 0 && lig && vbc_is_ligand(a);
            last = a;
        }
        kept += keep[i] = at < 0 && !ligand;
        if (at >= 0 && counts)
            counts[at]++;
        if (ligand)
            ligand_count(lig, s->info[i].resname);
    }
    int rc = kept == 0 ? vb_error(ctx, VB_EINPUT_EMPTY, s->source, 0,
                                  "--ignore, --membrane and the ligands leave no atom")
                       : vb_spheres_subset(ctx, s, keep, out);
    free(keep);
    if (rc == VB_OK)
        *dropped = s->n - kept;
    return rc;
}
