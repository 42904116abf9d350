/* `compare-halfspace --plot`: every format PLplot writes (svg, pdf, ps) is
 * produced, leak-free under the sanitizers; the plot goes through symbolic
 * links and into devices without replacing them; a failure is one line on
 * stderr (never PLplot's own multi-line report) and writes nothing, and a
 * missing plugin (libsubsurf_plplot.so) is found before the run. */
#include <criterion/criterion.h>

#include "cli/cli_run.h"

#include <sys/stat.h>

static char dir[64];
static cli_result res;

static void setup(void) {
  cli_tmpdir(dir, sizeof dir);
  cr_assert(dir[0]);
}

static void teardown(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_expect_eq(system(cmd), 0);
}

TestSuite(profile_plot_cli, .init = setup, .fini = teardown);

#define COMPARE                                                                                    \
  "compare-halfspace --models dipole --sigma-s 0.9 --sigma-a 0.1 --paths 2000 --threads 1 "        \
  "--quiet --rbins 8 --plot "

static void plot(const char *target, const char *env) {
  char args[512];
  snprintf(args, sizeof args, "%s%s", COMPARE, target);
  if (env) {
    setenv("TMPDIR", env, 1);
  }
  cli_run_in(&res, dir, args, 0.0);
  unsetenv("TMPDIR");
}

Test(profile_plot_cli, every_format_is_written_with_its_magic) {
  const char *names[3] = {"p.svg", "p.pdf", "p.ps"};
  const char *magic[3] = {"<?xml", "%PDF-", "%!PS-"};
  for (int i = 0; i < 3; ++i) {
    plot(names[i], NULL);
    cr_assert_eq(res.status, 0, "%s: exit %d, stderr: %s", names[i], res.status, res.err);
    char path[256], head[8] = {0};
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s was not written", names[i]);
    cr_assert_eq(fread(head, 1, 5, f), 5u);
    fclose(f);
    cr_expect_str_eq(head, magic[i], "%s starts with '%s'", names[i], head);
  }
  cr_expect_eq(cli_dir_count(dir), 3, "no temporary file is left");
}

Test(profile_plot_cli, a_link_to_a_device_stays_a_link) {
  char link[256];
  snprintf(link, sizeof link, "%s/null.svg", dir);
  cr_assert_eq(symlink("/dev/null", link), 0);
  plot("null.svg", NULL);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  struct stat sb;
  cr_assert_eq(lstat(link, &sb), 0);
  cr_assert(S_ISLNK(sb.st_mode), "the link was replaced");
  cr_assert_eq(stat("/dev/null", &sb), 0);
  cr_assert(S_ISCHR(sb.st_mode));
}

static void expect_one_line_failure(const char *needle) {
  cr_expect_eq(res.status, 1, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(strstr(res.err, needle) != NULL, "stderr should say '%s': %s", needle, res.err);
  cr_expect(strchr(res.err, '\n') == res.err + strlen(res.err) - 1, "one line: %s", res.err);
  cr_expect(strstr(res.err, "PLPLOT") == NULL, "PLplot's own report: %s", res.err);
}

Test(profile_plot_cli, failures_are_one_line_and_write_nothing) {
  char sub[256];
  snprintf(sub, sizeof sub, "%s/busy.svg", dir);
  cr_assert_eq(mkdir(sub, 0755), 0);
  plot("busy.svg", NULL);
  /* A directory is refused with the other bad input, before the run. */
  cr_expect_eq(res.status, 2, "exit %d, stderr: %s", res.status, res.err);
  cr_expect(strstr(res.err, "is a directory") != NULL, "stderr: %s", res.err);
  cr_expect(strchr(res.err, '\n') == res.err + strlen(res.err) - 1, "one line: %s", res.err);
  plot("p.svg", "/nonexistent-tmpdir");
  expect_one_line_failure("cannot create a temporary file");
  cr_expect_eq(cli_dir_count(dir), 1, "only the directory is there");
}

/* PLplot is in the plugin libsubsurf_plplot.so: a copy of the binary with no
 * plugin beside it (nor in ../lib) says so in one line before the run (no
 * table on stdout) and writes nothing. */
Test(profile_plot_cli, a_missing_plugin_is_one_line_before_the_run) {
  char cmd[1024];
  snprintf(cmd, sizeof cmd,
           "cp '%s' '%s/alone' && cd '%s' && ./alone " COMPARE "p.svg >out.txt 2>err.txt",
           getenv("SUBSURF_BIN"), dir, dir);
  int st = system(cmd);
  res.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128;
  char path[256];
  snprintf(path, sizeof path, "%s/err.txt", dir);
  cli_slurp(path, res.err, sizeof res.err);
  expect_one_line_failure("--plot: the plugin libsubsurf_plplot.so (for --plot) was found neither "
                          "beside ./alone nor in ../lib");
  snprintf(path, sizeof path, "%s/out.txt", dir);
  cli_slurp(path, res.out, sizeof res.out);
  cr_expect_str_empty(res.out, "the run happened: %s", res.out);
  cr_expect(!cli_file_exists(dir, "p.svg"));
}
