/* Energy compensation tables of rough conductors (KullaConty2017): the
 * directional albedo E(wo) of the single-scattering microfacet reflection
 * with F = 1, and its cosine average E_avg = (1/pi) int E(w) cos dw.
 *
 * E depends on cos(theta_o) and, for an anisotropic distribution, on the
 * azimuth; D is symmetric in x -> -x and y -> -y, so phi in [0, pi/2]
 * suffices. Nodes: MU_NODES + 1 cosines (k / MU_NODES, the grazing one at
 * 1e-3) times PHI_NODES azimuths (one when isotropic), each the mean of
 * G(wo, wi) / G1(wo) over jittered stratified visible normals (the weight
 * of visible-normal sampling, Heitz2014 eq. 38), own seed per node. E is
 * interpolated bilinearly and E_avg is the exact average of that
 * interpolant, so the compensated conductor with F = 1 has albedo 1 up to
 * the interpolation error of E.
 *
 * One table per (distribution, alpha_u, alpha_v) in the process, built when
 * first asked for and kept until the process ends (a few kilobytes). */
#include "optics/dielectric_ms.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#define MU_NODES SS_DIELECTRIC_MS_NODES
#define PHI_NODES 9
#define STRATA 64

struct ss_conductor_ms {
  ss_microfacet mf;
  int phi_nodes;
  double e[PHI_NODES][MU_NODES + 1];
  double e_avg;
  struct ss_conductor_ms *next;
};

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static struct ss_conductor_ms *tables;

static double node_albedo(const ss_microfacet *mf, double mu, double phi, uint64_t seed) {
  double s = sqrt(fmax(0.0, 1.0 - mu * mu));
  ss_vec3 wo = ss_vec3_make(s * cos(phi), s * sin(phi), mu);
  ss_rng rng;
  ss_rng_seed(&rng, seed, 11);
  double g1 = 1.0 / (1.0 + ss_microfacet_lambda(mf, wo)), sum = 0.0;
  for (int i = 0; i < STRATA; ++i) {
    for (int j = 0; j < STRATA; ++j) {
      double u1 = (i + ss_rng_uniform(&rng)) / STRATA, u2 = (j + ss_rng_uniform(&rng)) / STRATA;
      ss_vec3 wm = ss_microfacet_sample_visible(mf, wo, u1, u2);
      ss_vec3 wi = ss_reflect(wo, wm);
      if (wi.z > 0.0) {
        sum += ss_microfacet_g(mf, wo, wi, wm) / g1;
      }
    }
  }
  return fmin(sum / (STRATA * STRATA), 1.0);
}

static void build(struct ss_conductor_ms *t) {
  int nodes = t->phi_nodes * (MU_NODES + 1);
#pragma omp parallel for schedule(dynamic)
  for (int n = 0; n < nodes; ++n) {
    int p = n / (MU_NODES + 1), k = n % (MU_NODES + 1);
    double phi = t->phi_nodes > 1 ? 0.5 * SS_PI * p / (t->phi_nodes - 1) : 0.0;
    t->e[p][k] = node_albedo(&t->mf, fmax((double)k / MU_NODES, 1e-3), phi, (uint64_t)n);
  }
  /* The azimuthal mean of the interpolant (trapezoid over the nodes), then
   * its cosine average. */
  double mean[MU_NODES + 1];
  for (int k = 0; k <= MU_NODES; ++k) {
    double sum = 0.0;
    for (int p = 0; p < t->phi_nodes; ++p) {
      double w = t->phi_nodes > 1 && (p == 0 || p == t->phi_nodes - 1) ? 0.5 : 1.0;
      sum += w * t->e[p][k];
    }
    mean[k] = t->phi_nodes > 1 ? sum / (t->phi_nodes - 1) : sum;
  }
  t->e_avg = ss_dielectric_ms_average(mean);
}

ss_status ss_conductor_ms_get(const ss_microfacet *mf, const ss_conductor_ms **out, ss_error *err) {
  double av = ss_microfacet_alpha_v(mf);
  pthread_mutex_lock(&lock);
  struct ss_conductor_ms *t = tables;
  while (t && !(t->mf.type == mf->type && t->mf.alpha == mf->alpha &&
                ss_microfacet_alpha_v(&t->mf) == av)) {
    t = t->next;
  }
  ss_status st = SS_OK;
  if (!t) {
    t = calloc(1, sizeof *t);
    if (!t) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "conductor: no memory for compensation tables");
    } else {
      t->mf = *mf;
      t->phi_nodes = ss_microfacet_is_anisotropic(mf) ? PHI_NODES : 1;
      build(t);
      t->next = tables;
      tables = t;
    }
  }
  pthread_mutex_unlock(&lock);
  *out = st == SS_OK ? t : NULL;
  return st;
}

double ss_conductor_ms_albedo(const ss_conductor_ms *t, ss_vec3 wo) {
  double x = fmin(fmax(wo.z, 0.0), 1.0) * MU_NODES;
  int k = (int)fmin(x, MU_NODES - 1);
  double fk = x - k;
  double y = 0.0;
  int p = 0;
  if (t->phi_nodes > 1) {
    y = atan2(fabs(wo.y), fabs(wo.x)) / (0.5 * SS_PI) * (t->phi_nodes - 1);
    p = (int)fmin(y, t->phi_nodes - 2);
    y -= p;
  }
  double lo = (1.0 - fk) * t->e[p][k] + fk * t->e[p][k + 1];
  if (t->phi_nodes == 1) {
    return lo;
  }
  double hi = (1.0 - fk) * t->e[p + 1][k] + fk * t->e[p + 1][k + 1];
  return (1.0 - y) * lo + y * hi;
}

double ss_conductor_ms_average(const ss_conductor_ms *t) { return t->e_avg; }
