/* Format detection by content. PDB and PQR share the ATOM record; they are
 * told apart by PDB's fixed occupancy and B-factor columns (55-60, 61-66),
 * which PQR's free-format charge and radius do not respect. GRO is a title,
 * an atom count and fixed columns. Binary trajectories (XTC, TRR, DCD) are
 * known by their magic numbers and never parsed as text. */
#include "vbi_input.h"

#include <stdint.h>
#include <string.h>

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

int vbi_trajectory_kind(const unsigned char *p, size_t n)
{
    if (n < 8)
        return VBI_TRAJ_NONE;
    uint32_t m = be32(p);
    /* XTC: 1995 (2023 for GROMACS' 64-bit variant), then the atom count. */
    if (m == 1995 || m == 2023)
        return VBI_TRAJ_XTC;
    /* TRR: 1993, then the version string's two lengths (13, 12). */
    if (m == 1993)
        return VBI_TRAJ_TRR;
    /* DCD: a first Fortran record of 84 bytes in either byte order, "CORD". */
    if ((m == 84 || m == 0x54000000u) && memcmp(p + 4, "CORD", 4) == 0)
        return VBI_TRAJ_DCD;
    return VBI_TRAJ_NONE;
}

const char *vbi_trajectory_name(int kind)
{
    return kind == VBI_TRAJ_XTC ? "XTC" : kind == VBI_TRAJ_TRR ? "TRR" : kind == VBI_TRAJ_DCD ? "DCD" : "?";
}

int vbi_is_psf(const char *buf, size_t len)
{
    const char *p = buf, *tok;
    size_t k = vbi_token(&p, buf + len, &tok);
    return k == 3 && memcmp(tok, "PSF", 3) == 0;
}

int vbi_refuse_nonspheres(vb_ctx *ctx, const char *name, const char *buf, size_t len)
{
    int kind = vbi_trajectory_kind((const unsigned char *)buf, len);
    if (kind != VBI_TRAJ_NONE)
        return vb_error(ctx, VB_EINPUT_NOSPHERES, name, 0,
                        "%s trajectories hold coordinates only, no atoms or radii: give this "
                        "one with a topology (vorball channels TOPOLOGY --traj %s)",
                        vbi_trajectory_name(kind), name);
    if (vbi_is_psf(buf, len))
        return vb_error(ctx, VB_EINPUT_NOSPHERES, name, 0,
                        "a PSF topology holds atoms without coordinates: give it with a "
                        "trajectory (vorball channels %s --traj FILE.dcd|.xtc|.trr)",
                        name);
    return VB_OK;
}

int vbi_pdb_header_record(const char *line, size_t n)
{
    static const char *const rec[] = {"HEADER", "TITLE",  "COMPND", "SOURCE", "KEYWDS", "EXPDTA",
                                      "AUTHOR", "REVDAT", "JRNL",   "REMARK", "SEQRES", "HET",
                                      "HETNAM", "FORMUL", "HELIX",  "SHEET",  "CRYST1", "ORIGX1",
                                      "SCALE1", "MODEL",  "ENDMDL", "TER",    "CONECT", "MASTER",
                                      "END",    "DBREF",  "SEQADV", "LINK",   "SITE",   "NUMMDL"};
    for (size_t k = 0; k < sizeof rec / sizeof rec[0]; k++)
        if (vbi_pdb_record(line, n, rec[k]))
            return 1;
    return 0;
}

/* How many ATOM/HETATM lines are looked at to tell PDB from PQR. */
#define VBI_DETECT_ATOM_LINES 50

/* True when columns [from, to] (1-based, inclusive) hold one number or, when
 * blank_ok, nothing. */
static int column_number(const char *line, size_t n, size_t from, size_t to, int blank_ok)
{
    if (n < from)
        return blank_ok;
    size_t end = n < to ? n : to;
    const char *s = line + from - 1;
    size_t k = end - from + 1;
    while (k > 0 && *s == ' ') {
        s++;
        k--;
    }
    while (k > 0 && s[k - 1] == ' ')
        k--;
    if (k == 0)
        return blank_ok;
    vb_decimal e;
    return vb_decimal_parse(s, k, &e, NULL) == VB_OK;
}

static int pdb_columns_fit(const char *line, size_t n)
{
    return n >= 54 && column_number(line, n, 31, 38, 0) && column_number(line, n, 39, 46, 0) &&
           column_number(line, n, 47, 54, 0) && column_number(line, n, 55, 60, 1) &&
           column_number(line, n, 61, 66, 1);
}

/* Ten or more tokens of which the last five are numbers: x y z charge radius. */
static int pqr_tokens_fit(const char *line, size_t n)
{
    const char *p = line, *end = line + n, *tok;
    const char *last[5];
    size_t len[5], k;
    int count = 0;
    while ((k = vbi_token(&p, end, &tok)) > 0) {
        memmove(last, last + 1, 4 * sizeof *last);
        memmove(len, len + 1, 4 * sizeof *len);
        last[4] = tok;
        len[4] = k;
        count++;
    }
    if (count < 10)
        return 0;
    vb_decimal e;
    for (int t = 0; t < 5; t++)
        if (vb_decimal_parse(last[t], len[t], &e, NULL) != VB_OK)
            return 0;
    return 1;
}

/* GRO is told by its first three lines: a title, the atom count alone on
 * line 2, then (unless the count is 0) a line with GRO's atom layout.
 * Returns 1 (GRO), -1 (not GRO) or 0 (needs the next line). */
static int gro_line(vbi_detector *d, const char *line, size_t n)
{
    if (d->lines == 1)
        return 0;
    if (d->lines == 2) {
        const char *p = line, *tok;
        size_t k = vbi_token(&p, line + n, &tok);
        int32_t count;
        if (k == 0 || vbi_parse_int(tok, k, &count) != 0 || count < 0 ||
            vbi_token(&p, line + n, &tok))
            return -1;
        return count == 0 ? 1 : 0;
    }
    return vbi_gro_atom_fits(line, n) ? 1 : -1;
}

/* The other formats, line by line, as one pass over the text: the first
 * record decides mmCIF or XYZR; PDB against PQR is a vote of the first
 * VBI_DETECT_ATOM_LINES atom records. Sets d->other_done when decided. */
static void other_line(vbi_detector *d, const char *line, size_t n)
{
    const char *p = line, *tok;
    size_t k = vbi_token(&p, line + n, &tok);
    if (k == 0 || tok[0] == '#')
        return;
    if (!d->seen) {
        d->seen = 1;
        if ((k >= 5 && memcmp(tok, "data_", 5) == 0) || tok[0] == '_' ||
            (k == 5 && memcmp(tok, "loop_", 5) == 0)) {
            d->other = VB_FMT_MMCIF;
            d->other_done = 1;
            return;
        }
        /* Records of the other formats start with a letter or '_'; a
         * number first means XYZR, and its reader names what is wrong
         * with the line if anything is. */
        if (strchr("0123456789+-.", tok[0])) {
            d->other = VB_FMT_XYZR;
            d->other_done = 1;
            return;
        }
    }
    d->records += vbi_pdb_header_record(line, n);
    if (!vbi_pdb_record(line, n, "ATOM") && !vbi_pdb_record(line, n, "HETATM"))
        return;
    /* Lines that keep PDB's columns vote PDB; lines that break them but
     * read as PQR vote PQR. A PDB file with one broken line stays PDB,
     * so its reader can name the line. */
    if (pdb_columns_fit(line, n))
        d->pdb_votes++;
    else if (pqr_tokens_fit(line, n))
        d->pqr_votes++;
    if (++d->atoms == VBI_DETECT_ATOM_LINES)
        d->other_done = 1;
}

void vbi_detector_init(vbi_detector *d)
{
    memset(d, 0, sizeof *d);
}

int vbi_detector_line(vbi_detector *d, const char *line, size_t n)
{
    d->lines++;
    if (d->gro == 0)
        d->gro = gro_line(d, line, n);
    if (!d->other_done)
        other_line(d, line, n);
    return d->gro == 1 || (d->gro == -1 && d->other_done);
}

int vbi_detector_feed(vbi_detector *d, const char *buf, size_t len)
{
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line;
    size_t n;
    while (vbi_lines_next(&it, &line, &n))
        if (vbi_detector_line(d, line, n))
            return 1;
    return 0;
}

int vbi_detector_result(const vbi_detector *d, vb_format *out)
{
    if (d->gro == 1)
        return *out = VB_FMT_GRO, VB_OK;
    if (d->other == VB_FMT_MMCIF || d->other == VB_FMT_XYZR)
        return *out = d->other, VB_OK;
    if (!d->seen)
        return VB_EINPUT_EMPTY;
    /* PDB records without a single atom are a PDB file with no atoms: its
     * reader says so, naming the file. */
    if (d->atoms == 0 && d->records > 0)
        return *out = VB_FMT_PDB, VB_OK;
    if (d->atoms == 0)
        return VB_EINPUT_FORMAT;
    *out = d->pqr_votes > d->pdb_votes ? VB_FMT_PQR : VB_FMT_PDB;
    return VB_OK;
}

int vbi_detect_format(const char *buf, size_t len, vb_format *out)
{
    vbi_detector d;
    vbi_detector_init(&d);
    vbi_detector_feed(&d, buf, len);
    return vbi_detector_result(&d, out);
}
