/* `vorball`: dispatch to the subcommands. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"

typedef struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

/* Subcommands whose build component is absent are compiled with
 * VB_NO_<NAME>; they are left out of the table and named in --help. */
static const command commands[] = {
#ifndef VB_NO_VERTICES
    {"vertices", vb_cmd_vertices, "certified Voronoi vertices of spheres (sampling pipeline)"},
#endif
#ifndef VB_NO_REFERENCE
    {"reference", vb_cmd_reference, "all vertices exactly, by brute force (small inputs)"},
#endif
#ifndef VB_NO_VERIFY
    {"verify", vb_cmd_verify, "check a vertex file against the spheres, exactly"},
#endif
#ifndef VB_NO_CROSSCHECK
    {"crosscheck", vb_cmd_crosscheck, "compare with CGAL on equal-radius input"},
#endif
#ifndef VB_NO_JFA
    {"jfa", vb_cmd_jfa, "discrete Voronoi diagrams: JFA variants and Facet-JFA"},
#endif
#ifndef VB_NO_CHANNELS
    {"channels", vb_cmd_channels, "channels and cavities in proteins and trajectories"},
#endif
#ifndef VB_NO_BENCH
    {"bench", vb_cmd_bench, "per-stage timings of the vertex pipeline"},
#endif
#ifndef VB_NO_DEVICES
    {"devices", vb_cmd_devices, "list OpenCL platforms and devices"},
#endif
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
            "prints the version.\n"
            "Exit codes: 0 ok, 1 check failed, 2 usage, 3 i/o, 4 memory, 5 device,\n"
            "6 internal, 7 degenerate, 8 precision, 11-27 bad input (see README).\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return VB_EXIT_USAGE;
    }
    if (vb_cli_is_help(argv[1])) {
        usage(stdout);
        return VB_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("vorball 0.1.0\n");
        return VB_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(argv[1], commands[i].name) == 0)
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "vorball: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return VB_EXIT_USAGE;
}
