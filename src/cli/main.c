#include "cli/commands.h"
#include "cli/mpi_job.h"
#include "subsurf/version.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *out) {
  fprintf(out, "usage: subsurf COMMAND [options]   (subsurf COMMAND --help for its options)\n"
               "       subsurf --version\n\n"
               "Subsurface scattering models and their Monte Carlo references.\n\ncommands:\n");
  for (const ss_cli_command *c = ss_cli_commands; c->name; ++c) {
    fprintf(out, "  %-18s %s\n", c->name, c->summary);
  }
  fprintf(out, "\nNumbers are decimal and finite with nothing around them (no spaces, 0x, inf or\n"
               "nan). Bad input: one line on stderr, exit 2, nothing written. Ctrl-C or SIGTERM:\n"
               "work stops, partial results where the command has them, exit 130. Ranges: README,\n"
               "\"Limits of the input\".\n");
}

/* Under mpirun with several ranks: the commands that split their work over
 * ranks (docs/render.md, "Many machines"), started with the same arguments
 * on every rank; 0, or the exit code. */
static int mpi_launch_check(const ss_cli_command *c, int argc, char **argv) {
  if (strcmp(c->name, "render") && strcmp(c->name, "halfspace") && strcmp(c->name, "compare")) {
    if (ss_mpi_rank() == 0) {
      fprintf(stderr,
              "subsurf %s: does not use MPI; run it without mpirun (render, halfspace and "
              "compare split their work over MPI ranks)\n",
              c->name);
    }
    return 2;
  }
  return ss_mpi_check_args(c->name, argc - 1, argv + 1);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
    usage(stdout);
    return 0;
  }
  if (!strcmp(argv[1], "--version")) {
    printf("subsurf %s\n", ss_version());
    return 0;
  }
  const ss_cli_command *c = ss_cli_command_find(argv[1]);
  if (c) {
    int rc = ss_mpi_start() > 1 ? mpi_launch_check(c, argc, argv) : 0;
    rc = rc ? rc : c->run(argc - 1, argv + 1);
    ss_mpi_finish();
    return rc;
  }
  fprintf(stderr, "subsurf: unknown command '%s' (see subsurf --help)\n", argv[1]);
  return 2;
}
