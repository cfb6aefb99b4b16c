/* The catalogue of every diagnostic number vorball prints: errors E<n> and
 * warnings W<n>. A number is stable once released: tests and users match the
 * number, not the wording. Add a new number here, in the range of its room,
 * before using it; never reuse a retired one.
 *
 * Ranges:
 *   E1-E9      status categories (vb.h enum vb_status), printed as E<category>
 *   E101-E139  input errors (extended VB_EINPUT codes, exit 10 + detail)
 *   E140-E149  resource limits and pipeline errors
 *   E150-E159  MPI scale-out
 *   W701-W739  input layer (readers, element inference, validation)
 *   W740-W749  vertex files and verify
 *   W750-W759  device layer (program cache, device memory, fault fallback)
 *   W760-W779  vertex pipeline (device fallback, certification, topology)
 *   W780-W799  discrete Voronoi (JFA, Facet-JFA, exact engines) and crosscheck
 *   W800-W829  channels and trajectories
 *   W830-W839  MPI scale-out
 *   W850-W859  cell measures
 *
 * VB_DIAG_LIST(X) expands X(kind, number, name, exit, meaning) for every
 * entry (exit: the status of `vorball` for an error, 0 for a warning), so
 * the README table is checked against one list (tests/core/test_diag_readme.c,
 * which also prints it) and the CLI takes its exit codes from it;
 * every entry is also a name, VB_<kind>_<name> (VB_W_DEVICE_FALLBACK = 760),
 * which every vb_warn call uses instead of the bare number. Errors are
 * raised through their status codes (vb.h): vb_diag_number maps those to
 * the E numbers. */
#ifndef VB_DIAG_H
#define VB_DIAG_H

#define VB_DIAG_LIST(X)                                                                                  \
    X(E, 1, EINPUT, 10, "bad input")                                                                     \
    X(E, 2, EDEGENERATE, 7, "degenerate input for the operation")                                        \
    X(E, 3, EPREC, 8, "precision limit reached")                                                         \
    X(E, 4, ENOMEM, 4, "out of memory")                                                                  \
    X(E, 5, EDEVICE, 5, "OpenCL device failure that could not fall back")                                \
    X(E, 6, EINTERNAL, 6, "internal error (a bug: please report it)")                                    \
    X(E, 7, EMISUSE, 2, "misuse of an option or of the API")                                             \
    X(E, 8, EIO, 3, "file cannot be opened, read or written")                                            \
    X(E, 9, EMISMATCH, 1, "a check ran and found a difference")                                          \
    X(E, 101, INPUT_MALFORMED, 11, "malformed line")                                                     \
    X(E, 102, INPUT_NONFINITE, 12, "NaN or infinite value")                                              \
    X(E, 103, INPUT_RADIUS, 13, "radius < 0, or 0 where --zero-radius does not accept it")               \
    X(E, 104, INPUT_DUPLICATE, 14, "duplicate sphere")                                                   \
    X(E, 105, INPUT_EMPTY, 15, "empty input (no spheres; verify: no vertex lines)")                      \
    X(E, 106, INPUT_TOOFEW, 16, "fewer than 4 spheres")                                                  \
    X(E, 107, INPUT_MAGNITUDE, 17, "|coordinate| > 1e9, radius > 1e6 or over 18 significant digits")     \
    X(E, 108, INPUT_ELEMENT, 18, "unknown element (--strict-elements)")                                  \
    X(E, 109, INPUT_FORMAT, 19, "format not recognised")                                                 \
    X(E, 110, INPUT_TOOLARGE, 20, "input too large (a file over 2 GiB, or too many spheres)")            \
    X(E, 111, INPUT_MODEL, 21, "requested model absent")                                                 \
    X(E, 112, INPUT_INFERRED, 22, "element column blank: it would be guessed (--strict-elements)")       \
    X(E, 113, INPUT_COMPRESSED, 23, "gzip or bzip2 data damaged or cut short")                           \
    X(E, 114, INPUT_NOSPHERES, 24, "a trajectory or topology alone: no spheres (give both)")             \
    X(E, 115, INPUT_TRAJECTORY, 25, "XTC, TRR or DCD data damaged")                                      \
    X(E, 116, INPUT_TOPOLOGY, 26, "trajectory and topology disagree (atom count)")                       \
    X(E, 117, INPUT_ASSEMBLY, 27, "--assembly: absent, or its operators malformed")                      \
    X(E, 118, INPUT_SELECT, 28, "--select: malformed expression (position given) or no atom selected")  \
    X(E, 120, INPUT_BOX, 30, "--periodic: no box (file or --box), or a malformed or flat one")          \
    X(E, 127, INPUT_FRAMES_MEMORY, 37, "channels: frames in flight over VORBALL_FRAMES_MEMORY: says MiB a frame") \
    X(E, 130, INPUT_REFERENCE_SIZE, 40, "more spheres than `reference` takes without --force")           \
    X(E, 131, INPUT_SCALE, 41, "a radius below 1e-50 of the extent: beyond the sampler's doubles")       \
    X(E, 132, INPUT_TOL, 42, "--tol below 1e-12 of the extent: finer than the sampler resolves")         \
    X(E, 133, INPUT_PAGE_SIZE, 43, "vertices --html: over 2000 spheres, too many for a results page")      \
    X(E, 135, INPUT_BOX_SMALL, 45, "periodic box too small: its cells reach past 4 box heights")        \
    X(E, 140, MEMORY_ESTIMATE, 44, "not enough memory for the input: refused before the work starts")    \
    X(E, 142, DEVICE_MEMORY, 46, "device memory budget too small for the input: says how much")          \
    X(E, 150, MPI_FAILED, 50, "MPI failed between ranks: the job is aborted")                            \
    X(E, 151, MPI_COMMAND, 2, "the command runs on one process only, not on several MPI ranks")          \
    X(E, 152, MPI_STDIN, 2, "under MPI every rank reads the input: give a file, not stdin")              \
    X(W, 701, CONTAINED, 0, "a sphere lies strictly inside another: its cell is empty")                  \
    X(W, 702, CONTAINED_COUNT, 0, "count of spheres inside others")                                      \
    X(W, 703, WATER_DROPPED, 0, "water atoms dropped")                                                   \
    X(W, 704, ALTLOC_DROPPED, 0, "atoms of other alternate locations dropped")                           \
    X(W, 705, MODELS_IGNORED, 0, "atoms of other models ignored")                                        \
    X(W, 706, HYDROGENS_DROPPED, 0, "hydrogen atoms dropped (--no-hydrogens)")                           \
    X(W, 707, ELEMENT_UNKNOWN, 0, "unknown element: default radius used")                                \
    X(W, 708, ELEMENT_UNKNOWN_COUNT, 0, "count of atoms with an unknown element")                        \
    X(W, 709, NAMES_TRUNCATED, 0, "atom, residue or chain names truncated")                              \
    X(W, 710, AFTER_END, 0, "atom records after END ignored")                                            \
    X(W, 711, CIF_BLOCK_IGNORED, 0, "a further mmCIF _atom_site loop ignored")                           \
    X(W, 712, ZERO_DROPPED, 0, "spheres of radius 0 dropped (--zero-radius drop)")                       \
    X(W, 713, ZERO_POINTS, 0, "spheres of radius 0 kept as point sites")                                 \
    X(W, 714, ELEMENT_INFERRED, 0, "element column blank: element inferred from the atom name")          \
    X(W, 715, ELEMENT_INFERRED_COUNT, 0, "count of atoms whose element was inferred")                    \
    X(W, 716, ELEMENT_ALIGNMENT, 0, "a two-letter element read from the name's alignment alone")         \
    X(W, 717, ELEMENT_FROM_MASS, 0, "PSF: elements taken from the atom masses")                          \
    X(W, 718, TRR_NO_COORDINATES, 0, "TRR frames without coordinates skipped")                           \
    X(W, 719, COMPRESSED_TRAILING, 0, "bytes after the end of gzip/bzip2 data ignored")                  \
    X(W, 720, REFERENCE_SLOW, 0, "exact reference on a large input: may take very long")                 \
    X(W, 721, ASSEMBLY_CHAINS, 0, "--assembly: chains of the file outside the assembly left out")        \
    X(W, 722, TANGENT_INSIDE, 0, "a sphere touches a larger one from inside: a point or segment cell, kept") \
    X(W, 723, TANGENT_INSIDE_COUNT, 0, "count of spheres touching a larger one from inside")             \
    X(W, 727, VIRTUAL_SITES_DROPPED, 0, "massless virtual sites of water models left out")                \
    X(W, 735, MODEL_OPEN_AT_END, 0, "the input ends inside a MODEL (no ENDMDL/END): truncated?")         \
    X(W, 750, PROGRAM_CACHE_BAD, 0, "a cached OpenCL program cannot be used: rebuilt from source")       \
    X(W, 751, JFA_DEVICE_FAILED, 0, "OpenCL failed mid-run in jfa: the rest runs on the reference")      \
    X(W, 752, COVER_GROUP_CPU, 0, "VORBALL_COVER_KERNEL=group ignored on a CPU device")                 \
    X(W, 760, DEVICE_FALLBACK, 0, "no usable OpenCL device: vertices on the reference backend")          \
    X(W, 761, CAND_OVERFLOW, 0, "candidates did not fit a sampling grid cell")                           \
    X(W, 762, DEVICE_FAILED_RERUN, 0, "OpenCL device failed mid-run: rerun on the reference")            \
    X(W, 763, CERT_REJECTED, 0, "the certifier rejected candidates")                                     \
    X(W, 765, TOPO_UNPAIRED, 0, "trisector edges that could not be paired, or vertex faces not decided") \
    X(W, 766, ARCS_UNDECIDED, 0, "arcs that could not be traced exactly: the list is not proven closed") \
    X(W, 767, CERT_FILTER_DEVICE, 0, "certification filter failed on the device: judged on the host")      \
    X(W, 780, JFA_SEEDS_LOST, 0, "seeds share their start pixel with a nearer seed")                     \
    X(W, 781, JFA_DEVICE_FALLBACK, 0, "no usable OpenCL device: jfa on the reference backend")           \
    X(W, 782, FACET_START_FINE, 0, "Facet-JFA cannot start coarser than n")                              \
    X(W, 783, PNG_EXTENSION, 0, "--png FILE named as another image format: PNG data written")            \
    X(W, 790, CROSSCHECK_POWER, 0, "radii differ: compared with CGAL's power diagram (ids only)")        \
    X(W, 791, CROSSCHECK_FLAT, 0, "the centres span fewer than 3 dimensions: no vertices")               \
    X(W, 792, CROSSCHECK_HIDDEN, 0, "spheres hidden in the power diagram (no power cell)")               \
    X(W, 793, CROSSCHECK_REJECTED, 0, "lines marked rejected are not compared")                          \
    X(W, 801, DCD_PARTIAL_FRAME, 0, "DCD ends with less than a frame (cut or stray bytes): ignored")     \
    X(W, 802, VOLUME_FIRST_FRAME, 0, "volume file holds the first frame only")                           \
    X(W, 803, VOXEL_COARSE, 0, "voxel edge coarser than the probe radius")                               \
    X(W, 804, CHANNELS_DEVICE_FALLBACK, 0, "no usable OpenCL device: channels on the reference backend") \
    X(W, 806, CHANNELS_DEVICE_FAILED, 0, "OpenCL failed mid-run: rest of channels on reference")         \
    X(W, 807, PLOT_NO_GNUPLOT, 0, "gnuplot not found or failed: plot script kept, no PNG")               \
    X(W, 808, PORE_NOT_FOUND, 0, "no pore: no path crosses the molecule walled by its atoms")            \
    X(W, 809, ATOMS_IGNORED, 0, "atoms left out by --membrane or --ignore (count per name)")             \
    X(W, 810, PORE_AXIS_FOUND, 0, "note: where the pore's axis came from (symmetry, barrel, ...)")       \
    X(W, 811, LIGANDS_LEFT_OUT, 0, "channels: ligands (HETATM, no polymer residue) left out, per name")  \
    X(W, 812, MEMBRANE_NOT_FLAT, 0, "channels: membrane atoms left out make no flat, wide membrane: no normal axis") \
    X(W, 829, PAGE_FULL, 0, "results page full: later frames left out of it (the tables have them)")    \
    X(W, 830, MPI_SAMPLING_RANK0, 0, "--proposer sampling does not split: rank 0 runs it alone")         \
    X(W, 831, MPI_STOPPED, 0, "a rank failed: every rank stopped (the error names the rank)")                   \
    X(W, 850, CELL_EMPTY, 0, "cells: an atom's constrained cell is empty: its measures are 0")          \
    X(W, 851, CELL_LOOSE, 0, "cells: values left wider than --tolerance (patch budget spent)")

/* Retired numbers, never to be used again: X(kind, number, meaning, why). */
#define VB_DIAG_RETIRED(X)                                                                               \
    X(W, 740, "vertex file without vertex lines",                                                        \
      "verify refuses such a file: E105 (nothing verified is not a success)")                            \
    X(W, 805, "no usable OpenCL GPU: channels try the CPU device",                                       \
      "one fallback rule for every command: --device gpu means a GPU, else the reference")             \
    X(W, 736, "radius file: HOLE rows for particular atom or residue names left out",                    \
      "HOLE's rows are matched per atom and residue name as HOLE matches them")


enum vb_diag {
#define VB_DIAG_ENUM(kind, number, name, exit, meaning) VB_##kind##_##name = number,
    VB_DIAG_LIST(VB_DIAG_ENUM)
#undef VB_DIAG_ENUM
};

/* The exit status of `vorball` for a status code (primary or extended):
 * the exit of its E entry; 6 (internal) for a code without one. */
int vb_diag_exit(int status);

#endif
