/* The bad-input sweep: every command, every option that takes a
 * value, each malformed value that the option's documented range excludes
 * (negative, zero, NaN, inf, 1e308, empty, text, trailing garbage; for file
 * options an empty name, a missing directory and a directory). Each run must
 * exit 2 within a few seconds with exactly one line on stderr naming the
 * option, print nothing on stdout and write no file.
 * The ~1000 lines of the option sweeps call the commands in this process
 * (cli/cli_call.h: same argv, directory, stdout and stderr, and leaks still
 * reported at exit); the scene-file cases below run the `subsurf` binary. */
#include "cli/cli_call.h"
#include "subsurf/image_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <unistd.h>

CLI_SUITE(bad_input_sweep);

/* The generic malformed values; an option lists the ones it accepts. */
static const struct {
  const char *tag, *text;
} values[] = {{"neg", "-1"}, {"zero", "0"},   {"nan", "nan"},    {"inf", "inf"},  {"huge", "1e308"},
              {"empty", ""}, {"text", "abc"}, {"garbage", "1x"}, {"hex", "0x10"}, {"space", " 5"}};

/* Malformed file names: empty, in a missing directory, a directory. */
static const char *const paths[] = {"", "missing-dir/f", "/", "."};

typedef struct {
  const char *name;  /* without the leading "--" */
  const char *valid; /* tags of `values` that are valid for it; "path" for a file */
  const char *extra; /* arguments the option needs to matter, or NULL */
} option;

static int run_case(const char *base, const option *o, const char *value) {
  char args[1024], needle[80];
  snprintf(args, sizeof args, "%s %s --%s '%s'", base, o->extra ? o->extra : "", o->name, value);
  snprintf(needle, sizeof needle, "%s", o->name);
  double t0 = cli_now();
  cli_call_expect_bad_input(&res, dir, args, needle);
  cr_expect(res.out[0] == '\0', "'%s' printed on stdout: %s", args, res.out);
  cr_expect(cli_now() - t0 < 5.0, "'%s' took %.1f s to refuse", args, cli_now() - t0);
  return 1;
}

/* Runs every malformed value of every option after `base`; returns the count. */
static int sweep(const char *base, const option *opts, size_t n) {
  int cases = 0;
  for (size_t i = 0; i < n; ++i) {
    const option *o = &opts[i];
    if (!strcmp(o->valid, "path")) {
      for (size_t k = 0; k < sizeof paths / sizeof paths[0]; ++k) {
        cases += run_case(base, o, paths[k]);
      }
      continue;
    }
    for (size_t k = 0; k < sizeof values / sizeof values[0]; ++k) {
      if (!strstr(o->valid, values[k].tag)) {
        cases += run_case(base, o, values[k].text);
      }
    }
  }
  return cases;
}

#define SWEEP(base, opts) sweep(base, opts, sizeof opts / sizeof opts[0])

/* The medium and incidence options of halfspace, model, compare and layer. */
static const option slab[] = {
    {"sigma-s", "zero", NULL},
    {"sigma-a", "zero", NULL},
    {"g", "zero", NULL},
    {"phase", "", NULL},
    {"medium", "", NULL},
    {"scale", "", "--medium skin1"},
    {"channel", "", "--medium skin1"},
    {"eta", "", NULL},
    {"theta-i", "zero", NULL},
    {"theta-o", "zero neg", NULL},
};

/* The thickness and binning options of halfspace, model and compare. */
static const option medium[] = {
    {"thickness", "inf", NULL},
    {"rmin", "", NULL},
    {"rmax", "", NULL},
    {"rbins", "", NULL},
    {"xmin", "zero neg", NULL},
    {"xmax", "zero neg", NULL},
    {"xbins", "", NULL},
    {"ymin", "zero neg", NULL},
    {"ymax", "zero neg", NULL},
    {"ybins", "", NULL},
    {"flakes", "", NULL},
    {"flake-p", "zero", "--flakes fiber"},
    {"medium-axis", "", "--flakes fiber"},
    {"flake-albedo-falloff", "zero", "--flakes fiber"},
    {"flake-albedo-exponent", "zero", "--flakes fiber"},
};

/* The options of a Monte Carlo reference run. */
static const option run[] = {
    {"paths", "", NULL},       {"time-limit", "zero", NULL}, {"seed", "zero", NULL},
    {"threads", "zero", NULL}, {"max-depth", "", NULL},
};

Test(bad_input_sweep, halfspace, .timeout = 600) {
  static const option own[] = {
      {"json", "path", NULL}, {"map", "path", NULL}, {"exposure", "zero neg", "--map m.png"}};
  const char *base = "halfspace --paths 200 --quiet --json out.json";
  int n = SWEEP(base, slab) + SWEEP(base, medium) + SWEEP(base, run) + SWEEP(base, own);
  cr_log_info("halfspace: %d malformed command lines", n);
}

Test(bad_input_sweep, layer, .timeout = 600) {
  static const option own[] = {
      {"thickness", "", NULL},
      {"bottom", "", NULL},
      {"stack", "path", NULL},
      {"method", "", NULL},
      {"packing", "zero", NULL},
      {"nodes", "", NULL},
      {"modes", "", NULL},
      {"accuracy", "", NULL},
      {"threads", "zero", NULL},
      {"paths", "", "--method mc"},
      {"seed", "zero", "--method mc"},
      {"json", "path", NULL},
  };
  const char *base = "layer --quiet --json out.json";
  int n = SWEEP(base, slab) + SWEEP(base, own);
  cr_log_info("layer: %d malformed command lines", n);
}

Test(bad_input_sweep, model, .timeout = 600) {
  static const option own[] = {
      {"model", "", NULL},
      {"profile-r", "zero", NULL},
      {"beam-samples", "", "--model pbd"},
      {"s-rtol", "", "--model fwddip"},
      {"image-a", "", "--model fwddip"},
      {"ballistic", "zero", "--model fwddip"},
      {"layers", "", "--model layers"},
      {"table", "path", "--model table-radial"},
      {"json", "path", NULL},
  };
  const char *base = "model --model dipole --json out.json";
  int n = SWEEP(base, slab) + SWEEP(base, medium) + SWEEP(base, own);
  cr_log_info("model: %d malformed command lines", n);
}

Test(bad_input_sweep, compare_halfspace, .timeout = 600) {
  static const option own[] = {
      {"models", "", NULL}, {"plot", "path", NULL}, {"json", "path", NULL}};
  const char *base = "compare-halfspace --models dipole --paths 200 --quiet --json out.json";
  int n = SWEEP(base, slab) + SWEEP(base, medium) + SWEEP(base, run) + SWEEP(base, own);
  cr_log_info("compare-halfspace: %d malformed command lines", n);
}

Test(bad_input_sweep, render, .timeout = 600) {
  cli_write_file(dir, "scene.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                 " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
                 " \"integrator\": {\"type\": \"path\"}, \"render\": {\"spp\": 2}}\n");
  static const option own[] = {
      {"spp", "", NULL},
      {"threads", "zero", NULL},
      {"seed", "zero", NULL},
      {"integrator", "", NULL},
      {"crop", "", NULL},
      {"time-limit", "", NULL},
      {"exposure", "zero neg", NULL},
      {"checkpoint-interval", "zero", "--checkpoint c.ck"},
      {"output", "path", NULL},
      {"checkpoint", "path", NULL},
      {"resume", "path", NULL},
      {"trimmed-mean", "", NULL},
      {"irradiance-cache", "path", "--integrator hierarchical"},
  };
  int n = SWEEP("render scene.json -o out.exr --quiet", own);
  cr_log_info("render: %d malformed command lines", n);
}

Test(bad_input_sweep, table, .timeout = 600) {
  static const option build[] = {
      {"eta", "", NULL}, {"g", "zero", NULL},       {"kind", "", NULL},
      {"fit", "", NULL}, {"threads", "zero", NULL}, {"output", "path", NULL},
  };
  static const option check[] = {
      {"rho", "", NULL},      {"theta", "zero", NULL},   {"samples", "", NULL},
      {"seed", "zero", NULL}, {"threads", "zero", NULL},
  };
  int n = SWEEP("table build --kind radial --eta 1.33 --g 0 -o t.sstab --quiet", build);
  cli_run_in(&res, dir, "table build --kind radial --eta 1.33 --g 0 -o r.sstab --quiet", 0.0);
  cr_assert_eq(res.status, 0, "%s", res.err);
  n += SWEEP("table check r.sstab --rho 0.5 --theta 0 --samples 100", check);
  cr_log_info("table: %d malformed command lines", n);
}

/* Nested media: conflicting priorities, an interface without a
 * defined index and a priority out of range are refused when the scene is
 * read, naming the scene file and the key; integrators that cannot follow
 * nested media refuse them naming the material. */
Test(bad_input_sweep, nested_media, .timeout = 120) {
  static const struct {
    const char *materials, *key;
  } cases[] = {
      {"{\"name\": \"a\", \"type\": \"dielectric\"}, {\"name\": \"b\", \"type\": \"dielectric\"}",
       "priority"},
      {"{\"name\": \"a\", \"type\": \"dielectric\", \"priority\": 1},\n"
       " {\"name\": \"b\", \"type\": \"translucent\", \"boundary\": \"index-matched\",\n"
       "  \"medium\": {\"sigma_s\": 1, \"sigma_a\": 1}}",
       "eta"},
      {"{\"name\": \"a\", \"type\": \"dielectric\", \"priority\": -1}, {\"name\": \"b\", "
       "\"type\": \"dielectric\"}",
       "priority"},
      {"{\"name\": \"a\", \"type\": \"dielectric\", \"priority\": 1001}, {\"name\": \"b\", "
       "\"type\": \"dielectric\"}",
       "priority"},
      {"{\"name\": \"a\", \"type\": \"dielectric\", \"priority\": 1.5}, {\"name\": \"b\", "
       "\"type\": \"dielectric\"}",
       "priority"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    char text[2048];
    snprintf(
        text, sizeof text,
        "{\"camera\": {\"resolution\": [8, 8]},\n \"materials\": [%s],\n"
        " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1, \"material\": \"a\"},\n"
        "  {\"type\": \"sphere\", \"subdivisions\": 1, \"radius\": 0.5, \"material\": \"b\"}],\n"
        " \"lights\": [{\"type\": \"environment\"}], \"render\": {\"spp\": 1}}\n",
        cases[k].materials);
    cli_write_file(dir, "nested.json", text);
    cli_expect_bad_input(&res, dir, "render nested.json -o out.exr --quiet", "nested.json");
    cr_expect(strstr(res.err, cases[k].key), "case %zu: stderr should name '%s': %s", k,
              cases[k].key, res.err);
  }
  cli_write_file(dir, "nested.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"materials\": [{\"name\": \"a\", \"type\": \"dielectric\"},\n"
                 "  {\"name\": \"b\", \"type\": \"dielectric\", \"priority\": 1}],\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1, \"material\": \"a\"},\n"
                 "  {\"type\": \"sphere\", \"subdivisions\": 1, \"radius\": 0.5, \"material\": "
                 "\"b\"}],\n"
                 " \"lights\": [{\"type\": \"environment\"}], \"render\": {\"spp\": 1}}\n");
  static const char *const integrators[] = {"path", "bssrdf", "hierarchical", "hybrid", "fem"};
  for (size_t k = 0; k < 5; ++k) {
    char args[256];
    snprintf(args, sizeof args, "render nested.json -o out.exr --quiet --integrator %s",
             integrators[k]);
    cli_expect_bad_input(&res, dir, args, "material 'a'");
  }
  cli_run_in(&res, dir, "render nested.json -o out.exr --quiet", 0.0);
  cr_expect_eq(res.status, 0, "volpath refused nested media: %s", res.err);
  /* Nine concentric regions: deeper than a path's stack of media. */
  char text[2048] = "{\"camera\": {\"resolution\": [8, 8]},\n \"materials\": [{\"name\": "
                    "\"a\", \"type\": \"dielectric\"}],\n \"shapes\": [";
  for (int k = 1; k <= 9; ++k) {
    size_t used = strlen(text);
    snprintf(text + used, sizeof text - used,
             "%s{\"name\": \"s%d\", \"type\": \"sphere\", \"subdivisions\": 1, "
             "\"radius\": %d, \"material\": \"a\"}",
             k > 1 ? ",\n  " : "", k, k);
  }
  size_t used = strlen(text);
  snprintf(text + used, sizeof text - used,
           "],\n \"lights\": [{\"type\": \"environment\"}], \"render\": {\"spp\": 1}}\n");
  cli_write_file(dir, "nested.json", text);
  cli_expect_bad_input(&res, dir, "render nested.json -o out.exr --quiet",
                       "'s8', 's9' bound 9 media");
}

/* A whole number out of range is printed in full, not as 2e+09. */
Test(bad_input_sweep, whole_numbers_in_messages, .timeout = 60) {
  cli_write_file(dir, "spp.json",
                 "{\"camera\": {\"resolution\": [8, 8]}, \"shapes\": [{\"type\": \"sphere\"}],\n"
                 " \"render\": {\"spp\": 2e9}}\n");
  cli_expect_bad_input(&res, dir, "render spp.json -o out.exr --quiet",
                       "render.spp: 2000000000 is out of range [1, 1073741824]");
}

/* Integrators with one kernel per material refuse a textured medium as bad
 * input (exit 2), before any work. */
Test(bad_input_sweep, textured_media_for_kernel_integrators, .timeout = 120) {
  cli_write_file(dir, "tex.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"materials\": [{\"name\": \"skin\", \"type\": \"translucent\", "
                 "\"mfp\": 0.5,\n  \"albedo\": {\"texture\": {\"type\": \"noise\", "
                 "\"space\": \"world\", \"a\": 0.5, \"b\": 0.9}}}],\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1, \"material\": "
                 "\"skin\"}],\n"
                 " \"lights\": [{\"type\": \"environment\"}], \"render\": {\"spp\": 1}}\n");
  static const char *const integrators[] = {"hierarchical", "hybrid", "fem"};
  for (size_t k = 0; k < 3; ++k) {
    char args[256];
    snprintf(args, sizeof args, "render tex.json -o out.exr --quiet --integrator %s",
             integrators[k]);
    cli_expect_bad_input(&res, dir, args, "material 'skin': a textured albedo or mfp");
  }
}

/* Surface materials: an unknown metal (the message lists the known ones),
 * negative or missing roughness and index, mix and two-sided parts that do
 * not exist or are dielectric interfaces; one line naming the scene file
 * and the key, exit 2, nothing written. */
Test(bad_input_sweep, surface_materials, .timeout = 120) {
  static const struct {
    const char *material, *needle;
  } cases[] = {
      {"{\"name\": \"a\", \"type\": \"conductor\", \"metal\": \"Xx\"}", "Ag, Al, Au"},
      {"{\"name\": \"a\", \"type\": \"conductor\"}", "metal"},
      {"{\"name\": \"a\", \"type\": \"conductor\", \"eta\": 1, \"k\": -1}", "k"},
      {"{\"name\": \"a\", \"type\": \"conductor\", \"eta\": [1, 0, 1], \"k\": 1}", "eta"},
      {"{\"name\": \"a\", \"type\": \"conductor\", \"metal\": \"Au\", \"k\": 1}", "k"},
      {"{\"name\": \"a\", \"type\": \"conductor\", \"metal\": \"Au\", \"alpha\": 0.1}", "alpha"},
      {"{\"name\": \"a\", \"type\": \"roughconductor\", \"metal\": \"Cu\", \"alpha\": -0.1}",
       "alpha"},
      {"{\"name\": \"a\", \"type\": \"roughconductor\", \"metal\": \"Cu\", \"alpha_u\": 0.1}",
       "alpha_u"},
      {"{\"name\": \"a\", \"type\": \"roughconductor\", \"metal\": \"Cu\", \"alpha_u\": 0.1, "
       "\"alpha_v\": 5}",
       "alpha_v"},
      {"{\"name\": \"a\", \"type\": \"mirror\", \"reflectance\": 2}", "reflectance"},
      {"{\"name\": \"a\", \"type\": \"thindielectric\", \"eta\": 0}", "eta"},
      {"{\"name\": \"a\", \"type\": \"diffusetransmission\", \"reflectance\": 0.6, "
       "\"transmittance\": 0.6}",
       "transmittance"},
      {"{\"name\": \"a\", \"type\": \"twosided\", \"material\": \"nothing\"}", "material"},
      {"{\"name\": \"a\", \"type\": \"plastic\", \"eta\": 1}", "eta"},
      {"{\"name\": \"a\", \"type\": \"plastic\", \"albedo\": -0.5}", "albedo"},
      {"{\"name\": \"g\", \"type\": \"dielectric\"},\n"
       " {\"name\": \"a\", \"type\": \"twosided\", \"material\": \"g\"}",
       "material"},
      {"{\"name\": \"m\", \"type\": \"mirror\"},\n"
       " {\"name\": \"a\", \"type\": \"mix\", \"materials\": [\"m\"]}",
       "materials"},
      {"{\"name\": \"m\", \"type\": \"mirror\"},\n"
       " {\"name\": \"a\", \"type\": \"mix\", \"materials\": [\"m\", \"m\"], \"weight\": 2}",
       "weight"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"resolution\": [8, 8]},\n \"materials\": [%s],\n"
             " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1, \"material\": \"a\"}],\n"
             " \"lights\": [{\"type\": \"environment\"}], \"render\": {\"spp\": 1}}\n",
             cases[k].material);
    cli_write_file(dir, "surface.json", text);
    cli_expect_bad_input(&res, dir, "render surface.json -o out.exr --quiet", "surface.json");
    cr_expect(strstr(res.err, cases[k].needle), "case %zu: stderr should name '%s': %s", k,
              cases[k].needle, res.err);
  }
}

/* A scene whose medium has `medium_keys` (flakes and grids). */
static void write_volume_scene(const char *name, const char *medium_keys) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"camera\": {\"resolution\": [8, 8]},\n"
           " \"media\": [{\"name\": \"m\", \"sigma_s\": 1, \"sigma_a\": 0.1, %s}],\n"
           " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\",\n"
           "   \"boundary\": \"index-matched\", \"medium\": \"m\"}],\n"
           " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1, \"material\": \"t\"}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
           " \"render\": {\"spp\": 1}}\n",
           medium_keys);
  cli_write_file(dir, name, text);
}

/* A raw grid file of 2 x 2 x 2 voxels: the header, then `count` floats
 * (8 for a complete file) of `density` with the last set to `last`. */
static void write_raw_grid(const char *name, int count, float density, float last) {
  char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "wb");
  cr_assert_not_null(f);
  static const unsigned char header[32] = {'S', 'S', 'G', 'R', 'I', 'D', '1', '\n', 1, 0, 0,
                                           0,   1,   0,   0,   0,   2,   0,   0,    0, 2, 0,
                                           0,   0,   2,   0,   0,   0,   0,   0,    0, 0};
  const double box[6] = {-1, -1, -1, 1, 1, 1}; /* little-endian hosts (x86-64, arm64) */
  fwrite(header, 1, sizeof header, f);
  fwrite(box, sizeof box[0], 6, f);
  for (int i = 0; i < count; ++i) {
    float v = i == 7 ? last : density;
    fwrite(&v, sizeof v, 1, f);
  }
  fclose(f);
}

Test(bad_input_sweep, volume_media_keys_and_grid_files) {
  static const struct {
    const char *keys, *needle;
  } cases[] = {
      {"\"flakes\": {\"type\": \"fiber\", \"p\": 2000}", "flakes.p"},
      {"\"flakes\": {\"type\": \"fiber\", \"p\": -1}", "flakes.p"},
      {"\"flakes\": {\"type\": \"fiber\", \"axis\": [0, 0, 0]}", "flakes.axis"},
      {"\"flakes\": {\"type\": \"fiber\", \"albedo_falloff\": 2}", "flakes.albedo_falloff"},
      {"\"flakes\": {\"type\": \"spiky\"}", "flakes.type"},
      {"\"flakes\": {\"p\": 20}", "flakes"},
      {"\"flakes\": {\"type\": \"fiber\"}, \"phase\": {\"type\": \"hg\", \"g\": 0.5}", "phase"},
      {"\"grid\": {\"procedural\": \"yarn\", \"resolution\": 0}", "grid.resolution"},
      {"\"grid\": {\"procedural\": \"yarn\", \"plies\": 99}", "grid.plies"},
      {"\"grid\": {\"procedural\": \"wood\", \"size\": [1, 0, 1]}", "grid.size"},
      {"\"grid\": {\"procedural\": \"marble\"}", "grid.procedural"},
      {"\"grid\": {\"file\": \"g.ssgrid\", \"procedural\": \"yarn\"}", "grid"},
      {"\"grid\": {\"file\": \"missing.ssgrid\"}", "missing.ssgrid"},
      {"\"grid\": {\"file\": \"short.ssgrid\"}", "short.ssgrid"},
      {"\"grid\": {\"file\": \"long.ssgrid\"}", "long.ssgrid"},
      {"\"grid\": {\"file\": \"negative.ssgrid\"}", "negative.ssgrid"},
      {"\"grid\": {\"file\": \"nan.ssgrid\"}", "nan.ssgrid"},
  };
  write_raw_grid("short.ssgrid", 7, 1.0f, 1.0f);
  write_raw_grid("long.ssgrid", 9, 1.0f, 1.0f);
  write_raw_grid("negative.ssgrid", 8, 1.0f, -2.0f);
  write_raw_grid("nan.ssgrid", 8, 1.0f, NAN);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    write_volume_scene("v.json", cases[i].keys);
    cli_expect_bad_input(&res, dir, "render v.json -o out.exr --quiet", cases[i].needle);
    cr_expect(res.out[0] == '\0', "'%s' printed on stdout: %s", cases[i].keys, res.out);
  }
  char vdb[1024];
  snprintf(vdb, sizeof vdb, "\"grid\": {\"file\": \"%s/tests/io/data/vec3_only.vdb\"}",
           getenv("SUBSURF_SOURCE_DIR"));
  write_volume_scene("v.json", vdb);
  cli_expect_bad_input(&res, dir, "render v.json -o out.exr --quiet", "no float grid");
}

/* An image file `name` of w x h grey pixels of `value`, the last `last`. */
static void write_map(const char *name, int w, int h, float value, float last) {
  char path[256];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  ss_image *img = ss_image_create(w, h, 1);
  cr_assert_not_null(img);
  for (int i = 0; i < w * h; ++i) {
    img->data[i] = i == w * h - 1 ? last : value;
  }
  ss_error err;
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  ss_image_destroy(img);
}

/* Environment maps: a missing or unreadable file, an image that is not a
 * latitude-longitude map, pixels that are not radiances, and keys out of
 * range each name the file or the key. */
Test(bad_input_sweep, environment_map_keys_and_files) {
  static const struct {
    const char *keys, *needle;
  } cases[] = {
      {"\"map\": \"missing.exr\"", "missing.exr"},
      {"\"map\": \"square.png\"", "square.png: environment map: 4 x 4 pixels"},
      {"\"map\": \"negative.exr\"", "negative.exr: environment map: pixel (3, 1)"},
      {"\"map\": \"nan.exr\"", "nan.exr: environment map: pixel (3, 1)"},
      {"\"map\": \"black.exr\"", "black.exr: environment map: every pixel is black"},
      {"\"map\": \"notes.txt\"", "notes.txt: unknown texture format"},
      {"\"map\": \"fake.hdr\"", "fake.hdr: not a readable Radiance HDR image"},
      {"\"map\": \"\"", "lights[0].map: must not be empty"},
      {"\"map\": \"sky.exr\", \"scale\": -1", "lights[0].scale"},
      {"\"map\": \"sky.exr\", \"up\": [0, 0, 0]", "lights[0].up"},
      {"\"map\": \"sky.exr\", \"front\": [0, 2, 0]", "lights[0].front"},
      {"\"map\": \"sky.exr\", \"rotation\": 1000", "lights[0].rotation"},
      {"\"rotation\": 10", "lights[0].rotation: orients a map"},
  };
  write_map("sky.exr", 4, 2, 1.0f, 1.0f);
  write_map("square.png", 4, 4, 1.0f, 1.0f);
  write_map("negative.exr", 4, 2, 1.0f, -1.0f);
  write_map("nan.exr", 4, 2, 1.0f, NAN);
  write_map("black.exr", 4, 2, 0.0f, 0.0f);
  cli_write_file(dir, "notes.txt", "not an image\n");
  cli_write_file(dir, "fake.hdr", "#?RADIANCE\nnot really\n");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char text[1024];
    snprintf(text, sizeof text,
             "{\"camera\": {\"resolution\": [8, 8]},\n"
             " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
             " \"lights\": [{\"type\": \"environment\", %s}], \"render\": {\"spp\": 1}}\n",
             cases[i].keys);
    cli_write_file(dir, "env.json", text);
    cli_expect_bad_input(&res, dir, "render env.json -o out.exr --quiet", cases[i].needle);
    cr_expect(strstr(res.err, "env.json:"), "case %zu does not name the scene: %s", i, res.err);
    cr_expect(res.out[0] == '\0', "'%s' printed on stdout: %s", cases[i].keys, res.out);
  }
  cli_write_file(dir, "env.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                 " \"lights\": [{\"type\": \"environment\", \"map\": \"sky.exr\", \"scale\": "
                 "2}],\n \"render\": {\"spp\": 1}}\n");
  cli_run_in(&res, dir, "render env.json -o out.exr --quiet", 0.0);
  cr_expect_eq(res.status, 0, "a valid map was refused: %s", res.err);
}

Test(bad_input_sweep, spot_falloff_names_the_key) {
  cli_write_file(dir, "spot.json",
                 "{\"camera\": {\"resolution\": [8, 8]},\n"
                 " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}],\n"
                 " \"lights\": [{\"type\": \"spot\", \"position\": [0, 0, 5], \"falloff\": "
                 "\"cubic\"}], \"render\": {\"spp\": 1}}\n");
  cli_expect_bad_input(&res, dir, "render spot.json -o out.exr --quiet",
                       "lights[0].falloff: unknown falloff 'cubic' (quartic, smoothstep)");
}

/* pbrt-v3 scenes: a syntax error exits 2 with FILE:LINE and what
 * was expected; a directive subsurf reads past is a warning, not an error. */
Test(bad_input_sweep, pbrt_scenes, .timeout = 120) {
  static const char head[] =
      "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\n"
      "Film \"image\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
      "LightSource \"point\"\n";
  static const struct {
    const char *tail, *needle;
  } cases[] = {
      {"Shape \"sphere\"\n", "s.pbrt:7: end of file before WorldEnd"},
      {"Shape \"sphere\" \"float radius\" [1 2\n", "s.pbrt:7: parameter \"float radius\": "
                                                   "expected ']'"},
      {"Shape \"sphere\" \"float radius [1]\n", "s.pbrt:6: unterminated string"},
      {"Shape \"sphere\" \"float radius\" [1 \"2\"]\nWorldEnd\n", "s.pbrt:6: parameter \"float "
                                                                  "radius\": expected numbers"},
      {"Shape \"sphere\" \"float radius\" [1 2]\nWorldEnd\n", "s.pbrt:6: parameter \"float "
                                                              "radius\": expected 1 value, got 2"},
      {"Shape \"plymesh\" \"string filename\" \"no.ply\"\nWorldEnd\n", "no.ply"},
      {"Sphere\nWorldEnd\n", "s.pbrt:6: unknown directive 'Sphere'"},
      /* A string's escaped newline is quoted escaped: the message stays one line. */
      {"Include \"no\\nfile.pbrt\"\nWorldEnd\n", "s.pbrt:6: Include \"no\\nfile.pbrt\""},
      /* a file that reports 0 bytes and holds gigabytes, one past the cap */
      {"Include \"/proc/self/pagemap\"\nWorldEnd\n",
       "/proc/self/pagemap: more than 64 MiB, the limit for a scene file"},
      {"Shape \"plymesh\" \"string filename\" \"big.ply\"\nWorldEnd\n",
       "big.ply: more than 1024 MiB, the limit for a mesh file"},
  };
  cli_write_file(dir, "big.ply", "ply\n");
  char big[256];
  snprintf(big, sizeof big, "%s/big.ply", dir);
  cr_assert_eq(truncate(big, ((off_t)1 << 30) + 1), 0, "a sparse file");
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char text[1024];
    snprintf(text, sizeof text, "%s%s", head, cases[i].tail);
    cli_write_file(dir, "s.pbrt", text);
    cli_expect_bad_input(&res, dir, "render s.pbrt -o out.exr --quiet", cases[i].needle);
    cr_expect(res.out[0] == '\0', "case %zu printed on stdout: %s", i, res.out);
  }
  char text[1024];
  snprintf(text, sizeof text,
           "%sActiveTransform EndTime\nShape \"sphere\" \"integer "
           "subdivisions\" 0\nWorldEnd\n",
           head);
  cli_write_file(dir, "s.pbrt", text);
  cli_run_in(&res, dir, "render s.pbrt -o out.exr --quiet --spp 1", 0.0);
  cr_expect_eq(res.status, 0, "%s", res.err);
  cr_expect(strstr(res.err, "warning: s.pbrt:6: ActiveTransform is not supported (ignored)"), "%s",
            res.err);
}

/* A dense stack of the most layers `layers` takes, asked at the radii the
 * options allow at most: r / h of its table cell h ~ 24 / (512 sigma_tr) is
 * far beyond an int there. Each run answers (exit 0) or refuses (exit 2, one
 * line), and never reads outside the table. */
Test(bad_input_sweep, dense_layer_stack_at_extreme_radii, .timeout = 300) {
  static const char layer[] = "sigma_s=2e4 sigma_a=1e3 eta=1.4 d=0.01; ";
  static const char *const extra[] = {
      "--profile-r 0,1e-300,1,1e6",
      "--rmin 1e-6 --rmax 1e6",
      "--theta-i 60 --theta-o 30 --xmin -1e6 --xmax 1e6 --xbins 16",
  };
  char stack[512] = "";
  for (int k = 0; k < 7; ++k) {
    strcat(stack, layer);
  }
  strcat(stack, "sigma_s=2e4 sigma_a=1e3 eta=1.4 d=inf");
  for (size_t i = 0; i < sizeof extra / sizeof extra[0]; ++i) {
    char args[1024];
    snprintf(args, sizeof args, "model --model layers --layers '%s' %s --json out.json", stack,
             extra[i]);
    cli_call_in(&res, dir, args);
    cr_expect(res.status == 0 ||
                  (res.status == 2 && strchr(res.err, '\n') == strrchr(res.err, '\n')),
              "'%s' exited %d: %s", args, res.status, res.err);
  }
}
