/* Energy compensation of rough dielectrics whose roughness varies over the
 * surface (a textured alpha): the tables of bsdf_dielectric_ms.c (Kulla &
 * Conty 2017) at the nodes of a fixed grid of alpha, for one distribution
 * and eta, interpolated linearly in alpha per shading point.
 *
 * Everything the compensation needs is linear in the node values: E_s(mu)
 * at the cosine nodes, its cosine average E_avg,s (an integral of the
 * interpolant) and the transmitted average that fixes the split x_s. So the
 * interpolated E_s, E_avg,s and transmitted average are exactly those of
 * the interpolated curves, and the lobes built from them (x_s recomputed)
 * still give every direction the albedo 1 and keep the reciprocal split;
 * what interpolation costs is only the difference between the interpolated
 * E and the true single-scattering albedo at that alpha.
 *
 * One table per (distribution, eta) in the process, shared by every
 * material that asks for it and kept until the process ends (a few tens of
 * kilobytes each); the nodes a roughness range needs are built when first
 * asked for, under a lock, before any rendering reads them. */
#include "optics/dielectric_ms.h"

#include "subsurf/table_index.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>

/* The alpha grid: 1e-3 (the smallest rough alpha), then steps of 1/40 to 1
 * and of 1/8 to 4 (ss_microfacet_init's limit); j / 40 is the double
 * nearest the decimal, so alpha 0.3 is a node. Steps of 1/20 left the
 * interpolated albedo up to 0.7 % off between nodes (grazing cosines). */
#define FINE_PER_UNIT 40  /* nodes 1..40: alpha 0.025..1 */
#define COARSE_PER_UNIT 8 /* nodes 41..64: alpha 1.125..4 */
#define ALPHA_NODES (1 + FINE_PER_UNIT + 3 * COARSE_PER_UNIT)
#define ALPHA_MIN 1e-3

enum { MU_NODES = SS_DIELECTRIC_MS_NODES + 1 };

typedef struct {
  int built;
  double e[2][MU_NODES];
  double e_avg[2], t_avg[2];
} slice;

struct ss_dielectric_ms_alpha {
  ss_microfacet_type type;
  double eta;
  slice slices[ALPHA_NODES];
  struct ss_dielectric_ms_alpha *next;
};

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static struct ss_dielectric_ms_alpha *tables;

static double node_alpha(int j) {
  if (j == 0) {
    return ALPHA_MIN;
  }
  return j <= FINE_PER_UNIT ? (double)j / FINE_PER_UNIT
                            : 1.0 + (double)(j - FINE_PER_UNIT) / COARSE_PER_UNIT;
}

/* The grid cell [j, j + 1] holding alpha (clamped to the grid). */
static int cell(double alpha) {
  double x = alpha <= 1.0 ? alpha * FINE_PER_UNIT : FINE_PER_UNIT + (alpha - 1.0) * COARSE_PER_UNIT;
  return ss_table_cell_clamped(x, ALPHA_NODES - 1);
}

/* Builds the slices lo..hi of t that are not built yet, all nodes of all
 * slices in one parallel loop. Called under the lock. */
static ss_status build(struct ss_dielectric_ms_alpha *t, int lo, int hi, ss_error *err) {
  ss_bsdf single[ALPHA_NODES];
  int needed[ALPHA_NODES], n = 0;
  for (int j = lo; j <= hi; ++j) {
    if (t->slices[j].built) {
      continue;
    }
    ss_microfacet mf;
    ss_status st = ss_microfacet_init(&mf, t->type, node_alpha(j), err);
    if (st == SS_OK) {
      st = ss_bsdf_rough_dielectric_init(&single[n], t->eta, &mf, SS_TRANSPORT_IMPORTANCE, err);
    }
    if (st != SS_OK) {
      return st;
    }
    needed[n++] = j;
  }
  double trans[ALPHA_NODES][2][MU_NODES];
#pragma omp parallel for schedule(dynamic)
  for (int node = 0; node < n * 2 * MU_NODES; ++node) {
    int i = node / (2 * MU_NODES), side = node / MU_NODES % 2, k = node % MU_NODES;
    slice *s = &t->slices[needed[i]];
    ss_dielectric_ms_node(&single[i], side, k, &s->e[side][k], &trans[i][side][k]);
  }
  for (int i = 0; i < n; ++i) {
    slice *s = &t->slices[needed[i]];
    for (int side = 0; side < 2; ++side) {
      s->e_avg[side] = ss_dielectric_ms_average(s->e[side]);
      s->t_avg[side] = ss_dielectric_ms_average(trans[i][side]);
    }
    s->built = 1;
  }
  return SS_OK;
}

ss_status ss_dielectric_ms_alpha_get(ss_microfacet_type type, double eta, double alpha_lo,
                                     double alpha_hi, const ss_dielectric_ms_alpha **out,
                                     ss_error *err) {
  *out = NULL;
  if (!(isfinite(eta) && eta > 0.0 && eta != 1.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "energy compensation: eta = %g must be positive, finite and not 1", eta);
  }
  if (!(alpha_lo <= alpha_hi && alpha_lo >= 0.0 && alpha_hi <= node_alpha(ALPHA_NODES - 1))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "energy compensation: roughness range [%g, %g] outside [0, %g]", alpha_lo,
                        alpha_hi, node_alpha(ALPHA_NODES - 1));
  }
  pthread_mutex_lock(&lock);
  struct ss_dielectric_ms_alpha *t = tables;
  while (t && !(t->type == type && t->eta == eta)) {
    t = t->next;
  }
  if (!t) {
    t = calloc(1, sizeof *t);
    if (!t) {
      pthread_mutex_unlock(&lock);
      return ss_error_set(err, SS_ERR_NO_MEMORY, "energy compensation: out of memory");
    }
    t->type = type;
    t->eta = eta;
    t->next = tables;
    tables = t;
  }
  ss_status st = build(t, cell(alpha_lo), cell(alpha_hi) + 1, err);
  pthread_mutex_unlock(&lock);
  if (st == SS_OK) {
    *out = t;
  }
  return st;
}

void ss_dielectric_ms_alpha_at(const ss_dielectric_ms_alpha *t, double alpha,
                               ss_dielectric_ms *ms) {
  int j = cell(alpha);
  double a0 = node_alpha(j), a1 = node_alpha(j + 1);
  double w = fmin(fmax((alpha - a0) / (a1 - a0), 0.0), 1.0);
  const slice *s0 = &t->slices[j], *s1 = &t->slices[j + 1];
  double t_avg[2];
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < MU_NODES; ++k) {
      ms->e[side][k] = (1.0 - w) * s0->e[side][k] + w * s1->e[side][k];
    }
    ms->e_avg[side] = (1.0 - w) * s0->e_avg[side] + w * s1->e_avg[side];
    t_avg[side] = (1.0 - w) * s0->t_avg[side] + w * s1->t_avg[side];
  }
  ss_dielectric_ms_finish(ms, t->eta, t_avg);
}
