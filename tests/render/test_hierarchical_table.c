/* The tabulated kernel of the `hierarchical` integrator's pass 2
 * (hierarchical_table.c): for every radially symmetric model it matches
 * the model's own kernel within SS_HIER_TABLE_TOLERANCE (0.5 %) relative,
 * or 1e-6 of the channel's largest value where the kernel is smaller, at
 * random exit points, normals, view directions and radii; and a render
 * through the table matches a render through the model. */
#include "render/integrators/hierarchical.h"
#include "subsurf/render.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include "render/hier_sphere.h"

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

static ss_bssrdf *model(const char *name, double sigma_s, double sigma_a, double eta) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  p.medium.sigma_s = ss_rgb_make(sigma_s, 0.8 * sigma_s, 0.6 * sigma_s);
  p.medium.sigma_a = ss_rgb_make(sigma_a, 2.0 * sigma_a, 4.0 * sigma_a);
  p.eta = eta;
  ss_bssrdf *b = NULL;
  ss_error err;
  cr_assert_eq(ss_bssrdf_create(name, &p, &b, &err), SS_OK, "%s: %s", name, err.message);
  return b;
}

static ss_vec3 random_direction(ss_rng *rng) {
  return ss_sample_uniform_sphere(ss_rng_uniform(rng), ss_rng_uniform(rng));
}

Test(hierarchical_table, tabulated_kernel_matches_every_radial_model_within_tolerance) {
  static const char *const names[] = {"dipole", "better-dipole", "multipole", "burley",
                                      "table-radial"};
  static const double media[][3] = {{10.0, 0.5, 1.3}, {200.0, 0.02, 1.5}, {1.0, 1.0, 1.0}};
  ss_rng rng;
  ss_rng_seed(&rng, 12, 0);
  for (size_t m = 0; m < sizeof names / sizeof names[0]; ++m) {
    for (size_t k = 0; k < sizeof media / sizeof media[0]; ++k) {
      ss_bssrdf *b = model(names[m], media[k][0], media[k][1], media[k][2]);
      cr_assert(ss_hier_kernel_ok(b), "%s", names[m]);
      ss_hier_table t;
      ss_error err;
      cr_assert_eq(ss_hier_table_build(b, media[k][2], &t, &err), SS_OK, "%s", err.message);
      double peak[3] = {0, 0, 0};
      for (int i = 0; i < t.n; ++i) {
        for (int c = 0; c < 3; ++c) {
          peak[c] = fmax(peak[c], t.value[i][c]);
        }
      }
      double r_min = sqrt(1.0 / t.inv_s_min);
      double r_max = r_min * exp2(0.5 * (t.n - 1) / SS_HIER_TABLE_PER_OCTAVE);
      double worst = 0.0;
      for (int j = 0; j < 2000; ++j) {
        ss_vec3 n_o = random_direction(&rng), w_o = random_direction(&rng);
        if (ss_vec3_dot(w_o, n_o) < 0.0) {
          w_o = ss_vec3_neg(w_o);
        }
        ss_vec3 x_o = ss_vec3_scale(random_direction(&rng), 3.0 * ss_rng_uniform(&rng));
        double r = r_min * pow(r_max / r_min, ss_rng_uniform(&rng));
        ss_vec3 x_i = ss_vec3_madd(x_o, random_direction(&rng), r);
        ss_vec3 n_i = ss_vec3_normalize(ss_vec3_madd(n_o, random_direction(&rng), 0.5));
        ss_hier_kernel_ctx a = {.b = b,
                                .x_o = x_o,
                                .n_o = n_o,
                                .w_o = w_o,
                                .inv_ft_normal =
                                    1.0 / ss_irradiance_fresnel_weight(1.0, media[k][2])};
        ss_hier_table_ctx tc = {.table = &t, .x_o = x_o};
        ss_hier_table_angular(&t, &a, tc.a);
        double want[3], got[3];
        ss_hier_kernel(&a, x_i, n_i, want);
        ss_hier_kernel_tabulated(&tc, x_i, n_i, got);
        for (int c = 0; c < 3; ++c) {
          double scale = fmax(fabs(want[c]), 1e-6 * peak[c]);
          worst = fmax(worst, fabs(got[c] - want[c]) / scale);
        }
      }
      cr_expect(worst <= SS_HIER_TABLE_TOLERANCE, "%s, medium %zu: worst difference %.3g", names[m],
                k, worst);
      cr_expect(ss_hier_table_check(&t, b, media[k][2]) <= SS_HIER_TABLE_TOLERANCE,
                "%s: the build's own check refuses it", names[m]);
      ss_hier_table_destroy(&t);
      ss_bssrdf_destroy(b);
    }
  }
}

/* hier_sphere.h's sphere with the dipole, 2 000 points, 4 irradiance
 * samples and the kernel table on or off. */
static ss_scene *sphere(int kernel_table) {
  ss_scene *s = hier_sphere_uncommitted("dipole", 20.0);
  ss_error err;
  cr_assert_eq(ss_scene_set_integrator_option(s, "points", 2000, &err), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "irradiance_samples", 4, &err), SS_OK);
  cr_assert_eq(ss_scene_set_integrator_option(s, "kernel_table", kernel_table, &err), SS_OK);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

static ss_image *render(int kernel_table) {
  ss_scene *s = sphere(kernel_table);
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = 2;
  o.threads = 1;
  ss_film *film;
  ss_render_stats stats;
  ss_error err;
  cr_assert_eq(ss_render(s, &o, &film, &stats, &err), SS_OK, "%s", err.message);
  ss_image *img = ss_film_image(film);
  ss_film_destroy(film);
  ss_scene_destroy(s);
  return img;
}

Test(hierarchical_table, render_through_the_table_matches_the_model_render) {
  ss_image *a = render(0), *b = render(1);
  /* The same points and paths: only the kernel differs, by at most the
   * tolerance per term, so every pixel within it (plus float rounding). */
  double worst = 0.0, sum = 0.0;
  for (size_t i = 0; i < (size_t)a->width * a->height * a->channels; ++i) {
    sum += a->data[i];
    worst = fmax(worst, fabs(a->data[i] - b->data[i]) / fmax(fabs(a->data[i]), 1e-6));
  }
  cr_assert(sum > 0.0, "a black image tests nothing");
  cr_expect(worst <= SS_HIER_TABLE_TOLERANCE + 1e-5, "worst pixel difference %.3g", worst);
  ss_image_destroy(a);
  ss_image_destroy(b);
}
