/* mmCIF reader: the first _atom_site loop. Coordinates from Cartn_x/y/z,
 * element from type_symbol, models from pdbx_PDB_model_num, alternate
 * locations from label_alt_id; residue and chain from the auth_* items when
 * present (they match the PDB file), else label_*. */
#include "vb_array.h"
#include "vbi_cif.h"
#include "vbi_input.h"
#include "vb_diag.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* The atom_site items the reader uses; index into a column map. */
enum {
    COL_X, COL_Y, COL_Z, COL_TYPE, COL_MODEL, COL_ALT, COL_GROUP, COL_ID,
    COL_AUTH_ATOM, COL_LABEL_ATOM, COL_AUTH_COMP, COL_LABEL_COMP, COL_AUTH_ASYM,
    COL_LABEL_ASYM, COL_AUTH_SEQ, COL_LABEL_SEQ, COL_ICODE, COL_COUNT
};

static const char *const item_names[COL_COUNT] = {
    "cartn_x", "cartn_y", "cartn_z", "type_symbol", "pdbx_pdb_model_num", "label_alt_id",
    "group_pdb", "id", "auth_atom_id", "label_atom_id", "auth_comp_id", "label_comp_id",
    "auth_asym_id", "label_asym_id", "auth_seq_id", "label_seq_id", "pdbx_pdb_ins_code"};

/* A loop wider than this is not an atom_site loop anyone writes. */
#define VBI_CIF_MAX_COLUMNS 256

static const char atom_site[] = "_atom_site.";

static int prefix_ci(const char *s, size_t n, const char *prefix)
{
    size_t k = strlen(prefix);
    if (n < k)
        return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)s[i]) != prefix[i])
            return 0;
    return 1;
}

static int equal_ci(const char *s, size_t n, const char *w)
{
    return n == strlen(w) && prefix_ci(s, n, w);
}

/* '.' (inapplicable) and '?' (unknown) are CIF's null values. */
static int is_null(const vbi_cif_token *t)
{
    return t->len == 1 && (t->text[0] == '.' || t->text[0] == '?');
}

static const vbi_cif_token *cell(const vbi_cif_token *row, const int *col, int which)
{
    return col[which] >= 0 && !is_null(&row[col[which]]) ? &row[col[which]] : NULL;
}

/* The first present of two alternative items. */
static const vbi_cif_token *cell2(const vbi_cif_token *row, const int *col, int a, int b)
{
    const vbi_cif_token *t = cell(row, col, a);
    return t ? t : cell(row, col, b);
}

/* An integer cell; 0 when absent, null or not a plain integer. */
static int32_t int_cell(const vbi_cif_token *t)
{
    int32_t v = 0;
    if (t)
        vbi_parse_int(t->text, t->len, &v);
    return v;
}

static void text_cell(char *dst, size_t cap, const vbi_cif_token *t, int *truncated)
{
    dst[0] = '\0';
    if (t && vbi_copy_field(dst, cap, t->text, t->len))
        *truncated = 1;
}

typedef struct {
    vb_ctx *ctx;
    const char *name;
    const vb_read_options *opt;
    vbi_builder b;
    vbi_models models;
    vbi_altloc alt;
    vbi_dropped *dr;
    int have_model;
    int32_t last_model;
    int truncated;
    long truncated_line;
    char (*asym)[8];  /* --assembly: label_asym_id of each atom read */
    size_t asym_cap;
} cif_reader;

static const char *const axis_names[3] = {"Cartn_x", "Cartn_y", "Cartn_z"};

/* Records the label_asym_id of the atom just pushed (assemblies name
 * chains by it). */
static int note_asym(cif_reader *r, const vbi_cif_token *t)
{
    size_t n = r->b.set->n;
    if (VB_ARRAY_FIT(r->asym, r->asym_cap, n, 1024) != VB_OK)
        return vb_error(r->ctx, VB_ENOMEM, r->name, 0, "out of memory");
    int trunc = 0;
    text_cell(r->asym[n - 1], sizeof r->asym[n - 1], t, &trunc);
    return VB_OK;
}

static int take_row(cif_reader *r, const vbi_cif_token *row, const int *col)
{
    long line = row[0].line;
    const vbi_cif_token *model = cell(row, col, COL_MODEL);
    if (model) {
        int32_t serial = int_cell(model);
        if (!r->have_model || serial != r->last_model) {
            if (r->have_model)
                vbi_models_end(&r->models);
            vbi_models_begin(&r->models, serial, r->dr);
            r->have_model = 1;
            r->last_model = serial;
        }
    }
    if (!vbi_models_takes(&r->models)) {
        r->dr->other_models++;
        return VB_OK;
    }
    vb_decimal e[4];
    double d[4];
    for (int a = 0; a < 3; a++) {
        const vbi_cif_token *t = cell(row, col, COL_X + a);
        if (!t)
            return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, row[col[COL_X + a]].line,
                            "%s is missing ('.' or '?')", axis_names[a]);
        int rc = vbi_parse_number(r->ctx, r->name, t->line, axis_names[a], t->text, t->len, &e[a],
                                  &d[a]);
        if (rc != VB_OK)
            return rc;
    }
    vb_atom_info info;
    memset(&info, 0, sizeof info);
    int trunc = 0;
    const vbi_cif_token *group = cell(row, col, COL_GROUP);
    info.hetatm = group && equal_ci(group->text, group->len, "hetatm");
    info.serial = int_cell(cell(row, col, COL_ID));
    text_cell(info.name, sizeof info.name, cell2(row, col, COL_AUTH_ATOM, COL_LABEL_ATOM), &trunc);
    text_cell(info.resname, sizeof info.resname, cell2(row, col, COL_AUTH_COMP, COL_LABEL_COMP),
              &trunc);
    text_cell(info.chain, sizeof info.chain, cell2(row, col, COL_AUTH_ASYM, COL_LABEL_ASYM),
              &trunc);
    info.resseq = int_cell(cell2(row, col, COL_AUTH_SEQ, COL_LABEL_SEQ));
    const vbi_cif_token *t = cell(row, col, COL_ICODE);
    info.icode = t && t->len == 1 ? t->text[0] : ' ';
    t = cell(row, col, COL_ALT);
    info.altloc = t && t->len == 1 ? t->text[0] : ' ';
    t = cell(row, col, COL_TYPE);
    char el[4] = "";
    int how = VBI_INFER_NONE;
    if (t && !vbi_copy_field(el, sizeof el, t->text, t->len)) {
        for (size_t c = 0; el[c]; c++)
            info.element[c] = (char)toupper((unsigned char)el[c]);
    } else {
        how = vbi_infer_element(NULL, info.name, info.resname, VBI_LAYOUT_UNKNOWN, info.element);
    }
    if (trunc && !r->truncated) {
        r->truncated = 1;
        r->truncated_line = line;
    }
    int drop = vbi_atom_dropped(r->opt, &r->alt, &info, r->dr);
    if (drop < 0)
        return vb_error(r->ctx, VB_ENOMEM, r->name, line, "out of memory (alternate locations)");
    if (drop)
        return VB_OK;
    if (how != VBI_INFER_NONE) {
        int rc = vbi_element_inferred(r->ctx, r->opt, r->name, line, &info, how, r->dr);
        if (rc != VB_OK)
            return rc;
    }
    int rc = vbi_radius_for(r->ctx, r->opt, r->name, line, &info, &e[3], &d[3],
                            &r->dr->unknown_elements);
    if (rc == VB_OK)
        rc = vbi_builder_push(&r->b, e, d, &info, line);
    if (rc == VB_OK && r->opt->assembly > 0)
        rc = note_asym(r, cell(row, col, COL_LABEL_ASYM));
    return rc;
}

/* Reads the loop whose first tag is *t (an _atom_site item); on return *t is
 * the token after the loop. */
static int read_loop(cif_reader *r, vbi_cif *c, vbi_cif_token *t)
{
    int col[COL_COUNT];
    for (int k = 0; k < COL_COUNT; k++)
        col[k] = -1;
    int ncols = 0;
    while (t->kind == VBI_CIF_TAG) {
        if (ncols == VBI_CIF_MAX_COLUMNS)
            return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, t->line,
                            "_atom_site loop with more than %d items", VBI_CIF_MAX_COLUMNS);
        if (prefix_ci(t->text, t->len, atom_site)) {
            const char *item = t->text + strlen(atom_site);
            size_t n = t->len - strlen(atom_site);
            for (int k = 0; k < COL_COUNT; k++)
                if (equal_ci(item, n, item_names[k]) && col[k] < 0)
                    col[k] = ncols;
        }
        ncols++;
        vbi_cif_next(c, t);
    }
    for (int a = 0; a < 3; a++)
        if (col[COL_X + a] < 0)
            return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, t->line,
                            "_atom_site loop has no %s item", axis_names[a]);
    vbi_cif_token *row = malloc((size_t)ncols * sizeof *row);
    if (!row)
        return vb_error(r->ctx, VB_ENOMEM, r->name, 0, "out of memory");
    int rc = VB_OK, k = 0;
    while (rc == VB_OK && t->kind == VBI_CIF_VALUE) {
        row[k++] = *t;
        if (k == ncols) {
            rc = take_row(r, row, col);
            k = 0;
        }
        vbi_cif_next(c, t);
    }
    free(row);
    if (rc != VB_OK)
        return rc;
    if (t->kind == VBI_CIF_ERROR)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, t->line,
                        "unterminated quoted value or text field");
    if (k != 0)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, t->line,
                        "_atom_site loop ends inside a row (%d of %d values)", k, ncols);
    return VB_OK;
}

int vbi_mmcif_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                    const vb_read_options *opt, int ordinal, vbi_dropped *dr, int *serial,
                    vb_sphere_set **out)
{
    *out = NULL;
    cif_reader r;
    memset(&r, 0, sizeof r);
    r.ctx = ctx;
    r.name = name;
    r.opt = opt;
    r.dr = dr;
    vbi_models_init(&r.models, ordinal > 0 ? ordinal : opt->model);
    r.models.by_ordinal = ordinal > 0;
    vbi_altloc_init(&r.alt);
    int rc = vbi_builder_init(&r.b, ctx, name, opt->max_spheres, 1);
    if (rc != VB_OK)
        return rc;
    vbi_cif c;
    vbi_cif_init(&c, buf, len);
    vbi_cif_token t;
    int found = 0;
    vbi_cif_next(&c, &t);
    while (rc == VB_OK && t.kind != VBI_CIF_END && t.kind != VBI_CIF_ERROR) {
        if (t.kind != VBI_CIF_LOOP) {
            vbi_cif_next(&c, &t);
            continue;
        }
        vbi_cif_next(&c, &t);
        if (t.kind != VBI_CIF_TAG || !prefix_ci(t.text, t.len, atom_site))
            continue;
        if (found) {
            /* A second block's atoms are another structure, not more of this one. */
            vb_warn(ctx, VB_W_CIF_BLOCK_IGNORED, name, t.line, "a further _atom_site loop (another data block) ignored");
            break;
        }
        found = 1;
        rc = read_loop(&r, &c, &t);
    }
    if (rc == VB_OK && t.kind == VBI_CIF_ERROR)
        rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, t.line,
                      "unterminated quoted value or text field");
    if (rc == VB_OK && !found)
        rc = vb_error(ctx, VB_EINPUT_EMPTY, name, 0, "no _atom_site loop in the mmCIF input");
    vbi_altloc_free(&r.alt);
    rc = vbi_builder_close(&r.b, &r.models, rc, out);
    if (rc == VB_OK && opt->assembly > 0 && (*out)->n > 0)
        rc = vbi_assembly_build(ctx, name, buf, len, opt->assembly,
                                (const char(*)[8])r.asym, opt->max_spheres ? opt->max_spheres
                                                                           : VBI_DEFAULT_MAX_SPHERES, out);
    free(r.asym);
    if (rc != VB_OK) {
        vb_spheres_free(*out);
        *out = NULL;
        return rc;
    }
    if (r.truncated)
        vb_warn(ctx, VB_W_NAMES_TRUNCATED, name, r.truncated_line,
                "atom, residue or chain names longer than 7 characters were truncated");
    if (serial)
        *serial = r.models.taken_serial;
    return VB_OK;
}

int vbi_read_mmcif(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                   const vb_read_options *opt, vb_sphere_set **out)
{
    vbi_dropped dr;
    memset(&dr, 0, sizeof dr);
    int rc = vbi_mmcif_parse(ctx, name, buf, len, opt, 0, &dr, NULL, out);
    if (rc == VB_OK)
        vbi_report_dropped(ctx, name, &dr);
    return rc;
}
