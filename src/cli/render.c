/* `subsurf render`: renders a JSON scene to EXR (linear) and PNG
 * (tonemapped). Exit codes: 0 done, 1 run-time failure (e.g. cannot write),
 * 2 bad input, 130 interrupted (the image so far is written as
 * <name>-partial.exr/.png). */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/majorant_warning.h"
#include "cli/memory_check.h"
#include "cli/mpi_job.h"
#include "cli/output_check.h"
#include "cli/progress_bar.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/checkpoint.h"
#include "subsurf/fem_cache.h"
#include "subsurf/image_io.h"
#include "subsurf/integrator.h"
#include "subsurf/irradiance_cache.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"
#include "subsurf/trimmed_render.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CMD "render"

static void usage(FILE *out) {
  char names[256];
  ss_integrator_names(names, sizeof names);
  fprintf(out,
          "usage: subsurf render SCENE.json|SCENE.pbrt [options]\n\n"
          "Renders a scene (docs/scene-format.md) and writes an EXR and a PNG. A file ending\n"
          "in .pbrt is read as a pbrt-v3 scene (docs/pbrt-import.md); what it holds that\n"
          "subsurf ignores or approximates is printed as warnings with FILE:LINE.\n\n"
          "options:\n"
          "  -o, --output FILE.exr  output image (default: the scene's render.output, else\n"
          "                         SCENE's base name + .exr in the current directory);\n"
          "                         the PNG gets the same base name\n"
          "  --spp N                samples per pixel (overrides render.spp)\n"
          "  --threads N            worker threads, at most 4096 (default 0: all cores)\n"
          "  --seed N               random seed (default: render.seed, else 0)\n"
          "  --integrator NAME      %s (overrides integrator.type)\n"
          "  --crop x0,y0,x1,y1     render only this pixel window (x1, y1 exclusive)\n"
          "  --time-limit S         stop after S seconds (1e-3..1e9) and write what is done\n"
          "  --exposure E           PNG exposure in stops, [-64, 64] (default: render.exposure,\n"
          "                         else 0)\n"
          "  --variance             also write the per-pixel variance as NAME-variance.exr\n"
          "  --no-png               write only the EXR\n"
          "  --quiet                no progress bar and no statistics\n"
          "  --checkpoint FILE      save the film to FILE between passes (every\n"
          "                         --checkpoint-interval S seconds, default 60), on Ctrl-C\n"
          "                         and at the end\n"
          "  --irradiance-cache FILE\n"
          "                         hierarchical: read pass 1's points from FILE when it was\n"
          "                         made for this scene and lighting, else compute and write it\n"
          "  --resume FILE          continue the render saved in FILE (same scene file,\n"
          "                         integrator, spp, seed and crop) to the image an\n"
          "                         uninterrupted render gives; saves to FILE again unless\n"
          "                         --checkpoint names another\n"
          "  --trimmed-mean K,F     split the spp into K passes (K must divide it) and write per\n"
          "                         pixel the trimmed mean of the pass means, dropping the\n"
          "                         floor(F K) highest and lowest, F in [0, 0.5) (Frederickx &\n"
          "                         Dutre 2017, sec. 7.3; --variance: the passes' spread);\n"
          "                         not with --time-limit, --checkpoint or --resume\n"
          "  -h, --help             this help\n\n"
          "Everything is checked before rendering (the film must fit in memory: 56 bytes per\n"
          "pixel plus 12 per image). Ctrl-C or SIGTERM stops the render, writes\n"
          "NAME-partial.exr/.png and exits with 130.\n\n"
          "mpirun -np N subsurf render ... spreads the image's tiles over N processes (any\n"
          "machines of a hostfile); rank 0 writes the same bytes one process would\n"
          "(docs/render.md, \"Many machines\"). Not with --checkpoint, --resume,\n"
          "--trimmed-mean or --irradiance-cache.\n",
          names);
}

typedef struct {
  const char *scene;
  const char *output;
  unsigned long long seed;
  int spp, threads, has_seed;
  const char *integrator;
  int crop[4], has_crop;
  double time_limit, exposure;
  int has_time_limit, has_exposure, quiet, variance, no_png;
  const char *checkpoint, *resume;
  double checkpoint_interval;
  int passes; /* --trimmed-mean K,F: K (0: off) and F */
  double trim;
  const char *irradiance_cache;
} options;

static int parse_trimmed(const char *s, options *o) {
  double v[3];
  if (ss_cli_number_list(s, 0.0, 1e6, v, 3) != 2 || v[0] != floor(v[0]) || v[0] < 1.0 ||
      !(v[1] < 0.5)) {
    fprintf(stderr,
            "subsurf " CMD ": --trimmed-mean: expected K,F with a whole number of passes K >= 1 "
            "and a fraction 0 <= F < 0.5, got '%s'\n",
            s);
    return -1;
  }
  o->passes = (int)v[0];
  o->trim = v[1];
  return 0;
}

static int parse_crop(const char *s, int crop[4]) {
  double v[4];
  if (ss_cli_number_list(s, 0.0, 65536.0, v, 4) != 4) {
    return 0;
  }
  for (int i = 0; i < 4; ++i) {
    if (v[i] != floor(v[i])) {
      return 0;
    }
    crop[i] = (int)v[i];
  }
  return crop[0] < crop[2] && crop[1] < crop[3];
}

static int parse_option(void *ctx, const char *name, const char *v) {
  options *o = ctx;
  int rc = 0;
  if (!strcmp(name, "o") || !strcmp(name, "output")) {
    size_t n = strlen(v);
    if (n < 5 || strcmp(v + n - 4, ".exr")) {
      fprintf(stderr, "subsurf " CMD ": --output: expected an .exr file name, got '%s'\n", v);
      return -1;
    }
    o->output = v;
  } else if (!strcmp(name, "spp") || !strcmp(name, "threads") || !strcmp(name, "seed")) {
    double x = 0.0;
    rc = ss_parse_arg(CMD, ss_render_args, name, v, &x);
    if (rc != 0) {
      return -1;
    }
    if (!strcmp(name, "spp")) {
      o->spp = (int)x;
    } else if (!strcmp(name, "threads")) {
      o->threads = (int)x;
    } else {
      o->seed = (unsigned long long)x;
      o->has_seed = 1;
    }
  } else if (!strcmp(name, "integrator")) {
    if (!ss_integrator_find(v)) {
      char names[256];
      ss_integrator_names(names, sizeof names);
      fprintf(stderr, "subsurf " CMD ": --integrator: expected %s, got '%s'\n", names, v);
      return -1;
    }
    o->integrator = v;
  } else if (!strcmp(name, "crop")) {
    if (!parse_crop(v, o->crop)) {
      fprintf(stderr,
              "subsurf " CMD ": --crop: expected whole numbers x0,y0,x1,y1 with 0 <= x0 < x1, 0 <= "
              "y0 < y1, got '%s'\n",
              v);
      return -1;
    }
    o->has_crop = 1;
  } else if (!strcmp(name, "time-limit")) {
    rc = ss_parse_double_in(CMD, name, v, 1e-3, 1e9, &o->time_limit);
    o->has_time_limit = 1;
  } else if (!strcmp(name, "exposure")) {
    rc = ss_parse_double_in(CMD, name, v, -64.0, 64.0, &o->exposure);
    o->has_exposure = 1;
  } else if (!strcmp(name, "checkpoint")) {
    o->checkpoint = v;
  } else if (!strcmp(name, "resume")) {
    o->resume = v;
  } else if (!strcmp(name, "irradiance-cache")) {
    o->irradiance_cache = v;
  } else if (!strcmp(name, "checkpoint-interval")) {
    rc = ss_parse_double_in(CMD, name, v, 0.0, 1e9, &o->checkpoint_interval);
  } else if (!strcmp(name, "trimmed-mean")) {
    rc = parse_trimmed(v, o);
  } else {
    return 0;
  }
  return rc == 0 ? 1 : -1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  int *flag = !strcmp(name, "quiet")      ? &o->quiet
              : !strcmp(name, "variance") ? &o->variance
              : !strcmp(name, "no-png")   ? &o->no_png
                                          : NULL;
  if (flag) {
    *flag = 1;
  }
  return flag != NULL;
}

static int parse_scene(void *ctx, const char *arg) {
  options *o = ctx;
  if (o->scene) {
    return 0;
  }
  o->scene = arg;
  return 1;
}

/* Returns -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, options *o) {
  memset(o, 0, sizeof *o);
  o->checkpoint_interval = 60.0;
  const ss_cli_spec spec = {parse_flag, parse_option, parse_scene, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  if (!o->scene) {
    fprintf(stderr, "subsurf " CMD ": missing the scene file (see subsurf render --help)\n");
    return 2;
  }
  return -1;
}

/* out = base + suffix + ext, where base is `exr` without ".exr". */
static void derive(char *out, size_t size, const char *exr, const char *suffix, const char *ext) {
  size_t n = strlen(exr) - 4;
  snprintf(out, size, "%.*s%s%s", (int)n, exr, suffix, ext);
}

static void default_output(const char *scene, char *out, size_t size) {
  const char *base = strrchr(scene, '/');
  base = base ? base + 1 : scene;
  const char *dot = strrchr(base, '.');
  size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
  snprintf(out, size, "%.*s.exr", (int)n, base);
}

static int write_outputs(const ss_film *film, const char *exr, int partial, int png, int variance,
                         double exposure, int quiet) {
  const char *suffix = partial ? "-partial" : "";
  char path[SS_PATH_SIZE + 32], png_path[SS_PATH_SIZE + 32], var_path[SS_PATH_SIZE + 32];
  derive(path, sizeof path, exr, suffix, ".exr");
  derive(png_path, sizeof png_path, exr, suffix, ".png");
  char var_suffix[32];
  snprintf(var_suffix, sizeof var_suffix, "%s-variance", suffix);
  derive(var_path, sizeof var_path, exr, var_suffix, ".exr");
  ss_image *img = ss_film_image(film);
  ss_image *var = variance ? ss_film_variance_image(film) : NULL;
  ss_error err;
  ss_status st = SS_OK;
  if (!img || (variance && !var)) {
    st = ss_error_set(&err, SS_ERR_NO_MEMORY, "out of memory for the output image");
  }
  if (st == SS_OK)
    st = ss_image_write_exr(path, img, &err);
  if (st == SS_OK && png)
    st = ss_image_write_png(png_path, img, exposure, &err);
  if (st == SS_OK && variance)
    st = ss_image_write_exr(var_path, var, &err);
  ss_image_destroy(img);
  ss_image_destroy(var);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf render: %s\n", err.message);
    return 1;
  }
  if (!quiet || partial) {
    printf("wrote %s%s%s%s%s\n", path, png ? " and " : "", png ? png_path : "",
           variance ? ", variance " : "", variance ? var_path : "");
  }
  return 0;
}

static void print_stats(const ss_scene *scene, const ss_render_stats *s, int w, int h) {
  double secs = s->seconds > 0.0 ? s->seconds : 1e-9;
  printf("%s: %d x %d, %u spp (min over pixels), %.2f s on %d thread%s, %.3g samples/s, %.3g "
         "rays/s, %.3g scattering events/s\n",
         scene->integrator.name, w, h, s->min_spp, s->seconds, s->threads,
         s->threads == 1 ? "" : "s", s->samples / secs,
         (s->work.camera_rays + s->work.extension_rays + s->work.shadow_rays) / secs,
         s->work.scatter_events / secs);
  printf("NaN/Inf samples dropped: %llu%s\n", (unsigned long long)s->nonfinite,
         s->stopped_by_time ? " (stopped by the time limit)" : "");
  ss_table_cache_stats t;
  ss_subsurface_table_stats(scene->subsurface, &t);
  if (t.builds + t.loads) {
    printf("BSSRDF tables: %u built, %u read from the cache, %u cache files replaced\n", t.builds,
           t.loads, t.rejected);
  }
  if (t.write_failures) {
    fprintf(stderr, "subsurf render: table cache not written: %s\n", t.last_failure);
  }
}

typedef struct {
  const char *path; /* NULL: no checkpoints */
  ss_checkpoint_key key;
  int failed;
} checkpointer;

static void save_checkpoint(void *ctx, const ss_film *film) {
  checkpointer *c = ctx;
  ss_error err;
  if (ss_checkpoint_write(c->path, &c->key, film, &err) != SS_OK && !c->failed) {
    fprintf(stderr, "subsurf render: %s (the render goes on)\n", err.message);
    c->failed = 1;
  }
}

/* --checkpoint and --resume (the file saved to: --checkpoint, else the
 * --resume file itself; checked by plan_outputs): the key and the film to
 * continue. Returns 0, or 2 after printing why. */
static int setup_checkpoint(const options *o, const ss_scene *scene, ss_render_options *ro,
                            checkpointer *c) {
  memset(c, 0, sizeof *c);
  c->path = o->checkpoint ? o->checkpoint : o->resume;
  if (!c->path) {
    return 0;
  }
  ss_error err;
  if (ss_checkpoint_key_init(&c->key, o->scene, scene, ro, &err) != SS_OK) {
    fprintf(stderr, "subsurf render: %s\n", err.message);
    return 2;
  }
  if (o->resume && ss_checkpoint_read(o->resume, &c->key, &ro->resume, &err) != SS_OK) {
    fprintf(stderr, "subsurf render: --resume: %s\n", err.message);
    return 2;
  }
  ro->checkpoint = save_checkpoint;
  ro->checkpoint_ctx = c;
  ro->checkpoint_interval = o->checkpoint_interval;
  return 0;
}

/* The cache of the integrator, when it writes one (NULL: none). */
static const char *integrator_cache(const ss_scene *scene) {
  if (!scene->integrator.cache[0]) {
    return NULL;
  }
  if (!strcmp(scene->integrator.name, "fem")) {
    return ss_scene_integrator_option(scene, "cache_read_only", 0.0) == 1.0
               ? NULL
               : scene->integrator.cache;
  }
  return !strcmp(scene->integrator.name, "hierarchical") ? scene->integrator.cache : NULL;
}

/* Every file a render of a w x h window writes, checked together
 * (core/output_plan.h): the EXR with its PNG and variance image, the
 * partial ones an interrupt writes, the checkpoint and the integrator's
 * cache. Returns 0, or 2 after printing one line. */
static int plan_outputs(const options *o, const ss_scene *scene, const char *exr, int w, int h) {
  const char *label = o->output                 ? "--output"
                      : scene->render.output[0] ? "render.output"
                                                : "the default output";
  int png = scene->render.png && !o->no_png, variance = scene->render.variance || o->variance;
  uint64_t image_bytes = (uint64_t)ss_film_image_bytes(w, h);
  ss_output_plan p;
  ss_output_plan_init(&p);
  for (int partial = 0; partial < 2; ++partial) {
    const char *suffix = partial ? "-partial" : "";
    uint64_t bytes = partial ? 0 : image_bytes; /* instead of the complete image */
    char path[SS_PATH_SIZE + 32], var_suffix[32];
    derive(path, sizeof path, exr, suffix, ".exr");
    ss_output_plan_add(&p, label, path, SS_FILE_EXR, 0, bytes);
    if (png) {
      derive(path, sizeof path, exr, suffix, ".png");
      ss_output_plan_add(&p, label, path, SS_FILE_PNG, 0, bytes / 4);
    }
    if (variance) {
      snprintf(var_suffix, sizeof var_suffix, "%s-variance", suffix);
      derive(path, sizeof path, exr, var_suffix, ".exr");
      ss_output_plan_add(&p, label, path, SS_FILE_EXR, 0, bytes);
    }
  }
  if (o->checkpoint || o->resume) {
    ss_output_plan_add(&p, o->checkpoint ? "--checkpoint" : "--resume",
                       o->checkpoint ? o->checkpoint : o->resume, SS_FILE_CHECKPOINT,
                       SS_OUTPUT_CACHE, ss_checkpoint_bytes(w, h));
  }
  if (o->checkpoint && o->resume && strcmp(o->checkpoint, o->resume)) {
    ss_output_plan_add_input(&p, "--resume checkpoint", o->resume);
  }
  const char *cache = integrator_cache(scene);
  if (cache) {
    int fem = !strcmp(scene->integrator.name, "fem");
    ss_output_plan_add(&p, o->irradiance_cache ? "--irradiance-cache" : "integrator.cache", cache,
                       fem ? SS_FILE_FEM_CACHE : SS_FILE_IRRADIANCE_CACHE, SS_OUTPUT_CACHE, 0);
  }
  ss_output_plan_add_input(&p, "scene", o->scene);
  return ss_cli_check_outputs(&p, CMD);
}

/* Everything about the outputs that can be checked before rendering: the
 * EXR name, the files written (plan_outputs), the exposure and whether the
 * film and its images fit in this machine's memory. Returns 0, or 2 after
 * printing one line. */
static int check_outputs(const options *o, const ss_scene *scene, const ss_render_options *ro,
                         char *exr, size_t size) {
  if (o->output) {
    snprintf(exr, size, "%s", o->output);
  } else if (scene->render.output[0]) {
    snprintf(exr, size, "%s", scene->render.output);
  } else {
    default_output(o->scene, exr, size);
  }
  size_t n = strlen(exr);
  if (n < 5 || strcmp(exr + n - 4, ".exr")) {
    fprintf(stderr, "subsurf " CMD ": %s: render.output must name an .exr file, got '%s'\n",
            o->scene, exr);
    return 2;
  }
  double exposure = o->has_exposure ? o->exposure : scene->render.exposure;
  if (!(fabs(exposure) <= 64.0)) {
    fprintf(stderr, "subsurf " CMD ": %s: render.exposure must be in [-64, 64], got %g\n", o->scene,
            exposure);
    return 2;
  }
  int crop = ro->crop[2] > 0;
  int w = crop ? ro->crop[2] - ro->crop[0] : scene->camera.width;
  int h = crop ? ro->crop[3] - ro->crop[1] : scene->camera.height;
  if (plan_outputs(o, scene, exr, w, h) != 0) {
    return 2;
  }
  int images = 1 + (scene->render.variance || o->variance);
  /* --trimmed-mean keeps every pass's film and the combined one. */
  double need = (1 + o->passes) * ss_film_bytes(w, h) + images * ss_film_image_bytes(w, h);
  char what[SS_PATH_SIZE + 64];
  snprintf(what, sizeof what, "%s: a %d x %d film and its images", o->scene, w, h);
  if (ss_cli_check_memory(CMD, need, what, "lower camera.resolution or render a --crop") != 0) {
    return 2;
  }
  return 0;
}

/* --irradiance-cache: only for `hierarchical` (the file is checked by
 * plan_outputs). Returns 0, or 2 after printing one line. */
static int use_irradiance_cache(const options *o, ss_scene *scene) {
  if (strcmp(scene->integrator.name, "hierarchical")) {
    fprintf(stderr,
            "subsurf " CMD ": --irradiance-cache: only the hierarchical integrator uses it\n");
    return 2;
  }
  if (strlen(o->irradiance_cache) >= sizeof scene->integrator.cache) {
    fprintf(stderr, "subsurf " CMD ": --irradiance-cache: the name is longer than %zu bytes\n",
            sizeof scene->integrator.cache - 1);
    return 2;
  }
  snprintf(scene->integrator.cache, sizeof scene->integrator.cache, "%s", o->irradiance_cache);
  return 0;
}

/* After plan_outputs: a cache of the integrator's that exists but cannot
 * be used (with the fem integrator's cache_read_only, one that cannot be
 * read) is named with the reason; it is rebuilt, and rewritten unless
 * read-only. */
static void warn_unusable_cache(const ss_scene *scene) {
  const char *path = scene->integrator.cache;
  ss_error err;
  if (!path[0]) {
    return;
  }
  if (!strcmp(scene->integrator.name, "hierarchical")) {
    if (ss_hierarchical_cache_check(scene, path, &err) == SS_ERR_PARSE) {
      fprintf(stderr, "subsurf " CMD ": %s; rebuilding it\n", err.message);
    }
    return;
  }
  if (strcmp(scene->integrator.name, "fem")) {
    return;
  }
  int read_only = ss_scene_integrator_option(scene, "cache_read_only", 0.0) == 1.0;
  ss_fem_cache *c = NULL;
  ss_status st = ss_fem_cache_read(path, &c, &err);
  if (st == SS_ERR_PARSE || (read_only && st != SS_OK)) {
    fprintf(stderr, "subsurf " CMD ": warning: %s; recomputing it%s\n", err.message,
            read_only ? " (cache_read_only: not written)" : "");
  }
  ss_fem_cache_destroy(c);
}

/* A pbrt scene's warnings (what was ignored or approximated), once per job. */
static void print_warning(void *user, const char *message) {
  (void)user;
  if (ss_mpi_rank() == 0) {
    fprintf(stderr, "subsurf " CMD ": warning: %s\n", message);
  }
}

/* The scene, with the command line's overrides, and its render options;
 * NULL after printing one line (*rc is the exit code). */
static ss_scene *load(const options *o, ss_render_options *ro, int *rc) {
  ss_error err;
  ss_scene *scene = NULL;
  ss_status st = ss_scene_read(o->scene, &scene, print_warning, NULL, &err);
  if (ss_cli_interrupted()) {
    ss_scene_destroy(scene);
    *rc = ss_cli_interrupted_exit(CMD, "while loading the scene");
    return NULL;
  }
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    *rc = 2;
    return NULL;
  }
  if (o->integrator && strcmp(o->integrator, scene->integrator.name)) {
    /* the scene's cache was another integrator's */
    snprintf(scene->integrator.name, sizeof scene->integrator.name, "%s", o->integrator);
    scene->integrator.cache[0] = '\0';
  }
  if (o->irradiance_cache && use_irradiance_cache(o, scene) != 0) {
    ss_scene_destroy(scene);
    *rc = 2;
    return NULL;
  }
  ss_render_options_from_scene(scene, ro);
  if (o->spp > 0)
    ro->spp = o->spp;
  if (o->has_seed)
    ro->seed = (uint64_t)o->seed;
  if (o->has_time_limit)
    ro->time_limit = o->time_limit;
  ro->threads = o->threads;
  if (!ss_scene_emits(scene) && ss_mpi_rank() == 0) {
    fprintf(stderr,
            "subsurf " CMD ": warning: %s: nothing emits light (no light of positive radiance or "
            "power): the image will be black\n",
            o->scene);
  }
  if (o->has_crop) {
    if (o->crop[2] > scene->camera.width || o->crop[3] > scene->camera.height) {
      fprintf(stderr, "subsurf " CMD ": --crop %d,%d,%d,%d exceeds the %d x %d image\n", o->crop[0],
              o->crop[1], o->crop[2], o->crop[3], scene->camera.width, scene->camera.height);
      ss_scene_destroy(scene);
      *rc = 2;
      return NULL;
    }
    memcpy(ro->crop, o->crop, sizeof ro->crop);
  }
  const char *clash = o->has_time_limit ? "--time-limit"
                      : o->checkpoint   ? "--checkpoint"
                      : o->resume       ? "--resume"
                                        : NULL;
  if (o->passes > 0 && (clash || ro->spp % o->passes != 0)) {
    if (clash) {
      fprintf(stderr, "subsurf " CMD ": --trimmed-mean cannot be combined with %s\n", clash);
    } else {
      fprintf(stderr, "subsurf " CMD ": --trimmed-mean: %d passes must divide the spp (%d)\n",
              o->passes, ro->spp);
    }
    ss_scene_destroy(scene);
    *rc = 2;
    return NULL;
  }
  return scene;
}

/* Under mpirun (mpi_job.h): every rank must have the same scene file (main.c
 * compared the command lines), and the options that keep per-process files are refused.
 * Returns 0 or the exit code. */
static int mpi_check(options *o) {
  if (ss_mpi_size() <= 1) {
    return 0;
  }
  int rc = ss_mpi_check_same_file(CMD, o->scene);
  const char *alone = o->checkpoint         ? "--checkpoint"
                      : o->resume           ? "--resume"
                      : o->passes > 0       ? "--trimmed-mean"
                      : o->irradiance_cache ? "--irradiance-cache"
                                            : NULL;
  if (rc == 0 && alone) {
    if (ss_mpi_rank() == 0) {
      fprintf(stderr, "subsurf " CMD ": %s is not available with %d MPI ranks\n", alone,
              ss_mpi_size());
    }
    rc = 2;
  }
  o->quiet |= ss_mpi_rank() != 0;
  return rc;
}

int ss_cmd_render(int argc, char **argv) {
  options o;
  int rc = parse_args(argc, argv, &o);
  if (rc >= 0) {
    return rc;
  }
  if ((rc = mpi_check(&o)) != 0) {
    return rc;
  }
  ss_render_options ro;
  ss_cli_install_interrupt_handler(); /* loading a big scene takes time too */
  ss_scene *scene = load(&o, &ro, &rc);
  if ((rc = ss_mpi_all_ok(scene ? 0 : rc)) != 0) {
    ss_scene_destroy(scene);
    return rc;
  }
  ro.cancel = ss_cli_install_interrupt_handler();
  char exr[SS_PATH_SIZE];
  checkpointer ck;
  if (ss_mpi_rank() == 0) {
    rc = check_outputs(&o, scene, &ro, exr, sizeof exr);
    if (rc == 0) {
      warn_unusable_cache(scene);
      rc = setup_checkpoint(&o, scene, &ro, &ck);
    }
  }
  if ((rc = ss_mpi_all_ok(rc)) != 0) {
    ss_scene_destroy(scene);
    return rc;
  }
  ro.tile_stride = ss_mpi_size();
  ro.tile_offset = ss_mpi_rank();
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error err;
  ss_progress bar;
  ss_progress_begin(&bar, "render", 0, !o.quiet, ro.time_limit);
  ro.progress = ss_progress_report;
  ro.progress_ctx = &bar;
  ss_status st = o.passes > 0 ? ss_render_trimmed(scene, &ro, o.passes, o.trim, &film, &stats, &err)
                              : ss_render(scene, &ro, &film, &stats, &err);
  ss_progress_end(&bar, bar.done);
  if (st != SS_OK && st != SS_ERR_INTERRUPTED) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    ss_scene_destroy(scene);
    return st == SS_ERR_INVALID_ARGUMENT ? 2 : 1;
  }
  /* Rank 0 collects the other ranks' tiles; a rank interrupted anywhere
   * makes the image partial. */
  int partial = st == SS_ERR_INTERRUPTED;
  if (ss_mpi_size() > 1) {
    if (ss_mpi_gather_film(CMD, film, &stats, ss_mpi_timeout() + 2.0 * stats.seconds) != 0) {
      ss_film_destroy(film);
      ss_scene_destroy(scene);
      return 1;
    }
    partial = ss_mpi_any(partial);
    if (ss_mpi_rank() != 0) {
      ss_film_destroy(film);
      ss_scene_destroy(scene);
      return partial ? 130 : 0;
    }
  }
  double exposure = o.has_exposure ? o.exposure : scene->render.exposure;
  rc = write_outputs(film, exr, partial, scene->render.png && !o.no_png,
                     scene->render.variance || o.variance, exposure, o.quiet);
  if (!o.quiet) {
    print_stats(scene, &stats, ss_film_width(film), ss_film_height(film));
  }
  if (ck.path && ss_checkpoint_write(ck.path, &ck.key, film, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    rc = 1;
  } else if (ck.path && partial) {
    fprintf(stderr, "subsurf " CMD ": saved %s; continue with --resume %s\n", ck.path, ck.path);
  }
  uint64_t clamped = ss_film_clamped_count(film);
  if (clamped > 0) {
    fprintf(stderr,
            "subsurf " CMD ": warning: %llu pixel values exceed the float range of the images and "
            "were written as +-3.4e38\n",
            (unsigned long long)clamped);
  }
  ss_cli_warn_majorant(stderr, CMD, scene);
  if (partial && rc == 0) {
    fprintf(stderr, "subsurf " CMD ": interrupted; wrote the partial image\n");
    rc = 130;
  }
  ss_film_destroy(film);
  ss_scene_destroy(scene);
  return rc;
}
