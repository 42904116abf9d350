/* Dwivedi-guided walks for volpath (guided_walk.h). */
#include "render/integrators/guided_walk.h"

#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>

double ss_dwivedi_kappa(double albedo) {
  if (!(albedo < 1.0)) {
    return 0.0;
  }
  /* f(k) = a atanh(k) - k is negative just above 0 (f'(0) = a - 1 < 0) and
   * tends to +inf at 1: bisection for its only root in (0, 1) (Krivanek &
   * d'Eon 2014: 1 = a v0 / 2 ln((v0 + 1) / (v0 - 1)), kappa = 1/v0). */
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    double k = 0.5 * (lo + hi);
    if (albedo * atanh(k) - k < 0.0) {
      lo = k;
    } else {
      hi = k;
    }
  }
  return fmin(0.5 * (lo + hi), SS_GUIDE_MAX_KAPPA);
}

double ss_dwivedi_pdf(double kappa, double mu) {
  if (kappa < 1e-8) {
    return SS_INV_4PI;
  }
  /* Krivanek & d'Eon 2014, Dwivedi's direction density with v0 = 1/kappa:
   * 1 / (2 pi ln((v0 + 1) / (v0 - 1)) (v0 - mu)). */
  return kappa * SS_INV_4PI / (atanh(kappa) * (1.0 - kappa * mu));
}

double ss_dwivedi_sample_mu(double kappa, double u) {
  if (kappa < 1e-8) {
    return fmin(1.0, fmax(-1.0, 2.0 * u - 1.0));
  }
  /* The inverse of the cdf (1/(2 atanh k)) ln((1 + k) / (1 - k mu)):
   * mu = v0 - (v0 + 1) ((v0 - 1) / (v0 + 1))^u (Krivanek & d'Eon 2014). */
  double mu = (1.0 - (1.0 + kappa) * exp(-2.0 * u * atanh(kappa))) / kappa;
  return fmin(1.0, fmax(-1.0, mu));
}

ss_status ss_guide_init(ss_guide *g, const ss_scene *scene, double q, ss_error *err) {
  g->q = 0.0;
  g->kappa = NULL;
  if (!(q > 0.0) || scene->num_lights != 1) {
    return SS_OK;
  }
  const ss_light *l = &scene->lights[0];
  switch (l->type) {
  case SS_LIGHT_POINT:
  case SS_LIGHT_SPOT:
    g->toward = 1;
    g->target = l->position;
    break;
  case SS_LIGHT_DIRECTIONAL:
  case SS_LIGHT_BEAM:
    g->toward = 0;
    g->target = ss_vec3_normalize(ss_vec3_neg(l->direction));
    break;
  default:
    return SS_OK;
  }
  g->kappa = calloc(scene->num_media + 1, sizeof *g->kappa);
  if (!g->kappa) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "volpath: out of memory");
  }
  for (size_t i = 0; i < scene->num_media; ++i) {
    const ss_medium *m = &scene->media[i];
    for (int c = 0; c < 3; ++c) {
      double st = m->optics.sigma_s.c[c] + m->optics.sigma_a.c[c];
      g->kappa[i].c[c] = st > 0.0 ? ss_dwivedi_kappa(m->optics.sigma_s.c[c] / st) : 0.0;
    }
  }
  g->q = q;
  return SS_OK;
}

void ss_guide_free(ss_guide *g) {
  free(g->kappa);
  g->kappa = NULL;
  g->q = 0.0;
}

ss_vec3 ss_guide_direction(const ss_guide *g, ss_vec3 p) {
  if (!g->toward) {
    return g->target;
  }
  ss_vec3 v = ss_vec3_sub(g->target, p);
  double len = ss_vec3_length(v);
  return len > 0.0 ? ss_vec3_scale(v, 1.0 / len) : ss_vec3_make(0.0, 0.0, 1.0);
}

ss_vec3 ss_guided_sample_direction(const ss_guide *g, const ss_medium *med,
                                   const ss_volume_point *q, ss_vec3 d, ss_vec3 gdir, ss_rgb kappa,
                                   int hero, ss_rng *rng, ss_guided_segment *seg) {
  ss_vec3 wi;
  seg->guided = ss_rng_uniform(rng) < g->q;
  if (seg->guided) {
    double mu = ss_dwivedi_sample_mu(kappa.c[hero], ss_rng_uniform(rng));
    double phi = 2.0 * SS_PI * ss_rng_uniform(rng);
    double sin_theta = sqrt(fmax(0.0, 1.0 - mu * mu));
    ss_vec3 local = ss_vec3_make(sin_theta * cos(phi), sin_theta * sin(phi), mu);
    wi = ss_vec3_normalize(ss_frame_to_world(ss_frame_from_normal(gdir), local));
  } else {
    wi = ss_volume_phase_sample(med, q, d, rng);
  }
  seg->a = ss_volume_phase_eval(med, q, d, wi);
  seg->mu = fmin(1.0, fmax(-1.0, ss_vec3_dot(wi, gdir)));
  seg->kappa = kappa;
  for (int c = 0; c < 3; ++c) {
    seg->b.c[c] = ss_dwivedi_pdf(kappa.c[c], seg->mu);
  }
  return wi;
}

/* Krivanek & d'Eon 2014, Dwivedi's free flight: sigma_t' = sigma_t (1 - mu / v0). */
static double guided_sigma(const ss_guided_segment *seg, ss_rgb st, int c) {
  return st.c[c] * (1.0 - seg->kappa.c[c] * seg->mu);
}

double ss_guided_sample_distance(const ss_guided_segment *seg, ss_rgb st, int hero, ss_rng *rng) {
  double sigma = seg->guided ? guided_sigma(seg, st, hero) : st.c[hero];
  return ss_sample_exponential(ss_rng_uniform(rng), sigma);
}

int ss_guided_segment_weights(const ss_guided_segment *seg, double q, ss_rgb st, ss_rgb ss,
                              double t_pre, double tmax, int hero, ss_volume_weights w, double *t) {
  int event = t_pre < tmax;
  *t = event ? t_pre : tmax;
  /* Per channel c: the contribution f_c (phase function x transmittance, x
   * sigma_s at an event) and the mixture's density p_c of this direction
   * and distance (at the end: of the direction and survival to it). */
  double f[3], p[3];
  for (int c = 0; c < 3; ++c) {
    double s1 = st.c[c], s2 = guided_sigma(seg, st, c);
    double e1 = exp(-s1 * *t), e2 = exp(-s2 * *t);
    f[c] = seg->a * e1 * (event ? ss.c[c] : 1.0);
    p[c] = (1.0 - q) * seg->a * e1 * (event ? s1 : 1.0) + q * seg->b.c[c] * e2 * (event ? s2 : 1.0);
  }
  double ph = p[hero];
  if (!(ph > 0.0)) {
    return -1;
  }
  for (int c = 0; c < 3; ++c) {
    w.beta->c[c] *= f[c] / ph;
    w.r_u->c[c] *= p[c] / ph;
    if (!event) {
      w.r_l->c[c] /= ph;
    }
  }
  return event;
}
