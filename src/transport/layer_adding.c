/* Adding-doubling for a stack of layers (layer.h): each azimuthal Fourier
 * mode is solved on its own (the modes do not couple in a stack of
 * homogeneous layers and smooth or Lambertian faces), in parallel; the
 * stack is added from the top down and the values at the requested
 * directions are read off the final operators. */
#include "subsurf/layer.h"

#include "subsurf/sampling.h"
#include "transport/layer_ops.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* What one mode contributes. */
typedef struct {
  double brdf[SS_LAYER_MAX_DIRECTIONS], btdf[SS_LAYER_MAX_DIRECTIONS];
  double totals[6]; /* mode 0 only: the fields of ss_layer_result in order */
  int doublings;
  int failed; /* 1: out of memory, 2: singular, 3: cancelled */
} mode_result;

typedef struct {
  const ss_layer_params *p;
  const layer_nodes *nd;
  double *const *coeff;
  int modes;
} stack_ctx;

/* cur = cur over next (cur's top face first). */
static int add_below(layer_slab *cur, layer_slab *tmp, const layer_slab *next, int *have,
                     const layer_nodes *nd, layer_work *ws) {
  if (!*have) {
    layer_op_copy(&cur->r, &next->r, nd->n);
    layer_op_copy(&cur->t, &next->t, nd->n);
    layer_op_copy(&cur->rs, &next->rs, nd->n);
    layer_op_copy(&cur->ts, &next->ts, nd->n);
    *have = 1;
    return 1;
  }
  if (!layer_add(tmp, cur, next, nd->w[LAYER_MED], 0, ws)) {
    return 0;
  }
  layer_slab t = *cur;
  *cur = *tmp;
  *tmp = t;
  return 1;
}

/* Builds the whole stack for mode m into `cur`; returns the doublings of the
 * deepest layer, -1 when out of memory, -2 if singular, -3 when cancelled. */
static int build_stack(const stack_ctx *c, int m, layer_slab *cur, layer_slab *tmp,
                       layer_slab *part, layer_work *ws, double *specular) {
  const ss_layer_params *p = c->p;
  const layer_nodes *nd = c->nd;
  int have = 0, doublings = 0;
  *specular = 0.0;
  if (p->eta != 1.0) {
    layer_face(part, nd, 1);
    *specular = part->r.d[nd->incident];
    add_below(cur, tmp, part, &have, nd, ws);
  }
  for (int l = 0; l < p->n_layers; ++l) {
    int k = layer_slab_build(part, nd, &p->layers[l], c->coeff[l], c->modes, m, p->thin_tau, ws,
                             p->cancel);
    if (k < 0) {
      return k;
    }
    doublings = k > doublings ? k : doublings;
    if (!add_below(cur, tmp, part, &have, nd, ws)) {
      return -2;
    }
  }
  if (p->bottom == SS_LAYER_BOTTOM_SAME && p->eta != 1.0) {
    layer_face(part, nd, 0);
  } else if (p->bottom == SS_LAYER_BOTTOM_DIFFUSE) {
    layer_lambert(part, nd, p->bottom_albedo, m);
  } else {
    return doublings;
  }
  return add_below(cur, tmp, part, &have, nd, ws) ? doublings : -2;
}

/* f^m = s / c_m (the light comes from outside, n = 1); the totals from mode
 * 0: int f mu dw = 2 pi int f^0 mu dmu = sum_j w_j s_ji / n_j^2. */
static void read_off(const stack_ctx *c, int m, const layer_slab *s, double specular,
                     mode_result *out) {
  const layer_nodes *nd = c->nd;
  const ss_layer_params *p = c->p;
  int n = nd->n, i = nd->incident;
  double cm = m == 0 ? 2.0 * SS_PI : SS_PI;
  int exit = p->bottom == SS_LAYER_BOTTOM_MATCHED ? LAYER_MED : LAYER_OUT;
  for (int k = 0; k < p->n_theta_o; ++k) {
    double sign = p->theta_o[k] < 0.0 && (m & 1) ? -1.0 : 1.0; /* cos(m pi) */
    out->brdf[k] = sign * s->r.s[(size_t)nd->reflected[k] * n + i] / cm;
    out->btdf[k] = p->bottom == SS_LAYER_BOTTOM_DIFFUSE
                       ? 0.0
                       : sign * s->t.s[(size_t)nd->transmitted[k] * n + i] / cm;
  }
  if (m != 0) {
    return;
  }
  double refl = 0.0, trans = 0.0;
  for (int j = 0; j < n; ++j) {
    refl += nd->w[LAYER_OUT][j] * s->r.s[(size_t)j * n + i];
    trans += nd->w[exit][j] * s->t.s[(size_t)j * n + i];
  }
  int diffuse = p->bottom == SS_LAYER_BOTTOM_DIFFUSE;
  /* A beam keeps its solid angle x cosine x n^2 (etendue) across the faces. */
  double n2 = exit == LAYER_MED ? p->eta * p->eta : 1.0;
  out->totals[0] = specular;
  out->totals[1] = refl;
  out->totals[2] = s->r.d[i] - specular;
  out->totals[3] = diffuse ? 0.0 : trans / n2;
  out->totals[4] = diffuse ? 0.0 : s->t.d[i] / n2;
}

static void solve_mode(const stack_ctx *c, int m, mode_result *out) {
  int n = c->nd->n;
  layer_slab cur, tmp, part;
  layer_work ws;
  int ok = layer_slab_alloc(&cur, n);
  ok = layer_slab_alloc(&tmp, n) && ok;
  ok = layer_slab_alloc(&part, n) && ok;
  ok = layer_work_alloc(&ws, n) && ok;
  double specular = 0.0;
  int k = ok ? build_stack(c, m, &cur, &tmp, &part, &ws, &specular) : -1;
  if (k < 0) {
    out->failed = -k;
  } else {
    out->doublings = k;
    read_off(c, m, &cur, specular, out);
  }
  layer_slab_free(&cur);
  layer_slab_free(&tmp);
  layer_slab_free(&part);
  layer_work_free(&ws);
}

static void free_tables(double **coeff, int n_layers) {
  for (int l = 0; l < n_layers; ++l) {
    int shared = 0;
    for (int e = 0; e < l; ++e) {
      shared |= coeff[e] == coeff[l];
    }
    if (!shared) {
      free(coeff[l]);
    }
  }
}

/* Layers with the same phase function share its table. */
static int build_tables(const ss_layer_params *p, const layer_nodes *nd, int modes,
                        double **coeff) {
  for (int l = 0; l < p->n_layers; ++l) {
    coeff[l] = NULL;
    for (int e = 0; e < l && !coeff[l]; ++e) {
      const ss_phase *a = &p->layers[e].phase, *b = &p->layers[l].phase;
      if (a->type == b->type && a->g == b->g) {
        coeff[l] = coeff[e];
      }
    }
    if (!coeff[l] && !(coeff[l] = layer_phase_modes(&p->layers[l].phase, nd, modes))) {
      free_tables(coeff, l);
      return 0;
    }
  }
  return 1;
}

static void combine(const ss_layer_params *p, const mode_result *mr, int modes,
                    ss_layer_result *out) {
  out->specular = mr[0].totals[0];
  out->reflectance = mr[0].totals[1];
  out->reflectance_unscattered = mr[0].totals[2];
  out->transmittance = mr[0].totals[3];
  out->transmittance_unscattered = mr[0].totals[4];
  out->absorbed = 1.0 - (out->specular + out->reflectance + out->reflectance_unscattered +
                         out->transmittance + out->transmittance_unscattered);
  out->doublings = mr[0].doublings;
  for (int k = 0; k < p->n_theta_o; ++k) {
    double r = 0.0, t = 0.0;
    for (int m = 0; m < modes; ++m) {
      r += mr[m].brdf[k];
      t += mr[m].btdf[k];
    }
    out->brdf[k] = r;
    out->btdf[k] = t;
  }
}

ss_status ss_layer_adding(const ss_layer_params *p, ss_layer_result *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  ss_status st = ss_layer_validate(p, err);
  if (st != SS_OK) {
    return st;
  }
  int base, modes;
  ss_layer_discretisation(p, &base, &modes);
  layer_nodes nd;
  double *coeff[SS_LAYER_MAX_LAYERS];
  mode_result *mr = calloc((size_t)modes, sizeof *mr);
  if (!mr || !layer_nodes_init(&nd, p, base)) {
    free(mr);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for %d nodes", base);
  }
  if (!build_tables(p, &nd, modes, coeff)) {
    free(mr);
    layer_nodes_free(&nd);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the phase function's modes");
  }
  stack_ctx c = {p, &nd, coeff, modes};
  int threads = p->threads > 0 ? p->threads : omp_get_max_threads();
  int solved = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (int m = 0; m < modes; ++m) {
    if (p->cancel && *p->cancel) {
      mr[m].failed = 3;
      continue;
    }
    solve_mode(&c, m, &mr[m]);
#pragma omp critical(layer_progress)
    {
      ++solved;
      if (p->progress) {
        p->progress(p->progress_ctx, (uint64_t)solved, (uint64_t)modes);
      }
    }
  }
  int failed = 0;
  for (int m = 0; m < modes; ++m) {
    failed = mr[m].failed > failed ? mr[m].failed : failed;
  }
  if (!failed) {
    combine(p, mr, modes, out);
    out->nodes = base;
    out->modes = modes;
    for (int k = 0; k < nd.n; ++k) {
      out->outside_nodes += nd.present[LAYER_OUT][k] && nd.w[LAYER_OUT][k] > 0.0;
      out->medium_nodes += nd.present[LAYER_MED][k] && nd.w[LAYER_MED][k] > 0.0;
    }
  }
  free_tables(coeff, p->n_layers);
  layer_nodes_free(&nd);
  free(mr);
  if (failed == 1) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the operators of %d nodes", base);
  }
  if (failed == 3) {
    return ss_error_set(err, SS_ERR_INTERRUPTED, "interrupted");
  }
  if (failed == 2) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "the adding equations' interreflection is singular");
  }
  return SS_OK;
}
