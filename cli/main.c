/* `vorball`: dispatch to the subcommands. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "progress.h"
#include "vb_world.h"
#include "vb_output.h"

/* An ASan build of vorball keeps ASan's alternate signal stack off: on some
 * hosts ASan aborts when it cannot unmap that stack as a PoCL worker thread
 * exits (see tests/CMakeLists.txt). ASAN_OPTIONS still overrides it. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VB_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(VB_ASAN)
const char *__asan_default_options(void);
const char *__asan_default_options(void)
{
    return "use_sigaltstack=0";
}
#endif

typedef struct {
    const char *name;
    int (*run)(int argc, char **argv);
    void (*help)(FILE *f);
    const char *summary;
} command;

/* Every command is built, but crosscheck needs CGAL: without it the build
 * defines VB_NO_CROSSCHECK, leaves it out and --help says why. */
static const command commands[] = {
    {"vertices", vb_cmd_vertices, vb_cmd_vertices_help,
     "certified Voronoi vertices of spheres, proven complete (direction cover)"},
    {"reference", vb_cmd_reference, vb_cmd_reference_help,
     "all vertices exactly, by brute force (small inputs)"},
    {"verify", vb_cmd_verify, vb_cmd_verify_help,
     "check a vertex file against the spheres, exactly"},
#ifndef VB_NO_CROSSCHECK
    {"crosscheck", vb_cmd_crosscheck, vb_cmd_crosscheck_help,
     "compare with CGAL on equal-radius input"},
#endif
    {"jfa", vb_cmd_jfa, vb_cmd_jfa_help,
     "discrete Voronoi diagrams: JFA variants and Facet-JFA"},
    {"channels", vb_cmd_channels, vb_cmd_channels_help,
     "channels and cavities in proteins and trajectories"},
    {"cells", vb_cmd_cells, vb_cmd_cells_help,
     "per-atom cell volume, SAS and contact areas, as proven enclosures"},
    {"bench", vb_cmd_bench, vb_cmd_bench_help,
     "per-stage timings of the vertex pipeline"},
    {"devices", vb_cmd_devices, vb_cmd_devices_help,
     "list OpenCL platforms and devices"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: vorball <command> [options] [INPUT|-]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-11s %s\n", commands[i].name, commands[i].summary);
#ifdef VB_NO_CROSSCHECK
    fprintf(f, "  (crosscheck is not built: it needs CGAL headers and -DVORBALL_WITH_CGAL=ON)\n");
#endif
    fprintf(f,
            "\n'vorball <command> --help' describes each command; 'vorball --version'\n"
            "prints the version, commit, build options, library versions and device.\n"
            "Long work draws one progress line on stderr when it is a terminal;\n"
            "--quiet (anywhere on the line) turns it off, as VORBALL_NO_PROGRESS=1 does.\n"
            "Exit codes: 0 ok, 1 check failed, 2 usage, 3 i/o, 4 memory, 5 device,\n"
            "6 internal, 7 degenerate, 8 precision, 11-27 bad input (see README).\n");
}

/* The command line after the world joined: a command, help or version. */
static int dispatch(int argc, char **argv)
{
    /* Mistakes are the same on every MPI rank: rank 0 names them. */
    FILE *err = vb_world_rank() == 0 ? stderr : NULL;
    /* --quiet, anywhere on the line, is global: no progress line. */
    int kept = 1;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quiet") == 0)
            vb_cli_set_quiet(1);
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    argv[argc] = NULL;
    if (argc < 2) {
        if (err)
            usage(err);
        return VB_EXIT_USAGE;
    }
    if (vb_cli_is_help(argv[1])) {
        usage(stdout);
        return VB_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0)
        return vb_cli_version(stdout);
    vb_cli_set_args(argc, argv);
    /* A command's output files appear together when it succeeds (or when a
     * check ran and wrote its report of differences), none when it fails. */
    vb_output_defer(1);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(argv[1], commands[i].name) == 0) {
            int code = vb_world_check_command(commands[i].name);
            if (code)
                return code;
            /* -h or --help anywhere: the command's help, nothing run. */
            for (int k = 2; k < argc; k++)
                if (vb_cli_is_help(argv[k])) {
                    commands[i].help(stdout);
                    return VB_EXIT_OK;
                }
            code = commands[i].run(argc - 1, argv + 1);
            if (code == VB_EXIT_OK || code == VB_EXIT_MISMATCH) {
                vb_ctx *ctx = NULL;
                int rc = vb_open(&ctx, NULL);
                if (rc == VB_OK)
                    rc = vb_output_commit_deferred(ctx);
                if (rc != VB_OK)
                    code = vb_cli_fail(ctx, rc);
                vb_close(ctx);
            }
            vb_output_discard_all();
            return code;
        }
    if (err) {
        fprintf(err, "vorball: E%d: unknown command '%s'\n", vb_diag_number(VB_EMISUSE), argv[1]);
        usage(err);
    }
    return VB_EXIT_USAGE;
}

int main(int argc, char **argv)
{
    /* Under mpirun (a build with VORBALL_WITH_MPI) every rank runs this. */
    int code = vb_world_init(&argc, &argv);
    if (code)
        return code;
    return vb_world_finish(dispatch(argc, argv));
}
