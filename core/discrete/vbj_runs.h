/* A `vorball jfa` run, whole: seeds from their source (generated, a seed
 * file, points, or a protein's atom centres fitted into the grid), each
 * variant run `repeat` times and timed, its labels compared with the exact
 * diagram when asked, the figures written as the command prints them, and
 * the picture of the labels. The command (cli/cmd_jfa.c) and Python
 * (vorball.jfa) parse their arguments and call these. */
#ifndef VBJ_RUNS_H
#define VBJ_RUNS_H

#include <stdio.h>

#include "vb_spheres.h"
#include "vbj_jfa.h"

/* Most variants of one run ("all" is six), and the default. */
#define VBJ_MAX_VARIANTS 8
#define VBJ_VARIANTS_DEFAULT "jfa+1"

/* Where the seeds come from: the first of spheres, points, path given,
 * else generated (setup's dim, n, k, rng and dist). */
typedef struct vbj_seed_source {
    const vb_sphere_set *spheres; /* atom centres, fitted into [n]^3 with setup's margin */
    const char *spheres_name;     /* their file, for the source line */
    const double *points;         /* npoints rows of dim pixel coordinates */
    size_t npoints;
    const char *path;             /* a seed file: 'x y' or 'x y z' per line */
    vbj_distribution dist;
} vbj_seed_source;

/* Makes the seeds of `src` on setup's grid (setup checked by
 * vbj_setup_check; with spheres the grid is 3D) and writes the source line
 * of the figures ("protein F", "file F", "points", "uniform, rng 1") into
 * source[len]. VB_OK, or the readers' and vbj_seeds_*'s errors; free *out
 * with vbj_seeds_free. */
int vbj_seeds_make(vb_ctx *ctx, const vbj_setup *setup, const vbj_seed_source *src,
                   vbj_seeds *out, char *source, size_t len);

/* Parses "V[,V..]" (vbj_variant_parse's names, and "all": the five JFA and
 * Facet-JFA variants and exact) into v[VBJ_MAX_VARIANTS]; *nv gets the
 * count. VB_EMISUSE (message in ctx) for an unknown name, none or too many. */
int vbj_variants_parse(vb_ctx *ctx, const char *s, vbj_variant *v, int *nv);

/* One variant's figures: the last run's result, the times over the
 * repeats, and the comparison with the exact diagram (checked). */
typedef struct vbj_figures {
    vbj_variant v;
    vbj_result r;
    double mean_ms, min_ms, mean_gpu_ms;
    int checked;
    vbj_metrics m;
} vbj_figures;

typedef struct vbj_runs {
    vbj_figures run[VBJ_MAX_VARIANTS];
    int n;
    int repeat;
    double exact_ms;  /* the exact diagram's time with check, else -1 */
    char device[160]; /* the backend's device after the runs (W751 may move it) */
} vbj_runs;

/* Runs variants v[0..nv) on `s` through backend e with setup's m,
 * fuse_cells and repeat (a repeated variant runs once untimed first),
 * each with its labels; with check, compares each with the exact diagram.
 * Warns W780 (seeds lost to a shared start pixel) and W782 (Facet-JFA
 * starts at n) once each. Fills *out (free with vbj_runs_free, also after
 * a failure). VB_OK or vbj_run's errors. */
int vbj_runs_run(vb_ctx *ctx, vbj_backend *e, const vbj_seeds *s, const vbj_setup *setup,
                 const vbj_variant *v, int nv, int check, vbj_runs *out);

void vbj_runs_free(vbj_runs *r);

/* Writes the figures as `vorball jfa` prints them: a table, or with json
 * its JSON document. */
void vbj_runs_write(FILE *f, const vbj_runs *r, const vbj_seeds *s, const char *source,
                    int json);

/* The picture of a label grid (`vorball jfa --png`): 2D the diagram, 3D
 * the z-slices side by side (setup's slices, else n/2); each region a
 * colour derived from its label, boundary pixels black. *rgb gets h = n
 * rows of *w = n * slices pixels, 3 bytes each, row 0 at the top (malloc'd;
 * the caller frees). VB_OK or VB_ENOMEM. */
int vbj_picture(vb_ctx *ctx, const vbj_seeds *s, const uint32_t *labels, const vbj_setup *setup,
                uint8_t **rgb, uint32_t *w);

#endif
