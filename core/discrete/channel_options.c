/* The channel analysis's options, declared once (vbc_channels_config.h):
 * the table, its parser, its defaults and its --help. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_frames.h"
#include "vb_numtext.h"
#include "vbc_channels_config.h"

enum vbc_opt_id {
    O_OUT, O_JSON, O_STATS, O_STATS_FILE, O_PROBE, O_GRID, O_FRAMES, O_TRAJ, O_MIN_LENGTH,
    O_MIN_RADIUS, O_LINING_TOL, O_CAVITIES, O_CENTRELINES, O_PYMOL, O_VOLUME, O_VOLUME_MASK,
    O_PNG, O_PNG_NORMAL, O_JFA, O_DEVICE, O_REPEAT, O_AXIS, O_THROUGH, O_SAMPLE, O_END_RADIUS,
    O_NO_PORE, O_IGNORE, O_MEMBRANE, O_PROFILE, O_PLOT, O_HTML, O_FIXED_GRID, O_OCCUPANCY,
    O_AXIS_REFIT, O_KEEP_LIGANDS
};

#define NUM(a, b) (a), (b), NULL
#define NONE 0, 0, NULL

static const vbc_opt_spec table[] = {
    {O_OUT, "-o", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "channel table (CSV; default stdout); columns below", VBC_SECT_MAIN},
    {O_JSON, "--json", NULL, NULL, VB_OPT_FLAG, NONE, NULL, NULL,
     "the table as JSON, with centrelines", VBC_SECT_MAIN},
    {O_STATS, "--stats", NULL, NULL, VB_OPT_FLAG, NONE, NULL, NULL,
     "per-frame statistics (CSV: counts and timings) on stderr", VBC_SECT_MAIN},
    {O_STATS_FILE, "--stats-file", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "the same statistics to FILE", VBC_SECT_MAIN},
    {O_PROBE, "--probe", NULL, "probe", VB_OPT_REAL, NUM(0.0, 20.0), "R", "1.4",
     "solvent radius in A", VBC_SECT_MAIN},
    {O_GRID, "--grid", NULL, "grid", VB_OPT_POW2, NUM(16, 1024), "N", "128",
     "grid side, a power of two", VBC_SECT_MAIN},
    {O_FRAMES, "--frames", NULL, NULL, VB_OPT_FRAMES, NONE, "A:B:S", NULL,
     "frames A, A+S, ... before B (from 0, B excluded; parts optional)", VBC_SECT_MAIN},
    {O_TRAJ, "--traj", "--dcd", NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "coordinates from a DCD, XTC or TRR trajectory (INPUT = its topology; told apart by magic "
     "number); --dcd is the same", VBC_SECT_MAIN},
    {O_MIN_LENGTH, "--min-length", NULL, "min_length", VB_OPT_REAL, NUM(0.0, 1e4), "L", "5",
     "prune centrelines shorter than L A", VBC_SECT_MAIN},
    {O_MIN_RADIUS, "--min-radius", NULL, "min_radius", VB_OPT_REAL, NUM(0.0, 1e4), "R", "0",
     "prune channels whose bottleneck is below R A", VBC_SECT_MAIN},
    {O_LINING_TOL, "--lining-tol", NULL, "lining_tol", VB_OPT_REAL, NUM(0.0, 1e4), "T", "1",
     "an atom lines a point when its surface is within radius + T A", VBC_SECT_MAIN},
    {O_CAVITIES, "--cavities", NULL, "cavities", VB_OPT_FLAG, NONE, NULL, NULL,
     "report cavities too (components that do not reach the surface)", VBC_SECT_MAIN},
    {O_CENTRELINES, "--centerlines", "--centrelines", NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "centrelines as PDB pseudo-atoms, radius in the B-factor", VBC_SECT_MAIN},
    {O_PYMOL, "--pymol", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "PyMOL script drawing them (needs --centerlines) over the molecule and its trajectory "
     "(load_traj); where PyMOL cannot read the input's coordinates (a PSF, GRO, compressed or "
     "XYZR file) the first frame is written beside it as FILE.frame0.pdb", VBC_SECT_MAIN},
    {O_VOLUME, "--volume", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "mask volume, .mrc/.map (MRC) or .vtk; '%d' in the name writes one per frame, else the "
     "first frame only", VBC_SECT_MAIN},
    {O_VOLUME_MASK, "--volume-mask", NULL, NULL, VB_OPT_CHOICE, 0, 0,
     "channel,interior,molecular,atomic,edge", "M", "channel",
     "the mask --volume writes: channel, interior, molecular, atomic or edge",
     VBC_SECT_MAIN},
    {O_PNG, "--png", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "the 2D pipeline stages (paper Fig. 5) on the slice through the centroid of the first "
     "frame", VBC_SECT_MAIN},
    {O_PNG_NORMAL, "--png-normal", NULL, NULL, VB_OPT_CHOICE, 0, 0, "x,y,z", "x|y|z", "x",
     "normal of that slice (x: the slice holds the z axis)", VBC_SECT_MAIN},
    {O_JFA, "--jfa", NULL, "jfa", VB_OPT_CHOICE, 0, 0, "exact,facet,jfa,jfa+1,jfa+2,1+jfa",
     "VARIANT", "exact",
     "exact (the exact diagram by tiles, the fastest engine too), facet (Facet-JFA), jfa, "
     "jfa+1, jfa+2, 1+jfa (approximations: a few voxels may take a wrong label)",
     VBC_SECT_MAIN},
    {O_DEVICE, "--device", NULL, "device", VB_OPT_CHOICE, 0, 0, "auto,gpu,cpu,ref", "D", "auto",
     "auto (a GPU, else ref: on a host without a GPU the plain C twin costs less CPU than the "
     "CPU OpenCL device), gpu, cpu (the CPU OpenCL device) or ref (plain C, same output). If that "
     "OpenCL device cannot be used, the reference runs after warning W804 (W806: OpenCL failed "
     "mid-run, that frame and the rest rerun on the reference)", VBC_SECT_MAIN},
    {O_REPEAT, "--repeat", NULL, NULL, VB_OPT_COUNT, NUM(1, 100000), "N", "1",
     "run every frame N times (timings; outputs written once)", VBC_SECT_MAIN},
    {O_AXIS, "--axis", NULL, "axis", VB_OPT_VEC3, NONE, "X,Y,Z|fixed", NULL,
     "the pore axis (HOLE's cvect); default: the membrane's normal when membrane atoms were "
     "left out, else the C_n symmetry axis of the chains (a subunit's "
     "pore when that is closed), else two stacked chains, else a beta-barrel's axis, else a "
     "through channel, else a principal axis (W810 says which); fixed: later frames sweep the "
     "first frame's axis (the default; --axis-refit refits it)", VBC_SECT_PORE},
    {O_THROUGH, "--through", NULL, "through", VB_OPT_VEC3, NONE, "X,Y,Z", NULL,
     "a point in the pore where the sweep starts (HOLE's cpoint)", VBC_SECT_PORE},
    {O_SAMPLE, "--sample", NULL, "sample", VB_OPT_REAL, NUM(0.01, 5.0), "S", "0.25",
     "A between planes (HOLE's sample)", VBC_SECT_PORE},
    {O_END_RADIUS, "--end-radius", NULL, "end_radius", VB_OPT_REAL, NUM(0.0, 1e3), "R", NULL,
     "end a side where the radius exceeds R A (HOLE's endrad; default: none, the molecular "
     "surface ends it)", VBC_SECT_PORE},
    {O_NO_PORE, "--no-pore", NULL, "no_pore", VB_OPT_FLAG, NONE, NULL, NULL,
     "channels only, no pore sweep", VBC_SECT_PORE},
    {O_IGNORE, "--ignore", NULL, "ignore", VB_OPT_NAMES, NONE, "RES,...", NULL,
     "leave out atoms of these residue names (ligands, ions, ...)", VBC_SECT_PORE},
    {O_MEMBRANE, "--membrane", NULL, "membrane", VB_OPT_NAMES, NONE, "RES,...|none",
     VBC_MEMBRANE_DEFAULT,
     "leave out the membrane: atoms of these residue names (membrane dummy atoms, lipids, "
     "detergents; W809 counts them by name); none keeps every atom", VBC_SECT_PORE},
    {O_PROFILE, "--profile", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "radius profile of every channel and frame (CSV: axial s, arc length, point, radius, "
     "nearest and touching atoms)", VBC_SECT_PORE},
    {O_PLOT, "--plot", NULL, NULL, VB_OPT_PATH, NONE, "FILE.png", NULL,
     "the pore's radius profile (first frame; with several frames also its smallest radius per "
     "frame) drawn by gnuplot from FILE.png.gp (kept; W807 without gnuplot)", VBC_SECT_PORE},
    {O_HTML, "--html", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "a results page that opens offline in a browser: the molecule, channels coloured by radius, "
     "the pore's profile, the figures of each frame and a frame slider", VBC_SECT_PORE},
    {O_FIXED_GRID, "--fixed-grid", NULL, NULL, VB_OPT_FLAG, NONE, NULL, NULL,
     "one grid for every frame, fitted to the first with 5 A to spare (E1 when an atom leaves "
     "it), so volumes add up", VBC_SECT_PORE},
    {O_OCCUPANCY, "--occupancy", NULL, NULL, VB_OPT_PATH, NONE, "FILE", NULL,
     "per voxel the fraction of frames in which it is in a channel or inside a pore sphere "
     "(.mrc/.map float32 or .vtk; needs --fixed-grid)", VBC_SECT_PORE},
    {O_AXIS_REFIT, "--axis-refit", NULL, "axis_refit", VB_OPT_FLAG, NONE, NULL, NULL,
     "trajectories: refit the axis on every frame from the source the first frame found "
     "(membrane, symmetry, chains, barrel, subunit, principal; the sweep's start moves with "
     "it)",
     VBC_SECT_PORE},
    {O_KEEP_LIGANDS, "--keep-ligands", NULL, "keep_ligands", VB_OPT_FLAG, NONE, NULL, NULL,
     "keep the ligands: by default HETATM residues that are no polymer residue (sugars, ions, "
     "cofactors, drugs; not modified or D-amino acids, caps such as ACE, NME, ETA) are left out "
     "before the axis is chosen, as HOLE's examples ignore them, and W811 names them",
     VBC_SECT_PORE},
};

#define NOPT (sizeof table / sizeof table[0])

const vbc_opt_spec *vbc_channels_options(size_t *n)
{
    *n = NOPT;
    return table;
}

const vbc_opt_spec *vbc_channels_option(const char *name)
{
    for (size_t k = 0; k < NOPT; k++)
        if (strcmp(name, table[k].name) == 0 || (table[k].alias && strcmp(name, table[k].alias) == 0))
            return &table[k];
    return NULL;
}

const vbc_opt_spec *vbc_channels_option_py(const char *py)
{
    for (size_t k = 0; k < NOPT; k++)
        if (table[k].py && strcmp(py, table[k].py) == 0)
            return &table[k];
    return NULL;
}

/* A whole string as a non-negative integer, as a double (capped at 1e18:
 * every range here is far below). 0 or -1. */
static int whole_count(const char *s, double *out)
{
    size_t v;
    if (vb_parse_size(s, &v) != 0)
        return -1;
    *out = v > (size_t)1e18 ? 1e18 : (double)v;
    return 0;
}

/* Parses "X,Y,Z" (three numbers). */
static int parse_vec3(const char *s, double v[3])
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *p = buf;
    for (int k = 0; k < 3; k++) {
        char *c = strchr(p, ',');
        if ((k < 2) != (c != NULL))
            return -1;
        if (c)
            *c = '\0';
        if (vb_parse_double(p, &v[k]) != 0 || !isfinite(v[k]) || fabs(v[k]) > 1e6)
            return -1;
        p = c ? c + 1 : p;
    }
    return 0;
}

/* Parses "A:B:S" with each part optional ("10", ":50", "::5", "2:40:2"). */
static int parse_frames(const char *s, long *a, long *b, long *step)
{
    vb_frame_range r;
    if (vb_frame_range_parse(s, &r) != 0)
        return -1;
    *a = r.first;
    *b = r.end;
    *step = r.step;
    return 0;
}

/* The index of word w in the comma-separated list, or -1. */
static int choice_index(const char *list, const char *w)
{
    size_t n = strlen(w);
    int k = 0;
    for (const char *p = list; *p; k++) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncmp(p, w, n) == 0)
            return k;
        if (!e)
            break;
        p = e + 1;
    }
    return -1;
}

/* "a, b or c" from "a,b,c". */
static void choice_words(const char *list, char *out, size_t len)
{
    size_t o = 0, commas = 0;
    for (const char *p = list; *p; p++)
        commas += *p == ',';
    for (const char *p = list; *p && o + 5 < len; p++) {
        if (*p != ',') {
            out[o++] = *p;
            continue;
        }
        const char *sep = --commas ? ", " : " or ";
        o += (size_t)snprintf(out + o, len - o, "%s", sep);
    }
    out[o < len ? o : len - 1] = '\0';
}

static void fmt_range(const vbc_opt_spec *o, char *out, size_t len)
{
    snprintf(out, len, "%g..%g", o->min, o->max);
}

/* Checks and converts the value of o; the typed result in num / v3 / words. */
static int typed(const vbc_opt_spec *o, const char *v, double *num, double v3[3], char *err,
                 size_t errlen)
{
    char r[64];
    switch (o->type) {
    case VB_OPT_FLAG:
    case VB_OPT_PATH:
    case VB_OPT_NAMES:
        return 0;
    case VB_OPT_REAL:
        fmt_range(o, r, sizeof r);
        if (vb_parse_double(v, num) != 0 || !(*num >= o->min && *num <= o->max))
            return snprintf(err, errlen, "%s needs a number in %s (A), not '%s'", o->name, r, v), -1;
        return 0;
    case VB_OPT_COUNT:
    case VB_OPT_POW2:
        fmt_range(o, r, sizeof r);
        if (whole_count(v, num) != 0 || !(*num >= o->min && *num <= o->max) ||
            (o->type == VB_OPT_POW2 && ((unsigned long)*num & ((unsigned long)*num - 1))))
            return snprintf(err, errlen, "%s needs %s in %s, not '%s'", o->name,
                            o->type == VB_OPT_POW2 ? "a power of two" : "an integer", r, v), -1;
        return 0;
    case VB_OPT_CHOICE: {
        *num = choice_index(o->choices, v);
        if (*num < 0) {
            char w[160];
            choice_words(o->choices, w, sizeof w);
            return snprintf(err, errlen, "%s: %s, not '%s'", o->name, w, v), -1;
        }
        return 0;
    }
    case VB_OPT_VEC3:
        if (parse_vec3(v, v3) != 0)
            return snprintf(err, errlen, "%s needs X,Y,Z (three numbers), not '%s'", o->name, v), -1;
        return 0;
    default:
        return 0;
    }
}

/* A list of residue names into buf (1024 bytes) and names[*n]. */
static int set_names(const char *opt, const char *v, char *buf, const char **names, size_t *n,
                     char *err, size_t errlen)
{
    if (strlen(v) >= 1024)
        return snprintf(err, errlen, "%s: list too long", opt), -1;
    strcpy(buf, v);
    *n = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (*n == VBC_MAX_NAMES)
            return snprintf(err, errlen, "%s: at most %d names", opt, VBC_MAX_NAMES), -1;
        names[(*n)++] = tok;
    }
    if (*n == 0)
        return snprintf(err, errlen, "%s needs residue names, not '%s'", opt, v), -1;
    return 0;
}

int vbc_channels_set(vbc_channels_config *c, const vbc_opt_spec *o, const char *v, char *err,
                     size_t errlen)
{
    double num = 0.0, v3[3] = {0, 0, 0};
    if (o->type != VB_OPT_FLAG && !v)
        return snprintf(err, errlen, "%s needs a value", o->name), -1;
    if (o->id == O_AXIS && v && strcmp(v, "fixed") == 0) {
        c->axis_refit = 0; /* the default, named */
        return 0;
    }
    if (typed(o, v, &num, v3, err, errlen) != 0)
        return -1;
    static const unsigned masks[] = {VBC_F_CHANNEL, VBC_F_INTERIOR, VBC_F_MOLECULAR, VBC_F_ATOMIC,
                                     VBC_F_EDGE};
    switch (o->id) {
    case O_OUT: c->out = v; break;
    case O_JSON: c->json = 1; break;
    case O_STATS: c->stats_stderr = 1; break;
    case O_STATS_FILE: c->stats = v; break;
    case O_PROBE: c->probe = num; break;
    case O_GRID: c->grid = (int)num; break;
    case O_FRAMES:
        if (parse_frames(v, &c->f0, &c->f1, &c->fstep) != 0)
            return snprintf(err, errlen, "--frames needs A:B:S (from 0, B > A, S >= 1), not '%s'", v), -1;
        break;
    case O_TRAJ: c->traj = v; break;
    case O_MIN_LENGTH: c->opt.min_length = num; break;
    case O_MIN_RADIUS: c->opt.min_radius = num; break;
    case O_LINING_TOL: c->opt.lining_tol = num; break;
    case O_CAVITIES: c->opt.keep_cavities = 1; break;
    case O_CENTRELINES: c->centrelines = v; break;
    case O_PYMOL: c->pymol = v; break;
    case O_VOLUME: c->volume = v; break;
    case O_VOLUME_MASK: c->volume_bit = masks[(int)num]; break;
    case O_PNG: c->png = v; break;
    case O_PNG_NORMAL: c->png_axis = (int)num; break;
    case O_JFA: vbj_variant_parse(NULL, v, &c->variant); break;       /* one of its words */
    case O_DEVICE: vb_device_kind_parse(NULL, v, &c->device); break; /* one of its words */
    case O_REPEAT: c->repeat = (int)num; break;
    case O_AXIS: {
        double n = sqrt(v3[0] * v3[0] + v3[1] * v3[1] + v3[2] * v3[2]);
        if (!(n > 0.0) || !isfinite(n))
            return snprintf(err, errlen, "--axis needs a nonzero vector, not '%s'", v), -1;
        for (int k = 0; k < 3; k++)
            c->pore.u[k] = v3[k] / n;
        c->pore.have_axis = 1;
        break;
    }
    case O_THROUGH:
        memcpy(c->pore.c, v3, sizeof v3);
        c->pore.have_through = 1;
        break;
    case O_SAMPLE: c->pore.sweep.step = num; break;
    case O_END_RADIUS: c->pore.sweep.end_radius = num; break;
    case O_NO_PORE: c->pore.enabled = 0; break;
    case O_AXIS_REFIT: c->axis_refit = 1; break;
    case O_KEEP_LIGANDS: c->keep_ligands = 1; break;
    case O_IGNORE:
        return set_names(o->name, v, c->ignore_buf, c->ignore, &c->nignore, err, errlen);
    case O_MEMBRANE:
        if (strcmp(v, "none") == 0) {
            c->nmembrane = 0;
            return 0;
        }
        return set_names(o->name, v, c->membrane_buf, c->membrane, &c->nmembrane, err, errlen);
    case O_PROFILE: c->profile = v; break;
    case O_PLOT: c->plot = v; break;
    case O_HTML: c->html = v; break;
    case O_FIXED_GRID: c->fixed_grid = 1; break;
    case O_OCCUPANCY: c->occupancy = v; break;
    default: break;
    }
    return 0;
}

void vbc_channels_defaults(vbc_channels_config *c)
{
    memset(c, 0, sizeof *c);
    c->f1 = -1;
    c->fstep = 1;
    c->pore.enabled = 1;
    char err[160];
    /* Every default lies in its own range (test_channel_options). */
    for (size_t k = 0; k < NOPT; k++)
        if (table[k].def)
            (void)vbc_channels_set(c, &table[k], table[k].def, err, sizeof err);
}

int vbc_channels_check(vbc_channels_config *c, char *err, size_t errlen)
{
    const char *why = NULL;
    if (c->pymol && !c->centrelines)
        why = "--pymol draws the --centerlines file: give both";
    else if (c->stats && c->stats_stderr)
        why = "--stats (stderr) or --stats-file FILE, not both";
    else if (c->occupancy && !c->fixed_grid)
        why = "--occupancy adds frames on one grid: give --fixed-grid";
    else if (c->plot && !c->pore.enabled)
        why = "--plot draws the pore: drop --no-pore";
    else if ((c->pore.have_through || c->pore.sweep.end_radius > 0.0) && !c->pore.enabled)
        why = "--axis/--through/--end-radius set the pore sweep: drop --no-pore";
    if (why)
        return snprintf(err, errlen, "%s", why), -1;
    c->opt.pore = &c->pore;
    return 0;
}

/* Writes text wrapped at `width` columns, continuation lines indented by
 * `indent`, the first line starting at column `col`. A word longer than a
 * line (a list of names) breaks after its commas. */
static void wrap(FILE *f, const char *text, int col, int indent, int width)
{
    const char *p = text;
    int glued = 0; /* the piece continues a word broken after a comma */
    while (*p) {
        const char *w = p;
        while (*w && *w != ' ')
            w++;
        int len = (int)(w - p);
        if (len > width - indent) {
            /* Up to the last comma that fits the rest of this line (or a
             * whole line), at least one name. */
            int room = width - col - (col > indent && !glued), cut = 0;
            for (int k = 0; k < len; k++)
                if (p[k] == ',' && (k + 1 <= room || cut == 0))
                    cut = k + 1;
            if (cut > 0 && cut < len) {
                if (col > indent && col + (glued ? 0 : 1) + cut > width) {
                    fprintf(f, "\n%*s", indent, "");
                    col = indent;
                } else if (col > indent && !glued) {
                    fputc(' ', f);
                    col++;
                }
                fprintf(f, "%.*s", cut, p);
                col += cut;
                p += cut;
                glued = 1;
                continue;
            }
        }
        if (col > indent && (glued ? col + len > width : col + 1 + len > width)) {
            fprintf(f, "\n%*s", indent, "");
            col = indent;
        } else if (col > indent && !glued) {
            fputc(' ', f);
            col++;
        }
        glued = 0;
        fprintf(f, "%.*s", len, p);
        col += len;
        p = *w ? w + 1 : w;
    }
    fputc('\n', f);
}

void vbc_channels_help(FILE *f, int section)
{
    for (size_t k = 0; k < NOPT; k++) {
        const vbc_opt_spec *o = &table[k];
        if (o->section != section)
            continue;
        char head[64], text[1024], range[64] = "";
        snprintf(head, sizeof head, "  %s%s%s", o->name, o->value ? " " : "", o->value ? o->value : "");
        if (o->type == VB_OPT_REAL || o->type == VB_OPT_COUNT || o->type == VB_OPT_POW2)
            snprintf(range, sizeof range, " %g..%g", o->min, o->max);
        if (o->def)
            snprintf(text, sizeof text, "%s (%s%s%sdefault %s)", o->help, range[0] ? "range" : "",
                     range, range[0] ? "; " : "", o->def);
        else if (range[0])
            snprintf(text, sizeof text, "%s (range%s)", o->help, range);
        else
            snprintf(text, sizeof text, "%s", o->help);
        fputs(head, f);
        int col = (int)strlen(head);
        if (col >= 22) {
            fputc('\n', f);
            col = 0;
        }
        fprintf(f, "%*s", 22 - col, "");
        wrap(f, text, 22, 22, 80);
    }
}
