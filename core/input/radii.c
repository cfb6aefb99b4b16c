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
 * rad/simple.rad, bondi.rad: "VDWR ATOM RES RADIUS" with '?' wildcards,
 * "BOND" and "remark" lines): a VDWR row for every residue ("???") whose
 * atom pattern is letters then wildcards ("C???", "FE??") is the radius of
 * that element, the first such row winning as in HOLE; rows for particular
 * atom or residue names are counted and left out (W736). */
#include "vb_array.h"
#include "vbi_input.h"
#include "vb_diag.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct {
    char element[4];
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

int vbi_radius_for(vb_ctx *ctx, const vb_read_options *opt, const char *name, long line,
                   const char *element, vb_decimal *e, double *d, size_t *unknown)
{
    if (opt->radii)
        for (size_t k = 0; k < opt->radii->n; k++)
            if (strcmp(opt->radii->rows[k].element, element) == 0) {
                *e = opt->radii->rows[k].e;
                *d = opt->radii->rows[k].d;
                return VB_OK;
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
    size_t cap = 0, particular = 0;
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
        if (hole == 3) {
            /* VDWR ATOM RES RADIUS: the element's row, or a particular one. */
            const char *atom, *res;
            size_t ka = vbi_token(&p, end, &atom), kr = vbi_token(&p, end, &res);
            size_t letters = 0;
            while (letters < ka && isalpha((unsigned char)atom[letters]))
                letters++;
            int general = ka == 4 && kr == 3 && memcmp(res, "???", 3) == 0 && letters > 0 &&
                          letters <= 2 && strspn(atom + letters, "?") == ka - letters;
            /* A zero radius names no element (AMBER's lone pairs, "LP??"). */
            const char *cur = p, *val;
            size_t kv = vbi_token(&cur, end, &val);
            int zero = kv > 0 && strspn(val, "0.") >= kv;
            if (!general || zero) {
                particular++;
                continue;
            }
            tok = atom;
            k = letters;
        }
        radius_row row;
        memset(&row, 0, sizeof row);
        if (k >= sizeof row.element) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, it.lineno,
                          "'%.*s' is not an element symbol", (int)(k > 20 ? 20 : k), tok);
            break;
        }
        for (size_t c = 0; c < k; c++)
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
    if (rc == VB_OK && particular)
        vb_warn(ctx, VB_W_RADII_PARTICULAR, path, 0,
                "%zu HOLE radius rows for particular atom or residue names left out: radii by "
                "element only", particular);
    if (rc != VB_OK) {
        vb_radii_free(t);
        return rc;
    }
    *out = t;
    return VB_OK;
}
