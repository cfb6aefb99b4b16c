/* PDB reader: fixed columns of ATOM/HETATM records, MODEL/ENDMDL, alternate
 * locations, water and hydrogens per the read options; radii by element. */
#include "vbi_input.h"
#include "vb_box.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* Columns [from, to], 1-based inclusive, clipped to the line. */
static size_t column(const char *line, size_t n, size_t from, size_t to, const char **s)
{
    *s = line + (from - 1 < n ? from - 1 : n);
    if (n < from)
        return 0;
    return (n < to ? n : to) - from + 1;
}

static char column_char(const char *line, size_t n, size_t col)
{
    return col <= n ? line[col - 1] : ' ';
}

static const char *const axis_names[3] = {"x coordinate", "y coordinate", "z coordinate"};

/* The text a reader parses, and how its atom names are laid out (looked at
 * when a first atom lacks its element). */
typedef struct {
    const char *buf;
    size_t len;
    int layout; /* -1 until needed, then a VBI_LAYOUT_* */
    vbi_infer_memo *memo; /* elements inferred from the names (NULL: none) */
} pdb_text;

/* The residue of an atom line and its alternate location (columns 17,
 * 22-27) into info. */
static void residue_fields(const char *line, size_t n, vb_atom_info *info)
{
    const char *s;
    size_t k;
    info->altloc = column_char(line, n, 17);
    k = column(line, n, 22, 22, &s);
    vbi_copy_field(info->chain, sizeof info->chain, s, k);
    k = column(line, n, 23, 26, &s);
    vbi_parse_int(s, k, &info->resseq);
    info->icode = column_char(line, n, 27);
    k = column(line, n, 73, 76, &s);
    vbi_copy_field(info->segid, sizeof info->segid, s, k);
}

/* Offers every lettered atom of the models read (columns 55-60: its
 * occupancy) to alt, so each residue keeps its most occupied location
 * (vbi_altloc_offer) before the atoms are read. -1 when out of memory. */
static int altloc_prepass(const char *buf, size_t len, const vb_read_options *opt,
                          vbi_altloc *alt)
{
    vbi_atom_scan scan;
    vbi_atom_scan_init(&scan, opt->model);
    vbi_dropped ignored;
    memset(&ignored, 0, sizeof ignored);
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line;
    size_t n;
    while (vbi_lines_next(&it, &line, &n)) {
        vbi_record rec = vbi_record_kind(vbi_pdb_record, line, n);
        int32_t serial = rec == VBI_REC_MODEL ? vbi_pdb_model_serial(line, n) : 0;
        if (!vbi_atom_scan_takes(&scan, rec, serial, it.lineno, &ignored) ||
            column_char(line, n, 17) == ' ')
            continue;
        vb_atom_info info;
        memset(&info, 0, sizeof info);
        residue_fields(line, n, &info);
        const char *s;
        size_t k = column(line, n, 55, 60, &s);
        char field[8];
        vbi_copy_field(field, sizeof field, s, k);
        vb_decimal e;
        double occ = -1; /* blank or unreadable: below any occupancy */
        if (field[0] && vb_decimal_parse(field, strlen(field), &e, &occ) != VB_OK)
            occ = -1;
        if (vbi_altloc_offer(alt, &info, occ) != 0)
            return -1;
    }
    return 0;
}

/* Fills info, e and d from one ATOM/HETATM line (radius aside); *how gets
 * VBI_INFER_NONE when columns 77-78 give the element, else how it was
 * inferred. */
static int parse_atom_line(vb_ctx *ctx, const char *name, long lineno, const char *line,
                           size_t n, pdb_text *text, vb_atom_info *info, vb_decimal e[4],
                           double d[4], int *how)
{
    if (n < 54)
        return vb_error(ctx, VB_EINPUT_MALFORMED, name, lineno,
                        "ATOM/HETATM record shorter than 54 columns (coordinates in 31-54)");
    const char *s;
    size_t k;
    for (int a = 0; a < 3; a++) {
        k = column(line, n, 31 + 8 * (size_t)a, 38 + 8 * (size_t)a, &s);
        char field[9];
        vbi_copy_field(field, sizeof field, s, k);
        int rc = vbi_parse_number(ctx, name, lineno, axis_names[a], field, strlen(field), &e[a],
                                  &d[a]);
        if (rc != VB_OK)
            return rc;
    }
    memset(info, 0, sizeof *info);
    info->hetatm = line[0] == 'H';
    k = column(line, n, 7, 11, &s);
    vbi_parse_int(s, k, &info->serial);
    k = column(line, n, 13, 16, &s);
    char name4[5] = "    ";
    memcpy(name4, s, k);
    vbi_copy_field(info->name, sizeof info->name, s, k);
    k = column(line, n, 18, 21, &s);
    vbi_copy_field(info->resname, sizeof info->resname, s, k);
    residue_fields(line, n, info);
    k = column(line, n, 77, 78, &s);
    char el[4];
    vbi_copy_field(el, sizeof el, s, k);
    int alpha = el[0] != '\0';
    for (size_t c = 0; el[c]; c++)
        alpha &= isalpha((unsigned char)el[c]) != 0;
    *how = VBI_INFER_NONE;
    if (alpha) {
        for (size_t c = 0; el[c]; c++)
            info->element[c] = (char)toupper((unsigned char)el[c]);
    } else {
        if (text->layout < 0)
            text->layout = vbi_pdb_name_layout(text->buf, text->len);
        *how = vbi_infer_element_memo(text->memo, name4, info->name, info->resname, text->layout,
                                      info->element);
    }
    return VB_OK;
}

/* The box of a CRYST1 record (a b c in columns 7-33, alpha beta gamma in
 * 34-54): 1 and *box set when it gives one. The unit cube 1 1 1 is the
 * convention for "no crystal" (NMR models) and gives none. */
int vbi_pdb_cryst1_box(const char *line, size_t n, vb_box *box)
{
    static const int col[7] = {6, 15, 24, 33, 40, 47, 54};
    vb_decimal d[6];
    for (int k = 0; k < 6; k++) {
        size_t a = (size_t)col[k], b = (size_t)col[k + 1];
        if (b > n)
            return 0;
        while (a < b && line[a] == ' ')
            a++;
        while (b > a && line[b - 1] == ' ')
            b--;
        if (a == b || vb_decimal_parse(line + a, b - a, &d[k], NULL) != VB_OK)
            return 0;
    }
    const vb_decimal one = {1, 0};
    if (vb_decimal_cmp(d[0], one) == 0 && vb_decimal_cmp(d[1], one) == 0 &&
        vb_decimal_cmp(d[2], one) == 0)
        return 0;
    return vb_box_from_cell(NULL, d, d + 3, NULL, 0, box) == VB_OK;
}

int vbi_pdb_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out)
{
    vbi_builder b;
    vbi_atom_scan scan;
    int rc = vbi_atom_parse_begin(ctx, name, opt, &b, &scan, out);
    if (rc != VB_OK)
        return rc;
    vbi_altloc alt;
    vbi_altloc_init(&alt);
    if (altloc_prepass(buf, len, opt, &alt) != 0)
        rc = vb_error(ctx, VB_ENOMEM, name, 0, "out of memory (alternate locations)");
    pdb_text text;
    memset(&text, 0, sizeof text);
    text.buf = buf;
    text.len = len;
    text.layout = -1;
    text.memo = calloc(1, sizeof *text.memo); /* without it, slower, the same answers */
    size_t records = 0; /* ATOM/HETATM records met, read or not */
    vbi_lines it;
    vbi_lines_init(&it, buf, len, first_line);
    const char *line;
    size_t n;
    vb_box box;
    int has_box = 0;
    size_t taken = 0;
    while (rc == VB_OK && vbi_lines_next(&it, &line, &n)) {
        /* The box of the model read: the last CRYST1 before its first atom
         * (trajectories as PDB write one per model). */
        if (taken == 0 && vbi_pdb_record(line, n, "CRYST1"))
            has_box = vbi_pdb_cryst1_box(line, n, &box);
        vbi_record rec = vbi_record_kind(vbi_pdb_record, line, n);
        int32_t serial = rec == VBI_REC_MODEL ? vbi_pdb_model_serial(line, n) : 0;
        records += rec == VBI_REC_ATOM;
        if (!vbi_atom_scan_takes(&scan, rec, serial, it.lineno, dr))
            continue;
        vb_atom_info info;
        vb_decimal e[4];
        double d[4];
        int how;
        rc = parse_atom_line(ctx, name, it.lineno, line, n, &text, &info, e, d, &how);
        if (rc != VB_OK)
            break;
        int drop = vbi_atom_dropped(opt, &alt, &info, dr);
        if (drop < 0)
            rc = vb_error(ctx, VB_ENOMEM, name, it.lineno, "out of memory (alternate locations)");
        if (drop)
            continue;
        rc = vbi_atom_keep(ctx, opt, name, it.lineno, &info, how, dr, &b, e, d);
        taken++;
    }
    vbi_altloc_free(&alt);
    free(text.memo);
    if (rc == VB_OK && records == 0)
        rc = vb_error(ctx, VB_EINPUT_EMPTY, name, 0,
                      "no atoms: no ATOM or HETATM record in the PDB input");
    rc = vbi_atom_parse_end(&b, &scan, dr, rc, out);
    if (rc == VB_OK && *out && has_box) {
        (*out)->box = malloc(sizeof *(*out)->box);
        if (!(*out)->box) {
            vb_spheres_free(*out);
            *out = NULL;
            return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
        }
        *(*out)->box = box;
    }
    return rc;
}
