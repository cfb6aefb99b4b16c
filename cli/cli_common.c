/* Exit codes, diagnostics and file helpers for the subcommands. */
#include "cli_common.h"
#include "vb_diag.h"
#include "vb_world.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int vb_cli_exit_code(int status)
{
    return vb_diag_exit(status);
}

int vb_cli_fail(vb_ctx *ctx, int status)
{
    const char *msg = ctx ? vb_errmsg(ctx) : "";
    fprintf(stderr, "vorball: E%d: %s\n", vb_diag_number(status),
            msg && *msg ? msg : vb_errstr(status));
    return vb_cli_exit_code(status);
}

int vb_cli_usage_error(const char *cmd, const char *fmt, ...)
{
    /* Every MPI rank parses the same command line: one message. */
    if (vb_world_rank() != 0)
        return VB_EXIT_USAGE;
    fprintf(stderr, "vorball %s: ", cmd);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see 'vorball %s --help')\n", cmd);
    return VB_EXIT_USAGE;
}

FILE *vb_cli_open_output(vb_ctx *ctx, const char *path)
{
    if (!path || strcmp(path, "-") == 0)
        return stdout;
    FILE *f = fopen(path, "w");
    if (!f)
        vb_error(ctx, VB_EIO, path, 0, "cannot open for writing: %s", strerror(errno));
    return f;
}

int vb_cli_close_output(vb_ctx *ctx, FILE *f, const char *path)
{
    int bad = ferror(f);
    if (f == stdout)
        bad |= fflush(f) != 0;
    else
        bad |= fclose(f) != 0;
    if (bad)
        return vb_error(ctx, VB_EIO, path ? path : "<stdout>", 0, "write failed");
    return VB_OK;
}

int vb_cli_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE)
        return -1;
    *out = v;
    return 0;
}

int vb_cli_parse_size(const char *s, size_t *out)
{
    char *end;
    if (*s == '-' || *s == '\0')
        return -1;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end != '\0' || errno == ERANGE)
        return -1;
    *out = (size_t)v;
    return 0;
}

int vb_cli_is_help(const char *arg)
{
    return strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0;
}
