/* GRO reader (GROMACS coordinates): a title line, the atom count, one fixed
 * column line per atom - residue number (columns 1-5), residue name (6-10),
 * atom name (11-15), atom number (16-20), x y z in nm from column 21 - and
 * the box line. A file may hold several such frames (a trajectory).
 *
 * As GROMACS reads them, the coordinate fields are as wide as the distance
 * between the first two decimal points (8 for the usual %8.3f, wider for
 * files written with more precision). Coordinates become Angstrom exactly:
 * the decimal's exponent moves by one, and the double is the one nearest
 * that decimal. GRO has no element column: elements are inferred from atom
 * and residue names, and counted (W714, W715). */
#include "vbi_input.h"
#include "vb_box.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Width of the coordinate fields of an atom line: the distance between
 * its first two decimal points from column 21; 0 when there is none. */
static size_t field_width(const char *line, size_t n)
{
    if (n < 21)
        return 0;
    const char *p1 = memchr(line + 20, '.', n - 20);
    if (!p1)
        return 0;
    const char *p2 = memchr(p1 + 1, '.', (size_t)(line + n - p1 - 1));
    if (!p2)
        return 0;
    size_t w = (size_t)(p2 - p1);
    return w >= 4 && w <= 40 ? w : 0;
}

int vbi_gro_atom_fits(const char *line, size_t n)
{
    size_t w = field_width(line, n);
    if (w == 0 || n < 20 + 3 * w)
        return 0;
    int32_t v;
    if (vbi_parse_int(line, 5, &v) != 0)
        return 0;
    for (int a = 0; a < 3; a++) {
        char f[48];
        vbi_copy_field(f, sizeof f, line + 20 + (size_t)a * w, w);
        vb_decimal e;
        if (vb_decimal_parse(f, strlen(f), &e, NULL) != VB_OK)
            return 0;
    }
    return 1;
}

int vbi_decimal_times_ten(vb_decimal *e, double *d)
{
    if (e->mant == 0) {
        *d = 0.0;
        return VB_OK;
    }
    e->exp10++;
    *d = vb_decimal_double(*e);
    return VB_OK;
}

static const char *const axis_names[3] = {"x coordinate", "y coordinate", "z coordinate"};

/* One atom line into info, e[0..2] and d[0..2] (Angstrom). */
static int parse_atom(vb_ctx *ctx, const char *name, long lineno, const char *line, size_t n,
                      vb_atom_info *info, vb_decimal e[3], double d[3])
{
    size_t w = field_width(line, n);
    if (w == 0 || n < 20 + 3 * w)
        return vb_error(ctx, VB_EINPUT_MALFORMED, name, lineno,
                        "not a GRO atom line (x, y, z in nm from column 21)");
    memset(info, 0, sizeof *info);
    info->altloc = info->icode = ' ';
    vbi_parse_int(line, 5, &info->resseq);
    vbi_copy_field(info->resname, sizeof info->resname, line + 5, 5);
    vbi_copy_field(info->name, sizeof info->name, line + 10, 5);
    vbi_parse_int(line + 15, 5, &info->serial);
    for (int a = 0; a < 3; a++) {
        char f[48];
        vbi_copy_field(f, sizeof f, line + 20 + (size_t)a * w, w);
        int rc = vbi_parse_number(ctx, name, lineno, axis_names[a], f, strlen(f), &e[a], &d[a]);
        if (rc != VB_OK)
            return rc;
        vbi_decimal_times_ten(&e[a], &d[a]);
    }
    return VB_OK;
}

/* True when a line is a GRO box line: 3 numbers (a rectangular box) or 9
 * (a triclinic one), free format. An atom line never is one: its residue
 * field ("1MET") is not a number. */
static int box_line(const char *line, size_t n)
{
    const char *p = line, *tok;
    size_t k;
    int count = 0;
    while ((k = vbi_token(&p, line + n, &tok)) > 0) {
        vb_decimal e;
        if (++count > 9 || vb_decimal_parse(tok, k, &e, NULL) != VB_OK)
            return 0;
    }
    return count == 3 || count == 9;
}

/* The box of a GRO box line (nm, as Angstrom like the atoms): v1(x)
 * v2(y) v3(z) [v1(y) v1(z) v2(x) v2(z) v3(x) v3(y)]; NULL when the line
 * gives no box (zeros, a flat one). VB_OK or VB_ENOMEM. */
static int gro_box(const char *line, size_t n, vb_box **out)
{
    static const int slot[9] = {0, 4, 8, 1, 2, 3, 5, 6, 7};
    vb_decimal ev[9] = {{0, 0}};
    const char *p = line, *tok;
    size_t k;
    int count = 0;
    double d;
    while (count < 9 && (k = vbi_token(&p, line + n, &tok)) > 0) {
        vb_decimal e;
        if (vb_decimal_parse(tok, k, &e, &d) != VB_OK)
            return VB_OK;
        vbi_decimal_times_ten(&e, &d);
        ev[slot[count++]] = e;
    }
    vb_box b;
    if (!vb_box_try(ev, &b))
        return VB_OK;
    *out = malloc(sizeof **out);
    if (!*out)
        return VB_ENOMEM;
    **out = b;
    return VB_OK;
}

int vbi_gro_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out,
                  size_t *consumed)
{
    *out = NULL;
    *consumed = 0;
    vbi_lines it;
    vbi_lines_init(&it, buf, len, first_line);
    const char *line, *tok;
    size_t n;
    if (!vbi_lines_next(&it, &line, &n))
        return vb_error(ctx, VB_EINPUT_EMPTY, name, 0, "empty GRO input");
    if (!vbi_lines_next(&it, &line, &n))
        return vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno + 1,
                        "GRO title without the atom count line");
    const char *p = line;
    size_t k = vbi_token(&p, line + n, &tok);
    int32_t count = -1;
    /* The count stands alone on its line: "0 0 1 0.25" is not a GRO count
     * (an XYZR file forced to --format gro is malformed, not empty). */
    const char *rest;
    if (k == 0 || vbi_parse_int(tok, k, &count) != 0 || count < 0 || vbi_token(&p, line + n, &rest))
        return vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                        "GRO atom count '%.*s' is not a number >= 0 alone on line 2",
                        (int)(k > 20 ? 20 : k), tok);
    vbi_builder b;
    int rc = vbi_builder_init(&b, ctx, name, opt->max_spheres, 1);
    if (rc != VB_OK)
        return rc;
    vbi_infer_memo *memo = calloc(1, sizeof *memo); /* without it, slower, the same answers */
    for (int32_t i = 0; i < count && rc == VB_OK; i++) {
        if (!vbi_lines_next(&it, &line, &n)) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                          "GRO input ends after %d of its %d atoms", (int)i, (int)count);
            break;
        }
        /* A count above the atoms: the box line comes early (read as an
         * atom it would be one of unknown element). */
        if (box_line(line, n)) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                          "GRO box line after %d atoms, but the atom count on line %ld says %d",
                          (int)i, first_line + 1, (int)count);
            break;
        }
        vb_atom_info info;
        vb_decimal e[4];
        double d[4];
        if ((rc = parse_atom(ctx, name, it.lineno, line, n, &info, e, d)) != VB_OK)
            break;
        int how = vbi_infer_element_memo(memo, NULL, info.name, info.resname,
                                         VBI_LAYOUT_UNKNOWN, info.element);
        if (vbi_atom_dropped(opt, NULL, &info, dr))
            continue;
        rc = vbi_atom_keep(ctx, opt, name, it.lineno, &info, how, dr, &b, e, d);
    }
    free(memo);
    if (rc == VB_OK && !vbi_lines_next(&it, &line, &n))
        rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno + 1,
                      "GRO frame without its box line after %d atoms", (int)count);
    /* A count below the atoms: the line after them is another atom, not
     * the box (reading on would silently leave atoms out). */
    else if (rc == VB_OK && !box_line(line, n))
        rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                      "not a GRO box line (3 or 9 numbers)%s: the atom count on line %ld says %d",
                      vbi_gro_atom_fits(line, n) ? " but an atom line" : "", first_line + 1,
                      (int)count);
    if (rc != VB_OK) {
        vbi_builder_discard(&b);
        return rc;
    }
    vbi_builder_finish(&b, 1, out);
    if (*out && gro_box(line, n, &(*out)->box) != VB_OK) {
        vb_spheres_free(*out);
        *out = NULL;
        return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    }
    *consumed = (size_t)(it.p - buf);
    return VB_OK;
}

/* Skips one frame without parsing its atoms: *atoms gets its count, the
 * return value the bytes it takes (0 when it is not a whole frame). */
static size_t skip_frame(const char *buf, size_t len, size_t *atoms)
{
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line, *tok;
    size_t n;
    int32_t count = -1;
    if (!vbi_lines_next(&it, &line, &n) || !vbi_lines_next(&it, &line, &n))
        return 0;
    const char *p = line;
    size_t k = vbi_token(&p, line + n, &tok);
    const char *rest;
    if (k == 0 || vbi_parse_int(tok, k, &count) != 0 || count < 0 || vbi_token(&p, line + n, &rest))
        return 0;
    for (int32_t i = 0; i <= count; i++)
        if (!vbi_lines_next(&it, &line, &n))
            return 0;
    if (!box_line(line, n))
        return 0;
    *atoms = (size_t)count;
    return (size_t)(it.p - buf);
}

/* Bytes from off to the next non-blank character. */
static size_t skip_blank(const char *buf, size_t len, size_t off)
{
    while (off < len && (buf[off] == ' ' || buf[off] == '\t' || buf[off] == '\r' || buf[off] == '\n'))
        off++;
    return off;
}

int vbi_read_gro(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                 const vb_read_options *opt, vb_sphere_set **out)
{
    *out = NULL;
    vbi_dropped dr;
    memset(&dr, 0, sizeof dr);
    int want = opt->model > 0 ? opt->model : 1, frame = 0;
    long line = 1;
    size_t off = 0;
    int rc = VB_OK;
    /* Frame `want` is read; the others are counted as other models. */
    while (rc == VB_OK && !*out && off < len) {
        size_t used = 0, atoms = 0;
        if (frame + 1 == want) {
            rc = vbi_gro_parse(ctx, name, buf + off, len - off, line, opt, &dr, out, &used);
        } else if ((used = skip_frame(buf + off, len - off, &atoms)) == 0) {
            /* Not a whole frame: parse it, to name what is wrong. */
            vb_sphere_set *s = NULL;
            rc = vbi_gro_parse(ctx, name, buf + off, len - off, line, opt, &dr, &s, &used);
            vb_spheres_free(s);
            if (rc == VB_OK)
                rc = vb_error(ctx, VB_EINTERNAL, name, line, "GRO frame skipped but whole");
        } else {
            dr.other_models += atoms;
            dr.other_model_count++;
        }
        if (rc != VB_OK)
            break;
        frame++;
        for (size_t i = 0; i < used; i++)
            line += buf[off + i] == '\n';
        off = skip_blank(buf, len, off + used);
    }
    /* Frames after the one read are counted, not parsed. */
    while (rc == VB_OK && *out && off < len) {
        size_t atoms = 0, used = skip_frame(buf + off, len - off, &atoms);
        if (used == 0)
            break;
        dr.other_models += atoms;
        dr.other_model_count++;
        off = skip_blank(buf, len, off + used);
    }
    if (rc == VB_OK && !*out)
        rc = vb_error(ctx, VB_EINPUT_MODEL, name, 0, "frame %d is not in the GRO input (%d frames)",
                      want, frame);
    if (rc != VB_OK) {
        vb_spheres_free(*out);
        *out = NULL;
        return rc;
    }
    vbi_report_dropped(ctx, name, &dr);
    return VB_OK;
}
