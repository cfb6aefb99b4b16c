/* Helpers shared by the subcommands: exit codes, diagnostics, files. */
#ifndef VB_CLI_COMMON_H
#define VB_CLI_COMMON_H

#include <stdio.h>

#include "vb.h"
#include "vb_build.h"
#include "vb_parallel.h"

/* Exit codes of the `vorball` command (documented in README and --help):
 *   0 success, 1 a check found a difference (verify/crosscheck), 2 usage,
 *   3 i/o, 4 out of memory, 5 device, 6 internal, 7 degenerate, 8 precision,
 *   10 + detail for input errors: 11 malformed, 12 NaN/Inf, 13 radius <= 0,
 *   14 duplicate, 15 empty, 16 too few spheres, 17 magnitude, 18 unknown
 *   element, 19 format, 20 too large, 21 model absent. */
enum {
    VB_EXIT_OK = 0,
    VB_EXIT_MISMATCH = 1,
    VB_EXIT_USAGE = 2,
    VB_EXIT_IO = 3,
    VB_EXIT_NOMEM = 4,
    VB_EXIT_DEVICE = 5,
    VB_EXIT_INTERNAL = 6,
    VB_EXIT_DEGENERATE = 7,
    VB_EXIT_PREC = 8,
    VB_EXIT_INPUT = 10
};

/* Maps a status code (primary or extended) to the exit code above. */
int vb_cli_exit_code(int status);

/* Prints "vorball: E<num>: <message>" for the context's last error (or the
 * status name when the context has no message) and returns the exit code. */
int vb_cli_fail(vb_ctx *ctx, int status);

/* Prints "vorball <cmd>: <message>" (usage problems) to stderr and returns
 * VB_EXIT_USAGE. */
int vb_cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Remembers the command line (main does, before the subcommand runs), for
 * vb_cli_check_output. */
void vb_cli_set_args(int argc, char **argv);

/* The provenance of an output file (vb_build.h, issue 35): *p names the
 * input and its sphere count, and p->options points into buf, which gets the
 * command line from the subcommand on, as given, less what by contract does
 * not change an output's bytes (-o, --threads, --device, --stats, --quiet,
 * --progress; the same file on every device, thread count and rank, wherever
 * it is written) and with the paths of other outputs (--topology, --atoms,
 * --pymol, ...) written as FILE. Arguments with blanks or quotes are quoted
 * as a shell would read them; a line longer than size is cut with "...". */
void vb_cli_provenance(vb_provenance *p, char *buf, size_t size, const char *input,
                       size_t spheres);

/* VB_EMISUSE (message naming both) when `path` exists and is the same file
 * (device and inode, through links) as another argument of the command line:
 * an input, or another output; or as standard input when an argument is
 * "-" (stdin read as an input). VB_OK otherwise, and for "-" or NULL. */
int vb_cli_check_output(vb_ctx *ctx, const char *path);

/* Opens the output: NULL or "-" is stdout; a file is refused when it is an
 * input (vb_cli_check_output) and is otherwise written under a temporary
 * name and renamed when closed (vb_output.h), so a failing command leaves no
 * partial file. Returns NULL with the context error (VB_EMISUSE, VB_EIO) on
 * failure. Finish with vb_cli_close_output or vb_cli_finish_output. */
FILE *vb_cli_open_output(vb_ctx *ctx, const char *path);

/* Closes an output opened by vb_cli_open_output (stdout is flushed, not
 * closed) and puts the file in place. Returns VB_OK or VB_EIO (with message)
 * if a write, the close or the rename failed. */
int vb_cli_close_output(vb_ctx *ctx, FILE *f, const char *path);

/* Ends an output after a command's work returned rc: VB_OK closes it as
 * vb_cli_close_output does (and returns that status); a failure discards
 * the file (the path keeps what it held) and returns rc. f may be NULL. */
int vb_cli_finish_output(vb_ctx *ctx, FILE *f, const char *path, int rc);

/* Parses a whole string as a double / a non-negative integer. Returns 0 on
 * success, -1 if the text is not a complete number. */
int vb_cli_parse_double(const char *s, double *out);
int vb_cli_parse_size(const char *s, size_t *out);

/* True when `arg` equals -h or --help. */
int vb_cli_is_help(const char *arg);

/* Prints `vorball --version` to f: version and commit, build options, GMP,
 * MPFR and CGAL versions, and the OpenCL device --device auto takes with
 * its platform and driver versions. Returns the exit code (0). */
int vb_cli_version(FILE *f);

#endif
