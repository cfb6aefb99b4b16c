/* Entry points of the input layer: the whole input in one buffer
 * (slurp.c), format detection or the forced format, then the reader. */
#include "vbi_input.h"
#include "vb_select.h"

#include <stdlib.h>
#include <string.h>

int vb_format_parse(vb_ctx *ctx, const char *name, vb_format *out)
{
    static const struct {
        const char *name;
        vb_format fmt;
    } names[] = {{"auto", VB_FMT_AUTO}, {"xyzr", VB_FMT_XYZR}, {"balls", VB_FMT_XYZR},
                 {"pdb", VB_FMT_PDB},   {"pqr", VB_FMT_PQR},   {"cif", VB_FMT_MMCIF},
                 {"mmcif", VB_FMT_MMCIF}, {"gro", VB_FMT_GRO}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strcmp(names[k].name, name) == 0) {
            *out = names[k].fmt;
            return VB_OK;
        }
    return vb_error(ctx, VB_EMISUSE, NULL, 0,
                    "unknown format '%s' (auto, xyzr, balls, pdb, pqr, cif, mmcif, gro)", name);
}

int vb_read_options_check(vb_ctx *ctx, const vb_read_options *o)
{
    if (o->model < 0 || o->model > VB_MODEL_MAX)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--model needs a model number >= 1");
    if (o->assembly < 0 || o->assembly > VB_ASSEMBLY_MAX)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "--assembly needs an assembly number >= 1");
    return VB_OK;
}

int vbi_detect_error(vb_ctx *ctx, const char *name, int rc)
{
    if (rc == VB_EINPUT_EMPTY)
        return vb_error(ctx, rc, name, 0, "empty input (no spheres)");
    return vb_error(ctx, rc, name, 0,
                    "format not recognised (not XYZR, PDB, PQR, mmCIF or GRO); --format names it");
}

/* A PDB or PQR parse over the whole buffer, then the one-line reports of
 * what it left out. */
static int read_reported(int (*parse)(vb_ctx *, const char *, const char *, size_t, long,
                                      const vb_read_options *, vbi_dropped *, vb_sphere_set **),
                         vb_ctx *ctx, const char *name, const char *buf, size_t len,
                         const vb_read_options *opt, vb_sphere_set **out)
{
    vbi_dropped dr;
    memset(&dr, 0, sizeof dr);
    int rc = parse(ctx, name, buf, len, 1, opt, &dr, out);
    if (rc == VB_OK)
        vbi_report_dropped(ctx, name, &dr);
    return rc;
}

int vb_spheres_read_buffer(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                           const vb_read_options *opt, vb_sphere_set **out)
{
    *out = NULL;
    vb_read_options defaults;
    if (!opt) {
        memset(&defaults, 0, sizeof defaults);
        opt = &defaults;
    }
    if (len > VBI_MAX_FILE_BYTES)
        return vb_error(ctx, VB_EINPUT_TOOLARGE, name, 0, "input is larger than 2 GiB");
    /* Binary trajectories and topologies are known by their first bytes and
     * never parsed as text. */
    int rc0 = vbi_refuse_nonspheres(ctx, name, buf, len);
    if (rc0 != VB_OK)
        return rc0;
    /* A byte-order mark is not text of line 1; lone CRs end lines (read on
     * a copy with '\n' in their place, so every reader sees the same lines);
     * a NUL byte is never text. */
    size_t bom = vbi_bom_length(buf, len);
    buf += bom;
    len -= bom;
    char *copy = NULL;
    if (vbi_has_lone_cr(buf, len)) {
        if (!(copy = malloc(len + 1)))
            return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory reading the input");
        memcpy(copy, buf, len);
        copy[len] = '\0';
        vbi_lone_cr_to_lf(copy, len);
        buf = copy;
    }
    int rc = vbi_check_nul(ctx, name, buf, len, 1);
    vb_format fmt = opt->format;
    if (rc == VB_OK && fmt == VB_FMT_AUTO && (rc = vbi_detect_format(buf, len, &fmt)) != VB_OK)
        rc = vbi_detect_error(ctx, name, rc);
    if (rc == VB_OK && opt->assembly > 0 && fmt != VB_FMT_MMCIF)
        rc = vb_error(ctx, VB_EINPUT_ASSEMBLY, name, 0,
                      "--assembly reads mmCIF biological assemblies; this input is not mmCIF");
    if (rc == VB_OK) {
        switch (fmt) {
        case VB_FMT_XYZR: rc = vbi_read_xyzr(ctx, name, buf, len, opt, out); break;
        case VB_FMT_PDB: rc = read_reported(vbi_pdb_parse, ctx, name, buf, len, opt, out); break;
        case VB_FMT_PQR: rc = read_reported(vbi_pqr_parse, ctx, name, buf, len, opt, out); break;
        case VB_FMT_MMCIF: rc = vbi_read_mmcif(ctx, name, buf, len, opt, out); break;
        case VB_FMT_GRO: rc = vbi_read_gro(ctx, name, buf, len, opt, out); break;
        default:
            rc = vb_error(ctx, VB_EMISUSE, name, 0, "invalid format value %d", (int)fmt);
            break;
        }
    }
    free(copy);
    if (rc == VB_OK && opt->select) {
        vb_sphere_set *t;
        rc = vb_spheres_select(ctx, *out, opt->select, &t);
        vb_spheres_free(*out);
        *out = rc == VB_OK ? t : NULL;
    }
    return rc;
}

int vb_spheres_read_file(vb_ctx *ctx, const char *path, const vb_read_options *opt,
                         vb_sphere_set **out)
{
    *out = NULL;
    char *buf;
    size_t len;
    int rc = vbi_slurp(ctx, path, &buf, &len);
    if (rc != VB_OK)
        return rc;
    rc = vb_spheres_read_buffer(ctx, path, buf, len, opt, out);
    free(buf);
    return rc;
}
