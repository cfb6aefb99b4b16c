/* The options of the channel analysis, each declared once (geogram's
 * CmdLine::declare_arg): name, value type, range, default and help in one
 * table (channel_options.c) that `vorball channels` parses its command line
 * with and prints as its --help, and that the Python binding reads for its
 * keywords, their checks and its defaults. Input options (--radii, --model,
 * --water, ...) are the readers' and are not here. */
#ifndef VBC_CHANNELS_CONFIG_H
#define VBC_CHANNELS_CONFIG_H

#include <stddef.h>
#include <stdio.h>

#include "vb_device.h"
#include "vb_option.h"
#include "vbc_pore_frame.h"
#include "vbj_jfa.h"

/* Where --help lists an option (vb_option.section). */
enum vbc_opt_section { VBC_SECT_MAIN, VBC_SECT_PORE };

/* A row of the table (vb_option.h; its id an enum vbc_opt_id of
 * channel_options.c; NAMES: at most VBC_MAX_NAMES names). */
typedef vb_option vbc_opt_spec;

#define VBC_MAX_NAMES 64

/* The residues of a membrane that the channel analysis leaves out unless
 * told otherwise (--membrane): OPM/PPM's membrane dummy atoms; phospholipids
 * and sphingomyelin by their CHARMM/Slipids/GROMACS names; sterols; lipid
 * and detergent components of the PDB's chemical dictionary (PC, PE, PG and
 * cardiolipin ligands, monoolein, oleic and palmitic acid; LDAO, DDM, UDM,
 * DM, beta-OG, NG, CHAPS, C8E4, DPC, SDS, HTG, CHS). A membrane around a
 * channel hides the pore's mouths and turns its principal axes; a dummy
 * atom read as N or O fills the pore. */
#define VBC_MEMBRANE_DEFAULT                                                                   \
    "DUM,POPC,POPE,POPG,POPS,POPA,POPI,DPPC,DPPE,DPPG,DPPS,DMPC,DMPE,DMPG,DOPC,DOPE,DOPG,"     \
    "DOPS,DLPC,DLPE,DLPG,DSPC,DSPE,DSPG,SOPC,PLPC,PSM,CHL1,CHOL,CLR,PCW,PEE,PEF,PGW,LHG,CDL,"   \
    "OLC,OLA,PLM,LPP,3PE,LDA,LMT,UDM,DMU,BOG,BNG,CPS,C8E,DPC,SDS,HTG,Y01"

/* Everything `vorball channels` is asked to do besides reading its input:
 * the analysis (opt, pore), the engine, the frames and the outputs. */
typedef struct vbc_channels_config {
    const char *out, *traj, *centrelines, *pymol, *volume, *stats, *png;
    const char *profile, *plot, *occupancy, *html;
    int json, png_axis, fixed_grid, stats_stderr;
    vbc_pore_request pore;
    char ignore_buf[1024];
    const char *ignore[VBC_MAX_NAMES]; /* --ignore: residue names (into ignore_buf) */
    size_t nignore;
    char membrane_buf[1024];
    const char *membrane[VBC_MAX_NAMES]; /* --membrane: residue names (into membrane_buf) */
    size_t nmembrane;
    double probe;
    int grid;
    long f0, f1, fstep;   /* --frames a:b:step (f1 < 0: to the end) */
    int repeat;
    unsigned volume_bit;  /* VBC_F_* of --volume-mask */
    vbj_variant variant;
    vb_device_kind device;
    vbc_options opt;      /* its pore points at `pore` (vbc_channels_check) */
    int axis_refit;       /* --axis-refit: later frames refit the first frame's axis source */
    int keep_ligands;     /* --keep-ligands: keep HETATM ligands (vbc_is_ligand) */
    vbc_axis refit0;      /* that source refitted on the first frame (vbc_axis_refit) */
    double u0[3], c0[3];  /* and the first frame's pore axis */
} vbc_channels_config;

/* The table: *n gets its length. Static. */
const vbc_opt_spec *vbc_channels_options(size_t *n);

/* The option called `name` (its name or alias, "--probe"), or NULL. */
const vbc_opt_spec *vbc_channels_option(const char *name);

/* The option whose Python keyword is `py`, or NULL. */
const vbc_opt_spec *vbc_channels_option_py(const char *py);

/* Fills c with every option's default (the table's `def`). */
void vbc_channels_defaults(vbc_channels_config *c);

/* Parses `value` (NULL for a flag) as option o and stores it in c. Text
 * values are kept by pointer (paths) or copied (--ignore): value must
 * outlive c for a path. Returns 0, or -1 with a message in err ("--grid
 * needs a power of two in 16..1024, not '100'"). */
int vbc_channels_set(vbc_channels_config *c, const vbc_opt_spec *o, const char *value, char *err,
                     size_t errlen);

/* The rules between options (--pymol needs --centerlines, ...), checked
 * once every option is set; then points c->opt.pore at c->pore. Returns 0,
 * or -1 with a message in err. */
int vbc_channels_check(vbc_channels_config *c, char *err, size_t errlen);

/* Writes the options of `section` as --help lines: "  NAME VALUE" in a
 * column of 22, the help wrapped at 80 columns, range and default appended. */
void vbc_channels_help(FILE *f, int section);

#endif
