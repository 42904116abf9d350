/* The radial profile figure of `subsurf compare-halfspace --plot`: drawn by
 * the PLplot plugin (plplot_plugin.h) into a private temporary file, then
 * copied into the output. */
#include "cli/profile_plot.h"

#include "cli/plplot_plugin.h"
#include "core/atomic_file.h"
#include "io/plugin.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *device_for(const char *path) {
  const char *dot = strrchr(path, '.');
  if (!dot) {
    return NULL;
  }
  if (!strcmp(dot, ".svg")) {
    return "svg";
  }
  if (!strcmp(dot, ".pdf")) {
    return "pdf";
  }
  if (!strcmp(dot, ".ps")) {
    return "psc";
  }
  return NULL;
}

int ss_profile_plot_supported(const char *path) { return device_for(path) != NULL; }

/* The plugin's drawing function, opened once per process; NULL with err set
 * when it cannot be used. */
static ss_plplot_draw_fn *plugin_draw(ss_error *err) {
  static ss_plplot_draw_fn *draw;
  const ss_dynlib_symbol symbol = {"ss_plplot_plugin_draw", (void **)&draw};
  if (!draw) {
    ss_plugin_open(SS_PLPLOT_PLUGIN_FILE, "--plot", "libplplot", &symbol, 1, err);
  }
  return draw;
}

int ss_profile_plot_ready(const char *cmd) {
  ss_error err;
  if (!plugin_draw(&err)) {
    fprintf(stderr, "subsurf %s: --plot: %s\n", cmd, err.message);
    return -1;
  }
  return 0;
}

/* Copies the finished plot into the output (atomically, or straight into a
 * device or FIFO: core/atomic_file.h). */
static ss_status copy_into(const char *from, ss_atomic_file *out, ss_error *err) {
  FILE *f = fopen(from, "rb");
  if (!f) {
    return ss_error_set(err, SS_ERR_IO, "the plot was not written");
  }
  char buf[65536];
  size_t n;
  ss_status st = SS_OK;
  while (st == SS_OK && (n = fread(buf, 1, sizeof buf, f)) > 0) {
    st = ss_atomic_file_write(out, buf, n, err);
  }
  if (st == SS_OK && ferror(f)) {
    st = ss_error_set(err, SS_ERR_IO, "cannot read the plot back");
  }
  fclose(f);
  return st;
}

int ss_profile_plot_write(const char *cmd, const char *path, const char *title, const double *r,
                          const ss_estimate *ref, int n, const double *const *models,
                          const char *const *names, int nmodels) {
  if (ss_profile_plot_ready(cmd) != 0) {
    return -1;
  }
  ss_error err;
  ss_plplot_draw_fn *draw = plugin_draw(&err);
  ss_atomic_file out;
  if (ss_atomic_file_open(&out, path, ss_file_kind_of_name(path, SS_FILE_PS), &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: --plot: %s\n", cmd, err.message);
    return -1;
  }
  /* PLplot writes a private temporary file: it can always open it, and the
   * output is only touched once the plot is complete. */
  const char *tmpdir = getenv("TMPDIR");
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s/subsurf-plot-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
  int fd = mkstemp(tmp);
  if (fd >= 0) {
    close(fd);
  }
  ss_plot_data d = {title, r, ref, n, models, names, nmodels};
  char why[512];
  int rc = -1, released = 0;
  if (fd < 0) {
    fprintf(stderr, "subsurf %s: --plot: cannot create a temporary file in %s: %s\n", cmd,
            tmpdir && *tmpdir ? tmpdir : "/tmp", strerror(errno));
  } else if (draw(device_for(path), tmp, &d, why, sizeof why) != 0) {
    fprintf(stderr, "subsurf %s: --plot: PLplot could not draw '%s': %s\n", cmd, path, why);
  } else if (copy_into(tmp, &out, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: --plot: cannot write '%s': %s\n", cmd, path, err.message);
  } else if (ss_atomic_file_commit(&out, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: --plot: %s\n", cmd, err.message);
    released = 1;
  } else {
    rc = 0;
  }
  if (rc != 0 && !released) {
    ss_atomic_file_abort(&out);
  }
  if (fd >= 0) {
    unlink(tmp);
  }
  return rc;
}
