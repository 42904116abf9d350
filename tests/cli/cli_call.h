/* Runs a `subsurf` command inside the test process, for sweeps of hundreds
 * of command lines: the command's function (cli/commands.h) gets the same
 * argv, working directory, stdout and stderr as the `subsurf` process of
 * cli_run_in would, without a process start per line (0.15 CPU s each under
 * ASan: loading 45 shared libraries, and LeakSanitizer's scan at exit). A
 * leak in any line is still reported, by LeakSanitizer's scan when the test
 * process exits. The process path itself (main's dispatch and exit code) is
 * what the tests through cli_run_in keep proving. */
#ifndef SUBSURF_TESTS_CLI_CALL_H
#define SUBSURF_TESTS_CLI_CALL_H

#include "cli/cli_run.h"
#include "cli/commands.h"

#include <criterion/criterion.h>
#include <fcntl.h>

/* Splits `args` into words the way /bin/sh does for the subset the tests
 * write: words separated by blanks, and '...' quoting (possibly empty);
 * words go to buf, pointers to argv; returns argc. */
static inline int cli_call_split(const char *args, char *buf, char **argv, int max_words) {
  int argc = 0;
  const char *p = args;
  while (*p) {
    while (*p == ' ') {
      ++p;
    }
    if (!*p) {
      break;
    }
    cr_assert(argc < max_words, "'%s': too many words", args);
    argv[argc++] = buf;
    while (*p && *p != ' ') {
      cr_assert(!strchr("\"\\$`|;&<>*?", *p), "'%s': shell syntax beyond '...' quoting", args);
      if (*p == '\'') {
        const char *end = strchr(p + 1, '\'');
        cr_assert(end, "'%s': unterminated quote", args);
        memcpy(buf, p + 1, (size_t)(end - p - 1));
        buf += end - p - 1;
        p = end + 1;
      } else {
        *buf++ = *p++;
      }
    }
    *buf++ = '\0';
  }
  return argc;
}

/* Points file descriptor fd at `path` (created); returns the old one. */
static inline int cli_call_redirect(int fd, const char *path) {
  int saved = dup(fd), file = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  cr_assert(saved >= 0 && file >= 0, "cannot redirect to %s", path);
  dup2(file, fd);
  close(file);
  return saved;
}

static inline void cli_call_restore(int fd, int saved) {
  dup2(saved, fd);
  close(saved);
}

/* cli_run_in's `subsurf ARGS` in `dir`, as a call: r gets the command's
 * exit code, stdout and stderr. */
static inline void cli_call_in(cli_result *r, const char *dir, const char *args) {
  char buf[4096], *argv[64], cwd[4096], out_path[256], err_path[256];
  cr_assert(strlen(args) < sizeof buf);
  int argc = cli_call_split(args, buf, argv, 63);
  argv[argc] = NULL;
  const ss_cli_command *command = argc > 0 ? ss_cli_command_find(argv[0]) : NULL;
  cr_assert(command, "'%s': not a subsurf command", args);
  snprintf(out_path, sizeof out_path, "%s/.stdout", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  cr_assert(getcwd(cwd, sizeof cwd) && chdir(dir) == 0, "cannot enter %s", dir);
  fflush(stdout);
  fflush(stderr);
  int saved_out = cli_call_redirect(STDOUT_FILENO, out_path);
  int saved_err = cli_call_redirect(STDERR_FILENO, err_path);
  r->status = command->run(argc, argv);
  fflush(stdout);
  fflush(stderr);
  cli_call_restore(STDOUT_FILENO, saved_out);
  cli_call_restore(STDERR_FILENO, saved_err);
  cr_assert(chdir(cwd) == 0);
  cli_slurp(out_path, r->out, sizeof r->out);
  cli_slurp(err_path, r->err, sizeof r->err);
  unlink(out_path);
  unlink(err_path);
}

/* cli_expect_bad_input, the command called in this process. */
static inline void cli_call_expect_bad_input(cli_result *r, const char *dir, const char *args,
                                             const char *needle) {
  int before = cli_dir_count(dir);
  cli_call_in(r, dir, args);
  cli_check_bad_input(r, dir, args, needle, before);
}

#endif
