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
