/* PNG pictures of discrete Voronoi diagrams (vorball jfa --png). */
#ifndef VB_JFA_PNG_H
#define VB_JFA_PNG_H

#include <stdint.h>

#include "vb.h"

/* Writes an 8-bit RGB image (rgb: h rows of w pixels, 3 bytes each, row 0
 * at the top) to `path`. VB_EIO when the file cannot be written. */
int vb_png_write_rgb(vb_ctx *ctx, const char *path, uint32_t w, uint32_t h, const uint8_t *rgb);

#endif
