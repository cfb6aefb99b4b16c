/* What this build of vorball is: version, source commit, build type,
 * compiler, options, and the numeric libraries it links (provenance for
 * `vorball --version`, output headers and bug reports). */
#ifndef VB_BUILD_H
#define VB_BUILD_H

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the library, e.g. "0.1.0" (CMake's project version). */
const char *vb_build_version(void);

/* The source commit the library was built from: `git describe --always
 * --dirty` taken at build time ("unknown" outside a git checkout). */
const char *vb_build_commit(void);

/* One line: build type, compiler and the options that change what the
 * library does or checks, e.g. "Release, GNU 12.2.0, -ffp-contract=off,
 * sanitizers off, CGAL cross-check on, MPI off, results-page viewer
 * embedded". */
const char *vb_build_options(void);

/* The GMP version the library runs with (gmp_version). */
const char *vb_build_gmp_version(void);

#ifdef __cplusplus
}
#endif
#endif
