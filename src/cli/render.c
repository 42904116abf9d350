/* `subsurf render`: renders a JSON scene to EXR (linear) and PNG
 * (tonemapped). Exit codes: 0 done, 1 run-time failure (e.g. cannot write),
 * 2 bad input, 130 interrupted (the image so far is written as
 * <name>-partial.exr/.png). */
#include "cli/commands.h"
#include "cli/signals.h"

#include "subsurf/checkpoint.h"
#include "subsurf/image_io.h"
#include "subsurf/integrator.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void usage(FILE *out) {
  char names[256];
  ss_integrator_names(names, sizeof names);
  fprintf(out,
          "usage: subsurf render SCENE.json [options]\n\n"
          "Renders a scene (docs/scene-format.md) and writes an EXR and a PNG.\n\n"
          "options:\n"
          "  -o, --output FILE.exr  output image (default: the scene's render.output, else\n"
          "                         SCENE's base name + .exr in the current directory);\n"
          "                         the PNG gets the same base name\n"
          "  --spp N                samples per pixel (overrides render.spp)\n"
          "  --threads N            worker threads (default: all cores)\n"
          "  --seed N               random seed (default: render.seed, else 0)\n"
          "  --integrator NAME      %s (overrides integrator.type)\n"
          "  --crop x0,y0,x1,y1     render only this pixel window (x1, y1 exclusive)\n"
          "  --time-limit S         stop after S seconds and write what is done\n"
          "  --exposure E           PNG exposure in stops (default: render.exposure, else 0)\n"
          "  --variance             also write the per-pixel variance as NAME-variance.exr\n"
          "  --no-png               write only the EXR\n"
          "  --quiet                no progress bar and no statistics\n"
          "  --checkpoint FILE      save the film to FILE between passes (every\n"
          "                         --checkpoint-interval S seconds, default 60), on Ctrl-C\n"
          "                         and at the end\n"
          "  --resume FILE          continue the render saved in FILE (same scene file,\n"
          "                         integrator, spp, seed and crop) to the image an\n"
          "                         uninterrupted render gives; saves to FILE again unless\n"
          "                         --checkpoint names another\n"
          "  -h, --help             this help\n\n"
          "Ctrl-C stops the render, writes NAME-partial.exr/.png and exits with 130.\n",
          names);
}

static int bad(const char *fmt, const char *arg) {
  fprintf(stderr, "subsurf render: ");
  fprintf(stderr, fmt, arg);
  fprintf(stderr, " (see subsurf render --help)\n");
  return 2;
}

static int parse_long(const char *s, long lo, long hi, long *out) {
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || end == s || *end || v < lo || v > hi) {
    return 0;
  }
  *out = v;
  return 1;
}

static int parse_double(const char *s, double lo, double hi, double *out) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || end == s || *end || !(v >= lo && v <= hi)) {
    return 0;
  }
  *out = v;
  return 1;
}

static int parse_crop(const char *s, int crop[4]) {
  char extra;
  if (sscanf(s, "%d,%d,%d,%d%c", &crop[0], &crop[1], &crop[2], &crop[3], &extra) != 4) {
    return 0;
  }
  return crop[0] >= 0 && crop[1] >= 0 && crop[0] < crop[2] && crop[1] < crop[3];
}

typedef struct {
  const char *scene;
  const char *output;
  long spp, threads, seed;
  const char *integrator;
  int crop[4], has_crop;
  double time_limit, exposure;
  int has_time_limit, has_exposure, quiet, variance, no_png;
  const char *checkpoint, *resume;
  double checkpoint_interval;
} options;

/* Returns -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, options *o) {
  memset(o, 0, sizeof *o);
  o->spp = o->seed = -1;
  o->checkpoint_interval = 60.0;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      usage(stdout);
      return 0;
    }
    if (!strcmp(a, "--quiet")) {
      o->quiet = 1;
      continue;
    }
    if (!strcmp(a, "--variance")) {
      o->variance = 1;
      continue;
    }
    if (!strcmp(a, "--no-png")) {
      o->no_png = 1;
      continue;
    }
    if (a[0] != '-') {
      if (o->scene) {
        return bad("more than one scene file ('%s')", a);
      }
      o->scene = a;
      continue;
    }
    if (i + 1 >= argc) {
      return bad("option %s needs a value", a);
    }
    const char *v = argv[++i];
    if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
      size_t n = strlen(v);
      if (n < 5 || strcmp(v + n - 4, ".exr")) {
        return bad("--output must name an .exr file, got '%s'", v);
      }
      o->output = v;
    } else if (!strcmp(a, "--spp")) {
      if (!parse_long(v, 1, 1L << 30, &o->spp)) {
        return bad("--spp expects an integer >= 1, got '%s'", v);
      }
    } else if (!strcmp(a, "--threads")) {
      if (!parse_long(v, 1, 4096, &o->threads)) {
        return bad("--threads expects an integer in [1, 4096], got '%s'", v);
      }
    } else if (!strcmp(a, "--seed")) {
      if (!parse_long(v, 0, LONG_MAX, &o->seed)) {
        return bad("--seed expects an integer >= 0, got '%s'", v);
      }
    } else if (!strcmp(a, "--integrator")) {
      if (!ss_integrator_find(v)) {
        return bad("--integrator: unknown integrator '%s'", v);
      }
      o->integrator = v;
    } else if (!strcmp(a, "--crop")) {
      if (!parse_crop(v, o->crop)) {
        return bad("--crop expects x0,y0,x1,y1 with x0 < x1, y0 < y1, got '%s'", v);
      }
      o->has_crop = 1;
    } else if (!strcmp(a, "--time-limit")) {
      if (!parse_double(v, 1e-3, 1e9, &o->time_limit)) {
        return bad("--time-limit expects seconds > 0, got '%s'", v);
      }
      o->has_time_limit = 1;
    } else if (!strcmp(a, "--exposure")) {
      if (!parse_double(v, -64.0, 64.0, &o->exposure)) {
        return bad("--exposure expects stops in [-64, 64], got '%s'", v);
      }
      o->has_exposure = 1;
    } else if (!strcmp(a, "--checkpoint")) {
      o->checkpoint = v;
    } else if (!strcmp(a, "--resume")) {
      o->resume = v;
    } else if (!strcmp(a, "--checkpoint-interval")) {
      if (!parse_double(v, 0.0, 1e9, &o->checkpoint_interval)) {
        return bad("--checkpoint-interval expects seconds >= 0, got '%s'", v);
      }
    } else {
      return bad("unknown option '%s'", a);
    }
  }
  if (!o->scene) {
    return bad("%s", "missing the scene file");
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
  if (st == SS_OK) st = ss_image_write_exr(path, img, &err);
  if (st == SS_OK && png) st = ss_image_write_png(png_path, img, exposure, &err);
  if (st == SS_OK && variance) st = ss_image_write_exr(var_path, var, &err);
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
  printf("%s: %d x %d, %u spp (min over pixels), %.2f s, %.3g samples/s, %.3g rays/s, "
         "%.3g scattering events/s\n",
         scene->integrator.name, w, h, s->min_spp, s->seconds, s->samples / secs,
         (s->work.camera_rays + s->work.extension_rays + s->work.shadow_rays) / secs,
         s->work.scatter_events / secs);
  printf("NaN/Inf samples dropped: %llu%s\n", (unsigned long long)s->nonfinite,
         s->stopped_by_time ? " (stopped by the time limit)" : "");
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

/* --checkpoint and --resume: the key, a writable path and the film to
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
  char probe[SS_PATH_SIZE + 32];
  snprintf(probe, sizeof probe, "%s.tmp%ld", c->path, (long)getpid());
  FILE *f = fopen(probe, "wb");
  if (!f) {
    fprintf(stderr, "subsurf render: --checkpoint: cannot write next to '%s': %s\n", c->path,
            strerror(errno));
    return 2;
  }
  fclose(f);
  remove(probe);
  if (o->resume && ss_checkpoint_read(o->resume, &c->key, &ro->resume, &err) != SS_OK) {
    fprintf(stderr, "subsurf render: --resume: %s\n", err.message);
    return 2;
  }
  ro->checkpoint = save_checkpoint;
  ro->checkpoint_ctx = c;
  ro->checkpoint_interval = o->checkpoint_interval;
  return 0;
}

int ss_cmd_render(int argc, char **argv) {
  options o;
  int rc = parse_args(argc, argv, &o);
  if (rc >= 0) {
    return rc;
  }
  ss_error err;
  ss_scene *scene;
  if (ss_scene_read_json(o.scene, &scene, &err) != SS_OK) {
    fprintf(stderr, "subsurf render: %s\n", err.message);
    return 2;
  }
  if (o.integrator) {
    snprintf(scene->integrator.name, sizeof scene->integrator.name, "%s", o.integrator);
  }
  ss_render_options ro;
  ss_render_options_from_scene(scene, &ro);
  if (o.spp > 0) ro.spp = (int)o.spp;
  if (o.seed >= 0) ro.seed = (uint64_t)o.seed;
  if (o.has_time_limit) ro.time_limit = o.time_limit;
  ro.threads = (int)o.threads;
  ro.progress = !o.quiet;
  if (o.has_crop) {
    if (o.crop[2] > scene->camera.width || o.crop[3] > scene->camera.height) {
      fprintf(stderr, "subsurf render: --crop %d,%d,%d,%d exceeds the %d x %d image\n", o.crop[0],
              o.crop[1], o.crop[2], o.crop[3], scene->camera.width, scene->camera.height);
      ss_scene_destroy(scene);
      return 2;
    }
    memcpy(ro.crop, o.crop, sizeof ro.crop);
  }
  char exr[SS_PATH_SIZE];
  if (o.output) {
    snprintf(exr, sizeof exr, "%s", o.output);
  } else if (scene->render.output[0]) {
    snprintf(exr, sizeof exr, "%s", scene->render.output);
  } else {
    default_output(o.scene, exr, sizeof exr);
  }
  size_t n = strlen(exr);
  if (n < 5 || strcmp(exr + n - 4, ".exr")) {
    fprintf(stderr, "subsurf render: %s: render.output must name an .exr file, got '%s'\n",
            o.scene, exr);
    ss_scene_destroy(scene);
    return 2;
  }
  checkpointer ck;
  if (setup_checkpoint(&o, scene, &ro, &ck) != 0) {
    ss_scene_destroy(scene);
    return 2;
  }
  ro.cancel = ss_cli_install_interrupt_handler();
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_status st = ss_render(scene, &ro, &film, &stats, &err);
  if (st != SS_OK && st != SS_ERR_INTERRUPTED) {
    fprintf(stderr, "subsurf render: %s\n", err.message);
    ss_scene_destroy(scene);
    return st == SS_ERR_INVALID_ARGUMENT ? 2 : 1;
  }
  int partial = st == SS_ERR_INTERRUPTED;
  double exposure = o.has_exposure ? o.exposure : scene->render.exposure;
  rc = write_outputs(film, exr, partial, scene->render.png && !o.no_png,
                     scene->render.variance || o.variance, exposure, o.quiet);
  if (!o.quiet) {
    print_stats(scene, &stats, ss_film_width(film), ss_film_height(film));
  }
  if (ck.path && ss_checkpoint_write(ck.path, &ck.key, film, &err) != SS_OK) {
    fprintf(stderr, "subsurf render: %s\n", err.message);
    rc = 1;
  } else if (ck.path && partial) {
    fprintf(stderr, "subsurf render: saved %s; continue with --resume %s\n", ck.path, ck.path);
  }
  if (partial && rc == 0) {
    fprintf(stderr, "subsurf render: interrupted; wrote the partial image\n");
    rc = 130;
  }
  ss_film_destroy(film);
  ss_scene_destroy(scene);
  return rc;
}
