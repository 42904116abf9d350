#include "cli/signals.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted = 0;
static struct timespec first; /* written by the handler before the flag */

static double since_first(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now); /* async-signal-safe (POSIX) */
  return (double)(now.tv_sec - first.tv_sec) + 1e-9 * (double)(now.tv_nsec - first.tv_nsec);
}

static void on_signal(int sig) {
  (void)sig;
  if (!interrupted) {
    clock_gettime(CLOCK_MONOTONIC, &first);
    interrupted = 1;
    return;
  }
  if (since_first() > SS_CLI_SIGNAL_GRACE) {
    static const char msg[] = "subsurf: interrupted again; stopped without writing more\n";
    ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)n;
    _exit(130);
  }
}

const volatile sig_atomic_t *ss_cli_install_interrupt_handler(void) {
  static int installed = 0;
  if (!installed) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sa.sa_flags = SA_RESTART; /* a write in progress must not fail with EINTR */
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    installed = 1;
  }
  return &interrupted;
}

int ss_cli_interrupted(void) { return interrupted != 0; }

int ss_cli_interrupted_exit(const char *cmd, const char *when) {
  fprintf(stderr, "subsurf %s: interrupted%s%s; nothing written\n", cmd, when[0] ? " " : "", when);
  return 130;
}
