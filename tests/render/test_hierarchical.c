/* The `hierarchical` integrator (Jensen & Buhler 2002): the octree descent
 * with epsilon -> 0 is the direct sum over all points bit for bit; the
 * octree's aggregates conserve power and area exactly; pass 1 and the
 * images are identical for 1 and 2 threads; the direct sum over the points
 * converges to the `bssrdf` integrator's render as the density grows; bad
 * options and non-radial kernels are refused. */
#include "render/integrators/hierarchical.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include "render/hier_sphere.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static ss_scene *sphere_scene_fov(const char *model, double fov) {
  ss_scene *s = hier_sphere_uncommitted(model, fov);
  ss_error err;
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_scene *sphere_scene(const char *model) { return sphere_scene_fov(model, 20.0); }

static ss_hier_state *build(const ss_scene *s, size_t points, int samples, int threads) {
  ss_hier_options o;
  ss_error err;
  cr_assert_eq(ss_hier_options_read(s, &o, &err), SS_OK, "%s", err.message);
  o.points = points;
  o.irradiance_samples = samples;
  ss_hier_state *h;
  cr_assert_eq(ss_hier_build(s, &o, threads, NULL, &h, &err), SS_OK, "%s", err.message);
  return h;
}

static ss_hier_kernel_ctx kernel_at(const ss_hier_state *h, const ss_irradiance_point *x) {
  ss_hier_kernel_ctx k = {.b = h->kernel[0], .x_o = x->p, .n_o = x->n, .w_o = x->n};
  k.inv_ft_normal = 1.0 / ss_irradiance_fresnel_weight(1.0, h->eta[0]);
  return k;
}

Test(hierarchical, descent_with_epsilon_to_zero_equals_the_direct_sum_exactly) {
  ss_scene *s = sphere_scene("dipole");
  ss_hier_state *h = build(s, 3000, 4, 1);
  const ss_irradiance_octree *t = &h->trees[0];
  cr_assert_eq(t->num_points, h->num_points);
  for (size_t i = 0; i < h->num_points; i += 97) {
    ss_hier_kernel_ctx k = kernel_at(h, &h->points[i]);
    uint64_t evals = 0;
    ss_rgb tree = ss_irradiance_octree_sum(t, k.x_o, 1e-300, ss_hier_kernel, &k, &evals);
    ss_rgb direct = ss_irradiance_direct_sum(t->points, t->num_points, k.x_o, ss_hier_kernel, &k);
    cr_assert(!memcmp(&tree, &direct, sizeof tree), "point %zu: %.17g vs %.17g", i, tree.c[0],
              direct.c[0]);
    cr_assert_eq(evals, h->num_points);
    /* and the default threshold stays close with far fewer evaluations */
    uint64_t fewer = 0;
    ss_rgb approx =
        ss_irradiance_octree_sum(t, k.x_o, SS_HIER_DEFAULT_EPSILON, ss_hier_kernel, &k, &fewer);
    cr_expect_lt(fewer, evals / 2);
    for (int c = 0; c < 3; ++c) {
      cr_expect_leq(fabs(approx.c[c] - direct.c[c]), 0.02 * direct.c[c] + 1e-12, "channel %d", c);
    }
  }
  ss_hier_destroy(h);
  ss_scene_destroy(s);
}

Test(hierarchical, octree_aggregates_conserve_power_and_area_exactly) {
  ss_scene *s = sphere_scene("dipole");
  ss_hier_state *h = build(s, 5000, 2, 1);
  const ss_irradiance_octree *t = &h->trees[0];
  double area = 0.0;
  for (size_t i = 0; i < h->num_points; ++i) {
    area += h->points[i].area;
  }
  cr_expect(fabs(area - ss_mesh_area(s->shapes[0].mesh)) < 1e-12 * area);
  for (size_t n = 0; n < t->num_nodes; ++n) {
    const ss_octree_node *node = &t->nodes[n];
    ss_rgb power = ss_rgb_gray(0.0);
    double a = 0.0;
    for (uint32_t i = node->begin; i < node->end; ++i) {
      power = ss_rgb_add(power, t->points[i].power);
      a += t->points[i].area;
    }
    cr_assert(!memcmp(&power, &node->power, sizeof power), "node %zu power", n);
    cr_assert_eq(a, node->area, "node %zu area", n);
    uint32_t next = node->begin;
    ss_rgb children = ss_rgb_gray(0.0);
    int leaf = 1;
    for (int k = 0; k < 8; ++k) {
      if (node->child[k] >= 0) {
        const ss_octree_node *c = &t->nodes[node->child[k]];
        cr_assert_eq(c->begin, next, "node %zu: children do not tile its range", n);
        next = c->end;
        children = ss_rgb_add(children, c->power);
        leaf = 0;
      }
    }
    if (!leaf) {
      cr_assert_eq(next, node->end);
      for (int c = 0; c < 3; ++c) {
        cr_assert(fabs(children.c[c] - node->power.c[c]) <= 1e-12 * node->power.c[c]);
      }
    } else {
      cr_assert(node->end - node->begin <= SS_OCTREE_LEAF_POINTS);
    }
  }
  cr_assert_eq(t->nodes[0].begin, 0);
  cr_assert_eq(t->nodes[0].end, h->num_points);
  ss_hier_destroy(h);
  ss_scene_destroy(s);
}

Test(hierarchical, one_and_two_threads_give_identical_points_and_images) {
  /* 32 x 2 pixels: two tiles for the two threads (test_render), the sphere
   * across the middle of both and the sky at the ends */
  ss_scene *s = hier_sphere_uncommitted("better-dipole", 4.0);
  s->camera.width = 2 * SS_RENDER_TILE;
  s->camera.height = 2;
  ss_error err;
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  ss_hier_state *one = build(s, 1000, 8, 1), *two = build(s, 1000, 8, 2);
  cr_assert_eq(one->num_points, two->num_points);
  cr_assert(!memcmp(one->points, two->points, one->num_points * sizeof *one->points));
  ss_hier_destroy(one);
  ss_hier_destroy(two);
  cr_assert_eq(ss_scene_set_integrator_option(s, "points", 1000, NULL), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "irradiance_samples", 8, NULL), SS_OK);
  test_expect_thread_independent(s, 2, 3);
  ss_scene_destroy(s);
}

Test(hierarchical, bad_options_and_non_radial_kernels_are_refused) {
  ss_scene *s = sphere_scene("dipole");
  ss_error err;
  ss_hier_options o;
  const char *names[] = {"epsilon",    "epsilon",   "points", "points", "irradiance_samples",
                         "near_field", "near_field"};
  double values[] = {0.0, -1.0, 0.0, 2.5, 0.0, -0.5, SS_HIER_MAX_NEAR_FIELD + 1.0};
  for (int k = 0; k < 7; ++k) {
    ss_scene_set_integrator_option(s, names[k], values[k], NULL);
    cr_expect_eq(ss_hier_options_read(s, &o, &err), SS_ERR_INVALID_ARGUMENT, "%s %g", names[k],
                 values[k]);
    cr_expect(strstr(err.message, names[k]), "%s", err.message);
    s->integrator.num_options = 0;
  }
  ss_scene_set_integrator_option(s, "epsilon", NAN, NULL);
  cr_expect_eq(ss_hier_options_read(s, &o, &err), SS_ERR_INVALID_ARGUMENT);
  s->integrator.num_options = 0;
  ss_scene_set_integrator_option(s, "near_field", NAN, NULL);
  cr_expect_eq(ss_hier_options_read(s, &o, &err), SS_ERR_INVALID_ARGUMENT);
  ss_scene_destroy(s);
  const char *bad[] = {"fwddip", "single", "dipole-brdf"};
  for (int k = 0; k < 3; ++k) {
    s = sphere_scene(bad[k]);
    cr_assert_eq(ss_hier_options_read(s, &o, &err), SS_OK);
    ss_hier_state *h = NULL;
    cr_expect_eq(ss_hier_build(s, &o, 1, NULL, &h, &err), SS_ERR_INVALID_ARGUMENT, "%s", bad[k]);
    cr_expect(strstr(err.message, "radially symmetric"), "%s", err.message);
    cr_expect_null(h);
    ss_scene_destroy(s);
  }
}

/* The kernel's dependence on the light's direction is the Fresnel weight of
 * the irradiance: S(w_i) / S(n) = Ft(w_i . n) / Ft(1) for the radial models,
 * which makes sum_j K E_j A_j the integral of the bssrdf integrator. */
Test(hierarchical, kernel_entry_factor_is_the_irradiance_fresnel_weight) {
  const char *models[] = {"dipole", "better-dipole", "multipole", "table-radial"};
  for (int k = 0; k < 4; ++k) {
    ss_scene *s = sphere_scene(models[k]);
    const ss_bssrdf *b = ss_subsurface_bssrdf(s->subsurface, 0);
    double eta = ss_bssrdf_get_params(b)->eta;
    for (double cos_i = 0.1; cos_i < 1.0; cos_i += 0.2) {
      ss_vec3 n = ss_vec3_make(0, 0, 1), w = ss_vec3_make(sqrt(1 - cos_i * cos_i), 0, cos_i);
      ss_bssrdf_query qn = {ss_vec3_make(0.1, 0, 0), n, n, ss_vec3_make(0, 0, 0), n, n, 0.0};
      ss_bssrdf_query qw = qn;
      qw.w_i = w;
      double sn[3], sw[3];
      ss_bssrdf_eval(b, &qn, sn);
      ss_bssrdf_eval(b, &qw, sw);
      double want = ss_irradiance_fresnel_weight(cos_i, eta) / ss_irradiance_fresnel_weight(1, eta);
      for (int c = 0; c < 3; ++c) {
        cr_expect(fabs(sw[c] / sn[c] - want) < 1e-9 * want, "%s cos %g: %g vs %g", models[k], cos_i,
                  sw[c] / sn[c], want);
      }
    }
    ss_scene_destroy(s);
  }
}

static void image_mean(const ss_scene *s, const ss_integrator_ops *ops, const void *state, int n,
                       double mean[3], double se[3]) {
  test_image_mean(s, ops, state, n, 11, mean, se);
}

Test(hierarchical, direct_sum_converges_to_the_bssrdf_integrator, .timeout = 300) {
  ss_scene *s = sphere_scene_fov("dipole", 8.0); /* every pixel sees the sphere */
  double ref[3], ref_se[3];
  image_mean(s, ss_integrator_find("bssrdf"), NULL, 4000, ref, ref_se);
  const size_t counts[] = {150, 600, 2400};
  double err[3];
  for (int k = 0; k < 3; ++k) {
    ss_hier_state *h = build(s, counts[k], 64, 0);
    h->opt.epsilon = 1e-300; /* never aggregate: the direct sum */
    double m[3], se[3];
    image_mean(s, ss_integrator_find("hierarchical"), h, 16, m, se);
    err[k] = 0.0;
    for (int c = 0; c < 3; ++c) {
      double z = (m[c] - ref[c]) / sqrt(se[c] * se[c] + ref_se[c] * ref_se[c]);
      err[k] = fmax(err[k], fabs(z));
      cr_log_info("points %zu channel %d: %.5f vs bssrdf %.5f +- %.5f (z %.2f)", h->num_points, c,
                  m[c], ref[c], ref_se[c], z);
    }
    ss_hier_destroy(h);
  }
  cr_expect_lt(err[2], 4.0, "the densest point set is %.1f standard errors off", err[2]);
  cr_expect_gt(fmax(err[0], err[1]), err[2], "no sparser point set is further off");
  ss_scene_destroy(s);
}
