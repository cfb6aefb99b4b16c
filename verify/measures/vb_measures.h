/* Cell measures: per atom, the volume of its additively weighted Voronoi
 * cell inside its probe-expanded ball (radius R + probe), its
 * solvent-accessible (SAS) area (the part of the expanded sphere inside the
 * cell) and, on request, the contact area of each pair of atoms whose cells
 * share a face inside the expanded balls. Every value is an enclosure
 * lo <= exact <= hi proven by interval arithmetic on enclosures of the exact
 * input decimals (methods: verify/measures/stokes_cell.c in closed form,
 * verify/measures/cell_patches.c by patches where the former cannot decide).
 *
 * The union of the constrained cells is the union of the expanded balls (a
 * point of ball j lies in some cell i with |x - ci| - Ri <= |x - cj| - Rj <=
 * probe), so the volumes add up to the union's volume and the SAS areas to
 * its surface area. */
#ifndef VB_MEASURES_H
#define VB_MEASURES_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

#include "vb.h"
#include "vb_build.h"
#include "vb_spheres.h"

/* Default relative tolerance of --tolerance (see vb_measure_options). */
#define VB_MEASURES_TOLERANCE 1e-6
/* Default patch budget per atom of the patch integration (the atoms the
 * closed forms cannot decide): past it their values stay wider than 1e-6
 * on proteins (W851). */
#define VB_MEASURES_MAX_PATCHES 5000
/* The smallest patch budget per atom that may be asked (--max-patches). */
#define VB_MEASURES_MIN_PATCHES 96

typedef struct vb_measure_options {
    double probe;       /* >= 0, added to every radius (nearest double of the decimal;
                         * the enclosures widen it by one ulp each way) */
    double tolerance;   /* in (0, 1): each value is refined until hi - lo <= tolerance *
                         * max(|value|, 1e-3 * the expanded ball's volume or sphere area) */
    int contacts;       /* nonzero: contact areas too */
    size_t max_patches; /* per atom, 0 (= VB_MEASURES_MAX_PATCHES) or >= VB_MEASURES_MIN_PATCHES:
                         * past it the enclosure stands as proven, wider than asked,
                         * and is counted */
    int threads;        /* 0 = all cores, else 1..VB_MAX_THREADS */
    int patches;        /* nonzero: every atom by direction patches, never in closed form
                         * (the two methods compared in tests) */
    int contacts_both;  /* nonzero (tests): each contact integrated from both atoms' sides
                         * and the two enclosures met (disjoint: VB_EINTERNAL); 0: from the
                         * side that writes it alone (vb_contact), half the work */
    int clock;          /* nonzero: vb_cell_measures.stage_s timed (--stats) */
} vb_measure_options;

/* The stages of one atom's measures, timed with vb_measure_options.clock:
 * the neighbours within reach (the grid and their exact differences); the
 * caps of each neighbour's region (the active neighbours, their pair caps
 * and circles); the arrangement (each region's boundary arcs, vbm_cap_arcs,
 * and the arcs two regions share); the arcs' integrals (both passes and
 * the sums); the patch integration of the atoms the closed forms leave. */
enum { VB_CELL_NEIGHBOURS, VB_CELL_CAPS, VB_CELL_ARRANGE, VB_CELL_INTEGRALS, VB_CELL_PATCHES,
       VB_CELL_NSTAGE };

/* The stages' names as --stats prints them ("cells_<name>_s"). */
extern const char *const vb_cell_stage_name[VB_CELL_NSTAGE];

/* The contact of atoms i < j: the enclosure computed from i's side (with
 * contacts_both, met with the one from j's side). In a periodic run (vb_measure_images)
 * the contact is between atom i and atom j moved by the box shift s (the
 * notation j@(s0,s1,s2) of vb_periodic.h), each periodic face once: i < j,
 * or i == j (an atom meeting its own image) with s lexicographically
 * positive; s is (0,0,0) in open runs. */
typedef struct vb_contact {
    uint32_t i, j;
    double lo, hi;
    int16_t s[3];
} vb_contact;

typedef struct vb_cell_measures {
    size_t n;                        /* atoms */
    double *vol_lo, *vol_hi;         /* n each */
    double *sas_lo, *sas_hi;         /* n each */
    uint8_t *empty;                  /* 1: the constrained cell is empty (contained sphere,
                                      * or one touching a larger one from inside) */
    uint8_t *loose;                  /* 1: a value of the atom stayed wider than asked */
    vb_contact *contacts;            /* ncontacts, ordered by (i, j); only pairs whose hi > 0 */
    size_t ncontacts;
    size_t patches;                  /* direction patches integrated, all atoms (an atom in
                                      * closed form counts its arc pieces) */
    size_t nclosed;                  /* atoms measured in closed form (vbm_cell_stokes); the
                                      * others by direction patches */
    size_t nempty, nloose;
    int periodic;                    /* 1: a periodic run (contacts carry shifts) */
    double stage_s[VB_CELL_NSTAGE];  /* opt->clock: CPU seconds per stage, every thread
                                      * summed (each atom's stages on the monotonic clock,
                                      * scaled to the atom's CPU seconds) */
} vb_cell_measures;

/* Fills opt with the defaults (probe 1.4, tolerance 1e-6, no contacts). */
void vb_measure_defaults(vb_measure_options *opt);

/* The options' ranges, the one check of the command and the bindings:
 * probe >= 0 and finite, tolerance in (0, 1), max_patches 0 or >=
 * VB_MEASURES_MIN_PATCHES, threads in 0..VB_MAX_THREADS. Returns VB_OK, or
 * VB_EMISUSE with the option's range in ctx's message (the first refused,
 * in that order). vb_cell_measures_compute calls it. */
int vb_measure_options_check(vb_ctx *ctx, const vb_measure_options *opt);

/* Computes the measures of every sphere of `set` (validated: its
 * `contained` marks set). On VB_OK *out owns arrays (free with
 * vb_cell_measures_free). Errors: VB_EMISUSE for a negative probe or a
 * tolerance outside (0, 1) (E-numbers through the status), VB_ENOMEM,
 * VB_EINTERNAL if the two sides of a contact disagree (a bug). */
int vb_cell_measures_compute(vb_ctx *ctx, const vb_sphere_set *set, const vb_measure_options *opt,
                             vb_cell_measures *out);

/* The spheres of a periodic run (core/periodic/'s images): spheres
 * 0 .. n0 of the set are the box's atoms, the others their images; sphere
 * k is atom[k] moved by shift[k] times the box edges. */
typedef struct vb_measure_images {
    size_t n0;
    const uint32_t *atom;
    const int16_t (*shift)[3];
} vb_measure_images;

/* vb_cell_measures_compute for the atoms of a periodic run: the set holds
 * the atoms and every image within 2 (Rmax + probe) of an atom (so each
 * atom meets all the expanded balls that can cut its cell); only the n0
 * atoms are measured (out->n = n0) and each contact is met with its other
 * side, that of atom j against atom i moved by -s. img NULL: the open
 * run. Same returns. */
int vb_cell_measures_compute_images(vb_ctx *ctx, const vb_sphere_set *set,
                                    const vb_measure_options *opt, const vb_measure_images *img,
                                    vb_cell_measures *out);

/* Frees what vb_cell_measures_compute allocated (a zeroed struct is fine). */
void vb_cell_measures_free(vb_cell_measures *m);

/* Writes the per-atom table: a header line, then per atom id chain resname
 * resseq atom volume volume_lo volume_hi sas sas_lo sas_hi ('.' where the
 * input has no such field). Each value is the midpoint, then the ends
 * rounded outward to 12 significant digits (the printed interval contains
 * the proven one). Write errors are the stream's (ferror). */
void vb_cell_measures_write_atoms(FILE *f, const vb_sphere_set *set, const vb_cell_measures *m);

/* Writes the contacts table: header, then id1 id2 area area_lo area_hi;
 * in a periodic run (m->periodic) id2 is written j@(dx,dy,dz). */
void vb_cell_measures_write_contacts(FILE *f, const vb_cell_measures *m);

/* The headers and rows of the two tables apart, for tables of several
 * frames: with frames (the header) or frame >= 0 (the rows) a `frame`
 * column comes first; otherwise the bytes of the writers above. */
void vb_cell_measures_write_atoms_header(FILE *f, int frames);
void vb_cell_measures_write_atom_rows(FILE *f, const vb_sphere_set *set, const vb_cell_measures *m,
                                      long frame);
void vb_cell_measures_write_contacts_header(FILE *f, int frames);
void vb_cell_measures_write_contact_rows(FILE *f, const vb_cell_measures *m, long frame);

/* A sum of the measures over a group of atoms (a residue, a chain): each
 * an interval sum of the atoms' enclosures, every addition rounded
 * outward, so it encloses the group's exact sum. */
typedef struct vb_cell_group {
    size_t first;                    /* the group's first atom (its names) */
    size_t natoms;
    double vol_lo, vol_hi, sas_lo, sas_hi;
} vb_cell_group;

/* The residues (atoms of one chain, resseq, insertion code and resname,
 * wherever they lie in the input) or, with by_chain, the chains of `set`,
 * in the order of their first atom. *out is malloc'd (free it); none
 * (NULL, 0) for a set without atom records. VB_OK or VB_ENOMEM. */
int vb_cell_measures_groups(vb_ctx *ctx, const vb_sphere_set *set, const vb_cell_measures *m,
                            int by_chain, vb_cell_group **out, size_t *nout);

/* Writes one JSON object: "atoms" (per atom: id, chain, resname, resseq,
 * icode, atom, volume(_lo, _hi), sas(_lo, _hi) with the TSV's digits,
 * empty, loose) and, for inputs with atom records, "residues" and
 * "chains" (vb_cell_measures_groups: atoms and the sums, printed as the
 * TSV prints a value). With frame >= 0, "frame" and "model" first. No
 * newline after the closing brace. VB_OK or VB_ENOMEM (nothing written);
 * write errors are the stream's. */
int vb_cell_measures_write_json(vb_ctx *ctx, FILE *f, const vb_sphere_set *set,
                                const vb_cell_measures *m, long frame, int model);

/* vb_cell_measures_write_json with the provenance members (tool, input,
 * spheres, options: vb_provenance_write_json) first in the object when
 * prov is not NULL. Same returns. */
int vb_cell_measures_write_json_prov(vb_ctx *ctx, FILE *f, const vb_sphere_set *set,
                                     const vb_cell_measures *m, long frame, int model,
                                     const vb_provenance *prov);

#endif
