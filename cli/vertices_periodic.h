/* `vorball vertices --periodic`: the periodic box options and the periodic
 * run (parse, call the library's vb_periodic_vertices_run, write). */
#ifndef VB_CLI_VERTICES_PERIODIC_H
#define VB_CLI_VERTICES_PERIODIC_H

#include <stdio.h>

#include "input_options.h"
#include "vb_frames.h"
#include "vb_periodic.h"

typedef struct vb_cli_periodic {
    int on;                   /* --periodic */
    const char *box[9];       /* --box's numbers (argv strings) */
    int nbox;                 /* 0: the box of the file */
    const char *traj;         /* --traj: frames of a DCD/XTC/TRR (input = topology) */
    int frames;               /* --frames given */
    vb_frame_range range;     /* --frames (all when not given) */
} vb_cli_periodic;

/* Consumes argv[*i] when it is --periodic or --box (with its 3, 6 or 9
 * numbers: the arguments after it that are numbers), and for cmd
 * "vertices" --traj FILE or --frames A:B:S (both imply --periodic).
 * Returns 1 if
 * consumed, 0 if not one of them, -1 on a bad count (message printed). */
int vb_cli_periodic_option(const char *cmd, int argc, char **argv, int *i, vb_cli_periodic *p);

/* The help lines of --periodic and --box. */
void vb_cli_periodic_help(FILE *f);

/* The box of the run: --box's, else the set's; VB_EINPUT_BOX (E120) when
 * neither gives one. */
int vb_cli_periodic_box(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                        vb_box *box);

/* The periodic run of the validated set and its file: the box from --box
 * or else from the set (VB_EINPUT_BOX when neither), the run on the
 * default backends, --stats counters on stderr, the vertices to outpath
 * (NULL: stdout; tsv or json) with the provenance of `input` in the
 * header. Returns a status. */
int vb_cli_vertices_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                             const vb_vertices_config *cfg, const char *input,
                             const char *outpath, int json, int stats);

/* The periodic run of every selected frame (--traj, --frames) of `input`
 * (with --traj, its topology), each in its own box (or --box's): one tsv
 * file, each frame's vertices after a line `# frame K (model M)` and the
 * frame's certificate; --stats: per frame, on stderr. Returns a status. */
int vb_cli_vertices_periodic_frames(vb_ctx *ctx, const char *input, const vb_cli_input_opts *in,
                                    const vb_cli_periodic *p, const vb_vertices_config *cfg,
                                    const char *outpath, int stats);

#endif
