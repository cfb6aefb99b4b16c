/* The channels handle of vb_channels.h as its two files see it
 * (lib/channels.c: options, one frame, accessors; lib/channels_frames.c:
 * the run over frames). Private to lib/: not installed. */
#ifndef VB_CHANNELS_HANDLE_H
#define VB_CHANNELS_HANDLE_H

#include "vb_channels.h"
#include "vb_page.h"
#include "vbc_run.h"

struct vb_channels {
    vbc_channels_config cfg;  /* the options (vbc_channels_config.h) */
    vbc_pipe *pipe;           /* the engine (vb_channels_open), or NULL */
    vbc_run run;              /* the run over frames, or the last single frame's */
    int run_live;             /* `run` is initialised */
    vbc_run_out out;          /* the last single frame (vb_channels_run) */
    const vb_sphere_set *s0;  /* its spheres as given */
    int have_out;
    int keep_flags;           /* it was asked to keep its flag volume */
    /* The pore axis an engine's first frame found (VB_CHANNELS_CARRY_AXIS). */
    int have_carry;
    vbc_pore_request carry_pore;
    vbc_axis carry_refit0;
    double carry_u0[3], carry_c0[3];
    /* The run over frames' own outputs. */
    vbc_image stages;         /* --png: the first frame's picture (w 0: none) */
    vb_page *page;            /* --html */
    char frame0[4200];        /* --pymol: the first frame's PDB beside it, or "" */
    double t_frames, cpu_frames; /* vb_now() and vb_cpu_now() when the run over frames began */
};

/* Ends the handle's run (frames or single frame) and frees its results. */
void vb_channels_drop_run(vb_channels *ch);

#endif
