/* Provenance of this build (vb_build.h). The commit comes from vb_commit.h,
 * which CMake rewrites at every build when it changed (core/commit.cmake);
 * the rest from the configuration (VB_BUILD_* definitions). */
#include <gmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
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

void vb_provenance_write_json_head(FILE *f, const vb_provenance *p, const char *comment)
{
    fputs("{", f);
    if (p)
        vb_provenance_write_json(f, p);
    if (comment) {
        fputs("\"comment\":", f);
        vb_json_write_string(f, comment);
        fputs(",", f);
    }
}

void vb_comment_lines(FILE *f, const char *prefix, const char *text)
{
    for (const char *p = text; p && *p;) {
        size_t len = strcspn(p, "\n");
        fprintf(f, "%s%.*s\n", prefix, (int)len, p);
        p += len;
        p += *p == '\n';
    }
}

int vb_provenance_write_comments(FILE *f, const char *prefix, const vb_provenance *p,
                                 const char *comment)
{
    if (p) {
        size_t n = vb_provenance_text(p, NULL, 0);
        char *t = malloc(n + 1);
        if (!t)
            return VB_ENOMEM;
        vb_provenance_text(p, t, n + 1);
        vb_comment_lines(f, prefix, t);
        free(t);
    }
    vb_comment_lines(f, prefix, comment);
    return VB_OK;
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
