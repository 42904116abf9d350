/* Free flights and transmittance in homogeneous (possibly oriented) and
 * gridded media (volume.h). */
#include "subsurf/grid.h"
#include "subsurf/sampling.h"
#include "subsurf/volume.h"

#include <math.h>

/* A homogeneous medium's (only) point. */
static ss_volume_point everywhere(const ss_medium *m) {
  ss_volume_point q = {1.0, m->axis};
  return q;
}

double ss_volume_sample_distance(const ss_medium *m, ss_vec3 d, int hero, ss_rng *rng) {
  if (m->grid) {
    return INFINITY;
  }
  ss_volume_point q = everywhere(m);
  return ss_sample_exponential(ss_rng_uniform(rng), ss_volume_sigma_t(m, &q, d).c[hero]);
}

static void scale_weights(ss_volume_weights w, ss_rgb beta, ss_rgb r_u, ss_rgb r_l) {
  *w.beta = ss_rgb_mul(*w.beta, beta);
  *w.r_u = ss_rgb_mul(*w.r_u, r_u);
  *w.r_l = ss_rgb_mul(*w.r_l, r_l);
}

static ss_rgb rgb_exp(ss_rgb sigma, double t) {
  ss_rgb r;
  for (int c = 0; c < 3; ++c) {
    r.c[c] = exp(-sigma.c[c] * t);
  }
  return r;
}

/* Homogeneous: a real event at t_pre, or survival to tmax with probability
 * T_h(tmax); p_i(t) = sigma_t[i](d) T_i(t) for the channels' techniques. */
static int homogeneous_segment(const ss_medium *m, ss_vec3 d, double t_pre, double tmax, int hero,
                               ss_volume_weights w, double *t) {
  ss_volume_point q = everywhere(m);
  ss_rgb st = ss_volume_sigma_t(m, &q, d);
  if (t_pre < tmax) {
    ss_rgb tr = rgb_exp(st, t_pre);
    double pdf = st.c[hero] * tr.c[hero];
    ss_rgb ss = ss_volume_sigma_s(m, &q, d);
    for (int c = 0; c < 3; ++c) {
      w.beta->c[c] *= ss.c[c] * tr.c[c] / pdf;
      w.r_u->c[c] *= st.c[c] * tr.c[c] / pdf;
    }
    *t = t_pre;
    return pdf > 0.0 ? 1 : -1;
  }
  ss_rgb tr = rgb_exp(st, tmax);
  double p_surv = tr.c[hero];
  if (!(p_surv > 0.0)) {
    return -1;
  }
  for (int c = 0; c < 3; ++c) {
    w.beta->c[c] *= tr.c[c] / p_surv;
    w.r_u->c[c] *= tr.c[c] / p_surv;
    w.r_l->c[c] /= p_surv;
  }
  *t = tmax;
  return 0;
}

/* Rounding allowed above the majorant: a lerp of the flake table or a
 * trilinear density may exceed its largest node by a few ulps. */
#define MAJORANT_SLACK 1e-12

/* A tentative collision with sigma_t above the majorant biases the tracking
 * (its null coefficient is clamped at 0): counted (volume.h). */
static void check_majorant(const ss_medium *m, ss_rgb st, ss_rgb maj) {
  int above = 0;
  for (int c = 0; c < 3; ++c) {
    above |= st.c[c] > maj.c[c] * (1.0 + MAJORANT_SLACK);
  }
  if (above && m->majorant_exceeded) {
#pragma omp atomic update
    ++*m->majorant_exceeded;
  }
}

uint64_t ss_medium_majorant_exceeded(const ss_medium *m) {
  uint64_t n = 0;
  if (m->majorant_exceeded) {
#pragma omp atomic read
    n = *m->majorant_exceeded;
  }
  return n;
}

/* The closing stretch of a tracked segment, without a collision: every
 * weight by T_maj / T_maj[h] (pbrt-v4, VolPathIntegrator::Li). */
static ss_rgb closing_ratio(ss_rgb maj, double dt, int hero) {
  ss_rgb T = rgb_exp(maj, dt);
  return ss_rgb_scale(T, 1.0 / T.c[hero]);
}

int ss_volume_segment(const ss_medium *m, ss_vec3 o, ss_vec3 d, double t_pre, double tmax, int hero,
                      ss_rng *rng, ss_volume_weights w, double *t, uint64_t *tentative) {
  if (!m->grid) {
    return homogeneous_segment(m, d, t_pre, tmax, hero, w, t);
  }
  ss_rgb maj = ss_rgb_scale(m->sigma_t, m->majorant);
  double t0, t1;
  *t = tmax;
  if (!(maj.c[hero] > 0.0) || !ss_grid_clip(m->grid, o, d, 0.0, tmax, &t0, &t1)) {
    return 0; /* no density on the segment */
  }
  /* Delta tracking (Woodcock et al. 1965) against the majorant; the
   * channels' weights as pbrt-v4's VolPathIntegrator with absorption and
   * scattering as one real collision: probability sigma_t[h] / maj[h],
   * weighted by sigma_s / sigma_t per channel. */
  double s = t0;
  for (;;) {
    double dt = ss_sample_exponential(ss_rng_uniform(rng), maj.c[hero]);
    if (s + dt >= t1) {
      ss_rgb r = closing_ratio(maj, t1 - s, hero);
      scale_weights(w, r, r, r);
      return 0;
    }
    s += dt;
    if (tentative) {
      ++*tentative;
    }
    ss_vec3 p = ss_vec3_madd(o, d, s);
    ss_volume_point q = ss_volume_at(m, p);
    ss_rgb st = ss_volume_sigma_t(m, &q, d);
    check_majorant(m, st, maj);
    ss_rgb T = rgb_exp(maj, dt);
    if (ss_rng_uniform(rng) * maj.c[hero] < st.c[hero]) {
      double pdf = T.c[hero] * st.c[hero];
      ss_rgb ss = ss_volume_sigma_s(m, &q, d);
      ss_rgb k = ss_rgb_scale(T, 1.0 / pdf);
      scale_weights(w, ss_rgb_mul(k, ss), ss_rgb_mul(k, st), ss_rgb_gray(1.0));
      *t = s;
      return pdf > 0.0 ? 1 : -1;
    }
    ss_rgb sn;
    for (int c = 0; c < 3; ++c) {
      sn.c[c] = fmax(0.0, maj.c[c] - st.c[c]);
    }
    double pdf = T.c[hero] * sn.c[hero];
    if (!(pdf > 0.0)) {
      return -1;
    }
    ss_rgb k = ss_rgb_scale(T, 1.0 / pdf);
    scale_weights(w, ss_rgb_mul(k, sn), ss_rgb_mul(k, sn), ss_rgb_mul(k, maj));
  }
}

ss_rgb ss_volume_transmittance(const ss_medium *m, ss_vec3 o, ss_vec3 d, double dist, int hero,
                               ss_rng *rng, ss_rgb *a_l) {
  if (!m->grid) {
    ss_volume_point q = everywhere(m);
    return rgb_exp(ss_volume_sigma_t(m, &q, d), dist);
  }
  ss_rgb maj = ss_rgb_scale(m->sigma_t, m->majorant);
  double t0, t1;
  if (!(maj.c[hero] > 0.0) || !ss_grid_clip(m->grid, o, d, 0.0, dist, &t0, &t1)) {
    return ss_rgb_gray(1.0);
  }
  if (!rng) {
    return ss_rgb_gray(0.0); /* only volpath tracks grids (volume.h) */
  }
  /* Ratio tracking (Novak2014, eq. 7): the product of
   * sigma_n / sigma_maj over tentative collisions, per channel with the
   * hero's majorant as the sampling density. */
  ss_rgb tr = ss_rgb_gray(1.0), al = ss_rgb_gray(1.0);
  double s = t0;
  for (;;) {
    double dt = ss_sample_exponential(ss_rng_uniform(rng), maj.c[hero]);
    if (s + dt >= t1) {
      ss_rgb r = closing_ratio(maj, t1 - s, hero);
      tr = ss_rgb_mul(tr, r);
      al = ss_rgb_mul(al, r);
      break;
    }
    s += dt;
    ss_volume_point q = ss_volume_at(m, ss_vec3_madd(o, d, s));
    ss_rgb st = ss_volume_sigma_t(m, &q, d);
    check_majorant(m, st, maj);
    ss_rgb T = rgb_exp(maj, dt);
    double pdf = T.c[hero] * maj.c[hero];
    for (int c = 0; c < 3; ++c) {
      tr.c[c] *= T.c[c] * fmax(0.0, maj.c[c] - st.c[c]) / pdf;
      al.c[c] *= T.c[c] * maj.c[c] / pdf;
    }
    if (ss_rgb_is_black(tr)) {
      break;
    }
  }
  if (a_l) {
    *a_l = ss_rgb_mul(*a_l, al);
  }
  return tr;
}
