/* subsurf layer: the reflection and transmission of a slab or a stack of
 * slabs as a surface (docs/layer.md). */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/memory_check.h"
#include "cli/output_check.h"
#include "cli/progress_bar.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "io/layer_stack.h"
#include "subsurf/layer.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CMD "layer"
#define DEG (SS_PI / 180.0)

typedef enum { METHOD_ADDING, METHOD_MC, METHOD_FIRST_ORDER } method;
static const char *const method_names[] = {"adding", "mc", "first-order"};

typedef struct {
  ss_medium_options medium;
  char medium_option[32]; /* the first medium option given, for --stack's conflict */
  const char *stack_path;
  ss_layer_params stack; /* the layers read from --stack */
  const char *bottom_text;
  ss_layer_bottom bottom;
  double bottom_albedo;
  method method;
  double packing;
  int nodes, modes, threads;
  double accuracy;
  unsigned long long paths, seed;
  const char *json_path;
  int quiet;
} options;

/* One channel's answer (the errors are 0 for the deterministic methods). */
typedef struct {
  ss_estimate specular, reflectance, reflectance_unscattered;
  ss_estimate transmittance, transmittance_unscattered, absorbed;
  ss_estimate brdf[SS_LAYER_MAX_DIRECTIONS], btdf[SS_LAYER_MAX_DIRECTIONS];
  int nodes, modes;
  double seconds;
  uint64_t paths;
} answer;

static void usage(FILE *out) {
  ss_layer_params d;
  ss_layer_params_default(&d);
  fprintf(
      out,
      "usage: subsurf layer [options]\n\n"
      "A slab, or a stack of slabs, as a surface: its BRDF and BTDF at exact directions and\n"
      "its totals per unit incident power, for a collimated beam from above. Adding-doubling\n"
      "on Gauss-Legendre nodes x Fourier modes (deterministic), or the single-scattering\n"
      "closed forms of Blinn (1982) and Hanrahan & Krueger (1993), or a random walk in\n"
      "depth (Pharr & Hanrahan 2000) with standard errors.\n\n"
      "one layer (the options of subsurf halfspace):\n"
      "  --sigma-s X --sigma-a X --g X --phase iso|hg|gauss --medium NAME --scale X\n"
      "  --channel r|g|b|rgb  the layer's medium, as for halfspace (default sigma-s 1,\n"
      "                     sigma-a 0.01, iso)\n"
      "  --thickness X      the layer's thickness, finite, > 0 (default 1)\n"
      "  --eta X            n_layer / n_outside of the top face, [0.1, 10]; 1 is index\n"
      "                     matched (default 1)\n"
      "  --theta-i DEG      polar angle of the beam, tilted toward +x (default 0)\n"
      "  --theta-o DEG      an outgoing direction in the x-z plane, positive toward +x, where\n"
      "                     the BRDF and BTDF are reported; repeatable (default: none)\n"
      "  --bottom B         same (the top's face again, halfspace --thickness's slab) |\n"
      "                     index-matched (open below, no face) | diffuse:A (a Lambertian\n"
      "                     base of albedo A) (default same)\n"
      "  --stack FILE.json  several layers instead: {\"eta\": X, \"bottom\": B, \"layers\":\n"
      "                     [{\"tau\": T, \"albedo\": A, \"phase\": \"hg\", \"g\": G} or\n"
      "                     {\"sigma_s\", \"sigma_a\", \"thickness\", ...}, ...]} from the top\n"
      "  --packing D        Blinn's packing density: optical depths become tau / (1 - D),\n"
      "                     [0, 0.99] (default 0)\n"
      "method:\n"
      "  --method M         adding | mc (random walk, with standard errors) |\n"
      "                     first-order (one scattering event, closed form) (default adding)\n"
      "  --nodes N          Gauss-Legendre nodes per hemisphere, [2, %d] (default 0:\n"
      "                     from the phase function)\n"
      "  --modes N          Fourier modes in azimuth, [1, %d] (default 0: those above\n"
      "                     --accuracy)\n"
      "  --accuracy A       relative size of the last phase mode kept, [1e-12, 0.1]\n"
      "                     (default %g)\n"
      "  --paths N          paths of --method mc, [1, 1e15] (default %.0f)\n"
      "  --seed N           its random seed; results are identical for any --threads\n"
      "                     (default 0)\n"
      "  --threads N        OpenMP threads (default 0: all cores)\n"
      "  --quiet            no progress bar\n"
      "outputs:\n"
      "  --json FILE|-      results as JSON (default: a summary on stdout)\n\n"
      "Interrupted with Ctrl-C it writes nothing and exits 130.\n",
      SS_LAYER_MAX_NODES, SS_LAYER_MAX_MODES, d.accuracy, (double)d.paths);
}

/* The options of `subsurf halfspace` that describe the layer and the angles. */
static int is_medium_option(const char *name) {
  static const char *const names[] = {"sigma-s", "sigma-a", "g",         "phase",
                                      "medium",  "scale",   "channel",   "eta",
                                      "theta-i", "theta-o", "thickness", NULL};
  for (int i = 0; names[i]; ++i) {
    if (!strcmp(name, names[i])) {
      return 1;
    }
  }
  return 0;
}

static int parse_method(options *o, const char *value) {
  for (int m = 0; m < (int)(sizeof method_names / sizeof *method_names); ++m) {
    if (!strcmp(value, method_names[m])) {
      o->method = (method)m;
      return 1;
    }
  }
  fprintf(stderr, "subsurf " CMD ": --method: expected adding, mc or first-order, got '%s'\n",
          value);
  return -1;
}

static int parse_option(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  int rc = 0;
  if (!strcmp(name, "json")) {
    o->json_path = value;
  } else if (!strcmp(name, "stack")) {
    o->stack_path = value;
  } else if (!strcmp(name, "bottom")) {
    o->bottom_text = value;
    if (!ss_layer_bottom_parse(value, &o->bottom, &o->bottom_albedo)) {
      fprintf(stderr,
              "subsurf " CMD ": --bottom: expected same, index-matched or diffuse:A with A in "
              "[0, 1], got '%s'\n",
              value);
      return -1;
    }
  } else if (!strcmp(name, "method")) {
    return parse_method(o, value);
  } else if (!strcmp(name, "packing")) {
    rc = ss_parse_double_in(CMD, name, value, 0.0, 0.99, &o->packing);
  } else if (!strcmp(name, "nodes")) {
    rc = ss_parse_int(CMD, name, value, 2, SS_LAYER_MAX_NODES, &o->nodes);
  } else if (!strcmp(name, "modes")) {
    rc = ss_parse_int(CMD, name, value, 1, SS_LAYER_MAX_MODES, &o->modes);
  } else if (!strcmp(name, "accuracy")) {
    rc = ss_parse_double_in(CMD, name, value, 1e-12, 0.1, &o->accuracy);
  } else if (!strcmp(name, "paths")) {
    rc = ss_parse_u64(CMD, name, value, &o->paths);
    if (rc == 0 && !(o->paths >= 1 && o->paths <= 1000000000000000ull)) {
      fprintf(stderr, "subsurf " CMD ": --paths: expected a whole number in [1, 1e15], got '%s'\n",
              value);
      rc = -1;
    }
  } else if (!strcmp(name, "seed")) {
    rc = ss_parse_u64(CMD, name, value, &o->seed);
  } else if (!strcmp(name, "threads")) {
    rc = ss_parse_int(CMD, name, value, 0, 1024, &o->threads);
  } else if (is_medium_option(name)) {
    if (!o->medium_option[0] && strcmp(name, "eta") && strcmp(name, "theta-i") &&
        strcmp(name, "theta-o")) {
      snprintf(o->medium_option, sizeof o->medium_option, "%s", name);
    }
    return ss_medium_options_parse(&o->medium, CMD, name, value);
  } else {
    return 0;
  }
  return rc ? -1 : 1;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!strcmp(name, "quiet")) {
    o->quiet = 1;
    return 1;
  }
  return 0;
}

/* The layers, the faces, the angles and the discretisation of channel c. */
static int layer_params(const options *o, int c, ss_layer_params *p) {
  ss_medium_options m = o->medium;
  ss_medium_options_select_channel(&m, c);
  const ss_halfspace_params *h = &m.params;
  if (o->stack_path) {
    *p = o->stack;
  } else {
    ss_layer_params_default(p);
    double sigma_s = h->medium.sigma_s.c[c], sigma_t = sigma_s + h->medium.sigma_a.c[c];
    double tau = sigma_t * h->thickness;
    if (!(tau >= SS_LAYER_MIN_TAU && tau <= SS_LAYER_MAX_TAU)) {
      fprintf(stderr,
              "subsurf " CMD ": --thickness: the optical depth (sigma_s + sigma_a) x thickness = "
              "%g is outside [%g, %g]\n",
              tau, SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU);
      return -1;
    }
    p->layers[0].tau = tau;
    p->layers[0].albedo = sigma_s / sigma_t;
    ss_error err;
    if (ss_phase_init(&p->layers[0].phase, h->medium.phase, h->medium.g.c[c], &err) != SS_OK) {
      fprintf(stderr, "subsurf " CMD ": --g: %s\n", err.message);
      return -1;
    }
    p->eta = h->eta;
    p->bottom = o->bottom;
    p->bottom_albedo = o->bottom_albedo;
  }
  for (int l = 0; l < p->n_layers; ++l) {
    p->layers[l].tau /= 1.0 - o->packing;
    if (p->layers[l].tau > SS_LAYER_MAX_TAU) {
      fprintf(stderr, "subsurf " CMD ": --packing: layer %d's optical depth %g exceeds %g\n", l,
              p->layers[l].tau, SS_LAYER_MAX_TAU);
      return -1;
    }
  }
  p->theta_i = h->theta_i;
  p->n_theta_o = h->n_theta_o;
  memcpy(p->theta_o, h->theta_o, sizeof h->theta_o);
  p->nodes = o->nodes;
  p->modes = o->modes;
  p->accuracy = o->accuracy;
  p->threads = o->threads;
  p->paths = o->paths;
  p->seed = o->seed;
  ss_error err;
  if (ss_layer_validate(p, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
    return -1;
  }
  return 0;
}

/* --stack replaces the medium options; its "eta" and "bottom" the options. */
static int read_stack(options *o) {
  if (o->medium_option[0]) {
    fprintf(stderr, "subsurf " CMD ": --%s: the layers come from --stack; give one or the other\n",
            o->medium_option);
    return -1;
  }
  ss_layer_params_default(&o->stack);
  o->stack.eta = o->medium.params.eta;
  o->stack.bottom = o->bottom;
  o->stack.bottom_albedo = o->bottom_albedo;
  int eta_set = 0, bottom_set = 0;
  ss_error err;
  if (ss_layer_stack_read(o->stack_path, &o->stack, &eta_set, &bottom_set, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": --stack: %s\n", err.message);
    return -1;
  }
  if ((eta_set && o->medium.eta_set) || (bottom_set && o->bottom_text)) {
    fprintf(stderr, "subsurf " CMD ": --%s: also given by the stack file %s\n",
            eta_set && o->medium.eta_set ? "eta" : "bottom", o->stack_path);
    return -1;
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
  if (ss_medium_options_finish(&o->medium, CMD) != 0) {
    return 2;
  }
  if (!isfinite(o->medium.params.thickness)) {
    fprintf(stderr, "subsurf " CMD ": --thickness: expected a finite thickness, got inf\n");
    return 2;
  }
  if (o->stack_path && read_stack(o) != 0) {
    return 2;
  }
  int channels = ss_medium_options_channel_count(&o->medium);
  for (int i = 0; i < channels; ++i) {
    ss_layer_params p;
    if (layer_params(o, ss_medium_options_channel_at(&o->medium, i), &p) != 0) {
      return 2;
    }
    int nodes, modes;
    ss_layer_discretisation(&p, &nodes, &modes);
    char what[96];
    snprintf(what, sizeof what, "--nodes %d x --modes %d: the operators of adding-doubling", nodes,
             modes);
    if (o->method == METHOD_ADDING &&
        ss_cli_check_memory(CMD, ss_layer_bytes(&p), what,
                            "fewer --nodes or --modes, a looser --accuracy or fewer --threads") !=
            0) {
      return 2;
    }
  }
  return o->json_path ? ss_cli_check_output(CMD, "--json", o->json_path, SS_FILE_JSON) : 0;
}

static void from_result(const ss_layer_result *r, int n_theta_o, answer *a) {
  a->specular = (ss_estimate){r->specular, 0.0};
  a->reflectance = (ss_estimate){r->reflectance, 0.0};
  a->reflectance_unscattered = (ss_estimate){r->reflectance_unscattered, 0.0};
  a->transmittance = (ss_estimate){r->transmittance, 0.0};
  a->transmittance_unscattered = (ss_estimate){r->transmittance_unscattered, 0.0};
  a->absorbed = (ss_estimate){r->absorbed, 0.0};
  for (int k = 0; k < n_theta_o; ++k) {
    a->brdf[k] = (ss_estimate){r->brdf[k], 0.0};
    a->btdf[k] = (ss_estimate){r->btdf[k], 0.0};
  }
  a->nodes = r->nodes;
  a->modes = r->modes;
}

/* The walk's estimates and errors; *interrupted when Ctrl-C cut it short. */
static ss_status solve_mc(const ss_layer_params *p, answer *a, int *interrupted, ss_error *err) {
  ss_layer_mc_result r;
  ss_status st = ss_layer_mc(p, &r, err);
  if (st != SS_OK) {
    return st;
  }
  from_result(&r.value, p->n_theta_o, a);
  const ss_layer_result *e = &r.error;
  a->reflectance.error = e->reflectance;
  a->reflectance_unscattered.error = e->reflectance_unscattered;
  a->transmittance.error = e->transmittance;
  a->transmittance_unscattered.error = e->transmittance_unscattered;
  a->absorbed.error = e->absorbed;
  for (int k = 0; k < p->n_theta_o; ++k) {
    a->brdf[k].error = e->brdf[k];
    a->btdf[k].error = e->btdf[k];
  }
  a->paths = r.paths;
  *interrupted = r.interrupted;
  return SS_OK;
}

static ss_status solve(const options *o, ss_layer_params *p, answer *a, ss_error *err) {
  ss_layer_result r;
  double t0 = ss_seconds();
  if (o->method == METHOD_MC) {
    int interrupted = 0;
    ss_status st = solve_mc(p, a, &interrupted, err);
    a->seconds = ss_seconds() - t0;
    return st == SS_OK && interrupted ? ss_error_set(err, SS_ERR_INTERRUPTED, "interrupted") : st;
  }
  ss_status st =
      o->method == METHOD_ADDING ? ss_layer_adding(p, &r, err) : ss_layer_first_order(p, &r, err);
  if (st == SS_OK) {
    from_result(&r, p->n_theta_o, a);
  }
  a->seconds = ss_seconds() - t0;
  return st;
}

static cJSON *estimate_json(ss_estimate e) {
  cJSON *o = cJSON_CreateObject();
  cJSON_AddNumberToObject(o, "value", e.value);
  cJSON_AddNumberToObject(o, "stderr", e.error);
  return o;
}

static cJSON *directions_json(const ss_layer_params *p, const ss_estimate *f) {
  cJSON *a = cJSON_CreateArray();
  for (int k = 0; k < p->n_theta_o; ++k) {
    cJSON *d = estimate_json(f[k]);
    cJSON_AddNumberToObject(d, "theta_o", p->theta_o[k] / DEG);
    cJSON_AddItemToArray(a, d);
  }
  return a;
}

/* Every input, resolved: the layers as optical depth and albedo. */
static cJSON *params_json(const options *o, const ss_layer_params *p) {
  cJSON *j = cJSON_CreateObject();
  if (o->stack_path) {
    cJSON_AddStringToObject(j, "stack", o->stack_path);
  } else {
    const ss_medium_options *m = &o->medium;
    if (m->medium) {
      cJSON_AddStringToObject(j, "medium", m->medium->name);
      cJSON_AddNumberToObject(j, "scale", m->scale);
    } else {
      cJSON_AddNumberToObject(j, "sigma_s", m->sigma_s);
      cJSON_AddNumberToObject(j, "sigma_a", m->sigma_a);
    }
    cJSON_AddNumberToObject(j, "thickness", m->params.thickness);
  }
  cJSON_AddNumberToObject(j, "eta", p->eta);
  cJSON_AddStringToObject(j, "bottom", ss_layer_bottom_name(p->bottom));
  if (p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
    cJSON_AddNumberToObject(j, "bottom_albedo", p->bottom_albedo);
  }
  cJSON_AddNumberToObject(j, "packing", o->packing);
  cJSON *layers = cJSON_AddArrayToObject(j, "layers");
  for (int l = 0; l < p->n_layers; ++l) {
    cJSON *e = cJSON_CreateObject();
    cJSON_AddNumberToObject(e, "tau", p->layers[l].tau);
    cJSON_AddNumberToObject(e, "albedo", p->layers[l].albedo);
    cJSON_AddStringToObject(e, "phase", ss_phase_type_name(p->layers[l].phase.type));
    cJSON_AddNumberToObject(e, "g", p->layers[l].phase.g);
    cJSON_AddItemToArray(layers, e);
  }
  cJSON_AddNumberToObject(j, "theta_i", p->theta_i / DEG);
  cJSON *th = cJSON_AddArrayToObject(j, "theta_o");
  for (int k = 0; k < p->n_theta_o; ++k) {
    cJSON_AddItemToArray(th, cJSON_CreateNumber(p->theta_o[k] / DEG));
  }
  cJSON_AddStringToObject(j, "method", method_names[o->method]);
  if (o->method == METHOD_MC) {
    cJSON_AddNumberToObject(j, "paths", (double)p->paths);
    cJSON_AddNumberToObject(j, "seed", (double)p->seed);
  } else {
    cJSON_AddNumberToObject(j, "accuracy", p->accuracy);
  }
  cJSON_AddNumberToObject(j, "threads", p->threads);
  return j;
}

static void add_answer(cJSON *obj, const options *o, const ss_layer_params *p, const answer *a) {
  cJSON_AddItemToObject(obj, "params", params_json(o, p));
  cJSON_AddNumberToObject(obj, "seconds", a->seconds);
  if (o->method == METHOD_ADDING) {
    cJSON_AddNumberToObject(obj, "nodes", a->nodes);
    cJSON_AddNumberToObject(obj, "modes", a->modes);
  } else if (o->method == METHOD_MC) {
    cJSON_AddNumberToObject(obj, "paths", (double)a->paths);
  }
  cJSON_AddItemToObject(obj, "specular", estimate_json(a->specular));
  cJSON_AddItemToObject(obj, "reflectance", estimate_json(a->reflectance));
  cJSON_AddItemToObject(obj, "reflectance_unscattered", estimate_json(a->reflectance_unscattered));
  cJSON_AddItemToObject(obj, "transmittance", estimate_json(a->transmittance));
  cJSON_AddItemToObject(obj, "transmittance_unscattered",
                        estimate_json(a->transmittance_unscattered));
  cJSON_AddItemToObject(obj, "absorbed", estimate_json(a->absorbed));
  cJSON_AddItemToObject(obj, "brdf", directions_json(p, a->brdf));
  cJSON_AddItemToObject(obj, "btdf", directions_json(p, a->btdf));
}

static int write_json(const options *o, const ss_layer_params *p, const answer *a, int n) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "command", CMD);
  if (n == 1) {
    add_answer(root, o, &p[0], &a[0]);
  } else {
    cJSON *channels = cJSON_AddObjectToObject(root, "channels");
    for (int i = 0; i < n; ++i) {
      cJSON *ch = cJSON_AddObjectToObject(channels, ss_channel_name(i)); /* rgb: i is c */
      add_answer(ch, o, &p[i], &a[i]);
    }
  }
  int rc = ss_json_write_file(root, o->json_path, CMD) != 0;
  if (!rc && strcmp(o->json_path, "-") != 0) {
    fprintf(stderr, "wrote %s\n", o->json_path);
  }
  cJSON_Delete(root);
  return rc;
}

static void print_estimate(const char *name, ss_estimate e, int errors) {
  if (errors) {
    printf("  %-26s %.6f +- %.6f\n", name, e.value, e.error);
  } else {
    printf("  %-26s %.6f\n", name, e.value);
  }
}

static void print_summary(const options *o, const ss_layer_params *p, const answer *a,
                          const char *channel) {
  printf("layer%s%s: %s", channel[0] ? " " : "", channel, method_names[o->method]);
  if (o->method == METHOD_ADDING) {
    printf(", %d nodes x %d modes", a->nodes, a->modes);
  }
  if (o->method == METHOD_MC) {
    printf(", %llu paths", (unsigned long long)a->paths);
  }
  printf(" in %.2f s\n", a->seconds);
  int e = o->method == METHOD_MC;
  print_estimate("specular", a->specular, e);
  print_estimate("reflectance", a->reflectance, e);
  print_estimate("reflectance_unscattered", a->reflectance_unscattered, e);
  print_estimate("transmittance", a->transmittance, e);
  print_estimate("transmittance_unscattered", a->transmittance_unscattered, e);
  print_estimate("absorbed", a->absorbed, e);
  if (p->n_theta_o > 0) {
    printf("  %8s %14s %14s  (1/sr)\n", "theta_o", "brdf", "btdf");
  }
  for (int k = 0; k < p->n_theta_o; ++k) {
    printf("  %8.2f %14.6g %14.6g\n", p->theta_o[k] / DEG, a->brdf[k].value, a->btdf[k].value);
    if (e) {
      printf("  %8s %14.2g %14.2g  (standard errors)\n", "+-", a->brdf[k].error, a->btdf[k].error);
    }
  }
}

int ss_cmd_layer(int argc, char **argv) {
  options o;
  memset(&o, 0, sizeof o);
  ss_medium_options_init(&o.medium);
  o.medium.params.thickness = 1.0;
  o.bottom = SS_LAYER_BOTTOM_SAME;
  ss_layer_params d;
  ss_layer_params_default(&d);
  o.accuracy = d.accuracy;
  o.paths = d.paths;
  int rc = parse_args(&o, argc, argv);
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  const volatile sig_atomic_t *cancel = ss_cli_install_interrupt_handler();
  int n = ss_medium_options_channel_count(&o.medium);
  ss_layer_params p[3];
  answer a[3];
  memset(a, 0, sizeof a);
  for (int i = 0; i < n; ++i) {
    int c = ss_medium_options_channel_at(&o.medium, i);
    layer_params(&o, c, &p[i]);
    ss_progress progress;
    int nodes, modes;
    ss_layer_discretisation(&p[i], &nodes, &modes);
    uint64_t total = o.method == METHOD_MC ? p[i].paths : (uint64_t)modes;
    ss_progress_begin(&progress, "layer", total, !o.quiet && o.method != METHOD_FIRST_ORDER, 0.0);
    p[i].cancel = cancel;
    p[i].progress = ss_progress_report;
    p[i].progress_ctx = &progress;
    ss_error err;
    ss_status st = solve(&o, &p[i], &a[i], &err);
    ss_progress_end(&progress, progress.done);
    if (st == SS_ERR_INTERRUPTED || ss_cli_interrupted()) {
      return ss_cli_interrupted_exit(CMD, "while solving");
    }
    if (st != SS_OK) {
      fprintf(stderr, "subsurf " CMD ": %s\n", err.message);
      return 1;
    }
    if (!o.json_path || strcmp(o.json_path, "-") != 0) {
      print_summary(&o, &p[i], &a[i], o.medium.medium ? ss_channel_name(c) : "");
    }
  }
  return o.json_path && write_json(&o, p, a, n) != 0 ? 1 : 0;
}
