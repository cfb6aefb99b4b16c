/* Format detection by content. PDB and PQR share the ATOM record; they are
 * told apart by PDB's fixed occupancy and B-factor columns (55-60, 61-66),
 * which PQR's free-format charge and radius do not respect. */
#include "vbi_input.h"

#include <string.h>

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

int vbi_detect_format(const char *buf, size_t len, vb_format *out)
{
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line, *tok;
    size_t n;
    int first = 1, atoms = 0, pdb_votes = 0, pqr_votes = 0;
    while (vbi_lines_next(&it, &line, &n)) {
        const char *p = line;
        size_t k = vbi_token(&p, line + n, &tok);
        if (k == 0 || tok[0] == '#')
            continue;
        if (first) {
            first = 0;
            if ((k >= 5 && memcmp(tok, "data_", 5) == 0) || tok[0] == '_' ||
                (k == 5 && memcmp(tok, "loop_", 5) == 0))
                return *out = VB_FMT_MMCIF, VB_OK;
            /* Records of the other formats start with a letter or '_'; a
             * number first means XYZR, and its reader names what is wrong
             * with the line if anything is. */
            if (strchr("0123456789+-.", tok[0]))
                return *out = VB_FMT_XYZR, VB_OK;
        }
        if (!vbi_pdb_record(line, n, "ATOM") && !vbi_pdb_record(line, n, "HETATM"))
            continue;
        /* Lines that keep PDB's columns vote PDB; lines that break them but
         * read as PQR vote PQR. A PDB file with one broken line stays PDB,
         * so its reader can name the line. */
        if (pdb_columns_fit(line, n))
            pdb_votes++;
        else if (pqr_tokens_fit(line, n))
            pqr_votes++;
        if (++atoms == VBI_DETECT_ATOM_LINES)
            break;
    }
    if (first)
        return VB_EINPUT_EMPTY;
    if (atoms == 0)
        return VB_EINPUT_FORMAT;
    *out = pqr_votes > pdb_votes ? VB_FMT_PQR : VB_FMT_PDB;
    return VB_OK;
}
