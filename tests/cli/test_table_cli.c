/* `subsurf table`: a build/check round trip with the documented last line,
 * and bad input answered by one line on stderr and exit code 2. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* Runs the CLI with `args`; returns the exit code, fills out/err (first
 * bytes of each stream). */
static int run(const char *args, char *out, size_t out_size, char *err, size_t err_size) {
  const char *bin = getenv("SUBSURF_BIN");
  cr_assert(bin, "SUBSURF_BIN is not set");
  char cmd[2048], out_path[64], err_path[64];
  snprintf(out_path, sizeof out_path, "/tmp/subsurf_table_cli_%ld.out", (long)getpid());
  snprintf(err_path, sizeof err_path, "/tmp/subsurf_table_cli_%ld.err", (long)getpid());
  snprintf(cmd, sizeof cmd, "%s table %s >%s 2>%s", bin, args, out_path, err_path);
  int status = system(cmd);
  const char *paths[2] = {out_path, err_path};
  char *bufs[2] = {out, err};
  size_t sizes[2] = {out_size, err_size};
  for (int k = 0; k < 2; ++k) {
    FILE *f = fopen(paths[k], "r");
    size_t n = f ? fread(bufs[k], 1, sizes[k] - 1, f) : 0;
    bufs[k][n] = '\0';
    if (f) {
      fclose(f);
    }
    remove(paths[k]);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static int count_lines(const char *s) {
  int n = 0;
  for (; *s; ++s) {
    n += *s == '\n';
  }
  return n;
}

Test(table_cli, build_then_check_prints_the_mean_relative_error_last) {
  char out[4096], err[4096], args[512], path[64];
  snprintf(path, sizeof path, "/tmp/subsurf_table_cli_%ld.tbl", (long)getpid());
  snprintf(args, sizeof args, "build --kind radial --eta 1.33 --g 0 -o %s --quiet", path);
  cr_assert_eq(run(args, out, sizeof out, err, sizeof err), 0, "%s", err);
  snprintf(args, sizeof args, "check %s --rho 0.9 --theta 0 --samples 20000", path);
  cr_assert_eq(run(args, out, sizeof out, err, sizeof err), 0, "%s", err);
  const char *last = strstr(out, "mean relative error: ");
  cr_assert(last, "%s", out);
  double value;
  char unit[8];
  cr_assert_eq(sscanf(last, "mean relative error: %lf %7s", &value, unit), 2);
  cr_assert_str_eq(unit, "%");
  cr_assert(value > 0.0 && value < 0.5, "%g", value);
  cr_assert_eq(strchr(last, '\n')[1], '\0', "not the last line: %s", out);
  remove(path);
}

Test(table_cli, bad_input_is_one_line_and_exit_2) {
  char out[4096], err[4096], path[64], args[512];
  snprintf(path, sizeof path, "/tmp/subsurf_table_cli_bad_%ld.tbl", (long)getpid());
  FILE *f = fopen(path, "w");
  fputs("not a table\n", f);
  fclose(f);
  const char *cases[] = {
      "build --eta 0.9 --g 0 -o /tmp/x.tbl",
      "build --eta 1.33 --g 1.5 -o /tmp/x.tbl",
      "build --eta 1.33 --g 0",
      "build --eta abc --g 0 -o /tmp/x.tbl",
      "build --eta 1.33 --g 0 -o /nonexistent/x",
      "build --eta 1.33 --g 0 -o /tmp/x --kind z",
      "frobnicate",
      "check /nonexistent.tbl --rho 0.5 --theta 0",
      "check --rho 0.5 --theta 0",
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    cr_assert_eq(run(cases[k], out, sizeof out, err, sizeof err), 2, "'%s': %s", cases[k], err);
    cr_assert_eq(count_lines(err), 1, "'%s': %s", cases[k], err);
    cr_assert_eq(out[0], '\0', "'%s' wrote to stdout: %s", cases[k], out);
  }
  const char *file_cases[] = {"check %s --rho 0.5 --theta 0", "check %s --rho 1.5 --theta 0",
                              "check %s --rho 0.5 --theta 90"};
  for (size_t k = 0; k < 3; ++k) {
    snprintf(args, sizeof args, file_cases[k], path);
    cr_assert_eq(run(args, out, sizeof out, err, sizeof err), 2, "'%s': %s", args, err);
    cr_assert_eq(count_lines(err), 1, "'%s': %s", args, err);
  }
  cr_assert(access("/tmp/x.tbl", F_OK) != 0, "a failed build left a file");
  remove(path);
}
