/* The element of an atom whose file does not say it (PDB columns 77-78
 * blank, as CHARMM, NAMD, GROMACS and legacy writers leave them; mmCIF
 * without type_symbol; GRO), inferred the way the PDB atom-name convention
 * intends, and never silently:
 *
 *  1. the residue first: a single-atom ion residue (CA, CAL, ZN, SOD, CLA,
 *     ...) whose atom bears its name is that ion; in an amino acid, a
 *     nucleotide or water every atom is H, C, N, O, S or P (Se in MSE/SEC),
 *     so the first letter of the name is the element ("CA" in ALA is a
 *     C-alpha, never calcium);
 *  2. else the alignment of columns 13-16 (PDB only): a one-letter element
 *     starts in column 14, a two-letter one in column 13 ("CA  " is
 *     calcium, " CA " carbon) - but only in a file that keeps the
 *     convention: where its amino acids start one-letter names in column 13
 *     (CHARMM's "CA  " for the C-alpha) the column says nothing, and only
 *     the halogens CL and BR are read as two letters;
 *  3. else (no columns, or a file that does not keep them) an atom named
 *     ZN, MG, FE, MN or CU alone is that metal (ZN in ZNM, FE in HEM);
 *  4. else the first letter.
 * The caller counts every inference and warns (W714, W715; W716 for case 2
 * when it chose a two-letter element); --strict-elements refuses them. */
#include "vbi_input.h"
#include "vb_diag.h"

#include <ctype.h>
#include <stdint.h>
#include <string.h>

/* Residues whose atoms are all H, C, N, O, S, P: amino acids (with the
 * protonation and terminal variants of AMBER, CHARMM and GROMACS), caps,
 * nucleotides (PDB, AMBER and CHARMM names) and water. */
static const char *const plain_residues[] = {
    "ALA", "ARG", "ASN", "ASP", "CYS", "GLN", "GLU", "GLY", "HIS", "ILE", "LEU", "LYS", "MET",
    "PHE", "PRO", "SER", "THR", "TRP", "TYR", "VAL", "ASX", "GLX", "UNK",
    "HSD", "HSE", "HSP", "HID", "HIE", "HIP", "HISA", "HISB", "HISD", "HISE", "HISH", "CYX",
    "CYM", "CYS2", "ASH", "GLH", "LYN", "LSN", "ARN", "TYM", "ASPP", "GLUP", "ASPH", "GLUH",
    "NALA", "CALA", "NGLY", "CGLY", "NMET", "CMET",
    "ACE", "NME", "NMA", "NH2", "NHE",
    "A", "C", "G", "U", "T", "I", "DA", "DC", "DG", "DT", "DU", "DI", "RA", "RC", "RG", "RU",
    "ADE", "CYT", "GUA", "THY", "URA", "DA5", "DA3", "DC5", "DC3", "DG5", "DG3", "DT5", "DT3",
    "RA5", "RA3", "RC5", "RC3", "RG5", "RG3", "RU5", "RU3",
    "HOH", "WAT", "DOD", "H2O", "TIP", "TIP3", "TIP4", "TIP5", "SOL", "T3P", "T4P", "SPC", "SPCE",
};

/* Single-atom ion residues of the PDB, CHARMM (SOD, POT, CLA, CAL, CES) and
 * GROMACS, and the element they are. */
static const struct {
    const char *residue, *element;
} ions[] = {
    {"CA", "CA"},  {"CAL", "CA"}, {"MG", "MG"},  {"ZN", "ZN"},  {"ZN2", "ZN"}, {"NA", "NA"},
    {"SOD", "NA"}, {"K", "K"},    {"POT", "K"},  {"CL", "CL"},  {"CLA", "CL"}, {"FE", "FE"},
    {"FE2", "FE"}, {"MN", "MN"},  {"MN3", "MN"}, {"CU", "CU"},  {"CU1", "CU"}, {"CO", "CO"},
    {"NI", "NI"},  {"CD", "CD"},  {"CS", "CS"},  {"CES", "CS"}, {"LI", "LI"},  {"LIT", "LI"},
    {"RB", "RB"},  {"SR", "SR"},  {"BA", "BA"},  {"HG", "HG"},  {"BR", "BR"},  {"IOD", "I"},
    {"I", "I"},    {"AL", "AL"},  {"F", "F"},    {"NI2", "NI"}, {"CO2", "CO"}, {"CU2", "CU"},
};

/* Two-letter element symbols that column 13 can announce. */
static const char *const two_letter[] = {
    "AG", "AL", "AR", "AS", "AU", "BA", "BE", "BR", "CA", "CD", "CE", "CL", "CO", "CR", "CS",
    "CU", "FE", "GA", "GD", "GE", "HG", "IR", "KR", "LA", "LI", "MG", "MN", "MO", "NA", "NE",
    "NI", "OS", "PB", "PD", "PT", "RB", "RE", "RH", "RU", "SB", "SE", "SI", "SN", "SR", "TE",
    "TI", "TL", "XE", "YB", "ZN",
};

/* Metals that an atom named as the element alone is, in any residue that
 * is no amino acid, nucleotide or water (zinc "ZN" in ZNM, iron "FE" in
 * HEM: no organic atom is named so). Not calcium ("CA" in CAS, a modified
 * cysteine, is its C-alpha) nor nickel ("NI" may be a nitrogen). */
static const char *const named_metals[] = {"ZN", "MG", "FE", "MN", "CU"};

static int in_list(const char *s, const char *const *list, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (strcmp(s, list[k]) == 0)
            return 1;
    return 0;
}

int vbi_plain_residue(const char *resname)
{
    return in_list(resname, plain_residues, sizeof plain_residues / sizeof plain_residues[0]);
}

/* Upper-case copy of a trimmed name. */
static void upper(char *dst, size_t cap, const char *src)
{
    size_t k = 0;
    for (; src[k] && k + 1 < cap; k++)
        dst[k] = (char)toupper((unsigned char)src[k]);
    dst[k] = '\0';
}

/* The letters of a name (charges and digits aside: "NA+" is NA). */
static void letters(char *dst, size_t cap, const char *src)
{
    size_t k = 0;
    for (; *src && k + 1 < cap; src++)
        if (isalpha((unsigned char)*src))
            dst[k++] = *src;
    dst[k] = '\0';
}

/* The ion a residue is, when the atom bears the residue's or the element's
 * name ("ZN" in ZN2, "NA" in NA+, "SOD" in SOD). */
static const char *ion_of(const char *res, const char *name)
{
    char bare[8], bres[8];
    letters(bare, sizeof bare, name);
    letters(bres, sizeof bres, res);
    for (size_t i = 0; i < sizeof ions / sizeof ions[0]; i++)
        if ((strcmp(res, ions[i].residue) == 0 || strcmp(bres, ions[i].residue) == 0) &&
            (strcmp(name, res) == 0 || strcmp(bare, ions[i].element) == 0 ||
             strcmp(bare, bres) == 0))
            return ions[i].element;
    return NULL;
}

static void set(char element[4], char a, char b)
{
    element[0] = a;
    element[1] = b;
    element[2] = '\0';
}

int vbi_infer_element(const char *name4, const char *name, const char *resname, int layout,
                      char element[4])
{
    char res[8], nm[8];
    upper(res, sizeof res, resname ? resname : "");
    upper(nm, sizeof nm, name ? name : "");
    element[0] = '\0';
    const char *ion = ion_of(res, nm);
    if (ion) {
        strcpy(element, ion);
        return VBI_INFER_RESIDUE;
    }
    /* A residue named as a two-letter element whose atom bears that name
     * (argon "AR" in "AR"): that element. */
    char bare[8], bres[8];
    letters(bare, sizeof bare, nm);
    letters(bres, sizeof bres, res);
    if (bare[0] && bare[1] && !bare[2] && strcmp(bare, bres) == 0 &&
        in_list(bare, two_letter, sizeof two_letter / sizeof two_letter[0])) {
        strcpy(element, bare);
        return VBI_INFER_RESIDUE;
    }
    /* The first letter after leading digits ("1HG2" is a hydrogen). */
    size_t i = 0;
    while (nm[i] && !isalpha((unsigned char)nm[i]))
        i++;
    if (!nm[i])
        return VBI_INFER_NONE;
    char a = nm[i], b = nm[i + 1] && isalpha((unsigned char)nm[i + 1]) ? nm[i + 1] : '\0';
    if (vbi_plain_residue(res)) {
        if (a == 'S' && b == 'E' && (strcmp(res, "MSE") == 0 || strcmp(res, "SEC") == 0))
            set(element, 'S', 'E');
        else
            set(element, a, '\0');
        return VBI_INFER_RESIDUE;
    }
    char ab[3] = {a, b, '\0'};
    int two = b && in_list(ab, two_letter, sizeof two_letter / sizeof two_letter[0]);
    if (name4 && layout != VBI_LAYOUT_LEFT) {
        /* Column 13 holds the name's first letter: a two-letter element,
         * unless the name fills all four columns as hydrogens' do. */
        int col13 = isalpha((unsigned char)name4[0]) != 0;
        int four = name4[3] != ' ' && name4[3] != '\0';
        if (col13 && two && !(a == 'H' && four)) {
            set(element, a, b);
            return VBI_INFER_ALIGNMENT;
        }
        set(element, a, '\0');
        return VBI_INFER_LETTER;
    }
    /* No columns, or columns that do not follow the convention: only the
     * halogens, whose two letters no other atom name begins with, and the
     * metals no organic atom is named as. */
    if (in_list(nm, named_metals, sizeof named_metals / sizeof named_metals[0])) {
        strcpy(element, nm);
        return VBI_INFER_RESIDUE;
    }
    if (two && ((a == 'C' && b == 'L') || (a == 'B' && b == 'R')))
        set(element, a, b);
    else
        set(element, a, '\0');
    return VBI_INFER_LETTER;
}

int vbi_infer_element_memo(vbi_infer_memo *m, const char *name4, const char *name,
                           const char *resname, int layout, char element[4])
{
    size_t ln = strlen(name), lr = strlen(resname), l4 = name4 ? strlen(name4) : 0;
    if (!m || ln >= sizeof m->e[0].name || lr >= sizeof m->e[0].resname || l4 >= sizeof m->e[0].name4 ||
        (name4 && l4 == 0))
        return vbi_infer_element(name4, name, resname, layout, element);
    uint32_t h = 2166136261u; /* FNV-1a over the names and the layout */
    for (size_t k = 0; k <= ln; k++)
        h = (h ^ (unsigned char)name[k]) * 16777619u;
    for (size_t k = 0; k < lr; k++)
        h = (h ^ (unsigned char)resname[k]) * 16777619u;
    for (size_t k = 0; k < l4; k++)
        h = (h ^ (unsigned char)name4[k]) * 16777619u;
    h = (h ^ (uint32_t)(layout + 1)) * 16777619u;
    size_t slot = h % (sizeof m->e / sizeof m->e[0]);
    if (m->e[slot].used && m->e[slot].layout == layout && strcmp(m->e[slot].name, name) == 0 &&
        strcmp(m->e[slot].resname, resname) == 0 && strcmp(m->e[slot].name4, name4 ? name4 : "") == 0) {
        memcpy(element, m->e[slot].element, 4);
        return m->e[slot].how;
    }
    int how = vbi_infer_element(name4, name, resname, layout, element);
    memcpy(m->e[slot].name, name, ln + 1);
    memcpy(m->e[slot].resname, resname, lr + 1);
    memcpy(m->e[slot].name4, name4 ? name4 : "", l4 + 1);
    memcpy(m->e[slot].element, element, 4);
    m->e[slot].layout = layout;
    m->e[slot].how = how;
    m->e[slot].used = 1;
    return how;
}

int vbi_pdb_name_layout(const char *buf, size_t len)
{
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line;
    size_t n, seen = 0;
    long left = 0, aligned = 0;
    /* Names of one to three characters in amino acids and nucleotides are
     * one-letter elements: they start in column 14 by the convention, in
     * column 13 when the writer left-justifies. */
    while (vbi_lines_next(&it, &line, &n) && seen < 2000) {
        if (n < 27 || !(vbi_pdb_record(line, n, "ATOM") || vbi_pdb_record(line, n, "HETATM")))
            continue;
        char res[8];
        vbi_copy_field(res, sizeof res, line + 17, 4);
        if (!vbi_plain_residue(res))
            continue;
        seen++;
        const char *c = line + 12;
        if (c[3] != ' ')
            continue;
        if (isalpha((unsigned char)c[0]))
            left++;
        else if (c[0] == ' ' && isalpha((unsigned char)c[1]))
            aligned++;
    }
    if (left > aligned)
        return VBI_LAYOUT_LEFT;
    return aligned > 0 ? VBI_LAYOUT_PDB : VBI_LAYOUT_UNKNOWN;
}

int vbi_element_inferred(vb_ctx *ctx, const vb_read_options *opt, const char *file, long line,
                         const vb_atom_info *info, int how, vbi_dropped *dr)
{
    if (opt->strict_elements)
        return vb_error(ctx, VB_EINPUT_INFERRED, file, line,
                        "atom '%s' of residue '%s' has no element in the file (PDB columns 77-78 "
                        "blank, no mmCIF type_symbol, or GRO): it would be inferred as %s, "
                        "which --strict-elements refuses",
                        info->name, info->resname, info->element);
    if (dr->inferred++ == 0)
        vb_warn(ctx, VB_W_ELEMENT_INFERRED, file, line,
                "atom '%s' of residue '%s' has no element in the file (PDB columns 77-78 "
                "blank, no mmCIF type_symbol, or GRO): read as %s, from %s; such atoms are "
                "counted (--strict-elements refuses them)",
                info->name, info->resname, info->element,
                how == VBI_INFER_RESIDUE     ? "its residue"
                : how == VBI_INFER_ALIGNMENT ? "its column alignment"
                                             : "its first letter");
    if (how == VBI_INFER_ALIGNMENT && dr->inferred_alignment++ == 0)
        vb_warn(ctx, VB_W_ELEMENT_ALIGNMENT, file, line,
                "atom '%s' of residue '%s' starts in column 13: read as the two-letter element "
                "%s by the PDB convention (a left-justified name would be %c)",
                info->name, info->resname, info->element, info->element[0]);
    size_t k = 0;
    while (k < VBI_INFERRED_KINDS && dr->inferred_el[k][0] &&
           strcmp(dr->inferred_el[k], info->element) != 0)
        k++;
    if (k < VBI_INFERRED_KINDS) {
        if (!dr->inferred_el[k][0])
            strcpy(dr->inferred_el[k], info->element);
        dr->inferred_count[k]++;
    }
    return VB_OK;
}

void vbi_report_inferred(vb_ctx *ctx, const char *name, const vbi_dropped *dr)
{
    if (!dr->inferred)
        return;
    char list[256];
    size_t off = 0;
    list[0] = '\0';
    for (size_t k = 0; k < VBI_INFERRED_KINDS && dr->inferred_el[k][0]; k++) {
        int w = snprintf(list + off, sizeof list - off, "%s%s %zu", k ? ", " : "",
                         dr->inferred_el[k], dr->inferred_count[k]);
        if (w < 0 || (size_t)w >= sizeof list - off)
            break;
        off += (size_t)w;
    }
    vb_warn(ctx, VB_W_ELEMENT_INFERRED_COUNT, name, 0,
            "%zu atom%s without an element: inferred from name and residue (%s)%s", dr->inferred,
            dr->inferred == 1 ? "" : "s", list,
            dr->inferred_alignment ? "; some two-letter elements from column alignment alone (W716)"
                                   : "");
}
