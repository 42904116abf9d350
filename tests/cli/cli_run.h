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

static inline void cli_sleep(double seconds) {
  struct timespec ts = {(time_t)seconds, (long)((seconds - (double)(time_t)seconds) * 1e9)};
  nanosleep(&ts, NULL);
}

/* 1 when dir/name exists. */
static inline int cli_path_exists(const char *dir, const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return access(path, F_OK) == 0;
}

/* Monotonic seconds, to bound how long a command takes. */
static inline double cli_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* 1 when the child pid has ended; it is left to be reaped by waitpid. */
static inline int cli_has_ended(pid_t pid) {
  siginfo_t info;
  memset(&info, 0, sizeof info);
  return waitid(P_PID, (id_t)pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

/* 1 when pid runs `subsurf` (the shell has exec'd it) and has installed a
 * handler for sig (its SigCgt mask in /proc/PID/status). */
static inline int cli_catches(pid_t pid, int sig) {
  char path[64], line[256];
  snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
  FILE *f = fopen(path, "r");
  int is_subsurf = 0, catches = 0;
  while (f && fgets(line, sizeof line, f)) {
    if (strncmp(line, "Name:", 5) == 0) {
      is_subsurf = strstr(line, "subsurf") != NULL;
    } else if (strncmp(line, "SigCgt:", 7) == 0) {
      catches = (strtoull(line + 7, NULL, 16) >> (sig - 1)) & 1u;
    }
  }
  if (f) {
    fclose(f);
  }
  return is_subsurf && catches;
}

/* Runs `subsurf ARGS` through the shell in `dir`. If after > 0, sends `count`
 * copies of signal `sig`, the first after `after` seconds (counted from the
 * moment dir/wait_for exists, when wait_for is not NULL: a signal tied to the
 * program's progress rather than to the machine's speed), then one every
 * `gap` seconds. The delay starts only once the program has installed its
 * handler for sig (for at most a minute), so that a loaded machine that is
 * slow to start it does not turn the test into one of the default action. */
static inline void cli_run_signalled_after_file(cli_result *r, const char *dir, const char *args,
                                                const char *wait_for, double after, int sig,
                                                int count, double gap) {
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
  if (after > 0.0) {
    double give_up = cli_now() + 60.0;
    while ((!cli_catches(pid, sig) || (wait_for && !cli_path_exists(dir, wait_for))) &&
           !cli_has_ended(pid) && cli_now() < give_up) {
      cli_sleep(0.005);
    }
    cli_sleep(after);
    for (int i = 0; i < count; ++i) {
      if (i > 0) {
        cli_sleep(gap);
      }
      kill(pid, sig);
    }
  }
  int status = 0;
  waitpid(pid, &status, 0);
  r->status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  cli_slurp(out_path, r->out, sizeof r->out);
  cli_slurp(err_path, r->err, sizeof r->err);
  unlink(out_path);
  unlink(err_path);
}

/* cli_run_signalled_after_file with no file to wait for. */
static inline void cli_run_signalled(cli_result *r, const char *dir, const char *args, double after,
                                     int sig, int count, double gap) {
  cli_run_signalled_after_file(r, dir, args, NULL, after, sig, count, gap);
}

/* Runs `subsurf ARGS` through the shell in `dir`. If interrupt_after > 0,
 * sends SIGINT after that many seconds. */
static inline void cli_run_in(cli_result *r, const char *dir, const char *args,
                              double interrupt_after) {
  cli_run_signalled(r, dir, args, interrupt_after, SIGINT, 1, 0.0);
}

/* A fresh temporary directory for one test. */
static inline void cli_tmpdir(char *dir, size_t size) {
  snprintf(dir, size, "/tmp/subsurf-cli-XXXXXX");
  if (!mkdtemp(dir)) {
    dir[0] = '\0';
  }
}

/* Writes `text` to dir/name (for scene files made by a test). */
static inline void cli_write_file(const char *dir, const char *name, const char *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f, "cannot write %s", path);
  fputs(text, f);
  fclose(f);
}

/* Removes the test's directory and everything in it. */
static inline void cli_rmdir(const char *dir) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

static inline int cli_file_exists(const char *dir, const char *name) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return access(path, F_OK) == 0;
}

/* Visible entries in dir (the run's own .stdout/.stderr are hidden). */
static inline int cli_dir_count(const char *dir) {
  DIR *d = opendir(dir);
  struct dirent *e;
  int n = 0;
  while (d && (e = readdir(d))) {
    n += e->d_name[0] != '.';
  }
  if (d) {
    closedir(d);
  }
  return n;
}

/* No visible entry in dir (the run's own .stdout/.stderr are hidden). */
static inline int cli_dir_is_empty(const char *dir) { return cli_dir_count(dir) == 0; }

/* A test suite whose tests each run in a fresh temporary directory `dir`
 * (removed afterwards), with `res` for the command's result. */
#define CLI_SUITE(name)                                                                            \
  static char dir[64];                                                                             \
  static cli_result res;                                                                           \
  static void name##_setup(void) {                                                                 \
    cli_tmpdir(dir, sizeof dir);                                                                   \
    cr_assert(dir[0]);                                                                             \
  }                                                                                                \
  static void name##_teardown(void) { cli_rmdir(dir); }                                            \
  TestSuite(name, .init = name##_setup, .fini = name##_teardown)

/* The bad-input contract (common.md) for the result r of `args` run in dir,
 * which held `before` entries: exit code 2, exactly one line on stderr
 * naming `needle`, no new file in dir. */
static inline void cli_check_bad_input(const cli_result *r, const char *dir, const char *args,
                                       const char *needle, int before) {
  cr_expect_eq(r->status, 2, "'%s' exited %d; stderr: %s", args, r->status, r->err);
  cr_expect(strstr(r->err, needle) != NULL, "'%s': stderr should name '%s', got: %s", args, needle,
            r->err);
  cr_expect(strchr(r->err, '\n') == r->err + strlen(r->err) - 1,
            "'%s': expected one line on stderr, got: %s", args, r->err);
  cr_expect_eq(cli_dir_count(dir), before, "'%s' left a file behind", args);
}

/* `subsurf ARGS` in dir keeps the bad-input contract. */
static inline void cli_expect_bad_input(cli_result *r, const char *dir, const char *args,
                                        const char *needle) {
  int before = cli_dir_count(dir);
  cli_run_in(r, dir, args, 0.0);
  cli_check_bad_input(r, dir, args, needle, before);
}

#endif
