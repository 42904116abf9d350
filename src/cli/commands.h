/* The subcommands of the `subsurf` CLI: each parses its own argv (argv[0] is
 * the subcommand's name), prints its own errors and returns the exit code:
 * 0 success, 1 failure at run time, 2 bad input, 130 interrupted. */
#ifndef SUBSURF_CLI_COMMANDS_H
#define SUBSURF_CLI_COMMANDS_H

int ss_cmd_halfspace(int argc, char **argv);
int ss_cmd_render(int argc, char **argv);
int ss_cmd_table(int argc, char **argv);
int ss_cmd_model(int argc, char **argv);
int ss_cmd_compare_halfspace(int argc, char **argv);
int ss_cmd_compare_scene(int argc, char **argv);
int ss_cmd_fem(int argc, char **argv);

#endif
