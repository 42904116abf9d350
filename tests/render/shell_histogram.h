/* The brute-force side of the entry-sampler density tests: the mesh's area
 * in shells of distance from a point, by uniform area sampling, compared
 * with a sampler's estimate E[1{x in shell} / p(x)] of the same areas. */
#ifndef SUBSURF_TESTS_SHELL_HISTOGRAM_H
#define SUBSURF_TESTS_SHELL_HISTOGRAM_H

#include "subsurf/mesh.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

/* Counts m uniform points of the mesh's surface by shell of |p - centre|
 * in [0, dmax) (points farther away are not counted). */
static inline void shell_histogram_brute_force(const ss_mesh *mesh, ss_vec3 centre, double dmax,
                                               int shells, int m, ss_rng *rng, long *count) {
  size_t tris = mesh->num_triangles;
  double *areas = malloc(tris * sizeof *areas);
  for (size_t t = 0; t < tris; ++t) {
    areas[t] = ss_mesh_triangle_area(mesh, t);
  }
  ss_distribution1d dist;
  cr_assert_eq(ss_distribution1d_init(&dist, areas, tris), 0);
  for (int i = 0; i < m; ++i) {
    double prob, b0, b1;
    size_t t = ss_distribution1d_sample_discrete(&dist, ss_rng_uniform(rng), &prob);
    ss_sample_uniform_triangle(ss_rng_uniform(rng), ss_rng_uniform(rng), &b0, &b1);
    ss_vec3 v[3];
    ss_mesh_triangle(mesh, t, v);
    ss_vec3 p = ss_vec3_add(ss_vec3_add(ss_vec3_scale(v[0], b0), ss_vec3_scale(v[1], b1)),
                            ss_vec3_scale(v[2], 1.0 - b0 - b1));
    double d = ss_vec3_length(ss_vec3_sub(p, centre));
    if (d < dmax) {
      count[(int)(d / dmax * shells)]++;
    }
  }
  ss_distribution1d_free(&dist);
  free(areas);
}

/* Each shell's sampler estimate (sum, sum2 of 1/p over n draws) against its
 * brute-force area (count of m uniform points on a mesh of area total),
 * within 4 combined standard errors. */
static inline void shell_histogram_expect_match(const double *sum, const double *sum2, int n,
                                                const long *count, int m, double total, int shells,
                                                const char *label) {
  for (int k = 0; k < shells; ++k) {
    double mean = sum[k] / n, se = sqrt((sum2[k] / n - mean * mean) / n);
    double frac = (double)count[k] / m;
    double brute = frac * total, se_brute = total * sqrt(frac * (1.0 - frac) / m);
    cr_expect(fabs(mean - brute) < 4.0 * sqrt(se * se + se_brute * se_brute),
              "%s shell %d: sampler %g +- %g, brute force %g +- %g", label, k, mean, se, brute,
              se_brute);
  }
}

#endif
