/* Speed of the `bssrdf` integrator against volpath: for volpath
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
 * figure; the speed-up's bar combines both methods' relative errors.
 * Two tables: the same reference for all (the median image), and each
 * method against its own brightness, k x the median image with k its crop
 * mean over the median's per channel (its noise relative to its own
 * converged image, as a user sees it): at equal relative noise a model 18 %
 * brighter than the median has 1.4x the variance against the common
 * reference, which the first table counts as slower. All
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

/* The reference image per pixel and channel: the median over the methods of
 * their mean images. A method's own mean would correlate with its variance
 * (an outlier raises both, so heavy-tailed volpath looked faster the fewer
 * samples it had: 131 s to relMSE 0.01 from 6 x 1 spp, 251 s from 8 x 8
 * spp); the models' low-noise means fix the shape for all. */
static double *median_image(const run *runs, int n, int w, int h) {
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
        d[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] =
            n % 2 ? v[c][n / 2] : 0.5 * (v[c][n / 2 - 1] + v[c][n / 2]);
      }
    }
  }
  return d;
}

/* Method r's brightness per channel: its crop mean over the median image's
 * (one number per channel from every pixel and seed, so that one outlier
 * moves it by its share of the crop only). */
static void brightness(const run *r, const double *med, int w, int h, double k[3]) {
  double num[3] = {0}, den[3] = {0};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_rgb m = mean_of(r, x, y);
      for (int c = 0; c < 3; ++c) {
        num[c] += m.c[c];
        den[c] += med[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c];
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    k[c] = den[c] > 0.0 ? num[c] / den[c] : 1.0;
  }
}

/* The relMSE denominator per pixel and channel, (k_c med)^2 + 0.01: k = 1
 * for all methods (the common reference), or each method's brightness (its
 * noise relative to its own converged image, of the median's shape). */
static double *denominator(const double *med, const double k[3], int w, int h) {
  size_t n = (size_t)w * (size_t)h * 3;
  double *d = malloc(sizeof *d * n);
  if (!d) {
    fprintf(stderr, "out of memory\n");
    exit(1);
  }
  for (size_t i = 0; i < n; ++i) {
    double v = k[i % 3] * med[i];
    d[i] = v * v + 1e-2;
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

/* One row's timing columns; the speed-up over `vol` (NULL: none). */
static void report(const char *name, const timing *t, const timing *vol, int is_vol) {
  printf("%-14s %10.4g %10.4g %12.4g +- %6.2g", name, t->image_seconds, t->image_rel_mse,
         t->seconds, t->err);
  if (is_vol || !vol) {
    printf(" %16s", is_vol ? "1" : "n/a");
    return;
  }
  /* relative errors of a ratio add in quadrature */
  double ratio = vol->seconds / t->seconds;
  double rel = hypot(vol->err / vol->seconds, t->err / t->seconds);
  printf(" %9.1f +- %4.1f", ratio, ratio * rel);
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
  double *med = median_image(runs, n, c, c);
  const double one[3] = {1.0, 1.0, 1.0};
  double *den = denominator(med, one, c, c);
  timing common[MAX_METHODS], own[MAX_METHODS];
  double k[MAX_METHODS][3];
  for (int j = 0; j < n; ++j) {
    common[j] = measure(&runs[j], den);
    brightness(&runs[j], med, c, c, k[j]);
    double *den_own = denominator(med, k[j], c, c);
    own[j] = measure(&runs[j], den_own);
    free(den_own);
  }
  printf("seeds %llu..%llu; volpath %d spp, models %d spp per image\n",
         (unsigned long long)first_seed, (unsigned long long)first_seed + (unsigned)seeds - 1,
         vol_spp, spp);
  int vol = vol_spp > 0 ? 0 : -1;
  printf("relMSE against the median image of all methods (the same reference for all)\n");
  printf("%-14s %10s %10s %22s %16s %12s %10s\n", "method", "s/image", "relMSE/im",
         "CPU s to relMSE .01", "speed-up", "probes/s", "cache MB");
  for (int j = 0; j < n; ++j) {
    report(runs[j].name, &common[j], vol >= 0 ? &common[vol] : NULL, j == vol);
    printf(" %12.3g %10.2f\n", j == vol ? NAN : runs[j].probes, j == vol ? NAN : runs[j].cache_mb);
  }
  printf("relMSE against each method's own brightness k x the median image (k: crop mean / "
         "median's)\n");
  printf("%-14s %10s %10s %22s %16s %20s\n", "method", "s/image", "relMSE/im",
         "CPU s to relMSE .01", "speed-up", "k (r g b)");
  for (int j = 0; j < n; ++j) {
    report(runs[j].name, &own[j], vol >= 0 ? &own[vol] : NULL, j == vol);
    printf(" %6.3f %6.3f %6.3f\n", k[j][0], k[j][1], k[j][2]);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < runs[j].seeds; ++i) {
      ss_film_destroy(runs[j].img[i]);
    }
  }
  free(den);
  free(med);
  ss_scene_destroy(s);
  return 0;
}
