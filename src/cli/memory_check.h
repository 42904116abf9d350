/* Whether a run fits in this machine's memory, checked before it starts (a
 * size inside the documented ranges may still be too large to serve). The
 * rule: the peak allocation must fit in the physical memory. */
#ifndef SUBSURF_CLI_MEMORY_CHECK_H
#define SUBSURF_CLI_MEMORY_CHECK_H

/* 0 when `need` bytes fit, else -1 after printing "subsurf CMD: WHAT need(s)
 * X GB, more than this machine's Y GB of memory (HINT)". */
int ss_cli_check_memory(const char *cmd, double need, const char *what, const char *hint);

#endif
