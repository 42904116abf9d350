/* The normalised near field of the `hierarchical` integrator (option
 * near_field, hierarchical.h ss_hier_sum_near): the table's disk integral
 * equals the model kernel's, integrated by quadrature; the descent with a
 * near field of radius 0 is the plain descent bit for bit, and with
 * epsilon -> 0 its far and near parts add up to the direct sum; on a plane
 * of constant irradiance the normalised sum is the kernel's integral over
 * the plane where the plain point sum misses it; near an edge the plain sum
 * is kept. */
#include "render/integrators/hierarchical.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static ss_bssrdf *dipole(void) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.medium.sigma_s = ss_rgb_make(10.0, 8.0, 6.0);
  p.medium.sigma_a = ss_rgb_make(0.5, 1.0, 2.0);
  p.eta = 1.3;
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create("dipole", &p, &b, &err), SS_OK, "%s", err.message);
  return b;
}

/* The model's kernel at distance r on the plane z = 0, seen along the normal. */
static void kernel_at(const ss_bssrdf *b, double r, double k[3]) {
  ss_hier_kernel_ctx c = {.b = b,
                          .x_o = ss_vec3_make(0, 0, 0),
                          .n_o = ss_vec3_make(0, 0, 1),
                          .w_o = ss_vec3_make(0, 0, 1),
                          .inv_ft_normal = 1.0 / ss_irradiance_fresnel_weight(1.0, 1.3)};
  ss_hier_kernel(&c, ss_vec3_make(r, 0, 0), ss_vec3_make(0, 0, 1), k);
}

Test(hierarchical_near, disk_integral_of_the_table_equals_the_model_kernel_integral) {
  ss_bssrdf *b = dipole();
  ss_hier_table t;
  ss_error err;
  cr_assert_eq(ss_hier_table_build(b, 1.3, &t, &err), SS_OK, "%s", err.message);
  static const double radii[] = {0.01, 0.1, 0.3, 1.0, 3.0};
  for (size_t i = 0; i < sizeof radii / sizeof radii[0]; ++i) {
    double R = radii[i], want[3] = {0, 0, 0}, got[3];
    /* 2 pi int_0^R K(r) r dr by the midpoint rule in s = r^2 (pi ds = 2 pi r dr),
     * graded towards 0 where the dipole peaks: s = R^2 u^4 */
    int n = 200000;
    for (int j = 0; j < n; ++j) {
      double u = (j + 0.5) / n, s = R * R * u * u * u * u, ds = R * R * 4.0 * u * u * u / n, k[3];
      kernel_at(b, sqrt(s), k);
      for (int c = 0; c < 3; ++c) {
        want[c] += SS_PI * k[c] * ds;
      }
    }
    ss_hier_table_disk(&t, R, got);
    for (int c = 0; c < 3; ++c) {
      cr_expect_leq(fabs(got[c] - want[c]), 2e-3 * want[c], "R %g channel %d: %.9g vs %.9g", R, c,
                    got[c], want[c]);
    }
  }
  ss_hier_table_destroy(&t);
  ss_bssrdf_destroy(b);
}

/* Points on a jittered grid of spacing h over [-L, L]^2 on the plane z = 0
 * (or, with `fold`, the half x > 0 turned down onto the plane x = 0, an
 * edge along y), irradiance 1, area h^2 each. */
static ss_irradiance_point *plane_points(double L, double h, int fold, size_t *n) {
  int m = (int)(2.0 * L / h);
  ss_irradiance_point *p = calloc((size_t)m * (size_t)m, sizeof *p);
  cr_assert(p);
  ss_rng rng;
  ss_rng_seed(&rng, 5, 0);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      ss_irradiance_point *q = &p[(size_t)i * (size_t)m + (size_t)j];
      double x = -L + (i + 0.1 + 0.8 * ss_rng_uniform(&rng)) * h;
      double y = -L + (j + 0.1 + 0.8 * ss_rng_uniform(&rng)) * h;
      q->p = ss_vec3_make(x, y, 0);
      q->n = ss_vec3_make(0, 0, 1);
      if (fold && x > 0.0) {
        q->p = ss_vec3_make(0, y, -x);
        q->n = ss_vec3_make(1, 0, 0);
      }
      q->area = h * h;
      q->E = ss_rgb_gray(1.0);
      q->power = ss_rgb_gray(h * h);
    }
  }
  *n = (size_t)m * (size_t)m;
  return p;
}

Test(hierarchical_near, zero_radius_is_the_plain_descent_and_the_parts_add_up) {
  ss_bssrdf *b = dipole();
  ss_hier_table t;
  ss_error err;
  cr_assert_eq(ss_hier_table_build(b, 1.3, &t, &err), SS_OK, "%s", err.message);
  size_t n;
  ss_irradiance_point *p = plane_points(2.0, 0.05, 0, &n);
  ss_irradiance_octree tree;
  cr_assert_eq(ss_irradiance_octree_build(p, n, &tree, &err), SS_OK, "%s", err.message);
  ss_hier_table_ctx tk = {.table = &t, .x_o = ss_vec3_make(0.013, -0.021, 0), .a = {1, 1, 1}};
  ss_octree_near near = {.r2 = 0.0, .n = ss_vec3_make(0, 0, 1)};
  ss_rgb plain = ss_irradiance_octree_sum(&tree, tk.x_o, 0.05, ss_hier_kernel_tabulated, &tk, NULL);
  ss_rgb split = ss_irradiance_octree_sum_near(&tree, tk.x_o, 0.05, ss_hier_kernel_tabulated, &tk,
                                               &near, NULL);
  cr_assert(!memcmp(&plain, &split, sizeof plain));
  cr_assert_eq(near.count, 0);
  near.r2 = 0.2 * 0.2;
  ss_rgb far = ss_irradiance_octree_sum_near(&tree, tk.x_o, 1e-300, ss_hier_kernel_tabulated, &tk,
                                             &near, NULL);
  ss_rgb direct = ss_irradiance_direct_sum(tree.points, n, tk.x_o, ss_hier_kernel_tabulated, &tk);
  cr_assert_gt(near.count, 30);
  cr_assert(near.flat);
  for (int c = 0; c < 3; ++c) {
    cr_expect_leq(fabs(far.c[c] + near.sum.c[c] - direct.c[c]), 1e-12 * direct.c[c], "channel %d",
                  c);
  }
  ss_irradiance_octree_destroy(&tree);
  free(p);
  ss_hier_table_destroy(&t);
  ss_bssrdf_destroy(b);
}

Test(hierarchical_near, normalised_near_field_recovers_the_plane_integral_and_keeps_edges) {
  ss_bssrdf *b = dipole();
  ss_hier_table t;
  ss_error err;
  cr_assert_eq(ss_hier_table_build(b, 1.3, &t, &err), SS_OK, "%s", err.message);
  /* points 0.1 apart against the dipole's z_r = 1 / sigma_t' = 0.095-0.125
   * (as the marble cube's 0.28 mm against 0.33-0.45 mm): the peak falls
   * between a few points; L = 3 holds all but ~1e-5 of the kernel */
  double L = 3.0, h = 0.1, r = 3.0 * h;
  size_t n;
  ss_irradiance_point *p = plane_points(L, h, 0, &n);
  ss_irradiance_octree tree;
  cr_assert_eq(ss_irradiance_octree_build(p, n, &tree, &err), SS_OK, "%s", err.message);
  double disk[3], whole[3];
  ss_hier_table_disk(&t, r, disk);
  ss_hier_table_disk(&t, L,
                     whole); /* the kernel's integral over the plane (the disk of radius L) */
  ss_rng rng;
  ss_rng_seed(&rng, 9, 0);
  double err_plain = 0.0, err_near = 0.0;
  int lookups = 40;
  for (int i = 0; i < lookups; ++i) {
    ss_hier_table_ctx tk = {.table = &t, .a = {1, 1, 1}};
    tk.x_o =
        ss_vec3_make(0.5 * (ss_rng_uniform(&rng) - 0.5), 0.5 * (ss_rng_uniform(&rng) - 0.5), 0);
    ss_rgb plain =
        ss_irradiance_octree_sum(&tree, tk.x_o, 0.01, ss_hier_kernel_tabulated, &tk, NULL);
    ss_rgb normalised = ss_hier_sum_near(&tree, ss_vec3_make(0, 0, 1), 0.01, r, disk, &tk, NULL);
    for (int c = 0; c < 3; ++c) {
      err_plain += pow(plain.c[c] / whole[c] - 1.0, 2);
      err_near += pow(normalised.c[c] / whole[c] - 1.0, 2);
    }
  }
  err_plain = sqrt(err_plain / (3 * lookups));
  err_near = sqrt(err_near / (3 * lookups));
  cr_log_info("rms relative error: plain %.4g, normalised %.4g", err_plain, err_near);
  cr_expect_lt(err_near, 0.01, "normalised: rms relative error %.4g", err_near);
  cr_expect_lt(err_near, 0.25 * err_plain, "normalised %.4g vs plain %.4g", err_near, err_plain);
  ss_irradiance_octree_destroy(&tree);
  free(p);
  /* at an edge the near points are not on the tangent plane: the plain sum */
  p = plane_points(L, h, 1, &n);
  cr_assert_eq(ss_irradiance_octree_build(p, n, &tree, &err), SS_OK, "%s", err.message);
  ss_hier_table_ctx tk = {.table = &t, .x_o = ss_vec3_make(-0.5 * h, 0.01, 0), .a = {1, 1, 1}};
  ss_rgb plain = ss_irradiance_direct_sum(tree.points, n, tk.x_o, ss_hier_kernel_tabulated, &tk);
  ss_rgb edge = ss_hier_sum_near(&tree, ss_vec3_make(0, 0, 1), 1e-300, r, disk, &tk, NULL);
  for (int c = 0; c < 3; ++c) {
    cr_expect_leq(fabs(edge.c[c] - plain.c[c]), 1e-12 * plain.c[c], "channel %d", c);
  }
  ss_irradiance_octree_destroy(&tree);
  free(p);
  ss_hier_table_destroy(&t);
  ss_bssrdf_destroy(b);
}
