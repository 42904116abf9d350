/* The subcommands of the `subsurf` CLI: each parses its own argv (argv[0] is
 * the subcommand's name), prints its own errors and returns the exit code:
 * 0 success, 1 failure at run time, 2 bad input, 130 interrupted. */
#ifndef SUBSURF_CLI_COMMANDS_H
#define SUBSURF_CLI_COMMANDS_H

int ss_cmd_halfspace(int argc, char **argv);
int ss_cmd_layer(int argc, char **argv);
int ss_cmd_render(int argc, char **argv);
int ss_cmd_table(int argc, char **argv);
int ss_cmd_model(int argc, char **argv);
int ss_cmd_compare_halfspace(int argc, char **argv);
int ss_cmd_compare_scene(int argc, char **argv);
int ss_cmd_fem(int argc, char **argv);
int ss_cmd_diff(int argc, char **argv);

/* One subcommand: the word after `subsurf`, its function and the line
 * `subsurf --help` prints for it. */
typedef struct {
  const char *name;
  int (*run)(int argc, char **argv);
  const char *summary;
} ss_cli_command;

/* Every subcommand, in the order of `subsurf --help`; ends with an entry
 * whose name is NULL. The one list that main.c dispatches on and the tests
 * that call commands in their own process (tests/cli/cli_call.h) use. */
extern const ss_cli_command ss_cli_commands[];

/* The subcommand called `name`, or NULL. */
const ss_cli_command *ss_cli_command_find(const char *name);

#endif
