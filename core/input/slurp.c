/* A file or stdin into one buffer, with the size limit of the input layer:
 * the first step of every reader and of the radii table. Compressed input
 * arrives decompressed (vbi_open_input). */
#include "vbi_input.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int vbi_slurp(vb_ctx *ctx, const char *path, char **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    FILE *f = vbi_open_input(ctx, path, NULL);
    if (!f)
        return vb_errcode(ctx);
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
        rc = vbi_input_read_error(ctx, path);
    if (f != stdin)
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
