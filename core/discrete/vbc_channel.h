/* Channels and cavities from a discrete Voronoi diagram (Sec. 4 of the
 * Facet-JFA paper, Algorithm 2, and what it left out: components, pruning,
 * centrelines with radii, bottlenecks and lining atoms).
 *
 * Flow per frame: vbc_grid_fit -> vbc_atoms_pack -> labels (JFA, gpu/) ->
 * masks (gpu/channels.cl, or vbc_masks_ref here) -> compacted channel voxels
 * -> vbc_analyse (components, centrelines) -> writers. */
#ifndef VBC_CHANNEL_H
#define VBC_CHANNEL_H

#include <stdint.h>
#include <stdio.h>

#include "vb.h"
#include "vb_spheres.h"
#include "vbc_flags.h"

/* A cubic-voxel grid fitted around a molecule. dim 2 means nz == 1 and the
 * z coordinates of the atoms are ignored (the paper's 2D pictures). */
typedef struct vbc_grid {
    int nx, ny, nz;
    int dim;
    double origin[3]; /* Å, the corner of voxel (0,0,0) */
    double h;         /* voxel edge, Å */
} vbc_grid;

/* Fits an n^dim grid of cubic voxels around the spheres grown by `probe`
 * (voxel i has its centre at i + 0.5; the JFA fit, vbj_fit_grid, says why
 * its pixels differ),
 * with two voxels of empty margin on every side so every axis ray starts and
 * ends outside the atomic mask. VB_EMISUSE for n < 8 or n > 1024, dim not 2/3
 * or a negative probe; VB_EINPUT_EMPTY for an empty set. */
int vbc_grid_fit(vb_ctx *ctx, const vb_sphere_set *s, double probe, int n, int dim,
                 vbc_grid *out);

static inline size_t vbc_grid_voxels(const vbc_grid *g)
{
    return (size_t)g->nx * (size_t)g->ny * (size_t)g->nz;
}

/* Writes 4 floats per sphere to out4: the centre in grid units (voxel i has
 * its centre at i + 0.5) and (r + probe) / h. In 2D z is 0.5 (the slice). */
void vbc_atoms_pack(const vbc_grid *g, const vb_sphere_set *s, double probe, float *out4);

/* The ray bounds (rb, vbc_rb_size ints) of the atomic bits of am, ray by
 * ray with vbc_ray_scan: the definition the faster passes must match. */
void vbc_ray_bounds_plain(const uint8_t *am, int nx, int ny, int nz, int *rb);

/* The plain-C reference of the mask stage: from the packed atoms and a label
 * grid (nx*ny*nz ints, x fastest) writes the flag byte (VBC_F_*) of every
 * voxel into flags. min_labels: 3 in 3D, 2 in 2D. rb is scratch of
 * vbc_rb_size ints. Matches gpu/channels.cl bit for bit. */
void vbc_masks_ref(const vbc_grid *g, const float *atoms4, size_t natoms, const int32_t *labels,
                   int min_labels, int *rb, uint8_t *flags);

/* The mask stage in three steps, for a caller that reads few labels (the
 * reference engine without VBC_WANT_EDGES, vbc_channel_pipe.h).
 * vbc_masks_shape writes the atomic, molecular and interior bits of every
 * voxel (vbc_classify's, the labels aside) and the ray bounds rb, and
 * lists the interior voxels in increasing index order (*interior
 * malloc'ed, NULL when none; VB_ENOMEM). vbc_masks_need marks in need (one
 * byte per voxel, cleared first) the voxels whose labels the
 * classification of those voxels reads: each and its face neighbours
 * inside the grid. vbc_masks_edges then gives each listed voxel its whole
 * vbc_classify byte from labels that are right on the needed voxels (the
 * molecular bits of vbc_masks_shape's flags, not rb, give the mouths), and
 * rewrites the list's head with the channel voxels among them, in order,
 * the mouth flag in VBC_MOUTH_BIT (vbc_flags_compact's list); it returns
 * their number. The flags are vbc_masks_ref's bytes except the edge bit of
 * voxels that are not interior, which stays clear: channel, mouth,
 * interior, molecular and atomic bits are all the same. */
int vbc_masks_shape(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms, int *rb,
                    uint8_t *flags, uint32_t **interior, size_t *ninterior);
void vbc_masks_need(const vbc_grid *g, const uint32_t *interior, size_t n, uint8_t *need);
size_t vbc_masks_edges(const vbc_grid *g, const int32_t *labels, int min_labels, const int *rb,
                       uint32_t *interior, size_t n, uint8_t *flags);

/* Lists the channel voxels of a flag volume in increasing index order, the
 * mouth flag in VBC_MOUTH_BIT. *out is malloc'ed (NULL when none). */
int vbc_flags_compact(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, uint32_t **out,
                      size_t *count);

struct vbc_pore_request; /* vbc_pore_frame.h */

/* What the analysis keeps and how it decides. */
typedef struct vbc_options {
    double min_length;  /* Å; shorter centrelines are pruned */
    double min_radius;  /* Å; channels whose bottleneck is narrower are pruned */
    double lining_tol;  /* Å; an atom lines a point when its surface is within R + tol */
    int keep_cavities;  /* 0 drops components that do not reach the surface */
    const struct vbc_pore_request *pore; /* the pore stage of vbc_frame_run; NULL: none */
} vbc_options;

enum vbc_kind { VBC_CHANNEL = 0, VBC_CAVITY = 1, VBC_PORE = 2 };

/* Why a channel stands where it does in the table (vbc_rank). */
enum vbc_why {
    VBC_WHY_PORE = 0,     /* the pore along the axis, open at both ends */
    VBC_WHY_PORE_CLOSED,  /* the pore along the axis, closed somewhere (radius <= 0) */
    VBC_WHY_PORE_ONE_END, /* the pore along the axis, leaving the molecule at one end only */
    VBC_WHY_THROUGH,      /* openings on opposite faces of the molecule */
    VBC_WHY_PORE_BRANCH,  /* runs along the pore for part of its way: a vestibule or side branch */
    VBC_WHY_TUNNEL,       /* reaches the surface, not through */
    VBC_WHY_CAVITY        /* does not reach the surface */
};

/* A short phrase for the table ("pore along the axis, open at both ends", ...). */
const char *vbc_why_text(int why);

/* One point of a centreline: position (Å) and the radius of the largest
 * sphere centred there that overlaps no atom (distance to the nearest atom
 * surface), with the atom that bounds it. */
typedef struct vbc_point {
    double x, y, z, r;
    int32_t atom;
} vbc_point;

typedef struct vbc_channel {
    int kind;               /* enum vbc_kind */
    int why;                /* enum vbc_why, set by vbc_rank */
    int through;            /* the centreline joins openings on opposite faces (a pore) */
    size_t voxels;          /* channel voxels in the component */
    size_t mouths;          /* of those, voxels on the molecular surface */
    double length;          /* centreline length, Å: the polyline through its points */
    double bottleneck;      /* smallest radius on the centreline, Å */
    size_t bottleneck_at;   /* its index into the points */
    size_t first_point, npoints; /* slice of vbc_result.points */
    size_t first_lining, nlining; /* slice of vbc_result.lining (atom indices, ascending) */
} vbc_channel;

/* The pore of a frame (vbc_pore.h) as the writers need it. */
typedef struct vbc_pore_summary {
    int present;
    double u[3], c[3];      /* the axis: direction and start of the sweep */
    int source, chains;     /* enum vbc_axis_source; chains used */
    double step;            /* A between planes */
    double F, g_macro_pS;   /* HOLE's geometric factor (1/A) and Gmacro (1 M KCl) */
    int open_lo, open_hi;   /* each end left the molecule */
    int judged;             /* the verdict ran (a found axis): buried below */
    double buried;          /* A walled along the axis (vbc_pore_judge), also when no pore;
                             * for a pore VBC_PORE_MIN_BURIED or a little more (the
                             * verdict stops there) */
    int rejected_source;    /* no pore: the axis of the path judged (enum vbc_axis_source) */
    char why[128];          /* how the axis was found, in words (vbc_axis.why) */
} vbc_pore_summary;

typedef struct vbc_result {
    size_t nchannels;       /* kept channels and cavities, ranked by vbc_rank (else longest first) */
    vbc_channel *channels;
    vbc_point *points;
    int32_t *lining;
    size_t components;      /* connected components before pruning */
    size_t pruned;          /* components removed by the thresholds */
    int device_components;  /* the components are the device's labels (vbc_analyse_given) */
    double ms_graph;        /* the batch sweeps' wall time (vbc_analyse_paths), ms; else 0 */
    /* The analysis's steps, wall ms (vbc_analyse_paths): the voxels sorted,
     * linked and grouped into components; the members' clearances when
     * they did not come with the voxels; the components traced (ends,
     * sweeps, points, lining atoms) on the threads. */
    double ms_voxels, ms_clear, ms_trace;
    vbc_pore_summary pore;  /* when present, channels[0] is the pore (kind VBC_PORE) */
} vbc_result;

/* Connected components (26-connectivity) of the channel voxels `vox` (sorted
 * or not; VBC_MOUTH_BIT marks surface voxels), classified as channel (touches
 * the molecular surface) or cavity; per component the centreline (the longest
 * shortest path of the voxel graph, between two mouths for a channel), its
 * radii against the spheres `s` of the frame, bottleneck and lining atoms;
 * pruning by opt. Fills *res (free with vbc_result_free). VB_ENOMEM. */
int vbc_analyse(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                size_t nvox, const vbc_options *opt, vbc_result *res);

/* As vbc_analyse with the clearance of every voxel given (Å, parallel to
 * vox, e.g. from the device): it then steers the paths, while the radii
 * reported at centreline points are still computed here in double. */
int vbc_analyse_clear(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *clear, size_t nvox, const vbc_options *opt, vbc_result *res);

/* As vbc_analyse_clear (vclear may be NULL) with the components given:
 * comp (NULL: none) parallel to vox, per voxel the smallest voxel index of
 * its 26-connected component (the device's labels, vbc_frame_out.comp).
 * They replace the union-find when the host's checks hold on them (equal
 * across every edge it links; each label a listed voxel labelled itself,
 * no larger than the voxels it labels); else the union-find runs. The
 * result is vbc_analyse's either way. */
int vbc_analyse_given(vb_ctx *ctx, const vbc_grid *g, const vb_sphere_set *s, const uint32_t *vox,
                      const float *vclear, const uint32_t *comp, size_t nvox,
                      const vbc_options *opt, vbc_result *res);

void vbc_result_free(vbc_result *res);

/* Nearest atom surface and lining atoms by a cell list over a frame's spheres. */
typedef struct vbc_cells vbc_cells;

/* Builds the cell list (cell edge = cell Å, at least 1). VB_ENOMEM / VB_EINPUT_EMPTY. */
int vbc_cells_build(vb_ctx *ctx, const vb_sphere_set *s, double cell, vbc_cells **out);
void vbc_cells_free(vbc_cells *c);

/* The spheres the cell list was built over. */
const vb_sphere_set *vbc_cells_spheres(const vbc_cells *c);

/* The cell list as arrays, for a copy on a device (vbc_walls_prep): the
 * corner lo (the atoms' least coordinates), the cell edge, the cells per
 * axis, the largest radius, the CSR start (dim[0] dim[1] dim[2] + 1
 * entries: the atoms of cell x + dim[0] (y + dim[1] z) are idx[start[c]]
 * .. idx[start[c + 1] - 1]) and idx. An atom's cell is floor((x - lo) /
 * cell) per axis, clamped into 0 .. dim - 1. Borrowed: valid while c is. */
void vbc_cells_layout(const vbc_cells *c, double lo[3], double *cell, int dim[3], double *rmax,
                      const size_t **start, const int32_t **idx);

/* Distance from p to the nearest sphere surface (negative inside a sphere)
 * and that sphere's index in *atom. */
double vbc_cells_clearance(const vbc_cells *c, const double p[3], int32_t *atom);

/* vbc_cells_clearance, the walk started from the atom hint (-1: none; a
 * near atom, such as the last query's nearest, saves most of the walk):
 * the same answer for any hint. */
double vbc_cells_clearance_from(const vbc_cells *c, const double p[3], int32_t hint, int32_t *atom);

/* vbc_cells_clearance and the question of vbc_cells_within around its
 * answer in one walk of the cells: *R and *atom as vbc_cells_clearance
 * gives them, and in near[0..*nnear) with dist[] (|p - c| - r, the
 * expression vbc_cells_within tests) every sphere whose surface is within
 * *R + slack of p (slack >= 0), and maybe more, in the order
 * vbc_cells_within visits them: so vbc_cells_within(c, p, *R + s, fn) for
 * 0 <= s <= slack calls fn for exactly the near[k] with dist[k] <= *R + s,
 * in this order. hint as vbc_cells_clearance_from's (the same answer for
 * any). Returns 0, or -1 when more than cap spheres were to be listed (the
 * list then incomplete: ask vbc_cells_within). */
int vbc_cells_nearest_near(const vbc_cells *c, const double p[3], double slack, int32_t hint,
                           double *R, int32_t *atom, int32_t *near, double *dist, size_t cap,
                           size_t *nnear);

/* *R and *atom as vbc_cells_clearance_from gives them (hint likewise), and
 * in near[0..*nnear) with dist[] (|p - c| - r, vbc_cells_nearest_near's
 * expression) exactly the spheres whose surface is within *R + slack of p,
 * in no particular order: for callers that read the list as a set (the
 * lattice's and the ascent's local lists, channel_pore.c), a walk of rows
 * rather than of rings and the final bound rather than the falling one.
 * Returns 0, or -1 when more than cap spheres were to be listed or the set
 * is empty (the list then incomplete). */
int vbc_cells_near_set(const vbc_cells *c, const double p[3], double slack, int32_t hint,
                       double *R, int32_t *atom, int32_t *near, double *dist, size_t cap,
                       size_t *nnear);

/* vbc_cells_nearest_near's answer at p for slack, taken from the spheres
 * ids[0..n) alone: the caller vouches that they hold p's nearest sphere
 * and every sphere whose surface is within its distance + slack of p (as
 * vbc_cells_nearest_near's list at a point p0 for slack w does for a p
 * within (w - slack) / 2 of p0). The list holds exactly the spheres within
 * *R + slack, in the walk's order. Returns 0, or -1 when n is 0 or more
 * than cap (or 64) spheres were to be listed (ask vbc_cells_nearest_near). */
int vbc_cells_nearest_among(const vbc_cells *c, const int32_t *ids, size_t n, const double p[3],
                            double slack, double *R, int32_t *atom, int32_t *near, double *dist,
                            size_t cap, size_t *nnear);

/* Calls fn(atom, user) for every sphere whose surface is within `reach` of p
 * (|p - c| - r <= reach). */
void vbc_cells_within(const vbc_cells *c, const double p[3], double reach,
                      void (*fn)(int32_t atom, void *user), void *user);

/* Whether some sphere's surface is within `reach` of p: the question of
 * vbc_cells_within (the same per-atom test, so the same answer) that stops
 * at the first such sphere. hint (may be NULL) names an atom tried first
 * (-1: none) and gets the one found, so that neighbouring queries start
 * there. Returns 1 when there is one; else 0 with *low a lower bound of
 * the distance from p to every sphere surface (> reach; infinite when the
 * set is all walked and empty of surfaces near), which the caller may use
 * for points near p (the distance to the nearest surface moves by at most
 * the distance moved). */
int vbc_cells_any_within(const vbc_cells *c, const double p[3], double reach, int32_t *hint,
                         double *low);

/* The ligands a channel analysis left out, per residue name in the order
 * met (names past VBC_LIGAND_NAMES are counted in `atoms` only). */
#define VBC_LIGAND_NAMES 32
typedef struct vbc_ligands {
    size_t atoms;
    size_t n;
    char name[VBC_LIGAND_NAMES][8];
    size_t count[VBC_LIGAND_NAMES];
} vbc_ligands;

/* True when atom a is a ligand by default: a HETATM record (PDB, mmCIF,
 * PQR; GRO and XYZR have none) whose residue is no polymer residue
 * (VBC_POLYMER_HETATM: modified and D-amino acids, terminal caps such as
 * gramicidin's ethanolamine, modified nucleotides) nor of the membrane
 * (VBC_MEMBRANE_DEFAULT: --membrane decides on those). Sugars, ions,
 * cofactors, drugs and buffer molecules are ligands; water is dropped
 * before. */
int vbc_is_ligand(const vb_atom_info *a);

/* A copy of s without the atoms whose residue name is one of resnames[0..n)
 * (case-insensitive; a set without atom records keeps every sphere), and
 * without its ligands (vbc_is_ligand) when lig is not NULL, in *out (free
 * with vb_spheres_free), *dropped the count left out, counts[k] (when not
 * NULL) increased by the atoms of name k, lig's counts by the ligand atoms
 * (a name listed in resnames counts there); no exact decimals (a channel
 * set). VB_EINPUT_EMPTY when nothing is left, VB_ENOMEM. */
int vbc_spheres_without(vb_ctx *ctx, const vb_sphere_set *s, const char *const *resnames, size_t n,
                        size_t *counts, vbc_ligands *lig, vb_sphere_set **out, size_t *dropped);

/* Writers (core/discrete/channel_write.c). */

/* What a frame's table rows carry besides the channels. */
typedef struct vbc_frame_info {
    long frame;            /* index in the input, from 0 */
    int model;             /* MODEL serial (PDB) or frame + 1 */
    size_t atoms;
    size_t channel_voxels; /* before components */
    double ms_upload, ms_jfa, ms_masks, ms_analysis, ms_total;
    double ms_pore;        /* the pore stage (part of ms_total) */
    /* The stages around and inside those (per-run means like them; zero
     * when not measured): reading the frame from its file (once, not per
     * run), leaving out residues and fitting the grid, and the pore
     * stage's steps (vbc_pore_ms: their sum is about ms_pore). */
    double ms_read, ms_prepare;
    double ms_cells, ms_refine, ms_sweep, ms_verdict, ms_lining;
    double ms_graph;       /* the analysis's batch sweeps (part of ms_analysis; 0 without) */
    double ms_voxels, ms_clear, ms_trace; /* the analysis's steps (vbc_result) */
    double ms_beside;      /* of ms_analysis, what ran beside the pore stage (vbc_frame_analyse) */
    double t_start;        /* vb_now() when the frame's reading began; 0: unknown */
    double cpu_start;      /* vb_cpu_now() then (with t_start) */
} vbc_frame_info;

/* The channel table's columns, one "  name  meaning" line each (static
 * text): `vorball channels --help` and the README print it. */
const char *vbc_table_columns_help(void);

/* CSV: one header line, then one row per kept channel of each frame. */
void vbc_write_csv_header(FILE *f);
void vbc_write_csv_rows(FILE *f, const vbc_frame_info *fi, const vbc_grid *g,
                        const vb_sphere_set *s, const vbc_result *res);

/* Per-frame statistics as CSV (header, then one row per frame). */
void vbc_write_stats_header(FILE *f);
void vbc_write_stats_row(FILE *f, const vbc_frame_info *fi, const vbc_grid *g,
                         const vbc_result *res);

/* JSON: vbc_write_json_begin, one vbc_write_json_frame per frame (first = 1
 * for the first), vbc_write_json_end. Each frame object holds its statistics
 * and its channels with centreline points and lining residues. Its clocks
 * are two flat objects (no object inside them, so a reader or a sed can
 * drop them): "ms" after the statistics, the milliseconds of each stage
 * (VBC_JSON_MS_KEYS: read, prepare, upload, jfa = the Voronoi labels,
 * masks, analysis = the channel graph, graph = its ends and sweeps when
 * they ran as batches (VORBALL_DEVICE_PATHS, vbc_paths.h; else 0), voxels,
 * clear and trace = the analysis's steps (vbc_result's ms_voxels, ms_clear,
 * ms_trace), cells, refine, sweep, verdict,
 * lining, pore = the last five, beside = what of analysis ran within the
 * pore stage's span (vbc_frame_analyse; 0 when one ran after the other),
 * total = masks + analysis + pore - beside, the frame's span), and
 * "clock" closing the frame (VBC_JSON_CLOCK_KEYS: write = this frame's
 * JSON text, frame = end to end from the start of its reading, or the sum
 * of the stages when fi->t_start is 0, fps = 1000 / frame, and cpu = the
 * process's CPU ms over the same span, 0 when fi->t_start is 0). Every
 * other byte is the same whatever the clocks read. */
#define VBC_JSON_MS_KEYS "read prepare upload jfa masks analysis graph voxels clear trace cells refine sweep verdict lining pore beside total"
#define VBC_JSON_CLOCK_KEYS "write frame fps cpu"
void vbc_write_json_begin(FILE *f, const char *input, double probe, int n, const char *device);
/* As vbc_write_json_begin, with the provenance first when options is not
 * NULL (issue 35): "tool" (vorball V (commit C), vb_build.h) and "options"
 * (the command line that shaped the table); the sphere count is each
 * frame's "atoms". The CSV table has no comment convention (csv readers take
 * its first line as the header), so it carries none. */
void vbc_write_json_begin_prov(FILE *f, const char *options, const char *input, double probe,
                               int n, const char *device);
void vbc_write_json_frame(FILE *f, int first, const vbc_frame_info *fi, const vbc_grid *g,
                          const vb_sphere_set *s, const vbc_result *res);
/* The end of a run's JSON with its clock over every frame: after the
 * frames, "clock" (VBC_JSON_RUN_CLOCK_KEYS: frames, wall = ms from the
 * first frame's reading to the end of the last one's writing, fps = frames
 * per second on that clock (the whole run, reading included), cpu = the
 * process's CPU ms over it, cpu_per_frame). On one line, so that a filter
 * of "clock" lines drops it. */
#define VBC_JSON_RUN_CLOCK_KEYS "frames wall fps cpu cpu_per_frame"
void vbc_write_json_end_clock(FILE *f, long frames, double wall_ms, double cpu_ms);
void vbc_write_json_end(FILE *f);

/* Centrelines as PDB pseudo-atoms (one MODEL per frame): one residue per
 * channel (POR the pore, CHN a channel, CAV a cavity; chain A, B, ... and
 * number 1, 2, ... by rank), atom names P000, P001, ... unique in their
 * residue, serials 1.. unique in the model, the radius in the B-factor
 * column. At most 46,656 points a channel and 99,999 a model are written. */
void vbc_write_centrelines_pdb(FILE *f, int model, const vbc_result *res);

/* After the last model: CONECT records joining consecutive points of each
 * channel of the first model `first` (serials as written), then END. */
void vbc_write_centrelines_conect(FILE *f, const vbc_result *first);

/* A PyMOL script, to be written at path `script`, that loads the molecule
 * file (not when it is "-", stdin), then the trajectory traj into it (when
 * not NULL: PyMOL's load_traj) and the centreline PDB, all by paths
 * relative to the script's folder (core/discrete/channel_pymol.c), and
 * shows the points as spheres of their radius, coloured by it. */
void vbc_write_pymol(FILE *f, const char *script, const char *molecule, const char *centrelines,
                     const char *traj);

/* Whether the PyMOL script needs the first frame written as PDB beside it:
 * the input is not a file PyMOL reads with its coordinates (a PSF, a GRO, a
 * compressed or XYZR file), or it is the non-PDB topology of a trajectory.
 * Never for stdin ("-"). */
int vbc_pymol_needs_frame0(const char *input, const char *traj);

/* The spheres s as PDB ATOM/HETATM records (names, residues, chains and
 * elements from s->info; coordinates rounded to 0.001 A, the radius in the
 * B-factor column), then END. */
void vbc_write_molecule_pdb(FILE *f, const vb_sphere_set *s);

/* The radius profile of every channel of a frame as CSV rows (header first):
 * per point its index, axial coordinate s (on the pore's axis, when the
 * frame has a pore; else empty), arc length along the centreline, position,
 * radius, nearest atom ("A:GLY12:CA") and the atoms whose surface is within
 * radius + 0.05 A (those that bound the sphere), ';'-separated. */
void vbc_write_profile_header(FILE *f);
void vbc_write_profile_rows(FILE *f, const vbc_frame_info *fi, const vb_sphere_set *s,
                            const vbc_result *res);

/* Adds 1 to count[v] for every voxel v of g that is a channel voxel in flags
 * (may be NULL) or whose centre lies inside a sphere of the pore of res.
 * VB_ENOMEM. */
int vbc_occupancy_add(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_result *res,
                      float *count);

/* Writes values[v] * scale as a float32 volume on g: MRC (mode 2) or legacy
 * VTK, as vbc_write_volume decides by the name. VB_EMISUSE / VB_EIO. */
int vbc_write_volume_f32(vb_ctx *ctx, const char *path, const vbc_grid *g, const float *values,
                         double scale);

/* Writes the voxels of flags that have `bit` set as a 0/1 byte volume:
 * MRC (".mrc", ".map") or legacy VTK structured points (".vtk"), positioned in
 * Å. VB_EMISUSE for another extension, VB_EIO when writing fails. The file
 * appears whole or not at all (vb_output.h). */
int vbc_write_volume(vb_ctx *ctx, const char *path, const vbc_grid *g, const uint8_t *flags,
                     unsigned bit);

#endif
