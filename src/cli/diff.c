/* subsurf diff: one image against a reference, in the numbers `compare`
 * reports (relMSE as pbrt-v4's imgtool defines it, image_metrics.h; the mean
 * ratio per channel) and, with --map, compare's false-colour map of the
 * relative error (error_map.h). */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/output_check.h"
#include "cli/result_json.h"

#include "subsurf/error_map.h"
#include "subsurf/image_io.h"
#include "subsurf/image_metrics.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <string.h>

#define CMD "diff"

typedef struct {
  const char *image, *reference, *mask, *map, *json_path;
} options;

static void usage(FILE *out) {
  fprintf(out,
          "usage: subsurf diff IMAGE REFERENCE [options]\n\n"
          "IMAGE against REFERENCE (EXR, PNG or PFM; the same size, at least 3 channels):\n"
          "per channel the means, their ratio and the relMSE of pbrt-v4's imgtool,\n"
          "mean over pixels of (v - ref)^2 / (ref + 0.01)^2, as `subsurf compare` reports.\n"
          "  --mask FILE        one-channel image: only pixels > 0.5 count (default: all)\n"
          "  --map FILE         false-colour map of |v - ref| / (ref + 0.01), averaged over\n"
          "                     R, G, B: blue 0, green, yellow, red >= 1; grey outside the mask\n"
          "                     (PNG, EXR or PFM by its extension)\n"
          "  --json FILE|-      the numbers as JSON (default: a table on stdout)\n");
}

static int parse_option(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!strcmp(name, "mask")) {
    o->mask = value;
  } else if (!strcmp(name, "map")) {
    o->map = value;
  } else if (!strcmp(name, "json")) {
    o->json_path = value;
  } else {
    return 0;
  }
  return 1;
}

static int parse_positional(void *ctx, const char *arg) {
  options *o = ctx;
  if (!o->image) {
    o->image = arg;
  } else if (!o->reference) {
    o->reference = arg;
  } else {
    return 0;
  }
  return 1;
}

static int check_outputs(const options *o) {
  ss_output_plan p;
  ss_output_plan_init(&p);
  ss_output_plan_add_input(&p, "IMAGE", o->image);
  ss_output_plan_add_input(&p, "REFERENCE", o->reference);
  if (o->mask) {
    ss_output_plan_add_input(&p, "--mask", o->mask);
  }
  if (o->map) {
    if (!ss_image_format_supported(o->map)) {
      fprintf(stderr, "subsurf %s: --map: expected a file ending in .png, .exr or .pfm, got '%s'\n",
              CMD, o->map);
      ss_output_plan_free(&p);
      return 2;
    }
    ss_output_plan_add(&p, "--map", o->map, ss_file_kind_of_name(o->map, SS_FILE_PNG), 0, 0);
  }
  if (o->json_path) {
    ss_output_plan_add(&p, "--json", o->json_path, SS_FILE_JSON, 0, 0);
  }
  return ss_cli_check_outputs(&p, CMD);
}

static ss_image *read_image(const char *label, const char *path) {
  ss_image *img = NULL;
  ss_error err;
  if (ss_image_read(path, &img, &err) != SS_OK) {
    fprintf(stderr, "subsurf %s: %s: %s\n", CMD, label, err.message);
    return NULL;
  }
  return img;
}

static cJSON *to_json(const options *o, const ss_image_error *e) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "command", CMD);
  cJSON_AddStringToObject(root, "image", o->image);
  cJSON_AddStringToObject(root, "reference", o->reference);
  cJSON_AddNumberToObject(root, "pixels", (double)e->pixels);
  cJSON_AddNumberToObject(root, "rel_mse", e->rel_mse);
  double ratio[3];
  for (int c = 0; c < 3; ++c) {
    ratio[c] = ss_image_error_mean_ratio(e, c);
  }
  cJSON_AddItemToObject(root, "rel_mse_rgb", cJSON_CreateDoubleArray(e->rel_mse_c, 3));
  cJSON_AddItemToObject(root, "rmse_rgb", cJSON_CreateDoubleArray(e->rmse, 3));
  cJSON_AddItemToObject(root, "mean_rgb", cJSON_CreateDoubleArray(e->mean, 3));
  cJSON_AddItemToObject(root, "reference_mean_rgb", cJSON_CreateDoubleArray(e->ref_mean, 3));
  /* A reference whose mean is 0 has no ratio: null, never NaN. */
  cJSON *r = cJSON_AddArrayToObject(root, "mean_ratio_rgb");
  for (int c = 0; c < 3; ++c) {
    cJSON_AddItemToArray(r, isfinite(ratio[c]) ? cJSON_CreateNumber(ratio[c]) : cJSON_CreateNull());
  }
  return root;
}

static void print_table(const ss_image_error *e) {
  const char *names[3] = {"R", "G", "B"};
  printf("%zu pixels, relMSE %.4g\n", e->pixels, e->rel_mse);
  printf("channel  mean         reference    ratio    relMSE       RMSE\n");
  for (int c = 0; c < 3; ++c) {
    char ratio[32] = "-"; /* a reference whose mean is 0 has no ratio */
    double q = ss_image_error_mean_ratio(e, c);
    if (isfinite(q)) {
      snprintf(ratio, sizeof ratio, "%.4f", q);
    }
    printf("%-8s %-12.6g %-12.6g %-8s %-12.4g %.4g\n", names[c], e->mean[c], e->ref_mean[c], ratio,
           e->rel_mse_c[c], e->rmse[c]);
  }
}

static int run(const options *o) {
  ss_image *img = read_image("IMAGE", o->image);
  ss_image *ref = img ? read_image("REFERENCE", o->reference) : NULL;
  ss_image *mask = ref && o->mask ? read_image("--mask", o->mask) : NULL;
  int status = 2;
  if (img && ref && (mask || !o->mask)) {
    ss_image_error e;
    ss_error err;
    if (ss_image_error_compute(img, ref, mask, &e, &err) != SS_OK) {
      fprintf(stderr, "subsurf %s: %s against %s: %s\n", CMD, o->image, o->reference, err.message);
    } else {
      status = 0;
      if (o->map) {
        ss_image *map = ss_error_map(img, ref, mask);
        if (!map || ss_image_write(o->map, map, 0.0, &err) != SS_OK) {
          fprintf(stderr, "subsurf %s: --map: %s\n", CMD, map ? err.message : "out of memory");
          status = 1;
        }
        ss_image_destroy(map);
      }
      if (status == 0 && o->json_path) {
        cJSON *root = to_json(o, &e);
        status = ss_json_write_file(root, o->json_path, CMD) ? 1 : 0;
        cJSON_Delete(root);
      }
      if (status == 0 && (!o->json_path || strcmp(o->json_path, "-") != 0)) {
        print_table(&e);
      }
    }
  }
  ss_image_destroy(mask);
  ss_image_destroy(ref);
  ss_image_destroy(img);
  return status;
}

int ss_cmd_diff(int argc, char **argv) {
  options o = {0};
  ss_cli_spec spec = {NULL, parse_option, parse_positional, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, &o);
  if (rc) {
    return rc == 1 ? 0 : 2;
  }
  if (!o.reference) {
    fprintf(stderr, "subsurf %s: expected two images, IMAGE and REFERENCE (see --help)\n", CMD);
    return 2;
  }
  rc = check_outputs(&o);
  return rc ? rc : run(&o);
}
