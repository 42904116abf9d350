/* Ctrl-C handling for long commands: the first SIGINT sets a flag that the
 * library polls (work stops and what is done is written); a second one ends
 * the process at once. */
#ifndef SUBSURF_CLI_SIGNALS_H
#define SUBSURF_CLI_SIGNALS_H

#include <signal.h>

/* Installs the handler (once) and returns the flag it sets. */
const volatile sig_atomic_t *ss_cli_install_interrupt_handler(void);

#endif
