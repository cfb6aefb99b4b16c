/* PQR reader: whitespace-separated ATOM/HETATM records
 * "ATOM serial name resname [chain] resseq x y z charge radius". The radius
 * is the last column and the charge the one before it; counting from the end
 * keeps optional chain and insertion columns from shifting them. */
#include "vbi_input.h"

#include <ctype.h>
#include <string.h>

/* Most tokens a PQR record may have (record .. radius, with chain, icode
 * and an element column some writers add). */
#define VBI_PQR_MAX_TOKENS 13

static int record_is(const char *tok, size_t k, const char *rec)
{
    return k == strlen(rec) && memcmp(tok, rec, k) == 0;
}

/* One or two letters: an element symbol, never a number. */
static int is_element_token(const char *t, size_t k)
{
    return (k == 1 || k == 2) && isalpha((unsigned char)t[0]) &&
           (k == 1 || isalpha((unsigned char)t[1]));
}

static const char *const value_names[4] = {"x coordinate", "y coordinate", "z coordinate",
                                           "radius"};

int vbi_pqr_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out)
{
    vbi_builder b;
    vbi_atom_scan scan;
    int rc = vbi_atom_parse_begin(ctx, name, opt, &b, &scan, out);
    if (rc != VB_OK)
        return rc;
    const int zero_policy = vbi_zero_radius_policy(opt, VB_FMT_PQR);
    vbi_lines it;
    vbi_lines_init(&it, buf, len, first_line);
    const char *line;
    size_t n;
    while (rc == VB_OK && vbi_lines_next(&it, &line, &n)) {
        const char *tok[VBI_PQR_MAX_TOKENS + 1], *p = line;
        size_t tl[VBI_PQR_MAX_TOKENS + 1], k;
        int nt = 0;
        while (nt <= VBI_PQR_MAX_TOKENS && (k = vbi_token(&p, line + n, &tok[nt])) > 0)
            tl[nt++] = k;
        if (nt == 0)
            continue;
        vbi_record rec = vbi_record_kind(record_is, tok[0], tl[0]);
        int32_t serial = 0;
        if (rec == VBI_REC_MODEL && nt > 1)
            vbi_parse_int(tok[1], tl[1], &serial);
        if (!vbi_atom_scan_takes(&scan, rec, serial, it.lineno, dr))
            continue;
        if (nt < 10 || nt > VBI_PQR_MAX_TOKENS) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                          "PQR record with %d%s fields (expected 10 to %d: "
                          "ATOM serial name resname [chain] resseq x y z charge radius)",
                          nt, nt > VBI_PQR_MAX_TOKENS ? " or more" : "", VBI_PQR_MAX_TOKENS);
            break;
        }
        /* x y z charge radius are the last five tokens, unless a writer
         * appended an element symbol: then they end one earlier. */
        vb_decimal e[4], charge;
        double d[4], dq;
        int last = nt - 1;
        if (nt > 10 && is_element_token(tok[last], tl[last]))
            last--;
        int first = last - 4;
        for (int a = 0; a < 4 && rc == VB_OK; a++) {
            int t = a < 3 ? first + a : last;
            rc = vbi_parse_number(ctx, name, it.lineno, value_names[a], tok[t], tl[t], &e[a], &d[a]);
        }
        if (rc == VB_OK)
            rc = vbi_parse_number(ctx, name, it.lineno, "charge", tok[last - 1], tl[last - 1],
                                  &charge, &dq);
        if (rc != VB_OK)
            break;
        vb_atom_info info;
        memset(&info, 0, sizeof info);
        info.hetatm = tok[0][0] == 'H';
        info.altloc = info.icode = ' ';
        vbi_parse_int(tok[1], tl[1], &info.serial);
        vbi_copy_field(info.name, sizeof info.name, tok[2], tl[2]);
        vbi_copy_field(info.resname, sizeof info.resname, tok[3], tl[3]);
        /* Between resname and x: resseq, or chain and resseq. */
        if (first - 4 >= 2)
            vbi_copy_field(info.chain, sizeof info.chain, tok[4], tl[4]);
        vbi_parse_int(tok[first - 1], tl[first - 1], &info.resseq);
        /* PQR has no element column, and needs none for its radii: the
         * inferred element only says hydrogen or not (--no-hydrogens), so
         * it is not counted as an inference. */
        vbi_infer_element(NULL, info.name, info.resname, VBI_LAYOUT_UNKNOWN, info.element);
        if (vbi_atom_dropped(opt, NULL, &info, dr) || vbi_zero_radius_skip(zero_policy, e[3], dr))
            continue;
        rc = vbi_builder_push(&b, e, d, &info, it.lineno);
    }
    rc = vbi_atom_parse_end(&b, &scan, dr, rc, out);
    if (rc == VB_OK)
        (*out)->allows_zero_radius = zero_policy == VB_ZERO_RADIUS_POINT;
    return rc;
}
