/* Runs the `subsurf` binary (SUBSURF_BIN, set by CTest) for CLI tests and
 * captures its exit code, stdout and stderr; the Criterion expectations the
 * bad-input tests of several commands share. */
#ifndef SUBSURF_TESTS_CLI_RUN_H
#define SUBSURF_TESTS_CLI_RUN_H

#include <criterion/criterion.h>
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct {
  int status; /* exit code, or 128 + signal */
  char out[1 << 16];
  char err[1 << 14];
} cli_result;

static inline void cli_slurp(const char *path, char *buf, size_t size) {
  FILE *f = fopen(path, "r");
  size_t n = f ? fread(buf, 1, size - 1, f) : 0;
  buf[n] = '\0';
  if (f) {
    fclose(f);
  }
}

/* Runs `subsurf ARGS` through the shell in `dir`. If interrupt_after > 0,
 * sends SIGINT after that many seconds. */
static inline void cli_run_in(cli_result *r, const char *dir, const char *args,
                              double interrupt_after) {
  const char *bin = getenv("SUBSURF_BIN");
  char out_path[256], err_path[256], cmd[4096];
  snprintf(out_path, sizeof out_path, "%s/.stdout", dir);
  snprintf(err_path, sizeof err_path, "%s/.stderr", dir);
  snprintf(cmd, sizeof cmd, "cd '%s' && exec '%s' %s >'%s' 2>'%s' </dev/null", dir,
           bin ? bin : "subsurf", args, out_path, err_path);
  pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
    _exit(127);
  }
  if (interrupt_after > 0.0) {
    struct timespec ts = {(time_t)interrupt_after,
                          (long)((interrupt_after - (double)(time_t)interrupt_after) * 1e9)};
    nanosleep(&ts, NULL);
    kill(pid, SIGINT);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  r->status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  cli_slurp(out_path, r->out, sizeof r->out);
  cli_slurp(err_path, r->err, sizeof r->err);
  unlink(out_path);
  unlink(err_path);
}

/* A fresh temporary directory for one test. */
static inline void cli_tmpdir(char *dir, size_t size) {
  snprintf(dir, size, "/tmp/subsurf-cli-XXXXXX");
  if (!mkdtemp(dir)) {
    dir[0] = '\0';
  }
}

static inline int cli_file_exists(const char *dir, const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return access(path, F_OK) == 0;
}

/* No visible entry in dir (the run's own .stdout/.stderr are hidden). */
static inline int cli_dir_is_empty(const char *dir) {
  DIR *d = opendir(dir);
  struct dirent *e;
  int n = 0;
  while (d && (e = readdir(d))) {
    n += e->d_name[0] != '.';
  }
  if (d) {
    closedir(d);
  }
  return n == 0;
}

/* The bad-input contract (common.md): exit code 2, exactly one line on
 * stderr naming `needle`, no output file left in dir. */
static inline void cli_expect_bad_input(cli_result *r, const char *dir, const char *args,
                                        const char *needle) {
  cli_run_in(r, dir, args, 0.0);
  cr_expect_eq(r->status, 2, "'%s' exited %d; stderr: %s", args, r->status, r->err);
  cr_expect(strstr(r->err, needle) != NULL, "'%s': stderr should name '%s', got: %s", args,
            needle, r->err);
  cr_expect(strchr(r->err, '\n') == r->err + strlen(r->err) - 1,
            "'%s': expected one line on stderr, got: %s", args, r->err);
  cr_expect(cli_dir_is_empty(dir), "'%s' left a file behind", args);
}

#endif
