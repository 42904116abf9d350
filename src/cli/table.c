/* `subsurf table build` and `subsurf table check`: precomputed BSSRDF tables
 * (Ferrier2016's (rho, theta, r) table or pbrt-v3's radial table) written
 * to versioned files, and their accuracy against direct photon beam
 * diffusion at points drawn by the table's own sampler (Ferrier's Table 2). */
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/medium_options.h"
#include "cli/output_check.h"
#include "cli/result_json.h"
#include "cli/signals.h"

#include "subsurf/pbd.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/table_file.h"
#include "subsurf/threads.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CMD "table"

static void usage(FILE *out) {
  fprintf(out,
          "usage: subsurf table build --eta E --g G -o FILE [options]\n"
          "       subsurf table check FILE --rho R --theta DEG [options]\n\n"
          "build: tabulates photon beam diffusion for sigma_t = 1 and writes FILE.\n"
          "  --eta E            relative index n_inside/n_outside (> 1)\n"
          "  --g G              phase-function mean cosine in (-1, 1)\n"
          "  -o, --output FILE  table file to write\n"
          "  --kind K           gwc (Ferrier's rho x theta x r table, default) or radial\n"
          "                     (pbrt-v3's normal-incidence rho x r table)\n"
          "  --fit F            azimuthal model of a gwc table: two-lobe (default, two\n"
          "                     Wrapped Cauchy lobes) or anchors (Ferrier's three-anchor GWC)\n"
          "  --threads N        worker threads (0: all cores, default)\n"
          "  --quiet            print nothing on success\n\n"
          "check: mean relative error of the table against direct PBD at points drawn by\n"
          "the table's own sampler; the last line reads 'mean relative error: X %%'.\n"
          "  --rho R            single-scattering albedo in [0.001, 1]\n"
          "  --theta DEG        incidence angle in [0, 90) (0 for a radial table)\n"
          "  --samples N        sample count (default 100000)\n"
          "  --seed S           random seed (default 0)\n"
          "  --threads N        worker threads (0: all cores, default)\n\n"
          "Each action takes only its own options. Ctrl-C stops either one (build: once the\n"
          "table is computed), writes nothing and exits with 130.\n");
}

/* Smallest --rho of `check`: below it the table holds too little scattered
 * light for a relative error to mean anything (0 is refused alike). */
#define RHO_MIN 1e-3

typedef struct {
  const char *output, *file, *kind;
  double eta, g, rho, theta_deg;
  int eta_set, g_set, rho_set, theta_set, fit, threads, quiet;
  int check; /* 0: build; 1: check, which takes the table file as its argument */
  unsigned long long samples, seed;
} options;

/* 1 when option `name` belongs to the action (build or check). */
static int option_of_action(const char *name, int check) {
  static const char *const build[] = {"eta", "g", "output", "o", "kind", "fit", "threads", NULL};
  static const char *const chk[] = {"rho", "theta", "samples", "seed", "threads", NULL};
  for (const char *const *n = check ? chk : build; *n; ++n) {
    if (!strcmp(*n, name)) {
      return 1;
    }
  }
  return 0;
}

/* Returns 1 when consumed (value used), 0 when unknown, -1 on a bad value. */
static int parse_option(void *ctx, const char *name, const char *value) {
  options *o = ctx;
  if (!option_of_action(name, o->check)) {
    const char *action = o->check ? "check" : "build";
    fprintf(stderr, "subsurf " CMD " %s: %s%s is not an option of '" CMD " %s' (see --help)\n",
            action, name[1] ? "--" : "-", name, action);
    return -1;
  }
  if (!strcmp(name, "eta")) {
    o->eta_set = 1;
    return ss_parse_double(CMD, name, value, &o->eta) ? -1 : 1;
  }
  if (!strcmp(name, "g")) {
    o->g_set = 1;
    return ss_parse_double(CMD, name, value, &o->g) ? -1 : 1;
  }
  if (!strcmp(name, "rho")) {
    o->rho_set = 1;
    return ss_parse_double(CMD, name, value, &o->rho) ? -1 : 1;
  }
  if (!strcmp(name, "theta")) {
    o->theta_set = 1;
    return ss_parse_double(CMD, name, value, &o->theta_deg) ? -1 : 1;
  }
  if (!strcmp(name, "output") || !strcmp(name, "o")) {
    o->output = value;
    return 1;
  }
  if (!strcmp(name, "kind")) {
    if (strcmp(value, "gwc") && strcmp(value, "radial")) {
      fprintf(stderr, "subsurf " CMD ": --kind: expected gwc or radial, got '%s'\n", value);
      return -1;
    }
    o->kind = value;
    return 1;
  }
  if (!strcmp(name, "fit")) {
    if (!ss_table_gwc_fit_from_name(value, &o->fit)) {
      fprintf(stderr, "subsurf " CMD ": --fit: expected two-lobe or anchors, got '%s'\n", value);
      return -1;
    }
    return 1;
  }
  if (!strcmp(name, "threads")) {
    return ss_parse_int(CMD, name, value, 0, SS_THREADS_MAX, &o->threads) ? -1 : 1;
  }
  if (!strcmp(name, "samples")) {
    if (ss_parse_u64(CMD, name, value, &o->samples) != 0) {
      return -1;
    }
    if (o->samples == 0 || o->samples > 100000000ULL) {
      fprintf(stderr, "subsurf " CMD ": --samples: expected 1..100000000, got '%s'\n", value);
      return -1;
    }
    return 1;
  }
  if (!strcmp(name, "seed")) {
    return ss_parse_u64(CMD, name, value, &o->seed) ? -1 : 1;
  }
  return 0;
}

static int parse_flag(void *ctx, const char *name) {
  options *o = ctx;
  if (!o->check && !strcmp(name, "quiet")) {
    o->quiet = 1;
    return 1;
  }
  return 0;
}

static int parse_file(void *ctx, const char *arg) {
  options *o = ctx;
  if (o->check && !o->file) {
    o->file = arg;
    return 1;
  }
  return 0;
}

static int cmd_build(options *o) {
  if (!o->eta_set || !o->g_set || !o->output) {
    fprintf(stderr, "subsurf " CMD " build: --eta, --g and -o FILE are required (see --help)\n");
    return 2;
  }
  if (!(o->eta > 1.0 && o->eta < 10.0)) {
    fprintf(stderr, "subsurf " CMD " build: --eta: expected a number in (1, 10), got %g\n", o->eta);
    return 2;
  }
  if (!(fabs(o->g) < 1.0)) {
    fprintf(stderr, "subsurf " CMD " build: --g: expected a number in (-1, 1), got %g\n", o->g);
    return 2;
  }
  if (ss_cli_check_output(CMD " build", "--output", o->output, SS_FILE_TABLE) != 0) {
    return 2;
  }
  if (o->threads > 0) {
    omp_set_num_threads(o->threads);
  }
  ss_error err;
  double t0 = omp_get_wtime();
  ss_status st;
  size_t bytes = 0;
  if (!strcmp(o->kind, "radial")) {
    ss_table_radial *t;
    st = ss_table_radial_build(o->eta, o->g, &t, &err);
    if (st == SS_OK && ss_cli_interrupted()) {
      ss_table_radial_destroy(t);
      return ss_cli_interrupted_exit(CMD " build", "");
    }
    if (st == SS_OK) {
      bytes = t->n_rho * t->n_r * 2 * sizeof(float);
      st = ss_table_radial_save(t, o->output, &err);
      ss_table_radial_destroy(t);
    }
  } else {
    ss_table_gwc *t;
    st = ss_table_gwc_build(o->eta, o->g, o->fit, &t, &err);
    if (st == SS_OK && ss_cli_interrupted()) {
      ss_table_gwc_destroy(t);
      return ss_cli_interrupted_exit(CMD " build", "");
    }
    if (st == SS_OK) {
      bytes = ss_table_gwc_bytes(t);
      st = ss_table_gwc_save(t, o->output, &err);
      ss_table_gwc_destroy(t);
    }
  }
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD " build: %s\n", err.message);
    return st == SS_ERR_INVALID_ARGUMENT ? 2 : 1;
  }
  if (!o->quiet) {
    printf("wrote %s: %s table%s%s, eta %g, g %g, %zu bytes in memory, built in %.2f s\n",
           o->output, o->kind, strcmp(o->kind, "gwc") ? "" : ", fit ",
           strcmp(o->kind, "gwc") ? "" : ss_table_gwc_fit_name(o->fit), o->eta, o->g, bytes,
           omp_get_wtime() - t0);
  }
  return 0;
}

/* Relative error of the table at one sample drawn by its own sampler, or a
 * negative value when the sampler produced no point. */
typedef struct {
  const ss_table_gwc *gwc;
  const ss_table_radial *radial;
  ss_pbd pbd;
  ss_pbd_beam beam;
  double rho, theta;
} check_ctx;

static double check_one(const check_ctx *c, ss_rng *rng) {
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  if (c->gwc) {
    double r, phi;
    if (!ss_table_gwc_sample(c->gwc, c->rho, c->theta, u1, u2, &r, &phi)) {
      return -1.0;
    }
    double ref = ss_pbd_ms(&c->pbd, &c->beam, r, phi);
    return ref > 0.0 ? fabs(ss_table_gwc_eval(c->gwc, c->rho, c->theta, r, phi) / ref - 1.0) : -1.0;
  }
  double r = ss_table_radial_sample(c->radial, c->rho, u1);
  if (!(r > 0.0)) {
    return -1.0;
  }
  double ref = ss_pbd_ms(&c->pbd, &c->beam, r, 0.0) + ss_pbd_ss(&c->pbd, r);
  return ref > 0.0 ? fabs(ss_table_radial_sp(c->radial, c->rho, r) / ref - 1.0) : -1.0;
}

static int cmd_check(options *o) {
  if (!o->file || !o->rho_set || !o->theta_set) {
    fprintf(stderr, "subsurf " CMD " check: FILE, --rho and --theta are required (see --help)\n");
    return 2;
  }
  if (!(o->rho >= RHO_MIN && o->rho <= 1.0)) {
    fprintf(stderr,
            "subsurf " CMD " check: --rho: expected a number in [%g, 1] (below it too little "
            "light scatters to compare), got %g\n",
            RHO_MIN, o->rho);
    return 2;
  }
  if (!(o->theta_deg >= 0.0 && o->theta_deg < 90.0)) {
    fprintf(stderr, "subsurf " CMD " check: --theta: expected degrees in [0, 90), got %g\n",
            o->theta_deg);
    return 2;
  }
  ss_error err;
  ss_table_file_info info;
  if (ss_table_file_info_read(o->file, &info, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD " check: %s\n", err.message);
    return 2;
  }
  check_ctx c = {NULL, NULL, {0}, {0, 1}, o->rho, o->theta_deg * SS_PI / 180.0};
  ss_table_gwc *gwc = NULL;
  ss_table_radial *radial = NULL;
  ss_status st;
  if (info.kind == SS_TABLE_KIND_RADIAL) {
    if (o->theta_deg != 0.0) {
      fprintf(stderr,
              "subsurf " CMD " check: --theta: '%s' is a normal-incidence (radial) table, "
              "expected 0, got %g\n",
              o->file, o->theta_deg);
      return 2;
    }
    st = ss_table_radial_load(o->file, &radial, &err);
  } else {
    st = ss_table_gwc_load(o->file, &gwc, &err);
  }
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD " check: %s\n", err.message);
    return 2;
  }
  c.gwc = gwc;
  c.radial = radial;
  st = ss_pbd_init(&c.pbd, o->rho, 1.0 - o->rho, info.g, info.eta, 32, &err);
  if (st != SS_OK) {
    fprintf(stderr, "subsurf " CMD " check: %s\n", err.message);
    ss_table_gwc_destroy(gwc);
    ss_table_radial_destroy(radial);
    return 2;
  }
  c.beam = ss_pbd_beam_make(&c.pbd, c.theta);
  if (o->threads > 0) {
    omp_set_num_threads(o->threads);
  }
  /* Fixed chunks with their own streams, summed in order: the result does
   * not depend on the thread count. */
  enum { CHUNK = 1024 };
  long chunks = (long)((o->samples + CHUNK - 1) / CHUNK);
  double *sum = calloc((size_t)chunks, sizeof *sum), *max = calloc((size_t)chunks, sizeof *max);
  unsigned long long *count = calloc((size_t)chunks, sizeof *count);
  if (!sum || !max || !count) {
    fprintf(stderr, "subsurf " CMD " check: out of memory\n");
    free(sum);
    free(max);
    free(count);
    ss_table_gwc_destroy(gwc);
    ss_table_radial_destroy(radial);
    return 1;
  }
#pragma omp parallel for schedule(dynamic)
  for (long k = 0; k < chunks; ++k) {
    if (ss_cli_interrupted()) {
      continue;
    }
    ss_rng rng;
    ss_rng_seed_item(&rng, o->seed, (uint64_t)k);
    unsigned long long end = (unsigned long long)(k + 1) * CHUNK;
    for (unsigned long long i = (unsigned long long)k * CHUNK; i < end && i < o->samples; ++i) {
      double e = check_one(&c, &rng);
      if (e >= 0.0) {
        sum[k] += e;
        max[k] = fmax(max[k], e);
        count[k]++;
      }
    }
  }
  double total = 0.0, worst = 0.0;
  unsigned long long n = 0;
  for (long k = 0; k < chunks; ++k) {
    total += sum[k];
    worst = fmax(worst, max[k]);
    n += count[k];
  }
  free(sum);
  free(max);
  free(count);
  if (ss_cli_interrupted()) {
    ss_table_gwc_destroy(gwc);
    ss_table_radial_destroy(radial);
    return ss_cli_interrupted_exit(CMD " check", "");
  }
  printf("table %s: %s%s%s, eta %g, g %g\n", o->file, gwc ? "gwc" : "radial", gwc ? ", fit " : "",
         gwc ? ss_table_gwc_fit_name(gwc->fit) : "", info.eta, info.g);
  printf("rho %g, theta %g deg: %llu of %llu samples from the table's sampler vs direct PBD\n",
         o->rho, o->theta_deg, n, o->samples);
  printf("max relative error: %.3g %%\n", 100.0 * worst);
  ss_table_gwc_destroy(gwc);
  ss_table_radial_destroy(radial);
  if (n == 0) {
    fprintf(stderr, "subsurf " CMD " check: the table's sampler produced no point\n");
    return 1;
  }
  printf("mean relative error: %.3g %%\n", 100.0 * total / (double)n);
  return 0;
}

int ss_cmd_table(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "subsurf " CMD ": missing the action: expected build or check (see "
                    "subsurf " CMD " --help)\n");
    return 2;
  }
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    usage(stdout);
    return 0;
  }
  options o = {.kind = "gwc", .fit = SS_TABLE_GWC_TWO_LOBE, .samples = 100000};
  int build = !strcmp(argv[1], "build"), check = !strcmp(argv[1], "check");
  if (!build && !check) {
    fprintf(stderr, "subsurf " CMD ": unknown action '%s', expected build or check\n", argv[1]);
    return 2;
  }
  o.check = check;
  ss_cli_install_interrupt_handler();
  const ss_cli_spec spec = {parse_flag, parse_option, parse_file, usage};
  int rc = ss_cli_parse(CMD, argc, argv, 2, &spec, &o);
  if (rc != 0) {
    return rc == 1 ? 0 : rc;
  }
  return build ? cmd_build(&o) : cmd_check(&o);
}
