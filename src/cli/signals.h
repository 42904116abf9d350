/* SIGINT/SIGTERM handling shared by every command that runs for long
 * (render, halfspace, model, compare-halfspace, table):
 *   - the first signal sets a flag that the library polls: work stops and
 *     the command writes what it has (NAME-partial.*) or says that nothing
 *     was written, and exits with 130;
 *   - repeats within SS_CLI_SIGNAL_GRACE seconds of the first are the same
 *     interrupt (a terminal's Ctrl-C reaches every process of the group, so
 *     `timeout` forwards a second copy right after the first);
 *   - a repeat after that ends the process at once (exit 130, one line). */
#ifndef SUBSURF_CLI_SIGNALS_H
#define SUBSURF_CLI_SIGNALS_H

#include <signal.h>

#define SS_CLI_SIGNAL_GRACE 1.0

/* Installs the handler (once) and returns the flag it sets. */
const volatile sig_atomic_t *ss_cli_install_interrupt_handler(void);

/* 1 once SIGINT or SIGTERM has arrived (after the handler is installed). */
int ss_cli_interrupted(void);

/* Prints "subsurf CMD: interrupted WHEN; nothing written" and returns 130. */
int ss_cli_interrupted_exit(const char *cmd, const char *when);

#endif
