/* Element radii for PDB and mmCIF input (PQR and XYZR carry their own).
 *
 * Built-in values are van der Waals radii in Angstrom: Bondi (1964) for
 * H C N O F P S Cl Br I Se Na Mg K and the noble gases, Mantina et al. (2009)
 * for Ca, B, Al; Cu 1.40 and Zn 1.39 are Bondi's, while Fe, Mn and Co have no
 * Bondi value and get 1.40 like their neighbours (a convention: metal ions in
 * proteins are far smaller than any vdW radius, so any such value is rough).
 * Deuterium takes hydrogen's radius. Unknown elements get 1.70 (carbon) with
 * a warning, or are refused in strict mode.
 *
 * A radius file is "ELEMENT RADIUS" per line, or HOLE's format (its
 * rad/simple.rad, bondi.rad, amberuni.rad: "VDWR ATOM RES RADIUS" with '?'
 * wildcards, "BOND" and "remark" lines). HOLE's rows are matched as HOLE
 * matches them (its tsatr.f, LMATCH): the atom name blank-padded to 4
 * characters against the row's 4-character atom pattern, the residue name
 * padded to 3 against its residue pattern, '?' matching any character,
 * case ignored, the first matching row in the file winning ("put specific
 * records before general", as HOLE's files say). So "VDWR CA   GLY 1.925"
 * is glycine's C-alpha, "VDWR C??? ??? 1.85" every atom whose name starts
 * with C. Rows are tried in file order, "ELEMENT RADIUS" rows by element;
 * an atom no row matches gets the built-in radius of its element (HOLE
 * would stop). Rows of radius 0 (AMBER's lone pairs "LP??") are skipped:
 * a sphere needs a radius. */
#include "vb_array.h"
#include "vbi_input.h"
#include "vb_diag.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct {
    char element[4]; /* an "ELEMENT RADIUS" row; empty for a HOLE row */
    char atom[5];    /* a HOLE row: atom pattern, blank-padded, upper case */
    char res[4];     /* and residue pattern */
    vb_decimal e;
    double d;
} radius_row;

struct vb_radii_table {
    size_t n;
    radius_row *rows;
};

static const struct {
    const char *element, *radius;
} builtin[] = {
    {"H", "1.20"},  {"D", "1.20"},  {"C", "1.70"},  {"N", "1.55"},  {"O", "1.52"},
    {"S", "1.80"},  {"P", "1.80"},  {"F", "1.47"},  {"CL", "1.75"}, {"BR", "1.85"},
    {"I", "1.98"},  {"SE", "1.90"}, {"NA", "2.27"}, {"MG", "1.73"}, {"K", "2.75"},
    {"CA", "2.31"}, {"FE", "1.40"}, {"ZN", "1.39"}, {"CU", "1.40"}, {"MN", "1.40"},
    {"CO", "1.40"}, {"NI", "1.63"}, {"B", "1.92"},  {"AL", "1.84"}, {"SI", "2.10"},
    {"AS", "1.85"}, {"HE", "1.40"}, {"NE", "1.54"}, {"AR", "1.88"}, {"KR", "2.02"},
    {"XE", "2.16"}, {"LI", "1.82"},
};

/* Default for an element the table lacks: carbon's radius. */
static const char default_radius[] = "1.70";

static int builtin_lookup(const char *el, vb_decimal *e, double *d)
{
    for (size_t k = 0; k < sizeof builtin / sizeof builtin[0]; k++)
        if (strcmp(builtin[k].element, el) == 0)
            return vb_decimal_parse(builtin[k].radius, strlen(builtin[k].radius), e, d) == VB_OK;
    return 0;
}

/* HOLE's LMATCH: the first n characters of pattern p and of the text t
 * (blank-padded, NUL-ended within n), '?' any character, case ignored. */
static int hole_match(const char *p, const char *t, size_t n)
{
    int ended = 0;
    for (size_t i = 0; i < n; i++) {
        char c = ended || !t[i] ? ' ' : t[i];
        ended |= !t[i];
        if (p[i] != '?' && toupper((unsigned char)p[i]) != toupper((unsigned char)c))
            return 0;
    }
    return 1;
}

int vbi_radius_for(vb_ctx *ctx, const vb_read_options *opt, const char *name, long line,
                   const vb_atom_info *info, vb_decimal *e, double *d, size_t *unknown)
{
    const char *element = info->element;
    if (opt->radii)
        for (size_t k = 0; k < opt->radii->n; k++) {
            const radius_row *row = &opt->radii->rows[k];
            int hit = row->atom[0] ? hole_match(row->atom, info->name, 4) &&
                                         hole_match(row->res, info->resname, 3)
                                   : strcmp(row->element, element) == 0;
            if (hit) {
                *e = row->e;
                *d = row->d;
                return VB_OK;
            }
        }
    if (builtin_lookup(element, e, d))
        return VB_OK;
    if (opt->strict_elements)
        return vb_error(ctx, VB_EINPUT_ELEMENT, name, line,
                        "unknown element '%s' (no radius; --radii FILE supplies one)", element);
    if ((*unknown)++ == 0)
        vb_warn(ctx, VB_W_ELEMENT_UNKNOWN, name, line, "unknown element '%s': radius %s used", element,
                default_radius);
    vb_decimal_parse(default_radius, strlen(default_radius), e, d);
    return VB_OK;
}

void vb_radii_free(vb_radii_table *t)
{
    if (!t)
        return;
    free(t->rows);
    free(t);
}

/* HOLE's keywords: 1 a remark, 2 BOND, 3 VDWR, 0 none (case-insensitive). */
static int hole_keyword(const char *tok, size_t k)
{
    if (k >= 6 && strncasecmp(tok, "remark", 6) == 0)
        return 1;
    if (k == 4 && strncasecmp(tok, "bond", 4) == 0)
        return 2;
    if (k == 4 && strncasecmp(tok, "vdwr", 4) == 0)
        return 3;
    return 0;
}

int vb_radii_load(vb_ctx *ctx, const char *path, vb_radii_table **out)
{
    *out = NULL;
    char *buf;
    size_t len;
    int rc = vbi_slurp(ctx, path, &buf, &len);
    if (rc != VB_OK)
        return rc;
    vb_radii_table *t = calloc(1, sizeof *t);
    size_t cap = 0;
    if (!t) {
        free(buf);
        return vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
    }
    size_t bom = vbi_bom_length(buf, len);
    rc = vbi_check_nul(ctx, path, buf + bom, len - bom, 1);
    vbi_lines it;
    vbi_lines_init(&it, buf + bom, len - bom, 1);
    const char *line, *tok;
    size_t n, k;
    while (rc == VB_OK && vbi_lines_next(&it, &line, &n)) {
        const char *hash = memchr(line, '#', n);
        const char *end = hash ? hash : line + n, *p = line;
        if ((k = vbi_token(&p, end, &tok)) == 0)
            continue;
        int hole = hole_keyword(tok, k);
        if (hole == 1 || hole == 2) /* a remark, or HOLE's bond radius */
            continue;
        radius_row row;
        memset(&row, 0, sizeof row);
        if (hole == 3) {
            /* VDWR ATOM RES RADIUS: patterns of 4 and 3 characters. */
            const char *atom, *res;
            size_t ka = vbi_token(&p, end, &atom), kr = vbi_token(&p, end, &res);
            if (ka == 0 || ka > 4 || kr == 0 || kr > 3) {
                rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, it.lineno,
                              "expected 'VDWR ATOM RES RADIUS' (patterns of at most 4 and 3 "
                              "characters)");
                break;
            }
            /* A zero radius is no sphere (AMBER's lone pairs, "LP??"). */
            const char *cur = p, *val;
            size_t kv = vbi_token(&cur, end, &val);
            if (kv > 0 && strspn(val, "0.") >= kv)
                continue;
            memset(row.atom, ' ', 4);
            memset(row.res, ' ', 3);
            for (size_t c = 0; c < ka; c++)
                row.atom[c] = (char)toupper((unsigned char)atom[c]);
            for (size_t c = 0; c < kr; c++)
                row.res[c] = (char)toupper((unsigned char)res[c]);
        } else if (k >= sizeof row.element) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, it.lineno,
                          "'%.*s' is not an element symbol", (int)(k > 20 ? 20 : k), tok);
            break;
        }
        for (size_t c = 0; hole != 3 && c < k; c++)
            row.element[c] = (char)toupper((unsigned char)tok[c]);
        if ((k = vbi_token(&p, end, &tok)) == 0) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, it.lineno,
                          "expected 'ELEMENT RADIUS'");
            break;
        }
        rc = vbi_parse_number(ctx, path, it.lineno, "radius", tok, k, &row.e, &row.d);
        if (rc != VB_OK)
            break;
        if (row.e.mant <= 0) {
            rc = vb_error(ctx, VB_EINPUT_RADIUS, path, it.lineno, "radius %.*s is not positive",
                          (int)k, tok);
            break;
        }
        if (vbi_token(&p, end, &tok) != 0) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, it.lineno,
                          "extra text after 'ELEMENT RADIUS'");
            break;
        }
        if (VB_ARRAY_FIT(t->rows, cap, t->n + 1, 32) != VB_OK) {
            rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
            break;
        }
        t->rows[t->n++] = row;
    }
    free(buf);
    if (rc != VB_OK) {
        vb_radii_free(t);
        return rc;
    }
    *out = t;
    return VB_OK;
}

int vbi_atom_keep(vb_ctx *ctx, const vb_read_options *opt, const char *name, long line,
                  const vb_atom_info *info, int how, vbi_dropped *dr, vbi_builder *b,
                  vb_decimal e[4], double d[4])
{
    if (opt->keep_virtual_sites == 2 && vbi_is_virtual_site(info->resname, info->name)) {
        e[3] = (vb_decimal){170, -2}; /* the unknown element's 1.70, never used */
        d[3] = 1.70;
        return vbi_builder_push(b, e, d, info, line);
    }
    int rc = how != VBI_INFER_NONE ? vbi_element_inferred(ctx, opt, name, line, info, how, dr)
                                   : VB_OK;
    if (rc == VB_OK)
        rc = vbi_radius_for(ctx, opt, name, line, info, &e[3], &d[3], &dr->unknown_elements);
    return rc == VB_OK ? vbi_builder_push(b, e, d, info, line) : rc;
}
