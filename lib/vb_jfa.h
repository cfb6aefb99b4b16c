/* Discrete Voronoi diagrams on [n]^d grids (`vorball jfa`) through the
 * library's front door (issue 29): one opaque handle holds the options
 * (one table: spellings, type, range, default; set by name as a command
 * line or Python keywords give them, checked by the library's one check),
 * the seeds' source, the runs of the JFA variants, Facet-JFA and the exact
 * engine on a device of vb_default_devices, their figures and pictures.
 * Results are read through this header's plain structs and written by its
 * writers; the engine's own structures (core/discrete's vbj_*) are not
 * installed.
 *
 * Use: vb_jfa_new, vb_jfa_set per option, vb_jfa_source_* (at most one;
 * none: generated seeds), vb_jfa_check, vb_jfa_run, then vb_jfa_info,
 * vb_jfa_figures_get, vb_jfa_write and vb_jfa_picture; vb_jfa_free. */
#ifndef VB_JFA_H
#define VB_JFA_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vb.h"
#include "vb_option.h"
#include "vb_spheres.h"

/* ---- The option table ---- */

/* The number of options in the table. */
size_t vb_jfa_option_count(void);

/* Option k (0 .. count - 1) into *o (its strings are static). 0, or -1
 * past the end. */
int vb_jfa_option_at(size_t k, vb_option *o);

/* The option called `name`: a command-line spelling ("--size", "-n") when
 * it starts with '-', else a Python keyword ("size"). 0 with *o filled, -1
 * when there is none. */
int vb_jfa_option_find(const char *name, vb_option *o);

/* The options as --help lists them: one "  -n, --size N  meaning" entry
 * each, the meaning's lines aligned at column 25. */
void vb_jfa_help(FILE *f);

/* ---- The handle ---- */

typedef struct vb_jfa vb_jfa;

/* A handle on ctx (its diagnostics) with every option at its default.
 * VB_OK or VB_ENOMEM (*out NULL). */
int vb_jfa_new(vb_ctx *ctx, vb_jfa **out);

/* Releases the handle, its seeds, runs and engine. NULL is allowed. */
void vb_jfa_free(vb_jfa *j);

/* Sets option `name` (as vb_jfa_option_find) to `value` (text, as the
 * command line gives it; ignored for a flag, which it sets). The numbers
 * are checked at once by the library's ranges, the variants and the
 * distribution by their names; --slice and --device wait for
 * vb_jfa_check. Paths are kept by pointer. 0, or -1 with the message in
 * err ("bad --size '32768'") and VB_EMISUSE recorded in the context. */
int vb_jfa_set(vb_jfa *j, const char *name, const char *value, char *err, size_t errlen);

/* The seeds' source, at most one (else generated from --seeds, --dist and
 * --rng): a seed file ('x y' or 'x y z' per line, pixels); npoints rows
 * of dim pixel coordinates (copied; --dim set first); atom centres of s fitted into an
 * [n]^3 grid (kept by pointer until vb_jfa_run; `name` its file, for the
 * source line). VB_OK, VB_ENOMEM. */
int vb_jfa_source_file(vb_jfa *j, const char *path);
int vb_jfa_source_points(vb_jfa *j, const double *points, size_t npoints);
int vb_jfa_source_spheres(vb_jfa *j, const vb_sphere_set *s, const char *name);

/* The rules between options once every one is set: a protein (--protein or
 * spheres) with no seed file and in 3D (the default dim then), the 3D
 * picture's slices below n, the device's name. 0, or -1 with the message
 * in err and VB_EMISUSE recorded. */
int vb_jfa_check(vb_jfa *j, char *err, size_t errlen);

/* What a caller reads of the options: the protein file to read (NULL: not
 * given), the picture and figures files (NULL: not asked), --json, --check. */
typedef struct vb_jfa_request {
    const char *protein, *png, *out;
    int json, check;
} vb_jfa_request;

void vb_jfa_request_get(const vb_jfa *j, vb_jfa_request *r);

/* Makes the seeds, opens the engine on the checked device at the first
 * run (the reference with W781 when OpenCL has none; later runs of the
 * handle keep it), runs every variant `repeat` times
 * (timed) and with --check compares it with the exact diagram. Warnings
 * W780, W782, W751. VB_OK, or the seeds' readers' and the engine's errors
 * (the results of a failed run are not kept). */
int vb_jfa_run(vb_ctx *ctx, vb_jfa *j);

/* ---- Results ---- */

/* The run: the device in words, the grid, the seeds' count and source
 * ("uniform, rng 1", "file F", "points", "protein F"), the repeats, the
 * exact diagram's milliseconds with --check (else -1), the variants run. */
typedef struct vb_jfa_info {
    const char *device, *source;
    int dim;
    uint32_t n;
    size_t seeds;
    int repeat;
    double exact_ms;
    int runs;
} vb_jfa_info;

/* 0 with *i filled, -1 before a run. */
int vb_jfa_info_get(const vb_jfa *j, vb_jfa_info *i);

/* One variant's figures: its name; times (mean and fastest of the
 * repeats, device execution, label fill, preparation and transfer, the
 * exact variants' host preparation); the counts of work; with --check the
 * comparison with the exact diagram; its labels (the seed index of each
 * pixel, x fastest: n^dim entries, owned by the handle). */
typedef struct vb_jfa_figures {
    const char *variant;
    double time_ms, time_ms_min, gpu_ms, fill_ms, prep_transfer_ms, prep_ms;
    uint32_t steps, m, collisions;
    uint64_t pixels_processed, threads, boundary;
    uint64_t tiles, tiles_uniform, candidates, survivors, evals, exact_voxels, tiles_chunked,
        visited;
    int checked;
    size_t wrong, differ, boundary_exact, boundary_found, boundary_missed, boundary_extra;
    double wrong_rate, max_err, mean_err;
    const uint32_t *labels;
    size_t pixels;
} vb_jfa_figures;

/* Run k (0 .. runs - 1, in the order asked) into *f: 0, or -1 past the end. */
int vb_jfa_figures_get(const vb_jfa *j, int k, vb_jfa_figures *f);

/* The figures as `vorball jfa` prints them: the table, or with json its
 * JSON document. Nothing before a run. */
void vb_jfa_write(const vb_jfa *j, FILE *f, int json);

/* The picture of a label grid of the handle's dim and n (labels NULL: the
 * last run's; `--png`): 2D the diagram, 3D the slices of --slice (default
 * n/2) side by side; each region a colour of its label, boundaries black.
 * *rgb gets n rows of *w pixels, 3 bytes each, row 0 at the top (malloc'd;
 * the caller frees). VB_OK, VB_ENOMEM, VB_EMISUSE (no labels). */
int vb_jfa_picture(vb_ctx *ctx, const vb_jfa *j, const uint32_t *labels, uint8_t **rgb,
                   uint32_t *w);

#endif
