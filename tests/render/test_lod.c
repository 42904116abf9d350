/* Levels of detail of translucent materials (subsurface.h): "auto" picks
 * volpath, the BSSRDF or the BRDF from the object's size over the transport
 * mean free path, and the `bssrdf` integrator's volumetric walk ("volpath")
 * converges to what the `volpath` integrator renders. */
#include "subsurf/render.h"
#include "subsurf/scene.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* An index-matched chromatic sphere of the given radius lit by a point
 * light, seen by a 4 x 4 camera. */
static ss_scene *sphere(double radius, ss_lod lod) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  s->camera.width = 4;
  s->camera.height = 4;
  s->camera.position = ss_vec3_make(0, 0, 5.0 * radius);
  s->camera.fov_deg = 12;
  ss_medium med;
  memset(&med, 0, sizeof med);
  snprintf(med.name, sizeof med.name, "m");
  med.optics.sigma_s = ss_rgb_make(4.0, 3.0, 2.0);
  med.optics.sigma_a = ss_rgb_make(0.2, 0.5, 1.0);
  cr_assert_eq(ss_phase_init(&med.phase, SS_PHASE_ISOTROPIC, 0.0, &err), SS_OK);
  int mi;
  cr_assert_eq(ss_scene_add_medium(s, &med, &mi, &err), SS_OK, "%s", err.message);
  ss_material m;
  memset(&m, 0, sizeof m);
  snprintf(m.name, sizeof m.name, "t");
  m.kind = SS_MATERIAL_INTERFACE;
  m.boundary = SS_BOUNDARY_INDEX_MATCHED;
  m.medium = mi;
  m.lod = lod;
  cr_assert_eq(ss_scene_add_material(s, &m, NULL, &err), SS_OK, "%s", err.message);
  ss_mesh *mesh;
  cr_assert_eq(ss_shape_icosphere(radius, 3, &mesh, &err), SS_OK);
  cr_assert_eq(ss_scene_add_shape(s, "sphere", mesh, 0, NULL, &err), SS_OK, "%s", err.message);
  ss_light l;
  memset(&l, 0, sizeof l);
  snprintf(l.name, sizeof l.name, "lamp");
  l.type = SS_LIGHT_POINT;
  l.position = ss_vec3_make(3.0 * radius, 2.0 * radius, 4.0 * radius);
  l.value = ss_rgb_gray(10.0 * radius * radius);
  l.shape = -1;
  cr_assert_eq(ss_scene_add_light(s, &l, NULL, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

Test(lod, auto_chooses_volpath_bssrdf_or_brdf_by_size_over_mean_free_path) {
  /* The most translucent channel (blue): sigma_t' = 3, l = 1/3; n = 2 r / l. */
  const double radius[] = {1.0, 20.0, 400.0};
  const ss_lod want[] = {SS_LOD_VOLPATH, SS_LOD_BSSRDF, SS_LOD_BRDF};
  for (int i = 0; i < 3; ++i) {
    ss_scene *s = sphere(radius[i], SS_LOD_AUTO);
    double n = ss_subsurface_size_ratio(s, 0);
    cr_expect(fabs(n / (2.0 * radius[i] * 3.0) - 1.0) < 0.05, "n = %g", n);
    cr_expect_eq(ss_subsurface_lod(s->subsurface, 0), want[i], "radius %g: lod %s", radius[i],
                 ss_lod_name(ss_subsurface_lod(s->subsurface, 0)));
    const ss_bssrdf *b = ss_subsurface_bssrdf(s->subsurface, 0);
    cr_expect_eq(b != NULL, want[i] != SS_LOD_VOLPATH);
    if (want[i] == SS_LOD_BRDF) {
      cr_expect_str_eq(ss_bssrdf_name(b), SS_LOD_BRDF_MODEL);
    }
    ss_scene_destroy(s);
  }
}

/* Mean and standard error of the image average over independent passes. */
static void image_mean(ss_scene *s, const char *integrator, double mean[3], double se[3]) {
  snprintf(s->integrator.name, sizeof s->integrator.name, "%s", integrator);
  const int passes = 16;
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int p = 0; p < passes; ++p) {
    ss_render_options o;
    ss_render_options_from_scene(s, &o);
    o.spp = 64;
    o.seed = (uint64_t)p + 1;
    ss_film *film;
    ss_render_stats st;
    ss_error err;
    cr_assert_eq(ss_render(s, &o, &film, &st, &err), SS_OK, "%s", err.message);
    cr_assert_eq(st.nonfinite, 0);
    double v[3] = {0, 0, 0};
    for (int i = 0; i < 16; ++i) {
      ss_rgb px = ss_film_pixel_mean(film, i % 4, i / 4);
      for (int c = 0; c < 3; ++c) {
        v[c] += px.c[c] / 16.0;
      }
    }
    for (int c = 0; c < 3; ++c) {
      sum[c] += v[c];
      sum2[c] += v[c] * v[c];
    }
    ss_film_destroy(film);
  }
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / passes;
    se[c] = sqrt(fmax(sum2[c] / passes - mean[c] * mean[c], 0.0) / (passes - 1));
  }
}

Test(lod, volumetric_walk_converges_to_volpath, .timeout = 300) {
  ss_scene *s = sphere(1.0, SS_LOD_VOLPATH);
  double a[3], sa[3], b[3], sb[3];
  image_mean(s, "bssrdf", a, sa);
  image_mean(s, "volpath", b, sb);
  for (int c = 0; c < 3; ++c) {
    cr_expect(fabs(a[c] - b[c]) < 4.0 * sqrt(sa[c] * sa[c] + sb[c] * sb[c]),
              "channel %d: bssrdf (volpath lod) %g +- %g, volpath %g +- %g", c, a[c], sa[c], b[c],
              sb[c]);
    cr_expect_gt(a[c], 0.0);
  }
  ss_scene_destroy(s);
}
