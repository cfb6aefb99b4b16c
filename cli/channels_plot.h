/* `channels --plot`: the pore profile drawn by gnuplot (cli/channels_plot.c). */
#ifndef VB_CHANNELS_PLOT_H
#define VB_CHANNELS_PLOT_H

#include "vb_channels.h"

/* Writes png.gp (the profile of the pore of ch's first frame inline, HOLE's radius bands,
 * with series of more than one frame a second panel of the smallest radius
 * per frame) and runs gnuplot on it to draw png. Without gnuplot, or when
 * it fails, the script stays and W807 says so (VB_OK); without a pore W808.
 * VB_EIO when a file cannot be written. */
int vb_cli_channels_plot(vb_ctx *ctx, const char *png, const char *title, const vb_channels *ch);

#endif
