/* The CLI's progress bar draws only on a terminal, at most 10 times a second,
 * and reports elapsed and remaining time. A pseudo terminal stands in for the
 * user's terminal. */
#define _XOPEN_SOURCE 700
#include "cli/progress_bar.h"

#include <criterion/criterion.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static void sleep_seconds(double s) {
  struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
  nanosleep(&ts, NULL);
}

/* Replaces stderr by the slave side of a new pseudo terminal; returns the
 * master side, from which the test reads what was drawn. */
static int stderr_to_pty(void) {
  int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0) {
    cr_skip_test("no pseudo terminal available (posix_openpt failed)");
  }
  cr_assert_eq(grantpt(master), 0);
  cr_assert_eq(unlockpt(master), 0);
  int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
  cr_assert(slave >= 0, "cannot open the pty slave");
  cr_assert(dup2(slave, STDERR_FILENO) >= 0);
  close(slave);
  return master;
}

static size_t drain(int master, char *buf, size_t size) {
  size_t len = 0;
  struct pollfd pfd = {master, POLLIN, 0};
  while (len + 1 < size && poll(&pfd, 1, 100) > 0) {
    ssize_t n = read(master, buf + len, size - 1 - len);
    if (n <= 0) {
      break;
    }
    len += (size_t)n;
  }
  buf[len] = '\0';
  return len;
}

static int count_str(const char *s, const char *needle) {
  int n = 0;
  for (; (s = strstr(s, needle)) != NULL; s += strlen(needle)) {
    ++n;
  }
  return n;
}

Test(progress, draws_nothing_when_stderr_is_not_a_terminal) {
  FILE *f = tmpfile();
  cr_assert_not_null(f);
  cr_assert(dup2(fileno(f), STDERR_FILENO) >= 0);
  ss_progress p;
  ss_progress_begin(&p, "render", 100, 1, 0.0);
  cr_assert_eq(p.enabled, 0, "a file is not a terminal");
  ss_progress_update(&p, 50);
  ss_progress_end(&p, 100);
  fflush(stderr);
  cr_assert_eq(ftell(f), 0L, "nothing may be written to a non-terminal");
}

Test(progress, draws_nothing_when_disabled_on_a_terminal) {
  int master = stderr_to_pty();
  ss_progress p;
  ss_progress_begin(&p, "render", 100, 0, 0.0);
  ss_progress_update(&p, 50);
  ss_progress_end(&p, 100);
  char buf[256];
  cr_assert_eq(drain(master, buf, sizeof buf), 0u, "got '%s'", buf);
}

Test(progress, draws_bar_percentage_and_times_on_a_terminal) {
  int master = stderr_to_pty();
  ss_progress p;
  ss_progress_begin(&p, "halfspace", 200, 1, 0.0);
  cr_assert_eq(p.enabled, 1);
  sleep_seconds(0.05);
  ss_progress_update(&p, 90);
  char buf[4096];
  drain(master, buf, sizeof buf);
  cr_assert_not_null(strstr(buf, "\rhalfspace ["), "got '%s'", buf);
  cr_assert_not_null(strstr(buf, "=>"), "got '%s'", buf);
  cr_assert_not_null(strstr(buf, " 45%"), "got '%s'", buf);
  cr_assert_not_null(strstr(buf, "s elapsed, "), "got '%s'", buf);
  cr_assert_not_null(strstr(buf, "s left"), "got '%s'", buf);
  /* 90 of 200 after ~0.05 s: extrapolation says ~0.06 s left. */
  double elapsed = 0.0, left = 0.0;
  const char *e = strstr(buf, "%  ");
  cr_assert_not_null(e);
  cr_assert_eq(sscanf(e, "%%  %lf s elapsed, %lf s left", &elapsed, &left), 2, "got '%s'", e);
  cr_assert(elapsed >= 0.0 && elapsed < 1.0, "elapsed %g", elapsed);
  cr_assert(left <= 2.0 * elapsed + 0.1, "left %g for elapsed %g at 45%%", left, elapsed);
  ss_progress_end(&p, 200);
  drain(master, buf, sizeof buf);
  cr_assert_not_null(strstr(buf, "100%"), "got '%s'", buf);
  cr_assert_not_null(strchr(buf, '\n'), "the final draw ends the line");
}

Test(progress, redraws_at_most_ten_times_a_second) {
  int master = stderr_to_pty();
  ss_progress p;
  ss_progress_begin(&p, "x", 1000000, 1, 0.0);
  double t0 = ss_seconds();
  uint64_t i = 0;
  while (ss_seconds() - t0 < 0.35) {
    ss_progress_update(&p, ++i);
  }
  char buf[8192];
  drain(master, buf, sizeof buf);
  int draws = count_str(buf, "\rx [");
  /* Redraws at t = 0, >= 0.1, >= 0.2, >= 0.3: never more than 4. */
  cr_assert(draws >= 2 && draws <= 4, "%d redraws in 0.35 s after %llu updates", draws,
            (unsigned long long)i);
}

Test(progress, remaining_time_is_bounded_by_the_time_limit) {
  int master = stderr_to_pty();
  ss_progress p;
  /* 1% done after ~0.05 s extrapolates to ~5 s left; a 0.2 s limit wins. */
  ss_progress_begin(&p, "x", 100, 1, 0.2);
  sleep_seconds(0.05);
  ss_progress_update(&p, 1);
  char buf[1024];
  drain(master, buf, sizeof buf);
  double elapsed = 0.0, left = 0.0;
  const char *e = strstr(buf, "%  ");
  cr_assert_not_null(e, "got '%s'", buf);
  cr_assert_eq(sscanf(e, "%%  %lf s elapsed, %lf s left", &elapsed, &left), 2, "got '%s'", e);
  /* Both are printed to 0.1 s. */
  cr_assert(left <= 0.2 - elapsed + 0.1 && left >= 0.0, "left %g, elapsed %g", left, elapsed);
}

Test(progress, concurrent_updates_draw_whole_lines) {
  int master = stderr_to_pty();
  ss_progress p;
  ss_progress_begin(&p, "par", 4000000, 1, 0.0);
  double t0 = ss_seconds();
#pragma omp parallel num_threads(4)
  {
    uint64_t i = 0;
    while (ss_seconds() - t0 < 0.25) {
      ss_progress_update(&p, ++i);
    }
  }
  ss_progress_end(&p, 4000000);
  char buf[16384];
  drain(master, buf, sizeof buf);
  /* Each draw is one "\rpar [...left\033[K" line: as many line ends as
   * line starts shows that no two threads interleaved their output. */
  int draws = count_str(buf, "\rpar [");
  int ends = count_str(buf, "left\033[K");
  /* t = 0, >= 0.1, >= 0.2, and the final draw. */
  cr_assert(draws >= 2 && draws <= 4, "%d redraws in 0.25 s", draws);
  cr_assert_eq(ends, draws, "%d line ends for %d redraws", ends, draws);
}
