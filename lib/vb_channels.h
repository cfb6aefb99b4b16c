/* Channels and cavities through the library's front door (issue 29): one
 * opaque handle holds the options (the one table of the channel analysis,
 * set by name as a command line or Python keywords give them, checked and
 * defaulted by the library), the engine (the discrete Voronoi pipe on a
 * device of vb_default_devices) and the run over frames (the pore axis
 * carried from the first frame to the later ones, the pore series, the
 * occupancy). Results are read through this header's accessors and plain
 * structs, and written by its writers; the analysis's own structures
 * (core/discrete, vbc_* and vbj_*) are not installed.
 *
 * One frame: vb_channels_new, vb_channels_set per option, vb_channels_check,
 * vb_channels_open, vb_channels_run, then the accessors (vb_channels_frame_get,
 * vb_channels_last, vb_channels_flags) and writers (vb_channels_write_frame_csv,
 * _json). Every frame of a source, written as `vorball channels` writes them:
 * vb_channels_write_head, vb_channels_run_frames, vb_channels_finish. */
#ifndef VB_CHANNELS_H
#define VB_CHANNELS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "vb.h"
#include "vb_frames.h"
#include "vb_option.h"

/* ---- The option table (each option declared once: name, type, range,
 * default, help) ---- */

/* Where --help lists an option (vb_channels_help). */
enum vb_channels_help_section { VB_CHANNELS_HELP_MAIN, VB_CHANNELS_HELP_PORE };

/* A row of the table: spellings, type (enum vb_opt_type), range, choices,
 * default, help, section (enum vb_channels_help_section). */
typedef vb_option vb_channels_option;

/* The number of options in the table. */
size_t vb_channels_option_count(void);

/* Option k (0 .. count - 1) into *o (its strings are static). 0, or -1
 * past the end. */
int vb_channels_option_at(size_t k, vb_channels_option *o);

/* The option called `name`: a command-line spelling ("--probe", its alias)
 * when it starts with '-', else a Python keyword ("probe"). 0 with *o
 * filled, -1 when there is none. */
int vb_channels_option_find(const char *name, vb_channels_option *o);

/* The options of `section` as --help lines (wrapped at 80 columns, with
 * range and default); the table's columns, one "  name  meaning" line each
 * (static text). */
void vb_channels_help(FILE *f, int section);
const char *vb_channels_columns_help(void);

/* ---- The handle ---- */

typedef struct vb_channels vb_channels;

/* A handle with every option at its default and no engine. VB_OK or
 * VB_ENOMEM (*out NULL). */
int vb_channels_new(vb_ctx *ctx, vb_channels **out);

/* Releases the handle, its engine and results. NULL is allowed. */
void vb_channels_free(vb_channels *ch);

/* Sets option `name` (as vb_channels_option_find) to `value` (text; NULL
 * or ignored for a flag, which it sets). Paths are kept by pointer: value
 * must outlive the handle's use of it. 0, or -1 with a message in err
 * ("--grid needs a power of two in 16..1024, not '100'"). */
int vb_channels_set(vb_channels *ch, const char *name, const char *value, char *err,
                    size_t errlen);

/* The rules between options, once every one is set. 0, or -1 with a
 * message in err. */
int vb_channels_check(vb_channels *ch, char *err, size_t errlen);

/* Every option back to its default (then vb_channels_set, _check again);
 * the engine and the axis carried by VB_CHANNELS_CARRY_AXIS stay. */
void vb_channels_reset(vb_channels *ch);

/* What a caller reads of the options to open its outputs: the output
 * paths (NULL: not asked), the trajectory, and the frame selection. */
typedef struct vb_channels_request {
    const char *out, *traj, *centrelines, *pymol, *volume, *stats, *png;
    const char *profile, *plot, *occupancy, *html;
    int json;           /* --json: the table as JSON */
    int stats_stderr;   /* --stats without a file: the statistics rows on stderr */
    int fixed_grid;     /* --fixed-grid */
    long f0, f1, fstep; /* --frames a:b:step (f1 < 0: to the end) */
} vb_channels_request;

void vb_channels_request_get(const vb_channels *ch, vb_channels_request *r);

/* Opens the engine on the device and engine of the options (--device,
 * --jfa; the device falls back to the reference with W804 as every flow
 * does). VB_OK, VB_ENOMEM, VB_EDEVICE. */
int vb_channels_open(vb_ctx *ctx, vb_channels *ch);

/* The engine's device in words ("" before vb_channels_open). */
const char *vb_channels_device_name(const vb_channels *ch);

/* ---- One frame ---- */

enum {
    VB_CHANNELS_KEEP_FLAGS = 1, /* keep the flag volume (vb_channels_flags) */
    VB_CHANNELS_CARRY_AXIS = 2  /* the pore axis a first frame found is swept on the later
                                 * frames of this handle unless an axis is given (an engine's
                                 * frames, as the command's); without it nothing is carried */
};

/* Analyses frame `index` (MODEL `model`) of the spheres s with the checked
 * options on the opened engine; `first`: it is the first frame of its
 * selection. The results stay in the handle until the next run or free.
 * W809/W811 name the atoms left out. VB_OK, VB_ENOMEM, VB_EINPUT,
 * VB_EINPUT_EMPTY, VB_EDEVICE, VB_EMISUSE (no engine). */
int vb_channels_run(vb_ctx *ctx, vb_channels *ch, const vb_sphere_set *s, long index, int model,
                    int first, unsigned flags);

/* Frees the last run's results (the engine and the carried axis stay). */
void vb_channels_done(vb_channels *ch);

/* What the last vb_channels_run gave besides its rows: counts, grid and
 * per-run mean milliseconds of each stage. */
typedef struct vb_channels_frame {
    long frame;
    int model;
    size_t components, pruned; /* connected components before pruning; removed */
    size_t channel_voxels;     /* before components */
    int nx, ny, nz;
    double h, origin[3];       /* voxel edge and the grid's corner, Å */
    double ms_prepare, ms_upload, ms_jfa, ms_masks, ms_analysis, ms_cells, ms_refine, ms_sweep,
        ms_verdict, ms_lining, ms_pore, ms_total;
} vb_channels_frame;

/* 0 with *f filled, -1 before a run. */
int vb_channels_frame_get(const vb_channels *ch, vb_channels_frame *f);

/* The flag volume of the last run (nx*ny*nz bytes of VB_CHANNEL_F_* bits,
 * x fastest) with VB_CHANNELS_KEEP_FLAGS, else NULL; *n its length. */
const uint8_t *vb_channels_flags(const vb_channels *ch, size_t *n);

/* The bits of the flag volume. */
enum {
    VB_CHANNEL_F_ATOMIC = 1,
    VB_CHANNEL_F_MOLECULAR = 2,
    VB_CHANNEL_F_EDGE = 4,
    VB_CHANNEL_F_INTERIOR = 8,
    VB_CHANNEL_F_CHANNEL = 16,
    VB_CHANNEL_F_MOUTH = 32
};

/* The last run's table as the command writes it for this frame alone: the
 * CSV with its header; the JSON document (input named by the spheres'
 * source). Nothing before a run. */
void vb_channels_write_frame_csv(const vb_channels *ch, FILE *f);
void vb_channels_write_frame_json(const vb_channels *ch, FILE *f);

/* The last run's radius profile as `--profile` writes it for this frame
 * alone: the header, then per point of every row its axial and arc
 * coordinates, position, radius, nearest atom and bounding atoms. */
void vb_channels_write_frame_profile(const vb_channels *ch, FILE *f);

/* ---- A frame's rows ---- */

/* A frame's analysis (opaque; read through the accessors below). */
typedef struct vbc_result vb_channels_result;

/* The last run's (NULL before one); after vb_channels_run_frames, the
 * first frame's of the selection (NULL when none ran here). */
const vb_channels_result *vb_channels_last(const vb_channels *ch);
const vb_channels_result *vb_channels_first(const vb_channels *ch);

/* One row: the pore, a channel or a cavity, ranked as the table. */
typedef struct vb_channel_row {
    int kind;             /* 0 channel, 1 cavity, 2 pore */
    int through;          /* the centreline joins openings on opposite faces */
    size_t voxels, mouths; /* channel voxels; of those, on the molecular surface */
    double length;        /* centreline length, Å */
    double bottleneck;    /* smallest radius on the centreline, Å */
    size_t bottleneck_at; /* its index in the row's points */
    size_t first_point, npoints;  /* the row's points (vb_channels_result_point) */
    size_t first_lining, nlining; /* the row's lining atoms (vb_channels_result_lining) */
} vb_channel_row;

/* One centreline point: position and clearance radius (Å), the atom that
 * bounds it. */
typedef struct vb_channel_point {
    double x, y, z, r;
    int32_t atom;
} vb_channel_point;

size_t vb_channels_result_rows(const vb_channels_result *r);

/* Row k into *row: 0, or -1 past the end. */
int vb_channels_result_row(const vb_channels_result *r, size_t k, vb_channel_row *row);

/* The points of every row (the rows' slices); point k into *p: 0, or -1
 * past the end. */
size_t vb_channels_result_points(const vb_channels_result *r);
int vb_channels_result_point(const vb_channels_result *r, size_t k, vb_channel_point *p);

/* The lining atoms of every row (indices into the analysed spheres); *n
 * gets their count. */
const int32_t *vb_channels_result_lining(const vb_channels_result *r, size_t *n);

/* The frame's pore as the table's pore columns and the JSON describe it. */
typedef struct vb_channels_pore {
    double u[3], c[3];     /* the axis: direction (unit) and the sweep's start, Å */
    double step;           /* Å between planes */
    double F, g_macro_pS;  /* HOLE's geometric factor (1/Å) and its conductance estimate
                            * (pS, 1 M KCl) */
    int open_lo, open_hi;  /* the openings: each end of the sweep left the molecule */
    int judged;            /* the verdict ran on a found axis: `buried` below */
    double buried;         /* Å walled along the axis (also when there is no pore) */
    const char *why;       /* how the axis was found, in words ("" when none) */
} vb_channels_pore;

/* 1 when the frame has a pore (row 0), else 0; *p filled either way (the
 * verdict's figures stand without a pore). */
int vb_channels_result_pore(const vb_channels_result *r, vb_channels_pore *p);

/* ---- Every frame of a source ---- */

/* The sinks of a frame's text: the table (CSV or JSON), the statistics
 * rows, the centreline models. */
enum { VB_CHANNELS_SINK_TABLE, VB_CHANNELS_SINK_STATS, VB_CHANNELS_SINK_CENTRELINES,
       VB_CHANNELS_SINKS };

/* How a run over frames reaches its caller. Every hook may be NULL. */
typedef struct vb_channels_io {
    void *user;
    const char *input;  /* the input's name: warnings, the page's title, the PyMOL script */
    FILE *sink[VB_CHANNELS_SINKS]; /* where frames are written without `stream` (NULL: not
                                    * wanted) */
    FILE *profile;      /* --profile rows, or NULL */
    int quiet_read;     /* say nothing while reading frames (a process that is not the writer) */
    /* Frames dealt to several processes: whether frame j of the selection
     * is this one's (NULL: every frame, and frames may be read and run
     * ahead on a reader thread, vbc_ahead); the frames per round and the
     * collective after frames [j0, j1) of a round, which returns the status
     * every process agrees on (NULL: no rounds). */
    int (*mine)(void *user, long j);
    long round;
    int (*round_end)(vb_ctx *ctx, void *user, int rc, long j0, long j1);
    /* Where this frame's text of sink k goes (NULL: sink[k]); its end. */
    FILE *(*stream)(void *user, int k);
    int (*frame_done)(vb_ctx *ctx, void *user);
    /* The first frame is analysed: the spheres read and those analysed
     * (after --ignore and --membrane). VB_OK or a failure that ends the run. */
    int (*first_frame)(vb_ctx *ctx, void *user, const vb_sphere_set *read,
                       const vb_sphere_set *analysed);
    /* The files the run writes itself: whether one may be written (not an
     * input, say: VB_OK or a failure; NULL: any may), and how a text file
     * is opened and closed (the first frame's PDB, the PyMOL script; NULL:
     * vb_output's open and commit, so it appears whole or not at all). */
    int (*check_output)(vb_ctx *ctx, const char *path);
    FILE *(*open_output)(vb_ctx *ctx, const char *path);
    int (*close_output)(vb_ctx *ctx, FILE *f, const char *path);
    /* Frame `index` read, `done` analysed so far: a status line. */
    void (*status)(void *user, long index, long done, const char *device);
} vb_channels_io;

/* The heads of the table (CSV header, or the JSON document's start with
 * `options`, the command line, as provenance when not NULL), of the
 * statistics and of the profile, into the sinks that are not NULL. */
void vb_channels_write_head(const vb_channels *ch, const vb_channels_io *io, const char *options);

/* Reads the frames of F, runs the selected ones (this process's, io->mine)
 * and writes each: table, statistics and centrelines to the frame's
 * streams, the profile rows, the volume (per frame with '%d' in its name,
 * else the first frame's), the first frame's stage picture (kept:
 * vb_channels_stages) and PDB beside the PyMOL script, the results page's
 * frame. *selected gets the frames selected. E: VB_EINPUT_MODEL when none
 * is; the failures of reading and vb_channels_run. */
int vb_channels_run_frames(vb_ctx *ctx, vb_channels *ch, vb_frame_source *F,
                           const vb_channels_io *io, long *selected);

/* After vb_channels_run_frames succeeded: W809/W811 for the atoms left
 * out; with `writer` (the process that writes), W802 when a volume named
 * without '%d' holds the first of several frames, the JSON end, the
 * CONECT records, the PyMOL script, the occupancy volume and the results
 * page. VB_OK, VB_EIO, VB_ENOMEM. */
int vb_channels_finish(vb_ctx *ctx, vb_channels *ch, const vb_channels_io *io, int writer,
                       long selected);

/* What this process's run over frames did. */
typedef struct vb_channels_totals {
    long frames;               /* analysed */
    int repeat;                /* runs per frame (--repeat) */
    double ms_total, ms_masks; /* over every run of every frame */
} vb_channels_totals;

void vb_channels_totals_get(const vb_channels *ch, vb_channels_totals *t);

/* The first frame's eight-panel stage picture (--png): w x h RGB pixels,
 * row 0 on top. 0, or -1 when none was made. */
int vb_channels_stages(const vb_channels *ch, uint32_t *w, uint32_t *h, const uint8_t **rgb);

/* The pore's smallest radius per frame (--plot): the count; with k below
 * it, entry k into the pointers that are not NULL. */
size_t vb_channels_series(const vb_channels *ch, size_t k, long *frame, double *rmin, double *s);

#endif
