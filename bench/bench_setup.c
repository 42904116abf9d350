/* Set-up time of scenes/skin_sphere.json: the library's phases
 * (the 327 680-triangle icosphere with its uvs, the closedness check the
 * scene skips for generated shapes, Embree's low- and high-quality builds,
 * the whole scene read) and the set-up as the user sees it: the CPU and
 * wall time of a `subsurf render` process that traces one sample (one
 * pixel at 1 spp, one thread), from exec to exit, and of `subsurf --help`
 * (process start alone). Medians of REPS runs, CPU time of all threads.
 * usage: bench_setup [REPS (default 7)] [SUBSURF_BINARY ...]
 * (default: the subsurf beside this program); several binaries are run in
 * turn, one run each per round, so that they share the machine's load. */
#define _DEFAULT_SOURCE /* wait4 */
#include "bench_clock.h"
#include "bench_scene.h"
#include "subsurf/accel.h"
#include "subsurf/mesh.h"
#include "subsurf/progress.h"

#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#define MAX_REPS 101
#define MAX_BINARIES 4

typedef struct {
  double cpu[MAX_REPS], wall[MAX_REPS];
} timings;

static double median(double *x, int n) {
  qsort(x, (size_t)n, sizeof *x, compare_doubles);
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

static void report(const char *what, timings *t, int n) {
  double lo_c = t->cpu[0], hi_c = t->cpu[0];
  for (int i = 1; i < n; ++i) {
    lo_c = t->cpu[i] < lo_c ? t->cpu[i] : lo_c;
    hi_c = t->cpu[i] > hi_c ? t->cpu[i] : hi_c;
  }
  double mc = median(t->cpu, n), mw = median(t->wall, n);
  printf("%-58s %8.4f %8.4f-%-8.4f %8.4f\n", what, mc, lo_c, hi_c, mw);
}

/* One run of argv as a child: its CPU time (user + sys, all threads) and
 * wall time; 0 on success. */
static int run_child(char *const argv[], double *cpu, double *wall) {
  fflush(stdout); /* the child must not print this process's buffer */
  double t0 = ss_seconds();
  pid_t pid = fork();
  if (pid < 0) {
    return -1;
  }
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) {
      _exit(127);
    }
    execv(argv[0], argv);
    _exit(127);
  }
  int status;
  struct rusage ru;
  if (wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return -1;
  }
  *wall = ss_seconds() - t0;
  *cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
  return 0;
}

static ss_mesh *sphere(double radius, unsigned subdivisions, ss_vec3 centre) {
  ss_mesh *m;
  ss_error err;
  if (ss_shape_icosphere(radius, subdivisions, &m, &err) != SS_OK ||
      ss_mesh_transform(m, ss_mat4_translate(centre), &err) != SS_OK) {
    fprintf(stderr, "bench_setup: %s\n", err.message);
    exit(1);
  }
  return m;
}

static void library_phases(int reps) {
  timings ico, closed, low, high, scene;
  char path[4200];
  bench_scene_path(path, sizeof path, "skin_sphere.json");
  for (int r = 0; r < reps; ++r) {
    double c0 = process_seconds(), w0 = ss_seconds();
    ss_mesh *m = sphere(1.0, 7, ss_vec3_make(0, 0, 0));
    ico.cpu[r] = process_seconds() - c0;
    ico.wall[r] = ss_seconds() - w0;
    ss_mesh *lamp = sphere(2.0, 4, ss_vec3_make(6, 2, -2));
    ss_error err;
    c0 = process_seconds(), w0 = ss_seconds();
    if (ss_mesh_check_closed(m, &err) != SS_OK) {
      fprintf(stderr, "bench_setup: %s\n", err.message);
      exit(1);
    }
    closed.cpu[r] = process_seconds() - c0;
    closed.wall[r] = ss_seconds() - w0;
    const ss_mesh *meshes[2] = {m, lamp};
    ss_accel *a;
    c0 = process_seconds(), w0 = ss_seconds();
    if (ss_accel_create(meshes, 2, &a, &err) != SS_OK) {
      fprintf(stderr, "bench_setup: %s\n", err.message);
      exit(1);
    }
    low.cpu[r] = process_seconds() - c0;
    low.wall[r] = ss_seconds() - w0;
    c0 = process_seconds(), w0 = ss_seconds();
    if (ss_accel_refine(a, &err) != SS_OK) {
      fprintf(stderr, "bench_setup: %s\n", err.message);
      exit(1);
    }
    high.cpu[r] = process_seconds() - c0;
    high.wall[r] = ss_seconds() - w0;
    ss_accel_destroy(a);
    ss_mesh_destroy(m);
    ss_mesh_destroy(lamp);
    c0 = process_seconds(), w0 = ss_seconds();
    ss_scene *s = bench_read_scene(path);
    if (!s) {
      exit(1);
    }
    scene.cpu[r] = process_seconds() - c0;
    scene.wall[r] = ss_seconds() - w0;
    ss_scene_destroy(s);
  }
  report("icosphere, 7 subdivisions, with uvs (327 680 triangles)", &ico, reps);
  report("closedness check of it (skipped: closed by construction)", &closed, reps);
  report("Embree BVH, low quality (ss_accel_create, both spheres)", &low, reps);
  report("Embree BVH, high quality (ss_accel_refine)", &high, reps);
  report("skin_sphere.json read + commit (in process)", &scene, reps);
}

static void process_runs(int reps, char **binaries, int count) {
  char path[4200], out[64];
  bench_scene_path(path, sizeof path, "skin_sphere.json");
  snprintf(out, sizeof out, "/tmp/bench_setup_%d.exr", (int)getpid());
  timings help[MAX_BINARIES], render[MAX_BINARIES];
  for (int r = 0; r < reps; ++r) {
    for (int b = 0; b < count; ++b) {
      char *help_argv[] = {binaries[b], "--help", NULL};
      char *render_argv[] = {binaries[b], "render",  path,        "--spp", "1",
                             "--crop",    "0,0,1,1", "--threads", "1",     "--quiet",
                             "--no-png",  "-o",      out,         NULL};
      if (run_child(help_argv, &help[b].cpu[r], &help[b].wall[r]) != 0 ||
          run_child(render_argv, &render[b].cpu[r], &render[b].wall[r]) != 0) {
        fprintf(stderr, "bench_setup: %s failed\n", binaries[b]);
        exit(1);
      }
    }
  }
  remove(out);
  for (int b = 0; b < count; ++b) {
    char what[PATH_MAX + 64];
    printf("%s:\n", binaries[b]);
    snprintf(what, sizeof what, "  process start to exit (subsurf --help)");
    report(what, &help[b], reps);
    snprintf(what, sizeof what, "  set-up to the first sample (render, 1 pixel, 1 spp)");
    report(what, &render[b], reps);
  }
}

int main(int argc, char **argv) {
  int reps = argc > 1 ? atoi(argv[1]) : 7;
  if (reps < 1 || reps > MAX_REPS || argc - 2 > MAX_BINARIES) {
    fprintf(stderr, "usage: bench_setup [REPS in 1..%d] [SUBSURF_BINARY ... (at most %d)]\n",
            MAX_REPS, MAX_BINARIES);
    return 2;
  }
  char self[PATH_MAX], beside[PATH_MAX + 16];
  ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  self[n > 0 ? n : 0] = '\0';
  snprintf(beside, sizeof beside, "%s/subsurf", dirname(self));
  char *fallback[1] = {beside};
  char **binaries = argc > 2 ? argv + 2 : fallback;
  int count = argc > 2 ? argc - 2 : 1;
  printf("%-58s %8s %17s %8s\n", "phase (median of runs; CPU s of all threads)", "CPU", "CPU range",
         "wall");
  library_phases(reps);
  process_runs(reps, binaries, count);
  return 0;
}
