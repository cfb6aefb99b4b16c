/* The pore verdict's clearance queries as one batch (issue 33): every
 * plane of a swept pore rastered at once, each pixel free, blocked or
 * unsure by a float filter with a proven bound (channel_walls_math.h), on
 * a device (gpu/channel_walls.cl) or the plain-C twin (channel_walls.c).
 * The host's flood (vbc_plane_walled) then reads the pixels from the
 * raster and asks its cell list only for the unsure ones, so the verdict
 * is the host's to the bit: a pixel's freedom is its own, and the filter
 * decides no uncertain sign. Internal to core/discrete and gpu/. */
#ifndef VBC_WALLS_H
#define VBC_WALLS_H

#include <stddef.h>
#include <stdint.h>

#include "vbc_pore.h"

/* One pore's planes as the filter reads them (vbc_walls_prep). */
typedef struct vbc_walls_input {
    size_t natoms, ncells;    /* ncells + 1 entries in start */
    float *atoms;             /* 4 per atom in cell order: x, y, z less the cells'
                                 corner, (r + VBC_WALL_PROBE)^2 */
    const uint64_t *start;    /* the cell list's CSR (vbc_cells_layout) */
    int dim[3];
    float inv_cell, reach, far2, bound, pixel;
    float a[3], b[3];         /* vbc_plane_basis of the axis */
    size_t nplanes;
    float *planes;            /* 4 per plane: centre less the corner, 0 */
    int *half;                /* per plane: the raster's half side m (vbc_walls_window) */
    size_t *word0;            /* nplanes + 1: the first word of each plane's raster */
} vbc_walls_input;

/* Fills *in for the points of p against the cell list c (the atoms
 * converted, the bound derived: channel_walls.c). Returns 0, -1 out of
 * memory (nothing to free). Free with vbc_walls_input_free. */
int vbc_walls_prep(const vbc_cells *c, const vbc_pore *p, vbc_walls_input *in);
void vbc_walls_input_free(vbc_walls_input *in);

/* The rasters: word w of the planes' rasters (plane k's words are
 * word0[k] .. word0[k + 1]) in blocked[w] and unsure[w]. */
typedef struct vbc_walls_raster {
    uint32_t *blocked, *unsure; /* in->word0[nplanes] words each */
} vbc_walls_raster;

/* An engine that rasters elsewhere (a device): raster fills out (its two
 * arrays allocated by the caller, word0[nplanes] words each) and returns
 * VB_OK, or another status after which the verdict floods as without an
 * engine (the same verdict). Calls may come from several threads (frames
 * in flight); an engine locks inside. */
typedef struct vbc_walls_engine {
    void *user;
    int (*raster)(void *user, const vbc_walls_input *in, vbc_walls_raster *out);
} vbc_walls_engine;

/* The plain-C twin: the words of in's rasters, by channel_walls_math.h as
 * the kernel computes them, on the VORBALL_THREADS threads. Returns VB_OK. */
int vbc_walls_raster_ref(const vbc_walls_input *in, vbc_walls_raster *out);

/* The twin's engine (tests; --device ref floods without one: its lazy
 * flood asks fewer pixels than a whole raster holds). */
const vbc_walls_engine *vbc_walls_engine_ref(void);

/* Where the verdict's rasters are made, from VORBALL_DEVICE_WALLS: 0
 * (unset, or anything else) never: the host floods alone; 1 on the kernel
 * when the pipe's device is a GPU; 2 on the kernel of any OpenCL device
 * (tests of the kernel on PoCL; a CPU device gains nothing: a whole raster
 * costs it more than the host's lazy flood). Off by default: on an H100
 * (stop 46, run B, 16 threads, grid 128) the kernel made 1chb's frame 0.3 ms
 * shorter but YiiP's 1.0 ms and adk's 0.14 ms longer. The verdict is the
 * same whichever runs. */
int vbc_walls_mode(void);

/* vbc_pore_judge with the planes' pixels from W's rasters (NULL, or a
 * failed raster: vbc_pore_judge itself). The same verdict. */
int vbc_pore_judge_on(const vbc_walls_engine *W, const vbc_cells *c, const vbc_pore *p,
                      double enough, vbc_pore_verdict *v);

/* vbc_plane_walled with the pixels (i, j), |i|, |j| <= m, from a raster of
 * half side m (blocked, unsure: its words; NULL: none), the others asked
 * of the cell list as vbc_plane_walled asks them. */
int vbc_plane_walled_raster(const vbc_cells *c, const double u[3], const double p[3], double r,
                            int m, const uint32_t *blocked, const uint32_t *unsure, void **scratch,
                            size_t *scratch_len);

/* The half side m of a plane's raster for a sphere of radius r: the
 * pixels within VBC_WALLS_WINDOW A of the sphere (a walled plane's flood
 * mostly stays there; an open plane's leaves it and goes on through the
 * cell list), at most vbc_plane_raster_half(r). On PoCL (2-core machine,
 * 1chb at 128^3, 141 planes) the host's part of the verdict took 1.35 ms
 * with a window of 4 A (6,616 words), 0.93 ms with 8 A (13,129 words),
 * 0.65-0.97 ms with the whole square (36,527 words); the lazy flood alone
 * 3.6 ms. */
int vbc_walls_window(double r);
#define VBC_WALLS_WINDOW 8.0

/* The half side n of a plane's raster for a sphere of radius r: pixels
 * (i, j) with |i|, |j| <= n, n = ceil(min(2 r + VBC_WALL_REACH,
 * VBC_WALL_MAX_REACH) / VBC_WALL_PIXEL) (r < 0 counts as 0). */
int vbc_plane_raster_half(double r);

#endif
