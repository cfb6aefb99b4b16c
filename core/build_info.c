/* Provenance of this build (vb_build.h). The commit comes from vb_commit.h,
 * which CMake rewrites at every build when it changed (core/commit.cmake);
 * the rest from the configuration (VB_BUILD_* definitions). */
#include <gmp.h>

#include "vb_build.h"
#include "vb_commit.h"

#define VB_STR2(x) #x
#define VB_STR(x) VB_STR2(x)

const char *vb_build_version(void)
{
    return VB_STR(VB_BUILD_VERSION);
}

const char *vb_build_commit(void)
{
    return VB_COMMIT;
}

const char *vb_build_options(void)
{
    return VB_STR(VB_BUILD_TYPE) ", " VB_STR(VB_BUILD_COMPILER) ", -ffp-contract=off, sanitizers "
#ifdef VB_BUILD_SANITIZE
        "on (ASan+UBSan)"
#else
        "off"
#endif
        ", CGAL cross-check "
#ifdef VB_BUILD_CGAL
        "on"
#else
        "off"
#endif
        ", MPI "
#ifdef VB_BUILD_MPI
        "on"
#else
        "off"
#endif
        ", results-page viewer "
#ifdef VB_BUILD_VIEWER
        "embedded"
#else
        "absent"
#endif
        ;
}

const char *vb_build_gmp_version(void)
{
    return gmp_version;
}
