/* Texture lookup throughput: bilinear lookups in a 1024 x 1024
 * RGB image with each wrap mode, the checker, and 1- and 4-octave
 * gradient-noise fBm, at pseudo-random points, one thread (CPU time).
 * Usage: bench_texture [lookups (default 4000000)] */
#include "subsurf/rng.h"
#include "subsurf/texture.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Lookups per second; the sum keeps the compiler from dropping the loop. */
static double run(const ss_texture *t, long n, double *sink) {
  ss_rng rng;
  ss_rng_seed(&rng, 1, 0);
  double sum = 0.0, t0 = cpu_seconds();
  for (long k = 0; k < n; ++k) {
    double u = 3.0 * ss_rng_uniform(&rng) - 1.0, v = 3.0 * ss_rng_uniform(&rng) - 1.0;
    ss_texcoord tc = {u, v, ss_vec3_make(4.0 * u, 4.0 * v, u - v)};
    sum += ss_texture_eval(t, tc).c[1];
  }
  *sink += sum;
  return (double)n / (cpu_seconds() - t0);
}

int main(int argc, char **argv) {
  long n = argc > 1 ? atol(argv[1]) : 4000000;
  ss_error err;
  double sink = 0.0;
  printf("%-22s %12s %10s\n", "texture", "lookups/s", "ns/lookup");
  for (int wrap = 0; wrap < 3; ++wrap) {
    ss_image *img = ss_image_create(1024, 1024, 3);
    for (size_t i = 0; i < (size_t)1024 * 1024 * 3; ++i) {
      img->data[i] = (float)((i * 2654435761u) % 1000) / 1000.0f;
    }
    ss_texture *t;
    if (ss_texture_create_image(img, (ss_wrap)wrap, &t, &err) != SS_OK) {
      fprintf(stderr, "%s\n", err.message);
      return 1;
    }
    static const char *const names[] = {"image 1024^2 repeat", "image 1024^2 clamp",
                                        "image 1024^2 mirror"};
    double r = run(t, n, &sink);
    printf("%-22s %12.3g %10.1f\n", names[wrap], r, 1e9 / r);
    ss_texture_destroy(t);
  }
  ss_texture *c;
  ss_texture_create_checker(ss_rgb_gray(0.2), ss_rgb_gray(0.8), &c, &err);
  double r = run(c, n, &sink);
  printf("%-22s %12.3g %10.1f\n", "checker", r, 1e9 / r);
  ss_texture_destroy(c);
  for (int octaves = 1; octaves <= 4; octaves += 3) {
    ss_noise_params q = {
        .octaves = octaves, .lacunarity = 2.0, .gain = 0.5, .lo = 0.3, .hi = 0.7, .world = 1};
    ss_texture *t;
    ss_texture_create_noise(ss_rgb_gray(0.2), ss_rgb_gray(0.8), &q, &t, &err);
    r = run(t, n, &sink);
    printf("noise fBm %d octave%s    %12.3g %10.1f\n", octaves, octaves > 1 ? "s" : " ", r,
           1e9 / r);
    ss_texture_destroy(t);
  }
  return sink == 12345.678 ? 2 : 0;
}
