/* The subcommands of `vorball`, one file each (cli/cmd_<name>.c). Each takes
 * argv with argv[0] = subcommand name and returns the process exit code. */
#ifndef VB_COMMANDS_H
#define VB_COMMANDS_H

int vb_cmd_vertices(int argc, char **argv);
int vb_cmd_reference(int argc, char **argv);
int vb_cmd_verify(int argc, char **argv);
int vb_cmd_crosscheck(int argc, char **argv);
int vb_cmd_jfa(int argc, char **argv);
int vb_cmd_channels(int argc, char **argv);
int vb_cmd_bench(int argc, char **argv);
int vb_cmd_devices(int argc, char **argv);
int vb_cmd_cells(int argc, char **argv);

#endif
