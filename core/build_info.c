/* Provenance of this build (vb_build.h). The commit comes from vb_commit.h,
 * which CMake rewrites at every build when it changed (core/commit.cmake);
 * the rest from the configuration (VB_BUILD_* definitions). */
#include <gmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_build.h"
#include "vb_commit.h"
#include "vb_json.h"

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

/* "vorball V (commit C)": the tool line's value, shared by both forms. */
static void tool_name(char *buf, size_t size)
{
    snprintf(buf, size, "vorball %s (commit %s)", vb_build_version(), vb_build_commit());
}

size_t vb_provenance_text(const vb_provenance *p, char *buf, size_t size)
{
    char tool[160];
    tool_name(tool, sizeof tool);
    int n = snprintf(buf, size, "tool: %s\ninput: %s, %zu spheres\noptions: %s\n", tool,
                     p->input ? p->input : "-", p->spheres, p->options ? p->options : "");
    return n < 0 ? 0 : (size_t)n;
}

void vb_provenance_write_json(FILE *f, const vb_provenance *p)
{
    char tool[160];
    tool_name(tool, sizeof tool);
    fputs("\"tool\":", f);
    vb_json_write_string(f, tool);
    fputs(",\"input\":", f);
    vb_json_write_string(f, p->input ? p->input : "-");
    fprintf(f, ",\"spheres\":%zu,\"options\":", p->spheres);
    vb_json_write_string(f, p->options ? p->options : "");
    fputs(",", f);
}

int vb_provenance_write_comments(vb_ctx *ctx, FILE *f, const vb_provenance *p)
{
    size_t n = vb_provenance_text(p, NULL, 0);
    char *t = malloc(n + 1);
    if (!t)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing a table's header)");
    vb_provenance_text(p, t, n + 1);
    for (const char *q = t; *q;) {
        size_t len = strcspn(q, "\n");
        fprintf(f, "# %.*s\n", (int)len, q);
        q += len;
        if (*q == '\n')
            q++;
    }
    free(t);
    return VB_OK;
}
