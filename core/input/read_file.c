/* Entry points of the input layer: file or stdin into one buffer (with a
 * size limit), format detection or the forced format, then the reader. */
#include "vbi_input.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int vb_format_parse(vb_ctx *ctx, const char *name, vb_format *out)
{
    static const struct {
        const char *name;
        vb_format fmt;
    } names[] = {{"auto", VB_FMT_AUTO}, {"xyzr", VB_FMT_XYZR}, {"balls", VB_FMT_XYZR},
                 {"pdb", VB_FMT_PDB},   {"pqr", VB_FMT_PQR},   {"cif", VB_FMT_MMCIF},
                 {"mmcif", VB_FMT_MMCIF}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strcmp(names[k].name, name) == 0) {
            *out = names[k].fmt;
            return VB_OK;
        }
    return vb_error(ctx, VB_EMISUSE, NULL, 0,
                    "unknown format '%s' (auto, xyzr, balls, pdb, pqr, cif, mmcif)", name);
}

int vbi_detect_error(vb_ctx *ctx, const char *name, int rc)
{
    if (rc == VB_EINPUT_EMPTY)
        return vb_error(ctx, rc, name, 0, "empty input (no spheres)");
    return vb_error(ctx, rc, name, 0,
                    "format not recognised (not XYZR, PDB, PQR or mmCIF); --format names it");
}

int vbi_slurp(vb_ctx *ctx, const char *path, char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    int is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f)
        return vb_error(ctx, VB_EIO, path, 0, "cannot open: %s", strerror(errno));
    /* One byte past the limit is enough to know the input is too large. */
    size_t cap = 1 << 16, n = 0;
    char *b = malloc(cap + 1);
    int rc = VB_OK;
    while (b && rc == VB_OK) {
        size_t got = fread(b + n, 1, cap - n, f);
        n += got;
        if (n > VBI_MAX_FILE_BYTES)
            rc = vb_error(ctx, VB_EINPUT_TOOLARGE, path, 0, "input is larger than 2 GiB");
        else if (got == 0)
            break;
        else if (n == cap) {
            size_t ncap = cap > VBI_MAX_FILE_BYTES / 2 ? VBI_MAX_FILE_BYTES + 1 : 2 * cap;
            char *nb = realloc(b, ncap + 1);
            if (!nb) {
                free(b);
                b = NULL;
            } else {
                b = nb;
                cap = ncap;
            }
        }
    }
    if (rc == VB_OK && !b)
        rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory reading the input");
    else if (rc == VB_OK && ferror(f))
        rc = vb_error(ctx, VB_EIO, path, 0, "read error: %s", strerror(errno));
    if (!is_stdin)
        fclose(f);
    if (rc != VB_OK) {
        free(b);
        return rc;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return VB_OK;
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
    vb_format fmt = opt->format;
    if (fmt == VB_FMT_AUTO) {
        int rc = vbi_detect_format(buf, len, &fmt);
        if (rc != VB_OK)
            return vbi_detect_error(ctx, name, rc);
    }
    switch (fmt) {
    case VB_FMT_XYZR: return vbi_read_xyzr(ctx, name, buf, len, opt, out);
    case VB_FMT_PDB: return read_reported(vbi_pdb_parse, ctx, name, buf, len, opt, out);
    case VB_FMT_PQR: return read_reported(vbi_pqr_parse, ctx, name, buf, len, opt, out);
    case VB_FMT_MMCIF: return vbi_read_mmcif(ctx, name, buf, len, opt, out);
    default: return vb_error(ctx, VB_EMISUSE, name, 0, "invalid format value %d", (int)fmt);
    }
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
