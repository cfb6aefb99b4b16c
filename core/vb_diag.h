/* The catalogue of every diagnostic number vorball prints: errors E<n> and
 * warnings W<n>. A number is stable once released: tests and users match the
 * number, not the wording. Add a new number here, in the range of its room,
 * before using it; never reuse a retired one.
 *
 * Ranges:
 *   E1-E9      status categories (vb.h enum vb_status), printed as E<category>
 *   E101-E139  input errors (extended VB_EINPUT codes, exit 10 + detail)
 *   E140-E159  resource limits and pipeline errors
 *   W701-W739  input layer (readers, element inference, validation)
 *   W740-W749  vertex files and verify
 *   W750-W759  device layer (program cache, device memory, fault fallback)
 *   W760-W779  vertex pipeline (device fallback, certification, topology)
 *   W780-W799  discrete Voronoi (JFA, Facet-JFA, exact engines) and crosscheck
 *   W800-W829  channels and trajectories
 *   W830-W839  MPI scale-out
 *
 * VB_DIAG_LIST(X) expands X(kind, number, name, meaning) for every entry, so
 * the README table and the --help texts can be checked against one list;
 * every entry is also a name, VB_<kind>_<name> (VB_W_DEVICE_FALLBACK = 760),
 * which every vb_warn call uses instead of the bare number. Errors are
 * raised through their status codes (vb.h): vb_diag_number maps those to
 * the E numbers. */
#ifndef VB_DIAG_H
#define VB_DIAG_H

#define VB_DIAG_LIST(X)                                                                        \
    X(E, 1, EINPUT, "bad input")                                                               \
    X(E, 2, EDEGENERATE, "degenerate input for the operation")                                 \
    X(E, 3, EPREC, "precision limit reached")                                                  \
    X(E, 4, ENOMEM, "out of memory")                                                           \
    X(E, 5, EDEVICE, "OpenCL device failure that could not fall back")                         \
    X(E, 6, EINTERNAL, "internal error (a bug: please report it)")                             \
    X(E, 7, EMISUSE, "misuse of an option or of the API")                                      \
    X(E, 8, EIO, "file cannot be opened, read or written")                                     \
    X(E, 9, EMISMATCH, "a check ran and found a difference")                                   \
    X(E, 101, INPUT_MALFORMED, "malformed line")                                               \
    X(E, 102, INPUT_NONFINITE, "NaN or infinite value")                                        \
    X(E, 103, INPUT_RADIUS, "radius < 0, or 0 where --zero-radius does not accept it")         \
    X(E, 104, INPUT_DUPLICATE, "duplicate sphere")                                             \
    X(E, 105, INPUT_EMPTY, "empty input")                                                      \
    X(E, 106, INPUT_TOOFEW, "fewer than 4 spheres")                                            \
    X(E, 107, INPUT_MAGNITUDE, "absurd magnitude or more than 18 significant digits")          \
    X(E, 108, INPUT_ELEMENT, "unknown element (--strict-elements)")                            \
    X(E, 109, INPUT_FORMAT, "format not recognised")                                           \
    X(E, 110, INPUT_TOOLARGE, "input too large")                                               \
    X(E, 111, INPUT_MODEL, "requested model absent")                                           \
    X(W, 701, CONTAINED, "a sphere lies inside another: its cell is empty")                    \
    X(W, 702, CONTAINED_COUNT, "count of spheres inside others")                               \
    X(W, 703, WATER_DROPPED, "water atoms dropped")                                            \
    X(W, 704, ALTLOC_DROPPED, "atoms of other alternate locations dropped")                    \
    X(W, 705, MODELS_IGNORED, "atoms of other models ignored")                                 \
    X(W, 706, HYDROGENS_DROPPED, "hydrogen atoms dropped (--no-hydrogens)")                    \
    X(W, 707, ELEMENT_UNKNOWN, "unknown element: default radius used")                         \
    X(W, 708, ELEMENT_UNKNOWN_COUNT, "count of atoms with an unknown element")                 \
    X(W, 709, NAMES_TRUNCATED, "atom, residue or chain names truncated")                       \
    X(W, 710, AFTER_END, "atom records after END ignored")                                     \
    X(W, 711, CIF_BLOCK_IGNORED, "a further mmCIF _atom_site loop ignored")                    \
    X(W, 712, ZERO_DROPPED, "spheres of radius 0 dropped (--zero-radius drop)")                \
    X(W, 713, ZERO_POINTS, "spheres of radius 0 kept as point sites")                          \
    X(W, 720, REFERENCE_SLOW, "exact reference on a large input: may take very long")          \
    X(W, 760, DEVICE_FALLBACK, "no usable OpenCL device: reference backend used")              \
    X(W, 761, CAND_OVERFLOW, "candidates did not fit a sampling grid cell")                    \
    X(W, 762, DEVICE_FAILED_RERUN, "OpenCL device failed mid-run: rerun on the reference")     \
    X(W, 763, CERT_REJECTED, "the certifier rejected candidates")                              \
    X(W, 765, TOPO_UNPAIRED, "trisector edges that could not be paired")                       \
    X(W, 780, JFA_SEEDS_LOST, "seeds share their start pixel with a nearer seed")              \
    X(W, 781, JFA_DEVICE_FALLBACK, "no OpenCL device for jfa: reference backend used")         \
    X(W, 782, FACET_START_FINE, "Facet-JFA cannot start coarser than n")                       \
    X(W, 790, CROSSCHECK_POWER, "radii differ: compared with CGAL's power diagram (ids only)") \
    X(W, 793, CROSSCHECK_REJECTED, "lines marked rejected are not compared")                   \
    X(W, 801, DCD_PARTIAL_FRAME, "DCD ends inside a frame: partial frame ignored")             \
    X(W, 802, VOLUME_FIRST_FRAME, "volume file holds the first frame only")                    \
    X(W, 803, VOXEL_COARSE, "voxel edge coarser than the probe radius")                        \
    X(W, 804, CHANNELS_DEVICE_FALLBACK, "no usable OpenCL device: channels on the reference")  \
    X(W, 806, CHANNELS_DEVICE_FAILED, "OpenCL failed mid-run: rest of channels on reference")

/* Retired numbers, never to be used again: X(kind, number, meaning, why). */
#define VB_DIAG_RETIRED(X)                                                                     \
    X(W, 740, "vertex file without vertex lines",                                              \
      "verify refuses such a file: E105 (nothing verified is not a success)")                  \
    X(W, 805, "no usable OpenCL GPU: channels try the CPU device",                             \
      "one fallback rule for every command: --device gpu means a GPU, else the reference")


enum vb_diag {
#define VB_DIAG_ENUM(kind, number, name, meaning) VB_##kind##_##name = number,
    VB_DIAG_LIST(VB_DIAG_ENUM)
#undef VB_DIAG_ENUM
};

#endif
