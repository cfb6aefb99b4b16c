/* PNG output of label grids through libpng. */
#include "jfa_png.h"

#include "cli_common.h"
#include "vb_diag.h"
#include "vb_output.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* Warns (W783) when the name ends in another image format's extension:
 * the bytes are PNG whatever the name says. */
static void check_extension(vb_ctx *ctx, const char *path)
{
    static const char *const other[] = {".jpg", ".jpeg", ".gif", ".bmp", ".tif", ".tiff",
                                        ".webp", ".ppm", ".svg", ".pdf", ".eps"};
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/'))
        return;
    for (size_t k = 0; k < sizeof other / sizeof other[0]; k++)
        if (strcasecmp(dot, other[k]) == 0) {
            vb_warn(ctx, VB_W_PNG_EXTENSION, path, 0,
                    "named '%s', but --png writes PNG data (name it .png)", dot);
            return;
        }
}

int vb_png_write_rgb(vb_ctx *ctx, const char *path, uint32_t w, uint32_t h, const uint8_t *rgb)
{
    check_extension(ctx, path);
    FILE *f = vb_cli_open_output(ctx, path);
    if (!f)
        return vb_errcode(ctx);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, NULL);
        return vb_cli_finish_output(ctx, f, path,
                                    vb_error(ctx, VB_ENOMEM, path, 0, "libpng: out of memory"));
    }
    /* libpng reports write errors by longjmp. */
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return vb_cli_finish_output(ctx, f, path,
                                    vb_error(ctx, VB_EIO, path, 0, "PNG write failed"));
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (uint32_t y = 0; y < h; y++)
        png_write_row(png, (png_const_bytep)(rgb + (size_t)y * w * 3));
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return vb_cli_close_output(ctx, f, path);
}

/* A bright, well-spread colour per label (integer hash). */
static void colour(uint32_t label, uint8_t out[3])
{
    uint32_t h = label * 0x9e3779b1u;
    h ^= h >> 15;
    h *= 0x85ebca77u;
    h ^= h >> 13;
    for (int c = 0; c < 3; c++)
        out[c] = (uint8_t)(64 + ((h >> (8 * c)) & 0xff) * 191 / 255);
}

void vb_jfa_render_slice(int dim, uint32_t n, const uint32_t *labels, uint32_t z, uint8_t *rgb,
                         size_t row_stride)
{
    const uint32_t *sl = labels + (size_t)z * n * n;
    int rz = dim == 3 ? 1 : 0;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            uint32_t me = sl[(size_t)y * n + x];
            int edge = 0;
            for (int dz = -rz; dz <= rz && !edge; dz++)
                for (int dy = -1; dy <= 1 && !edge; dy++)
                    for (int dx = -1; dx <= 1 && !edge; dx++) {
                        int64_t xx = (int64_t)x + dx, yy = (int64_t)y + dy, zz = (int64_t)z + dz;
                        if (xx < 0 || yy < 0 || zz < 0 || xx >= n || yy >= n ||
                            zz >= (dim == 3 ? (int64_t)n : 1))
                            continue;
                        edge = labels[((size_t)zz * n + (size_t)yy) * n + (size_t)xx] != me;
                    }
            /* Image rows run top-down; grid y runs up. */
            uint8_t *px = rgb + (size_t)(n - 1 - y) * row_stride + (size_t)x * 3;
            if (edge)
                px[0] = px[1] = px[2] = 0;
            else
                colour(me, px);
        }
}
