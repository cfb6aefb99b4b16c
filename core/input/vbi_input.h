/* Internal to the input layer (core/read_*.c, detect_format.c, frame_reader.c):
 * the growing sphere set the readers fill, line and token helpers, and the
 * per-format entry points behind vb_spheres_read_buffer.
 *
 * Warnings of the input layer (stable numbers, W701-W719):
 *   W701 a sphere lies inside another (named with both lines)
 *   W702 total of contained spheres when more than ten
 *   W703 water atoms dropped (count)        W704 other alternate locations dropped
 *   W705 atoms of other models ignored      W706 hydrogens dropped (--no-hydrogens)
 *   W707 unknown element, default radius    W708 total of atoms with unknown elements
 *   W709 mmCIF names truncated to 7 characters
 *   W710 atom records after END ignored     W711 a further mmCIF _atom_site loop ignored
 *   W712 spheres of radius 0 dropped        W713 spheres of radius 0 kept as points */
#ifndef VBI_INPUT_H
#define VBI_INPUT_H

#include "vb_hash.h"
#include "vb_spheres.h"

/* Default sphere limit (vb_read_options.max_spheres == 0). */
#define VBI_DEFAULT_MAX_SPHERES ((size_t)50000000)
/* Files above this are refused before reading (VB_EINPUT_TOOLARGE). */
#define VBI_MAX_FILE_BYTES ((size_t)2 << 30)

/* A sphere set under construction. */
typedef struct vbi_builder {
    vb_ctx *ctx;
    const char *name;   /* source name for messages */
    vb_sphere_set *set;
    size_t cap;
    size_t max;         /* sphere limit */
} vbi_builder;

/* Starts an empty set named `name`; with_info allocates atom records.
 * Returns VB_OK or VB_ENOMEM. */
int vbi_builder_init(vbi_builder *b, vb_ctx *ctx, const char *name, size_t max, int with_info);

/* Appends one sphere: exact decimals e[0..3] = x y z r, their doubles d[0..3],
 * the atom record (may be NULL) and the 1-based source line. Returns VB_OK,
 * VB_ENOMEM or VB_EINPUT_TOOLARGE (message set). */
int vbi_builder_push(vbi_builder *b, const vb_decimal e[4], const double d[4],
                     const vb_atom_info *info, long line);

/* Hands the set to *out (drops the atom records when keep_info is 0). */
void vbi_builder_finish(vbi_builder *b, int keep_info, vb_sphere_set **out);

/* Frees a set that will not be finished. */
void vbi_builder_discard(vbi_builder *b);

/* Iterates over the lines of a buffer: *line and *len get each line without its
 * "\n" or "\r\n"; returns 0 at the end. */
typedef struct vbi_lines {
    const char *p, *end;
    long lineno;        /* number of the line last returned */
} vbi_lines;

/* Lines end at "\n", "\r\n" or a lone "\r" (old Mac OS files). */
void vbi_lines_init(vbi_lines *it, const char *buf, size_t len, long first_line);
int vbi_lines_next(vbi_lines *it, const char **line, size_t *len);

/* 3 when buf starts with a UTF-8 byte-order mark (skipped by every text
 * reader), else 0. */
size_t vbi_bom_length(const char *buf, size_t len);

/* Whether buf holds a '\r' not followed by '\n'; vbi_lone_cr_to_lf turns
 * each into '\n' in place (same length, same line numbers), so readers with
 * their own tokenizer (mmCIF) see the lines vbi_lines sees. */
int vbi_has_lone_cr(const char *buf, size_t len);
void vbi_lone_cr_to_lf(char *buf, size_t len);

/* VB_EINPUT_MALFORMED naming the line (counted from first_line as vbi_lines
 * counts) and column of the first NUL byte of buf, else VB_OK: a NUL inside a
 * fixed-column field would otherwise end the field's text early. */
int vbi_check_nul(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line);

/* Next whitespace-separated token of [*p, end): returns its length (0 at the
 * end) and its start in *tok; advances *p. */
size_t vbi_token(const char **p, const char *end, const char **tok);

/* Parses one number token with file:line context; on failure sets the context
 * error naming `what` (e.g. "x coordinate") and returns its code. */
int vbi_parse_number(vb_ctx *ctx, const char *name, long line, const char *what,
                     const char *tok, size_t len, vb_decimal *e, double *d);

/* Parses a whole (blank-trimmed) field as an int32 into *out; returns 0, or
 * -1 leaving *out alone when the field is not a plain integer. */
int vbi_parse_int(const char *s, size_t len, int32_t *out);

/* True when a PDB-style line holds record `rec` ("ATOM", "MODEL", "END",
 * ...): the name, then blanks up to column 6. */
int vbi_pdb_record(const char *line, size_t n, const char *rec);

/* The serial of a MODEL record: the first token after "MODEL" (the standard
 * puts it in columns 11-14, but writers vary, and columns 73-80 may hold an
 * identifier such as "1GRM 124"). 0 when there is none. */
int32_t vbi_pdb_model_serial(const char *line, size_t n);

/* Copies at most cap-1 non-blank-trimmed characters into dst (NUL-ended);
 * returns 1 if the text had to be truncated. */
int vbi_copy_field(char *dst, size_t cap, const char *src, size_t len);

/* The radius of an atom for PDB/mmCIF/GRO/PSF: the first row of opt->radii
 * that matches it (an element row by info->element, a HOLE row by its atom
 * and residue names: radii.c), else the built-in table by element, else
 * the default 1.70 with a warning counted in *unknown (or
 * VB_EINPUT_ELEMENT in strict mode). */
int vbi_radius_for(vb_ctx *ctx, const vb_read_options *opt, const char *name, long line,
                   const vb_atom_info *info, vb_decimal *e, double *d, size_t *unknown);

/* Water residue names dropped unless keep_water. */
int vbi_is_water(const char *resname);

/* 1 when an atom of a water residue is a water model's massless virtual
 * site (TIP4P's MW/OM/EPW, TIP5P's LP1/LP2/EP1/EP2): a point charge, no
 * atom, so no ball (read as one it would swallow its oxygen). */
int vbi_is_virtual_site(const char *resname, const char *name);
/* Hydrogen or deuterium element symbol. */
int vbi_is_hydrogen(const char *element);

/* Distinct inferred elements counted one by one in the W715 line. */
#define VBI_INFERRED_KINDS 12

/* Counts of atoms a reader left out on purpose (or read with an inferred
 * element), reported as one line each. */
typedef struct vbi_dropped {
    size_t water, altloc, hydrogens;
    size_t other_models;      /* atoms */
    size_t other_model_count; /* models */
    size_t unknown_elements;
    size_t after_end;         /* atom records after END */
    size_t zero_dropped;      /* radius-0 spheres left out (--zero-radius drop) */
    size_t zero_points;       /* radius-0 spheres kept as points */
    size_t virtual_sites;     /* water models' massless sites left out (W727) */
    size_t inferred;          /* atoms whose element was inferred (W714, W715) */
    size_t inferred_alignment;/* of those, two-letter elements from column 13 alone (W716) */
    char inferred_el[VBI_INFERRED_KINDS][4]; /* the inferred elements and their counts */
    size_t inferred_count[VBI_INFERRED_KINDS];
    long open_model_line;     /* the MODEL record of a taken model the input ends
                                 inside (no ENDMDL, no END): W735 */
} vbi_dropped;

/* How an element was inferred (element_infer.c says the rules). */
enum { VBI_INFER_NONE = 0, VBI_INFER_RESIDUE, VBI_INFER_ALIGNMENT, VBI_INFER_LETTER };
/* How a PDB file lays out atom names in columns 13-16. */
enum { VBI_LAYOUT_UNKNOWN = 0, VBI_LAYOUT_PDB, VBI_LAYOUT_LEFT };

/* True for a residue whose atoms are all H C N O S P (amino acids and their
 * force-field variants, nucleotides, water): the first letter of an atom
 * name is its element. */
int vbi_plain_residue(const char *resname);

/* Infers the element of an atom whose file does not give it: name4 is
 * columns 13-16 of a PDB record (NULL for formats without columns), name
 * the trimmed atom name, resname its residue, layout what
 * vbi_pdb_name_layout said of the file. Writes the symbol (upper case, ""
 * when the name has no letter) and returns VBI_INFER_RESIDUE,
 * VBI_INFER_ALIGNMENT, VBI_INFER_LETTER or VBI_INFER_NONE. */
int vbi_infer_element(const char *name4, const char *name, const char *resname, int layout,
                      char element[4]);

/* The answers of vbi_infer_element kept for the names met last: a
 * trajectory's topology repeats a few pairs (a water's three atoms) tens of
 * thousands of times, and a protein's PDB file its residues' atoms. The key
 * is everything the function reads: the four name columns (PDB; "" for
 * files without them: GRO, PSF, mmCIF, PQR), the atom and residue names
 * and the layout. Zero it before the first use. */
typedef struct vbi_infer_memo {
    struct {
        char name4[5], name[8], resname[8], element[4];
        int layout, how, used;
    } e[512]; /* a protein's residues hold a few hundred keys */
} vbi_infer_memo;

/* vbi_infer_element(name4, name, resname, layout, element) (name4 NULL or
 * its four columns), answered from m when it holds the key (the same
 * answer: the function reads nothing else). m may be NULL (a memo that
 * could not be allocated): the function answers. */
int vbi_infer_element_memo(vbi_infer_memo *m, const char *name4, const char *name,
                           const char *resname, int layout, char element[4]);

/* Whether the amino acids and nucleotides of a PDB text start one-letter
 * names in column 14 (VBI_LAYOUT_PDB, the convention) or 13
 * (VBI_LAYOUT_LEFT: CHARMM, NAMD and other writers that left-justify);
 * VBI_LAYOUT_UNKNOWN when it has none. Looks at up to 2000 such atoms. */
int vbi_pdb_name_layout(const char *buf, size_t len);

/* Records that the element of `info` (atom of file:line) was inferred
 * (`how`): VB_EINPUT_INFERRED under --strict-elements; otherwise counted in
 * dr, with warning W714 for the first such atom and W716 for the first
 * two-letter element taken from alignment alone. */
int vbi_element_inferred(vb_ctx *ctx, const vb_read_options *opt, const char *file, long line,
                         const vb_atom_info *info, int how, vbi_dropped *dr);

/* An atom a reader keeps (PDB, GRO): its inferred element recorded
 * (vbi_element_inferred, unless how is VBI_INFER_NONE), its radius put in
 * e[3] and d[3] (vbi_radius_for) and the sphere pushed to b. VB_OK or the
 * first error. */
int vbi_atom_keep(vb_ctx *ctx, const vb_read_options *opt, const char *name, long line,
                  const vb_atom_info *info, int how, vbi_dropped *dr, vbi_builder *b,
                  vb_decimal e[4], double d[4]);

/* Warning W715: how many atoms had their element inferred, per element. */
void vbi_report_inferred(vb_ctx *ctx, const char *name, const vbi_dropped *dr);


/* The zero-radius policy of opt for a format, AUTO resolved: points for PQR,
 * an error elsewhere. Returns VB_ZERO_RADIUS_ERROR, _POINT or _DROP. */
int vbi_zero_radius_policy(const vb_read_options *opt, vb_format fmt);

/* Applies the policy to one sphere of radius `r`: returns 1 when the reader
 * should leave it out (counted in dr), 0 when it is pushed (a radius-0 point
 * is counted; a refused one is left for vb_spheres_validate to name). */
int vbi_zero_radius_skip(int policy, vb_decimal r, vbi_dropped *dr);

/* Emits the one-line warnings W703..W706, W708 (the unknown-element total)
 * and W710 for nonzero counts. */
void vbi_report_dropped(vb_ctx *ctx, const char *name, const vbi_dropped *dr);

/* Model selection over MODEL/ENDMDL blocks (PDB, PQR) or runs of one
 * pdbx_PDB_model_num (mmCIF): `want` is the requested serial, 0 the first. */
typedef struct vbi_models {
    int want;
    int seen_model; /* a model block was met */
    int in_model;   /* inside a block */
    int taking;     /* atoms of the current block are read */
    int found;      /* the wanted model was met */
    int by_ordinal; /* want counts blocks (1 = first) instead of naming a serial */
    int blocks;     /* blocks met so far */
    int taken_serial; /* serial of the block read (1 for the implicit model) */
} vbi_models;

void vbi_models_init(vbi_models *m, int want);
/* A block with this serial starts; a skipped block is counted in dr. */
void vbi_models_begin(vbi_models *m, int serial, vbi_dropped *dr);
void vbi_models_end(vbi_models *m);
/* True when atoms met now belong to the wanted model. */
int vbi_models_takes(const vbi_models *m);
/* VB_EINPUT_MODEL (message set) when the wanted model never came. */
int vbi_models_check(vb_ctx *ctx, const char *name, const vbi_models *m);

/* Ends a reader's pass over the builder: unless rc is already a failure,
 * vbi_models_check on m; then the set goes to *out with its atom records, or
 * is discarded and the failure returned. */
int vbi_builder_close(vbi_builder *b, const vbi_models *m, int rc, vb_sphere_set **out);

/* The records a PDB or PQR reader acts on. */
typedef enum vbi_record {
    VBI_REC_OTHER,
    VBI_REC_MODEL,
    VBI_REC_ENDMDL,
    VBI_REC_END,
    VBI_REC_ATOM /* ATOM or HETATM */
} vbi_record;

/* What record s[0..n) is; is(s, n, rec) says whether it holds record `rec`
 * (vbi_pdb_record for PDB columns, a whole-token match for PQR). */
vbi_record vbi_record_kind(int (*is)(const char *, size_t, const char *), const char *s,
                           size_t n);

/* Which atom records of a PDB or PQR file are read: those of the wanted
 * model (MODEL/ENDMDL blocks), none after END. */
typedef struct vbi_atom_scan {
    vbi_models models;
    int ended;       /* an END record was met: what follows is not this entry */
    long model_line; /* line of the last MODEL record (0: none yet) */
} vbi_atom_scan;

void vbi_atom_scan_init(vbi_atom_scan *s, int want);
/* Feeds one record of line lineno (model_serial: the serial of a MODEL
 * record, else ignored). Returns 1 for an atom record the reader parses, 0
 * for any other record (MODEL, ENDMDL and END update the scan; atoms of
 * other models or after END are counted in dr). */
int vbi_atom_scan_takes(vbi_atom_scan *s, vbi_record rec, int32_t model_serial, long lineno,
                        vbi_dropped *dr);

/* Starts a PDB or PQR reader's pass: *out = NULL, b ready for up to
 * opt->max_spheres spheres with their atom records (vbi_builder_init), scan
 * taking opt->model. Returns VB_OK or vbi_builder_init's failure. */
int vbi_atom_parse_begin(vb_ctx *ctx, const char *name, const vb_read_options *opt,
                         vbi_builder *b, vbi_atom_scan *scan, vb_sphere_set **out);

/* Ends the pass vbi_atom_parse_begin started: when the input ended inside
 * the taken model (no ENDMDL, no END after it), records its MODEL line in dr
 * for warning W735 (the frame reader clears it for blocks that did not end
 * the input); then vbi_builder_close(b, &scan->models, rc, out). */
int vbi_atom_parse_end(vbi_builder *b, const vbi_atom_scan *scan, vbi_dropped *dr, int rc,
                       vb_sphere_set **out);

/* Alternate locations, per residue (chain, resseq, icode): blank is always
 * kept, and of the lettered ones the most occupied, ties to the first met
 * in the residue (the rule of Biopython and PyMOL). Readers that know the
 * occupancies offer them first (vbi_altloc_offer); without an offer the
 * first met is kept. */
typedef struct vbi_altloc_res {
    char chain[8];
    int32_t resseq;
    char icode;
    char kept;        /* the kept location's letter */
    double occupancy; /* of the kept location's most occupied atom offered */
} vbi_altloc_res;

typedef struct vbi_altloc {
    vbi_altloc_res *res;   /* residues that had a lettered location, as met */
    size_t cap, n;         /* res allocated (VB_ARRAY_FIT), held */
    vb_hash h;             /* items of res by chain, number and insertion code */
    size_t last;           /* the residue of the previous lettered atom (SIZE_MAX: none) */
} vbi_altloc;

/* The residue is remembered for the whole file, so a block of location B
 * that comes back after other residues is still dropped beside A. */
void vbi_altloc_init(vbi_altloc *a);
void vbi_altloc_free(vbi_altloc *a);
/* Offers a lettered atom's occupancy (blank: a negative value): its
 * location becomes the residue's kept one when it is the residue's first
 * offer or more occupied than any offered before. 0, or -1 when out of
 * memory. An atom without a letter is ignored. */
int vbi_altloc_offer(vbi_altloc *a, const vb_atom_info *info, double occupancy);
/* 1 when the atom's alternate location is the one kept, 0 when it is
 * dropped, -1 when out of memory. */
int vbi_altloc_keeps(vbi_altloc *a, const vb_atom_info *info);

/* The atoms a reader leaves out on purpose, tested in this order: water
 * (unless opt->keep_water), other alternate locations (alt NULL: the format
 * has none), hydrogens (opt->drop_hydrogens). Returns 1 when the atom is
 * left out (counted in dr), 0 when it is read, -1 when out of memory. */
int vbi_atom_dropped(const vb_read_options *opt, vbi_altloc *alt, const vb_atom_info *info,
                     vbi_dropped *dr);

/* vb_spheres_validate, with the contained spheres marked but named (W701,
 * W702) only when warn_contained: the frame source names them for the
 * first frame that has any and counts the others (one line for a
 * trajectory, not one per frame). */
int vbi_spheres_validate(vb_ctx *ctx, vb_sphere_set *s, size_t min_count, int warn_contained);

/* Content detection, the one path of every reader (whole buffers and
 * streams alike): lines are fed one by one, whole, until the format is
 * decided - GRO by its first three lines, mmCIF and XYZR by the first
 * record, PDB against PQR by the first VBI_DETECT_ATOM_LINES atom records,
 * however many header lines come before them. No byte budget: a stream is
 * read as far as the decision needs. */
typedef struct vbi_detector {
    long lines;             /* lines fed */
    int gro;                /* 1 GRO, -1 not GRO, 0 undecided */
    int seen;               /* a record (non-blank, non-'#' line) was met */
    int other_done;         /* the non-GRO decision is made */
    vb_format other;        /* VB_FMT_MMCIF or VB_FMT_XYZR when the first record said so */
    int atoms, pdb_votes, pqr_votes, records;
} vbi_detector;

void vbi_detector_init(vbi_detector *d);
/* Feeds one whole line (without its terminator); returns 1 once the format
 * is decided (later lines would not change it). */
int vbi_detector_line(vbi_detector *d, const char *line, size_t n);
/* Feeds the whole lines of buf (split as vbi_lines splits them; buf must
 * end at a line end or at the end of the input); returns 1 once decided. */
int vbi_detector_feed(vbi_detector *d, const char *buf, size_t len);
/* The decision on the lines fed so far, into *out. Returns VB_OK,
 * VB_EINPUT_EMPTY (only blank and '#' lines) or VB_EINPUT_FORMAT (nothing
 * fits); sets no message. PDB header records without atoms are VB_FMT_PDB
 * (its reader says "no atoms"). */
int vbi_detector_result(const vbi_detector *d, vb_format *out);

/* vbi_detector over the whole buffer: returns as vbi_detector_result. */
int vbi_detect_format(const char *buf, size_t len, vb_format *out);

/* True when the line is one of the common PDB records (HEADER, REMARK,
 * CRYST1, ATOM, END, ...). */
int vbi_pdb_header_record(const char *line, size_t n);

/* Binary trajectories, by magic number. */
enum { VBI_TRAJ_NONE = 0, VBI_TRAJ_DCD, VBI_TRAJ_XTC, VBI_TRAJ_TRR };
/* The trajectory the first bytes announce (XTC 1995/2023 or TRR 1993 as
 * big-endian integers, DCD an 84-byte record "CORD"), or VBI_TRAJ_NONE. */
int vbi_trajectory_kind(const unsigned char *p, size_t n);
/* "XTC", "TRR", "DCD". */
const char *vbi_trajectory_name(int kind);
/* True when the text is a PSF topology (first word "PSF"). */
int vbi_is_psf(const char *buf, size_t len);
/* VB_EINPUT_NOSPHERES (message naming what to give with it) when buf is a
 * binary trajectory or a PSF topology: inputs that hold no spheres by
 * themselves. VB_OK otherwise. Called before any text is parsed. */
int vbi_refuse_nonspheres(vb_ctx *ctx, const char *name, const char *buf, size_t len);

/* True when a line has GRO's atom layout: x, y, z decimals from column 21
 * at a fixed spacing. */
int vbi_gro_atom_fits(const char *line, size_t n);
/* Sets the context message for a failed detection and returns rc. */
int vbi_detect_error(vb_ctx *ctx, const char *name, int rc);

/* Per-format readers over a whole buffer. */
int vbi_read_xyzr(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                  const vb_read_options *opt, vb_sphere_set **out);
/* The box of a PDB CRYST1 line (a b c alpha beta gamma): 1 and *box set
 * when it gives one (the unit cube 1 1 1 of NMR models gives none), 0
 * otherwise. */
int vbi_pdb_cryst1_box(const char *line, size_t n, vb_box *box);
/* The PDB reader on part of a file: lines are numbered from first_line, and
 * what it leaves out is added to *dr instead of being reported. */
int vbi_pdb_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out);
int vbi_read_mmcif(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                   const vb_read_options *opt, vb_sphere_set **out);
/* The PQR reader on part of a file, as vbi_pdb_parse. */
int vbi_pqr_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out);
/* The mmCIF reader adding to *dr. ordinal > 0 reads the ordinal-th model
 * (frame readers; VB_EINPUT_MODEL past the last) instead of opt->model;
 * *serial (may be NULL) gets the model number read. */
int vbi_mmcif_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                    const vb_read_options *opt, int ordinal, vbi_dropped *dr, int *serial,
                    vb_sphere_set **out);

/* The GRO reader on one frame at the start of buf (lines numbered from
 * first_line; what it leaves out is added to *dr); *consumed gets the bytes
 * of the frame. */
int vbi_gro_parse(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line,
                  const vb_read_options *opt, vbi_dropped *dr, vb_sphere_set **out,
                  size_t *consumed);
/* A GRO file: frame opt->model (1 = the first), the others counted. */
int vbi_read_gro(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                 const vb_read_options *opt, vb_sphere_set **out);
/* Replaces *set - atoms read from the mmCIF text buf, atom i of chain
 * asym[i] (label_asym_id) - by the copies of biological assembly `id`
 * (assembly.c): coordinates moved by the operators exactly, E107 for one
 * beyond 18 significant digits, VB_EINPUT_ASSEMBLY when the assembly, an
 * operator or its expression is absent or malformed, VB_EINPUT_TOOLARGE past
 * `max` spheres. On failure *set is left as it was. */
int vbi_assembly_build(vb_ctx *ctx, const char *name, const char *buf, size_t len, int id,
                       const char (*asym)[8], size_t max, vb_sphere_set **set);

/* The PSF reader (read_psf.c): the !NATOM section as a sphere set with
 * zero coordinates (a topology: not for vb_spheres_validate), radii from
 * the elements of the masses. */
int vbi_read_psf(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                 const vb_read_options *opt, vb_sphere_set **out);

/* Multiplies a decimal by ten exactly (nm to Angstrom) and sets *d to the
 * double nearest the result. Returns VB_OK. */
int vbi_decimal_times_ten(vb_decimal *e, double *d);

/* Reads a whole file ("-" = stdin) into a NUL-terminated buffer, refusing
 * more than VBI_MAX_FILE_BYTES (decompressed: vbi_open_input). Caller frees
 * *buf. */
int vbi_slurp(vb_ctx *ctx, const char *path, char **buf, size_t *len);

/* Compression of a stream, told by its first bytes. */
enum { VBI_PLAIN = 0, VBI_GZIP, VBI_BZIP2 };
/* VBI_GZIP for 1f 8b, VBI_BZIP2 for "BZh1".."BZh9", else VBI_PLAIN. */
int vbi_compression_of(const unsigned char *p, size_t n);
/* "gzip", "bzip2" or "plain". */
const char *vbi_compression_name(int kind);

/* Opens `path` ("-" = stdin) as the bytes it holds: gzip and bzip2 data
 * (by magic number, whatever the name; concatenated streams too) come out
 * decompressed. A plain file is its own stream (seekable); stdin and
 * compressed input are read-only streams that seek forward only. NULL with
 * the context error set when it cannot be opened (VB_EIO; a directory is
 * named as one) or on VB_ENOMEM; *kind (may be NULL) gets VBI_PLAIN,
 * VBI_GZIP or VBI_BZIP2. Damaged compressed data makes reads fail with the
 * context error VB_EINPUT_COMPRESSED (E113) set; bytes after the end of the
 * last stream are ignored with warning W719. Close with fclose. */
FILE *vbi_open_input(vb_ctx *ctx, const char *path, int *kind);

/* The error to return when a read from a vbi_open_input stream failed:
 * VB_EINPUT_COMPRESSED when the decompressor already said why, else
 * VB_EIO "read error" (message set). Call with errno as the read left it. */
int vbi_input_read_error(vb_ctx *ctx, const char *path);

#endif
