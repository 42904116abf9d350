/* The parameters of a layered surface (layer.h): defaults, validation, the
 * automatic discretisation and the memory it takes. */
#include "subsurf/layer.h"

#include "subsurf/sampling.h"
#include "transport/layer_ops.h"

#include <math.h>
#include <omp.h>
#include <string.h>

#define DEG (180.0 / SS_PI)

void ss_layer_params_default(ss_layer_params *p) {
  memset(p, 0, sizeof *p);
  p->n_layers = 1;
  p->layers[0].tau = 1.0;
  p->layers[0].albedo = 0.9;
  ss_phase_init(&p->layers[0].phase, SS_PHASE_ISOTROPIC, 0.0, NULL);
  p->eta = 1.0;
  p->bottom = SS_LAYER_BOTTOM_SAME;
  p->accuracy = 1e-4;
  p->thin_tau = ldexp(1.0, -30);
  p->paths = 1000000;
}

static int in_range(double x, double lo, double hi) { return x >= lo && x <= hi; }

ss_status ss_layer_validate(const ss_layer_params *p, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  if (p->n_layers < 1 || p->n_layers > SS_LAYER_MAX_LAYERS) {
    return ss_error_set(err, bad, "layers: expected 1 to %d layers, got %d", SS_LAYER_MAX_LAYERS,
                        p->n_layers);
  }
  for (int l = 0; l < p->n_layers; ++l) {
    const ss_layer_medium *m = &p->layers[l];
    if (!in_range(m->tau, SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU)) {
      return ss_error_set(err, bad, "layer %d: optical depth must be in [%g, %g], got %g", l,
                          SS_LAYER_MIN_TAU, SS_LAYER_MAX_TAU, m->tau);
    }
    if (!in_range(m->albedo, 0.0, 1.0)) {
      return ss_error_set(err, bad, "layer %d: albedo must be in [0, 1], got %g", l, m->albedo);
    }
    ss_phase check;
    if (ss_phase_init(&check, m->phase.type, m->phase.g, err) != SS_OK) {
      ss_error_prefix(err, "layer %d: ", l);
      return bad;
    }
  }
  if (!in_range(p->eta, 0.1, 10.0)) {
    return ss_error_set(err, bad, "eta must be in [0.1, 10], got %g", p->eta);
  }
  if (p->bottom != SS_LAYER_BOTTOM_SAME && p->bottom != SS_LAYER_BOTTOM_MATCHED &&
      p->bottom != SS_LAYER_BOTTOM_DIFFUSE) {
    return ss_error_set(err, bad, "bottom: unknown kind %d", (int)p->bottom);
  }
  if (p->bottom == SS_LAYER_BOTTOM_DIFFUSE && !in_range(p->bottom_albedo, 0.0, 1.0)) {
    return ss_error_set(err, bad, "bottom: diffuse albedo must be in [0, 1], got %g",
                        p->bottom_albedo);
  }
  if (!(p->theta_i >= 0.0 && p->theta_i < 0.5 * SS_PI)) {
    return ss_error_set(err, bad, "theta-i must be in [0, 90) degrees, got %g", p->theta_i * DEG);
  }
  if (p->n_theta_o < 0 || p->n_theta_o > SS_LAYER_MAX_DIRECTIONS) {
    return ss_error_set(err, bad, "theta-o: at most %d directions", SS_LAYER_MAX_DIRECTIONS);
  }
  for (int i = 0; i < p->n_theta_o; ++i) {
    if (!(fabs(p->theta_o[i]) < 0.5 * SS_PI)) {
      return ss_error_set(err, bad, "theta-o must be in (-90, 90) degrees, got %g",
                          p->theta_o[i] * DEG);
    }
  }
  if (p->nodes != 0 && (p->nodes < 2 || p->nodes > SS_LAYER_MAX_NODES)) {
    return ss_error_set(err, bad, "nodes must be 0 (automatic) or in [2, %d], got %d",
                        SS_LAYER_MAX_NODES, p->nodes);
  }
  if (p->modes < 0 || p->modes > SS_LAYER_MAX_MODES) {
    return ss_error_set(err, bad, "modes must be 0 (automatic) or in [1, %d], got %d",
                        SS_LAYER_MAX_MODES, p->modes);
  }
  if (!in_range(p->accuracy, 1e-12, 0.1)) {
    return ss_error_set(err, bad, "accuracy must be in [1e-12, 0.1], got %g", p->accuracy);
  }
  if (!in_range(p->thin_tau, 1e-12, 1.0)) {
    return ss_error_set(err, bad, "thin-tau must be in [1e-12, 1], got %g", p->thin_tau);
  }
  if (p->paths < 1 || p->paths > (uint64_t)1e15) {
    return ss_error_set(err, bad, "paths must be in [1, 1e15], got %llu",
                        (unsigned long long)p->paths);
  }
  if (p->threads < 0) {
    return ss_error_set(err, bad, "threads must be >= 0, got %d", p->threads);
  }
  return SS_OK;
}

/* Modes: the largest count any layer's phase function needs at `accuracy`.
 * Nodes: half as many as modes, at least 24 and at most 256 unless given
 * (HG g = 0.7 and 0.9 behind eta 1.5: the BRDF and BTDF agree to 1e-7 with
 * twice the nodes; docs/layer.md). */
void ss_layer_discretisation(const ss_layer_params *p, int *nodes, int *modes) {
  int m = p->modes;
  if (m == 0) {
    m = 1;
    for (int l = 0; l < p->n_layers; ++l) {
      int need = layer_phase_mode_count(&p->layers[l].phase, p->accuracy);
      m = need > m ? need : m;
    }
  }
  int n = p->nodes;
  if (n == 0) {
    n = m / 2 < 24 ? 24 : (m / 2 > 256 ? 256 : m / 2);
  }
  *nodes = n;
  *modes = m;
}

double ss_layer_bytes(const ss_layer_params *p) {
  int nodes, modes;
  ss_layer_discretisation(p, &nodes, &modes);
  double n = 2.0 * nodes + 1.0 + 2.0 * p->n_theta_o;
  int threads = p->threads > 0 ? p->threads : omp_get_max_threads();
  /* The phase modes of each layer, and per thread 4 slabs of 4 operators
   * plus the work space's 5 matrices. */
  double tables = p->n_layers * 2.0 * n * n * modes;
  double per_thread = (16.0 * 4.0 + 5.0) * n * n;
  return 8.0 * (tables + threads * per_thread);
}
