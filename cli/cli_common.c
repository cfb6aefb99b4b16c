/* Exit codes, diagnostics and file helpers for the subcommands. */
#include "cli_common.h"
#include "vb_numtext.h"
#include "vb_diag.h"
#include "vb_world.h"
#include "progress.h"

#include <errno.h>
#include <sys/stat.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "vb_output.h"

int vb_cli_exit_code(int status)
{
    return vb_diag_exit(status);
}

int vb_cli_fail(vb_ctx *ctx, int status)
{
    vb_cli_progress_clear(); /* the error starts its own line */
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
    /* A usage error is misuse: its number, as every error has one. */
    fprintf(stderr, "vorball %s: E%d: ", cmd, vb_diag_number(VB_EMISUSE));
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see 'vorball %s --help')\n", cmd);
    return VB_EXIT_USAGE;
}

/* The command line, for the check that no output overwrites an input. */
static int cli_argc;
static char **cli_argv;

void vb_cli_set_args(int argc, char **argv)
{
    cli_argc = argc;
    cli_argv = argv;
}

/* Options left out of the options line: they change no byte of an output
 * (backends, thread counts and ranks give the same file; -o is where it
 * goes). value: 1 when the option takes one. */
static const struct {
    const char *name;
    int value;
} not_shaping[] = {{"-o", 1},     {"--threads", 1}, {"--device", 1},
                   {"--stats", 0}, {"--quiet", 0},   {"--progress", 0}};

/* Options that name another output file: kept, the path written FILE, so
 * that two runs writing to other places give the same header. */
static const char *const output_paths[] = {
    "--topology", "--atoms",   "--centerlines", "--centrelines", "--pymol", "--volume",
    "--occupancy", "--profile", "--stats-file",  "--png",         "--plot",  "--html",
    "--cgal-out",  "--contacts"};

/* Appends s; once the line does not fit, it ends in "..." and stays cut. */
static void append(char *buf, size_t size, size_t *at, const char *s)
{
    size_t n = strlen(s);
    if (*at >= size)
        return;
    if (*at + n + 1 <= size) {
        memcpy(buf + *at, s, n + 1);
        *at += n;
        return;
    }
    if (size >= 4)
        strcpy(buf + size - 4, "...");
    *at = size;
}

/* One argument, single-quoted when a shell would split or expand it. */
static void append_arg(char *buf, size_t size, size_t *at, const char *a)
{
    if (*at)
        append(buf, size, at, " ");
    if (*a && !a[strcspn(a, " \t\n'\"\\$`*?;&|<>(){}")]) {
        append(buf, size, at, a);
        return;
    }
    append(buf, size, at, "'");
    for (const char *p = a; *p; p++) {
        char c[2] = {*p, 0};
        append(buf, size, at, *p == '\'' ? "'\\''" : c);
    }
    append(buf, size, at, "'");
}

void vb_cli_provenance(vb_provenance *p, char *buf, size_t size, const char *input,
                       size_t spheres)
{
    p->input = input;
    p->spheres = spheres;
    p->options = buf;
    size_t at = 0;
    if (size)
        buf[0] = '\0';
    for (int i = 1; i < cli_argc; i++) {
        const char *a = cli_argv[i];
        int skip = -1;
        for (size_t k = 0; k < sizeof not_shaping / sizeof *not_shaping; k++)
            if (strcmp(a, not_shaping[k].name) == 0)
                skip = not_shaping[k].value;
        if (skip >= 0) {
            i += skip;
            continue;
        }
        append_arg(buf, size, &at, a);
        for (size_t k = 0; k < sizeof output_paths / sizeof *output_paths; k++)
            if (strcmp(a, output_paths[k]) == 0 && i + 1 < cli_argc) {
                append_arg(buf, size, &at, "FILE");
                i++;
                break;
            }
    }
}

int vb_cli_check_output(vb_ctx *ctx, const char *path)
{
    struct stat out;
    if (!path || strcmp(path, "-") == 0 || stat(path, &out) != 0 || !S_ISREG(out.st_mode))
        return VB_OK;
    /* Arguments naming the output's file: the output itself (its own
     * argument, if the path was given on the command line) and anything
     * else, which is an input or another output. Compared by device and
     * inode, so "./in.pdb", "in.pdb" and a link to it are the same file. */
    int same = 0, self = 0;
    const char *other = NULL;
    for (int i = 1; i < cli_argc; i++) {
        struct stat st;
        const char *a = cli_argv[i];
        if (a[0] == '-' || stat(a, &st) != 0 || st.st_dev != out.st_dev || st.st_ino != out.st_ino)
            continue;
        same++;
        if (!self && (a == path || strcmp(a, path) == 0))
            self = 1;
        else if (!other)
            other = a;
    }
    if (same > self)
        return vb_error(ctx, VB_EMISUSE, path, 0,
                        "output is the same file as '%s' on the command line: refused (it "
                        "would be overwritten)", other ? other : path);
    /* An input '-' is stdin: `vorball vertices - -o IN < IN` would replace
     * the file it reads. */
    struct stat in;
    for (int i = 1; i < cli_argc; i++)
        if (strcmp(cli_argv[i], "-") == 0 && fstat(0, &in) == 0 && in.st_dev == out.st_dev &&
            in.st_ino == out.st_ino)
            return vb_error(ctx, VB_EMISUSE, path, 0,
                            "output is the file standard input reads ('-' on the command "
                            "line): refused (it would be overwritten)");
    return VB_OK;
}

FILE *vb_cli_open_output(vb_ctx *ctx, const char *path)
{
    if (!path || strcmp(path, "-") == 0)
        return stdout;
    if (vb_cli_check_output(ctx, path) != VB_OK)
        return NULL;
    return vb_output_open(ctx, path);
}

int vb_cli_close_output(vb_ctx *ctx, FILE *f, const char *path)
{
    if (f != stdout)
        return vb_output_commit(ctx, f);
    if (ferror(f) || fflush(f) != 0)
        return vb_error(ctx, VB_EIO, path ? path : "<stdout>", 0, "write failed");
    return VB_OK;
}

int vb_cli_finish_output(vb_ctx *ctx, FILE *f, const char *path, int rc)
{
    if (!f)
        return rc;
    if (rc == VB_OK)
        return vb_cli_close_output(ctx, f, path);
    if (f == stdout)
        fflush(f);
    else
        vb_output_discard(f);
    return rc;
}

int vb_cli_parse_double(const char *s, double *out)
{
    return vb_parse_double(s, out);
}

int vb_cli_parse_size(const char *s, size_t *out)
{
    return vb_parse_size(s, out);
}

int vb_cli_is_help(const char *arg)
{
    return strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0;
}
