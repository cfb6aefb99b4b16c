/* Sphere sets and their readers (XYZR / Voronota balls, PDB, PQR, mmCIF,
 * GRO; gzip or bzip2 compressed or not).
 *
 * A sphere set is a struct of arrays. Every coordinate and radius is kept twice:
 * as the double nearest to the decimal written in the file (strtod, correctly
 * rounded) and as that exact decimal (vb_decimal), which verify/ turns into a
 * GMP rational. The exact value is never derived from the double. */
#ifndef VB_SPHERES_H
#define VB_SPHERES_H

#include "vb.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An exact decimal: value = mant * 10^exp10. At most 18 significant digits
 * (more is VB_EINPUT_MAGNITUDE); trailing zeros are stripped so equal values
 * have equal representations. */
typedef struct vb_decimal {
    int64_t mant;
    int32_t exp10;
} vb_decimal;

/* Per-atom annotation for PDB/PQR/mmCIF input (empty strings for XYZR; the
 * Voronota annotation after '#' is kept in `name`..`resname` when present). */
typedef struct vb_atom_info {
    int32_t serial;
    int32_t resseq;
    char name[8];     /* atom name, e.g. "CA" */
    char resname[8];  /* residue name, e.g. "ALA" */
    char chain[8];    /* chain id (mmCIF auth_asym_id may be long: truncated, warned) */
    char element[4];  /* element symbol, upper case, e.g. "C", "FE" */
    char icode;       /* insertion code or ' ' */
    char altloc;      /* alternate location or ' ' */
    uint8_t hetatm;   /* 1 for HETATM */
    char segid[8];    /* segment id: PDB columns 73-76, a PSF's segment; else empty */
} vb_atom_info;

/* A periodic box: the edge vectors a, b, c (rows of ev and v: a = ev[0..2],
 * b = ev[3..5], c = ev[6..8]) as exact decimals and their nearest doubles.
 * The files' boxes (GRO's last line, PDB's CRYST1) and --box become one
 * (core/periodic/vb_periodic.h says how lengths and angles do). */
typedef struct vb_box {
    vb_decimal ev[9];
    double v[9];
} vb_box;

typedef struct vb_sphere_set {
    size_t n;
    double *x, *y, *z, *r;           /* nearest doubles */
    vb_decimal *ex, *ey, *ez, *er;   /* exact decimals as written (radius from the table for PDB/mmCIF) */
    vb_atom_info *info;              /* NULL when the format has no atom records (XYZR) */
    long *line;                      /* 1-based source line of each sphere */
    uint8_t *contained;              /* 1 if the sphere lies inside another (empty cell); set by vb_spheres_validate */
    uint8_t allows_zero_radius;      /* the reader accepted radius-0 spheres as points (--zero-radius point) */
    char *source;                    /* file name as given ("-" = stdin), owned */
    vb_box *box;                     /* the periodic box the file carries (GRO box line,
                                      * PDB CRYST1), NULL when none; owned */
} vb_sphere_set;

typedef enum vb_format {
    VB_FMT_AUTO = 0,
    VB_FMT_XYZR,
    VB_FMT_PDB,
    VB_FMT_PQR,
    VB_FMT_MMCIF,
    VB_FMT_GRO
} vb_format;

/* Radii table (element symbol -> radius as an exact decimal). */
typedef struct vb_radii_table vb_radii_table;

/* What a reader does with a sphere of radius exactly 0 (negative radii are
 * always VB_EINPUT_RADIUS). AUTO keeps them as points in PQR files, whose
 * PARSE radii give polar hydrogens radius 0 on purpose, and refuses them
 * elsewhere. A point is a legal site of the additively weighted diagram. */
typedef enum vb_zero_radius {
    VB_ZERO_RADIUS_AUTO = 0,
    VB_ZERO_RADIUS_ERROR,  /* VB_EINPUT_RADIUS naming the line */
    VB_ZERO_RADIUS_POINT,  /* keep as a point site, counted in warning W713 */
    VB_ZERO_RADIUS_DROP    /* leave out, counted in warning W712 */
} vb_zero_radius;

typedef struct vb_read_options {
    vb_format format;            /* VB_FMT_AUTO detects by content */
    int model;                   /* PDB/mmCIF model number to read; 0 = first model */
    int keep_water;              /* 1 keeps HOH/WAT/DOD/TIP3 residues (default 0: dropped, with a count on stderr) */
    int drop_hydrogens;          /* 1 drops H/D atoms (default 0: kept) */
    int strict_elements;         /* 1: unknown element is VB_EINPUT_ELEMENT; 0: default radius + warning */
    const vb_radii_table *radii; /* NULL = built-in table (C 1.70, N 1.55, O 1.52, S 1.80, P 1.80, H 1.20, ...) */
    size_t max_spheres;          /* 0 = default limit (50,000,000) */
    int zero_radius;             /* enum vb_zero_radius */
    int assembly;                /* mmCIF: biological assembly N of _pdbx_struct_assembly_gen
                                  * (0 = the asymmetric unit as written) */
    const char *select;          /* keep only the atoms this expression selects (vb_select.h);
                                  * NULL: all. Applied after water and hydrogens are dropped */
    int keep_virtual_sites;      /* water models' massless virtual sites (MW, OM, EPW, LP1, ...):
                                  * 0 (default) left out with W727 (a point charge is no atom);
                                  * 1 read as atoms; 2 kept as placeholders (radius 1.70) without
                                  * element diagnostics (a trajectory's topology, whose atoms
                                  * must match the frames', is read so and drops them after) */
} vb_read_options;

/* The largest --model and --assembly numbers asked. */
#define VB_MODEL_MAX 999999999
#define VB_ASSEMBLY_MAX 999999

/* The read options' ranges, the one check of the commands and the
 * bindings: model 0 (the first) or 1..VB_MODEL_MAX, assembly 0 (the
 * asymmetric unit) or 1..VB_ASSEMBLY_MAX. Returns VB_OK, or VB_EMISUSE with
 * ctx's message naming the range ("--model needs a model number >= 1";
 * the caller adds the value as it was given). */
int vb_read_options_check(vb_ctx *ctx, const vb_read_options *o);

/* Parses a format name ("xyzr", "pdb", "pqr", "cif"/"mmcif", "gro", "auto").
 * Returns VB_OK or VB_EMISUSE. */
int vb_format_parse(vb_ctx *ctx, const char *name, vb_format *out);

/* Reads spheres from a file ("-" = stdin). On success *out owns a new set
 * (free with vb_spheres_free). Errors are VB_EINPUT_* with file:line in the
 * context message, or VB_EIO / VB_ENOMEM. Does not validate geometry: call
 * vb_spheres_validate. */
int vb_spheres_read_file(vb_ctx *ctx, const char *path, const vb_read_options *opt,
                         vb_sphere_set **out);

/* As vb_spheres_read_file from a memory buffer; `name` is used in messages.
 * This is the entry point of the fuzzing targets. */
int vb_spheres_read_buffer(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                           const vb_read_options *opt, vb_sphere_set **out);

/* Checks a set for use as Voronoi input: empty (VB_EINPUT_EMPTY), fewer than
 * `min_count` spheres (VB_EINPUT_TOOFEW; pass 4 for vertices), duplicate
 * spheres (VB_EINPUT_DUPLICATE, both lines named), absurd magnitudes.
 * Contained spheres are legal: they get contained[i] = 1 and warning W701;
 * indices stay stable. Decided exactly on the decimals. */
int vb_spheres_validate(vb_ctx *ctx, vb_sphere_set *set, size_t min_count);

/* A set of n spheres built in memory (a frame of a binary trajectory, a
 * planar cut): x, y, z, r and line zeroed, info zeroed when with_info,
 * source a copy of name. It has no exact decimals (ex .. er NULL), so it is
 * not Voronoi input for the exact side (vb_spheres_validate needs them).
 * VB_OK or VB_ENOMEM; free with vb_spheres_free. */
int vb_spheres_new(vb_ctx *ctx, const char *name, size_t n, int with_info, vb_sphere_set **out);

/* Reads `path` ("-" = stdin) with the options (radii_path, when not NULL,
 * a radii table file to load for it instead of ro->radii) and validates
 * the set with vb_spheres_validate(min_count). On success *out owns the set
 * (free with vb_spheres_free); on failure *out is NULL and the status says
 * why (message in the context). */
int vb_spheres_load(vb_ctx *ctx, const char *path, const vb_read_options *ro,
                    const char *radii_path, size_t min_count, vb_sphere_set **out);

/* A guess, before reading, of how many spheres the file at path holds: for
 * XYZR (one sphere a line, the format decided on the first 4 KiB as the
 * reader decides it) its bytes over the longest line there; for the other
 * text formats its bytes over VB_BYTES_PER_SPHERE_MAX (no text format spends
 * more on an atom's line). Meant as a lower bound; comments, records that
 * are not atoms and dropped waters can break it. 0 for stdin ("-"), a
 * compressed file (gzip, bzip2: by their magic bytes) or one that cannot be
 * opened. For opening a device ahead of the reading
 * (vb_vertices_open_early). */
#define VB_BYTES_PER_SPHERE_MAX 200
size_t vb_spheres_count_hint(const char *path);

struct vb_stage_clock; /* vb_stage_clock.h */

/* vb_spheres_load with its two stages timed on clk (may be NULL): the
 * reading as VB_STAGE_READ, the checks as VB_STAGE_VALIDATE
 * (vb_stage_clock.h; the stage before them ends at the call). */
int vb_spheres_load_clocked(vb_ctx *ctx, const char *path, const vb_read_options *ro,
                            const char *radii_path, size_t min_count, vb_sphere_set **out,
                            struct vb_stage_clock *clk);

/* Frees a set; NULL is allowed. */
void vb_spheres_free(vb_sphere_set *set);

/* Multi-model input (PDB MODEL/ENDMDL, mmCIF pdbx_PDB_model_num) read frame by
 * frame: one frame in memory at a time. */
typedef struct vb_frame_reader vb_frame_reader;

/* Opens a frame reader. Free with vb_frame_reader_close. */
int vb_frame_reader_open(vb_ctx *ctx, const char *path, const vb_read_options *opt,
                         vb_frame_reader **out);

/* Reads the next frame into *out (caller frees). At the end returns VB_OK with
 * *out == NULL. *model_number gets the MODEL serial (or 1 for single-model).
 * When the options name a model, only that frame is returned (VB_EINPUT_MODEL
 * at the end if it never came). Counts of dropped atoms are reported once, at
 * the end. */
int vb_frame_reader_next(vb_ctx *ctx, vb_frame_reader *rd, vb_sphere_set **out,
                         int *model_number);

void vb_frame_reader_close(vb_frame_reader *rd);

/* Loads a radii table file: lines "ELEMENT RADIUS" ('#' comments).
 * Free with vb_radii_free. */
int vb_radii_load(vb_ctx *ctx, const char *path, vb_radii_table **out);
void vb_radii_free(vb_radii_table *t);

/* Exact decimal helpers. vb_decimal_parse parses a full token (no spaces);
 * returns VB_OK, VB_EINPUT_MALFORMED, VB_EINPUT_NONFINITE (nan/inf) or
 * VB_EINPUT_MAGNITUDE (> 18 digits or |exp| out of range). *d gets the nearest
 * double (strtod of the same token). */
int vb_decimal_parse(const char *tok, size_t len, vb_decimal *out, double *d);

/* Compares two decimals exactly: -1, 0, +1. */
int vb_decimal_cmp(vb_decimal a, vb_decimal b);

/* The double nearest a decimal (correctly rounded, as strtod of its
 * digits): the double the readers keep beside an exact value. */
double vb_decimal_double(vb_decimal d);

/* Writes the sphere table of s to f (TSV, `--atoms FILE`): a '#' line
 * naming the source and count, a header line, then one row per sphere:
 * id (0-based, as in vertex, cell and contact files), chain, resname,
 * resseq, icode, atom, element, altloc, serial ('.' for each where the
 * input has no atom records or the field is blank), the 1-based source
 * line, and x, y, z, r as the exact decimals the library computed with
 * (the radius from the radii table for PDB/mmCIF/GRO), or as the doubles
 * (%.17g) in a set without decimals (a trajectory's frame, a channel
 * analysis's copy). VB_OK or VB_EIO. */
int vb_atoms_write(vb_ctx *ctx, FILE *f, const vb_sphere_set *s);

/* Writes d as its exact decimal: digits with a point where the exponent
 * puts one, no exponent notation ("56.068", "-0.005", "1200"), into out
 * (at most 48 characters are needed for any decimal the readers make). */
void vb_decimal_format(vb_decimal d, char *out, size_t size);

#ifdef __cplusplus
}
#endif
#endif
