/* The subcommands of `vorball`, one file each (cli/cmd_<name>.c). Each
 * vb_cmd_<name> takes argv with argv[0] = subcommand name and returns the
 * process exit code; vb_cmd_<name>_help prints its --help text to f (main.c
 * calls it when -h or --help is anywhere on the command's line, so the
 * commands' parsers never see them). */
#ifndef VB_COMMANDS_H
#define VB_COMMANDS_H

#include <stdio.h>

int vb_cmd_vertices(int argc, char **argv);
void vb_cmd_vertices_help(FILE *f);
int vb_cmd_reference(int argc, char **argv);
void vb_cmd_reference_help(FILE *f);
int vb_cmd_verify(int argc, char **argv);
void vb_cmd_verify_help(FILE *f);
int vb_cmd_crosscheck(int argc, char **argv);
void vb_cmd_crosscheck_help(FILE *f);
int vb_cmd_jfa(int argc, char **argv);
void vb_cmd_jfa_help(FILE *f);
int vb_cmd_channels(int argc, char **argv);
void vb_cmd_channels_help(FILE *f);
int vb_cmd_bench(int argc, char **argv);
void vb_cmd_bench_help(FILE *f);
int vb_cmd_devices(int argc, char **argv);
void vb_cmd_devices_help(FILE *f);
int vb_cmd_cells(int argc, char **argv);
void vb_cmd_cells_help(FILE *f);

#endif
