/* `vorball --version`: what this program is and what it runs on, from the
 * rooms that know it (core's build record, the verifier's MPFR, the CGAL
 * bridge, the device layer's choice for --device auto). */
#include <stdio.h>

#include "cli_common.h"
#include "vb_build.h"
#include "vb_default.h"
#include "vb_verify.h"
#ifndef VB_NO_CROSSCHECK
#include "vb_cgal.h"
#endif

int vb_cli_version(FILE *f)
{
    fprintf(f, "vorball %s (commit %s)\n", vb_build_version(), vb_build_commit());
    fprintf(f, "build: %s\n", vb_build_options());
    fprintf(f, "exact arithmetic: GMP %s, MPFR %s\n", vb_build_gmp_version(), vb_verify_mpfr_version());
#ifndef VB_NO_CROSSCHECK
    fprintf(f, "cross-check: CGAL %s (GPL-3+)\n", vb_cgal_version());
#else
    fprintf(f, "cross-check: not built (no CGAL)\n");
#endif
    vb_ctx *ctx = NULL;
    if (vb_open(&ctx, NULL) != VB_OK)
        return vb_cli_fail(NULL, VB_ENOMEM);
    vb_devices_write_auto(ctx, f);
    vb_close(ctx);
    return VB_EXIT_OK;
}
