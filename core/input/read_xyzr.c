/* XYZR reader: "x y z r" per line, '#' comments, and Voronota balls lines
 * "x y z r # serial chain resseq resname name [altloc icode]". */
#include "vbi_input.h"

#include <string.h>

static const char *const axis_names[4] = {"x coordinate", "y coordinate", "z coordinate",
                                          "radius"};

/* Fills `info` from a Voronota annotation; returns 1 when it has that shape. */
static int parse_annotation(const char *p, const char *end, vb_atom_info *info)
{
    const char *tok[7];
    size_t len[7];
    int n = 0;
    size_t k;
    const char *t;
    while (n < 7 && (k = vbi_token(&p, end, &t)) > 0) {
        tok[n] = t;
        len[n++] = k;
    }
    if (n < 5 || vbi_parse_int(tok[0], len[0], &info->serial) != 0 ||
        vbi_parse_int(tok[2], len[2], &info->resseq) != 0)
        return 0;
    /* Voronota writes '.' for an empty chain, altloc or insertion code. */
    if (!(len[1] == 1 && tok[1][0] == '.'))
        vbi_copy_field(info->chain, sizeof info->chain, tok[1], len[1]);
    vbi_copy_field(info->resname, sizeof info->resname, tok[3], len[3]);
    vbi_copy_field(info->name, sizeof info->name, tok[4], len[4]);
    info->altloc = n > 5 && len[5] == 1 && tok[5][0] != '.' ? tok[5][0] : ' ';
    info->icode = n > 6 && len[6] == 1 && tok[6][0] != '.' ? tok[6][0] : ' ';
    return 1;
}

int vbi_read_xyzr(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                  const vb_read_options *opt, vb_sphere_set **out)
{
    /* XYZR is a single model, number 1: another one is absent. */
    vbi_models m;
    vbi_models_init(&m, opt->model);
    int rc = vbi_models_check(ctx, name, &m);
    if (rc != VB_OK)
        return rc;
    vbi_builder b;
    rc = vbi_builder_init(&b, ctx, name, opt->max_spheres, 1);
    if (rc != VB_OK)
        return rc;
    const int zero_policy = vbi_zero_radius_policy(opt, VB_FMT_XYZR);
    vbi_dropped dr;
    memset(&dr, 0, sizeof dr);
    vbi_lines it;
    vbi_lines_init(&it, buf, len, 1);
    const char *line;
    size_t n;
    int annotated = 0;
    while (vbi_lines_next(&it, &line, &n)) {
        const char *hash = memchr(line, '#', n);
        const char *end = hash ? hash : line + n;
        const char *p = line, *tok;
        size_t k;
        vb_decimal e[4];
        double d[4];
        int nt = 0;
        while ((k = vbi_token(&p, end, &tok)) > 0) {
            if (nt == 4) {
                vbi_builder_discard(&b);
                return vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                                "more than 4 numbers (expected 'x y z r')");
            }
            rc = vbi_parse_number(ctx, name, it.lineno, axis_names[nt], tok, k, &e[nt], &d[nt]);
            if (rc != VB_OK) {
                vbi_builder_discard(&b);
                return rc;
            }
            nt++;
        }
        if (nt == 0)
            continue; /* blank or comment line */
        if (nt < 4) {
            vbi_builder_discard(&b);
            return vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                            "%d number%s where 'x y z r' expected", nt, nt == 1 ? "" : "s");
        }
        vb_atom_info info;
        memset(&info, 0, sizeof info);
        info.altloc = info.icode = ' ';
        if (hash && parse_annotation(hash + 1, line + n, &info))
            annotated = 1;
        if (vbi_zero_radius_skip(zero_policy, e[3], &dr))
            continue;
        rc = vbi_builder_push(&b, e, d, &info, it.lineno);
        if (rc != VB_OK) {
            vbi_builder_discard(&b);
            return rc;
        }
    }
    vbi_builder_finish(&b, annotated, out);
    (*out)->allows_zero_radius = zero_policy == VB_ZERO_RADIUS_POINT;
    vbi_report_dropped(ctx, name, &dr);
    return VB_OK;
}
