/* PSF reader (CHARMM, NAMD, X-PLOR protein structure files): the !NATOM
 * section only - atom number, segment, residue number, residue name, atom
 * name, type, charge, mass, whitespace-separated as every PSF variant
 * (standard, EXT, XPLOR with named types) writes them. A PSF has no
 * coordinates: it is the topology of a trajectory (DCD, XTC, TRR).
 *
 * Elements come from the masses: a mass within 0.1 u of an element's
 * standard atomic weight is that element (counted in W717; it is read, not
 * guessed, so --strict-elements accepts it). A mass that matches none
 * (hydrogen mass repartitioning, Drude particles, lone pairs) leaves the
 * atom name to infer from (W714, refused by --strict-elements). */
#include "vbi_input.h"
#include "vb_diag.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *element;
    double mass;
} weights[] = {
    {"H", 1.008},    {"D", 2.014},    {"LI", 6.94},   {"B", 10.81},    {"C", 12.011},
    {"N", 14.007},   {"O", 15.999},   {"F", 18.998},  {"NA", 22.990},  {"MG", 24.305},
    {"AL", 26.982},  {"SI", 28.085},  {"P", 30.974},  {"S", 32.06},    {"CL", 35.45},
    {"K", 39.098},   {"AR", 39.948},  {"CA", 40.078}, {"MN", 54.938},  {"FE", 55.845},
    {"CO", 58.933},  {"NI", 58.693},  {"CU", 63.546}, {"ZN", 65.38},   {"SE", 78.971},
    {"BR", 79.904},  {"RB", 85.468},  {"SR", 87.62},  {"CD", 112.414}, {"I", 126.904},
    {"CS", 132.905}, {"BA", 137.327},
};

/* The element whose standard weight is within 0.1 u of `mass`, or NULL. */
static const char *element_of_mass(double mass)
{
    for (size_t k = 0; k < sizeof weights / sizeof weights[0]; k++)
        if (fabs(mass - weights[k].mass) <= 0.1)
            return weights[k].element;
    return NULL;
}

/* Finds "N !NATOM" and returns N, with *it on that line; -1 when absent. */
static long find_natom(vbi_lines *it)
{
    const char *line, *tok, *p;
    size_t n, k;
    while (vbi_lines_next(it, &line, &n)) {
        p = line;
        k = vbi_token(&p, line + n, &tok);
        const char *tag = memchr(line, '!', n);
        if (!tag || (size_t)(line + n - tag) < 6 || memcmp(tag, "!NATOM", 6) != 0)
            continue;
        int32_t count;
        if (k == 0 || vbi_parse_int(tok, k, &count) != 0 || count < 0)
            return -2;
        return count;
    }
    return -1;
}

int vbi_read_psf(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                 const vb_read_options *opt, vb_sphere_set **out)
{
    *out = NULL;
    if (!vbi_is_psf(buf, len))
        return vb_error(ctx, VB_EINPUT_FORMAT, name, 0, "not a PSF file (no 'PSF' first)");
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    long natom = find_natom(&it);
    if (natom < 0)
        return vb_error(ctx, natom == -1 ? VB_EINPUT_EMPTY : VB_EINPUT_MALFORMED, name,
                        natom == -1 ? 0 : it.lineno,
                        natom == -1 ? "PSF without a !NATOM section" : "PSF atom count is not a number");
    vbi_builder b;
    int rc = vbi_builder_init(&b, ctx, name, opt->max_spheres, 1);
    if (rc != VB_OK)
        return rc;
    vbi_dropped dr;
    memset(&dr, 0, sizeof dr);
    size_t from_mass = 0;
    int truncated = 0;
    long truncated_line = 0;
    for (long i = 0; i < natom && rc == VB_OK; i++) {
        const char *line;
        size_t n;
        if (!vbi_lines_next(&it, &line, &n)) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                          "PSF ends after %ld of its %ld atoms", i, natom);
            break;
        }
        const char *tok[9], *p = line;
        size_t tl[9], k;
        int nt = 0;
        while (nt < 9 && (k = vbi_token(&p, line + n, &tok[nt])) > 0)
            tl[nt++] = k;
        if (nt < 8) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                          "PSF atom line needs 8 fields (id segment resid resname name type "
                          "charge mass), has %d", nt);
            break;
        }
        vb_atom_info info;
        memset(&info, 0, sizeof info);
        info.altloc = info.icode = ' ';
        vbi_parse_int(tok[0], tl[0], &info.serial);
        truncated |= vbi_copy_field(info.chain, sizeof info.chain, tok[1], tl[1]);
        vbi_copy_field(info.segid, sizeof info.segid, tok[1], tl[1]);
        /* A residue number may carry an insertion code ("27A"). */
        size_t digits = 0;
        while (digits < tl[2] && (tok[2][digits] == '-' || (tok[2][digits] >= '0' && tok[2][digits] <= '9')))
            digits++;
        vbi_parse_int(tok[2], digits, &info.resseq);
        if (digits + 1 == tl[2])
            info.icode = tok[2][digits];
        truncated |= vbi_copy_field(info.resname, sizeof info.resname, tok[3], tl[3]);
        truncated |= vbi_copy_field(info.name, sizeof info.name, tok[4], tl[4]);
        if (truncated && !truncated_line)
            truncated_line = it.lineno;
        vb_decimal em;
        double mass;
        if ((rc = vbi_parse_number(ctx, name, it.lineno, "mass", tok[7], tl[7], &em, &mass)) != VB_OK)
            break;
        const char *el = element_of_mass(mass);
        int how = VBI_INFER_NONE;
        if (el) {
            strcpy(info.element, el);
            from_mass++;
        } else {
            how = vbi_infer_element(NULL, info.name, info.resname, VBI_LAYOUT_UNKNOWN, info.element);
        }
        if (how != VBI_INFER_NONE &&
            (rc = vbi_element_inferred(ctx, opt, name, it.lineno, &info, how, &dr)) != VB_OK)
            break;
        /* Every atom of the topology is kept: the trajectory has them all,
         * and the frame source selects (water, hydrogens) afterwards. */
        vb_decimal e[4] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
        double d[4] = {0, 0, 0, 0};
        rc = vbi_radius_for(ctx, opt, name, it.lineno, &info, &e[3], &d[3],
                            &dr.unknown_elements);
        if (rc == VB_OK)
            rc = vbi_builder_push(&b, e, d, &info, it.lineno);
    }
    if (rc != VB_OK) {
        vbi_builder_discard(&b);
        return rc;
    }
    vbi_builder_finish(&b, 1, out);
    if (from_mass)
        vb_warn(ctx, VB_W_ELEMENT_FROM_MASS, name, 0,
                "%zu of %ld atoms: element from the mass (PSF has no element field)", from_mass,
                natom);
    if (truncated)
        vb_warn(ctx, VB_W_NAMES_TRUNCATED, name, truncated_line,
                "atom, residue or segment names longer than 7 characters were truncated");
    vbi_report_dropped(ctx, name, &dr);
    return VB_OK;
}
