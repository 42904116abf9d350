/* `subsurf compare`: renders one scene with several methods (integrators,
 * or BSSRDF models with options, method.h) at the same budget and measures
 * each image against a reference over the translucent objects' pixels.
 * Exit codes: 0 done, 1 run-time failure, 2 bad input, 130 interrupted. */
#include "cli/compare_scene.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/mpi_job.h"
#include "cli/signals.h"

#include "subsurf/error_map.h"
#include "subsurf/image_io.h"
#include "subsurf/render.h"
#include "subsurf/scene_io.h"
#include "subsurf/threads.h"
#include "subsurf/translucent_mask.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define CMD "compare"

static void usage(FILE *out) {
  fprintf(out,
          "usage: subsurf compare SCENE.json|SCENE.pbrt --methods LIST (--spp N | --time S)\n"
          "       [options]\n\n"
          "Renders the scene with each method and compares every image with a reference over\n"
          "the pixels where the camera first sees a translucent object.\n\n"
          "A method is an integrator (volpath, path, bssrdf, ...) or a BSSRDF model rendered\n"
          "by the bssrdf integrator in every translucent material, with options after ':' as\n"
          "NAME=VALUE: the model's, or the integrator's (max_depth, rr_depth), e.g.\n"
          "--methods volpath:max_depth=64,dipole,pbd:beam_samples=50:max_depth=8.\n\n"
          "options:\n"
          "  --methods LIST         comma-separated methods (at most %d)\n"
          "  --spp N                samples per pixel of every method\n"
          "  --time S               wall-time budget of every method, seconds (1e-3..1e9)\n"
          "  --reference FILE.exr   the reference image (same size as the scene's camera);\n"
          "                         without it a volpath reference is rendered into\n"
          "                         DIR/reference.exr and reused while its settings hold\n"
          "  --reference-spp N      samples per pixel of that reference (default 16 x --spp,\n"
          "                         or 256 with --time)\n"
          "  --reference-time S     or its time budget in seconds\n"
          "  --reference-rel-error E  or passes of doubling spp until its estimated relative\n"
          "                         standard error over the translucent pixels is below E\n"
          "                         (1e-4..1): sqrt(mean variance / (value + 0.01)^2)\n"
          "  -o, --output DIR       output folder (default compare-out; created if missing)\n"
          "  --threads N            worker threads (default: all cores)\n"
          "  --seed N               random seed of the methods (default: render.seed)\n"
          "  --quiet                no progress lines\n"
          "  -h, --help             this help\n\n"
          "Writes DIR/results.json and DIR/results.csv (per method and channel: relMSE =\n"
          "mean((v - ref)^2 / (ref + 0.01)^2) as pbrt-v4's imgtool, RMSE, mean radiance and\n"
          "its ratio to the reference; wall time (with the integrator's preparation, made\n"
          "once for all passes: `prepares`), samples; relMSE after each pass of\n"
          "doubling spp, the time the log-log fit of relMSE over time needs to reach\n"
          "volpath's relMSE, the relMSE it converges to), DIR/METHOD.exr/.png and\n"
          "DIR/METHOD-error.png (relative error |v - ref| / (ref + 0.01): blue 0 .. red 1),\n"
          "the plots DIR/convergence.svg, DIR/mean-ratio-{r,g,b}.svg, DIR/error-colorbar.svg,\n"
          "and last DIR/index.html, a report that works offline from the folder.\n\n"
          "mpirun -np N subsurf compare ... renders every pass's tiles on N processes; with\n"
          "--spp the images are the same bytes as one process's (docs/render.md).\n",
          SS_COMPARE_MAX_METHODS);
}

static int parse_option(void *ctx, const char *name, const char *v) {
  ss_compare_options *o = ctx;
  int rc = 0;
  if (!strcmp(name, "methods")) {
    o->methods = v;
  } else if (!strcmp(name, "spp")) {
    rc = ss_parse_int(CMD, name, v, 1, 1 << 24, &o->spp);
  } else if (!strcmp(name, "time")) {
    rc = ss_parse_double_in(CMD, name, v, 1e-3, 1e9, &o->time);
  } else if (!strcmp(name, "reference")) {
    o->reference = v;
  } else if (!strcmp(name, "reference-spp")) {
    rc = ss_parse_int(CMD, name, v, 1, 1 << 24, &o->ref_spp);
  } else if (!strcmp(name, "reference-time")) {
    rc = ss_parse_double_in(CMD, name, v, 1e-3, 1e9, &o->ref_time);
  } else if (!strcmp(name, "reference-rel-error")) {
    rc = ss_parse_double_in(CMD, name, v, 1e-4, 1.0, &o->ref_rel_error);
  } else if (!strcmp(name, "o") || !strcmp(name, "output")) {
    o->dir = v;
  } else if (!strcmp(name, "threads")) {
    rc = ss_parse_int(CMD, name, v, 1, SS_THREADS_MAX, &o->threads);
  } else if (!strcmp(name, "seed")) {
    rc = ss_parse_u64(CMD, name, v, &o->seed);
    o->has_seed = 1;
  } else {
    return 0;
  }
  return rc == 0 ? 1 : -1;
}

static int parse_flag(void *ctx, const char *name) {
  ss_compare_options *o = ctx;
  if (!strcmp(name, "quiet")) {
    o->quiet = 1;
    return 1;
  }
  return 0;
}

static int parse_scene(void *ctx, const char *arg) {
  ss_compare_options *o = ctx;
  if (o->scene) {
    return 0;
  }
  o->scene = arg;
  return 1;
}

/* Splits --methods into o->results; 0, or 2 after printing why. */
static int parse_methods(ss_compare_options *o) {
  if (!ss_cli_name_list_ok(o->methods, ",")) {
    fprintf(stderr, "subsurf " CMD ": --methods: expected names separated by ',', got '%s'\n",
            o->methods);
    return 2;
  }
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", o->methods);
  for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    if (o->num_methods == SS_COMPARE_MAX_METHODS) {
      fprintf(stderr, "subsurf " CMD ": --methods: at most %d methods\n", SS_COMPARE_MAX_METHODS);
      return 2;
    }
    ss_compare_result *r = &o->results[o->num_methods];
    ss_error err;
    if (ss_method_parse(t, &r->method, &err) != SS_OK) {
      fprintf(stderr, "subsurf " CMD ": --methods: %s\n", err.message);
      return 2;
    }
    ss_method_file_name(&r->method, r->file, sizeof r->file);
    for (int k = 0; k < o->num_methods; ++k) {
      if (!strcmp(o->results[k].file, r->file)) {
        fprintf(stderr, "subsurf " CMD ": --methods: '%s' is given twice\n", t);
        return 2;
      }
    }
    ++o->num_methods;
  }
  return 0;
}

/* Returns -1 to go on, else the exit code. */
static int parse_args(int argc, char **argv, ss_compare_options *o) {
  memset(o, 0, sizeof *o);
  o->dir = "compare-out";
  const ss_cli_spec spec = {parse_flag, parse_option, parse_scene, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  const char *missing = !o->scene ? "the scene file" : !o->methods ? "--methods" : NULL;
  if (missing) {
    fprintf(stderr, "subsurf " CMD ": missing %s (see subsurf compare --help)\n", missing);
    return 2;
  }
  int ref_budgets = (o->ref_spp > 0) + (o->ref_time > 0.0) + (o->ref_rel_error > 0.0);
  if ((o->spp > 0) == (o->time > 0.0) || ref_budgets > 1) {
    fprintf(stderr, "subsurf " CMD ": expected exactly one of --spp and --time, and at most one "
                    "of --reference-spp, --reference-time and --reference-rel-error\n");
    return 2;
  }
  if (o->reference && ref_budgets > 0) {
    fprintf(stderr, "subsurf " CMD ": --reference-spp/-time/-rel-error describe a reference to "
                    "render; they do not go with --reference\n");
    return 2;
  }
  if (ref_budgets == 0) {
    o->ref_spp = o->spp > 0 ? (o->spp <= (1 << 24) / 16 ? 16 * o->spp : 1 << 24) : 256;
  }
  return parse_methods(o) ? 2 : -1;
}

/* Creates the output folder when missing and checks every file the run
 * writes in it; 0, or 2 after printing why (and nothing left behind). */
static int prepare_dir(const ss_compare_options *o, const ss_scene *scene) {
  int made = mkdir(o->dir, 0777) == 0;
  if (!made && errno != EEXIST) {
    fprintf(stderr, "subsurf " CMD ": --output: cannot create folder '%s': %s\n", o->dir,
            strerror(errno));
    return 2;
  }
  int rc = ss_compare_check_outputs(o, scene->camera.width, scene->camera.height);
  if (rc != 0 && made) {
    rmdir(o->dir);
  }
  return rc;
}

/* A pbrt scene's warnings, printed on the first of compare's loads only. */
static void print_warning(void *user, const char *message) {
  (void)user;
  fprintf(stderr, "subsurf " CMD ": warning: %s\n", message);
}

ss_scene *ss_compare_load_scene(const char *path, ss_error *err) {
  static int loaded;
  ss_scene *scene = NULL;
  if (ss_scene_read(path, &scene, loaded++ ? NULL : print_warning, NULL, err) != SS_OK) {
    ss_scene_destroy(scene);
    return NULL;
  }
  return scene;
}

void ss_compare_render_options(const ss_scene *scene, const ss_compare_options *o,
                               ss_render_options *ro) {
  ss_render_options_from_scene(scene, ro);
  ro->threads = o->threads;
  ro->cancel = ss_cli_install_interrupt_handler();
  ro->tile_stride = ss_mpi_size();
  ro->tile_offset = ss_mpi_rank();
  if (o->has_seed) {
    ro->seed = o->seed;
  }
}

ss_status ss_compare_agree(ss_status st, ss_error *err) {
  if (ss_mpi_size() <= 1) {
    return st;
  }
  int interrupted = ss_mpi_any(st == SS_ERR_INTERRUPTED);
  if (ss_mpi_any(st != SS_OK) && st == SS_OK) {
    st = interrupted ? SS_ERR_INTERRUPTED
                     : ss_error_set(err, SS_ERR_IO, "another MPI rank failed (its message above)");
  }
  return st;
}

ss_status ss_compare_pass_end(ss_status st, ss_film *film, ss_render_stats *stats, ss_error *err) {
  if (ss_mpi_size() <= 1 || (st = ss_compare_agree(st, err)) != SS_OK) {
    return st;
  }
  stats->stopped_by_time = ss_mpi_any(stats->stopped_by_time);
  if (ss_mpi_gather_film(CMD, film, stats, ss_mpi_timeout() + 2.0 * stats->seconds) != 0) {
    return ss_error_set(err, SS_ERR_IO, "the ranks could not exchange their tiles");
  }
  return SS_OK;
}

/* Appends the error of `film` against `ref` as the result's next pass
 * (rank 0 alone holds the whole film: the others only count the pass). */
static ss_status record_pass(const ss_film *film, const ss_image *ref, const ss_image *mask,
                             ss_compare_result *r, ss_error *err) {
  if (ss_mpi_rank() != 0) {
    r->num_passes++;
    return SS_OK;
  }
  ss_image *img = ss_film_image(film);
  if (!img) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for an image");
  }
  ss_status st = ss_image_error_compute(img, ref, mask, &r->error, err);
  ss_image_destroy(img);
  ss_compare_pass *p = &r->passes[r->num_passes++];
  p->spp = r->spp;
  p->seconds = r->seconds;
  p->rel_mse = r->error.rel_mse;
  return st;
}

/* The passes of render_passes with ro->prepared set. */
static ss_status render_passes_prepared(const ss_scene *scene, const ss_compare_options *o,
                                        ss_render_options *ro, const ss_image *ref,
                                        const ss_image *mask, ss_compare_result *r, ss_film **film,
                                        ss_error *err) {
  for (unsigned next = 1;; next *= 2) {
    int last = r->num_passes == SS_COMPARE_MAX_PASSES - 1;
    if (o->time > 0.0) {
      ro->spp = last ? 1 << 30 : (int)next;
      ro->time_limit = o->time - r->seconds > 1e-3 ? o->time - r->seconds : 1e-3;
    } else {
      ro->spp = next < (unsigned)o->spp ? (int)next : o->spp;
    }
    ro->resume = *film;
    *film = NULL;
    ss_render_stats stats;
    ss_status st = ss_render(scene, ro, film, &stats, err);
    st = ss_compare_pass_end(st, *film, &stats, err);
    if (st != SS_OK) {
      return st;
    }
    r->seconds += stats.seconds + stats.prepare_seconds;
    r->prepares += stats.prepares;
    r->spp = stats.min_spp;
    r->samples += stats.samples;
    if ((st = record_pass(*film, ref, mask, r, err)) != SS_OK) {
      return st;
    }
    if (o->time > 0.0 ? stats.stopped_by_time || last : ro->spp >= o->spp) {
      return SS_OK;
    }
  }
}

/* Renders `scene` in passes of doubling spp (1, 2, 4, ...) up to `spp`, or
 * until `time` seconds, each continuing the film of the one before, and
 * records each pass's error against `ref`. The integrator is prepared once
 * for all passes; its preparation counts in the method's seconds. */
static ss_status render_passes(const ss_scene *scene, const ss_compare_options *o,
                               const ss_image *ref, const ss_image *mask, ss_compare_result *r,
                               ss_film **film, ss_error *err) {
  ss_render_options ro;
  ss_compare_render_options(scene, o, &ro);
  *film = NULL;
  ss_render_prepared *prepared = NULL;
  ss_status st = ss_compare_agree(ss_render_prepare(scene, &prepared, err), err);
  if (st != SS_OK) {
    ss_render_prepared_destroy(prepared);
    return st;
  }
  ro.prepared = prepared;
  r->prepares = ss_render_prepared_count(prepared);
  r->seconds = ss_render_prepared_seconds(prepared);
  st = render_passes_prepared(scene, o, &ro, ref, mask, r, film, err);
  ss_render_prepared_destroy(prepared);
  return st;
}
ss_status ss_compare_write_images(const char *dir, const char *name, const ss_image *img,
                                  double exposure, ss_error *err) {
  char path[SS_PATH_SIZE + 300];
  snprintf(path, sizeof path, "%s/%s.exr", dir, name);
  ss_status st = ss_image_write_exr(path, img, err);
  if (st == SS_OK) {
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    st = ss_image_write_png(path, img, exposure, err);
  }
  return st;
}

/* Writes DIR/NAME-error.png, the false-colour relative error (error_map.h). */
static ss_status write_error_map(const char *dir, const char *name, const ss_image *img,
                                 const ss_image *ref, const ss_image *mask, ss_error *err) {
  ss_image *map = ss_error_map(img, ref, mask);
  if (!map) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for an error map");
  }
  char path[SS_PATH_SIZE + 300];
  snprintf(path, sizeof path, "%s/%s-error.png", dir, name);
  ss_status st = ss_image_write_png(path, map, 0.0, err);
  ss_image_destroy(map);
  return st;
}

/* Renders method r and writes its images. */
static ss_status run_method(const ss_compare_options *o, const ss_image *ref, const ss_image *mask,
                            ss_compare_result *r, ss_error *err) {
  ss_scene *scene = ss_compare_load_scene(o->scene, err);
  if (!scene) {
    return SS_ERR_PARSE;
  }
  ss_film *film = NULL;
  ss_status st = ss_method_apply(&r->method, scene, err);
  if (st == SS_OK) {
    st = render_passes(scene, o, ref, mask, r, &film, err);
  }
  if (ss_mpi_rank() != 0) {
    ss_film_destroy(film); /* rank 0 writes */
    ss_scene_destroy(scene);
    return st;
  }
  ss_image *img = st == SS_OK ? ss_film_image(film) : NULL;
  if (st == SS_OK && !img) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for an image");
  }
  if (st == SS_OK) {
    st = ss_compare_write_images(o->dir, r->file, img, scene->render.exposure, err);
  }
  if (st == SS_OK) {
    st = write_error_map(o->dir, r->file, img, ref, mask, err);
  }
  if (st == SS_OK && !o->quiet) {
    printf("%-24s %8.3f s %6u spp  relMSE %.4g\n", r->method.text, r->seconds, r->spp,
           r->error.rel_mse);
  }
  ss_image_destroy(img);
  ss_film_destroy(film);
  ss_scene_destroy(scene);
  return st;
}

/* Checks the scene, the reference and the folder before any work; the exit
 * code (-1: go on). */
static int prepare(const ss_compare_options *o, ss_scene **scene, ss_image **ref, ss_image **mask) {
  ss_error err;
  /* Under mpirun every rank must read the same bytes. */
  if (ss_mpi_check_same_file(CMD, o->scene) != 0 ||
      (o->reference && ss_mpi_check_same_file(CMD, o->reference) != 0)) {
    return 2;
  }
  if (!(*scene = ss_compare_load_scene(o->scene, &err))) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    return 2;
  }
  if (o->reference && !(*ref = ss_compare_read_reference(o, *scene))) {
    return 2;
  }
  if (ss_translucent_mask(*scene, mask, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    return 1;
  }
  for (int i = 0; i < o->num_methods; ++i) {
    if (ss_method_apply(&o->results[i].method, *scene, &err) != SS_OK) {
      fprintf(stderr, "subsurf " CMD ": --methods: %s: %s\n", o->results[i].method.text,
              err.message);
      return 2;
    }
  }
  size_t count = 0, n = (size_t)(*mask)->width * (size_t)(*mask)->height;
  for (size_t i = 0; i < n; ++i) {
    count += (*mask)->data[i] > 0.5f;
  }
  if (count == 0) {
    fprintf(stderr, "subsurf " CMD ": %s: the camera sees no translucent object to compare\n",
            o->scene);
    return 2;
  }
  return ss_mpi_rank() == 0 && prepare_dir(o, *scene) ? 2 : -1;
}

static int finish(int rc, ss_scene *scene, ss_image *ref, ss_image *mask) {
  ss_scene_destroy(scene);
  ss_image_destroy(ref);
  ss_image_destroy(mask);
  return rc;
}

static int fail(ss_status st, const ss_error *err) {
  if (st == SS_ERR_INTERRUPTED) {
    return ss_mpi_rank() == 0 ? ss_cli_interrupted_exit(CMD, "before the report was written") : 130;
  }
  fprintf(stderr, "subsurf " CMD ": %s\n", err->message);
  return st == SS_ERR_INVALID_ARGUMENT || st == SS_ERR_PARSE ? 2 : 1;
}

int ss_cmd_compare_scene(int argc, char **argv) {
  static ss_compare_options o;
  int rc = parse_args(argc, argv, &o);
  if (rc >= 0) {
    return rc;
  }
  ss_scene *scene = NULL;
  ss_image *ref = NULL, *mask = NULL;
  ss_cli_install_interrupt_handler();
  o.quiet |= ss_mpi_rank() != 0;
  rc = prepare(&o, &scene, &ref, &mask);
  /* Under mpirun all ranks go on only if all can. */
  if ((rc = ss_mpi_all_ok(rc >= 0 ? rc : 0)) != 0) {
    return finish(rc, scene, ref, mask);
  }
  ss_error err;
  o.ref.file = o.reference;
  /* A report from an earlier run would present this run's files as its own. */
  char index[SS_PATH_SIZE + 32];
  snprintf(index, sizeof index, "%s/index.html", o.dir);
  if (ss_mpi_rank() == 0) {
    remove(index);
  }
  ss_status st = o.reference ? SS_OK : ss_compare_render_reference(&o, scene, mask, &ref, &err);
  if (st == SS_OK && o.reference && ss_mpi_rank() == 0) {
    /* The report shows the given reference from the folder too. */
    char path[SS_PATH_SIZE + 32];
    snprintf(path, sizeof path, "%s/reference.png", o.dir);
    st = ss_image_write_png(path, ref, scene->render.exposure, &err);
  }
  st = ss_compare_agree(st, &err);
  for (int i = 0; st == SS_OK && i < o.num_methods; ++i) {
    st = ss_compare_agree(run_method(&o, ref, mask, &o.results[i], &err), &err);
  }
  if (st != SS_OK || ss_mpi_rank() != 0) {
    return finish(st != SS_OK ? fail(st, &err) : 0, scene, ref, mask);
  }
  rc = ss_compare_write_results(&o);
  if (rc == 0 && !o.quiet) {
    printf("wrote %s/results.json and %s/results.csv\n", o.dir, o.dir);
  }
  rc = rc ? rc : ss_compare_write_plots(&o);
  /* Last, so that a report exists only when everything it shows does. */
  rc = rc ? rc : ss_compare_write_html(&o, scene->camera.width, scene->camera.height);
  if (rc == 0) {
    printf("report: %s/index.html\n", o.dir);
  }
  return finish(rc, scene, ref, mask);
}
