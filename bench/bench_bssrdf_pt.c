/* Speed of the `bssrdf` integrator against volpath (issue 9): for volpath
 * and each model, the CPU time to reach a relMSE of 0.01 on a centred crop
 * of the scene, the speed-up over volpath, probe queries per CPU second,
 * and the memory the scene's BSSRDF cache adds (resident set before and
 * after building it).
 *
 * The estimate: each method renders the crop SEEDS times at SPP samples per
 * pixel with independent seeds S..S+SEEDS-1 (S = $BENCH_SEED, default 1:
 * set it to repeat a run independently). Per pixel and channel the sample
 * variance of those images over the square of the median of all methods'
 * mean images (+ 0.01, as relMSE), averaged over the crop, is the relMSE of
 * one image at SPP; the time to relMSE 0.01 is the mean CPU time of one
 * image times that relMSE / 0.01 (relMSE falls as 1/time). The error bar is
 * the jackknife standard error over the seeds (each seed left out in turn),
 * so that heavy-tailed pixels show as a wide bar instead of a silently wrong
 * figure; the speed-up's bar combines both methods' relative errors. All
 * times are process CPU time (user + system), so run it with
 * OMP_NUM_THREADS=1 on a loaded machine, and compare methods within one run
 * (volpath is rendered first in every run).
 * usage: bench_bssrdf_pt [SCENE.json CROP VOLPATH_SPP MODEL_SPP SEEDS MODEL...]
 * (VOLPATH_SPP 0: the models alone, speed-ups n/a);
 * without arguments a quick run on scenes/marble_sphere_mm.json (from
 * $SUBSURF_SOURCE_DIR or the current directory). */
#include "bench_scene.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

static double peak_rss_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

/* Process CPU seconds (user + system): with one thread the render's own
 * work, whatever else the machine runs. */
static double cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec +
         1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static ss_film *render(ss_scene *s, const char *integrator, int spp, uint64_t seed,
                       const int crop[4], ss_render_stats *st) {
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = spp;
  o.seed = seed;
  memcpy(o.crop, crop, sizeof o.crop);
  ss_film *film = NULL;
  ss_error err;
  double t0 = cpu_seconds();
  if (ss_render(s, &o, &film, st, &err) != SS_OK) {
    fprintf(stderr, "render: %s\n", err.message);
    exit(1);
  }
  st->seconds = cpu_seconds() - t0;
  return film;
}

#define MAX_SEEDS 64
#define MAX_METHODS 32

/* One method's images (one per seed) and rates. */
typedef struct {
  const char *name;
  int seeds;
  ss_film *img[MAX_SEEDS];
  double sec[MAX_SEEDS]; /* CPU s of each image */
  double probes;         /* probe queries per CPU second */
  double cache_mb;
} run;

typedef struct {
  double image_seconds, image_rel_mse; /* mean CPU s of one image, relMSE of one image */
  double seconds, err;                 /* CPU s to relMSE 0.01 and its jackknife standard error */
} timing;

static void render_seeds(ss_scene *s, const char *integrator, int spp, int seeds,
                         uint64_t first_seed, const int crop[4], run *r) {
  unsigned long long probes = 0;
  double cpu = 0.0;
  r->seeds = seeds;
  for (int k = 0; k < seeds; ++k) {
    ss_render_stats st;
    r->img[k] = render(s, integrator, spp, first_seed + (uint64_t)k, crop, &st);
    r->sec[k] = st.seconds;
    probes += st.work.probe_rays;
    cpu += st.seconds;
  }
  r->probes = (double)probes / cpu;
}

static ss_rgb mean_of(const run *r, int x, int y) {
  ss_rgb m = ss_rgb_gray(0.0);
  for (int k = 0; k < r->seeds; ++k) {
    m = ss_rgb_add(m, ss_film_pixel_mean(r->img[k], x, y));
  }
  return ss_rgb_scale(m, 1.0 / r->seeds);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The relMSE denominator per pixel and channel: the median over the methods
 * of their mean images. A method's own mean would correlate with its
 * variance (an outlier raises both, so heavy-tailed volpath looked faster
 * the fewer samples it had: 131 s to relMSE 0.01 from 6 x 1 spp, 251 s from
 * 8 x 8 spp); the models' low-noise means fix the scale for all. */
static double *denominator(const run *runs, int n, int w, int h) {
  double *d = malloc(sizeof *d * (size_t)w * (size_t)h * 3);
  if (!d) {
    fprintf(stderr, "out of memory\n");
    exit(1);
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double v[3][MAX_METHODS];
      for (int j = 0; j < n; ++j) {
        ss_rgb m = mean_of(&runs[j], x, y);
        for (int c = 0; c < 3; ++c) {
          v[c][j] = m.c[c];
        }
      }
      for (int c = 0; c < 3; ++c) {
        qsort(v[c], (size_t)n, sizeof v[c][0], cmp_double);
        double med = n % 2 ? v[c][n / 2] : 0.5 * (v[c][n / 2 - 1] + v[c][n / 2]);
        d[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] = med * med + 1e-2;
      }
    }
  }
  return d;
}

/* CPU seconds to relMSE 0.01 from the images of r except `skip` (-1:
 * none); *t and *e (when not NULL) get the mean CPU time and the relMSE of
 * one image (sample variance across the seeds over den). */
static double seconds_to_target(const run *r, const double *den, int skip, double *t, double *e) {
  int n = r->seeds, m = n - (skip >= 0);
  int w = ss_film_width(r->img[0]), h = ss_film_height(r->img[0]);
  double sum = 0.0, time = 0.0;
  for (int k = 0; k < n; ++k) {
    time += k == skip ? 0.0 : r->sec[k];
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_rgb v[MAX_SEEDS];
      ss_rgb mean = ss_rgb_gray(0.0);
      for (int k = 0; k < n; ++k) {
        v[k] = ss_film_pixel_mean(r->img[k], x, y);
        mean = k == skip ? mean : ss_rgb_add(mean, v[k]);
      }
      mean = ss_rgb_scale(mean, 1.0 / m);
      for (int c = 0; c < 3; ++c) {
        double var = 0.0;
        for (int k = 0; k < n; ++k) {
          double d = v[k].c[c] - mean.c[c];
          var += k == skip ? 0.0 : d * d;
        }
        sum += var / (m - 1) / den[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] / 3.0;
      }
    }
  }
  time /= m;
  sum /= w * h;
  if (t) {
    *t = time;
    *e = sum;
  }
  return time * sum / 0.01;
}

/* The figure of one method and its jackknife standard error over the seeds. */
static timing measure(const run *r, const double *den) {
  timing out = {0};
  out.seconds = seconds_to_target(r, den, -1, &out.image_seconds, &out.image_rel_mse);
  double jk[MAX_SEEDS], jk_mean = 0.0, ss = 0.0;
  for (int k = 0; k < r->seeds; ++k) {
    jk[k] = seconds_to_target(r, den, k, NULL, NULL);
    jk_mean += jk[k] / r->seeds;
  }
  for (int k = 0; k < r->seeds; ++k) {
    ss += (jk[k] - jk_mean) * (jk[k] - jk_mean);
  }
  out.err = sqrt((r->seeds - 1.0) / r->seeds * ss);
  return out;
}

int main(int argc, char **argv) {
  char scene[4096];
  bench_scene_path(scene, sizeof scene, "marble_sphere_mm.json");
  char *quick[] = {argv[0], scene, "16", "2", "4", "4", "dipole", "pbd", "table-gwc"};
  if (argc == 1) {
    argc = 9;
    argv = quick;
  }
  if (argc < 7 || argc - 6 >= MAX_METHODS) {
    fprintf(stderr,
            "usage: bench_bssrdf_pt SCENE.json CROP VOLPATH_SPP MODEL_SPP SEEDS MODEL... "
            "(at most %d models)\n",
            MAX_METHODS - 1);
    return 2;
  }
  int c = atoi(argv[2]), vol_spp = atoi(argv[3]), spp = atoi(argv[4]), seeds = atoi(argv[5]);
  if (c < 1 || vol_spp < 0 || spp < 1 || seeds < 3 || seeds > MAX_SEEDS) {
    fprintf(stderr,
            "bench_bssrdf_pt: CROP, MODEL_SPP >= 1, VOLPATH_SPP >= 0 (0: no volpath), SEEDS in "
            "[3, %d]\n",
            MAX_SEEDS);
    return 2;
  }
  ss_scene *s = bench_read_scene(argv[1]);
  if (!s) {
    return 2;
  }
  ss_error err;
  int x0 = (s->camera.width - c) / 2, y0 = (s->camera.height - c) / 2;
  const int crop[4] = {x0, y0, x0 + c, y0 + c};
  const char *seed_env = getenv("BENCH_SEED");
  uint64_t first_seed = seed_env ? strtoull(seed_env, NULL, 10) : 1;
  static run runs[MAX_METHODS];
  int n = 0;
  if (vol_spp > 0) {
    runs[n].name = "volpath";
    render_seeds(s, "volpath", vol_spp, seeds, first_seed, crop, &runs[n++]);
  }
  int material = s->shapes[0].material;
  for (int k = 6; k < argc; ++k) {
    snprintf(s->materials[material].bssrdf, SS_NAME_SIZE, "%s", argv[k]);
    s->materials[material].lod = SS_LOD_BSSRDF;
    ss_subsurface_destroy(s->subsurface);
    double rss0 = peak_rss_mb();
    if (ss_subsurface_create(s, &s->subsurface, &err) != SS_OK) {
      printf("%-14s n/a: %s\n", argv[k], err.message);
      continue;
    }
    runs[n].name = argv[k];
    runs[n].cache_mb = peak_rss_mb() - rss0;
    render_seeds(s, "bssrdf", spp, seeds, first_seed, crop, &runs[n++]);
  }
  if (n == 0) {
    ss_scene_destroy(s);
    return 1;
  }
  double *den = denominator(runs, n, c, c);
  printf("seeds %llu..%llu; volpath %d spp, models %d spp per image\n",
         (unsigned long long)first_seed, (unsigned long long)first_seed + (unsigned)seeds - 1,
         vol_spp, spp);
  printf("%-14s %10s %10s %22s %16s %12s %10s\n", "method", "s/image", "relMSE/im",
         "CPU s to relMSE .01", "speed-up", "probes/s", "cache MB");
  timing vol = {.seconds = NAN};
  for (int j = 0; j < n; ++j) {
    timing t = measure(&runs[j], den);
    if (vol_spp > 0 && j == 0) {
      vol = t;
      printf("%-14s %10.4g %10.4g %12.4g +- %6.2g %16s %12s %10s\n", "volpath", t.image_seconds,
             t.image_rel_mse, t.seconds, t.err, "1", "-", "-");
    } else {
      /* relative errors of a ratio add in quadrature */
      double ratio = vol.seconds / t.seconds;
      double rel = hypot(vol.err / vol.seconds, t.err / t.seconds);
      printf("%-14s %10.4g %10.4g %12.4g +- %6.2g %9.1f +- %4.1f %12.3g %10.2f\n", runs[j].name,
             t.image_seconds, t.image_rel_mse, t.seconds, t.err, ratio, ratio * rel, runs[j].probes,
             runs[j].cache_mb);
    }
    for (int k = 0; k < runs[j].seeds; ++k) {
      ss_film_destroy(runs[j].img[k]);
    }
  }
  free(den);
  ss_scene_destroy(s);
  return 0;
}
