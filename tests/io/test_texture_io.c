/* Texture images (PNG sRGB/linear decoding, EXR and Radiance HDR linear) and textured
 * parameters in scene files, including the errors for bad input. */
#include "subsurf/image_io.h"
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"
#include "subsurf/texture_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char tmpdir[256];

static void make_dir(void) {
  const char *base = getenv("TMPDIR");
  snprintf(tmpdir, sizeof tmpdir, "%s/subsurf_texture_io_XXXXXX", base ? base : "/tmp");
  cr_assert_not_null(mkdtemp(tmpdir));
}

static void remove_dir(void) {
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(texture_io, .init = make_dir, .fini = remove_dir);

static const char *path_of(const char *name) {
  static char path[400];
  snprintf(path, sizeof path, "%s/%s", tmpdir, name);
  return path;
}

/* IEC 61966-2-1 encoding, as the PNG writer applies it. */
static double srgb_encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* A 3-channel w x 1 image with linear values k / (w - 1) in red, their
 * squares in green and 0.5 in blue. */
static ss_image *ramp(int w) {
  ss_image *img = ss_image_create(w, 1, 3);
  for (int k = 0; k < w; ++k) {
    float *p = ss_image_pixel(img, k, 0);
    double x = (double)k / (w - 1);
    p[0] = (float)x;
    p[1] = (float)(x * x);
    p[2] = 0.5f;
  }
  return img;
}

Test(texture_io, srgb_decode_inverts_the_standard_curve) {
  cr_assert_eq(ss_srgb_decode(0.0), 0.0);
  cr_assert_float_eq(ss_srgb_decode(1.0), 1.0, 1e-15);
  cr_assert_float_eq(ss_srgb_decode(0.04045), 0.04045 / 12.92, 1e-15);
  cr_assert_float_eq(ss_srgb_decode(0.5), 0.21404114048223255, 1e-12);
  for (int k = 0; k <= 100; ++k) {
    double x = k / 100.0;
    cr_assert_float_eq(ss_srgb_decode(srgb_encode(x)), x, 1e-12);
  }
}

Test(texture_io, png_colour_is_srgb_decoded_and_data_is_linear) {
  ss_image *img = ramp(64);
  ss_error err;
  cr_assert_eq(ss_image_write_png(path_of("ramp.png"), img, 0.0, &err), SS_OK, "%s", err.message);
  ss_image *srgb, *lin;
  cr_assert_eq(ss_texture_image_read(path_of("ramp.png"), 1, &srgb, &err), SS_OK, "%s",
               err.message);
  cr_assert_eq(ss_texture_image_read(path_of("ramp.png"), 0, &lin, &err), SS_OK);
  cr_assert_eq(srgb->width, 64);
  cr_assert_eq(srgb->channels, 3);
  for (int k = 0; k < 64; ++k) {
    for (int c = 0; c < 3; ++c) {
      double byte = lrint(srgb_encode(img->data[3 * k + c]) * 255.0);
      cr_assert_float_eq(srgb->data[3 * k + c], ss_srgb_decode(byte / 255.0), 1e-7);
      cr_assert_float_eq(lin->data[3 * k + c], byte / 255.0, 1e-7);
      /* 8-bit sRGB keeps the linear value within half a code's slope */
      cr_assert(fabs(srgb->data[3 * k + c] - img->data[3 * k + c]) < 0.01);
    }
  }
  ss_image_destroy(img);
  ss_image_destroy(srgb);
  ss_image_destroy(lin);
}

Test(texture_io, exr_is_read_linear_and_grey_stays_one_channel) {
  ss_image *img = ss_image_create(3, 2, 1);
  for (int k = 0; k < 6; ++k) {
    img->data[k] = 0.25f * (float)k + 0.1f;
  }
  ss_error err;
  cr_assert_eq(ss_image_write_exr(path_of("g.exr"), img, &err), SS_OK, "%s", err.message);
  ss_image *back;
  cr_assert_eq(ss_texture_image_read(path_of("g.exr"), 1, &back, &err), SS_OK, "%s", err.message);
  cr_assert_eq(back->channels, 1);
  for (int k = 0; k < 6; ++k) {
    cr_assert_eq(back->data[k], img->data[k]);
  }
  ss_image_destroy(img);
  ss_image_destroy(back);
}

Test(texture_io, radiance_hdr_is_read_linear_as_rgb) {
  /* Ward1991's RGBE: value = mantissa 2^(exponent - 136); a flat
   * (uncompressed) scanline of 2 pixels. */
  static const unsigned char file[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n"
                                      "\x80\x40\x20\x81\xff\x00\x01\x88";
  FILE *f = fopen(path_of("sky.hdr"), "wb");
  cr_assert_not_null(f);
  fwrite(file, 1, sizeof file - 1, f);
  fclose(f);
  ss_image *img;
  ss_error err;
  cr_assert_eq(ss_texture_image_read(path_of("sky.hdr"), 1, &img, &err), SS_OK, "%s", err.message);
  cr_assert(img->width == 2 && img->height == 1 && img->channels == 3);
  const float want[6] = {1.0f, 0.5f, 0.25f, 255.0f, 0.0f, 1.0f};
  for (int k = 0; k < 6; ++k) {
    cr_expect_eq(img->data[k], want[k], "value %d: %g, expected %g", k, img->data[k], want[k]);
  }
  ss_image_destroy(img);
}

Test(texture_io, missing_truncated_and_unknown_files_name_the_path) {
  ss_image *img;
  ss_error err;
  cr_assert_eq(ss_texture_image_read(path_of("none.png"), 1, &img, &err), SS_ERR_IO);
  cr_assert(strstr(err.message, "none.png"), "%s", err.message);
  FILE *f = fopen(path_of("cut.png"), "wb");
  fwrite("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 1, 16, f);
  fclose(f);
  cr_assert_eq(ss_texture_image_read(path_of("cut.png"), 1, &img, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "cut.png"), "%s", err.message);
  cr_assert_eq(ss_texture_image_read(path_of("x.tga"), 1, &img, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "x.tga"), "%s", err.message);
}

static ss_status parse(const char *materials, const char *shapes, ss_scene **s, ss_error *err) {
  char text[4096];
  snprintf(text, sizeof text,
           "{\n\"camera\": {\"resolution\": [8, 8]},\n\"materials\": [\n%s\n],\n"
           "\"shapes\": [\n%s\n]\n}\n",
           materials, shapes);
  return ss_scene_parse_json(text, "t.json", tmpdir, s, err);
}

/* The scene is refused with "t.json:<line>: <path>..." containing `words`. */
static void expect_error(const char *materials, const char *shapes, int line, const char *path,
                         const char *words) {
  ss_scene *s = NULL;
  ss_error err;
  cr_assert_neq(parse(materials, shapes, &s, &err), SS_OK, "expected an error at %s", path);
  char head[128];
  snprintf(head, sizeof head, "t.json:%d: %s", line, path);
  cr_expect(!strncmp(err.message, head, strlen(head)), "expected '%s...', got '%s'", head,
            err.message);
  cr_expect(strstr(err.message, words) != NULL, "'%s' does not say '%s'", err.message, words);
}

static const char *quad = "{\"type\": \"quad\", \"material\": \"m\"}";

Test(texture_io, textured_parameters_are_read_and_owned_by_the_scene) {
  ss_image *img = ramp(8);
  ss_error err;
  cr_assert_eq(ss_image_write_png(path_of("c.png"), img, 0.0, &err), SS_OK);
  ss_image_destroy(img);
  ss_scene *s;
  cr_assert_eq(parse("{\"name\": \"m\", \"type\": \"diffuse\", \"albedo\": {\"texture\": "
                     "{\"type\": \"checker\", \"a\": {\"texture\": \"c.png\"}, \"b\": 0.5, "
                     "\"scale\": 8}}},\n"
                     "{\"name\": \"r\", \"type\": \"roughdielectric\", \"alpha\": {\"texture\": "
                     "{\"type\": \"noise\", \"a\": 0.05, \"b\": 0.4, \"space\": \"world\", "
                     "\"ridged\": true, \"range\": [0.6, 0.9]}}}",
                     quad, &s, &err),
               SS_OK, "%s", err.message);
  cr_assert_eq(s->num_textures, 3);
  cr_assert_not_null(s->materials[0].textures[SS_PARAM_ALBEDO]);
  cr_assert_not_null(s->materials[1].textures[SS_PARAM_ALPHA]);
  ss_scene_destroy(s);
}

Test(texture_io, bad_textures_are_refused_naming_file_line_and_key) {
  expect_error("{\"name\": \"m\", \"type\": \"diffuse\",\n \"albedo\": {\"texture\": {\"type\": "
               "\"image\", \"file\": \"missing.png\"}}}",
               quad, 5, "materials[0].albedo.texture.file", "missing.png");
  expect_error("{\"name\": \"m\", \"type\": \"diffuse\",\n \"albedo\": {\"texture\": {\"type\": "
               "\"checker\", \"b\": 1.5}}}",
               quad, 5, "materials[0].albedo", "outside");
  expect_error("{\"name\": \"m\", \"type\": \"diffuse\",\n \"albedo\": {\"texture\": {\"type\": "
               "\"marble\"}}}",
               quad, 5, "materials[0].albedo.texture.type", "unknown texture type");
  expect_error("{\"name\": \"m\", \"type\": \"diffuse\",\n \"albedo\": {\"texture\": {\"type\": "
               "\"image\", \"file\": \"c.png\", \"wrap\": \"tile\"}}}",
               quad, 5, "materials[0].albedo.texture.wrap", "unknown wrap mode");
  expect_error("{\"name\": \"m\", \"type\": \"diffuse\",\n \"albedo\": {\"texture\": \"x.png\", "
               "\"scale\": 2}}",
               quad, 5, "materials[0].albedo.scale", "unknown key");
  expect_error("{\"name\": \"m\", \"type\": \"translucent\", \"medium\": {\"sigma_s\": 1, "
               "\"sigma_a\": 0.1},\n \"alpha\": {\"texture\": {\"type\": \"checker\"}}}",
               "{\"type\": \"sphere\", \"material\": \"m\"}", 5, "materials[0].alpha",
               "no parameter 'alpha'");
}

Test(texture_io, a_uv_texture_on_a_mesh_without_uvs_is_refused) {
  FILE *f = fopen(path_of("tri.obj"), "w");
  fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", f);
  fclose(f);
  const char *mat = "{\"name\": \"m\", \"type\": \"diffuse\", \"albedo\": {\"texture\": "
                    "{\"type\": \"checker\"}}}";
  expect_error(mat,
               "{\"type\": \"quad\", \"material\": \"m\"},\n"
               "{\"type\": \"mesh\", \"file\": \"tri.obj\", \"material\": \"m\"}",
               8, "shapes[1]", "texture coordinates");
  /* world-space noise needs no uvs */
  ss_scene *s;
  ss_error err;
  cr_assert_eq(parse("{\"name\": \"m\", \"type\": \"diffuse\", \"albedo\": {\"texture\": "
                     "{\"type\": \"noise\", \"space\": \"world\"}}}",
                     "{\"type\": \"mesh\", \"file\": \"tri.obj\", \"material\": \"m\"}", &s, &err),
               SS_OK, "%s", err.message);
  ss_scene_destroy(s);
}

Test(texture_io, a_translucent_materials_albedo_and_mfp_may_be_textures) {
  ss_scene *s;
  ss_error err;
  const char *sphere = "{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"m\"}";
  cr_assert_eq(parse("{\"name\": \"m\", \"type\": \"translucent\", \"eta\": 1.33, \"bssrdf\": "
                     "\"dipole\", \"mfp\": [0.4, 0.2, 0.1], \"albedo\": {\"texture\": {\"type\": "
                     "\"noise\", \"space\": \"world\", \"a\": 0.2, \"b\": [0.8, 0.6, 0.4]}}}",
                     sphere, &s, &err),
               SS_OK, "%s", err.message);
  const ss_material *m = &s->materials[0];
  cr_assert(m->by_albedo);
  cr_assert(ss_material_varies(m));
  /* the medium is built from the middle of the texture's range */
  cr_assert_float_eq(m->albedo.c[0], 0.5, 1e-15);
  cr_assert_float_eq(m->albedo.c[2], 0.3, 1e-15);
  cr_assert_float_eq(m->mfp.c[1], 0.2, 1e-15);
  ss_scene_destroy(s);
  expect_error("{\"name\": \"m\", \"type\": \"translucent\", \"mfp\": 0.1,\n \"albedo\": "
               "{\"texture\": {\"type\": \"checker\", \"a\": 0.2, \"b\": 1}}}",
               sphere, 5, "materials[0].albedo", "(0, 1)");
  expect_error("{\"name\": \"m\", \"type\": \"translucent\", \"albedo\": 0.5,\n \"mfp\": "
               "{\"texture\": {\"type\": \"checker\", \"a\": 0, \"b\": 1}}}",
               sphere, 5, "materials[0].mfp", "> 0");
  /* behind eta 1.33 the exact inversion reaches albedo 1 - F(0) = 0.98 only */
  expect_error("{\"name\": \"m\", \"type\": \"translucent\", \"eta\": 1.33, \"mfp\": 0.1,\n "
               "\"albedo\": {\"texture\": {\"type\": \"checker\", \"a\": 0.5, \"b\": 0.99}}}",
               sphere, 5, "materials[0].albedo", "0.99");
  /* refused when the scene is committed: the message names the file and the material */
  cr_assert_neq(parse("{\"name\": \"m\", \"type\": \"translucent\", \"bssrdf\": \"pbd\", "
                      "\"mfp\": 0.1, \"albedo\": {\"texture\": {\"type\": \"checker\", \"a\": "
                      "0.5, \"b\": 0.6}}}",
                      sphere, &s, &err),
                SS_OK);
  cr_assert(strstr(err.message, "t.json: material 'm'") && strstr(err.message, "tabulates"), "%s",
            err.message);
}
