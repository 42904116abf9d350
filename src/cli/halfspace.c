/* subsurf halfspace: the plane-parallel Monte Carlo reference. */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/memory_check.h"
#include "cli/mpi_job.h"
#include "cli/output_check.h"
#include "cli/progress_bar.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/image_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CMD "halfspace"

typedef struct {
  ss_medium_options medium;
  const char *json_path;
  const char *map_paths[4];
  int n_maps;
  double exposure;
  int exposure_auto;
  int quiet;
} options;

static void usage(FILE *out) {
  ss_halfspace_params d;
  ss_halfspace_params_default(&d);
  fprintf(out,
          "usage: subsurf halfspace [options]\n\n"
          "Exact Monte Carlo reference: a collimated unit-power beam enters a half-space (or a\n"
          "slab) at the origin; the light is traced with exact free flights, phase sampling and\n"
          "Fresnel events at a smooth boundary. Every number comes with its standard error.\n\n");
  ss_medium_options_help(out);
  fprintf(out,
          "run:\n"
          "  --paths N          number of light paths (default %.0f)\n"
          "  --time-limit S     stop after S seconds with the paths done so far (default 0: none)\n"
          "  --seed N           random seed; results are identical for any --threads (default 0)\n"
          "  --threads N        OpenMP threads (default 0: all cores)\n"
          "  --max-depth N      scattering events a path may have (1: first-order light); one\n"
          "                     that would scatter again is cut, its power reported as\n"
          "                     \"truncated\" (default %.0f)\n"
          "  --quiet            no progress bar\n"
          "outputs:\n"
          "  --json FILE|-      results as JSON (default: a summary on stdout)\n"
          "  --map FILE         exitance map over the x/y bins: .exr (linear), .png or .pfm;\n"
          "                     repeatable, to write several formats of one run\n"
          "  --exposure E|auto  PNG exposure in stops, in [-64, 64] (default auto: 99.5th\n"
          "                     percentile -> 1)\n\n"
          "Interrupted with Ctrl-C, it writes what it has to NAME-partial.EXT and exits 130.\n"
          "mpirun -np N subsurf halfspace ... splits the batches of paths over N processes\n"
          "(any machines); rank 0 writes the same numbers as one process (docs/halfspace.md).\n",
          (double)d.paths, (double)d.max_depth);
}

static int parse_option(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!strcmp(name, "json")) {
    o->json_path = value;
  } else if (!strcmp(name, "map")) {
    if (o->n_maps == 4) {
      fprintf(stderr, "subsurf " CMD ": --map: at most 4 map files\n");
      return -1;
    }
    o->map_paths[o->n_maps++] = value;
  } else if (!strcmp(name, "exposure")) {
    o->exposure_auto = !strcmp(value, "auto");
    if (!o->exposure_auto) {
      return ss_parse_double_in(CMD, name, value, -64.0, 64.0, &o->exposure) ? -1 : 1;
    }
  } else {
    int rc = ss_medium_options_parse_run(&o->medium, CMD, name, value);
    return rc ? rc : ss_medium_options_parse(&o->medium, CMD, name, value);
  }
  return 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!strcmp(name, "quiet")) {
    o->quiet = 1;
    return 1;
  }
  return 0;
}

/* Returns 0, 1 to exit successfully (--help), or 2 on bad input. */
static int parse_args(options *o, int argc, char **argv) {
  const ss_cli_spec spec = {parse_flag, parse_option, NULL, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 1, &spec, o);
  if (rc != 0) {
    return rc;
  }
  o->medium.params.want_map = o->n_maps > 0; /* the map's size is validated too */
  if (ss_medium_options_finish(&o->medium, CMD) != 0) {
    return 2;
  }
  if (ss_cli_check_memory(CMD, ss_halfspace_bytes(&o->medium.params),
                          "the tallies of every bin on every thread",
                          "fewer --xbins/--ybins or --threads") != 0) {
    return 2;
  }
  if (ss_mpi_rank() != 0) {
    o->quiet = 1;
    return 0; /* rank 0 alone writes */
  }
  ss_output_plan p;
  ss_output_plan_init(&p);
  if (o->json_path) {
    ss_output_plan_add(&p, "--json", o->json_path, SS_FILE_JSON, 0, 0);
  }
  for (int i = 0; i < o->n_maps; ++i) {
    if (!ss_image_format_supported(o->map_paths[i])) {
      fprintf(stderr, "subsurf " CMD ": --map: expected a .exr, .png or .pfm file, got '%s'\n",
              o->map_paths[i]);
      ss_output_plan_free(&p);
      return 2;
    }
    ss_output_plan_add(&p, "--map", o->map_paths[i],
                       ss_file_kind_of_name(o->map_paths[i], SS_FILE_EXR), 0, 0);
  }
  return ss_cli_check_outputs(&p, CMD);
}

static void on_progress(void *ctx, uint64_t done, uint64_t total) {
  (void)total;
  ss_progress_update(ctx, done);
}

static int compare_float(const void *a, const void *b) {
  float x = *(const float *)a, y = *(const float *)b;
  return (x > y) - (x < y);
}

/* PNG exposure that maps the 99.5th percentile of the non-zero values to 1. */
static double auto_exposure(const ss_image *img) {
  size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels, m = 0;
  float *v = malloc(n * sizeof *v);
  if (!v) {
    return 0.0;
  }
  for (size_t i = 0; i < n; ++i) {
    if (img->data[i] > 0.0f && isfinite(img->data[i])) {
      v[m++] = img->data[i];
    }
  }
  double e = 0.0;
  if (m > 0) {
    qsort(v, m, sizeof *v, compare_float);
    e = -log2(v[(size_t)(0.995 * (double)(m - 1))]);
  }
  free(v);
  return e;
}

/* NAME.EXT -> NAME-partial.EXT for results cut short by Ctrl-C. */
static char *output_name(const char *path, int partial) {
  size_t len = strlen(path);
  char *out = malloc(len + 16);
  if (!out) {
    return NULL;
  }
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  if (!partial || !strcmp(path, "-")) {
    memcpy(out, path, len + 1);
  } else if (dot && (!slash || dot > slash)) {
    snprintf(out, len + 16, "%.*s-partial%s", (int)(dot - path), path, dot);
  } else {
    snprintf(out, len + 16, "%s-partial", path);
  }
  return out;
}

static void print_estimate(const char *name, ss_estimate e) {
  printf("  %-14s %.6f +- %.6f\n", name, e.value, e.error);
}

static void print_summary(const ss_halfspace_result *r, const char *channel) {
  printf("channel %s: %llu paths in %.2f s (%.3g scattering events/s)%s\n", channel,
         (unsigned long long)r->paths, r->seconds,
         r->seconds > 0.0 ? (double)r->scatter_events / r->seconds : 0.0,
         r->partial ? " [partial]" : "");
  print_estimate("reflectance", r->reflectance);
  print_estimate("transmittance", r->transmittance);
  print_estimate("specular", r->specular);
  print_estimate("absorbed", r->absorbed);
  if (r->truncated.value > 0.0) {
    print_estimate("truncated", r->truncated);
  }
}

/* Copies channel `c` of the exitance map into `img` (row 0 = largest y). */
static void map_to_image(const ss_halfspace_result *r, ss_image *img, int c) {
  for (int y = 0; y < r->ybins; ++y) {
    for (int x = 0; x < r->xbins; ++x) {
      ss_image_pixel(img, x, r->ybins - 1 - y)[c] =
          (float)r->map[(size_t)y * (size_t)r->xbins + (size_t)x].value;
    }
  }
}

/* The run's own inputs, next to the medium's in "params". */
static cJSON *params_json(const ss_medium_options *m) {
  cJSON *j = ss_medium_options_to_json(m);
  const ss_halfspace_params *p = &m->params;
  cJSON_AddNumberToObject(j, "paths", (double)p->paths);
  cJSON_AddNumberToObject(j, "time_limit", p->time_limit);
  cJSON_AddNumberToObject(j, "seed", (double)p->seed);
  cJSON_AddNumberToObject(j, "threads", p->threads);
  cJSON_AddNumberToObject(j, "max_depth", (double)p->max_depth);
  return j;
}

static int write_outputs(const options *o, ss_halfspace_result **results, int nres, int partial) {
  int rc = 0;
  if (o->json_path) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "command", CMD);
    ss_medium_options m = o->medium;
    if (nres == 1) {
      ss_medium_options_select_channel(&m, ss_medium_options_channel_at(&m, 0));
      cJSON_AddItemToObject(root, "params", params_json(&m));
      ss_result_add_json(root, results[0]);
    } else {
      cJSON_AddItemToObject(root, "params", params_json(&m));
      cJSON *channels = cJSON_AddObjectToObject(root, "channels");
      for (int i = 0; i < nres && results[i]; ++i) {
        int c = ss_medium_options_channel_at(&m, i);
        ss_medium_options one = m;
        ss_medium_options_select_channel(&one, c);
        one.channel = c;
        cJSON *ch = cJSON_AddObjectToObject(channels, ss_channel_name(c));
        cJSON_AddItemToObject(ch, "params", params_json(&one));
        ss_result_add_json(ch, results[i]);
      }
    }
    cJSON_AddBoolToObject(root, "interrupted", partial);
    char *path = output_name(o->json_path, partial);
    if (!path || ss_json_write_file(root, path, CMD) != 0) {
      rc = 1;
    } else if (strcmp(path, "-") != 0) {
      fprintf(stderr, "wrote %s\n", path);
    }
    free(path);
    cJSON_Delete(root);
  }
  if (o->n_maps > 0 && results[0]) {
    ss_image *img = ss_image_create(results[0]->xbins, results[0]->ybins, nres == 1 ? 1 : 3);
    if (!img) {
      fprintf(stderr, "subsurf " CMD ": out of memory for the map\n");
      return 1;
    }
    for (int i = 0; i < nres && results[i]; ++i) {
      map_to_image(results[i], img, i);
    }
    double exposure = o->exposure_auto ? auto_exposure(img) : o->exposure;
    for (int m = 0; m < o->n_maps; ++m) {
      char *path = output_name(o->map_paths[m], partial);
      ss_error err;
      if (!path) {
        rc = 1;
      } else if (ss_image_write(path, img, exposure, &err) != SS_OK) {
        fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
        rc = 1;
      } else {
        fprintf(stderr, "wrote %s\n", path);
      }
      free(path);
    }
    ss_image_destroy(img);
  }
  return rc;
}

int ss_cmd_halfspace(int argc, char **argv) {
  options o;
  memset(&o, 0, sizeof o);
  ss_medium_options_init(&o.medium);
  o.exposure_auto = 1;
  int rc = ss_mpi_all_ok(parse_args(&o, argc, argv));
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  o.medium.params.cancel = ss_cli_install_interrupt_handler();

  int nres = ss_medium_options_channel_count(&o.medium);
  ss_halfspace_result *results[3] = {NULL, NULL, NULL};
  int interrupted = 0, failed = 0;
  for (int i = 0; i < nres && !interrupted; ++i) {
    int c = ss_medium_options_channel_at(&o.medium, i);
    ss_medium_options_select_channel(&o.medium, c);
    char label[32];
    snprintf(label, sizeof label, "halfspace %s", o.medium.medium ? ss_channel_name(c) : "");
    ss_progress progress;
    ss_progress_begin(&progress, label, o.medium.params.paths, !o.quiet,
                      o.medium.params.time_limit);
    o.medium.params.progress = on_progress;
    o.medium.params.progress_ctx = &progress;
    ss_mpi_batches batches; /* under mpirun: the ranks share the batches */
    ss_mpi_split_batches(&o.medium.params, &batches, CMD, i);
    ss_error err;
    ss_status st = ss_halfspace_run(&o.medium.params, &results[i], &err);
    ss_progress_end(&progress, results[i] ? results[i]->paths : 0);
    if (st != SS_OK) {
      fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
      failed = 1;
    } else if (ss_mpi_rank() == 0 && ss_result_check_finite(results[i], CMD) != 0) {
      failed = 1;
    }
    /* A rank interrupted or failed anywhere ends the job for all. */
    interrupted = ss_mpi_any(!failed && results[i]->interrupted);
    if ((failed = ss_mpi_any(failed)) != 0) {
      break;
    }
    if (ss_mpi_rank() == 0 && (!o.json_path || strcmp(o.json_path, "-") != 0)) {
      print_summary(results[i], ss_channel_name(o.medium.medium ? c : 0));
    }
  }
  if (!failed && ss_mpi_rank() == 0 && write_outputs(&o, results, nres, interrupted) != 0) {
    failed = 1;
  }
  for (int i = 0; i < 3; ++i) {
    ss_halfspace_result_destroy(results[i]);
  }
  if (interrupted && ss_mpi_rank() == 0) {
    fprintf(stderr, "subsurf " CMD ": interrupted; partial results written\n");
  }
  return interrupted ? 130 : failed ? 1 : 0;
}
