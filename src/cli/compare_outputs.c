/* The files `subsurf compare` writes in its folder, checked together before
 * any render (core/output_plan.h). */
#include "cli/compare_scene.h"
#include "cli/output_check.h"

#include <stdio.h>

/* NAME.exr and NAME.png of a w x h image, and NAME-error.png when `error`. */
static void add_images(ss_output_plan *p, const char *dir, const char *name, int error, int w,
                       int h) {
  char path[SS_PATH_SIZE + 300];
  uint64_t pixels = (uint64_t)w * (uint64_t)h;
  snprintf(path, sizeof path, "%s/%s.exr", dir, name);
  ss_output_plan_add(p, "--output", path, SS_FILE_EXR, 0, 16 * pixels);
  snprintf(path, sizeof path, "%s/%s.png", dir, name);
  ss_output_plan_add(p, "--output", path, SS_FILE_PNG, 0, 4 * pixels);
  if (error) {
    snprintf(path, sizeof path, "%s/%s-error.png", dir, name);
    ss_output_plan_add(p, "--output", path, SS_FILE_PNG, 0, 4 * pixels);
  }
}

static void add_file(ss_output_plan *p, const char *dir, const char *name, ss_file_kind kind) {
  char path[SS_PATH_SIZE + 64];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  ss_output_plan_add(p, "--output", path, kind, 0, 0);
}

int ss_compare_check_outputs(const ss_compare_options *o, int width, int height) {
  ss_output_plan p;
  ss_output_plan_init(&p);
  const char *dir = o->dir;
  if (o->reference) {
    char path[SS_PATH_SIZE + 32];
    snprintf(path, sizeof path, "%s/reference.png", dir);
    ss_output_plan_add(&p, "--output", path, SS_FILE_PNG, 0, 4 * (uint64_t)width * height);
    ss_output_plan_add_input(&p, "--reference", o->reference);
  } else {
    add_images(&p, dir, "reference", 0, width, height);
    add_file(&p, dir, "reference.key", SS_FILE_REFERENCE_KEY);
  }
  for (int i = 0; i < o->num_methods; ++i) {
    add_images(&p, dir, o->results[i].file, 1, width, height);
  }
  add_file(&p, dir, "results.json", SS_FILE_JSON);
  add_file(&p, dir, "results.csv", SS_FILE_CSV);
  add_file(&p, dir, "convergence.svg", SS_FILE_SVG);
  for (int c = 0; c < 3; ++c) {
    char name[32];
    snprintf(name, sizeof name, "mean-ratio-%c.svg", "rgb"[c]);
    add_file(&p, dir, name, SS_FILE_SVG);
  }
  add_file(&p, dir, "error-colorbar.svg", SS_FILE_SVG);
  add_file(&p, dir, "index.html", SS_FILE_HTML);
  ss_output_plan_add_input(&p, "scene", o->scene);
  return ss_cli_check_outputs(&p, "compare");
}
