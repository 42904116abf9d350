/* The pbrt-v3 importer's objects: each shape, material, medium, texture
 * and light becomes the scene object docs/pbrt-import.md says, with
 * pbrt-v3's defaults and units. */
#include "io/pbrt_test.h"

#include "subsurf/albedo_inversion.h"
#include "subsurf/image_io.h"
#include "subsurf/media.h"

#include <math.h>

static ss_scene *read_ok(const char *dir, const char *text, pbrt_warnings *w) {
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_eq(pbrt_read(dir, "t.pbrt", text, &s, w, &err), SS_OK, "%s", err.message);
  return s;
}

/* each sphere beside the last: interfaces must not overlap */
#define SPHERE "Translate 3 0 0 Shape \"sphere\" \"integer subdivisions\" 1\n"

Test(pbrt_objects, materials_map_with_pbrts_defaults) {
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  pbrt_warnings w;
  ss_scene *s = read_ok(
      dir,
      PBRT_TEST_HEADER SPHERE                                          /* 0: default matte */
      "AttributeBegin\nMaterial \"matte\" \"rgb Kd\" [0 0 0]\n" SPHERE /* 1: black */
      "Material \"glass\"\n" SPHERE                                    /* 2 */
      "Material \"glass\" \"float uroughness\" 1 \"float vroughness\" 1\n" SPHERE /* 3 */
      "Material \"glass\" \"float uroughness\" 0.3 \"float vroughness\" 0.3 \"bool "
      "remaproughness\" \"false\" \"float eta\" 1.4\n" SPHERE /* 4 */
      "Material \"subsurface\" \"string name\" \"Skin1\" \"float scale\" 5 \"float g\" "
      "0.7\n" SPHERE /* 5 */
      "Material \"kdsubsurface\" \"rgb Kd\" [0.5 0.6 0.7] \"rgb mfp\" [1 2 4] \"float scale\" "
      "0.5\n" SPHERE /* 6 */
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"string preset\" \"Ketchup\" "
      "\"float g\" 0.5 \"float scale\" 2\n"
      "MediumInterface \"fog\" \"\"\nMaterial \"none\"\n" SPHERE /* 7 */
      "AttributeEnd\nWorldEnd\n",
      &w);
  cr_assert_eq(s->num_shapes, 8, "%s", w.text);
  const ss_material *m[8];
  for (int i = 0; i < 8; ++i) {
    m[i] = s->shapes[i].material >= 0 ? &s->materials[s->shapes[i].material] : NULL;
  }
  cr_expect_eq(m[0]->kind, SS_MATERIAL_DIFFUSE);
  cr_expect_eq(m[0]->albedo.c[1], 0.5);
  cr_expect_null(m[1]);
  cr_expect_eq(m[2]->boundary, SS_BOUNDARY_SMOOTH);
  cr_expect_eq(m[2]->eta, 1.5);
  cr_expect_eq(m[2]->medium, -1);
  /* pbrt-v3's RoughnessToAlpha at roughness 1 (x = 0) is its constant term */
  cr_expect_eq(m[3]->boundary, SS_BOUNDARY_ROUGH);
  cr_expect_eq(m[3]->mf.type, SS_MICROFACET_GGX);
  cr_expect_float_eq(m[3]->mf.alpha, 1.62142, 1e-12);
  cr_expect_eq(m[3]->energy_compensation, 0);
  cr_expect_float_eq(m[4]->mf.alpha, 0.3, 1e-12);
  cr_expect_eq(m[4]->eta, 1.4);
  /* Skin1's reduced scattering taken as sigma_s, g forced to 0, x 5 */
  const ss_medium *skin = &s->media[m[5]->medium];
  cr_expect_float_eq(skin->optics.sigma_s.c[0], 0.74 * 5, 1e-12);
  cr_expect_float_eq(skin->optics.sigma_a.c[2], 0.48 * 5, 1e-12);
  cr_expect_eq(skin->optics.phase, SS_PHASE_ISOTROPIC);
  cr_expect_eq(m[5]->eta, 1.33);
  cr_expect_str_eq(m[5]->bssrdf, "pbd");
  cr_expect(strstr(w.text, "t.pbrt:17: Material \"subsurface\": g 0.7 replaced by 0"), "%s",
            w.text);
  /* kdsubsurface: sigma_t = 1 / (mfp scale), albedo inverted by PBD */
  const ss_medium *kd = &s->media[m[6]->medium];
  const double mfp[3] = {0.5, 1, 2}, albedo[3] = {0.5, 0.6, 0.7};
  for (int c = 0; c < 3; ++c) {
    double sig_s, sig_a;
    ss_error e;
    cr_assert_eq(ss_albedo_to_coefficients(SS_ALBEDO_INVERSION_PBD, albedo[c], mfp[c], 0.0, 1.33,
                                           &sig_s, &sig_a, &e),
                 SS_OK);
    cr_expect_float_eq(kd->optics.sigma_s.c[c] + kd->optics.sigma_a.c[c], 1.0 / mfp[c], 1e-9);
    cr_expect_float_eq(kd->optics.sigma_s.c[c], sig_s, 1e-12);
  }
  cr_expect(m[6]->by_albedo);
  /* a medium keeps g with a preset (pbrt-v3), its sigma_s' unreduced */
  cr_expect_eq(m[7]->boundary, SS_BOUNDARY_INDEX_MATCHED);
  const ss_medium *fog = &s->media[m[7]->medium];
  cr_expect_str_eq(fog->name, "fog");
  cr_expect_float_eq(fog->optics.sigma_s.c[0], 0.18 * 2, 1e-12);
  cr_expect_float_eq(fog->optics.g.c[0], 0.5, 1e-12);
  cr_expect_eq(fog->optics.phase, SS_PHASE_HG);
  ss_scene_destroy(s);
  pbrt_rmdir(dir);
}

Test(pbrt_objects, lights_map_with_pbrts_conventions) {
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  /* a 2 x 2 EXR map: rows of 1 and 3 at equal solid angle, mean 2 */
  ss_image *img = ss_image_create(2, 2, 3);
  for (int i = 0; i < 12; ++i) {
    img->data[i] = i < 6 ? 1.0f : 3.0f;
  }
  char path[256];
  snprintf(path, sizeof path, "%s/sky.exr", dir);
  ss_error e;
  cr_assert_eq(ss_image_write_exr(path, img, &e), SS_OK, "%s", e.message);
  ss_image_destroy(img);
  pbrt_warnings w;
  ss_scene *s = read_ok(
      dir,
      PBRT_TEST_HEADER SPHERE
      "AttributeBegin\nTranslate 1 0 0\n"
      "LightSource \"point\" \"rgb I\" [1 2 3] \"point from\" [0 2 0] \"rgb scale\" [2 2 2]\n"
      "LightSource \"spot\" \"point from\" [0 0 0] \"point to\" [0 -1 0] \"float coneangle\" 20\n"
      "LightSource \"distant\" \"point from\" [0 0 0] \"point to\" [0 0 -1] \"rgb L\" [4 4 4]\n"
      "AttributeEnd\n"
      "LightSource \"infinite\" \"rgb L\" [0.5 0.5 0.5] \"string mapname\" \"sky.exr\"\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [7 8 9]\nTranslate 0 5 0\n" SPHERE
      "AttributeEnd\nWorldEnd\n",
      &w);
  cr_assert_eq(s->num_lights, 6, "%s", w.text); /* the header's point light first */
  const ss_light *l = s->lights;
  cr_expect_eq(l[1].type, SS_LIGHT_POINT);
  cr_expect_float_eq(l[1].position.x, 4.0, 1e-12); /* after the header sphere's Translate 3 */
  cr_expect_float_eq(l[1].position.y, 2.0, 1e-12);
  cr_expect_float_eq(l[1].value.c[2], 6.0, 1e-12);
  cr_expect_eq(l[2].type, SS_LIGHT_SPOT);
  cr_expect_float_eq(l[2].direction.y, -1.0, 1e-12);
  cr_expect_float_eq(l[2].cone_angle, 20.0, 1e-12);
  cr_expect_float_eq(l[2].falloff_angle, 15.0, 1e-12);
  cr_expect_eq(l[3].type, SS_LIGHT_DIRECTIONAL);
  cr_expect_float_eq(l[3].direction.z, -1.0, 1e-12); /* light travels from -> to */
  cr_expect_float_eq(l[3].value.c[0], 4.0, 1e-12);
  cr_expect_eq(l[4].type, SS_LIGHT_ENVIRONMENT);
  cr_expect_float_eq(l[4].value.c[0], 1.0, 1e-6);
  cr_expect(strstr(w.text, "t.pbrt:14: LightSource \"infinite\": the map \"sky.exr\""), "%s",
            w.text);
  cr_expect_eq(l[5].type, SS_LIGHT_AREA);
  cr_expect_eq(l[5].shape, 1);
  ss_vec3 lo, hi;
  ss_mesh_bounds(s->shapes[1].mesh, &lo, &hi);
  cr_expect_float_eq(0.5 * (lo.y + hi.y), 5.0, 1e-6);
  cr_expect_float_eq(l[5].value.c[1], 8.0, 1e-12);
  ss_scene_destroy(s);
  pbrt_rmdir(dir);
}

Test(pbrt_objects, meshes_instances_and_textures) {
  char dir[64];
  pbrt_tmpdir(dir, sizeof dir);
  pbrt_write(dir, "quad.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
             "property float z\nproperty float u\nproperty float v\nelement face 1\nproperty list "
             "uchar int vertex_indices\n"
             "end_header\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n");
  pbrt_warnings w;
  ss_scene *s = read_ok(
      dir,
      PBRT_TEST_HEADER
      "Texture \"check\" \"spectrum\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 4\n"
      "  \"rgb tex1\" [0.9 0.9 0.9] \"rgb tex2\" [0.1 0.1 0.1]\n"
      "Material \"matte\" \"texture Kd\" \"check\"\n"
      "Shape \"plymesh\" \"string filename\" \"quad.ply\"\n"
      "ObjectBegin \"tri\"\nTranslate 0 0 1\n"
      /* normals pointing down: pbrt-v3 orients the triangle by them */
      "Shape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0] \"normal N\" [0 0 -1 0 0 -1 0 0 -1]"
      " \"float uv\" [0 0 1 0 0 1]\n"
      "ObjectEnd\n"
      "Translate 5 0 0\nObjectInstance \"tri\"\nTranslate 5 0 0\nObjectInstance \"tri\"\n"
      "WorldEnd\n",
      &w);
  cr_assert_eq(s->num_shapes, 3, "%s", w.text);
  cr_expect_eq(s->shapes[0].mesh->num_triangles, 2u);
  const ss_material *m = &s->materials[s->shapes[0].material];
  cr_expect_not_null(m->textures[SS_PARAM_ALBEDO]);
  ss_vec3 p = ss_mesh_position(s->shapes[2].mesh, 0);
  cr_expect(p.x == 10.0 && p.z == 1.0, "(%g %g %g)", p.x, p.y, p.z);
  cr_expect_lt(ss_mesh_triangle_normal(s->shapes[1].mesh, 0).z, 0.0);
  cr_expect_not_null(s->shapes[1].mesh->uvs);
  ss_scene_destroy(s);
  pbrt_rmdir(dir);
}
